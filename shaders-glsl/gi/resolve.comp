#version 460
// Radiance injection, step 1 (Freed 2018 §4.3, the "transfer" of occlusion): starts the
// injection target with each voxel's emitted radiance and opacity 1 for every occupied voxel, 0
// elsewhere: one invocation per voxel the voxelizers listed (the target cleared first), or per
// voxel of the grid. Direct light is added by inject.comp.
#include "config.h"
#include "rgb9e5.glsl"
#define OCCUPIED_SET 0
#define OCCUPIED_BINDING 3
#include "listed.glsl"

layout(local_size_x = WORKGROUP_3D, local_size_y = WORKGROUP_3D, local_size_z = WORKGROUP_3D) in;
layout(set = 0, binding = 0, r32ui) uniform readonly uimage3D voxel_albedo;
layout(set = 0, binding = 1, r32ui) uniform readonly uimage3D voxel_emission;
layout(set = 0, binding = 2, rgba16f) uniform writeonly image3D target;
#define BRICKS_SET 0
#define BRICKS_BINDING 4
#include "bricks.glsl"

// Over the occupied voxels the voxelizers listed (the rest of the target cleared), or every voxel.
layout(constant_id = 0) const bool LISTED = false;

void main() {
    ivec3 v;
    if (!listed_or_dense(LISTED, stored_grid(imageSize(target)), v)) return;
    // Sparse storage: a voxel outside every brick is the empty slot, which this leaves zero.
    v = stored_at(v);
    bool full = (imageLoad(voxel_albedo, v).r >> 24) != 0u;
    vec3 emission = decode_rgb9e5(imageLoad(voxel_emission, v).r);
    imageStore(target, v, full ? vec4(emission, 1.0) : vec4(0.0));
}
