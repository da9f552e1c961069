#version 460
// Temporal filtering (Freed 2018 §4.7.2): the radiance volume's level 0 becomes
// mix(previous, injected, factor); factor 1 (the default) keeps only this frame.
#include "frame.glsl"

layout(local_size_x = WORKGROUP_3D, local_size_y = WORKGROUP_3D, local_size_z = WORKGROUP_3D) in;
layout(set = 1, binding = 0, rgba16f) uniform readonly image3D injected;
layout(set = 1, binding = 1, rgba16f) uniform image3D radiance;

void main() {
    ivec3 v = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(v, imageSize(radiance)))) return;
    vec4 now = imageLoad(injected, v);
    float factor = frame.voxel_grid.w > 0.5 ? 1.0 : frame.voxel_grid.z;
    if (factor < 1.0) now = mix(imageLoad(radiance, v), now, factor);
    imageStore(radiance, v, now);
}
