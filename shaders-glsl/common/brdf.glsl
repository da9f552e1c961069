// Cook-Torrance direct lighting as Freed 2018 §4.5.1 (after UE4, Karis 2013): GGX normal
// distribution, Smith–Schlick geometry term with k = (r+1)^2/8, Schlick Fresnel, Lambert
// diffuse albedo/pi. Denominator 4 (n.l)(n.v): the thesis' pi is already inside D.
#ifndef VCT_BRDF_GLSL
#define VCT_BRDF_GLSL
#include "config.h"

const float PI = 3.14159265358979;

float ggx_d(float n_h, float alpha) {
    float a2 = alpha * alpha;
    float d = n_h * n_h * (a2 - 1.0) + 1.0;
    return a2 / (PI * d * d);
}

float smith_g1(float n_x, float k) {
    return n_x / (n_x * (1.0 - k) + k);
}

vec3 fresnel_schlick(vec3 f0, float cos_theta) {
    return f0 + (1.0 - f0) * pow(1.0 - clamp(cos_theta, 0.0, 1.0), 5.0);
}

// The specular lobe's directional albedo as a + f0 b: how much of the light from a surround of
// even radiance `cook_torrance`'s GGX lobe (the same D, G and F) reflects towards a view at
// `n_v` from the normal (Karis 2013's split sum, its second factor). This weights the specular
// cone's light, whose radiance stands for the lobe's surround. Schlick's Fresnel at the view
// angle would not do: it tends to 1 at grazing angles whatever the roughness, where a rough lobe
// reflects little (masked, and spread below the horizon): at roughness 0.8 and f0 0.04 it gives
// 0.61 at n.v = 0.1 and 0.20 at 0.3 against 0.042 and 0.031, and weighted by it Sponza's floor,
// seen at such angles, gathers 2.6 times the path tracer's indirect light (docs/design/cones.md).
// Integrated here, with no table to bind: the lobe's half vectors importance-sampled at
// SPECULAR_ALBEDO_SAMPLES Hammersley points (within 6% of a 32768-sample integral wherever
// n.v >= 0.03, within 2% at most angles).
vec2 ggx_albedo(float n_v, float roughness) {
    float alpha = roughness * roughness;
    float k = (roughness + 1.0) * (roughness + 1.0) / 8.0;
    n_v = clamp(n_v, 1e-4, 1.0);
    vec3 v = vec3(sqrt(1.0 - n_v * n_v), 0.0, n_v);
    float g_v = smith_g1(n_v, k);
    vec2 sum = vec2(0.0);
    for (uint i = 0u; i < uint(SPECULAR_ALBEDO_SAMPLES); i++) {
        float u = (float(i) + 0.5) / float(SPECULAR_ALBEDO_SAMPLES);
        float phi = 6.28318530718 * float(bitfieldReverse(i)) * 2.3283064365386963e-10;
        // GGX's half vectors, drawn in proportion to D(h) (n.h).
        float cos_h = sqrt((1.0 - u) / (1.0 + (alpha * alpha - 1.0) * u));
        float sin_h = sqrt(max(1.0 - cos_h * cos_h, 0.0));
        vec3 h = vec3(sin_h * cos(phi), sin_h * sin(phi), cos_h);
        float v_h = dot(v, h);
        float n_l = 2.0 * v_h * cos_h - n_v;
        if (v_h <= 0.0 || n_l <= 0.0) continue;
        // f (n.l) over the sample's density: G (v.h) / ((n.h) (n.v)), F split as f0 (1 - c) + c.
        float w = g_v * smith_g1(n_l, k) * v_h / (cos_h * n_v);
        float c = pow(1.0 - v_h, 5.0);
        sum += w * vec2(c, 1.0 - c);
    }
    return sum / float(SPECULAR_ALBEDO_SAMPLES);
}

// Reflected radiance per unit irradiance: (diffuse + specular BRDF) * (n.l).
vec3 cook_torrance(vec3 n, vec3 v, vec3 l, vec3 albedo, vec3 f0_dielectric, float roughness, float metallic) {
    float n_l = max(dot(n, l), 0.0);
    if (n_l <= 0.0) return vec3(0.0);
    vec3 diffuse = albedo * (1.0 - metallic) / PI;
    vec3 f0 = mix(f0_dielectric, albedo, metallic);
    vec3 specular = vec3(0.0);
    float n_v = max(dot(n, v), 1e-4);
    if (max(f0.r, max(f0.g, f0.b)) > 0.0) {
        vec3 h = normalize(l + v);
        float alpha = roughness * roughness;
        float k = (roughness + 1.0) * (roughness + 1.0) / 8.0;
        float g = smith_g1(n_v, k) * smith_g1(n_l, k);
        specular = ggx_d(max(dot(n, h), 0.0), alpha) * g * fresnel_schlick(f0, dot(h, v)) / (4.0 * n_l * n_v);
    }
    return (diffuse + specular) * n_l;
}

#endif
