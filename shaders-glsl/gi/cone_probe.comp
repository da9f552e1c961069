#version 460
// Test probe: traces one cone per invocation through a given (cubic) radiance volume with the
// renderer's own trace_cone (common/cone.glsl), so tests can compare it with a CPU model.
#include "config.h"
#include "cone.glsl"

layout(local_size_x = WORKGROUP_1D) in;

struct Probe {
    vec4 uvw_aperture;  // xyz: start (texture space); w: tangent of the half aperture
    vec4 normal;
    vec4 dir;
};

layout(set = 0, binding = 0) uniform sampler3D volume;
layout(set = 0, binding = 1, std430) readonly buffer Probes { Probe probes[]; };
layout(set = 0, binding = 2, std430) writeonly buffer Results { vec4 results[]; };
layout(push_constant) uniform Push {
    int steps; float bias; float start; float lod_offset; float resolution; float step; uint flags; uint count;
    float max_level;
} push;

// The probe's volume holds every level in one texture, filtered by the sampler.
vec4 level0_sample(sampler3D level0, vec3 pos) {
    return textureLod(level0, pos, 0.0);
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= push.count) return;
    Probe p = probes[i];
    ConeParams params =
        ConeParams(push.steps, push.bias, push.start, push.lod_offset, vec3(push.resolution), push.max_level, push.step,
                   push.flags, 0.5, vec3(0.0), 1.0, vec4(0.5, 0.5, 0.5, 1.0), 1.0, 0, mat4(1.0));  // isotropic, unwarped
    results[i] = trace_cone(volume, p.uvw_aperture.xyz, p.normal.xyz, p.dir.xyz, p.uvw_aperture.w, params);
}
