/* Scene graph bookkeeping: building blocks, freeing, transforms, bounds, asset paths. */
#include "scene/scene.h"
#include "fileio.h"

#include <cglm/cglm.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* ---- small utilities -------------------------------------------------------------------- */

static char *dup_str(const char *s) { return s ? strdup(s) : NULL; }

/* Grows *items (each `size` bytes) so that index `count` fits; zero-fills the new slot. */
static bool grow(void **items, int count, size_t size) {
    if (count < 0 || count >= (1 << 28)) return false;
    /* capacity doubles: realloc on powers of two only */
    if (count == 0 || (count & (count - 1)) == 0) {
        size_t cap = count == 0 ? 4 : (size_t)count * 2;
        void *p = realloc(*items, cap * size);
        if (!p) return false;
        *items = p;
    }
    memset((char *)*items + (size_t)count * size, 0, size);
    return true;
}

/* ---- properties --------------------------------------------------------------------------- */

const sl_prop *sl_prop_find(const sl_prop_list *list, const char *key) {
    if (!list || !key) return NULL;
    for (int i = 0; i < list->count; i++)
        if (strcmp(list->items[i].key, key) == 0) return &list->items[i];
    return NULL;
}

static sl_prop *prop_slot(sl_prop_list *list, const char *key, int line) {
    for (int i = 0; i < list->count; i++) {
        sl_prop *p = &list->items[i];
        if (strcmp(p->key, key) == 0) {
            free(p->str);
            p->str = NULL;
            memset(p->v, 0, sizeof p->v);
            p->count = 0;
            p->line = line;
            return p;
        }
    }
    if (!grow((void **)&list->items, list->count, sizeof(sl_prop))) return NULL;
    sl_prop *p = &list->items[list->count];
    p->key = strdup(key);
    if (!p->key) return NULL;
    p->line = line;
    list->count++;
    return p;
}

sl_prop *sl_prop_set_number(sl_prop_list *list, const char *key, float value, int line) {
    sl_prop *p = prop_slot(list, key, line);
    if (!p) return NULL;
    p->kind = SL_PROP_NUMBER;
    p->v[0] = value;
    p->count = 1;
    return p;
}

sl_prop *sl_prop_set_bool(sl_prop_list *list, const char *key, bool value, int line) {
    sl_prop *p = prop_slot(list, key, line);
    if (!p) return NULL;
    p->kind = SL_PROP_BOOL;
    p->v[0] = value ? 1.0f : 0.0f;
    p->count = 1;
    return p;
}

sl_prop *sl_prop_set_string(sl_prop_list *list, const char *key, const char *value, int line) {
    sl_prop *p = prop_slot(list, key, line);
    if (!p) return NULL;
    p->kind = SL_PROP_STRING;
    p->str = strdup(value ? value : "");
    return p->str ? p : NULL;
}

sl_prop *sl_prop_set_vec(sl_prop_list *list, const char *key, const float *v, int count, int line) {
    if (count < 1 || count > 4) return NULL;
    sl_prop *p = prop_slot(list, key, line);
    if (!p) return NULL;
    p->kind = count == 1 ? SL_PROP_NUMBER : SL_PROP_VEC;
    memcpy(p->v, v, sizeof(float) * (size_t)count);
    p->count = count;
    return p;
}

void sl_prop_list_free(sl_prop_list *list) {
    if (!list) return;
    for (int i = 0; i < list->count; i++) {
        free(list->items[i].key);
        free(list->items[i].str);
    }
    free(list->items);
    list->items = NULL;
    list->count = 0;
}

/* ---- meshes ------------------------------------------------------------------------------- */

bool sl_mesh_alloc(sl_mesh_data *m, int vertex_count, int index_count) {
    memset(m, 0, sizeof *m);
    if (vertex_count < 0 || index_count < 0 || vertex_count > (1 << 26) || index_count > (1 << 28))
        return false;
    size_t v = (size_t)(vertex_count > 0 ? vertex_count : 1);
    size_t i = (size_t)(index_count > 0 ? index_count : 1);
    m->positions = calloc(v * 3, sizeof(float));
    m->normals = calloc(v * 3, sizeof(float));
    m->tangents = calloc(v * 4, sizeof(float));
    m->uvs = calloc(v * 2, sizeof(float));
    m->indices = calloc(i, sizeof(uint32_t));
    if (!m->positions || !m->normals || !m->tangents || !m->uvs || !m->indices) {
        sl_mesh_free(m);
        return false;
    }
    m->vertex_count = vertex_count;
    m->index_count = index_count;
    return true;
}

