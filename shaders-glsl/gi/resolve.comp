#version 460
// Radiance injection, step 1 (Freed 2018 §4.3, the "transfer" of occlusion): one thread per
// voxel starts the injection target with the voxel's emitted radiance and opacity 1 for every
// occupied voxel, 0 elsewhere, and appends every occupied voxel to the compact list of occupied
// voxels. Direct light is added by inject.comp.
#include "config.h"
#include "rgb9e5.glsl"
#define OCCUPIED_SET 0
#define OCCUPIED_BINDING 3
#include "occupied.glsl"

layout(local_size_x = WORKGROUP_3D, local_size_y = WORKGROUP_3D, local_size_z = WORKGROUP_3D) in;
layout(set = 0, binding = 0, r32ui) uniform readonly uimage3D voxel_albedo;
layout(set = 0, binding = 1, r32ui) uniform readonly uimage3D voxel_emission;
layout(set = 0, binding = 2, rgba16f) uniform writeonly image3D target;

void main() {
    ivec3 v = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(v, imageSize(target)))) return;
    bool full = (imageLoad(voxel_albedo, v).r >> 24) != 0u;
    vec3 emission = decode_rgb9e5(imageLoad(voxel_emission, v).r);
    imageStore(target, v, full ? vec4(emission, 1.0) : vec4(0.0));
    if (full) occupied.voxels[atomicAdd(occupied.count, 1u)] = pack_voxel(v);
}
