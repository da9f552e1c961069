#version 460
// Tone mapping c/(c+1) then gamma 2.2 (Freed 2018, Algorithm 3), linear HDR -> RGBA8.
// Views that are already in [0, 1] (ambient occlusion, voxel albedo) skip the c/(c+1) step.
#include "config.h"

layout(local_size_x = WORKGROUP_2D, local_size_y = WORKGROUP_2D) in;
layout(set = 0, binding = 0, rgba32f) uniform readonly image2D hdr;
layout(set = 0, binding = 1, rgba8) uniform writeonly image2D ldr;
layout(push_constant) uniform Push { uint raw; } push;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(hdr)))) return;
    vec3 c = max(imageLoad(hdr, p).rgb, vec3(0.0));
    if (push.raw == 0u) c = c / (c + 1.0);
    c = pow(c, vec3(1.0 / 2.2));
    imageStore(ldr, p, vec4(c, 1.0));
}
