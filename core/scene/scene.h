/* The scene graph: what a JSON scene (or the built-in default) describes, after loading.
 * Pure CPU data; the renderer uploads meshes and textures. Schema-free for material and light
 * properties: the parameter store validates them against the plugins' declared keys. */
#ifndef SL_SCENE_H
#define SL_SCENE_H

#include <shadelab/shadelab.h>

/* Triangle mesh, interleaving-free arrays, counter-clockwise front faces. tangents are xyz +
 * handedness w (±1), generated when the source has none (bitangent = w · cross(normal,
 * tangent)). UV convention: v = 0 is the TOP row of the image (glTF; see core/image/image.h),
 * so the tangent points toward increasing u and the bitangent toward DECREASING v, i.e. "up"
 * in the image: the direction a normal map's green channel encodes (OpenGL/glTF "+Y up"). An
 * unmirrored layout has w = +1, a mirrored one w = −1. */
typedef struct sl_mesh_data {
    int vertex_count, index_count;
    float *positions;   /* 3 per vertex */
    float *normals;     /* 3 */
    float *tangents;    /* 4 */
    float *uvs;         /* 2 */
    uint32_t *indices;  /* 3 per triangle */
    float bounds_min[3], bounds_max[3];
    float *uvs1;        /* 2, or NULL: a second UV set (glTF TEXCOORD_1), same convention as uvs;
                           drawn only for materials with a texture on it (SL_MAT_USES_UV1) */
    float *colors;      /* 4 (linear RGBA), or NULL: vertex colours (glTF COLOR_0; VEC3 with a = 1),
                           multiplying the base colour and its alpha in the programs of materials
                           some coloured mesh uses (SL_MAT_USES_VERTEX_COLOR); other meshes read 1 */
} sl_mesh_data;

/* How one texture slot of a material reads its UVs (glTF 2.0 textureInfo.texCoord and
 * KHR_texture_transform): uv' = T(offset) R(rotation) S(scale) (uv of set `texcoord`, 1), with
 * R = [cos sin; −sin cos] (the extension's matrices, v = 0 at the image top as in glTF). Keyed by
 * the standard material input ("base_color_texture"); the composer applies it to the key that
 * takes that input. */
typedef struct sl_uv_mapping {
    char *input;
    int texcoord;           /* 0 or 1 */
    float offset[2], rotation, scale[2];
} sl_uv_mapping;

/* A raw key/value read from the scene file for materials, lights and parameter assignments.
 * Numbers and arrays are kept as floats; the parameter store interprets them per schema. */
typedef enum sl_prop_kind { SL_PROP_NUMBER, SL_PROP_BOOL, SL_PROP_STRING, SL_PROP_VEC } sl_prop_kind;
typedef struct sl_prop {
    char *key;
    sl_prop_kind kind;
    float v[4];      /* NUMBER: v[0]; VEC: v[0..count-1]; BOOL: v[0] = 0/1 */
    int count;       /* VEC: 2..4 */
    char *str;       /* STRING: text (texture path or procedural spec, enum name, …) */
    int line;        /* 1-based line in the scene file, 0 if unknown */
} sl_prop;

typedef struct sl_prop_list { sl_prop *items; int count; } sl_prop_list;

typedef struct sl_material {
    char *name;
    char *model;            /* shading model ("lambert" by default) */
    bool cast_shadows;      /* default true */
    sl_prop_list props;     /* everything else: base_color, base_color_map, alpha, … */
    int line;
    /* Imported materials: the standard material inputs the asset gives (<shadelab/params.h>:
     * "brdf", "metallic", "normal_texture"…), which the app writes into
     * the keys plugins declare for them (props above win), and the asset file they came from
     * (messages name it; NULL for materials the scene file defines). */
    sl_prop_list inputs;
    char *source;
    sl_uv_mapping *uv_maps; /* texture slots not read with UV set 0 untransformed (imports) */
    int uv_map_count;
} sl_material;

/* How a mesh deforms each frame (glTF 2.0 §3.7.2.2 morph targets, §3.7.3 skins), on the GPU
 * (core/render/deform.c) into the buffers every draw reads (forward, depth, shadow maps, plugins'
 * programs), before any pass; a mesh without one is drawn from its static buffers and pays
 * nothing. Per vertex v, in the drawing node's space (the draw keeps its model matrix):
 *   p = data.positions[v] + Σ_t (weights[t] − rest_weights[t]) · target_positions[t][v]
 *   (normals and tangents alike; data holds the shape at rest_weights, normals re-normalised)
 *   skinned: p' = Σ_k joint_weights[v][k] · N⁻¹ · world(joint j) · inverse_bind[j] · p,
 *   j = joints[v][k], N the drawing node's world matrix (the node's own transform is ignored, as
 *   §3.7.3 says); normals by the cofactor of the blended matrix, tangents by the matrix. */
