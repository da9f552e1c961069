#version 460
// Deferred variant, geometry pass: writes what `shade_surface` needs per pixel — albedo with
// textures applied and the material index; the shading normal and the distance from the
// camera (the compute pass rebuilds the position along the pixel's ray from it).
#include "frame.glsl"
#include "surface.glsl"

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in vec4 in_tangent;

layout(location = 0) out vec4 out_albedo_material;
layout(location = 1) out vec4 out_normal;

void main() {
    Material m = materials[push.material];
    vec3 albedo, n;
    surface_inputs(m, in_normal, in_uv, in_tangent, albedo, n);
    out_albedo_material = vec4(albedo, float(push.material));
    out_normal = vec4(n, distance(in_world, frame.camera_pos.xyz));
}
