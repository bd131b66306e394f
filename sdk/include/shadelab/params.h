/* Parameters: one declarative schema per parameter. The same schema drives the GUI panel,
 * `--set id=value`, scene files and `--dump-params` (JSON). Never describe a parameter twice.
 *
 * Addressing:
 *   plugin globals       "<plugin>.<id>"             e.g. "ggx.zero_specular"
 *   per-material values  "material.<NAME>.<key>"     e.g. "material.skin.alpha"
 *   per-light values     "light.<NAME>.<key>"        e.g. "light.key.enabled"
 * Precedence: schema default < scene file < command line (--set) < GUI.
 * Changes apply at frame boundaries. */
#ifndef SHADELAB_PARAMS_H
#define SHADELAB_PARAMS_H

#ifdef __cplusplus
extern "C" {
#endif

typedef enum sl_param_type {
    SL_PARAM_BOOL = 1,
    SL_PARAM_INT,
    SL_PARAM_FLOAT,
    SL_PARAM_ENUM,    /* one of enum_values; stored as the index */
    SL_PARAM_COLOR,   /* linear RGB, 3 floats */
    SL_PARAM_VEC3,    /* 3 floats (directions, positions) */
    SL_PARAM_TEXTURE  /* material scope only: an image path or a procedural texture */
} sl_param_type;

/* Where a parameter lives. */
typedef enum sl_param_scope {
    SL_SCOPE_GLOBAL = 0, /* one value per plugin: "<plugin>.<id>" */
    SL_SCOPE_MATERIAL,   /* a key a material may carry: "material.<NAME>.<id>" */
    SL_SCOPE_LIGHT       /* a key a light may carry:    "light.<NAME>.<id>" */
} sl_param_scope;

enum sl_param_flags {
    /* Value becomes a GLSL #define (permutation): changing it recompiles programs.
     * Without it, global parameters reach GLSL as uniforms "<plugin>_<id>" (dashes become
     * underscores) and material keys as uniforms "sl_mat_<id>". */
    SL_PARAM_NEEDS_RECOMPILE = 1u << 0,
    /* Trades quality for time; swept by shadelab-bench. */
    SL_PARAM_QUALITY_KNOB = 1u << 1,
    /* Textures only: data texture (normals, roughness, masks): no sRGB decoding. */
    SL_PARAM_LINEAR_DATA = 1u << 2,
    /* Not shown in the GUI (still settable and dumped). */
    SL_PARAM_HIDDEN = 1u << 3,
    /* ABI 1.3, textures only: sample with clamp-to-edge instead of repeat (object-space maps,
     * lookup tables). */
    SL_PARAM_CLAMP_TO_EDGE = 1u << 4
};

/* A parameter value. Which member is meaningful follows the type. */
typedef struct sl_value {
    bool b;
    int i;        /* INT, and ENUM (index into enum_values) */
    float f[4];   /* FLOAT: f[0]; COLOR/VEC3: f[0..2] */
    const char *s; /* TEXTURE: path or procedural spec (owned by the host) */
} sl_value;

typedef struct sl_param_desc {
    uint32_t struct_size;            /* sizeof(sl_param_desc) */
    const char *id;                  /* [a-z0-9_]; unique within the plugin and scope */
    sl_param_type type;
    sl_param_scope scope;
    sl_value default_value;          /* zero is a valid default for every type */
    float min, max;                  /* INT/FLOAT range (inclusive); min == max: unbounded */
    float step;                      /* GUI step; 0 = automatic */
    const char *unit;                /* "px", "ms", "deg", "" … shown in the GUI and help */
    const char *group;               /* GUI group within the plugin's panel; NULL = none */
    const char *description;         /* one sentence; shown as tooltip and in --dump-params */
    const char *const *enum_values;  /* ENUM: NULL-terminated names */
    uint32_t flags;                  /* sl_param_flags */
    /* LIGHT scope: which float of the light record's params[0..7] receives the value
     * (COLOR/VEC3 take three consecutive slots). Ignored for other scopes. */
    int light_slot;
    /* LIGHT scope: the light type this key belongs to ("spot"); NULL = every light. */
    const char *light_type;
    /* ABI 1.6, MATERIAL scope: the standard material input (the names below) this
     * key receives from imported assets (glTF, OBJ…), or NULL. The importer publishes inputs by
     * these names only; the host writes each into the key that declares it, so the core never
     * names a plugin's key. List the same names in sl_plugin_desc.material_inputs. */
    const char *material_input;
    /* ABI 1.24, INT/FLOAT: what the value 0 means ("auto", "off"), shown by the GUI and
     * --dump-params in place of "0 <unit>"; NULL: the number. */
    const char *zero_label;
} sl_param_desc;

/* ABI 1.6: the standard material inputs an importer publishes, named after the glTF 2.0
 * material model (KHR spec, "Materials"). Values arrive in the schema's own text form. Which
 * plugin key takes which input is what the keys declare (material_input; --dump-params shows
 * it), never a list in the host.
 *   brdf                      the BRDF the asset asks for: "metallic-roughness" (glTF 2.0,
 *                             appendix B). The plugin whose key declares it provides the shading
 *                             model the material uses (its SHADING_MODEL chunk); the value is
 *                             parsed by that key's schema (an enum containing the name).
 *   base_color                colour: baseColorFactor.rgb (linear)
 *   base_color_texture        texture (sRGB): baseColorTexture
 *   opacity                   float: baseColorFactor.a (or the file format's opacity)
 *   metallic, roughness       float: metallicFactor, roughnessFactor
 *   metallic_roughness_texture texture (linear): B = metal, G = roughness
 *   normal_texture            texture (linear, tangent space, +Y up); normal_scale: its scale
 *   occlusion_texture         texture (linear, R); occlusion_strength: its strength
 *   emissive                  colour: emissiveFactor; emissive_texture: texture (sRGB)
 *   emissive_strength, ior    floats (KHR_materials_emissive_strength, KHR_materials_ior)
 *   alpha_cutoff              float: alphaMode MASK's alphaCutoff (absent: not masked)
 *   double_sided              bool: glTF doubleSided (back faces drawn, not culled)
 *   alpha_blend               bool: alphaMode BLEND (sorted, blended over what is behind)
 *   unlit                     bool (ABI 1.7): KHR_materials_unlit (the base colour, unlit)
 *   clearcoat, clearcoat_roughness  floats (KHR_materials_clearcoat, present when the factor > 0);
 *                             clearcoat_texture (linear, R), clearcoat_roughness_texture (linear, G),
 *                             clearcoat_normal_texture (linear, tangent space) and clearcoat_normal_scale
 *   sheen_color, sheen_roughness  colour, float (KHR_materials_sheen, present when the colour is not
 *                             black); sheen_color_texture (sRGB, RGB), sheen_roughness_texture (linear, A)
 *   specular, specular_color  float, colour (KHR_materials_specular, published when not 1, [1, 1, 1]);
 *                             specular_texture (linear, A), specular_color_texture (sRGB, RGB)
 *   transmission              float (KHR_materials_transmission, present when > 0); transmission_texture
 *                             (linear, R)
 *   thickness                 float (KHR_materials_volume, present when > 0, mesh units); thickness_texture
 *                             (linear, G); attenuation_distance (world units, present when finite) and
 *                             attenuation_color (colour, present when given)
 *   dispersion                float (KHR_materials_dispersion, 20 / Abbe number, present when > 0)
 *   iridescence               float (KHR_materials_iridescence, present when > 0 and the film has a
 *                             thickness); iridescence_ior, iridescence_thickness_minimum/_maximum (nm)
 *                             when not 1.3, 100, 400; iridescence_texture (linear, R),
 *                             iridescence_thickness_texture (linear, G)
 *   anisotropy_strength       float (KHR_materials_anisotropy, present when > 0); anisotropy_rotation
 *                             (radians, when not 0); anisotropy_texture (linear: rg direction, b strength)
 * ior (KHR_materials_ior) is the dielectric's index of refraction: glTF's F0 = ((ior − 1)/(ior + 1))². */
#ifdef __cplusplus
}
#endif
#endif