typedef struct sl_mesh_deform {
    int node;               /* the scene node drawing the mesh (a deformed mesh has one) */
    int target_count;       /* morph targets (0: none) */
    float *target_positions, *target_normals, *target_tangents; /* target_count × vertex_count × 3, or NULL */
    float *weights;         /* target_count: this frame's (sl_scene_animate writes animated ones) */
    float *rest_weights;    /* target_count: the weights data.positions/normals/tangents hold */
    int skin;               /* index into scene.skins, −1: none */
    int influences;         /* joints per vertex: 4 per JOINTS_n set */
    uint16_t *joints;       /* vertex_count × influences: indices into the skin's joints */
    float *joint_weights;   /* vertex_count × influences, each vertex's summing to 1 */
} sl_mesh_deform;

/* The most JOINTS_n/WEIGHTS_n sets a skinned primitive may have (4 joints each); more is an error
 * naming the file and attribute. */
#define SL_MAX_INFLUENCE_SETS 2

/* A glTF skin: the scene nodes of its joints and their inverse bind matrices (column-major). */
typedef struct sl_skin {
    int joint_count;
    int *joints;            /* scene node indices */
    float *inverse_bind;    /* 16 per joint */
} sl_skin;

typedef struct sl_mesh {
    char *name;
    sl_mesh_data data;
    int material;           /* index into scene.materials */
    sl_mesh_deform *deform; /* NULL: static */
} sl_mesh;

typedef struct sl_node {
    char *name;
    int parent;             /* -1 = root */
    float local[16];        /* column-major: translation * rotation * scale */
    float world[16];        /* filled by sl_scene_update_transforms */
    int *meshes;            /* indices into scene.meshes */
    int mesh_count;
    /* Scene-file "tags" (names [a-z0-9_-]); a node also carries its ancestors' tags
     * (sl_scene_node_has_tag). VERTEX chunks with when_node_tag run only on such nodes. */
    char **tags;
    int tag_count;
} sl_node;

/* The most radiance a pixel can hold: the largest finite half float (the colour target is
 * RGBA16F). The forward pass clamps its output to it; inputs whose radiance alone exceeds it (an
 * environment colour) are refused. */
#define SL_MAX_RADIANCE 65504.0

/* The farthest a scene file's node may reach from the origin. float32 positions have a step of 1
 * at 1e7 (geometry and lighting vectors collapse there); the loader refuses a scene reaching
 * further and warns beyond SL_SCENE_WARN_EXTENT (steps of 1/128). */
#define SL_SCENE_MAX_EXTENT 1e7
/* The most triangles one imported file may hold (all its meshes): about 48 bytes per vertex and
 * 12 per triangle on the CPU, the same again on the GPU. 10 M triangles import in well under a
 * minute (tools/import/bench_import.sh). */
#define SL_IMPORT_MAX_TRIANGLES 32000000
/* The project's OBJ reader (core/scene/obj_reader.c) refuses, naming the file and line: a logical
 * line ("\\" continuations joined) over SL_OBJ_MAX_LINE bytes, a file over SL_OBJ_MAX_FILE_BYTES,
 * more than SL_OBJ_MAX_ELEMENTS "v", "vt" or "vn" lines (each), more than SL_IMPORT_MAX_TRIANGLES
 * triangles, more than 2^26 distinct vertices in one mesh. Its memory is the output meshes, the
 * file's v/vt/vn lists and one vertex hash table (8 bytes per 2 vertices of the mesh being read). */
#define SL_OBJ_MAX_LINE (1u << 20)
#define SL_OBJ_MAX_FILE_BYTES (4ull << 30)
#define SL_OBJ_MAX_ELEMENTS (1u << 26)
#define SL_SCENE_WARN_EXTENT 1e5

typedef enum sl_light_animation { SL_ANIMATE_NONE, SL_ANIMATE_ORBIT, SL_ANIMATE_WOBBLE } sl_light_animation;

