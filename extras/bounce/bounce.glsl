// bounce: the light "bounce.indirect" (a LIGHT chunk with SL_CHUNK_LIGHT_RADIANCE, type
// "indirect"): the one-bounce diffuse irradiance of the probe grid (bounce_probes.frag: order-2
// spherical harmonics, 27 floats in seven 3D textures), trilinear at the shading point moved half a
// cell along its normal (out of the surface it lies on, so the probes behind it weigh less),
// E(n) = Σ_k C_k P_k(n), clamped at 0. Every model is lit through its lobe contract: diffuse
// albedo/π × E (its glossy lobes get no indirect light); a model asking for
// SL_LOBES_MODEL_AT_DOMINANT_LIGHT gets its own response at the order-1 terms' direction d with
// E_d = 2 (C_1..3 · d), and its diffuse the rest (common.glsl). s.ao scales it as it scales the
// environment; so does the light's colour × intensity (white, 1: the plugin sets them). The debug
// view "bounce" shows it alone.
uniform sampler3D bounce_probe[7];
uniform vec3 bounce_box_min, bounce_box_max, bounce_cell;

// The radiance the bounce gives s (the light's colour and intensity aside).
vec3 bounce_outgoing(SlSurface s) {
    vec3 p = s.position + 0.25 * s.normal * bounce_cell;
    vec3 uvw = (p - bounce_box_min) / (bounce_box_max - bounce_box_min);
    vec4 q0 = texture(bounce_probe[0], uvw), q1 = texture(bounce_probe[1], uvw), q2 = texture(bounce_probe[2], uvw);
    vec4 q3 = texture(bounce_probe[3], uvw), q4 = texture(bounce_probe[4], uvw), q5 = texture(bounce_probe[5], uvw);
    vec3 C0 = q0.xyz, C1 = vec3(q0.w, q1.xy), C2 = vec3(q1.zw, q2.x), C3 = q2.yzw;
    vec3 C4 = q3.xyz, C5 = vec3(q3.w, q4.xy), C6 = vec3(q4.zw, q5.x), C7 = q5.yzw, C8 = texture(bounce_probe[6], uvw).xyz;
    vec3 n = s.normal;
    vec3 E = C0 + C1 * n.y + C2 * n.z + C3 * n.x + C4 * (n.x * n.y) + C5 * (n.y * n.z) + C6 * (3.0 * n.z * n.z - 1.0) +
             C7 * (n.x * n.z) + C8 * (n.x * n.x - n.y * n.y);
    E = max(E, vec3(0.0));
    SlLobes lobes = sl_model_lobes(s);
    vec3 Lo = lobes.diffuse * SL_INV_PI * E;
    if ((lobes.flags & SL_LOBES_MODEL_AT_DOMINANT_LIGHT) != 0) {
        mat3 b = 2.0 * mat3(C3, C1, C2); // Σ e_j ω_j per channel (x, y, z columns)
        vec3 dm = transpose(b) * vec3(0.2126, 0.7152, 0.0722);
        vec3 d = length(dm) > 1e-8 ? normalize(dm) : n;
        vec3 Ed = max(b * d, vec3(0.0));
        Lo = sl_shading_model(s, d, Ed) + lobes.diffuse * SL_INV_PI * max(E - Ed * max(dot(n, d), 0.0), vec3(0.0));
    }
    return s.ao * Lo;
}

vec3 bounce_radiance(SlLight L, SlSurface s) { return L.color.rgb * bounce_outgoing(s); }

// Debug view "bounce": that radiance alone.
vec3 bounce_view(SlSurface s) { return bounce_outgoing(s); }
