#version 460
// Forward shading (Freed 2018 §4.5, Algorithm 3 without the cone-traced part): emission plus
// Cook-Torrance direct light from the scene's light, shadowed by 3x3 PCF over the shadow map.
// Writes linear radiance; tone mapping is a separate pass.
#include "frame.glsl"
#include "brdf.glsl"
#include "light.glsl"

layout(set = 2, binding = 0) uniform sampler2DShadow shadow_map;

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in vec4 in_tangent;

layout(location = 0) out vec4 out_radiance;

float shadow_factor(vec3 p) {
    vec4 clip = frame.light_view_proj * vec4(p, 1.0);
    if (clip.w <= 0.0) return 0.0;
    vec3 ndc = clip.xyz / clip.w;
    vec2 uv = ndc.xy * 0.5 + 0.5;
    float texel = frame.light_cone.z;
    float lit = 0.0;
    for (int y = -PCF_RADIUS; y <= PCF_RADIUS; y++)
        for (int x = -PCF_RADIUS; x <= PCF_RADIUS; x++)
            lit += texture(shadow_map, vec3(uv + vec2(x, y) * texel, ndc.z));
    return lit / float((2 * PCF_RADIUS + 1) * (2 * PCF_RADIUS + 1));
}

void main() {
    Material m = materials[push.material];
    vec3 albedo = m.albedo.rgb;
    if (m.tex.x == HAS_TEXTURE) albedo *= texture(albedo_texture, in_uv).rgb;
    vec3 v = normalize(frame.camera_pos.xyz - in_world);
    vec3 n = normalize(in_normal);
    if (m.tex.y == HAS_TEXTURE) {
        vec3 t = normalize(in_tangent.xyz - n * dot(n, in_tangent.xyz));
        vec3 b = cross(n, t) * in_tangent.w;
        vec3 tn = texture(normal_texture, in_uv).xyz * 2.0 - 1.0;
        n = normalize(mat3(t, b, n) * tn);
    }
    // Two-sided: shade the side facing the viewer.
    if (dot(n, v) < 0.0) n = -n;

    vec3 l;
    vec3 irradiance = light_incident(in_world, l);
    vec3 direct = vec3(0.0);
    if (dot(n, l) > 0.0 && max(irradiance.r, max(irradiance.g, irradiance.b)) > 0.0) {
        direct = irradiance * cook_torrance(n, v, l, albedo, m.specular.rgb, m.emissive.a, m.albedo.a) * shadow_factor(in_world);
    }
    out_radiance = vec4(m.emissive.rgb + direct, 1.0);
}
