#version 460
// Point-based voxelizer (Mavridis & Papaioannou 2011, §3.1, "imperfect volumes"): one vertex per
// sample point scattered over the triangles when the volume was built (voxel::points); each
// writes the voxel it falls in with its material's albedo (times the texture at its UV), its
// interpolated normal and the emission, through the same averaging as the other voxelizers.
// Nothing is rasterized.
#include "frame.glsl"
#include "material_textures.glsl"
#include "voxel.glsl"

layout(location = 0) in vec3 in_pos;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;

void main() {
    Material m = materials[push.material];
    vec3 albedo = m.albedo.rgb;
    if (m.tex.x == HAS_TEXTURE) albedo *= textureLod(albedo_texture, in_uv, 0.0).rgb;
    vec3 normal = dot(in_normal, in_normal) < 1e-12 ? vec3(0.0, 1.0, 0.0) : in_normal;
    ivec3 v = ivec3(floor(to_voxel_space(in_pos)));
    write_voxel(v, voxel_albedo_of(m, albedo), normal, voxel_emission_of(m));
    gl_Position = vec4(in_pos, 1.0);
    gl_PointSize = 1.0;
}
