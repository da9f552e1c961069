// The compact list of occupied voxels (render::occupancy; OPEngine's sparse voxel list): a count
// and the packed coordinates (x | y << 10 | z << 20) of every occupied voxel, appended by the
// resolve pass, so that passes over voxels run one invocation per occupied voxel (dispatched
// indirectly) instead of one per voxel of the grid.
#ifndef VCT_OCCUPIED_GLSL
#define VCT_OCCUPIED_GLSL
#include "config.h"

#ifndef OCCUPIED_SET
#define OCCUPIED_SET 1
#endif

layout(set = OCCUPIED_SET, binding = OCCUPIED_BINDING, std430) buffer Occupied {
    uint count;
    uint pad0, pad1, pad2;
    uint voxels[];
} occupied;

uint pack_voxel(ivec3 v) {
    return uint(v.x) | (uint(v.y) << 10) | (uint(v.z) << 20);
}

ivec3 unpack_voxel(uint p) {
    return ivec3(p & 1023u, (p >> 10) & 1023u, (p >> 20) & 1023u);
}

// A pass over a grid, one invocation per voxel (dense: its global id), or one per listed voxel
// in the indirect dispatch the list's arguments give (WORKGROUP_1D invocations a group, however
// the group is shaped): the voxel this invocation works on, or false when it has none. (The
// group size is the constant, not gl_WorkGroupSize: this file comes before the includer's
// local_size declaration, where glslang still reads gl_WorkGroupSize as 1.)
bool listed_or_dense(bool listed, ivec3 size, out ivec3 v) {
    if (!listed) {
        v = ivec3(gl_GlobalInvocationID);
        return all(lessThan(v, size));
    }
    uint i = gl_WorkGroupID.x * uint(WORKGROUP_1D) + gl_LocalInvocationIndex;
    if (i >= occupied.count) return false;
    v = unpack_voxel(occupied.voxels[i]);
    return true;
}

#endif
