/* Material textures decoded on a worker thread while the main thread creates the GL context,
 * activates the plugins and compiles (issue 18 item 5: the head scene's three 1024² JPEGs took
 * 150-350 ms of decoding on the main thread before the first frame). See texture_prefetch.h. */
#include "render/texture_prefetch.h"
#include "state.h"
#include "scene/scene.h"
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

typedef struct job {
    char *spec, *path;                /* the scene's string; the resolved file (NULL: embedded) */
    const sl_embedded_image *embedded;
    sl_image img;
    bool ok, done, taken;
    char err[1024];
} job;

static struct {
    const void *app; /* whose textures (one app prefetches at a time) */
    job *jobs;
    int count;
    bool started;
    pthread_t thread;
    pthread_mutex_t lock;
    pthread_cond_t cond;
} P = {.lock = PTHREAD_MUTEX_INITIALIZER, .cond = PTHREAD_COND_INITIALIZER};

static void *worker(void *arg) {
    (void)arg;
    for (int i = 0; i < P.count; i++) {
        job *j = &P.jobs[i];
        sl_image img;
        char err[1024] = "";
        bool ok = j->embedded ? sl_image_load_memory(&img, j->embedded->data, j->embedded->size, j->embedded->name, err,
                                                     sizeof err)
                              : sl_image_load(&img, j->path, err, sizeof err);
        pthread_mutex_lock(&P.lock);
        j->img = img, j->ok = ok, j->done = true;
        memcpy(j->err, err, sizeof err);
        pthread_cond_broadcast(&P.cond);
        pthread_mutex_unlock(&P.lock);
    }
    return NULL;
}

static bool listed(const char *spec) {
    for (int i = 0; i < P.count; i++)
        if (!strcmp(P.jobs[i].spec, spec)) return true;
    return false;
}

void sl_texture_prefetch_start(sl_app *app) {
    sl_texture_prefetch_finish(NULL);
    if (getenv("SHADELAB_NO_PREFETCH")) return;
    int cap = 0;
    for (int m = 0; m < app->scene.material_count; m++)
        for (int i = 0; i < app->params.count; i++) {
            const sl_param *q = &app->params.items[i];
            if (q->desc.type != SL_PARAM_TEXTURE || q->desc.scope != SL_SCOPE_MATERIAL) continue;
            sl_mat_value *v = sl_app_material_value(app, m, q->full_id);
            if (!v || !v->str || !*v->str || sl_image_is_procedural(v->str) || listed(v->str)) continue;
            const sl_embedded_image *e = sl_scene_find_image(&app->scene, v->str);
            char err[256], *path = e ? NULL : sl_scene_resolve_path(&app->scene, app->opt.data_dir, v->str, err, sizeof err);
            if (!e && !path) continue; /* load_texture reports it */
            if (P.count == cap) {
                cap = cap ? 2 * cap : 8;
                job *grown = realloc(P.jobs, (size_t)cap * sizeof *grown);
                if (!grown) {
                    free(path);
                    goto start;
                }
                P.jobs = grown;
            }
            P.jobs[P.count++] = (job){.spec = strdup(v->str), .path = path, .embedded = e};
        }
start:
    if (!P.count) return;
    P.app = app;
    P.started = pthread_create(&P.thread, NULL, worker, NULL) == 0;
    if (!P.started) sl_texture_prefetch_finish(NULL); /* load_texture decodes itself */
}

bool sl_texture_prefetch_take(const sl_app *app, const char *spec, sl_image *img, bool *ok, char *err, size_t err_size) {
    if (!P.started || P.app != app) return false;
    for (int i = 0; i < P.count; i++) {
        job *j = &P.jobs[i];
        if (j->taken || strcmp(j->spec, spec)) continue;
        pthread_mutex_lock(&P.lock);
        while (!j->done) pthread_cond_wait(&P.cond, &P.lock);
        pthread_mutex_unlock(&P.lock);
        *img = j->img, *ok = j->ok;
        snprintf(err, err_size, "%s", j->err);
        memset(&j->img, 0, sizeof j->img);
        j->taken = true; /* a second use (other flags) decodes again, as before */
        return true;
    }
    return false;
}

void sl_texture_prefetch_finish(const sl_app *app) {
    if (app && P.app != app) return;
    if (P.started) pthread_join(P.thread, NULL);
    for (int i = 0; i < P.count; i++) {
        free(P.jobs[i].spec);
        free(P.jobs[i].path);
        sl_image_free(&P.jobs[i].img);
    }
    free(P.jobs);
    P.jobs = NULL;
    P.count = 0;
    P.started = false;
    P.app = NULL;
}