typedef struct sl_light {
    char *name;
    char *type;             /* "directional", "point", or a plugin type ("spot") */
    float position[3];
    float direction[3];     /* unit, the direction light travels */
    float color[3];         /* linear RGB */
    float intensity;        /* directional: irradiance E; point/spot: intensity I (E = I/d²) */
    bool enabled;           /* default true */
    bool cast_shadows;      /* default false */
    float angular_radius;   /* degrees, directional lights: the disk's (default 0.5; the sun 0.27) */
    /* Animation (core light keys animate / animate_speed / animate_amount), for every type:
     * orbit turns position and direction about the world Y axis at speed rad/s; wobble swings
     * the direction by ±amount° about the horizontal axis across it, angle amount·sin(speed·t). */
    sl_light_animation animate;
    float animate_speed;    /* rad/s, default 0.5 */
    float animate_amount;   /* degrees, default 15 */
    sl_prop_list props;     /* type-specific keys (cone_angle, falloff, radius, …) */
    int line;
    int plugin;             /* 1 + the index of the plugin that added it (SDK add_light); 0: the scene's */
    bool plugin_on;         /* such a light: its plugin's switch (set_light); `enabled` stays the user's */
    bool stand_in;          /* --shadows' key light: off while a plugin's shadow-casting directional
                               light shines (envmap's sky sun), so a model gets one sun */
} sl_light;

typedef struct sl_camera {
    char *name;
    float position[3], target[3], up[3];
    float fov_y_deg;        /* vertical field of view, default 45 */
    float znear, zfar;      /* default 0.05, 100 */
    /* "type": "orthographic" (glTF 2.0): a parallel projection whose view is 2·ymag high (and
     * the viewport's aspect wide; xmag is the file's own half-width, kept for listings). */
    bool orthographic;
    float xmag, ymag;
} sl_camera;

typedef struct sl_environment {
    char *map;              /* image path (resolved at load: absolute or relative to the
                               working directory), or a procedural spec; NULL = none */
    float color[3];         /* constant radiance when map is NULL (default 0) */
    float intensity;        /* multiplier, default 1 */
    float yaw_deg;          /* rotation about +Y */
    sl_prop_list props;     /* plugin keys */
} sl_environment;

/* The environment is one constant radiance, color × intensity: no map and a colour that is not
 * black (a black one without a map is no environment at all; plugins light it as they choose). */
bool sl_environment_is_constant(const sl_environment *env);

typedef struct sl_scene {
    char *path;             /* file it came from ("<default>" for the built-in one) */
    char *dir;              /* directory used to resolve relative asset paths */
    char *generated_by;     /* the command that writes the scene's generated files, or NULL */
    sl_material *materials; int material_count;
    sl_mesh *meshes;        int mesh_count;
    sl_node *nodes;         int node_count;
    sl_light *lights;       int light_count;
    sl_camera *cameras;     int camera_count;
    sl_environment environment;
    char **plugins;         int plugin_count;   /* plugin NAMES only (never paths) */
    sl_prop_list params;    /* "plugin.param": value assignments from the scene */
    float bounds_min[3], bounds_max[3];         /* world bounds after transforms */
    /* Encoded images held in memory (a .glb's buffer views, data: URIs), by the name texture
     * values use for them ("<file>#image<N>.<ext>"); the renderer decodes them like files. */
    struct sl_embedded_image *images; int image_count;
    /* The scene is one model file opened directly (shadelab model.glb): the app adds a default
     * environment and tone mapping, and frames the camera on it. */
    bool from_model;
    /* glTF samplers of imported textures, by texture value (see sl_texture_sampler) */
    struct sl_texture_sampler *samplers; int sampler_count;
    /* Node TRS animation (glTF animations; sl_scene_animate): channels and the animated nodes'
     * rest TRS; played looping over anim_duration seconds */
    struct sl_anim_channel *anim_channels; int anim_channel_count;
    struct sl_anim_node *anim_nodes; int anim_node_count;
    float anim_duration;
    sl_skin *skins; int skin_count;             /* glTF skins (sl_mesh_deform.skin) */
} sl_scene;

/* One animation channel (glTF 2.0 §3.11): a node's translation (path 0, 3 values), rotation
 * (1, a quaternion x y z w), scale (2, 3 values) or morph target weights (3, `components`
 * values: the weights of the node's deformed meshes), keyed at increasing times; CUBICSPLINE
 * keys hold in-tangent, value, out-tangent. */
