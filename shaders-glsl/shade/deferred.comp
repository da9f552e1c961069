#version 460
// Deferred variant, shading pass: one thread per pixel reads the G-buffer, rebuilds the world
// position from the camera distance along the pixel's ray and runs the same `shade_surface`
// as the forward path.
#include "frame.glsl"

layout(local_size_x = WORKGROUP_2D, local_size_y = WORKGROUP_2D) in;
layout(set = 2, binding = 0) uniform sampler2DArrayShadow shadow_map;
layout(set = 2, binding = 1) uniform sampler3D radiance_volume;
layout(set = 2, binding = 2, rgba16f) uniform readonly image2D gbuffer_albedo;
layout(set = 2, binding = 3, rgba32f) uniform readonly image2D gbuffer_normal;
layout(set = 2, binding = 4, rgba32f) uniform writeonly image2D hdr;
layout(set = 2, binding = 5) uniform sampler3D radiance_aniso;
layout(set = 2, binding = 6) uniform sampler3D radiance_moment;
layout(set = 2, binding = 7) uniform sampler3D radiance_chain;
#define BRICKS_SET 2
#define BRICKS_BINDING 8
#include "level0.glsl"

#include "shading.glsl"

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(px, imageSize(hdr)))) return;
    vec4 nd = imageLoad(gbuffer_normal, px);
    if (nd.w <= 0.0) { imageStore(hdr, px, vec4(0.0)); return; }
    vec2 ndc = (vec2(px) + 0.5) / frame.viewport.xy * 2.0 - 1.0;
    vec4 far = frame.inv_view_proj * vec4(ndc, 1.0, 1.0);
    vec3 dir = normalize(far.xyz / far.w - frame.camera_pos.xyz);
    vec4 a = imageLoad(gbuffer_albedo, px);
    Material m = materials[uint(a.w + 0.5)];
    imageStore(hdr, px, vec4(shade_surface(m, a.rgb, nd.xyz, frame.camera_pos.xyz + dir * nd.w), 1.0));
}
