#version 460
// Voxel debug view: flat-shaded cube faces with darkened edges (so single voxels read),
// written as display colour.

layout(location = 0) in vec3 in_color;
layout(location = 1) in vec2 in_face_uv;
layout(location = 0) out vec4 out_color;

void main() {
    vec2 d = min(in_face_uv, 1.0 - in_face_uv);
    float edge = min(d.x, d.y) < 0.07 ? 0.55 : 1.0;
    out_color = vec4(in_color * edge, 1.0);
}
