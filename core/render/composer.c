#include "render/composer.h"
#include "fileio.h"
#include "log.h"
#include "startup.h"
#include <shadelab/gl.h>
#include <errno.h>
#include <libgen.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define SL_LINE_STRIDE 100000

void sl_sb_append(sl_strbuf *b, const char *t) {
    size_t l = strlen(t);
    if (b->len + l + 1 > b->cap) {
        size_t cap = (b->len + l + 1) * 2;
        char *grown = realloc(b->s, cap);
        if (!grown) {
            fprintf(stderr, "shadelab: out of memory composing a shader (%zu bytes)\n", cap);
            abort(); /* a truncated shader would compile to something else */
        }
        b->s = grown;
        b->cap = cap;
    }
    memcpy(b->s + b->len, t, l + 1);
    b->len += l;
}

void sl_sb_printf(sl_strbuf *b, const char *fmt, ...) {
    char tmp[4096];
    va_list ap;
    va_start(ap, fmt);
    int l = vsnprintf(tmp, sizeof tmp, fmt, ap);
    va_end(ap);
    if (l < (int)sizeof tmp) { sl_sb_append(b, tmp); return; }
    char *big = malloc(l + 1);
    va_start(ap, fmt);
    vsnprintf(big, l + 1, fmt, ap);
    va_end(ap);
    sl_sb_append(b, big);
    free(big);
}

void sl_sb_free(sl_strbuf *b) { free(b->s); memset(b, 0, sizeof *b); }

uint64_t sl_hash64(const void *data, size_t len, uint64_t h) {
    /* FNV-1a, 64-bit */
    const unsigned char *p = data;
    if (!h) h = 1469598103934665603ull;
    for (size_t i = 0; i < len; i++) { h ^= p[i]; h *= 1099511628211ull; }
    return h;
}

const char *sl_shader_dir(void) {
    static char dir[1024];
    if (dir[0]) return dir;
    const char *env = getenv("SHADELAB_SHADER_DIR");
    struct stat st;
    /* an installed executable uses the shaders installed beside it, even when the source tree
     * it was built from still exists; a build-tree executable has none there */
    char exe[1024], installed[1200], probe[1300];
    ssize_t l = readlink("/proc/self/exe", exe, sizeof exe - 1);
    exe[l > 0 ? l : 0] = 0;
    snprintf(installed, sizeof installed, "%s/../%s/shadelab/shaders", dirname(exe), SL_INSTALL_DATADIR);
    snprintf(probe, sizeof probe, "%s/common.glsl", installed);
    if (env && *env) snprintf(dir, sizeof dir, "%s", env);
    else if (stat(probe, &st) == 0) snprintf(dir, sizeof dir, "%s", installed);
    else if (stat(SL_SOURCE_SHADER_DIR "/common.glsl", &st) == 0) snprintf(dir, sizeof dir, "%s", SL_SOURCE_SHADER_DIR);
    else snprintf(dir, sizeof dir, "%s", installed);
    return dir;
}

const char *sl_display_path(const char *p, char *buf, size_t n) {
    size_t l = strlen(SL_SOURCE_DIR);
    if (!strncmp(p, SL_SOURCE_DIR, l) && p[l] == '/') snprintf(buf, n, "%s", p + l + 1);
    else snprintf(buf, n, "%s", p);
    return buf;
}

void sl_source_init(sl_source *s) { memset(s, 0, sizeof *s); }

void sl_source_free(sl_source *s) {
    sl_sb_free(&s->text);
    for (int i = 0; i < s->file_count; i++) free(s->files[i]);
    memset(s, 0, sizeof *s);
}

static int file_index(sl_source *s, const char *abs, bool *added) {
    for (int i = 0; i < s->file_count; i++)
        if (!strcmp(s->files[i], abs)) { *added = false; return i; }
    if (s->file_count == 64) return -1;
    struct stat st;
    s->mtimes[s->file_count] = stat(abs, &st) == 0 ? st.st_mtime : 0;
    s->files[s->file_count] = strdup(abs);
    *added = true;
    return s->file_count++;
}

