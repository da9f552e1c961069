#version 460
// Tessellation voxelizer, control stage (Freed 2018 §4.1.2): each outer level is the number
// of voxels its edge spans along its dominant direction (|E|_inf / voxel), the inner level the
// triangle's largest altitude (Heron) over the voxel size; both times a level scale (the
// thesis' levels undersample diagonals, docs/design/voxelizers.md), clamped to the device maximum. With
// VOXEL_FLAG_MIN_LEVEL levels stay >= 1; without, a level below one truncates to 0 and the
// hardware discards the patch (the thesis' failure for triangles inside one voxel).
#include "voxel.glsl"

layout(vertices = 3) out;

layout(location = 0) in vec3 in_world[];
layout(location = 1) in vec3 in_normal[];
layout(location = 2) in vec2 in_uv[];
layout(location = 0) out vec3 out_world[];
layout(location = 1) out vec3 out_normal[];
layout(location = 2) out vec2 out_uv[];

float max3(vec3 v) { return max(v.x, max(v.y, v.z)); }

float level(float voxels) {
    float l = voxels * voxel.tess.x;
    if ((voxel.grid.y & VOXEL_FLAG_MIN_LEVEL) != 0u) l = max(l, 1.0);
    else if (l < 1.0) l = 0.0;
    return min(l, voxel.tess.y);
}

void main() {
    out_world[gl_InvocationID] = in_world[gl_InvocationID];
    out_normal[gl_InvocationID] = in_normal[gl_InvocationID];
    out_uv[gl_InvocationID] = in_uv[gl_InvocationID];
    if (gl_InvocationID == 0) {
        // In texels of the finest the grid has (a warped grid's are 1.5 - a/2 to a grid voxel).
        float fine = warp_peak_slope(voxel.warp);
        vec3 p0 = to_grid_space(in_world[0]) * fine;
        vec3 p1 = to_grid_space(in_world[1]) * fine;
        vec3 p2 = to_grid_space(in_world[2]) * fine;
        if (warp_projective(voxel.warp)) {
            // Among the texels, where the triangle stays flat, unless it reaches behind the
            // apex's clip plane (then at the finest texels' size, as above).
            vec3 n = vec3(voxel.dims.xyz);
            vec4 h0 = warp_project_h(to_grid_space(in_world[0]) / n, voxel.warp_proj);
            vec4 h1 = warp_project_h(to_grid_space(in_world[1]) / n, voxel.warp_proj);
            vec4 h2 = warp_project_h(to_grid_space(in_world[2]) / n, voxel.warp_proj);
            float near = min(h0.w, min(h1.w, h2.w));
            if (near > voxel.warp.z) {
                // Even steps along the triangle stretch among the texels by up to the ratio of
                // its corners' distances from the apex, where it is nearest: as much finer.
                float stretch = max(h0.w, max(h1.w, h2.w)) / near;
                p0 = h0.xyz / h0.w * n * stretch;
                p1 = h1.xyz / h1.w * n * stretch;
                p2 = h2.xyz / h2.w * n * stretch;
            }
        }
        // Outer level i belongs to the edge opposite vertex i.
        gl_TessLevelOuter[0] = level(max3(abs(p2 - p1)));
        gl_TessLevelOuter[1] = level(max3(abs(p0 - p2)));
        gl_TessLevelOuter[2] = level(max3(abs(p1 - p0)));
        float a = length(p2 - p1), b = length(p0 - p2), c = length(p1 - p0);
        float s = 0.5 * (a + b + c);
        float area = sqrt(max(s * (s - a) * (s - b) * (s - c), 0.0));
        float shortest = max(min(a, min(b, c)), 1e-12);
        gl_TessLevelInner[0] = level(2.0 * area / shortest);
    }
}
