#version 460
// The occupied texels of the next mip level (render::occupancy): each listed texel of level l
// marks its parent at level l + 1 in a bit set, and the invocation that sets the bit appends
// the parent to the next level's list, so every occupied parent is listed once. The mip
// filters then run over these lists instead of every texel of each level.
#include "config.h"
#define OCCUPIED_SET 0
#define OCCUPIED_BINDING 0
#include "occupied.glsl"

layout(local_size_x = WORKGROUP_1D) in;
layout(set = 0, binding = 1, std430) buffer Parents {
    uint count;
    uint pad0, pad1, pad2;
    uint voxels[];
} parents;
layout(set = 0, binding = 2, std430) buffer Marks { uint bits[]; } marks;
// The parent level's extent.
layout(push_constant) uniform Push { uvec4 size; } push;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= occupied.count) return;
    ivec3 p = unpack_voxel(occupied.voxels[i]) >> 1;
    uint index = uint(p.x) + push.size.x * (uint(p.y) + push.size.y * uint(p.z));
    uint bit = 1u << (index & 31u);
    if ((atomicOr(marks.bits[index >> 5], bit) & bit) == 0u) parents.voxels[atomicAdd(parents.count, 1u)] = pack_voxel(p);
}
