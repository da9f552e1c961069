#version 460
// Forward shading (Freed 2018 §4.5, the thesis' choice): after the depth prepass, each visible
// fragment applies its material's textures and runs `shade_surface` (common/shading.glsl).
// Constants 3 and 4: whether any light is an area light (common/light.glsl), and whether any
// material reflects specularly (common/shading.glsl).
layout(constant_id = 3) const bool AREA_LIGHTS = true;
layout(constant_id = 4) const bool SPECULAR_MATERIALS = true;
#define VCT_AREA_LIGHTS AREA_LIGHTS
#define VCT_SPECULAR SPECULAR_MATERIALS
#include "frame.glsl"

layout(set = 2, binding = 0) uniform sampler2DArrayShadow shadow_map;
layout(set = 2, binding = 1) uniform sampler3D radiance_volume;
layout(set = 2, binding = 2) uniform sampler3D radiance_aniso;
layout(set = 2, binding = 3) uniform sampler3D radiance_moment;
layout(set = 2, binding = 4) uniform sampler3D radiance_chain;
#define BRICKS_SET 2
#define BRICKS_BINDING 5
#include "level0.glsl"

#include "shading.glsl"
#include "surface.glsl"

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in vec4 in_tangent;

layout(location = 0) out vec4 out_radiance;

void main() {
    Material m = materials[push.material];
    vec3 albedo, n;
    surface_inputs(m, in_normal, in_uv, in_tangent, albedo, n);
    out_radiance = vec4(shade_surface(m, albedo, n, in_world, ivec2(gl_FragCoord.xy)), 1.0);
}
