/* The glTF2 test models Debian ships (package assimp-testmodels, installed by
 * tools/install-deps.sh with the test dependencies), each opened directly as a scene, against a
 * committed table of what must happen (tests/data/gltf_models.tsv): opens with N meshes, M
 * textures (distinct texture values of its materials), C cameras and L lights, or fails with an
 * error containing a stated cause. Model by model, so a change in what any one file does shows.
 *
 *   test_gltf_models                 check every row (a model missing from the table, or a row
 *                                    whose file is gone, fails too)
 *   test_gltf_models --print         print the table as the code sees it (to review a change) */
#include "check.h"
#include "log.h"
#include "scene/scene.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define MODELS "/usr/share/assimp/models/glTF2"
#define TABLE SL_TEST_DATA_DIR "/gltf_models.tsv"

static char paths[256][1024];
static int npaths;

static void find(const char *dir, int depth) {
    DIR *d = opendir(dir);
    if (!d || depth > 6) {
        if (d) closedir(d);
        return;
    }
    for (struct dirent *e; (e = readdir(d));) {
        if (e->d_name[0] == '.') continue;
        char p[1024];
        snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
        struct stat st;
        if (stat(p, &st) != 0) continue;
        if (S_ISDIR(st.st_mode)) find(p, depth + 1);
        size_t n = strlen(p);
        if (S_ISREG(st.st_mode) && npaths < 256 &&
            ((n > 5 && !strcmp(p + n - 5, ".gltf")) || (n > 4 && !strcmp(p + n - 4, ".glb"))))
            snprintf(paths[npaths++], sizeof paths[0], "%s", p + strlen(MODELS) + 1);
    }
    closedir(d);
}

static int cmp(const void *a, const void *b) { return strcmp(a, b); }

/* "ok\tmeshes\ttextures\tcameras\tlights" or "error\t<message without the path>" */
static void outcome(const char *rel, char *out, size_t size) {
    char path[1200], err[4096] = "";
    snprintf(path, sizeof path, "%s/%s", MODELS, rel);
    sl_scene s = {0};
    static char logbuf[1 << 16];
    sl_log_capture(logbuf, sizeof logbuf); /* warnings are the files' own business here */
    bool ok = sl_scene_load_file(&s, path, NULL, err, sizeof err);
    sl_log_capture(NULL, 0);
    if (!ok) {
        const char *why = strstr(err, path) == err ? err + strlen(path) : err;
        while (*why == ':' || *why == ' ') why++;
        char clean[300];
        snprintf(clean, sizeof clean, "%.*s", (int)strcspn(why, "\t\n"), why);
        snprintf(out, size, "error\t%s", clean);
        return;
    }
    const char *tex[256];
    int ntex = 0;
    for (int m = 0; m < s.material_count; m++)
        for (int k = 0; k < s.materials[m].inputs.count; k++) {
            const sl_prop *p = &s.materials[m].inputs.items[k];
            if (p->kind != SL_PROP_STRING || !strstr(p->key, "texture")) continue;
            bool seen = false;
            for (int t = 0; t < ntex && !seen; t++) seen = !strcmp(tex[t], p->str);
            if (!seen && ntex < 256) tex[ntex++] = p->str;
        }
    snprintf(out, size, "ok\t%d\t%d\t%d\t%d", s.mesh_count, ntex, s.camera_count, s.light_count);
    sl_scene_free(&s);
}

int main(int argc, char **argv) {
    bool print = argc > 1 && !strcmp(argv[1], "--print");
    struct stat st;
    if (stat(MODELS, &st) != 0) {
        fprintf(stderr, "%s is missing: install assimp-testmodels (tools/install-deps.sh installs it)\n", MODELS);
        return 1;
    }
    find(MODELS, 0);
    qsort(paths, npaths, sizeof paths[0], cmp);
    if (print) {
        printf("# model (under %s)\toutcome\tmeshes|cause\ttextures\tcameras\tlights\n", MODELS);
        for (int i = 0; i < npaths; i++) {
            char o[600];
            outcome(paths[i], o, sizeof o);
            printf("%s\t%s\n", paths[i], o);
        }
        return 0;
    }
    FILE *f = fopen(TABLE, "r");
    CHECK_MSG(f, "cannot read %s", TABLE);
    if (!f) return check_result();
    char line[2048];
    bool listed[256] = {false};
    int rows = 0;
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = 0;
        if (!line[0] || line[0] == '#') continue;
        char *tab = strchr(line, '\t');
        if (!tab) continue;
        *tab = 0;
        const char *rel = line, *want = tab + 1;
        int i = 0;
        while (i < npaths && strcmp(paths[i], rel)) i++;
        CHECK_MSG(i < npaths, "%s: in the table but not installed", rel);
        if (i == npaths) continue;
        listed[i] = true;
        rows++;
        char got[600];
        outcome(rel, got, sizeof got);
        if (!strncmp(want, "error\t", 6)) /* the stated cause must be in the message */
            CHECK_MSG(!strncmp(got, "error\t", 6) && strstr(got, want + 6), "%s: expected an error containing \"%s\", got %s",
                      rel, want + 6, got);
        else
            CHECK_MSG(!strcmp(got, want), "%s: expected %s, got %s", rel, want, got);
    }
    fclose(f);
    for (int i = 0; i < npaths; i++) CHECK_MSG(listed[i], "%s: installed but not in %s", paths[i], TABLE);
    printf("%d models checked against %s\n", rows, TABLE);
    return check_result();
}
