/* Key bindings: two plugins (keys-a loaded first, keys-b second) want the same keys, some of
 * which the viewer owns. The documented resolution (core/viewer.h): first come keeps the key,
 * the next binding moves to Shift+key, and when Shift+key is taken too it is left unbound
 * (panel only); every clash is reported naming both sides. Also: a key press runs the binding
 * through the panel's apply path (bool toggles, enum cycles). */
#include "check.h"
#include "app.h"
#include "viewer.h"
#include <stdlib.h>

static const char *scene =
    "{\"materials\": [{\"name\": \"m\"}], \"nodes\": [{\"name\": \"n\", \"mesh\": {\"primitive\": \"sphere\"}, \"material\": \"m\"}],"
    " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, -1, -1]}]}";

static const sl_key_binding *find(const sl_key_binding *b, int n, sl_app *app, const char *owner, const char *key) {
    for (int i = 0; i < n; i++) {
        const sl_key_reg *k = &app->plugins.keys[b[i].reg];
        if (!strcmp(app->plugins.items[k->owner]->id, owner) && !strcmp(k->d.key, key)) return &b[i];
    }
    return NULL;
}

int main(void) {
    sl_app app;
    char err[4096];
    sl_app_options opt = {.scene_text = scene, .backend = SL_BACKEND_OSMESA, .width = 16, .height = 16,
                          .plugins = {SL_KEYS_A, SL_KEYS_B}, .plugin_count = 2, .strict = true,
                          .no_default_plugins = true}; /* these two plugins' keys only */
    CHECK_MSG(sl_app_init(&app, &opt, err, sizeof err), "%s", err);
    sl_key_binding b[32];
    char *warnings = NULL;
    size_t wsize = 0;
    FILE *w = open_memstream(&warnings, &wsize);
    int n = sl_viewer_resolve_keys(&app, b, 32, w);
    fclose(w);
    printf("%s", warnings);
    CHECK(n == 10);

    const sl_key_binding *a1 = find(b, n, &app, "keys-a", "1"), *b1 = find(b, n, &app, "keys-b", "1");
    CHECK(a1 && !a1->shift && !a1->unbound && !a1->clash[0] && !strcmp(a1->key, "1"));
    CHECK(b1 && b1->shift && !b1->unbound);       /* keys-a came first: keys-b gets Shift+1 */
    if (b1) CHECK_CONTAINS(b1->clash, "plugin keys-a");
    CHECK_CONTAINS(warnings, "key 1: plugin keys-b");
    CHECK_CONTAINS(warnings, "plugin keys-a (\"keys-a flag\") both want it; plugin keys-a (\"keys-a flag\") keeps 1");
    CHECK_CONTAINS(warnings, "plugin keys-b gets Shift+1");

    /* "p" is the viewer's screenshot key: keys-a moves to Shift+P; keys-b finds Shift+P taken */
    const sl_key_binding *ap = find(b, n, &app, "keys-a", "p"), *bp = find(b, n, &app, "keys-b", "p");
    CHECK(ap && ap->shift && !ap->unbound && !strcmp(ap->key, "P"));
    if (ap) CHECK_CONTAINS(ap->clash, "the viewer (screenshot)");
    CHECK(bp && bp->unbound);
    CHECK_CONTAINS(warnings, "Shift+P is taken too; keys-b's binding is left unbound");

    /* W and Shift+W both belong to the viewer (fly, fast fly) */
    const sl_key_binding *aw = find(b, n, &app, "keys-a", "W");
    CHECK(aw && aw->unbound);
    if (aw) CHECK_CONTAINS(aw->clash, "the viewer (fly)");

    /* invalid key names are reported, not silently dropped */
    const sl_key_binding *ak = find(b, n, &app, "keys-a", "Ctrl+K");
    CHECK(ak && ak->unbound && ak->code < 0);
    CHECK_CONTAINS(warnings, "plugin keys-a: key \"Ctrl+K\"");

    /* each clash is reported once per binding */
    int lines = 0;
    for (const char *p = warnings; (p = strstr(p, "warning: ")); p++) lines++;
    CHECK_MSG(lines == 8, "%d warnings", lines); /* b:1 b:2 a:P b:P a:W b:W a:Ctrl+K b:Ctrl+K */

    /* --help-keys prints the resolved table */
    char *help = NULL;
    size_t hsize = 0;
    FILE *h = open_memstream(&help, &hsize);
    sl_viewer_print_keys(&app, h);
    fclose(h);
    CHECK_CONTAINS(help, "Shift+1       keys-b flag [keys-b]  (1 was taken by plugin keys-a");
    CHECK_CONTAINS(help, "(panel only)  keys-b wants the screenshot key [keys-b]");

    /* pressing a binding toggles a bool and cycles an enum through the GUI path (source GUI) */
    sl_param *flag = sl_params_find(&app.params, "keys-b.flag");
    sl_param *mode = sl_params_find(&app.params, "keys-a.mode");
    CHECK(flag && !flag->value.b);
    if (b1) sl_viewer_trigger_binding(&app, b1);
    CHECK(flag && flag->value.b && flag->source == SL_SRC_GUI);
    const sl_key_binding *a2 = find(b, n, &app, "keys-a", "2");
    CHECK(mode && mode->value.i == 0);
    for (int i = 0; i < 4 && a2; i++) sl_viewer_trigger_binding(&app, a2);
    CHECK(mode && mode->value.i == 1); /* one → two → three → one → two */
    /* a binding of a plugin switched off does nothing */
    CHECK(sl_app_set(&app, "keys-b.enabled=false", SL_SRC_GUI, err, sizeof err));
    if (b1) sl_viewer_trigger_binding(&app, b1);
    CHECK(flag && flag->value.b);

    free(warnings);
    free(help);
    sl_app_shutdown(&app);
    return check_result();
}
