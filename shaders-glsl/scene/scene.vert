#version 460
// Transforms scene vertices. Spec constant VIEW: 0 camera (depth prepass and shading: one
// shader, so their depths match exactly), 1 light (shadow-map layer FACE).
#include "frame.glsl"

layout(constant_id = 0) const uint VIEW = 0;
layout(constant_id = 1) const uint FACE = 0;

layout(location = 0) in vec3 in_pos;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in vec4 in_tangent;

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec2 out_uv;
layout(location = 3) out vec4 out_tangent;

invariant gl_Position;

void main() {
    out_world = in_pos;
    out_normal = in_normal;
    out_uv = in_uv;
    out_tangent = in_tangent;
    mat4 m = VIEW == 1 ? frame.light_layers[FACE] : frame.view_proj;
    gl_Position = m * vec4(in_pos, 1.0);
}
