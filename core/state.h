/* The application's state, as data: options, scene, parameters, plugin registry, per-material
 * and per-light values, camera, debug view, time. The app module (app.h) owns its lifecycle; the
 * renderer (core/render) and the host module (core/host) read and edit it through this header
 * only, so neither depends on the app module above them. */
#ifndef SL_STATE_H
#define SL_STATE_H
#include <shadelab/shadelab.h>
#include "backend/backend.h"
#include "camera.h"
#include "params.h"
#include "plugin/plugins.h"
#include "scene/scene.h"

struct sl_renderer;

typedef struct sl_app_options {
    const char *scene_path;      /* NULL = built-in default scene */
    const char *scene_text;      /* alternative: JSON text (tests) */
    const char *data_dir;        /* --data / SHADELAB_DATA */
    sl_backend_kind backend;
    int width, height;
    const char *plugins[64]; int plugin_count;   /* --plugin NAME|PATH */
    const char *settings[128]; int setting_count; /* --set id=value */
    const char *camera;          /* --camera NAME */
    const char *debug_view;      /* --debug-view NAME */
    bool strict;                 /* a plugin that fails is fatal */
    bool no_default_plugins;     /* do not load the plugins declared SL_PLUGIN_DEFAULT_EVERY_SCENE (aa) */
    bool float32;                /* RGBA32F colour target instead of RGBA16F */
    bool finish_timing;          /* force glFinish timing (default on CPU rasterisers) */
    bool timings;                /* time every pass of every frame (--bench, --stats, --explain, benchmarks);
                                    otherwise only frames after sl_renderer_request_timing (the panel) */
    bool keep_color;             /* "color" must hold the final linear image after each frame (EXR
                                    output, readers of sl_app_read_color): no display-on-write */
    int accumulate;              /* frames averaged per output frame (references), >= 1 */
    /* A model needs no JSON scene: */
    const char *env_map;         /* --env FILE: the environment map (replaces the scene's) */
    bool ground;                 /* --ground: a floor under the bounds that receives shadows */
    bool shadows;                /* --shadows: every light casts them, plus a key light */
    const char *gltf_variant;    /* --variant NAME (KHR_materials_variants) */
    const char *gltf_animation;  /* --animation N|NAME */
    double fixed_dt;             /* seconds per frame for sl_time in headless runs */
} sl_app_options;

/* Per-material values of material-scope keys (validated against the schema). */
typedef struct sl_mat_value {
    int param;          /* index into app->params.items */
    sl_value v;
    char *str;          /* TEXTURE: spec as written (path or procedural) */
    bool present;       /* the scene or --set gave it (only present keys enable chunks) */
} sl_mat_value;
typedef struct sl_mat_state { sl_mat_value *values; int count; } sl_mat_state;

typedef struct sl_app {
    sl_app_options opt;
    sl_backend backend;
    bool gl_ready;
    sl_params params;
    sl_plugins plugins;
    sl_scene scene;
    bool scene_loaded;
    sl_camera_state camera;
    struct sl_renderer *renderer;
    sl_mat_state *materials;     /* one per scene material */
    float (*light_params)[8];    /* light-scope keys packed by light_slot, one row per light */
    uint64_t materials_version, lights_version;
    bool plugin_lights_moved;    /* a plugin set its own light (plugin_lights.h): the renderer repacks */
    char *debug_view;            /* NULL = final render */
    double time;
    uint64_t frame_index;
    float frame_min[3], frame_max[3]; /* what the default camera and turntables frame: the scene's
                                         bounds before --ground added its floor */
    bool environment_read;       /* a plugin asked for the scene's environment (sl_host.environment) */
    char *strict_failure;        /* --strict: why the run must fail (a plugin's program did not compile) */
    struct sl_post *post;        /* fused full-screen passes (render/post.h, ext/post.h); NULL: none registered */
    struct sl_budget_state *budget; /* the frame-time budget (budget/budget.h); NULL: no model registered */
} sl_app;

/* A material's value for a key, or NULL when the key is not in the schema. */
sl_mat_value *sl_app_material_value(sl_app *app, int material, const char *key);
#endif
