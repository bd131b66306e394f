/* The glTF extensions shadelab knows of and what it does with each: the one list that
 * --list-gltf-extensions prints and the reader checks a file's extensionsRequired and
 * extensionsUsed against (glTF 2.0 §3.12: a file requiring an extension a reader does not
 * support must not be loaded as if it were understood). An extension not listed is not read.
 * Before it, what the reader makes of glTF 2.0's own features. Both lists are README.md's glTF
 * table (--gltf-markdown; the readme_options test fails when README's copy differs). */
#include "log.h"
#include "scene/gltf.h"

#include <stdio.h>
#include <string.h>

static const sl_gltf_extension features[] = {
    {"metallic-roughness materials", SL_GLTF_RENDERED,
     "base colour (factor x sRGB texture), metallic and roughness factors and texture: the BRDF of the "
     "specification's appendix B (ggx)"},
    {"normal, occlusion and emissive textures", SL_GLTF_RENDERED,
     "normal scale; occlusion on indirect light only; emissive factor and texture"},
    {"samplers and UV sets 0 and 1", SL_GLTF_RENDERED, "wrap modes, filters, texCoord 0 or 1"},
    {"alphaMode MASK and doubleSided", SL_GLTF_RENDERED, "cut out in the colour pass and in shadow maps; back faces"},
    {"cameras", SL_GLTF_RENDERED, "perspective and orthographic: the first, or --camera NAME"},
    {"node animation", SL_GLTF_RENDERED,
     "translation, rotation and scale channels, LINEAR, STEP and CUBICSPLINE, one animation (the first or "
     "--animation): looping in the window, at --time T headless; motion vectors for TAA"},
    {"skins", SL_GLTF_RENDERED,
     "up to 8 joints per vertex (JOINTS_0/1, WEIGHTS_0/1; more is an error), posed on the GPU before every pass"},
    {"morph targets", SL_GLTF_RENDERED, "POSITION, NORMAL and TANGENT targets; node or mesh weights, animated"},
    {"accessors", SL_GLTF_RENDERED, "interleaved, sparse, without a bufferView, normalized integers"},
    {"triangle lists, strips and fans", SL_GLTF_RENDERED, "flat normals where a primitive has none"},
    {"vertex colours (COLOR_0)", SL_GLTF_RENDERED,
     "VEC3 or VEC4, multiplying the base colour and alpha in every shading model; not morphed"},
    {"alphaMode BLEND", SL_GLTF_APPROXIMATED,
     "blended back to front per draw by the depth of its bounds' centre: not where blended meshes intersect, nor "
     "within one mesh"},
    {"generated tangents", SL_GLTF_APPROXIMATED,
     "where a primitive has no TANGENT: from its UVs by Lengyel's method, not MikkTSpace"},
    {"normal textures on UV set 1", SL_GLTF_APPROXIMATED, "the tangent frame of UV set 0"},
    {"lights and cameras under animated nodes", SL_GLTF_APPROXIMATED, "at the file's rest pose, not animated"},
    {"UV sets beyond 1", SL_GLTF_IGNORED, "those textures read UV set 0 (named)"},
    {"points and lines", SL_GLTF_IGNORED, "not drawn (named)"},
};

