#version 460
// Rasterized voxelizer, fragment stage (Freed 2018 §4.1.1): maps the fragment back to its
// voxel (undoing the dominant-axis swizzle) and writes it with atomic averaging. With
// VOXEL_FLAG_DEPTH_SPAN it writes every depth layer the triangle's plane crosses within the
// pixel (clamped to the triangle's depth range), which a slanted face needs within one pixel
// column; without, only the layer at the pixel centre's depth (the thesis' method).
#include "frame.glsl"
#include "voxel.glsl"

layout(location = 0) in vec3 in_normal;
layout(location = 1) in vec2 in_uv;
layout(location = 2) flat in uint in_axis;
layout(location = 3) flat in vec4 in_depth;

vec3 unswizzle(vec3 v, uint axis) {
    return axis == 0u ? v.zxy : (axis == 1u ? v.yzx : v);
}

void main() {
    float res = float(voxel.grid.x);
    float scale = float(voxel.grid.z);
    vec2 xy = floor(gl_FragCoord.xy / scale);
    float z = gl_FragCoord.z * res;
    Material m = materials[push.material];
    vec3 albedo = m.albedo.rgb;
    if (m.tex.x == HAS_TEXTURE) albedo *= texture(albedo_texture, in_uv).rgb;
    float lo = z, hi = z;
    if ((voxel.grid.y & VOXEL_FLAG_DEPTH_SPAN) != 0u) {
        // Half a pixel (in voxel units) in x and y around the centre.
        float reach = 0.5 / scale * (abs(in_depth.z) + abs(in_depth.w));
        lo = max(z - reach, in_depth.x);
        hi = min(z + reach, in_depth.y);
        if (lo > hi) { lo = z; hi = z; }
    }
    int first = int(floor(lo)), last = min(int(floor(hi)), int(floor(lo)) + 3);
    for (int layer = first; layer <= last; layer++) {
        write_voxel(ivec3(unswizzle(vec3(xy, float(layer)), in_axis)), albedo, in_normal);
    }
}