/* GLSL source string number 0 is reserved for generated text. */
static void ensure_generated_slot(sl_source *s) {
    if (s->file_count == 0) {
        s->files[0] = strdup("<generated>");
        s->mtimes[0] = 0;
        s->file_count = 1;
    }
}

static bool include_file(sl_source *s, const char *path, int owner, int depth, char *err, size_t n) {
    ensure_generated_slot(s);
    char resolved[2048];
    if (!strncmp(path, "sl:", 3)) snprintf(resolved, sizeof resolved, "%s/%s", sl_shader_dir(), path + 3);
    else snprintf(resolved, sizeof resolved, "%s", path);
    char *abs = realpath(resolved, NULL);
    if (!abs) { snprintf(err, n, "%s: no such shader file", resolved); return false; }
    bool added;
    int idx = file_index(s, abs, &added);
    if (idx < 0) { snprintf(err, n, "%s: too many included files", abs); free(abs); return false; }
    if (!added) { free(abs); return true; } /* each file once */
    s->file_owner[idx] = strncmp(path, "sl:", 3) ? owner : 0;
    if (depth > 16) { snprintf(err, n, "%s: #include nested too deeply", abs); free(abs); return false; }
    char *text = sl_read_file(abs, NULL, NULL, 0);
    if (!text) {
        snprintf(err, n, "%s: cannot open (%s)", abs, strerror(errno));
        free(abs);
        return false;
    }
    char dir[2048];
    snprintf(dir, sizeof dir, "%s", abs);
    char *d = dirname(dir);
    /* Mesa drops the source-string number from its logs, so the file index is also encoded in
     * the line number: line = file * SL_LINE_STRIDE + line in file. */
    sl_sb_printf(&s->text, "#line %d %d\n", idx * SL_LINE_STRIDE + 1, idx);
    int line = 1;
    bool ok = true;
    for (char *p = text; *p && ok;) {
        char *end = strchr(p, '\n');
        size_t len = end ? (size_t)(end - p) : strlen(p);
        const char *q = p;
        while (*q == ' ' || *q == '\t') q++;
        if (!strncmp(q, "#include", 8)) {
            const char *a = strchr(q, '"'), *b = a ? strchr(a + 1, '"') : NULL;
            if (!a || !b || b > p + len) {
                char shown[1024];
                snprintf(err, n, "%s:%d: malformed #include (expected #include \"file\")",
                         sl_display_path(abs, shown, sizeof shown), line);
                ok = false;
                break;
            }
            char inc[1024], full[3072];
            snprintf(inc, sizeof inc, "%.*s", (int)(b - a - 1), a + 1);
            if (!strncmp(inc, "sl:", 3) || inc[0] == '/') snprintf(full, sizeof full, "%s", inc);
            else snprintf(full, sizeof full, "%s/%s", d, inc);
            char sub[1024] = "";
            if (!include_file(s, full, owner, depth + 1, sub, sizeof sub)) {
                char shown[1024];
                snprintf(err, n, "%s:%d: %s", sl_display_path(abs, shown, sizeof shown), line, sub);
                ok = false;
                break;
            }
            sl_sb_printf(&s->text, "#line %d %d\n", idx * SL_LINE_STRIDE + line + 1, idx);
        } else {
            sl_sb_printf(&s->text, "%.*s\n", (int)len, p);
        }
        line++;
        p = end ? end + 1 : p + len;
    }
    free(text);
    free(abs);
    return ok;
}

bool sl_source_include(sl_source *s, const char *path, char *err, size_t n) {
    return include_file(s, path, 0, 0, err, n);
}

bool sl_source_include_from(sl_source *s, const char *path, int owner, char *err, size_t n) {
    return include_file(s, path, owner, 0, err, n);
}

void sl_source_generated(sl_source *s, const char *text) {
    ensure_generated_slot(s);
    /* number generated lines by their position in the whole text so errors stay findable */
    int line = 1;
    for (const char *c = s->text.s; c && *c; c++) line += *c == '\n';
    sl_sb_printf(&s->text, "#line %d 0\n", line + 1);
    sl_sb_append(&s->text, text);
    if (text[0] && text[strlen(text) - 1] != '\n') sl_sb_append(&s->text, "\n");
}

