// Voxel warping, the shaders' copy of `voxel::warp` and `voxel::perspective`.
// By a function (Freed 2018 §4.6.1): each axis's grid fraction x maps to a texture fraction by
// the thesis' cubic, its slope peaking at the camera's fraction c and falling to the end slope a
// at the grid's faces (a = 1: no warp). `warp` is a vec4: xyz the centre c per axis, w the end
// slope a.
// By perspective (§4.6.2, made projective): texture fraction = (H x).xyz / (H x).w, H a mat4
// (`proj`, its inverse `unproj`) whose w is the distance from the frustum's apex. `warp` then
// holds x the peak slope, y the cube root of |det H|, z the w triangles are clipped at, w = 0.
#ifndef VCT_WARP_GLSL
#define VCT_WARP_GLSL
#include "config.h"

// Whether the pipeline was built for a warped grid: off, every warp_on() is false at compile
// time and the warp costs nothing (a CPU driver runs both sides of a branch inside a loop).
layout(constant_id = WARP_CONSTANT_ID) const bool WARPED = false;

bool warp_on(vec4 warp) {
    return WARPED && warp.w < 1.0;
}

// The perspective warp: a projective map, not axis by axis.
bool warp_projective(vec4 warp) {
    return WARPED && warp.w <= 0.0;
}

// The function warp: each axis on its own, a texel a box of the unwarped grid.
bool warp_separable(vec4 warp) {
    return warp_on(warp) && warp.w > 0.0;
}

// Texels per grid voxel where they are finest (1: no warp): the function's centre, the
// perspective's near plane.
float warp_peak_slope(vec4 warp) {
    return warp.w <= 0.0 ? warp.x : 1.5 - 0.5 * min(warp.w, 1.0);
}

// The perspective warp's homogeneous texture fraction of grid fraction `x`.
vec4 warp_project_h(vec3 x, mat4 proj) {
    return proj * vec4(x, 1.0);
}

// The perspective warp's texture fraction of grid fraction `x`; far outside the texels (-4)
// within the clip distance of the apex or behind it.
vec3 warp_project(vec3 x, vec4 warp, mat4 proj) {
    vec4 q = warp_project_h(x, proj);
    return q.w > warp.z ? q.xyz / q.w : vec3(-4.0);
}

// The perspective warp's texels per grid voxel at grid fraction `x`, as one size: the cube
// root of the map's Jacobian determinant, |det H| / w^4.
float warp_project_slope(vec3 x, vec4 warp, mat4 proj) {
    float w = max(warp_project_h(x, proj).w, warp.z);
    return warp.y / pow(w, 4.0 / 3.0);
}

// One side's half-cubic: h(0) = 0, h(1) = 1, slope a at 0 and 1.5 - a/2 at 1.
vec3 warp_h(vec3 u, float a) {
    return u * (a + u * (1.5 - 1.5 * a + u * (0.5 * a - 0.5)));
}

vec3 warp_h_slope(vec3 u, float a) {
    return a + u * (3.0 - 3.0 * a + u * (1.5 * a - 1.5));
}

// Texture fraction of grid fraction `x` (each axis; beyond the faces at slope a).
vec3 warp_forward(vec3 x, vec4 warp) {
    vec3 c = warp.xyz;
    float a = warp.w;
    vec3 below = c * warp_h(clamp(x / max(c, 1e-6), 0.0, 1.0), a);
    vec3 above = 1.0 - (1.0 - c) * warp_h(clamp((1.0 - x) / max(1.0 - c, 1e-6), 0.0, 1.0), a);
    vec3 inside = mix(above, below, lessThan(x, c));
    return x + (inside - x) * vec3(greaterThan(x, vec3(0.0))) * vec3(lessThan(x, vec3(1.0))) +
           (a - 1.0) * (min(x, 0.0) + max(x - 1.0, 0.0));
}

// The slope dw/dx at grid fraction `x`: texels per unwarped texel.
vec3 warp_slope(vec3 x, vec4 warp) {
    vec3 c = warp.xyz;
    float a = warp.w;
    vec3 below = warp_h_slope(clamp(x / max(c, 1e-6), 0.0, 1.0), a);
    vec3 above = warp_h_slope(clamp((1.0 - x) / max(1.0 - c, 1e-6), 0.0, 1.0), a);
    vec3 inside = mix(above, below, lessThan(x, c));
    return mix(vec3(a), inside, vec3(greaterThan(x, vec3(0.0))) * vec3(lessThan(x, vec3(1.0))));
}

