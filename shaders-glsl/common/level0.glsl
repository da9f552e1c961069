// Level 0 of the radiance volume, filtered trilinearly (render::radiance). It is stored as the
// per-voxel textures are (voxel::bricks): dense, the sampler filters it; in the brick pool,
// neighbouring voxels lie in other bricks' slots, so the eight taps are fetched through the
// page table and weighted here, with zeros outside the grid as the sampler's border gives.
// Cones read level 0 only below level 1 (common/cone.glsl), the pool's price: on lavapipe the
// shading took 4-8% longer than with the dense sampler (docs/benchmarks.md). The includer
// binds the page table (BRICKS_SET, BRICKS_BINDING) and includes frame.glsl.
#ifndef VCT_LEVEL0_GLSL
#define VCT_LEVEL0_GLSL
#include "bricks.glsl"

vec4 level0_sample(sampler3D level0, vec3 pos) {
    if (!SPARSE) return textureLod(level0, pos, 0.0);
    ivec3 dims = ivec3(frame.voxel_dims.xyz);
    vec3 u = pos * vec3(dims) - 0.5;
    ivec3 first = ivec3(floor(u));
    vec3 f = u - vec3(first);
    vec4 sum = vec4(0.0);
    for (int i = 0; i < 8; i++) {
        ivec3 o = ivec3(i & 1, (i >> 1) & 1, i >> 2);
        ivec3 c = first + o;
        if (any(lessThan(c, ivec3(0))) || any(greaterThanEqual(c, dims))) continue;
        vec3 w = mix(1.0 - f, f, vec3(o));
        sum += (w.x * w.y * w.z) * texelFetch(level0, stored_at(c), 0);
    }
    return sum;
}

#endif
