#version 460
// Deferred variant, shading pass: one thread per pixel reads the G-buffer, rebuilds the world
// position from the camera distance along the pixel's ray and runs the same `shade_surface`
// as the forward path. With GI_SCALE s > 1 the diffuse cones run at one pixel in s² (PASS
// TRACE: the centre pixel of each s x s block, into `diffuse_low`), and the shading pass
// (PASS SHADE) upsamples them edge-aware (joint bilateral: of the four nearest traced pixels,
// only those on the pixel's own surface count, by their normal and their distance from its
// tangent plane); where none does (a silhouette, a thin object) the nearest stands in.
// The specular cone stays at full resolution.
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

layout(set = 2, binding = 9, rgba16f) uniform image2D diffuse_low;

#include "shading.glsl"

layout(constant_id = 3) const uint GI_SCALE = 1;
layout(constant_id = 4) const uint PASS = 0;
const uint PASS_SHADE = 0;
const uint PASS_TRACE = 1;

// The G-buffer at `px`: false for background; else the world position and shading normal.
bool surface_at(ivec2 px, out vec3 world, out vec3 n) {
    vec4 nd = imageLoad(gbuffer_normal, px);
    if (nd.w <= 0.0) return false;
    vec2 ndc = (vec2(px) + 0.5) / frame.viewport.xy * 2.0 - 1.0;
    vec4 far = frame.inv_view_proj * vec4(ndc, 1.0, 1.0);
    vec3 dir = normalize(far.xyz / far.w - frame.camera_pos.xyz);
    world = frame.camera_pos.xyz + dir * nd.w;
    n = facing_normal(nd.xyz, world);
    return true;
}

// The full-resolution pixel block `q` of the reduced grid traces for.
ivec2 traced_pixel(ivec2 q) {
    return min(q * int(GI_SCALE) + int(GI_SCALE) / 2, ivec2(frame.viewport.xy) - 1);
}

// The diffuse gather at `world` (normal `n`) upsampled from the four traced pixels around
// `px`. A traced pixel counts when its surface continues this one: its normal within ~25
// degrees and its position within half a voxel of this pixel's tangent plane. Where none does
// (a silhouette, an object thinner than the traced grid) the one nearest this pixel's tangent
// plane stands in: tracing here instead would cost every pixel on a CPU driver, which runs a
// branch for all lanes when any lane takes it.
vec4 upsampled_gather(ivec2 px, vec3 world, vec3 n) {
    vec2 f = (vec2(px) + 0.5) / float(GI_SCALE) - 0.5;
    ivec2 base = ivec2(floor(f));
    vec2 t = f - vec2(base);
    ivec2 size = imageSize(diffuse_low);
    float plane = 0.5 * frame.voxel_origin.w;
    vec4 sum = vec4(0.0), nearest = vec4(0.0);
    float total = 0.0, closest = 1e30;
    for (int i = 0; i < 4; i++) {
        ivec2 o = ivec2(i & 1, i >> 1);
        ivec2 q = clamp(base + o, ivec2(0), size - 1);
        vec3 wq, nq;
        if (!surface_at(traced_pixel(q), wq, nq)) continue;
        vec4 g = imageLoad(diffuse_low, q);
        float d = abs(dot(wq - world, n)) + plane * max(0.9 - dot(nq, n), 0.0) * 10.0;
        if (d < closest) {
            closest = d;
            nearest = g;
        }
        if (dot(nq, n) < 0.9 || abs(dot(wq - world, n)) > plane) continue;
        float w = (o.x == 1 ? t.x : 1.0 - t.x) * (o.y == 1 ? t.y : 1.0 - t.y) + 1e-4;
        sum += w * g;
        total += w;
    }
    return total > 0.0 ? sum / total : nearest;
}

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (PASS == PASS_TRACE) {
        if (any(greaterThanEqual(px, imageSize(diffuse_low)))) return;
        vec3 world, n;
        vec4 g = vec4(0.0);
        if (frame.view.z > 0.5 && surface_at(traced_pixel(px), world, n)) {
            g = gather_diffuse(world_to_uvw(world), n, frame_cone_params());
        }
        imageStore(diffuse_low, px, g);
        return;
    }
    if (any(greaterThanEqual(px, imageSize(hdr)))) return;
    vec3 world, n;
    if (!surface_at(px, world, n)) {
        imageStore(hdr, px, vec4(0.0));
        return;
    }
    vec4 a = imageLoad(gbuffer_albedo, px);
    Material m = materials[uint(a.w + 0.5)];
    bool given = GI_SCALE > 1u && frame.view.z > 0.5;
    vec4 gathered = given ? upsampled_gather(px, world, n) : vec4(0.0);
    imageStore(hdr, px, vec4(shade_surface_given(m, a.rgb, n, world, given, gathered), 1.0));
}
