// Level 0 of the radiance volume, filtered trilinearly (render::radiance). It is stored as the
// per-voxel textures are (voxel::bricks): dense, the sampler filters it; in the brick pool,
// neighbouring voxels lie in other bricks' slots, so the eight taps are fetched through the
// page table and weighted here, with zeros outside the grid as the sampler's border gives.
// Cones read level 0 only below level 1 (common/cone.glsl), the pool's price: on lavapipe the
// shading takes 4-8% longer than with the dense sampler (docs/design/storage.md). The includer
// binds the page table (BRICKS_SET, BRICKS_BINDING) and includes frame.glsl.
#ifndef VCT_LEVEL0_GLSL
#define VCT_LEVEL0_GLSL
#include "bricks.glsl"

vec4 level0_sample(sampler3D level0, vec3 pos) {
    if (!SPARSE) return textureLod(level0, pos, 0.0);
    ivec3 dims = ivec3(frame.voxel_dims.xyz);
    vec3 u = pos * vec3(dims) - 0.5;
    ivec3 c0 = ivec3(floor(u));
    vec3 f = u - vec3(c0);
    // Per axis, the two taps' bricks and whether they lie inside the grid; a tap outside reads
    // the empty slot 0, as the sampler's zero border would give.
    ivec3 c1 = c0 + 1;
    bvec3 in0 = greaterThanEqual(c0, ivec3(0)), in1 = lessThan(c1, dims);
    uvec3 b0 = uvec3(max(c0, 0)) >> BRICK_SHIFT, b1 = uvec3(min(c1, dims - 1)) >> BRICK_SHIFT;
    uint cx = bricks.count_x, cy = bricks.count_y;
    uint mask_x = (1u << bricks.pool_x) - 1u, mask_y = (1u << bricks.pool_y) - 1u, shift_z = bricks.pool_x + bricks.pool_y;
    vec4 sum = vec4(0.0);
    for (int k = 0; k < 8; k++) {
        bvec3 o = bvec3((k & 1) != 0, (k & 2) != 0, (k & 4) != 0);
        uvec3 b = mix(b0, b1, o);
        bool inside = all(mix(in0, in1, o));
        uint s = inside ? bricks.page[(b.z * cy + b.y) * cx + b.x] : 0u;
        s = s >= BRICK_REFUSED ? 0u : s;
        ivec3 c = mix(c0, c1, o);
        ivec3 at = ivec3(uvec3(s & mask_x, (s >> bricks.pool_x) & mask_y, s >> shift_z) << BRICK_SHIFT) + (c & (BRICK_SIZE - 1));
        vec3 w = mix(1.0 - f, f, vec3(o));
        sum += (w.x * w.y * w.z) * texelFetch(level0, at, 0);
    }
    return sum;
}

#endif
