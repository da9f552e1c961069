#version 460
// Rasterized voxelizer, geometry stage (Freed 2018 §4.1.1, Algorithm 1): projects each
// triangle orthographically along the dominant axis of its face normal, computed from its
// edges (vertex normals can cancel), onto an N x N (times the viewport scale) attachment-less
// framebuffer. The fragment stage takes the voxel depth from the triangle's plane. It works in
// the unwarped grid, where the triangle is flat; the fragment stage finds a function-warped
// grid's texels. A perspective warp (§4.6.2, made projective: voxel::perspective) keeps
// triangles flat among its texels, so there the triangle is mapped to them, clipped first where
// it reaches behind the apex (a quad is left: two triangles), and voxelized as on an even grid.
//
// With VOXEL_FLAG_CONSERVATIVE the projected triangle is grown so that every pixel it touches
// gets a fragment (Hasselgren, Akenine-Moeller & Ohlsson 2005, GPU Gems 2 ch. 42; Crassin &
// Green 2012, OpenGL Insights ch. 22): each edge moves out by half a pixel diagonal (the
// pixel square's support along the edge normal) and the new corners are where neighbouring
// moved edges meet. Acute corners shoot out, so the fragment stage discards pixels outside
// the triangle's bounding box; its exact triangle/voxel test keeps precision. A triangle with
// no area in its projection (a needle or a point), or with a corner so sharp that it would
// move more than 4 pixels, gets its bounding box instead.
#include "voxel.glsl"

layout(triangles) in;
layout(triangle_strip, max_vertices = 8) out;

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
// Conservative: the triangle's bounding box in pixels, grown by half a pixel (pixel centres
// inside it are pixels whose square meets the box); otherwise unbounded.
layout(location = 7) flat out vec4 out_bounds;

// Rotates voxel coordinates so the dominant axis becomes z.
vec3 swizzle(vec3 v, uint axis) {
    return axis == 0u ? v.yzx : (axis == 1u ? v.zxy : v);
}

vec3 q[3];
vec3 nrm[3];
vec2 uv[3];
uint axis;
vec4 depth;
vec4 bounds;

// Emits a vertex at pixel position `px` with the attributes of barycentric point `b`
// (extrapolated outside the triangle, as the grown corners need).
void emit(vec2 px, vec3 b, float scale, float res) {
    gl_Position = vec4(px / (scale * res) * 2.0 - 1.0, 0.5, 1.0);
    out_normal = nrm[0] * b.x + nrm[1] * b.y + nrm[2] * b.z;
    out_uv = uv[0] * b.x + uv[1] * b.y + uv[2] * b.z;
    out_axis = axis;
    out_depth = depth;
    out_tri = q;
    out_bounds = bounds;
    EmitVertex();
}

