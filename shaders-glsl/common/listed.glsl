// Compute passes that run either over every voxel of a grid or over a list of occupied voxels
// (occupied.glsl, bound by the includer as OCCUPIED_SET / OCCUPIED_BINDING).
#ifndef VCT_LISTED_GLSL
#define VCT_LISTED_GLSL
#include "config.h"
#include "occupied.glsl"

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