void sl_mesh_free(sl_mesh_data *m) {
    if (!m) return;
    free(m->positions);
    free(m->normals);
    free(m->tangents);
    free(m->uvs);
    free(m->uvs1);
    free(m->colors);
    free(m->indices);
    memset(m, 0, sizeof *m);
}

void sl_mesh_compute_bounds(sl_mesh_data *m) {
    if (m->vertex_count <= 0) {
        memset(m->bounds_min, 0, sizeof m->bounds_min);
        memset(m->bounds_max, 0, sizeof m->bounds_max);
        return;
    }
    for (int c = 0; c < 3; c++) m->bounds_min[c] = m->bounds_max[c] = m->positions[c];
    for (int i = 1; i < m->vertex_count; i++)
        for (int c = 0; c < 3; c++) {
            float x = m->positions[3 * i + c];
            if (x < m->bounds_min[c]) m->bounds_min[c] = x;
            if (x > m->bounds_max[c]) m->bounds_max[c] = x;
        }
}

/* ---- scene items -------------------------------------------------------------------------- */

#define FIND_BY_NAME(array, count)                                                           \
    if (!scene || !name) return -1;                                                          \
    for (int i = 0; i < scene->count; i++)                                                   \
        if (scene->array[i].name && strcmp(scene->array[i].name, name) == 0) return i;       \
    return -1;

int sl_scene_find_material(const sl_scene *scene, const char *name) { FIND_BY_NAME(materials, material_count) }
int sl_scene_find_node(const sl_scene *scene, const char *name) { FIND_BY_NAME(nodes, node_count) }
int sl_scene_find_light(const sl_scene *scene, const char *name) { FIND_BY_NAME(lights, light_count) }

bool sl_environment_is_constant(const sl_environment *env) {
    return !env->map && (env->color[0] > 0 || env->color[1] > 0 || env->color[2] > 0);
}

bool sl_scene_node_has_tag(const sl_scene *scene, int node, const char *tag) {
    /* parents come before children (sl_scene_add_node), so the walk up ends */
    for (int n = node; n >= 0 && n < scene->node_count; n = scene->nodes[n].parent)
        for (int k = 0; k < scene->nodes[n].tag_count; k++)
            if (!strcmp(scene->nodes[n].tags[k], tag)) return true;
    return false;
}
int sl_scene_find_camera(const sl_scene *scene, const char *name) { FIND_BY_NAME(cameras, camera_count) }

int sl_scene_add_material(sl_scene *scene, const char *name, const char *model) {
    if (!grow((void **)&scene->materials, scene->material_count, sizeof(sl_material))) return -1;
    sl_material *m = &scene->materials[scene->material_count];
    m->name = dup_str(name ? name : "");
    m->model = dup_str(model ? model : "lambert");
    m->cast_shadows = true;
    if (!m->name || !m->model) {
        free(m->name);
        free(m->model);
        return -1;
    }
    return scene->material_count++;
}