enum { SL_ANIM_TRANSLATION, SL_ANIM_ROTATION, SL_ANIM_SCALE, SL_ANIM_WEIGHTS };
enum { SL_ANIM_LINEAR, SL_ANIM_STEP, SL_ANIM_CUBICSPLINE };
typedef struct sl_anim_channel {
    int node, path, interpolation, key_count;
    int components; /* SL_ANIM_WEIGHTS: the morph target count (other paths: 3 or 4 by path) */
    float *times;   /* key_count */
    float *values;  /* key_count × components (× 3 for CUBICSPLINE) */
} sl_anim_channel;
typedef struct sl_anim_node { int node; float t[3], r[4], s[3]; } sl_anim_node;

/* The animated value of a channel at time t (seconds; clamped to its keys) per the glTF 2.0
 * specification's appendix C: STEP holds the key, LINEAR lerps (rotation: slerp), CUBICSPLINE is
 * the cubic Hermite spline with the keys' tangents scaled by the key interval. out: 3 or 4
 * floats, `components` for weights. */
void sl_anim_sample(const sl_anim_channel *c, double t, float *out);
/* Poses the animated nodes at time t (looping over anim_duration), writes animated morph
 * weights into the deformed meshes of their nodes and updates world transforms. */
void sl_scene_animate(sl_scene *scene, double t);

/* How an imported texture is sampled (glTF 2.0 "samplers", whose values are OpenGL's enums):
 * wrap_s/wrap_t GL_REPEAT, GL_CLAMP_TO_EDGE or GL_MIRRORED_REPEAT; mag/min filters GL_NEAREST,
 * GL_LINEAR, GL_*_MIPMAP_*; 0 = the renderer's default for that field. */
typedef struct sl_texture_sampler {
    char *texture;          /* the texture value (an embedded image's name or a path) */
    int wrap_s, wrap_t, mag_filter, min_filter;
} sl_texture_sampler;

typedef struct sl_embedded_image {
    char *name;
    unsigned char *data;
    size_t size;
} sl_embedded_image;

/* Where relative asset paths are looked up, in order: the scene file's directory, then
 * data_dir (--data DIR or SHADELAB_DATA). */
typedef struct sl_scene_load_opts {
    const char *data_dir;   /* may be NULL */
    /* glTF files, opened or imported (--variant, --animation): the KHR_materials_variants
     * variant shown (NULL: the default materials) and the animation played ("2" or its name;
     * NULL: the first). A variant or animation the file lacks is an error naming the file's. */
    const char *gltf_variant, *gltf_animation;
} sl_scene_load_opts;

/* Loads a JSON scene file (format: scenes/README.md). On failure returns false and writes a
 * message naming the file, line and column and the cause into err. Warnings (unknown keys with
 * the nearest valid key) go to stderr through sl_log. Meshes referenced by file go through
 * sl_scene_import_file. On success *scene is overwritten (it must not hold a scene: free it first or pass a
 * zeroed one); on failure *scene is left untouched, so a viewer can keep the scene it has.
 * opts may be NULL; a NULL data_dir falls back to the SHADELAB_DATA environment variable. */
bool sl_scene_load_file(sl_scene *scene, const char *path, const sl_scene_load_opts *opts,
                        char *err, size_t err_size);
/* Same from NUL-terminated text in memory; `name` is used in messages and `dir` for relative
 * paths (NULL: only the data directory is searched). */
bool sl_scene_load_text(sl_scene *scene, const char *text, const char *name, const char *dir,
                        const sl_scene_load_opts *opts, char *err, size_t err_size);
/* The built-in default scene (scenes/default.json, embedded at build time; path "<default>"). */
bool sl_scene_load_default(sl_scene *scene, const sl_scene_load_opts *opts, char *err,
                           size_t err_size);
/* Frees everything and zeroes *scene (safe on a zeroed scene, twice, or NULL). */
void sl_scene_free(sl_scene *scene);
/* Recomputes node world matrices and scene bounds. */
void sl_scene_update_transforms(sl_scene *scene);
/* Resolves an asset path as documented above; returns a malloc'd path or NULL and writes
 * where it looked into err. */
char *sl_scene_resolve_path(const sl_scene *scene, const char *data_dir, const char *rel,
                            char *err, size_t err_size);

/* The property with this key, or NULL. */
const sl_prop *sl_prop_find(const sl_prop_list *list, const char *key);

/* Procedural primitives (core/scene/primitives.c). All have normals, uvs and tangents (w = +1),
 * CCW front faces, bounds; each returns false with *m zeroed on invalid arguments (non-positive
 * or non-finite sizes, too few or too many segments). UV layouts: scenes/README.md. */