/* The file index and line of a log line "0:12(5): …" (Mesa) or "0(12) : …" (NVIDIA), with the
 * index recovered from the line number (include_file); false for a line without a position. */
static bool log_position(const char *p, int *file, int *line, int *consumed, bool *mesa) {
    *mesa = sscanf(p, "%d:%d%n", file, line, consumed) == 2;
    bool nv = !*mesa && sscanf(p, "%d(%d)%n", file, line, consumed) == 2;
    if ((*mesa || nv) && *line >= SL_LINE_STRIDE) {
        *file = *line / SL_LINE_STRIDE;
        *line %= SL_LINE_STRIDE;
    }
    return *mesa || nv;
}

int sl_source_log_owner(const sl_source *s, const char *log) {
    for (const char *p = log; p && *p; p = strchr(p, '\n') ? strchr(p, '\n') + 1 : NULL) {
        int file, line, consumed;
        bool mesa;
        if (log_position(p, &file, &line, &consumed, &mesa) && file >= 0 && file < s->file_count) return s->file_owner[file];
    }
    return 0;
}

void sl_source_map_log(const sl_source *s, const char *log, char *out, size_t n) {
    out[0] = 0;
    size_t used = 0;
    for (const char *p = log; *p && used + 1 < n;) {
        const char *end = strchr(p, '\n');
        size_t len = end ? (size_t)(end - p) : strlen(p);
        int file, line, consumed = 0;
        char shown[1024];
        /* Mesa: "0:12(5): error: …"; NVIDIA: "0(12) : error …" */
        bool mesa;
        bool positioned = log_position(p, &file, &line, &consumed, &mesa);
        if (positioned && file >= 0 && file < s->file_count) {
            used += snprintf(out + used, n - used, "%s:%d%.*s\n", sl_display_path(s->files[file], shown, sizeof shown),
                             line, (int)(len - consumed), p + consumed);
        } else if (len) {
            used += snprintf(out + used, n - used, "%.*s\n", (int)len, p);
        }
        if (used >= n) break;
        p = end ? end + 1 : p + len;
    }
}

static unsigned compile_stage(GLenum type, const sl_source *src, char *err, size_t n, int *err_owner) {
    unsigned sh = glCreateShader(type);
    const char *text = src->text.s;
    glShaderSource(sh, 1, &text, NULL);
    glCompileShader(sh);
    int ok = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[8192] = "";
        glGetShaderInfoLog(sh, sizeof log, NULL, log);
        sl_source_map_log(src, log, err, n);
        *err_owner = sl_source_log_owner(src, log);
        glDeleteShader(sh);
        return 0;
    }
    return sh;
}

static void free_uniforms(sl_program *p);

static unsigned long builds;
bool sl_program_built_since(unsigned long *seen) {
    bool built = builds != *seen;
    *seen = builds;
    return built;
}

