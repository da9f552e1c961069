// Voxel grid parameters (set 2, mirrored by `voxel::VoxelParams`) and the atomic running
// average that writes a voxel: packed RGBA8 in an R32UI image, the sample count in the alpha
// byte, updated with a compare-and-swap loop (Crassin & Green, OpenGL Insights ch. 22).
#ifndef VCT_VOXEL_GLSL
#define VCT_VOXEL_GLSL
#include "config.h"
#include "warp.glsl"

layout(set = 2, binding = 0) uniform VoxelParams {
    vec4 origin_size;   // xyz: grid origin (world); w: voxel edge length
    uvec4 grid;         // x: the longest axis N (the raster framebuffer is N x N); y: flags (VOXEL_FLAG_*);
                        // z: the slab the grid is written to (a clipmap level's first texel along z)
    vec4 tess;          // x: tessellation level scale; y: max tessellation level; z: raster viewport scale
    uvec4 dims;         // xyz: voxels along each axis
    mat4 camera;        // world to clip: the view the point voxelizer's refinement sees
    vec4 warp;          // the grid's warp (common/warp.glsl): xyz centre, w end slope (1: none)
    mat4 warp_proj;     // a perspective warp's grid fraction to texture fraction (homogeneous)
} voxel;

// Whether voxel `coord` lies inside the grid.
bool in_grid(ivec3 coord) {
    return all(greaterThanEqual(coord, ivec3(0))) && all(lessThan(coord, ivec3(voxel.dims.xyz)));
}

layout(set = 2, binding = 1, r32ui) uniform coherent volatile uimage3D voxel_albedo;
layout(set = 2, binding = 2, r32ui) uniform coherent volatile uimage3D voxel_normal;
// Emitted radiance, RGB9E5 (atomic max: exact for a voxel with one emissive material).
layout(set = 2, binding = 3, r32ui) uniform coherent volatile uimage3D voxel_emission;
// The list of occupied voxels: a voxel's first write appends it.
#define OCCUPIED_SET 2
#define OCCUPIED_BINDING 4
#include "occupied.glsl"
// Sparse storage: the page table, which the first write into a brick claims a slot of.
#define BRICKS_SET 2
#define BRICKS_BINDING 5
#define BRICKS_CLAIM
#include "bricks.glsl"

// World position to unwarped grid coordinates (voxels of the even grid; the voxelizers
// rasterize and tessellate here, where triangles stay flat).
vec3 to_grid_space(vec3 world) {
    return (world - voxel.origin_size.xyz) / voxel.origin_size.w;
}

// Grid coordinates to texel coordinates (texel v spans [v, v + 1)), through the warp if any.
vec3 grid_to_voxel_space(vec3 g) {
    if (!warp_on(voxel.warp)) return g;
    vec3 n = vec3(voxel.dims.xyz);
    return warp_to_texture(g / n, voxel.warp, voxel.warp_proj) * n;
}

// World position to texel coordinates.
vec3 to_voxel_space(vec3 world) {
    return grid_to_voxel_space(to_grid_space(world));
}

// Texel `v`'s box in grid coordinates: its centre and half size (a function-warped texel is a
// box of its own size, each axis being warped on its own; not for the perspective warp, whose
// voxelizers work among the texels).
void texel_box(ivec3 v, out vec3 centre, out vec3 half_size) {
    if (!warp_on(voxel.warp)) {
        centre = vec3(v) + 0.5;
        half_size = vec3(0.5);
        return;
    }
    vec3 n = vec3(voxel.dims.xyz);
    vec3 lo = warp_inverse(vec3(v) / n, voxel.warp) * n, hi = warp_inverse(vec3(v + 1) / n, voxel.warp) * n;
    centre = 0.5 * (lo + hi);
    half_size = 0.5 * (hi - lo);
}

uint pack_rgba8(vec4 v) {
    uvec4 u = uvec4(clamp(round(v), 0.0, 255.0));
    return u.x | (u.y << 8) | (u.z << 16) | (u.w << 24);
}

vec4 unpack_rgba8(uint p) {
    return vec4(float(p & 0xffu), float((p >> 8) & 0xffu), float((p >> 16) & 0xffu), float(p >> 24));
}

// GLSL cannot pass images to functions: pick the texture by index.
uint voxel_cas(uint which, ivec3 coord, uint expected, uint desired) {
    return which == 0u ? imageAtomicCompSwap(voxel_albedo, coord, expected, desired)
                       : imageAtomicCompSwap(voxel_normal, coord, expected, desired);
}

// Folds `value` (rgb in [0,1]) into the running average stored at `coord` of texture `which`
// (0 albedo, 1 normal). Returns whether this was the voxel's first write (the swap from empty:
// exactly one writer of a voxel sees it).
bool atomic_average(uint which, ivec3 coord, vec3 value) {
    vec4 add = vec4(value * 255.0, 1.0);
    uint desired = pack_rgba8(add);
    uint expected = 0u;
    for (int i = 0; i < CAS_MAX_ITERATIONS; i++) {
        uint found = voxel_cas(which, coord, expected, desired);
        if (found == expected) return i == 0;
        expected = found;
        vec4 avg = unpack_rgba8(found);
        float n = avg.w;
        if (n >= 255.0) break;  // count saturated: the average has converged
        vec3 sum = avg.rgb * n + add.rgb;
        desired = pack_rgba8(vec4(sum / (n + 1.0), n + 1.0));
    }
    return false;
}

#include "rgb9e5.glsl"

// Voxel `v` of the grid being written (a clipmap level's, in_grid) as a texel of the volume: in
// its slab of the stack.
ivec3 in_slab(ivec3 v) {
    return v + ivec3(0, 0, int(voxel.grid.z));
}

// Writes one voxel sample (albedo, unit normal, emission) if `coord` lies inside the grid (and,
// with sparse storage, its brick has or gets a slot).
void write_voxel(ivec3 coord, vec3 albedo, vec3 normal, vec3 emission) {
    ivec3 t;
    if (!in_grid(coord)) return;
    coord = in_slab(coord);
    if (!claim_brick(coord, t)) return;
    if (atomic_average(0u, t, clamp(albedo, 0.0, 1.0))) occupied.voxels[atomicAdd(occupied.count, 1u)] = pack_voxel(coord);
    atomic_average(1u, t, normalize(normal) * 0.5 + 0.5);
    if (max(emission.r, max(emission.g, emission.b)) > 0.0) imageAtomicMax(voxel_emission, t, encode_rgb9e5(emission));
}

#endif
