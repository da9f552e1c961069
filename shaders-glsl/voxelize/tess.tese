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
        // In the unwarped grid, each texel as its own box there (a warped one's is not a unit
        // cube); a perspective warp's texels are unit cubes among the texels, where the triangle
        // is flat once clipped where it reaches behind the apex (then a quad: two triangles).
        vec3 t[4];
        t[0] = to_grid_space(in_world[0]);
        t[1] = to_grid_space(in_world[1]);
        t[2] = to_grid_space(in_world[2]);
        t[3] = t[2];
        bool projective = warp_projective(voxel.warp), fill = true;
        if (projective) {
            vec3 n = vec3(voxel.dims.xyz);
            vec4 h[3];
            for (int k = 0; k < 3; k++) h[k] = warp_project_h(t[k] / n, voxel.warp_proj);
            vec3 corner[4];
            int count = warp_clip(h, voxel.warp.z, corner);
            fill = count >= 3;  // none of it in front of the clip plane: no texel to fill
            for (int k = 0; k < 4 && fill; k++) t[k] = warp_clipped_texel(h, corner[min(k, count - 1)], n);
        }
        for (int i = 0; i < 27 && fill; i++) {
            ivec3 c = own + ivec3(i % 3, (i / 3) % 3, i / 9) - 1;
            if (i == 13 || !in_grid(c)) continue;
            vec3 centre = vec3(c) + 0.5, half_size = vec3(0.5);
            if (!projective) texel_box(c, centre, half_size);
            // The second triangle of a clipped quad (a triangle's own again otherwise).
            bool meets = triangle_box_overlap(t[0] - centre, t[1] - centre, t[2] - centre, half_size) ||
                         (projective && triangle_box_overlap(t[0] - centre, t[2] - centre, t[3] - centre, half_size));
            if (imageLoad(voxel_albedo, stored_at(in_slab(c))).r == 0u && meets) {
                write_voxel(c, voxel_albedo_of(m, albedo), normal, voxel_emission_of(m));
            }
        }
    }
    gl_Position = vec4(world, 1.0);
}
