#version 460
// Rasterized voxelizer, fragment stage (Freed 2018 §4.1.1): maps the fragment back to its
// voxel (undoing the dominant-axis swizzle) and writes it with atomic averaging. With
// VOXEL_FLAG_DEPTH_SPAN it considers every depth layer the triangle's plane crosses within
// the pixel (a slanted face can cross into the next layer within one pixel column) and
// writes those whose voxel the triangle really touches (triangle/box test); without, only
// the layer at the pixel centre's depth (the thesis' method). Conservative coverage
// (raster.geom) needs the depth span: its extra fragments are kept only where the test passes.
// In a warped grid (Freed 2018 §4.6.1) the pixel is a box of the unwarped grid, and the texels
// tested are those its box (over the plane's depth span) warps onto, each as the box it is in
// the unwarped grid: coverage stays exact however the warp stretches texels, where the thesis
// raised the viewport resolution by the warp's largest slope and still sampled points. A
// perspective warp's triangles arrive among the texels (raster.geom): the even grid's path.
#include "frame.glsl"
#include "material_textures.glsl"
#include "voxel.glsl"
#include "tribox.glsl"

layout(location = 0) in vec3 in_normal;
layout(location = 1) in vec2 in_uv;
layout(location = 2) flat in uint in_axis;
layout(location = 3) flat in vec4 in_depth;
layout(location = 4) flat in vec3 in_tri[3];
layout(location = 7) flat in vec4 in_bounds;

// Depth (voxels) of the triangle's plane at `p` (swizzled voxel x, y).
float plane_depth(vec2 p) {
    return in_tri[0].z + dot(in_depth.zw, p - in_tri[0].xy);
}

vec3 unswizzle(vec3 v, uint axis) {
    return axis == 0u ? v.zxy : (axis == 1u ? v.yzx : v);
}

vec3 swizzle(vec3 v, uint axis) {
    return axis == 0u ? v.yzx : (axis == 1u ? v.zxy : v);
}

// Warped grid: writes every texel that the box lo..hi (swizzled grid coordinates: the pixel's
// column over the plane's depth span) warps onto and whose share of the pixel's column the
// triangle meets. Each texel is judged only within this pixel's column, as an even grid's
// texel is judged by its own pixel: the pixels that tile a texel each test their share, so
// the coverage is exact, and each writes only the texels it covers (judged whole, a texel
// would take the albedo of every pixel around it).
void write_warped(vec3 lo, vec3 hi, vec3 albedo, Material m) {
    ivec3 a = ivec3(floor(grid_to_voxel_space(unswizzle(lo, in_axis)) - 1e-4));
    ivec3 b = ivec3(floor(grid_to_voxel_space(unswizzle(hi, in_axis)) + 1e-4));
    a = max(a, ivec3(0));
    b = min(b, min(ivec3(voxel.dims.xyz) - 1, a + 7));
    for (int z = a.z; z <= b.z; z++) {
        for (int y = a.y; y <= b.y; y++) {
            for (int x = a.x; x <= b.x; x++) {
                vec3 c, h;
                texel_box(ivec3(x, y, z), c, h);
                c = swizzle(c, in_axis);
                h = swizzle(h, in_axis);
                vec2 from = max(c.xy - h.xy, lo.xy), to = min(c.xy + h.xy, hi.xy);
                if (any(lessThanEqual(to, from))) continue;
                c.xy = 0.5 * (from + to);
                h.xy = 0.5 * (to - from);
                if (triangle_box_overlap(in_tri[0] - c, in_tri[1] - c, in_tri[2] - c, h)) {
                    write_voxel(ivec3(x, y, z), voxel_albedo_of(m, albedo), in_normal, voxel_emission_of(m));
                }
            }
        }
    }
}

void main() {
    // Conservative coverage grows the triangle past its bounding box at acute corners.
    if (any(lessThanEqual(gl_FragCoord.xy, in_bounds.xy)) || any(greaterThanEqual(gl_FragCoord.xy, in_bounds.zw))) {
        discard;
    }
    float scale = voxel.tess.z;
    vec2 xy = floor(gl_FragCoord.xy / scale);
    Material m = materials[push.material];
    vec3 albedo = m.albedo.rgb;
    if (m.tex.x == HAS_TEXTURE) albedo *= texture(albedo_texture, in_uv).rgb;
    if ((voxel.grid.y & VOXEL_FLAG_DEPTH_SPAN) == 0u) {
        float z = plane_depth(gl_FragCoord.xy / scale);
        vec3 at = warp_separable(voxel.warp)
                      ? floor(swizzle(grid_to_voxel_space(unswizzle(vec3(gl_FragCoord.xy / scale, z), in_axis)), in_axis))
                      : vec3(xy, floor(z));
        write_voxel(ivec3(unswizzle(at, in_axis)), voxel_albedo_of(m, albedo), in_normal, voxel_emission_of(m));
        return;
    }
    if (warp_separable(voxel.warp)) {
        // The pixel's box and the plane's depth over it (dominant axis: slopes are <= 1; a
        // triangle too thin for its plane spans its whole depth range).
        vec2 lo = floor(gl_FragCoord.xy) / scale, hi = lo + 1.0 / scale;
        bool planeless = in_depth.zw == vec2(0.0) || any(greaterThan(abs(in_depth.zw), vec2(1.5)));
        float zc = plane_depth(0.5 * (lo + hi)), reach = 0.5 / scale * (abs(in_depth.z) + abs(in_depth.w));
        float z0 = planeless ? in_depth.x : max(zc - reach, in_depth.x);
        float z1 = planeless ? in_depth.y : min(zc + reach, in_depth.y);
        write_warped(vec3(lo, z0), vec3(hi, z1), albedo, m);
        return;
    }
    // The plane's depth over the whole voxel column cell (dominant axis: slopes are <= 1).
    float reach = 0.5 * (abs(in_depth.z) + abs(in_depth.w));
    float zc = plane_depth(xy + 0.5);
    int cap = 3;
    // Along the dominant axis the plane's slopes are at most 1; larger ones (or none) mean the
    // triangle is too thin for its normal to be computed: every layer of its depth range then.
    bool planeless = in_depth.zw == vec2(0.0) || any(greaterThan(abs(in_depth.zw), vec2(1.5)));
    if (planeless && in_depth.y - in_depth.x > 1.0) {
        zc = 0.5 * (in_depth.x + in_depth.y);
        reach = 0.5 * (in_depth.y - in_depth.x) + 1.0;
        cap = 64;
    }
    // Widened by a hair so a face lying exactly on a layer boundary writes both layers it
    // touches (the triangle/box test below keeps only voxels it really meets): a wall thinner
    // than a voxel then has a voxel on each side, and light injected on one side stays there.
    int first = int(floor(max(zc - reach, in_depth.x) - 1e-4));
    int last = min(int(floor(min(zc + reach, in_depth.y) + 1e-4)), first + cap);
    for (int layer = first; layer <= last; layer++) {
        vec3 c = vec3(xy, float(layer)) + 0.5;
        if (triangle_box_overlap(in_tri[0] - c, in_tri[1] - c, in_tri[2] - c, vec3(0.5))) {
            write_voxel(ivec3(unswizzle(vec3(xy, float(layer)), in_axis)), voxel_albedo_of(m, albedo), in_normal, voxel_emission_of(m));
        }
    }
}
