#version 460
// Point voxelizer's refinement (Mavridis & Papaioannou 2011, §3.2): every pixel the camera
// sees (depth equal to the depth pass: the G-buffer's surface) is re-projected into the volume
// and fills its voxel where the points left it empty, with its material's albedo (times the
// texture), its normal and its emission. Voxels the points found keep their points' average.
#include "frame.glsl"
#include "material_textures.glsl"
#include "voxel.glsl"

layout(early_fragment_tests) in;

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;

void main() {
    ivec3 v = ivec3(floor(to_voxel_space(in_world)));
    if (!in_grid(v) || imageLoad(voxel_albedo, stored_at(in_slab(v))).r != 0u) return;
    Material m = materials[push.material];
    vec3 albedo = m.albedo.rgb;
    if (m.tex.x == HAS_TEXTURE) albedo *= texture(albedo_texture, in_uv).rgb;
    vec3 normal = dot(in_normal, in_normal) < 1e-12 ? vec3(0.0, 1.0, 0.0) : in_normal;
    write_voxel(v, voxel_albedo_of(m, albedo), normal, voxel_emission_of(m));
}