/* Lat-long UV sphere: u = φ/2π, v = θ/π for d = (sin θ sin φ, cos θ, sin θ cos φ). */
bool sl_mesh_sphere(sl_mesh_data *m, float radius, int segments, int rings);
bool sl_mesh_plane(sl_mesh_data *m, float size_x, float size_z, int subdivisions); /* +Y up */
bool sl_mesh_cube(sl_mesh_data *m, float size);
bool sl_mesh_torus(sl_mesh_data *m, float major_radius, float minor_radius, int segments, int sides);
/* The Utah teapot from Newell's 32 bicubic Bezier patches, tessellated per patch
 * (tessellation² quads each), Y up, standing on y = 0, height `size`. */
bool sl_mesh_teapot(sl_mesh_data *m, float size, int tessellation);
/* Loads every mesh in a glTF/OBJ/… file, appending meshes, materials, lights and cameras to the
 * scene under a new node, child of parent_node (−1: a root): a file named *.obj through the
 * project's own OBJ reader (sl_scene_import_obj), everything else through assimp. path is used
 * as given (resolve it first). Needs the parent's world matrix (sl_scene_update_transforms)
 * to place lights and cameras. On failure err says why ("path: assimp could not import it:
 * …") and the scene may hold part of the file (a loader then discards the whole scene). */
bool sl_scene_import_file(sl_scene *scene, const char *path, int parent_node, char *err, size_t err_size);
/* The same with the glTF choices of opts (may be NULL); a choice given for a file that is not
 * glTF is an error. */
bool sl_scene_import_model(sl_scene *scene, const char *path, int parent_node, const sl_scene_load_opts *opts,
                           char *err, size_t err_size);
/* The two readers behind it, the same contract (tests compare them on the same OBJ files): the
 * project's streaming OBJ reader (errors "path:line: cause"), and assimp for any format. */
bool sl_scene_import_obj(sl_scene *scene, const char *path, int parent_node, char *err, size_t err_size);
bool sl_scene_import_assimp(sl_scene *scene, const char *path, int parent_node, char *err, size_t err_size);
/* A model file (glTF, GLB, OBJ… anything sl_scene_import_file reads) as a whole scene: one root node named
 * after the file holding its contents, from_model set (the app adds a default environment and
 * tone mapping and frames the camera). sl_scene_load_file calls it when the file's content is
 * not a shadelab scene. On failure *scene is untouched. */
bool sl_scene_load_model(sl_scene *scene, const char *path, const sl_scene_load_opts *opts, char *err,
                         size_t err_size);
/* glTF files go to the project's own reader (core/scene/gltf_*.c; glTF by its name or its
 * content): the file's materials, meshes, nodes, cameras and lights keep their glTF identity
 * (material i of the file is one scene material, whatever its name), every accessor is checked
 * against glTF 2.0 §3.6 and every constrained value (finite transforms, camera ranges, index and
 * key ranges); errors name the file, the JSON pointer and the cause ("model.glb: /accessors/7:
 * …"), and what is dropped or replaced is named in one warning. Same contract as above. */
bool sl_scene_import_gltf(sl_scene *scene, const char *path, int parent_node, const sl_scene_load_opts *opts,
                          char *err, size_t err_size);
/* Whether the file is a glTF by its content (the GLB magic, or JSON with "asset" near the start). */
bool sl_file_is_gltf(const char *path);

/* The glTF extensions the reader knows of and what it does with each (one list: the reader's
 * checks and --list-gltf-extensions). An extension not listed is not read: refused when a file
 * requires it, ignored with a warning when it only uses it. */
typedef enum sl_gltf_support { SL_GLTF_RENDERED, SL_GLTF_APPROXIMATED, SL_GLTF_IGNORED } sl_gltf_support;
typedef struct sl_gltf_extension {
    const char *name;
    sl_gltf_support support;
    const char *what;       /* what the viewer shows of it */
} sl_gltf_extension;
const sl_gltf_extension *sl_gltf_extensions(int *count);
/* glTF 2.0's own features (materials, skins, …) and what the reader makes of each. */
const sl_gltf_extension *sl_gltf_features(int *count);
/* Both lists as README.md's glTF table: one row each for rendered, approximated, not rendered. */
void sl_gltf_print_markdown(void); /* to stdout */

/* Generates tangents (xyz + handedness w) from positions, normals and uvs; degenerate UVs
 * fall back to an arbitrary tangent orthogonal to the normal. */
