#version 460
// Anisotropic radiance filtering (Crassin et al. 2011 §5; the thesis' future work): six mip
// chains, one per axis direction. A parent voxel seen along +X composites its two children
// front to back along X (premultiplied: c = c_front + (1 - a_front) c_back), then averages
// the four columns. A wall one voxel thick thus stays opaque when seen face-on, where the
// isotropic 8-child average halves its opacity per level (light leaks and dims).
#include "config.h"

layout(local_size_x = WORKGROUP_3D, local_size_y = WORKGROUP_3D, local_size_z = WORKGROUP_3D) in;
layout(set = 0, binding = 0, rgba16f) uniform readonly image3D src;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image3D dst;
layout(push_constant) uniform Push { uint direction; } push;  // 0 +X, 1 -X, 2 +Y, 3 -Y, 4 +Z, 5 -Z

void main() {
    ivec3 v = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(v, imageSize(dst)))) return;
    int axis = int(push.direction / 2u);
    bool positive = (push.direction & 1u) == 0u;
    ivec3 step = ivec3(0);
    step[axis] = 1;
    ivec3 u = ivec3(0), w = ivec3(0);
    u[(axis + 1) % 3] = 1;
    w[(axis + 2) % 3] = 1;
    vec4 sum = vec4(0.0);
    for (int i = 0; i < 4; i++) {
        ivec3 base = 2 * v + u * (i & 1) + w * (i >> 1);
        vec4 near = imageLoad(src, positive ? base : base + step);
        vec4 far = imageLoad(src, positive ? base + step : base);
        sum += near + (1.0 - near.a) * far;
    }
    imageStore(dst, v, sum * 0.25);
}
