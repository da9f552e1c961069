// Cook-Torrance direct lighting as Freed 2018 §4.5.1 (after UE4, Karis 2013): GGX normal
// distribution, Smith–Schlick geometry term with k = (r+1)^2/8, Schlick Fresnel, Lambert
// diffuse albedo/pi. Denominator 4 (n.l)(n.v): the thesis' pi is already inside D.
#ifndef VCT_BRDF_GLSL
#define VCT_BRDF_GLSL

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
