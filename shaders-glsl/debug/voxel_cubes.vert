#version 460
// Voxel debug view (Freed 2018 Fig. 4.1/4.4): one instanced cube per occupied voxel, its
// corners generated from gl_VertexIndex, coloured by the voxel's averaged albedo.

layout(push_constant) uniform CubePush {
    mat4 view_proj;
    vec4 origin_size;  // xyz: grid origin; w: voxel size
    vec4 light_dir;    // xyz: unit direction towards the light
} pc;

layout(location = 0) in uint in_coord;  // x | y << 10 | z << 20
layout(location = 1) in uint in_color;  // packed RGBA8

layout(location = 0) out vec3 out_color;
layout(location = 1) out vec2 out_face_uv;

const vec3 FACE_NORMALS[6] = vec3[](vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1));

void main() {
    int face = gl_VertexIndex / 6;
    int corner = gl_VertexIndex % 6;
    // Two triangles per face: (0,0) (1,0) (1,1) / (0,0) (1,1) (0,1) in the face's (u, v).
    vec2 uv = vec2[](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1), vec2(0, 1))[corner];
    vec3 n = FACE_NORMALS[face];
    int axis = face / 2;
    vec3 p = vec3(0.0);
    p[axis] = (face % 2 == 0) ? 1.0 : 0.0;
    p[(axis + 1) % 3] = uv.x;
    p[(axis + 2) % 3] = uv.y;
    uvec3 c = uvec3(in_coord & 1023u, (in_coord >> 10) & 1023u, in_coord >> 20);
    vec3 world = pc.origin_size.xyz + (vec3(c) + p) * pc.origin_size.w;
    gl_Position = pc.view_proj * vec4(world, 1.0);
    vec3 albedo = vec3(float(in_color & 255u), float((in_color >> 8) & 255u), float((in_color >> 16) & 255u)) / 255.0;
    out_color = albedo * (0.3 + 0.7 * max(dot(n, pc.light_dir.xyz), 0.0));
    out_face_uv = uv;
}