bool sl_program_build(sl_program *p, char *err, size_t n) {
    builds++;
    char log[8192] = "";
    int err_owner = 0;
    double cpu0 = sl_startup_thread_cpu_ms(), wall0 = sl_startup_wall_ms();
    unsigned vs = compile_stage(GL_VERTEX_SHADER, &p->vs, log, sizeof log, &err_owner);
    unsigned fs = vs ? compile_stage(GL_FRAGMENT_SHADER, &p->fs, log, sizeof log, &err_owner) : 0;
    /* tessellation stages (DISPLACEMENT hooks, shader.h ABI 1.7) only when composed */
    unsigned tcs = 0, tes = 0;
    if (p->tessellated && fs) {
        tcs = compile_stage(GL_TESS_CONTROL_SHADER, &p->tcs, log, sizeof log, &err_owner);
        tes = tcs ? compile_stage(GL_TESS_EVALUATION_SHADER, &p->tes, log, sizeof log, &err_owner) : 0;
    }
    unsigned prog = 0;
    if (vs && fs && (!p->tessellated || (tcs && tes))) {
        prog = glCreateProgram();
        glAttachShader(prog, vs);
        if (tcs) glAttachShader(prog, tcs);
        if (tes) glAttachShader(prog, tes);
        glAttachShader(prog, fs);
        glLinkProgram(prog);
        int ok = 0;
        glGetProgramiv(prog, GL_LINK_STATUS, &ok);
        if (!ok) {
            char raw[8192] = "";
            glGetProgramInfoLog(prog, sizeof raw, NULL, raw);
            sl_source_map_log(&p->fs, raw, log, sizeof log);
            err_owner = sl_source_log_owner(&p->fs, raw);
            glDeleteProgram(prog);
            prog = 0;
        }
    }
    if (vs) glDeleteShader(vs);
    if (fs) glDeleteShader(fs);
    if (tcs) glDeleteShader(tcs);
    if (tes) glDeleteShader(tes);
    sl_startup_note_glsl(sl_startup_thread_cpu_ms() - cpu0, sl_startup_wall_ms() - wall0);
    SL_DEBUG("built program %s (%zu + %zu bytes of GLSL) in %.1f ms CPU", p->label ? p->label : "?", p->vs.text.len,
             p->fs.text.len, sl_startup_thread_cpu_ms() - cpu0);
    free(p->error);
    p->error = NULL;
    p->error_owner = 0;
    if (!prog) {
        p->error = strdup(log);
        p->error_owner = err_owner;
        snprintf(err, n, "%s: shader compile failed%s:\n%s", p->label ? p->label : "program",
                 p->id ? " (keeping the last good program)" : "", log);
        return false;
    }
    if (p->id) glDeleteProgram(p->id);
    free_uniforms(p); /* GL may give a new program an old one's name */
    p->id = prog;
    return true;
}

/* The fused pointwise functions (ext/post.h) before the fragment file: each one's defines and
 * file, then sl_pointwise_epilogue calling them in order. */
static bool compose_epilogue(sl_program *p, sl_source *fs, char *err, size_t n) {
    sl_strbuf chain = {0};
    sl_sb_append(&chain, "vec3 sl_pointwise_epilogue(vec3 color, ivec2 pixel) {\n");
    for (int i = 0; i < p->point_count; i++) {
        const sl_epilogue_point *e = &p->points[i];
        if (e->defines && *e->defines) {
            sl_strbuf d = {0};
            char *copy = strdup(e->defines), *save = NULL;
            for (char *l = strtok_r(copy, "\n", &save); l; l = strtok_r(NULL, "\n", &save)) sl_sb_printf(&d, "#define %s\n", l);
            free(copy);
            sl_source_generated(fs, d.s ? d.s : "");
            sl_sb_free(&d);
        }
        if (!sl_source_include_from(fs, e->file, e->owner, err, n)) { sl_sb_free(&chain); return false; }
        sl_sb_printf(&chain, "    color = %s(color, pixel);\n", e->function);
    }
    sl_sb_append(&chain, "    return color;\n}\n");
    sl_source_generated(fs, chain.s);
    sl_sb_free(&chain);
    return true;
}

static bool compose_files(sl_program *p, const char *dir, char *err, size_t n) {
    sl_source_free(&p->vs);
    sl_source_free(&p->fs);
    const char *paths[2] = {p->vs_path, p->fs_path};
    sl_source *srcs[2] = {&p->vs, &p->fs};
    for (int k = 0; k < 2; k++) {
        sl_strbuf head = {0};
        sl_sb_append(&head, "#version 450 core\n");
        if (p->defines) {
            char *copy = strdup(p->defines), *save = NULL;
            /* "NAME VALUE" lines become #defines; an "#extension NAME : BEHAVIOR" line is kept as
             * it is, here before any code, where GLSL requires it (the fused epilogue and the
             * files come after) */
            for (char *l = strtok_r(copy, "\n", &save); l; l = strtok_r(NULL, "\n", &save))
                sl_sb_printf(&head, strncmp(l, "#extension ", 11) ? "#define %s\n" : "%s\n", l);
            free(copy);
        }
        sl_sb_append(&srcs[k]->text, head.s);
        sl_sb_free(&head);
        ensure_generated_slot(srcs[k]);
        if (k == 1 && p->epilogue && !compose_epilogue(p, srcs[k], err, n)) return false;
        char full[2048];
        if (!strncmp(paths[k], "sl:", 3) || paths[k][0] == '/' || !dir || !*dir) snprintf(full, sizeof full, "%s", paths[k]);
        else snprintf(full, sizeof full, "%s/%s", dir, paths[k]);
        if (!sl_source_include(srcs[k], full, err, n)) return false;
    }
    p->hash = sl_hash64(p->vs.text.s, p->vs.text.len, sl_hash64(p->fs.text.s, p->fs.text.len, 0));
    return true;
}

