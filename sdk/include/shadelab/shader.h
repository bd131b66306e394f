/* Shader hooks: how a plugin adds GLSL to the composed forward material shader.
 *
 * Plugins never edit core templates. They register chunks: a GLSL file (relative to the
 * plugin's resource directory) plus the name of a function with the signature fixed by the
 * hook below. The composer includes a chunk only in the programs of materials that use it, so
 * a material without, say, a normal map compiles no normal-map code. Errors in a chunk are
 * reported with the plugin file and line (#line mapping).
 *
 * GLSL types available to every chunk (shaders/common.glsl):
 *   struct SlVertex  { vec3 position; vec3 normal; vec4 tangent; vec2 uv; };      object space
 *   struct SlSurface { vec3 position; vec3 normal; vec3 geometric_normal;
 *                      vec3 tangent; vec3 bitangent; vec2 uv; vec3 view;        world space
 *                      vec3 base_color; float alpha; float specular; float ao; float opacity;
 *                      float lod_bias; vec3 object_position; float metallic; vec2 uv1;
 *                      vec3 emission_weight; };
 *                      lod_bias (ABI 1.5): mip bias of lookups that follow
 *                      the normal map's level; normal-map sets it, phong's gloss map reads it;
 *                      object_position (ABI 1.6): the mesh's object-space position before
 *                      VERTEX hooks (rest pose), interpolated: regions defined in object space
 *                      stay on the surface while vertex hooks move it;
 *                      metallic (ABI 1.7): glTF metalness, 0 by default; ggx sets it from the
 *                      material's metallic × the metallic-roughness map's blue channel, and
 *                      its metallic-roughness Fresnel, envmap's split sum and area lights read it;
 *                      emission_weight (ABI 1.20): what the model's layers over the material's
 *                      emission leave of it, 1 by default; SURFACE hooks of a layered model set
 *                      it (ggx's clear coat: 1 − w·F_c(n_c·v)) and sl_emission(s) applies it
 *   struct SlLight   { vec4 position; vec4 direction; vec4 color; vec4 params[2]; };
 *                      direction.w (ABI 1.22): the angular_radius key in radians (directional
 *                      lights' disk); float sl_light_spread: the angular radius of the light a
 *                      model is being evaluated for (the core's directional light sets it, 0 for
 *                      every other light and outside the light loop); sl:ggx_brdf.glsl's D is
 *                      convolved with it (ggx_D_disk), so a polished surface shows the disk.
 *   uniforms: float sl_time; mat4 sl_view, sl_proj, sl_view_proj; vec3 sl_camera_pos;
 *             int sl_frame_index; vec2 sl_viewport_size;
 *             int sl_sample_index, sl_sample_count (ABI 1.9: sl_frame.sample_index/count, a
 *             sample sequence that continues across a TAA still's frames and accumulated frames).
 *   constant environment (ABI 1.27, forward programs): uniform vec3 sl_ambient_irradiance, π ×
 *             the scene environment's colour × intensity (the irradiance it gives an unoccluded
 *             surface). SL_ENVIRONMENT_CONSTANT is defined when that colour is the whole
 *             environment (no map, a colour that is not black): an integrator reads
 *             sl_ambient_irradiance/π in place of its environment lookups (envmap does), a
 *             permutation, so a constant environment pays for no texture read.
 *   function (ABI 1.6, fragment stage of forward programs):
 *             vec3 sl_shading_model(SlSurface s, vec3 l, vec3 E)   the material's SHADING_MODEL
 *   footprint (ABI 1.23, fragment stage): float sl_normal_footprint, the pixel's footprint of
 *             the interpolated normal (its screen derivatives' parallelogram /π, in slopes);
 *             sl_surface_from_varyings sets it, a pass building its surface otherwise calls
 *             sl_set_normal_footprint(n) in uniform control flow; 0 elsewhere.
 *             sl:ggx_brdf.glsl filters D over it for the light loop's lights.
 *             ABI 1.28: vec3 sl_normal_to_centre, set with it: the normal's change from the
 *             fragment's jittered sample to its pixel's centre (uniform vec2 sl_jitter,
 *             sl_frame.jitter in pixels); ggx centres the footprint of a lobe about a pixel
 *             wide on the pixel in every frame of a TAA still.
 *   texture bias (ABI 1.30): uniform float sl_texture_lod_bias, the mip LOD bias every material
 *             texture has this frame (host set_texture_lod_bias: negative in a TAA still's
 *             jittered frames, which then sample their share of the pixel; 0 otherwise). A
 *             filter standing in for sub-pixel variance steps aside where it is negative (ggx's
 *             and phong's specular antialiasing).
 *   bool sl_light_in_loop (ABI 1.25, common.glsl): true while the core's light loop (or
 *             sl_light_radiance) evaluates the model for one of its lights, false elsewhere:
 *             a model filters its lobe over the footprint only then, never for the directions an
 *             integrator samples.
 *   lobes (ABI 1.14, common.glsl): struct SlLobe, struct SlLobes, SL_MAX_LOBES, sl_lobes_none(),
 *             and in forward programs  SlLobes sl_model_lobes(SlSurface s)  the material's
 *             MODEL_LOBES description, or the fallback (Lambert diffuse of s.base_color, no
 *             lobe; SL_MODEL_HAS_LOBES undefined). Integrators (AMBIENT hooks, radiance LIGHTs)
 *             light every model through it and name none (plugin-guide.md, "Lobes").
 *             ABI 1.16: SlLobes.flags; SL_LOBES_MODEL_AT_DOMINANT_LIGHT asks integrators to
 *             evaluate the model's own f at the light's dominant direction (a toon model's
 *             bands) instead of integrating lobes (common.glsl, sdk/example/toon).
 *             ABI 1.19: SL_LOBES_BLINN_PHONG << k in SlLobes.flags: lobe k is normalised
 *             Blinn-Phong of power sl_lobe_blinn_power(alpha), not GGX (sl_lobe_blinn_phong(L, k)).
 *             ABI 1.26: SlLobes.normal[k], lobe k's own shading normal (vec3(0): s.normal; a clear
 *             coat's normal texture), which integrators read through sl_lobe_normal(L, k, s).
 *
 * Every program also gets "#define SL_MODEL_<NAME> 1" for its material's shading model (SL_MODEL_GGX),
 * and "#define SL_MODEL_MASKS_FACING_AWAY 1" when that model's chunk carries
 * SL_CHUNK_MASKS_FACING_AWAY (ABI 1.4): SURFACE hooks that perturb the normal (normal maps) then
 * leave a normal facing away from the viewer (n·v ≤ 0) as it is, because the model handles it
 * itself (e.g. Smith masking gives it no specular), instead of guarding it as they do for other
 * models (sl_view_guard, "sl:normal_guard.glsl": a normal whose reflection falls below the
 * surface is bent back above it, as Blender's Cycles does; no bundled model declares the flag).
 *
 * Hook signatures (FN is sl_shader_chunk_desc.function):
 *   VERTEX           void FN(inout SlVertex v)                   the mesh's object-space vertex,
 *                                                                before the model transform
 *                                                                (sl_model; normal by
 *                                                                sl_normal_matrix); once per
 *                                                                vertex in every program of the
 *                                                                material: forward, depth-only
 *                                                                (shadow maps) and
 *                                                                SL_DRAW_MATERIALS, not in
 *                                                                SL_DRAW_PROGRAM; sl_time and
 *                                                                the parameter uniforms available
 *   SURFACE          void FN(inout SlSurface s)                  edits the surface record
 *                                                                (normal maps, gloss/AO maps)
 *   SHADING_MODEL    vec3 FN(SlSurface s, vec3 l, vec3 E)        outgoing radiance towards
 *                                                                s.view from one light; l points
 *                                                                to the light, E is its
 *                                                                irradiance at normal incidence;
 *                                                                the model applies max(0, n·l)
 *   MODEL_AMBIENT    vec3 FN(SlSurface s, vec3 ambient_irradiance)
 *                                                                optional per-model term
 *                                                                outside the light loop, once
 *                                                                per pixel; gets vec3(0) when
 *                                                                AMBIENT hooks supply the
 *                                                                ambient light
 *   LIGHT            bool FN(SlLight L, SlSurface s, out vec3 l, out vec3 E)
 *                                                                evaluates one light of type
 *                                                                `name`; false = no light here.
 *                                                                With SL_CHUNK_LIGHT_RADIANCE
 *                                                                (ABI 1.6, area lights):
 *                                                                vec3 FN(SlLight L, SlSurface s),
 *                                                                outgoing radiance (see below)
 *   AMBIENT          vec3 FN(SlSurface s)                        added irradiance-like term
 *                                                                (environment lighting);
 *                                                                summed over plugins; not in
 *                                                                SL_DRAW_MATERIALS overrides
 *   DEBUG_VIEW       vec3 FN(SlSurface s)                        replaces the output when the
 *                                                                view `name` is selected
 *   DEBUG_VIEW_LIGHT vec3 FN(SlSurface s, vec3 l, vec3 E)       like DEBUG_VIEW, summed over
 *                                                                the lights (e.g. "GGX D")
 *   LIBRARY          (no function)                               helper code included whenever
 *                                                                the plugin is enabled
 *   SHADOW           float FN(int i, SlLight L, SlSurface s, vec3 l)
 *                                                                visibility in [0,1] of light
 *                                                                sl_lights[i] (any type) at s;
 *                                                                the light loop multiplies E by
 *                                                                it. Compiled in only when a
 *                                                                light casts shadows (enabled
 *                                                                or not: toggling recompiles
 *                                                                nothing), and called only for
 *                                                                the lights that cast them
 *                                                                (their own loop; with a
 *                                                                LIGHT_LOOP, for every light);
 *                                                                one provider (the first enabled)
 *   LIGHT_LOOP       vec3 FN(SlSurface s)                        ABI 1.7: replaces the core's
 *                                                                iteration over sl_lights in
 *                                                                the forward programs (not in
 *                                                                model_override programs): the
 *                                                                direct lighting is FN(s). FN
 *                                                                picks the lights (a culled list
 *                                                                per tile or cluster) and adds
 *                                                                vec3 sl_light_radiance(int i,
 *                                                                SlSurface s), generated in these
 *                                                                programs: light sl_lights[i]
 *                                                                through its LIGHT chunk, the
 *                                                                SHADOW hook and the material's
 *                                                                model (or the DEBUG_VIEW_LIGHT
 *                                                                view), exactly as the core's
 *                                                                loop. One provider (the
 *                                                                first enabled); absent, the
 *                                                                programs are unchanged
 *   MODEL_LOBES      SlLobes FN(SlSurface s)                     ABI 1.14: the model `name`
 *                                                                described as a diffuse albedo
 *                                                                and up to SL_MAX_LOBES GGX
 *                                                                lobes at s.view (common.glsl);
 *                                                                defines SL_MODEL_HAS_LOBES
 *   DISPLACEMENT     float FN(SlVertex v)                        ABI 1.7: height along the
 *                                                                object-space normal at a
 *                                                                tessellated vertex (v after the
 *                                                                VERTEX hooks, interpolated over
 *                                                                the triangle), in object-space
 *                                                                units; see "Displacement" below
 *   SCENE_BEHIND     vec3 FN(SlSurface s)                        ABI 1.17: radiance the surface
 *                                                                passes on from the opaque scene
 *                                                                behind it (transmission,
 *                                                                refraction), added once per
 *                                                                pixel after the SURFACE hooks;
 *                                                                gated like SURFACE hooks; see
 *                                                                "The scene behind" below
 *
 * Displacement (ABI 1.7). A material that gets a DISPLACEMENT chunk (gated like VERTEX hooks:
 * when_material_has, when_model; when_node_tag is refused) is drawn as GL_PATCHES of 3 vertices
 * through a tessellation stage in every program of the material (forward, depth-only shadow
 * maps, SL_DRAW_MATERIALS passes; not SL_DRAW_PROGRAM), so displaced geometry casts and receives
 * its own shadows. Programs of other materials are byte-for-byte those without the hook.
 *   - the tessellation control stage gives each triangle edge a level computed from that edge's
 *     two world-space endpoints only, in a canonical order, so the two triangles sharing an edge
 *     agree and the surface has no cracks (as long as they share the vertex data: a hard edge
 *     with split normals opens, as with any displacement along the normal);
 *   - `tess_level` names a function  float LEVEL(vec3 a, vec3 b)  (world space; the host passes
 *     the endpoints in a canonical order) returning the wanted level of one edge; NULL = edges
 *     of about 8 pixels. The host takes the maximum over the material's DISPLACEMENT chunks,
 *     clamps to [1, min(gl_MaxTessGenLevel, 48)] (llvmpipe breaks patches of level 64); inner
 *     level = the largest outer one.
 *     Helper (sl:tess.glsl, in every tessellation stage):
 *       float sl_tess_screen_level(vec3 a, vec3 b, float target_px)
 *     the edge's length in pixels seen from the frame's camera (not the pass's view: shadow maps
 *     tessellate exactly as the camera view does, so caster and receiver are the same surface),
 *     over target_px;
 *   - the evaluation stage sums every chunk's height h and moves the vertex to
 *     p + h·n (n the interpolated unit normal); the shading normal is that of the displaced
 *     surface, normalize(n - ∇h), with ∇h the surface gradient of h from finite differences over
 *     the patch (Mikkelsen 2020, "Surface gradient based bump mapping"); depth-only programs
 *     skip it. SlSurface.object_position stays the rest pose.
 *
 * The scene behind (ABI 1.17). A material whose program gets a SCENE_BEHIND chunk (its gates:
 * when_material_has, when_model, when_param) is drawn by the core's "forward-behind" pass
 * (SL_STAGE_BEHIND, pass.h) instead of the forward pass: after every opaque pass (envmap's
 * background included) the core copies "color" into a mip chain (a box-filtered pyramid, level 0
 * the viewport's pixels) and draws these materials over it, back to front per draw as blended
 * ones, depth-tested against "depth" by the fragment (no depth writes; they are not in the capture:
 * they do not see each other). FN's value is added to the shaded radiance (not in debug views, not in
 * SL_DRAW_MATERIALS programs). In those programs SL_SCENE_BEHIND is defined and
 *     uniform sampler2D sl_scene_behind;  the captured opaque scene (linear radiance, mipmapped)
 *     uniform float sl_scene_behind_levels;  its mip count − 1 (log2 of its larger side)
 *     vec2 sl_screen_uv(vec3 world)       where a world point lands in it (through sl_view_proj)
 * are declared. The pass and the capture exist only while such a material does.
 */
