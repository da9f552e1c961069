#version 460
// Point voxelizer's refinement (Mavridis & Papaioannou 2011, §3.2): the scene seen from the
// camera in the voxel parameters, for a depth pass and then the pass that writes the visible
// surface into the volume (one shader for both, so their depths match exactly).
#include "frame.glsl"
#include "voxel.glsl"

layout(location = 0) in vec3 in_pos;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec2 out_uv;

invariant gl_Position;

void main() {
    out_world = in_pos;
    out_normal = in_normal;
    out_uv = in_uv;
    gl_Position = voxel.camera * vec4(in_pos, 1.0);
}
