/* Discovery: which plugins are installed or built, and which standard material inputs each one
 * declares it handles (sl_plugin_desc.material_inputs, ABI 1.6), read from the descriptors in
 * the search directories without calling create(). The app uses it to load the plugins an
 * imported material needs, and no more (docs/design-notes.md, "Material inputs"). */
#include "plugin/plugins.h"
#include <dirent.h>
#include <dlfcn.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static bool plugin_file(const char *dir, const char *id, char *out, size_t n) {
    struct stat st;
    snprintf(out, n, "%s/%s/%s.so", dir, id, id);
    return stat(out, &st) == 0 && S_ISREG(st.st_mode);
}

bool sl_plugin_available(const char *id) {
    char dirs[16][1024], path[2200];
    int nd = sl_plugin_search_dirs(dirs, 16);
    for (int i = 0; i < nd; i++)
        if (plugin_file(dirs[i], id, path, sizeof path)) return true;
    return false;
}

static int cmp_str(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

/* The entries of plugin directory `path` (not hidden, names shorter than 64), sorted: the same
 * order, so the same choices, on every machine. Returns the count; the caller frees each name. */
static int sorted_entries(const char *path, char *names[256]) {
    DIR *dir = opendir(path);
    if (!dir) return 0;
    int count = 0;
    for (struct dirent *e; (e = readdir(dir)) && count < 256;)
        if (e->d_name[0] != '.' && strlen(e->d_name) < 64) names[count++] = strdup(e->d_name);
    closedir(dir);
    qsort(names, count, sizeof *names, cmp_str);
    return count;
}

/* The descriptor's list of standard material inputs or of shading models (NULL when it has none
 * or is too old to have that field). */
typedef enum { LIST_MATERIAL_INPUTS, LIST_SHADING_MODELS } desc_list;

static const char *const *desc_list_of(const sl_plugin_desc *d, desc_list which) {
    if (!d || d->abi_major != SL_ABI_MAJOR || d->abi_minor > SL_ABI_MINOR) return NULL;
    if (which == LIST_MATERIAL_INPUTS)
        return d->struct_size >= offsetof(sl_plugin_desc, material_inputs) + sizeof(void *) ? d->material_inputs : NULL;
    return d->abi_minor >= 15 && d->struct_size >= offsetof(sl_plugin_desc, shading_models) + sizeof(void *)
               ? d->shading_models : NULL;
}

/* Does the descriptor of the plugin file list `name` (a material input or a shading model)? The
 * library is opened lazily and closed again: nothing of it runs but its entry function. */
static bool declares(const char *path, desc_list which, const char *name) {
    void *dl = dlopen(path, RTLD_LAZY | RTLD_LOCAL);
    if (!dl) return false;
    bool found = false;
    sl_plugin_entry_fn entry = (sl_plugin_entry_fn)dlsym(dl, SL_PLUGIN_ENTRY_SYMBOL);
    const char *const *list = desc_list_of(entry ? entry() : NULL, which);
    for (int k = 0; list && list[k] && k < 256 && !found; k++) found = !strcmp(list[k], name);
    dlclose(dl);
    return found;
}

/* The default_for bits of the plugin file's descriptor (0 when it has none or cannot be read). */
static unsigned default_bits(const char *path) {
    void *dl = dlopen(path, RTLD_LAZY | RTLD_LOCAL);
    if (!dl) return 0;
    sl_plugin_entry_fn entry = (sl_plugin_entry_fn)dlsym(dl, SL_PLUGIN_ENTRY_SYMBOL);
    const sl_plugin_desc *d = entry ? entry() : NULL;
    unsigned bits = d && d->abi_major == SL_ABI_MAJOR && d->abi_minor <= SL_ABI_MINOR &&
                    d->struct_size >= offsetof(sl_plugin_desc, default_for) + sizeof(unsigned) ? d->default_for : 0;
    dlclose(dl);
    return bits;
}

int sl_plugin_defaults(unsigned bits, char ids[][64], int max) {
    char dirs[16][1024];
    int nd = sl_plugin_search_dirs(dirs, 16), found = 0;
    for (int i = 0; i < nd; i++) {
        char *names[256];
        int count = sorted_entries(dirs[i], names);
        for (int k = 0; k < count; k++) {
            char path[2200];
            bool seen = false; /* an id found in an earlier directory wins */
            for (int j = 0; j < found && names[k]; j++) seen |= !strcmp(ids[j], names[k]);
            if (names[k] && !seen && found < max && plugin_file(dirs[i], names[k], path, sizeof path) &&
                (default_bits(path) & bits))
                snprintf(ids[found++], 64, "%s", names[k]);
            free(names[k]);
        }
    }
    return found;
}

/* The first plugin (directory order, then by name) whose descriptor lists `name`. */
static bool plugin_declaring(desc_list which, const char *name, char *id, size_t n) {
    char dirs[16][1024];
    int nd = sl_plugin_search_dirs(dirs, 16);
    for (int i = 0; i < nd; i++) {
        char *names[256];
        int count = sorted_entries(dirs[i], names);
        bool found = false;
        for (int k = 0; k < count; k++) {
            char path[2200];
            if (!found && names[k] && plugin_file(dirs[i], names[k], path, sizeof path) && declares(path, which, name)) {
                snprintf(id, n, "%s", names[k]);
                found = true;
            }
            free(names[k]);
        }
        if (found) return true;
    }
    return false;
}

bool sl_plugin_for_input(const char *input, char *id, size_t n) {
    return plugin_declaring(LIST_MATERIAL_INPUTS, input, id, n);
}

bool sl_plugin_for_model(const char *model, char *id, size_t n) {
    return plugin_declaring(LIST_SHADING_MODELS, model, id, n);
}

/* The description and the shading models in the plugin file's descriptor (empty when it cannot
 * be read). */
static void describe(const char *path, char *text, size_t n, char *models, size_t m) {
    text[0] = models[0] = 0;
    void *dl = dlopen(path, RTLD_LAZY | RTLD_LOCAL);
    if (!dl) return;
    sl_plugin_entry_fn entry = (sl_plugin_entry_fn)dlsym(dl, SL_PLUGIN_ENTRY_SYMBOL);
    const sl_plugin_desc *d = entry ? entry() : NULL;
    if (d && d->abi_major == SL_ABI_MAJOR && d->description) snprintf(text, n, "%s", d->description);
    sl_plugin_models_text(desc_list_of(d, LIST_SHADING_MODELS), models, m);
    dlclose(dl);
}

void sl_plugin_models_text(const char *const *list, char *out, size_t n) {
    size_t used = 0;
    out[0] = 0;
    for (int k = 0; list && list[k] && k < 256 && used < n; k++)
        used += (size_t)snprintf(out + used, n - used, "%s%s", k ? ", " : "", list[k]);
}

void sl_plugin_print_available(const sl_plugins *P, FILE *f) {
    char dirs[16][1024], listed[256][64];
    int nd = sl_plugin_search_dirs(dirs, 16), count = 0;
    for (int i = 0; i < nd; i++) {
        char *names[256];
        int n = sorted_entries(dirs[i], names);
        for (int k = 0; k < n; k++) {
            char path[2200], text[512], models[512];
            bool seen = false; /* loaded, or found in an earlier directory */
            for (int j = 0; j < P->count && !seen; j++) seen = !strcmp(P->items[j]->id, names[k]);
            for (int j = 0; j < count && !seen; j++) seen = !strcmp(listed[j], names[k]);
            if (!seen && count < 256 && plugin_file(dirs[i], names[k], path, sizeof path)) {
                if (!count) fprintf(f, "available (--plugin NAME):\n");
                snprintf(listed[count++], 64, "%s", names[k]);
                describe(path, text, sizeof text, models, sizeof models);
                fprintf(f, "%-20s          %s\n", names[k], path);
                if (*text) fprintf(f, "    %s\n", text);
                if (*models) fprintf(f, "    shading models: %s\n", models);
            }
            free(names[k]);
        }
    }
}