#ifndef SHADELAB_SHADER_H
#define SHADELAB_SHADER_H

#ifdef __cplusplus
extern "C" {
#endif

typedef enum sl_hook {
    SL_HOOK_VERTEX = 1,
    SL_HOOK_SURFACE,
    SL_HOOK_SHADING_MODEL,
    SL_HOOK_MODEL_AMBIENT,
    SL_HOOK_LIGHT,
    SL_HOOK_AMBIENT,
    SL_HOOK_DEBUG_VIEW,
    SL_HOOK_DEBUG_VIEW_LIGHT,
    SL_HOOK_LIBRARY,
    SL_HOOK_SHADOW,         /* ABI 1.1 (shadow maps); an older host refuses the chunk */
    SL_HOOK_LIGHT_LOOP,     /* ABI 1.7 (light culling); an older host refuses the chunk */
    SL_HOOK_DISPLACEMENT,   /* ABI 1.7 (tessellation, see above); an older host refuses it */
    SL_HOOK_MODEL_LOBES,    /* ABI 1.14 (the lobe contract); an older host refuses it */
    SL_HOOK_SCENE_BEHIND    /* ABI 1.17 (transmission, see "The scene behind"); an older host refuses it */
} sl_hook;

typedef struct sl_shader_chunk_desc {
    uint32_t struct_size;  /* sizeof(sl_shader_chunk_desc) */
    sl_hook hook;
    const char *file;      /* GLSL file relative to the plugin's resource directory */
    const char *function;  /* entry function (see the signatures above); NULL for LIBRARY */
    /* SHADING_MODEL / MODEL_AMBIENT / MODEL_LOBES: the model name materials select ("ggx").
     * LIGHT: the light type ("spot"). DEBUG_VIEW(_LIGHT): the view name ("ggx-d"). */
    const char *name;
    /* VERTEX/SURFACE/AMBIENT/DISPLACEMENT/SCENE_BEHIND: include the chunk only for materials
     * carrying this material key (e.g. "normal_map"); NULL = every material. */
    const char *when_material_has;
    int order;             /* SURFACE/VERTEX hooks run in ascending order, then by plugin */
    const char *description; /* DEBUG_VIEW: shown in the GUI and --list-debug-views */
    uint32_t flags;        /* ABI 1.4: sl_chunk_flags */
    /* ABI 1.5, VERTEX/SURFACE/AMBIENT: include the chunk only for materials whose shading model
     * is this one ("blinn-gloss"); NULL = every model. Combines with when_material_has. */
    const char *when_model;
    /* ABI 1.6, VERTEX only: run the hook only on meshes of scene nodes carrying this tag (the
     * scene file's node "tags": ["nod"]; a node carries its ancestors' tags too, so meshes
     * imported under a tagged node are included); other meshes drawn with the same program keep
     * their vertices. NULL = every node. Combines with when_material_has and when_model. The
     * core selects per draw with a uniform (one branch per vertex, no extra program). */
    const char *when_node_tag;
    /* ABI 1.7, DISPLACEMENT only: the chunk's edge tessellation level function
     * float LEVEL(vec3 a, vec3 b) (see "Displacement" above); NULL = about 8-pixel edges. */
    const char *tess_level;
    /* ABI 1.13, DEBUG_VIEW with SL_CHUNK_PASS_VIEW only: the render-graph resource the view shows
     * ("my-plugin.ao", "normal"). */
    const char *resource;
    /* ABI 1.17, VERTEX/SURFACE/AMBIENT/DISPLACEMENT/SCENE_BEHIND: include the chunk only while this
     * bool global parameter of the same plugin is true ("layer_transmission"); it must be declared
     * with SL_PARAM_NEEDS_RECOMPILE (else the plugin is disabled at load). Combines with the other
     * gates. NULL = always. */
    const char *when_param;
} sl_shader_chunk_desc;

typedef enum sl_chunk_flags {
    /* SHADING_MODEL: the model handles shading normals facing away from the viewer itself
     * (e.g. Smith masking G1(v) = 0 for n·v <= 0), so normal perturbation must not bend them;
     * defines SL_MODEL_MASKS_FACING_AWAY in its programs (see above). */
    SL_CHUNK_MASKS_FACING_AWAY = 1u << 0,
    /* ABI 1.6, LIGHT: the light integrates the material's model over its own extent (area
     * lights) and returns outgoing radiance instead of a direction and an irradiance. Signature
     *     vec3 FN(SlLight L, SlSurface s)        radiance towards s.view, added to the light loop
     * It may call sl_shading_model(s, l, E) (declared in every forward program, ABI 1.6: the
     * material's model, e.g. for sampling points on the light) and sl_model_lobes(s) (ABI 1.14,
     * the lobe contract) to integrate any model without naming it. The SHADOW hook is not applied (the light handles its
     * own visibility) and per-light debug views (DEBUG_VIEW_LIGHT) get nothing from it. */
    SL_CHUNK_LIGHT_RADIANCE = 1u << 1,
    /* ABI 1.13, DEBUG_VIEW: a view of a render-graph resource a pass wrote, not of the materials
     * (a pass's own visualisation, shown as it is, not through tone mapping). `resource` names it;
     * `file` holds
     *     vec3 FN(sampler2D resource, vec2 uv)       uv in [0, 1] over the viewport
     * While the view is chosen every pass runs as usual and the material programs are unchanged;
     * the core's display pass then writes FN's value, clamped to [0, 1], straight into the 8-bit
     * output: no tone mapping and no sRGB encoding (0.5 is the code value 128). A resource no
     * pass wrote this frame shows black. Listed, chosen (--debug-view, the GUI, keys) and named
     * like every debug view. */
    SL_CHUNK_PASS_VIEW = 1u << 2
} sl_chunk_flags;

/* A stand-alone program (for passes: shadow maps, blurs, post effects). Files are relative to
 * the plugin's resource directory; "sl:" prefixes name the core's shader library
 * ("sl:fullscreen.vert"). `defines` is a newline-separated list of "NAME VALUE" lines; a line
 * "#extension NAME : BEHAVIOR" is passed through as that directive, right after #version in both
 * stages (check the extension first: glGetStringi(GL_EXTENSIONS, i)). */
typedef struct sl_program_desc {
    uint32_t struct_size;
    const char *vertex;
    const char *fragment;
    const char *defines;
} sl_program_desc;

#ifdef __cplusplus
}
#endif
#endif
