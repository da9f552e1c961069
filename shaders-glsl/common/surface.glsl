// A fragment's material inputs: albedo times its texture, and the shading normal (normal map
// applied through the tangent frame when the material has one). Needs set 1 (material textures).
#ifndef VCT_SURFACE_GLSL
#define VCT_SURFACE_GLSL
#include "frame.glsl"
#include "material_textures.glsl"

void surface_inputs(Material m, vec3 normal, vec2 uv, vec4 tangent, out vec3 albedo, out vec3 n) {
    albedo = m.albedo.rgb;
    if (m.tex.x == HAS_TEXTURE) albedo *= texture(albedo_texture, uv).rgb;
    n = normalize(normal);
    if (m.tex.y == HAS_TEXTURE) {
        vec3 t = normalize(tangent.xyz - n * dot(n, tangent.xyz));
        vec3 b = cross(n, t) * tangent.w;
        vec3 tn = texture(normal_texture, uv).xyz * 2.0 - 1.0;
        n = normalize(mat3(t, b, n) * tn);
    }
}

#endif