sl_program *sl_program_from_files_deferred(const char *dir, const char *vs, const char *fs, const char *defines,
                                           char *err, size_t n) {
    sl_program *p = calloc(1, sizeof *p);
    p->vs_path = strdup(vs);
    p->fs_path = strdup(fs);
    p->defines = defines ? strdup(defines) : NULL;
    char label[1024];
    snprintf(label, sizeof label, "%s + %s", vs, fs);
    p->label = strdup(label);
    if (!compose_files(p, dir, err, n)) {
        free(p->error);
        p->error = strdup(err);
        return p; /* id 0, not deferred: a reload that finds the files compiles it */
    }
    p->deferred = true;
    return p;
}

sl_program *sl_program_from_files(const char *dir, const char *vs, const char *fs, const char *defines,
                                  char *err, size_t n) {
    sl_program *p = sl_program_from_files_deferred(dir, vs, fs, defines, err, n);
    if (p->deferred) { /* compiled now; id 0 and the error kept on failure: a later reload may fix it */
        p->deferred = false;
        sl_program_build(p, err, n);
    }
    return p;
}

unsigned sl_program_id(sl_program *p) {
    if (!p) return 0;
    if (p->deferred) {
        p->deferred = false;
        char err[16384] = "";
        /* a plugin's program is reported once, where its failure disables the plugin (app.c) */
        if (!sl_program_build(p, err, sizeof err) && p->owner < 1) SL_ERROR("%s", err);
    }
    return p->id;
}

sl_program *sl_program_epilogue_variant(const sl_program *base, const char *dir, const sl_epilogue_point *points,
                                        int count, char *err, size_t n) {
    sl_program *p = calloc(1, sizeof *p);
    p->vs_path = strdup(base->vs_path);
    p->fs_path = strdup(base->fs_path);
    p->defines = base->defines ? strdup(base->defines) : NULL;
    p->owner = base->owner;
    p->epilogue = true;
    for (int i = 0; i < count && i < SL_EPILOGUE_MAX; i++, p->point_count++) {
        p->points[i].file = strdup(points[i].file);
        p->points[i].owner = points[i].owner;
        p->points[i].function = strdup(points[i].function);
        p->points[i].defines = points[i].defines ? strdup(points[i].defines) : NULL;
    }
    sl_strbuf label = {0};
    sl_sb_printf(&label, "%s", base->label ? base->label : base->fs_path);
    for (int i = 0; i < p->point_count; i++) sl_sb_printf(&label, " + %s()", p->points[i].function);
    p->label = label.s;
    if (!compose_files(p, dir, err, n)) {
        p->error = strdup(err);
        p->error_owner = p->point_count ? p->points[0].owner : p->owner; /* a missing file: which one */
        for (int i = 0; i < p->point_count; i++)
            if (strstr(err, p->points[i].file)) p->error_owner = p->points[i].owner;
        return p;
    }
    sl_program_build(p, err, n);
    return p;
}