void sl_mesh_generate_tangents(sl_mesh_data *m);
void sl_mesh_compute_bounds(sl_mesh_data *m);
void sl_mesh_free(sl_mesh_data *m);
void sl_mesh_deform_free(sl_mesh_deform *d); /* NULL is fine */

/* ---- building blocks (used by the loaders; handy for tools and tests) -------------------- */

/* Deepest node nesting the loaders accept ("children" inside "children"…, imported
 * hierarchies included); deeper is an error, never a stack overflow. */
#define SL_SCENE_MAX_DEPTH 64

/* Allocates the five arrays (zeroed) for vertex_count vertices and index_count indices; false
 * (and *m zeroed) on overflow or out of memory. */
bool sl_mesh_alloc(sl_mesh_data *m, int vertex_count, int index_count);
/* Makes every normal unit and every tangent unit, orthogonal to its normal, with w = ±1:
 * non-finite or zero normals become the face normal of a triangle using the vertex (or +Y),
 * bad tangents any vector orthogonal to the normal. Returns how many vertices were repaired. */
int sl_mesh_repair_frames(sl_mesh_data *m);

/* Index of the named item, or -1. */
int sl_scene_find_material(const sl_scene *scene, const char *name);
int sl_scene_find_node(const sl_scene *scene, const char *name);
/* Whether node (or one of its ancestors) carries the scene-file tag. */
bool sl_scene_node_has_tag(const sl_scene *scene, int node, const char *tag);
int sl_scene_find_light(const sl_scene *scene, const char *name);
int sl_scene_find_camera(const sl_scene *scene, const char *name);

/* Append an item and return its index (-1 when out of memory). Strings are copied; indices
 * stay valid, pointers into the arrays do not (they may move on the next append).
 * Materials: model NULL = "lambert", cast_shadows true. Nodes: identity transform; parent
 * must be -1 or an existing node (parents always come before their children).
 * Meshes: takes ownership of *data (zeroed on return, also on failure). Lights: white,
 * intensity 1, enabled, direction (0,-1,0). Cameras: at (0,0,5) looking at the origin, 45°,
 * near 0.05, far 100. */
int sl_scene_add_material(sl_scene *scene, const char *name, const char *model);
int sl_scene_add_node(sl_scene *scene, const char *name, int parent);
int sl_scene_add_mesh(sl_scene *scene, const char *name, sl_mesh_data *data, int material);
bool sl_scene_node_add_mesh(sl_scene *scene, int node, int mesh);
int sl_scene_add_light(sl_scene *scene, const char *name, const char *type);
/* Where an animated light is at time t (seconds): its position and unit direction. */
void sl_light_at_time(const sl_light *light, double t, float position[3], float direction[3]);
int sl_scene_add_camera(sl_scene *scene, const char *name);
/* Copies size bytes of an encoded image under `name`; its index, or -1 when out of memory. */
int sl_scene_add_image(sl_scene *scene, const char *name, const void *data, size_t size);
/* The embedded image a texture value names, or NULL. */
const sl_embedded_image *sl_scene_find_image(const sl_scene *scene, const char *name);
/* Records the sampler of a texture value (the first one recorded stands; false when another
 * sampler was recorded for it already, or out of memory). */
bool sl_scene_set_sampler(sl_scene *scene, const sl_texture_sampler *sampler);
/* The sampler recorded for a texture value, or NULL. */
const sl_texture_sampler *sl_scene_find_sampler(const sl_scene *scene, const char *texture);

/* Set (add or replace) a property; returns it, or NULL when out of memory. */
sl_prop *sl_prop_set_number(sl_prop_list *list, const char *key, float value, int line);
sl_prop *sl_prop_set_bool(sl_prop_list *list, const char *key, bool value, int line);
sl_prop *sl_prop_set_string(sl_prop_list *list, const char *key, const char *value, int line);
sl_prop *sl_prop_set_vec(sl_prop_list *list, const char *key, const float *v, int count, int line);
void sl_prop_list_free(sl_prop_list *list);

/* local = T · R · S (column-major). rotation_xyzw is a unit quaternion (x, y, z, w). */
void sl_mat4_from_trs(float out[16], const float translate[3], const float rotation_xyzw[4],
                      const float scale[3]);
/* Quaternion (x, y, z, w) for Euler angles in degrees, applied about the fixed X axis first,
 * then Y, then Z: R = Rz · Ry · Rx. */
void sl_quat_from_euler_deg(float out_xyzw[4], const float degrees_xyz[3]);

#endif
