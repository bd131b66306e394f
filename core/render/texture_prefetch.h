/* Material textures decoded ahead on a worker thread (issue 18 item 5). sl_app_start_gl starts it
 * before the GL context (the parameters, hence which material keys are textures, are known then);
 * load_texture (scene_gpu.c) takes a decoded image by its scene string, waiting for it if need
 * be, and decodes itself what was not prefetched; the scene upload then joins the thread and
 * frees what was not taken. Decoding is sl_image_load, the same call load_texture made: the same
 * pixels and messages (the log is thread-safe), earlier. SHADELAB_NO_PREFETCH=1 decodes on the
 * main thread as before (for A/B timing). */
#ifndef SL_TEXTURE_PREFETCH_H
#define SL_TEXTURE_PREFETCH_H
#include "image/image.h"
#include <stdbool.h>
#include <stddef.h>

typedef struct sl_app sl_app;
void sl_texture_prefetch_start(sl_app *app);
/* True when `spec` was prefetched for app (not taken before): *img, *ok and err as sl_image_load
 * gave them; the caller owns img. */
bool sl_texture_prefetch_take(const sl_app *app, const char *spec, sl_image *img, bool *ok, char *err, size_t err_size);
/* Joins the worker and frees what was not taken (app NULL: whatever is pending). */
void sl_texture_prefetch_finish(const sl_app *app);
#endif
