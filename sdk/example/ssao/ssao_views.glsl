// Debug views of the ssao example's pass (SL_CHUNK_PASS_VIEW): shown as stored, no tone mapping.
vec3 ssao_view_visibility(sampler2D visibility, vec2 uv) { return vec3(texture(visibility, uv).r); }
vec3 ssao_view_normal(sampler2D normal, vec2 uv) { return texture(normal, uv).xyz * 0.5 + 0.5; }
