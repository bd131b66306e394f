#include "state.h"
#include <string.h>

sl_mat_value *sl_app_material_value(sl_app *app, int m, const char *key) {
    if (m < 0 || m >= app->scene.material_count || !app->materials) return NULL;
    sl_mat_state *ms = &app->materials[m];
    for (int i = 0; i < ms->count; i++)
        if (!strcmp(app->params.items[ms->values[i].param].full_id, key)) return &ms->values[i];
    return NULL;
}
