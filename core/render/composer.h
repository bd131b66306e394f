/* Shader composer: assembles GLSL from files with #include, keeps a file table so #line
 * directives map compile errors back to "file:line", links programs, caches them by the hash of
 * their final source and rebuilds them when their files change (keeping the last good program
 * when the new source fails). */
#ifndef SL_COMPOSER_H
#define SL_COMPOSER_H
#include <shadelab/shadelab.h>
#include <time.h>

typedef struct sl_strbuf { char *s; size_t len, cap; } sl_strbuf;
void sl_sb_append(sl_strbuf *b, const char *text);
void sl_sb_printf(sl_strbuf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void sl_sb_free(sl_strbuf *b);

/* One composed source: text plus the files it was built from (index = GLSL source number in
 * #line directives). */
typedef struct sl_source {
    sl_strbuf text;
    char *files[64]; int file_count;
    time_t mtimes[64];
    int file_owner[64];   /* plugin index that included the file (sl_source_include_from); 0 = core */
} sl_source;

void sl_source_init(sl_source *s);
void sl_source_free(sl_source *s);
/* Appends `path`'s contents (resolved, with nested #include "x" relative to it and
 * #include "sl:x" from the core shader directory), each file once, with #line mapping.
 * Returns false and fills err ("file:line: cause") when a file is missing. */
bool sl_source_include(sl_source *s, const char *path, char *err, size_t n);
/* The same for a file of plugin `owner` (its chunk, library or fragment): the file and those it
 * includes (but "sl:" ones) are that plugin's, so an error in them is blamed on it. */
bool sl_source_include_from(sl_source *s, const char *path, int owner, char *err, size_t n);
/* Appends generated text (reported as "<generated>" in errors). */
void sl_source_generated(sl_source *s, const char *text);
/* Rewrites a driver info log ("0:12(5): error: …") into "path:12(5): error: …". */
void sl_source_map_log(const sl_source *s, const char *log, char *out, size_t n);
/* The owner (file_owner) of the file the first positioned line of a driver info log names; 0
 * when none does or it is generated text. */
int sl_source_log_owner(const sl_source *s, const char *log);

/* One fused pointwise function of an epilogue program (ext/post.h): a plugin's file (absolute
 * path; errors in it are blamed on `owner`), its function and the defines it is composed with. */
#define SL_EPILOGUE_MAX 4
typedef struct sl_epilogue_point { char *file; int owner; char *function; char *defines; } sl_epilogue_point;

struct sl_program {
    uint64_t hash;          /* of vertex + fragment (+ tessellation) source */
    unsigned id;            /* GL program; 0 until compiled successfully */
    char *label;
    sl_source vs, fs;
    sl_source tcs, tes;     /* tessellation stages (DISPLACEMENT hooks); empty text = none */
    char *error;            /* last compile/link error (mapped), NULL when good */
    int error_owner;        /* plugin owning the file its first error names (sl_source_include_from);
                               0 for the core's files, generated text or no position */
    char *vs_path, *fs_path, *defines; /* for stand-alone programs: rebuilt on reload */
    int owner;
    bool composed;          /* forward material program (rebuilt by the material code) */
    bool stale;             /* its files changed (hot reload): not reused from the cache */
    bool tessellated;       /* has tcs/tes: draw GL_PATCHES of 3 vertices */
    bool failure_reported;  /* a failed first compile was handled (sl_renderer_failed_plugin) */
    bool deferred;          /* sources read, not compiled yet: built at the first sl_program_id()
                               (lazy creation: a program whose pass never runs costs no compile) */
    /* sl_ext_post (ext/post.h): the fragment stage gets vec3 sl_pointwise_epilogue(vec3, ivec2),
     * composed of `points` in order (the identity when there are none) before the fragment file */
    bool epilogue;
    sl_epilogue_point points[SL_EPILOGUE_MAX]; int point_count;
    /* sl_program_uniform's cache for GL program uniforms_of (0: none yet): the names looked up,
     * uniform_count of them in uniform_slots slots, with their locations */
    struct sl_uniform_slot *uniforms; int uniform_slots, uniform_count; unsigned uniforms_of;
};

/* Compiles and links; on failure keeps any previous id and stores the mapped error. */
bool sl_program_build(sl_program *p, char *err, size_t n);
/* Whether sl_program_build has built a program since *seen was last set, and sets it: a frame
 * (or interval) that compiled timed the compiler, not its settings (the frame-time budget's cost
 * model and the panel's frame rate leave it out). */
bool sl_program_built_since(unsigned long *seen);
/* Loads a stand-alone program from files (relative to dir; "sl:" = core shader dir). */
sl_program *sl_program_from_files(const char *dir, const char *vs, const char *fs, const char *defines,
                                  char *err, size_t n);
/* The same, but only reads and composes the sources (a missing file fails here, with id 0 and
 * the error in err): the GLSL compile and link wait for the first sl_program_id(). */
sl_program *sl_program_from_files_deferred(const char *dir, const char *vs, const char *fs, const char *defines,
                                           char *err, size_t n);
/* The GL id, compiling a deferred program first (once: a failure is logged as an error and
 * the program stays 0 until a reload fixes its files). NULL gives 0. */
unsigned sl_program_id(sl_program *p);
/* A program with base's files and defines whose epilogue runs `points` (copied), composed now and
 * compiled now; on failure id 0 with p->error and p->error_owner set (err holds the message). */
sl_program *sl_program_epilogue_variant(const sl_program *base, const char *dir, const sl_epilogue_point *points,
                                        int count, char *err, size_t n);
/* Re-reads the files; a deferred program is only recomposed (it compiles when first used). */
bool sl_program_rebuild_files(sl_program *p, const char *dir, char *err, size_t n);
bool sl_source_changed(const sl_source *s);
void sl_program_free(sl_program *p);
/* glGetUniformLocation(p's GL program, name), from a cache of the names asked for since the
 * last link, each asked of GL once: Mesa's glGetUniformLocation compares the name with the
 * program's uniforms one by one on every call, and the forward pass asks for every material and
 * plugin parameter of every draw (on llvmpipe that cost more than rasterising a 320x180 frame).
 * An array's name alone is its element 0, "a[k]" its element k. -1 when p has no GL program or
 * no such active uniform. */
int sl_program_uniform(sl_program *p, const char *name);

/* The directory holding the core's GLSL (source tree in a build tree; installed otherwise). */
const char *sl_shader_dir(void);
uint64_t sl_hash64(const void *data, size_t len, uint64_t seed);
/* Path shown to users: relative to the source tree when inside it. */
const char *sl_display_path(const char *abs_path, char *buf, size_t n);
#endif