static const float identity16[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

int sl_scene_add_node(sl_scene *scene, const char *name, int parent) {
    if (parent < -1 || parent >= scene->node_count) return -1;
    if (!grow((void **)&scene->nodes, scene->node_count, sizeof(sl_node))) return -1;
    sl_node *n = &scene->nodes[scene->node_count];
    n->name = dup_str(name ? name : "");
    if (!n->name) return -1;
    n->parent = parent;
    memcpy(n->local, identity16, sizeof identity16);
    memcpy(n->world, identity16, sizeof identity16);
    return scene->node_count++;
}

int sl_scene_add_mesh(sl_scene *scene, const char *name, sl_mesh_data *data, int material) {
    if (!grow((void **)&scene->meshes, scene->mesh_count, sizeof(sl_mesh))) {
        sl_mesh_free(data);
        return -1;
    }
    sl_mesh *m = &scene->meshes[scene->mesh_count];
    m->name = dup_str(name ? name : "");
    if (!m->name) {
        sl_mesh_free(data);
        return -1;
    }
    m->data = *data;
    memset(data, 0, sizeof *data);
    m->material = material;
    return scene->mesh_count++;
}

bool sl_scene_node_add_mesh(sl_scene *scene, int node, int mesh) {
    if (node < 0 || node >= scene->node_count || mesh < 0 || mesh >= scene->mesh_count) return false;
    sl_node *n = &scene->nodes[node];
    if (!grow((void **)&n->meshes, n->mesh_count, sizeof(int))) return false;
    n->meshes[n->mesh_count++] = mesh;
    return true;
}

int sl_scene_add_light(sl_scene *scene, const char *name, const char *type) {
    if (!grow((void **)&scene->lights, scene->light_count, sizeof(sl_light))) return -1;
    sl_light *l = &scene->lights[scene->light_count];
    l->name = dup_str(name ? name : "");
    l->type = dup_str(type ? type : "point");
    if (!l->name || !l->type) {
        free(l->name);
        free(l->type);
        return -1;
    }
    l->direction[1] = -1.0f;
    l->color[0] = l->color[1] = l->color[2] = 1.0f;
    l->intensity = 1.0f;
    l->angular_radius = 0.5f;
    l->enabled = true;
    l->animate_speed = 0.5f;
    l->animate_amount = 15.0f;
    return scene->light_count++;
}

/* v rotated by angle a about the unit axis k (Rodrigues' formula). */
static void rotate_about(float v[3], const float k[3], float a) {
    float c = cosf(a), s = sinf(a), d = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
    float x[3] = {k[1] * v[2] - k[2] * v[1], k[2] * v[0] - k[0] * v[2], k[0] * v[1] - k[1] * v[0]};
    for (int i = 0; i < 3; i++) v[i] = v[i] * c + x[i] * s + k[i] * d * (1 - c);
}

void sl_light_at_time(const sl_light *L, double t, float pos[3], float dir[3]) {
    memcpy(pos, L->position, 3 * sizeof *pos);
    memcpy(dir, L->direction, 3 * sizeof *dir);
    const float up[3] = {0, 1, 0};
    if (L->animate == SL_ANIMATE_ORBIT) {
        float a = (float)(L->animate_speed * t);
        rotate_about(pos, up, a);
        rotate_about(dir, up, a);
    } else if (L->animate == SL_ANIMATE_WOBBLE) {
        float axis[3] = {-dir[2], 0, dir[0]}; /* dir × up */
        float len = sqrtf(axis[0] * axis[0] + axis[2] * axis[2]);
        if (len > 1e-4f) axis[0] /= len, axis[2] /= len;
        else axis[0] = 1, axis[2] = 0;
        rotate_about(dir, axis, (float)(L->animate_amount * M_PI / 180 * sin(L->animate_speed * t)));
        float n = sqrtf(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
        for (int i = 0; i < 3; i++) dir[i] /= n;
    }
}

int sl_scene_add_camera(sl_scene *scene, const char *name) {
    if (!grow((void **)&scene->cameras, scene->camera_count, sizeof(sl_camera))) return -1;
    sl_camera *c = &scene->cameras[scene->camera_count];
    c->name = dup_str(name ? name : "");
    if (!c->name) return -1;
    c->position[2] = 5.0f;
    c->up[1] = 1.0f;
    c->fov_y_deg = 45.0f;
    c->xmag = c->ymag = 1.0f;
    c->znear = 0.05f;
    c->zfar = 100.0f;
    return scene->camera_count++;
}

int sl_scene_add_image(sl_scene *scene, const char *name, const void *data, size_t size) {
    if (!grow((void **)&scene->images, scene->image_count, sizeof(sl_embedded_image))) return -1;
    sl_embedded_image *e = &scene->images[scene->image_count];
    e->name = dup_str(name);
    e->data = malloc(size ? size : 1);
    if (!e->name || !e->data) {
        free(e->name);
        free(e->data);
        return -1;
    }
    memcpy(e->data, data, size);
    e->size = size;
    return scene->image_count++;
}

const sl_texture_sampler *sl_scene_find_sampler(const sl_scene *scene, const char *texture) {
    for (int i = 0; texture && i < scene->sampler_count; i++)
        if (!strcmp(scene->samplers[i].texture, texture)) return &scene->samplers[i];
    return NULL;
}

bool sl_scene_set_sampler(sl_scene *scene, const sl_texture_sampler *sampler) {
    const sl_texture_sampler *prev = sl_scene_find_sampler(scene, sampler->texture);
    if (prev)
        return prev->wrap_s == sampler->wrap_s && prev->wrap_t == sampler->wrap_t &&
               prev->mag_filter == sampler->mag_filter && prev->min_filter == sampler->min_filter;
    if (!grow((void **)&scene->samplers, scene->sampler_count, sizeof(sl_texture_sampler))) return false;
    sl_texture_sampler *d = &scene->samplers[scene->sampler_count];
    *d = *sampler;
    if (!(d->texture = dup_str(sampler->texture))) return false;
    scene->sampler_count++;
    return true;
}

const sl_embedded_image *sl_scene_find_image(const sl_scene *scene, const char *name) {
    for (int i = 0; name && i < scene->image_count; i++)
        if (!strcmp(scene->images[i].name, name)) return &scene->images[i];
    return NULL;
}

void sl_scene_free(sl_scene *scene) {
    if (!scene) return;
    for (int i = 0; i < scene->image_count; i++) {
        free(scene->images[i].name);
        free(scene->images[i].data);
    }
    free(scene->images);
    for (int i = 0; i < scene->sampler_count; i++) free(scene->samplers[i].texture);
    free(scene->samplers);
    for (int i = 0; i < scene->anim_channel_count; i++) {
        free(scene->anim_channels[i].times);
        free(scene->anim_channels[i].values);
    }
    free(scene->anim_channels);
    free(scene->anim_nodes);
    free(scene->path);
    free(scene->dir);
    free(scene->generated_by);
    for (int i = 0; i < scene->material_count; i++) {
        free(scene->materials[i].name);
        free(scene->materials[i].model);
        sl_prop_list_free(&scene->materials[i].props);
        sl_prop_list_free(&scene->materials[i].inputs);
        free(scene->materials[i].source);
        for (int k = 0; k < scene->materials[i].uv_map_count; k++) free(scene->materials[i].uv_maps[k].input);
        free(scene->materials[i].uv_maps);
    }
    free(scene->materials);
    for (int i = 0; i < scene->mesh_count; i++) {
        free(scene->meshes[i].name);
        sl_mesh_free(&scene->meshes[i].data);
        sl_mesh_deform_free(scene->meshes[i].deform);
    }
    free(scene->meshes);
    for (int i = 0; i < scene->skin_count; i++) free(scene->skins[i].joints), free(scene->skins[i].inverse_bind);
    free(scene->skins);
    for (int i = 0; i < scene->node_count; i++) {
        free(scene->nodes[i].name);
        free(scene->nodes[i].meshes);
        for (int k = 0; k < scene->nodes[i].tag_count; k++) free(scene->nodes[i].tags[k]);
        free(scene->nodes[i].tags);
    }
    free(scene->nodes);
    for (int i = 0; i < scene->light_count; i++) {
        free(scene->lights[i].name);
        free(scene->lights[i].type);
        sl_prop_list_free(&scene->lights[i].props);
    }
    free(scene->lights);
    for (int i = 0; i < scene->camera_count; i++) free(scene->cameras[i].name);
    free(scene->cameras);
    free(scene->environment.map);
    sl_prop_list_free(&scene->environment.props);
    for (int i = 0; i < scene->plugin_count; i++) free(scene->plugins[i]);
    free(scene->plugins);
    sl_prop_list_free(&scene->params);
    memset(scene, 0, sizeof *scene);
}

/* ---- transforms --------------------------------------------------------------------------- */

void sl_mat4_from_trs(float out[16], const float t[3], const float q_xyzw[4], const float s[3]) {
    /* cglm's mat4/versor are aligned types: work on aligned locals, copy out. */
    mat4 m;
    versor q = {q_xyzw[0], q_xyzw[1], q_xyzw[2], q_xyzw[3]};
    glm_quat_normalize(q);
    glm_quat_mat4(q, m);
    for (int c = 0; c < 3; c++)
        for (int r = 0; r < 3; r++) m[c][r] *= s[c];
    m[3][0] = t[0];
    m[3][1] = t[1];
    m[3][2] = t[2];
    memcpy(out, m, sizeof(float) * 16);
}

void sl_quat_from_euler_deg(float out[4], const float deg[3]) {
    versor qx, qy, qz, qyx, q;
    glm_quatv(qx, glm_rad(deg[0]), (vec3){1, 0, 0});
    glm_quatv(qy, glm_rad(deg[1]), (vec3){0, 1, 0});
    glm_quatv(qz, glm_rad(deg[2]), (vec3){0, 0, 1});
    glm_quat_mul(qy, qx, qyx); /* X first, then Y … */
    glm_quat_mul(qz, qyx, q);  /* … then Z */
    memcpy(out, q, sizeof(float) * 4);
}

static void transform_point(const float m[16], const float p[3], float out[3]) {
    for (int r = 0; r < 3; r++)
        out[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
}

void sl_scene_update_transforms(sl_scene *scene) {
    bool any = false;
    for (int i = 0; i < scene->node_count; i++) {
        sl_node *n = &scene->nodes[i];
        mat4 local, world;
        memcpy(local, n->local, sizeof local);
        /* Parents come first (sl_scene_add_node enforces it); anything else is a root. */
        if (n->parent >= 0 && n->parent < i) {
            mat4 parent;
            memcpy(parent, scene->nodes[n->parent].world, sizeof parent);
            glm_mat4_mul(parent, local, world);
        } else {
            glm_mat4_copy(local, world);
        }
        memcpy(n->world, world, sizeof world);
        for (int k = 0; k < n->mesh_count; k++) {
            int mi = n->meshes[k];
            if (mi < 0 || mi >= scene->mesh_count || scene->meshes[mi].data.vertex_count == 0) continue;
            const sl_mesh_data *d = &scene->meshes[mi].data;
            for (int corner = 0; corner < 8; corner++) {
                float p[3] = {(corner & 1) ? d->bounds_max[0] : d->bounds_min[0],
                              (corner & 2) ? d->bounds_max[1] : d->bounds_min[1],
                              (corner & 4) ? d->bounds_max[2] : d->bounds_min[2]};
                float w[3];
                transform_point(n->world, p, w);
                for (int c = 0; c < 3; c++) {
                    if (!any || w[c] < scene->bounds_min[c]) scene->bounds_min[c] = w[c];
                    if (!any || w[c] > scene->bounds_max[c]) scene->bounds_max[c] = w[c];
                }
                any = true;
            }
        }
    }
    if (!any) {
        memset(scene->bounds_min, 0, sizeof scene->bounds_min);
        memset(scene->bounds_max, 0, sizeof scene->bounds_max);
    }
}

/* ---- asset paths -------------------------------------------------------------------------- */

/* Why `path` cannot be used as a file: NULL when it is a readable regular file (never opened:
 * a FIFO named by a scene must not block the check). */
static const char *file_problem(const char *path) {
    static _Thread_local char why[128];
    return sl_input_file_problem(path, why, sizeof why);
}

static char *join_path(const char *dir, const char *rel) {
    size_t n = strlen(dir) + strlen(rel) + 2;
    char *p = malloc(n);
    if (!p) return NULL;
    size_t dl = strlen(dir);
    snprintf(p, n, "%s%s%s", dir, (dl && dir[dl - 1] != '/') ? "/" : "", rel);
    return p;
}

char *sl_scene_resolve_path(const sl_scene *scene, const char *data_dir, const char *rel,
                            char *err, size_t err_size) {
    if (err && err_size) err[0] = 0;
    if (!rel || !rel[0]) {
        if (err && err_size) snprintf(err, err_size, "empty path");
        return NULL;
    }
    if (!data_dir || !data_dir[0]) data_dir = getenv("SHADELAB_DATA");
    if (rel[0] == '/') {
        const char *why = file_problem(rel);
        if (!why) return strdup(rel);
        if (err && err_size) snprintf(err, err_size, "'%s': %s", rel, why);
        return NULL;
    }
    const char *dirs[2] = {scene && scene->dir && scene->dir[0] ? scene->dir : NULL,
                           data_dir && data_dir[0] ? data_dir : NULL};
    const char *labels[2] = {"scene directory", "data directory"};
    char tried[2048];
    size_t used = 0;
    bool unusable = false; /* a candidate exists but cannot be read (FIFO, device, directory, permission) */
    tried[0] = 0;
    for (int i = 0; i < 2; i++) {
        if (!dirs[i]) continue;
        char *full = join_path(dirs[i], rel);
        if (!full) break;
        const char *why = file_problem(full);
        if (!why) return full;
        struct stat st;
        unusable |= stat(full, &st) == 0;
        if (used < sizeof tried) {
            int w = snprintf(tried + used, sizeof tried - used, "%s%s %s (%s)", used ? "; " : "",
                             labels[i], full, why);
            if (w > 0) used += (size_t)w;
        }
        free(full);
    }
    if (err && err_size) {
        if (!used)
            snprintf(err, err_size, "'%s' not found: no scene directory and no data directory "
                     "(--data DIR or SHADELAB_DATA) to look in", rel);
        else if (scene && scene->generated_by && !unusable)
            snprintf(err, err_size, "'%s' not found; looked in: %s. This scene's files are generated: run %s", rel,
                     tried, scene->generated_by);
        else
            snprintf(err, err_size, "'%s' %s; looked in: %s%s", rel, unusable ? "cannot be read" : "not found", tried,
                     dirs[1] || unusable ? "" : " (no data directory set: --data DIR or SHADELAB_DATA)");
    }
    return NULL;
}

/* ---- node TRS animation (glTF 2.0 §3.11 and appendix C, "Animation interpolation") ---- */

void sl_mesh_deform_free(sl_mesh_deform *d) {
    if (!d) return;
    free(d->target_positions), free(d->target_normals), free(d->target_tangents);
    free(d->weights), free(d->rest_weights), free(d->joints), free(d->joint_weights);
    free(d);
}

void sl_anim_sample(const sl_anim_channel *c, double t, float *out) {
    int comps = c->path == SL_ANIM_WEIGHTS ? c->components : c->path == SL_ANIM_ROTATION ? 4 : 3, n = c->key_count;
    int stride = c->interpolation == SL_ANIM_CUBICSPLINE ? 3 * comps : comps;
    int vo = c->interpolation == SL_ANIM_CUBICSPLINE ? comps : 0; /* the value within a key */
    if (n <= 0) return;
    if (t <= c->times[0] || n == 1) {
        memcpy(out, c->values + vo, sizeof(float) * (size_t)comps);
    } else if (t >= c->times[n - 1]) {
        memcpy(out, c->values + (size_t)(n - 1) * stride + vo, sizeof(float) * (size_t)comps);
    } else {
        int k = 0, hi = n - 1; /* the key interval [k, k + 1] holding t (binary search) */
        while (hi - k > 1) {
            int mid = (k + hi) / 2;
            if (c->times[mid] <= t) k = mid;
            else hi = mid;
        }
        double td = c->times[k + 1] - c->times[k], s = td > 0 ? (t - c->times[k]) / td : 0;
        const float *a = c->values + (size_t)k * stride, *b = c->values + (size_t)(k + 1) * stride;
        if (c->interpolation == SL_ANIM_STEP) {
            memcpy(out, a, sizeof(float) * (size_t)comps);
        } else if (c->interpolation == SL_ANIM_CUBICSPLINE) {
            /* p(s) = (2s³ − 3s² + 1) v_k + td (s³ − 2s² + s) b_k + (−2s³ + 3s²) v_k+1 + td (s³ − s²) a_k+1,
             * keys stored as (in-tangent a, value v, out-tangent b) */
            double s2 = s * s, s3 = s2 * s;
            for (int i = 0; i < comps; i++)
                out[i] = (float)((2 * s3 - 3 * s2 + 1) * a[comps + i] + td * (s3 - 2 * s2 + s) * a[2 * comps + i] +
                                 (-2 * s3 + 3 * s2) * b[comps + i] + td * (s3 - s2) * b[i]);
        } else if (c->path == SL_ANIM_ROTATION) {
            /* spherical linear interpolation along the shorter arc */
            double d = 0, q1[4];
            for (int i = 0; i < 4; i++) d += (double)a[i] * b[i];
            double sign = d < 0 ? -1 : 1;
            d = fabs(d);
            for (int i = 0; i < 4; i++) q1[i] = sign * b[i];
            double wa = 1 - s, wb = s;
            if (d < 0.9999995) {
                double th = acos(d), st = sin(th);
                wa = sin((1 - s) * th) / st, wb = sin(s * th) / st;
            }
            for (int i = 0; i < 4; i++) out[i] = (float)(wa * a[i] + wb * q1[i]);
        } else {
            for (int i = 0; i < comps; i++) out[i] = (float)(a[i] + s * (b[i] - a[i]));
        }
    }
    if (c->path == SL_ANIM_ROTATION) { /* unit quaternion (cubic splines and lerps leave the sphere) */
        double l = sqrt((double)out[0] * out[0] + (double)out[1] * out[1] + (double)out[2] * out[2] + (double)out[3] * out[3]);
        if (l > 1e-12 && isfinite(l)) for (int i = 0; i < 4; i++) out[i] = (float)(out[i] / l);
        else out[0] = out[1] = out[2] = 0, out[3] = 1;
    }
}

void sl_scene_animate(sl_scene *scene, double t) {
    if (!scene->anim_channel_count) return;
    double d = scene->anim_duration;
    if (d > 0 && isfinite(t)) t = fmod(t, d) + (fmod(t, d) < 0 ? d : 0);
    for (int a = 0; a < scene->anim_node_count; a++) {
        const sl_anim_node *an = &scene->anim_nodes[a];
        float T[3], R[4], S[3];
        memcpy(T, an->t, sizeof T), memcpy(R, an->r, sizeof R), memcpy(S, an->s, sizeof S);
        for (int i = 0; i < scene->anim_channel_count; i++) {
            const sl_anim_channel *c = &scene->anim_channels[i];
            if (c->node != an->node || c->path == SL_ANIM_WEIGHTS) continue;
            float v[4];
            sl_anim_sample(c, t, v);
            if (c->path == SL_ANIM_TRANSLATION) memcpy(T, v, sizeof T);
            else if (c->path == SL_ANIM_ROTATION) memcpy(R, v, sizeof R);
            else memcpy(S, v, sizeof S);
        }
        /* local = T · R · S, column-major; R from the unit quaternion (x, y, z, w) */
        float x = R[0], y = R[1], z = R[2], w = R[3], *m = scene->nodes[an->node].local;
        float r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w),
                      2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
                      2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)};
        for (int col = 0; col < 3; col++) {
            for (int row = 0; row < 3; row++) m[col * 4 + row] = r[col * 3 + row] * S[col];
            m[col * 4 + 3] = 0;
        }
        m[12] = T[0], m[13] = T[1], m[14] = T[2], m[15] = 1;
    }
    /* morph target weights: into every deformed mesh the node draws with that many targets */
    for (int i = 0; i < scene->anim_channel_count; i++) {
        const sl_anim_channel *c = &scene->anim_channels[i];
        if (c->path != SL_ANIM_WEIGHTS) continue;
        const sl_node *node = &scene->nodes[c->node];
        for (int k = 0; k < node->mesh_count; k++) {
            sl_mesh_deform *d = scene->meshes[node->meshes[k]].deform;
            if (d && d->target_count == c->components) sl_anim_sample(c, t, d->weights);
        }
    }
    sl_scene_update_transforms(scene);
}
