#version 460
// Point voxelizer generating its points on the GPU each frame (Mavridis & Papaioannou 2011,
// §3.1): POINTS_PER_TRIANGLE vertex slots a triangle (gl_VertexIndex / slots is the triangle,
// the remainder the point), no vertex input. Each slot below the triangle's point count
// (density · area / voxel², at least one; triangles needing more were split at load) places its
// point on the triangle by the R2 sequence, rotated per triangle, folded onto the triangle, and
// writes its voxel as points.vert does.
#include "frame.glsl"
#include "material_textures.glsl"
#include "voxel.glsl"

layout(set = 3, binding = 0, std430) readonly buffer Vertices { float vertex_data[]; };
layout(set = 3, binding = 1, std430) readonly buffer Indices { uint index_data[]; };

// A hash of the triangle to a rotation of the sequence (voxel::points::rotation).
float hash01(uint x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return float(x >> 8) / 16777216.0;
}

void main() {
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
    gl_PointSize = 1.0;
    uint t = uint(gl_VertexIndex) / POINTS_PER_TRIANGLE;
    uint k = uint(gl_VertexIndex) % POINTS_PER_TRIANGLE;
    vec3 p[3], n[3];
    vec2 uv[3];
    for (int i = 0; i < 3; i++) {
        uint b = index_data[3u * t + uint(i)] * VERTEX_FLOATS;
        p[i] = vec3(vertex_data[b], vertex_data[b + 1u], vertex_data[b + 2u]);
        n[i] = vec3(vertex_data[b + 3u], vertex_data[b + 4u], vertex_data[b + 5u]);
        uv[i] = vec2(vertex_data[b + 6u], vertex_data[b + 7u]);
    }
    float area = 0.5 * length(cross(p[1] - p[0], p[2] - p[0]));
    if (!(area > 0.0)) return;
    float size = voxel.origin_size.w;
    float count = clamp(ceil(voxel.tess.w * area / (size * size)), 1.0, float(POINTS_PER_TRIANGLE));
    if (float(k) >= count) return;
    const float G = 1.32471795724474602596;
    vec2 s = fract(vec2(hash01(2u * t), hash01(2u * t + 1u)) + vec2(1.0 / G, 1.0 / (G * G)) * float(k));
    if (s.x + s.y > 1.0) s = 1.0 - s;
    vec3 w = vec3(1.0 - s.x - s.y, s.x, s.y);
    vec3 world = w.x * p[0] + w.y * p[1] + w.z * p[2];
    vec3 normal = w.x * n[0] + w.y * n[1] + w.z * n[2];
    vec2 tex = w.x * uv[0] + w.y * uv[1] + w.z * uv[2];
    Material m = materials[push.material];
    vec3 albedo = m.albedo.rgb;
    if (m.tex.x == HAS_TEXTURE) albedo *= textureLod(albedo_texture, tex, 0.0).rgb;
    if (dot(normal, normal) < 1e-12) normal = vec3(0.0, 1.0, 0.0);
    write_voxel(ivec3(floor(to_voxel_space(world))), voxel_albedo_of(m, albedo), normal, voxel_emission_of(m));
}
