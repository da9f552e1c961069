#version 460
// Rasterized voxelizer, fragment stage (Freed 2018 §4.1.1): maps the fragment back to its
// voxel (undoing the dominant-axis swizzle) and writes it with atomic averaging. With
// VOXEL_FLAG_DEPTH_SPAN it considers every depth layer the triangle's plane crosses within
// the pixel (a slanted face can cross into the next layer within one pixel column) and
// writes those whose voxel the triangle really touches (triangle/box test); without, only
// the layer at the pixel centre's depth (the thesis' method). Conservative coverage
// (raster.geom) needs the depth span: its extra fragments are kept only where the test passes.
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
        write_voxel(ivec3(unswizzle(vec3(xy, floor(z)), in_axis)), voxel_albedo_of(m, albedo), in_normal, voxel_emission_of(m));
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