// Voxelizes triangle `p` (grid or texel coordinates; attributes in nrm and uv).
void voxelize(vec3 p[3]) {
    vec3 n = abs(cross(p[1] - p[0], p[2] - p[0]));
    axis = (n.x >= n.y && n.x >= n.z) ? 0u : (n.y >= n.z ? 1u : 2u);
    float res = float(voxel.grid.x);
    float scale = voxel.tess.z;
    bool conservative = (voxel.grid.y & VOXEL_FLAG_CONSERVATIVE) != 0u;
    if (conservative && n.x + n.y + n.z == 0.0) {
        // No face normal: project along the axis the triangle spans least.
        vec3 lo = min(p[0], min(p[1], p[2])), hi = max(p[0], max(p[1], p[2]));
        vec3 e = hi - lo;
        axis = (e.x <= e.y && e.x <= e.z) ? 0u : (e.y <= e.z ? 1u : 2u);
    }
    for (int i = 0; i < 3; i++) q[i] = swizzle(p[i], axis);
    // Depth gradient of the triangle's plane in voxels per voxel step in x and y.
    vec3 e1 = q[1] - q[0], e2 = q[2] - q[0];
    float det = e1.x * e2.y - e2.x * e1.y;
    vec2 slope = abs(det) > 1e-20 ? vec2(e1.z * e2.y - e2.z * e1.y, e2.z * e1.x - e1.z * e2.x) / det : vec2(0.0);
    float zmin = min(q[0].z, min(q[1].z, q[2].z)), zmax = max(q[0].z, max(q[1].z, q[2].z));
    depth = vec4(zmin, zmax, slope);
    vec2 s[3];
    for (int i = 0; i < 3; i++) s[i] = q[i].xy * scale;
    bounds = vec4(-1e30, -1e30, 1e30, 1e30);
    if (!conservative) {
        emit(s[0], vec3(1, 0, 0), scale, res);
        emit(s[1], vec3(0, 1, 0), scale, res);
        emit(s[2], vec3(0, 0, 1), scale, res);
        EndPrimitive();
        return;
    }
    vec2 lo = min(s[0], min(s[1], s[2])) - 0.5, hi = max(s[0], max(s[1], s[2])) + 0.5;
    bounds = vec4(lo, hi);
    float area = (s[1].x - s[0].x) * (s[2].y - s[0].y) - (s[2].x - s[0].x) * (s[1].y - s[0].y);
    // Edge lines a*x + b*y + c = 0 in pixels, positive inside, each moved out by half a
    // pixel diagonal; corner i is where the lines of edges (i-1, i) and (i, i+1) meet.
    float side = area > 0.0 ? 1.0 : -1.0;
    vec3 line[3];
    for (int i = 0; i < 3; i++) {
        vec3 l = side * cross(vec3(s[i], 1.0), vec3(s[(i + 1) % 3], 1.0));
        l.z += 0.5 * (abs(l.x) + abs(l.y));
        line[i] = l;
    }
    vec2 corner[3];
    bool thin = abs(area) <= 1e-6 * dot(hi - lo, hi - lo);
    for (int i = 0; i < 3 && !thin; i++) {
        vec3 h = cross(line[(i + 2) % 3], line[i]);
        corner[i] = h.xy / h.z;
        // A corner sharper than about 10 degrees moves more than 4 pixels: far corners lose
        // precision in clipping and rasterization, and the box is then the smaller shape.
        thin = !(abs(h.z) > 0.0) || distance(corner[i], s[i]) > 4.0;
    }
    if (thin) {
        // Degenerate or sharp in projection: its bounding box (the fragment stage tests voxels
        // exactly), with the centre's attributes.
        vec3 b = vec3(1.0 / 3.0);
        emit(vec2(lo.x, lo.y), b, scale, res);
        emit(vec2(hi.x, lo.y), b, scale, res);
        emit(vec2(lo.x, hi.y), b, scale, res);
        emit(vec2(hi.x, hi.y), b, scale, res);
        EndPrimitive();
        return;
    }
    for (int i = 0; i < 3; i++) {
        // The corner's barycentric coordinates in the original triangle, for its attributes.
        vec2 d0 = s[1] - s[0], d1 = s[2] - s[0], dc = corner[i] - s[0];
        float b1 = (dc.x * d1.y - d1.x * dc.y) / area;
        float b2 = (d0.x * dc.y - dc.x * d0.y) / area;
        emit(corner[i], vec3(1.0 - b1 - b2, b1, b2), scale, res);
    }
    EndPrimitive();
}

void main() {
    vec3 p[3];
    if (!warp_projective(voxel.warp)) {
        for (int i = 0; i < 3; i++) {
            p[i] = to_grid_space(in_world[i]);  // a function-warped grid's texels are found per fragment
            nrm[i] = in_normal[i];
            uv[i] = in_uv[i];
        }
        voxelize(p);
        return;
    }
    // Perspective: clip against w >= the clip distance (no texel lies nearer the apex), then
    // map each corner among the texels.
    vec3 dims = vec3(voxel.dims.xyz);
    vec4 h[3];
    for (int i = 0; i < 3; i++) h[i] = warp_project_h(to_grid_space(in_world[i]) / dims, voxel.warp_proj);
    vec3 corner[4];
    int count = warp_clip(h, voxel.warp.z, corner);
    for (int first = 1; first + 1 < count; first++) {
        int k[3] = int[3](0, first, first + 1);
        for (int i = 0; i < 3; i++) {
            vec3 b = corner[k[i]];
            p[i] = warp_clipped_texel(h, b, dims);
            nrm[i] = in_normal[0] * b.x + in_normal[1] * b.y + in_normal[2] * b.z;
            uv[i] = in_uv[0] * b.x + in_uv[1] * b.y + in_uv[2] * b.z;
        }
        voxelize(p);
    }
}
