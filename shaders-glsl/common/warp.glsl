// Voxel warping by a function (Freed 2018 §4.6.1), the shaders' copy of `voxel::warp`: each
// axis's grid fraction x maps to a texture fraction by the thesis' cubic, its slope peaking at
// the camera's fraction c and falling to the end slope a at the grid's faces (a = 1: no warp).
// `warp` is a vec4: xyz the centre c per axis, w the end slope a.
#ifndef VCT_WARP_GLSL
#define VCT_WARP_GLSL
#include "config.h"

// Whether the pipeline was built for a warped grid: off, every warp_on() is false at compile
// time and the warp costs nothing (a CPU driver runs both sides of a branch inside a loop).
layout(constant_id = WARP_CONSTANT_ID) const bool WARPED = false;

bool warp_on(vec4 warp) {
    return WARPED && warp.w < 1.0;
}

// The largest slope (at the centre): texels per grid voxel where they are finest (1: no warp).
float warp_peak_slope(vec4 warp) {
    return 1.5 - 0.5 * min(warp.w, 1.0);
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

#endif
