#version 460
// Tessellation voxelizer, evaluation stage (Freed 2018 §4.1.2): point mode, equal spacing;
// every generated vertex writes the voxel it falls in, with barycentric-interpolated albedo
// (material colour times texture) and normal.
#include "frame.glsl"
#include "material_textures.glsl"
#include "voxel.glsl"

layout(triangles, equal_spacing, point_mode) in;

layout(location = 0) in vec3 in_world[];
layout(location = 1) in vec3 in_normal[];
layout(location = 2) in vec2 in_uv[];

void main() {
    vec3 b = gl_TessCoord;
    vec3 world = b.x * in_world[0] + b.y * in_world[1] + b.z * in_world[2];
    vec3 normal = b.x * in_normal[0] + b.y * in_normal[1] + b.z * in_normal[2];
    vec2 uv = b.x * in_uv[0] + b.y * in_uv[1] + b.z * in_uv[2];
    Material m = materials[push.material];
    vec3 albedo = m.albedo.rgb;
    if (m.tex.x == HAS_TEXTURE) albedo *= textureLod(albedo_texture, uv, 0.0).rgb;
    if (dot(normal, normal) < 1e-12) normal = vec3(0.0, 1.0, 0.0);
    write_voxel(ivec3(floor(to_voxel_space(world))), albedo, normal, m.emissive.rgb);
    gl_Position = vec4(world, 1.0);
}
