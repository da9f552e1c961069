#version 460
// Voxelization vertex stage (Freed 2018 §4.1.1: "the only operation performed is
// transforming the object to world space"): passes world position, normal and UV on to the
// tessellation or geometry stage, which project.

layout(location = 0) in vec3 in_pos;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec2 out_uv;

void main() {
    out_world = in_pos;
    out_normal = in_normal;
    out_uv = in_uv;
    gl_Position = vec4(in_pos, 1.0);
}