// Texels per grid voxel at grid fraction `x`, as one size: the geometric mean of the three
// axes' slopes.
float warp_mean_slope(vec3 x, vec4 warp) {
    vec3 s = warp_slope(x, warp);
    return exp2((log2(s.x) + log2(s.y) + log2(s.z)) / 3.0);
}

// u in [0, 1] with h(u) = t: Newton's method from min(1, t/a), right of the root (h(u) >= a u),
// from where it moves monotonically onto it, h being convex and increasing.
vec3 warp_h_inverse(vec3 t, float a) {
    vec3 u = min(t / a, 1.0);
    for (int i = 0; i < 6; i++) u -= (warp_h(u, a) - t) / warp_h_slope(u, a);
    return clamp(u, 0.0, 1.0);
}

// Grid fraction of texture fraction `w` (the inverse of warp_forward on [0, 1]).
vec3 warp_inverse(vec3 w, vec4 warp) {
    vec3 c = warp.xyz;
    float a = warp.w;
    vec3 below = c * warp_h_inverse(clamp(w / max(c, 1e-6), 0.0, 1.0), a);
    vec3 above = 1.0 - (1.0 - c) * warp_h_inverse(clamp((1.0 - w) / max(1.0 - c, 1e-6), 0.0, 1.0), a);
    vec3 inside = mix(above, below, lessThan(w, c));
    vec3 outside = mix(1.0 + (w - 1.0) / a, w / a, lessThan(w, vec3(0.0)));
    return mix(outside, inside, vec3(greaterThanEqual(w, vec3(0.0))) * vec3(lessThanEqual(w, vec3(1.0))));
}

// The perspective warp's texels crossed per grid voxel moving along unit direction `n` from grid
// fraction `x` (each axis; `dims` the texel counts, which grid voxels share): the map's Jacobian,
// (H3 m - t (h_w . m)) / w for m = n / dims, t the texture fraction and h_w H's bottom row.
vec3 warp_project_along(vec3 x, vec3 n, vec3 dims, mat4 proj) {
    vec4 q = warp_project_h(x, proj);
    vec4 dq = proj * vec4(n / dims, 0.0);
    return dims * (dq.xyz - q.xyz / q.w * dq.w) / q.w;
}

// Clips triangle `h` (homogeneous texture fractions) to w >= `clip`, where the perspective warp
// has texels: the corners of what is left (none, a triangle, or a quad fanned from corner 0),
// each as weights of the triangle's corners (for its attributes too). Returns their count.
int warp_clip(vec4 h[3], float clip, out vec3 weights[4]) {
    int count = 0;
    for (int k = 0; k < 3; k++) {
        int next = (k + 1) % 3;
        float da = h[k].w - clip, db = h[next].w - clip;
        vec3 a = vec3(k == 0, k == 1, k == 2), b = vec3(next == 0, next == 1, next == 2);
        if (da >= 0.0) weights[count++] = a;
        if ((da >= 0.0) != (db >= 0.0)) weights[count++] = mix(a, b, da / (da - db));
    }
    return count;
}

// The point of triangle `h` with corner weights `b`, among `dims` texels.
vec3 warp_clipped_texel(vec4 h[3], vec3 b, vec3 dims) {
    vec4 q = h[0] * b.x + h[1] * b.y + h[2] * b.z;
    return q.xyz / q.w * dims;
}

// Texture fraction of grid fraction `x`, by either warp.
vec3 warp_to_texture(vec3 x, vec4 warp, mat4 proj) {
    return warp_projective(warp) ? warp_project(x, warp, proj) : warp_forward(x, warp);
}

// Grid fraction of texture fraction `w`, by either warp (`unproj`: the perspective's inverse).
vec3 warp_to_grid(vec3 w, vec4 warp, mat4 unproj) {
    if (warp_projective(warp)) {
        vec4 q = unproj * vec4(w, 1.0);
        return q.xyz / q.w;
    }
    return warp_inverse(w, warp);
}

// Texels per grid voxel at grid fraction `x`, as one size, by either warp.
float warp_local_slope(vec3 x, vec4 warp, mat4 proj) {
    return warp_projective(warp) ? warp_project_slope(x, warp, proj) : warp_mean_slope(x, warp);
}

#endif
