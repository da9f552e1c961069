#version 460
// Debug views of the voxel volumes: one thread per pixel marches the camera ray through the
// grid (half-voxel steps at the chosen level) and shows the first voxel it meets — the
// averaged albedo (VIEW_VOXELS) or the filtered radiance of a mip level (VIEW_RADIANCE).
#include "frame.glsl"

layout(local_size_x = WORKGROUP_2D, local_size_y = WORKGROUP_2D) in;
layout(set = 1, binding = 0, r32ui) uniform readonly uimage3D voxel_albedo;
layout(set = 1, binding = 1) uniform sampler3D radiance_volume;
layout(set = 1, binding = 2, rgba32f) uniform writeonly image2D hdr;
#define BRICKS_SET 1
#define BRICKS_BINDING 3
#include "bricks.glsl"
layout(set = 1, binding = 4) uniform sampler3D radiance_chain;
#include "level0.glsl"

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(px, imageSize(hdr)))) return;
    vec2 ndc = (vec2(px) + 0.5) / frame.viewport.xy * 2.0 - 1.0;
    vec4 near = frame.inv_view_proj * vec4(ndc, 0.0, 1.0);
    vec4 far = frame.inv_view_proj * vec4(ndc, 1.0, 1.0);
    // The ray is straight in the unwarped grid; each sample is warped to its texel.
    vec3 o = world_to_march(near.xyz / near.w), e = world_to_march(far.xyz / far.w);
    vec3 d = normalize(e - o);
    // Clip the ray to the unit cube (a clipmap's coarsest level's box).
    vec3 lo = vec3(0.0), hi = vec3(1.0);
    if (clip_on()) {
        vec4 l = frame.clip_levels[clip_count() - 1];
        lo = l.xyz / frame.clip.y;
        hi = lo + l.w;
    }
    vec3 inv = 1.0 / d;
    vec3 t0 = (lo - o) * inv, t1 = (hi - o) * inv;
    float tmin = max(max(min(t0.x, t1.x), min(t0.y, t1.y)), max(min(t0.z, t1.z), 0.0));
    float tmax = min(min(max(t0.x, t1.x), max(t0.y, t1.y)), max(t0.z, t1.z));
    vec3 color = vec3(0.0);
    bool radiance = uint(frame.view.x) == VIEW_RADIANCE;
    float level = radiance ? frame.view.y : 0.0;
    // Half a texel of the level along the longest axis (the finest in texture space).
    float step = 0.5 * exp2(level) / (clip_on() ? frame.clip.y : frame.voxel_grid.x) / warp_peak();
    for (float t = tmin; t < tmax; t += step) {
        vec3 tx = grid_to_texel((o + d * t) * march_dims());
        if (clip_on()) {
            // Inside its level's slab, by half a texel of the level shown.
            float n = frame.clip.y, slab = floor(tx.z / n) * n, h = 0.5 * exp2(level);
            tx.z = clamp(tx.z, slab + h, slab + n - h);
        }
        vec3 p = tx / frame.voxel_dims.xyz;
        if (radiance) {
            vec4 s = level < 0.5 ? level0_sample(radiance_volume, p) : textureLod(radiance_chain, p, level - 1.0);
            if (s.a > 0.3) { color = s.rgb / s.a; break; }
        } else {
            uint a = imageLoad(voxel_albedo, stored_at(clamp(ivec3(floor(p * frame.voxel_dims.xyz)), ivec3(0), ivec3(frame.voxel_dims.xyz) - 1))).r;
            if ((a >> 24) != 0u) {
                color = vec3(float(a & 0xffu), float((a >> 8) & 0xffu), float((a >> 16) & 0xffu)) / 255.0;
                break;
            }
        }
    }
    imageStore(hdr, px, vec4(color, 1.0));
}
