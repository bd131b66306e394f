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

/* Does the descriptor of the plugin file declare `input`? The library is opened lazily and
 * closed again: nothing of it runs but its entry function. */
static bool declares(const char *path, const char *input) {
    void *dl = dlopen(path, RTLD_LAZY | RTLD_LOCAL);
    if (!dl) return false;
    bool found = false;
    sl_plugin_entry_fn entry = (sl_plugin_entry_fn)dlsym(dl, SL_PLUGIN_ENTRY_SYMBOL);
    const sl_plugin_desc *d = entry ? entry() : NULL;
    if (d && d->abi_major == SL_ABI_MAJOR && d->abi_minor <= SL_ABI_MINOR &&
        d->struct_size >= offsetof(sl_plugin_desc, material_inputs) + sizeof(void *) && d->material_inputs)
        for (int k = 0; d->material_inputs[k] && k < 256 && !found; k++) found = !strcmp(d->material_inputs[k], input);
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

bool sl_plugin_for_input(const char *input, char *id, size_t n) {
    char dirs[16][1024];
    int nd = sl_plugin_search_dirs(dirs, 16);
    for (int i = 0; i < nd; i++) {
        char *names[256];
        int count = sorted_entries(dirs[i], names);
        bool found = false;
        for (int k = 0; k < count; k++) {
            char path[2200];
            if (!found && names[k] && plugin_file(dirs[i], names[k], path, sizeof path) && declares(path, input)) {
                snprintf(id, n, "%s", names[k]);
                found = true;
            }
            free(names[k]);
        }
        if (found) return true;
    }
    return false;
}
