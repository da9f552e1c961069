#version 460
// Radiance filtering (Freed 2018 §4.4): one dispatch per mip level, each voxel the average of
// its 8 children in the level below (premultiplied radiance and opacity alike). With LISTED, one
// invocation per occupied texel of the level (render::occupancy's parent lists); the rest of
// the level is cleared, and an average of empty children is zero.
#include "config.h"
#define OCCUPIED_SET 0
#define OCCUPIED_BINDING 2
#include "listed.glsl"

layout(local_size_x = WORKGROUP_3D, local_size_y = WORKGROUP_3D, local_size_z = WORKGROUP_3D) in;
layout(set = 0, binding = 0, rgba16f) uniform readonly image3D src;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image3D dst;
#define BRICKS_SET 0
#define BRICKS_BINDING 3
#include "bricks.glsl"
layout(constant_id = 0) const bool LISTED = false;
// base: src is level 0, stored as the per-voxel targets (in the brick pool with sparse storage:
// a parent's eight children are one brick, so the table is read once).
layout(push_constant) uniform Push { uint base; } push;

void main() {
    ivec3 v;
    if (!listed_or_dense(LISTED, imageSize(dst), v)) return;
    vec4 sum = vec4(0.0);
    ivec3 first = push.base != 0u ? stored_at(2 * v) : 2 * v;
    for (int i = 0; i < 8; i++) {
        sum += imageLoad(src, first + ivec3(i & 1, (i >> 1) & 1, i >> 2));
    }
    imageStore(dst, v, sum * 0.125);
}
