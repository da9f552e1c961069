#version 460
// Tessellation voxelizer, evaluation stage (Freed 2018 §4.1.2): point mode, equal spacing;
// every generated vertex writes the voxel it falls in, with barycentric-interpolated albedo
// (material colour times texture) and normal. With VOXEL_FLAG_NEIGHBOURS it also tests the 26
// voxels around that one against the triangle (exact triangle/box test) and fills those the
// triangle meets that are still empty: a lattice with at most one voxel between samples then
// reaches every voxel the triangle touches, even those a thin or small triangle only grazes,
// and the fill never competes with the averaging of voxels already written.
#include "frame.glsl"
#include "material_textures.glsl"
#include "voxel.glsl"
#include "tribox.glsl"

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
    ivec3 own = ivec3(floor(to_voxel_space(world)));
    write_voxel(own, voxel_albedo_of(m, albedo), normal, voxel_emission_of(m));
    if ((voxel.grid.y & VOXEL_FLAG_NEIGHBOURS) != 0u) {
        // In the unwarped grid, each texel as its own box there (a warped one's is not a unit cube).
        vec3 p0 = to_grid_space(in_world[0]), p1 = to_grid_space(in_world[1]), p2 = to_grid_space(in_world[2]);
        for (int i = 0; i < 27; i++) {
            ivec3 c = own + ivec3(i % 3, (i / 3) % 3, i / 9) - 1;
            if (i == 13 || !in_grid(c)) continue;
            vec3 centre, half_size;
            texel_box(c, centre, half_size);
            if (imageLoad(voxel_albedo, stored_at(in_slab(c))).r == 0u &&
                triangle_box_overlap(p0 - centre, p1 - centre, p2 - centre, half_size)) {
                write_voxel(c, voxel_albedo_of(m, albedo), normal, voxel_emission_of(m));
            }
        }
    }
    gl_Position = vec4(world, 1.0);
}
