#version 460
// Radiance filtering (Freed 2018 §4.4): one dispatch per mip level, each voxel the average of
// its 8 children in the level below (premultiplied radiance and opacity alike).
#include "config.h"

layout(local_size_x = WORKGROUP_3D, local_size_y = WORKGROUP_3D, local_size_z = WORKGROUP_3D) in;
layout(set = 0, binding = 0, rgba16f) uniform readonly image3D src;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image3D dst;

void main() {
    ivec3 v = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(v, imageSize(dst)))) return;
    vec4 sum = vec4(0.0);
    for (int i = 0; i < 8; i++) {
        sum += imageLoad(src, 2 * v + ivec3(i & 1, (i >> 1) & 1, i >> 2));
    }
    imageStore(dst, v, sum * 0.125);
}
