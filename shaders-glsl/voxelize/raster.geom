#version 460
// Rasterized voxelizer, geometry stage (Freed 2018 §4.1.1, Algorithm 1): projects each
// triangle orthographically along the dominant axis of its face normal, computed from its
// edges (vertex normals can cancel), onto an N x N (times the viewport scale) attachment-less
// framebuffer. Depth carries the third voxel coordinate in [0, 1).
#include "voxel.glsl"

layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

layout(location = 0) in vec3 in_world[];
layout(location = 1) in vec3 in_normal[];
layout(location = 2) in vec2 in_uv[];

layout(location = 0) out vec3 out_normal;
layout(location = 1) out vec2 out_uv;
layout(location = 2) flat out uint out_axis;
// Depth range of the triangle (voxel units) and the plane's depth slope per voxel step.
layout(location = 3) flat out vec4 out_depth;
// The triangle in swizzled voxel space, for the fragment stage's exact voxel test.
layout(location = 4) flat out vec3 out_tri[3];

// Rotates voxel coordinates so the dominant axis becomes z.
vec3 swizzle(vec3 v, uint axis) {
    return axis == 0u ? v.yzx : (axis == 1u ? v.zxy : v);
}

void main() {
    vec3 p[3];
    for (int i = 0; i < 3; i++) p[i] = to_voxel_space(in_world[i]);
    vec3 n = abs(cross(p[1] - p[0], p[2] - p[0]));
    uint axis = (n.x >= n.y && n.x >= n.z) ? 0u : (n.y >= n.z ? 1u : 2u);
    float res = float(voxel.grid.x);
    vec3 q[3];
    for (int i = 0; i < 3; i++) q[i] = swizzle(p[i], axis);
    // Depth gradient of the triangle's plane in voxels per voxel step in x and y.
    vec3 e1 = q[1] - q[0], e2 = q[2] - q[0];
    float det = e1.x * e2.y - e2.x * e1.y;
    vec2 slope = abs(det) > 1e-20 ? vec2(e1.z * e2.y - e2.z * e1.y, e2.z * e1.x - e1.z * e2.x) / det : vec2(0.0);
    float zmin = min(q[0].z, min(q[1].z, q[2].z)), zmax = max(q[0].z, max(q[1].z, q[2].z));
    for (int i = 0; i < 3; i++) {
        gl_Position = vec4(q[i].xy / res * 2.0 - 1.0, q[i].z / res, 1.0);
        out_normal = in_normal[i];
        out_uv = in_uv[i];
        out_axis = axis;
        out_depth = vec4(zmin, zmax, slope);
        out_tri = q;
        EmitVertex();
    }
    EndPrimitive();
}