static const sl_gltf_extension extensions[] = {
    {"KHR_lights_punctual", SL_GLTF_APPROXIMATED,
     "directional, point and spot lights (spot fall-off as the extension gives it); range is not applied"},
    {"KHR_materials_emissive_strength", SL_GLTF_RENDERED, "emissiveFactor scaled by emissiveStrength"},
    {"KHR_materials_ior", SL_GLTF_RENDERED, "the dielectric's F0 from ior (ggx)"},
    {"KHR_materials_unlit", SL_GLTF_RENDERED, "the base colour, unlit"},
    {"KHR_texture_transform", SL_GLTF_APPROXIMATED,
     "offset, rotation, scale and texCoord per texture; normal maps keep UV set 0's tangent frame"},
    {"KHR_mesh_quantization", SL_GLTF_RENDERED, "8- and 16-bit integer positions, normals, tangents and UVs"},
    {"KHR_materials_pbrSpecularGlossiness", SL_GLTF_APPROXIMATED,
     "diffuse as base colour, metallic 0, roughness 1 - glossiness; the specular colour and its texture are "
     "not rendered"},
    {"KHR_materials_clearcoat", SL_GLTF_APPROXIMATED,
     "a second GGX lobe with its roughness, textures and normal texture, over the emission too (ggx); environment "
     "and area lights see the coat about the base's normal"},
    {"KHR_materials_sheen", SL_GLTF_APPROXIMATED,
     "Charlie sheen with the albedo scaling of the layers below (ggx); environment and area lights see it as a "
     "diffuse albedo sheenColor * E(n.v)"},
    {"KHR_materials_specular", SL_GLTF_APPROXIMATED,
     "the dielectric's specular strength and F0 colour, factors and textures (ggx); environment and area lights "
     "weight the diffuse by 1 - F per channel"},
    {"KHR_materials_transmission", SL_GLTF_APPROXIMATED,
     "thin walls showing the opaque scene behind them, blurred by roughness (ggx); transmissive surfaces do not see "
     "each other, and cast full shadows"},
    {"KHR_materials_volume", SL_GLTF_APPROXIMATED,
     "refraction through the thickness by the IOR and Beer-Lambert absorption along it (ggx), from the thickness "
     "factor and texture, not the mesh"},
    {"KHR_materials_iridescence", SL_GLTF_APPROXIMATED,
     "the thin film's Fresnel (Belcour & Barla, spectrally integrated) in the base's specular, factors and textures "
     "(ggx); environment and area lights see the film's Fresnel at n.v"},
    {"KHR_materials_anisotropy", SL_GLTF_APPROXIMATED,
     "the anisotropic GGX lobe (Burley's D, Smith's G) along the rotated tangent or texture direction (ggx); "
     "environment and area lights see an isotropic lobe of alpha sqrt(alpha_t * alpha_b)"},
    {"KHR_materials_dispersion", SL_GLTF_APPROXIMATED,
     "an IOR per colour channel (the extension's Cauchy fit at the C, d and F lines) for the volume's refracted "
     "lookups (ggx): three rays, not a spectrum; thin walls (no volume) do not disperse"},
    {"KHR_materials_variants", SL_GLTF_RENDERED, "the default materials, or the variant --variant NAME names"},
    {"KHR_animation_pointer", SL_GLTF_IGNORED, "those channels are not played"},
    {"KHR_draco_mesh_compression", SL_GLTF_RENDERED, "decoded with Debian's libdraco (a module loaded for the first one)"},
    {"EXT_meshopt_compression", SL_GLTF_RENDERED, "decoded with meshoptimizer: every mode and filter"},
    {"KHR_texture_basisu", SL_GLTF_IGNORED, "refused when required; the fallback image otherwise"},
    {"EXT_texture_webp", SL_GLTF_RENDERED, "WebP images (decoded by OpenImageIO), in place of the fallback"},
    {"EXT_mesh_gpu_instancing", SL_GLTF_IGNORED, "one instance, at the node"},
    {"KHR_xmp_json_ld", SL_GLTF_IGNORED, "metadata, nothing to render"},
};

const sl_gltf_extension *sl_gltf_extensions(int *count) {
    *count = (int)(sizeof extensions / sizeof *extensions);
    return extensions;
}

const sl_gltf_extension *sl_gltf_features(int *count) {
    *count = (int)(sizeof features / sizeof *features);
    return features;
}

void sl_gltf_print_markdown(void) {
    static const char *const label[] = {"✓", "approximate", "not rendered"};
    printf("| | glTF 2.0 feature or extension |\n|---|---|\n");
    for (int k = SL_GLTF_RENDERED; k <= SL_GLTF_IGNORED; k++) {
        printf("| %s | ", label[k]);
        int n = 0;
        for (size_t i = 0; i < sizeof features / sizeof *features; i++)
            if ((int)features[i].support == k) printf("%s%s", n++ ? "; " : "", features[i].name);
        for (size_t i = 0; i < sizeof extensions / sizeof *extensions; i++)
            if ((int)extensions[i].support == k) printf("%s`%s`", n++ ? "; " : "", extensions[i].name);
        printf("%s |\n", k == SL_GLTF_IGNORED ? "; any other extension (refused where a file requires it)" : "");
    }
}

bool gltf_extension_read(const char *name) {
    for (size_t i = 0; i < sizeof extensions / sizeof *extensions; i++)
        if (!strcmp(extensions[i].name, name)) return extensions[i].support != SL_GLTF_IGNORED;
    return false;
}

/* Lists the names in `arr` that shadelab does not read into out ("A, B"); their count. */
static int not_read(const cJSON *arr, char *out, size_t size) {
    int count = 0;
    size_t u = 0;
    out[0] = 0;
    const cJSON *e;
    cJSON_ArrayForEach(e, arr) {
        if (!cJSON_IsString(e) || gltf_extension_read(e->valuestring)) continue;
        if (u < size) u += snprintf(out + u, size - u, "%s%.100s", count ? ", " : "", e->valuestring);
        count++;
    }
    return count;
}

bool gltf_check_extensions(gltf_doc *d) {
    const cJSON *required, *used;
    if (!gltf_get_array(d, d->root, "", "extensionsRequired", &required) ||
        !gltf_get_array(d, d->root, "", "extensionsUsed", &used))
        return false;
    char list[1024];
    int n = not_read(required, list, sizeof list);
    if (n)
        return gltf_fail(d, NULL, "the file requires glTF extension%s shadelab does not support: %s", n > 1 ? "s" : "", list);
    if (not_read(used, list, sizeof list))
        SL_WARN("%s: uses glTF extensions shadelab does not render (ignored, the file shows without them): %s", d->path, list);
    return true;
}

bool gltf_uses_extension(const gltf_doc *d, const char *name) {
    const cJSON *e;
    cJSON_ArrayForEach(e, cJSON_GetObjectItemCaseSensitive(d->root, "extensionsUsed"))
        if (cJSON_IsString(e) && !strcmp(e->valuestring, name)) return true;
    return false;
}