bool sl_program_rebuild_files(sl_program *p, const char *dir, char *err, size_t n) {
    sl_program tmp = *p;
    memset(&tmp.vs, 0, sizeof tmp.vs);
    memset(&tmp.fs, 0, sizeof tmp.fs);
    if (!compose_files(&tmp, dir, err, n)) {
        sl_source_free(&tmp.vs);
        sl_source_free(&tmp.fs);
        free(p->error);
        p->error = strdup(err);
        return false;
    }
    sl_source_free(&p->vs);
    sl_source_free(&p->fs);
    p->vs = tmp.vs;
    p->fs = tmp.fs;
    p->hash = tmp.hash;
    free(p->error);
    p->error = NULL;
    if (p->deferred) return true; /* never used yet: compiles at its first use, from these files */
    return sl_program_build(p, err, n);
}

bool sl_source_changed(const sl_source *s) {
    for (int i = 1; i < s->file_count; i++) {
        struct stat st;
        if (stat(s->files[i], &st) != 0 || st.st_mtime != s->mtimes[i]) return true;
    }
    return false;
}

typedef struct sl_uniform_slot { uint64_t hash; char *name; int location; } sl_uniform_slot;

static void free_uniforms(sl_program *p) {
    for (int i = 0; i < p->uniform_slots; i++) free(p->uniforms[i].name);
    free(p->uniforms);
    p->uniforms = NULL;
    p->uniform_slots = p->uniform_count = 0;
    p->uniforms_of = 0;
}

/* The slot of `name` (hash h) in the open-addressed table: its own, or the empty one it would take. */
static sl_uniform_slot *uniform_slot(sl_program *p, const char *name, uint64_t h) {
    int mask = p->uniform_slots - 1;
    for (int i = (int)(h & (uint64_t)mask);; i = (i + 1) & mask) {
        sl_uniform_slot *s = &p->uniforms[i];
        if (!s->name || (s->hash == h && !strcmp(s->name, name))) return s;
    }
}

/* Twice the slots (64 at first), the names kept: at most half full, so that every probe ends. */
static bool grow_uniforms(sl_program *p) {
    sl_uniform_slot *old = p->uniforms;
    int old_slots = p->uniform_slots, slots = old_slots ? 2 * old_slots : 64;
    sl_uniform_slot *table = calloc((size_t)slots, sizeof *table);
    if (!table) return false;
    p->uniforms = table, p->uniform_slots = slots;
    for (int i = 0; i < old_slots; i++)
        if (old[i].name) *uniform_slot(p, old[i].name, old[i].hash) = old[i];
    free(old);
    return true;
}

/* A location from the program's cache of the names asked for, each asked of GL once (−1 kept
 * too: not an active uniform), array elements "a[k]" as any name. Not a table of every active
 * uniform made up front: enumerating them (glGetActiveUniform by index) is quadratic in Mesa,
 * whose index lookup walks the program's resource list, and a forward program with arrays of
 * light structs has thousands (ggx_layers' 17 programs took 307 ms at their first draw). An
 * array's bare name is its element 0 (GL). */
int sl_program_uniform(sl_program *p, const char *name) {
    if (!p || !p->id) return -1;
    if (p->uniforms_of != p->id) {
        free_uniforms(p);
        p->uniforms_of = p->id;
    }
    uint64_t h = sl_hash64(name, strlen(name), 0);
    if (p->uniform_slots) {
        const sl_uniform_slot *s = uniform_slot(p, name, h);
        if (s->name) return s->location;
    }
    int location = glGetUniformLocation(p->id, name);
    if (2 * (p->uniform_count + 1) > p->uniform_slots && !grow_uniforms(p)) return location;
    sl_uniform_slot *s = uniform_slot(p, name, h);
    char *copy = strdup(name);
    if (copy) *s = (sl_uniform_slot){.hash = h, .name = copy, .location = location}, p->uniform_count++;
    return location;
}

void sl_program_free(sl_program *p) {
    if (!p) return;
    free_uniforms(p);
    if (p->id) glDeleteProgram(p->id);
    sl_source_free(&p->vs);
    sl_source_free(&p->fs);
    sl_source_free(&p->tcs);
    sl_source_free(&p->tes);
    free(p->label); free(p->error); free(p->vs_path); free(p->fs_path); free(p->defines);
    for (int i = 0; i < p->point_count; i++) free(p->points[i].file), free(p->points[i].function), free(p->points[i].defines);
    free(p);
}
