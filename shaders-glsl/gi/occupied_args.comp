#version 460
// The indirect dispatch arguments of the passes over occupied voxels: one workgroup of
// WORKGROUP_1D invocations per WORKGROUP_1D voxels of the list (common/occupied.glsl).
#include "config.h"
#define OCCUPIED_SET 0
#define OCCUPIED_BINDING 0
#include "occupied.glsl"

layout(local_size_x = 1) in;
layout(set = 0, binding = 1, std430) writeonly buffer Args { uint groups[3]; } args;

void main() {
    args.groups[0] = (occupied.count + WORKGROUP_1D - 1) / WORKGROUP_1D;
    args.groups[1] = 1;
    args.groups[2] = 1;
}
