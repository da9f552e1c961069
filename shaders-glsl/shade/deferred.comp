#version 460
// Deferred variant, shading pass: one thread per pixel reads the G-buffer, rebuilds the world
// position from the camera distance along the pixel's ray and runs the same `shade_surface`
// as the forward path. With GI_SCALE s > 1 the diffuse cones run at one pixel in s² (PASS
// TRACE: one pixel of each s x s block, `frame.gi_jitter.xy`, into `diffuse_low`), and the
// shading pass (PASS SHADE) upsamples them edge-aware (joint bilateral: of the four nearest
// traced pixels, only those on the pixel's own surface count, by their normal and their
// distance from its tangent plane); where none does (a silhouette, a thin object) the nearest
// stands in; a traced pixel shows its own trace. With SPECULAR_REDUCED the specular cone
// is traced with them (into `specular_low`, before the Fresnel factor, which each pixel applies
// with its own material) and upsampled and accumulated alike; otherwise every pixel traces its
// own. On Sponza the specular cone (narrow, so many steps) is 70% of the shading pass (640x360,
// scale 4: 920 ms with it, 275 without; docs/design/reduced-scale.md).
//
// ACCUMULATE (screen-space accumulation, `--gi-accumulate`; PASS ACCUMULATE, between the two,
// writes each pixel's gather to `history_out`, which the shading pass reads): the traced pixel
// moves through the block frame by frame (render::deferred::jitter), and every pixel keeps the
// last trace it got,
// reprojected with the previous frame's camera and rejected where the surface found there is
// not this pixel's (its normal and tangent plane: disocclusion); a pixel that keeps none shows
// the upsampled light, averaged over the frames until its own trace comes (an estimate,
// SURFACE_ESTIMATE). On a still camera every pixel is traced once in s² frames, and the
// image is then full-resolution tracing exactly. Light that changes is shown up to s² frames
// late. Measured (96², 32³, Cornell, after s² frames): under a camera orbiting 0.5° a frame the
// indirect light is within 1.3% / 3.3% of full-resolution tracing at scale 2 / 4 (upsampling
// alone: 5.3% / 14.4%), under a spot turning 0.5° a frame within 0.6% / 2.3% (6.1% / 15.0%),
// and it changes from frame to frame no more than full-resolution tracing does. Measured and
// not used: a neighbourhood clamp (Karis 2014), whose range moves with the traced pixels, so a
// still view keeps changing by 0.6-1.0% a frame; and moving the kept trace by its traced
// neighbours' change since their own traces, whose estimate differs with each frame's traced
// pixels: it flickers 2.5-14% a frame.
// Constants 7 and 8: whether any light is an area light (common/light.glsl), and whether any
// material reflects specularly (common/shading.glsl; without, SPECULAR_REDUCED is off too).
layout(constant_id = 7) const bool AREA_LIGHTS = true;
layout(constant_id = 8) const bool SPECULAR_MATERIALS = true;
// Constant 9: the cone set turns by pixel (CONE_FLAG_TURN) and every pixel holds a gather of its
// own: at full resolution the cones are traced into `diffuse_low` (PASS_TRACE), or accumulated
// (`history_out`), and the shading resolves each pixel's from its neighbours' (`resolved_gather`).
layout(constant_id = 9) const bool RESOLVE = false;
// Constant 10: the set is split among each 2×2 block of traced pixels (GiFile::split_cones,
// common/gather.glsl): each traced pixel traces a quarter of it into `diffuse_low`, and the
// resolve gathers each quarter from the neighbours that traced it (`split_resolved`): in the
// shading pass at full resolution, in a pass of its own over the traced pixels (PASS_RESOLVE) at
// a reduced scale.
layout(constant_id = 10) const bool SPLIT = false;
const int SPLIT_RADIUS = 2;
#define VCT_AREA_LIGHTS AREA_LIGHTS
#define VCT_SPECULAR SPECULAR_MATERIALS
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
layout(set = 2, binding = 10, rgba16f) uniform readonly image2D history_in;
layout(set = 2, binding = 11, rgba16f) uniform image2D history_out;
layout(set = 2, binding = 12, rgba32ui) uniform readonly uimage2D surface_in;
layout(set = 2, binding = 13, rgba32ui) uniform writeonly uimage2D surface_out;
// The specular cone's light (rgb; a: 1 where a cone was traced) at the traced pixels, and its
// history (as `history_in`, `history_out`).
layout(set = 2, binding = 14, rgba16f) uniform image2D specular_low;
layout(set = 2, binding = 15, rgba16f) uniform readonly image2D specular_history_in;
layout(set = 2, binding = 16, rgba16f) uniform image2D specular_history_out;
// With SPLIT at a reduced scale: each traced pixel's gather resolved from its neighbours' quarters
// (PASS_RESOLVE), which the upsampling reads in place of `diffuse_low`.
layout(set = 2, binding = 17, rgba16f) uniform image2D diffuse_resolved;

#include "shading.glsl"

layout(constant_id = 3) const uint GI_SCALE = 1;
layout(constant_id = 4) const uint PASS = 0;
layout(constant_id = 5) const bool ACCUMULATE = false;
layout(constant_id = 6) const bool SPECULAR_REDUCED = false;
const uint PASS_SHADE = 0;
const uint PASS_TRACE = 1;
const uint PASS_ACCUMULATE = 2;
const uint PASS_RESOLVE = 3;

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

// The full-resolution pixel block `q` of the reduced grid traces for this frame.
ivec2 traced_pixel(ivec2 q) {
    return min(q * int(GI_SCALE) + ivec2(frame.gi_jitter.xy), ivec2(frame.viewport.xy) - 1);
}

// The diffuse gather at `world` (normal `n`) upsampled from the four traced pixels around
// `px`. A traced pixel counts when its surface continues this one: its normal within ~25
// degrees and its position within half a voxel of this pixel's tangent plane. Where none does
// (a silhouette, an object thinner than the traced grid) the one nearest this pixel's tangent
// plane stands in: tracing here instead would cost every pixel on a CPU driver, which runs a
// branch for all lanes when any lane takes it. `own`: `px` was traced itself (the value is its
// trace). `spec`: the specular cone's light alike (SPECULAR_REDUCED), from the traced pixels
// that traced one (a material without specular traces none).
vec4 upsampled_gather(ivec2 px, vec3 world, vec3 n, out bool own, out vec4 spec) {
    ivec2 size = imageSize(diffuse_low);
    vec2 f = vec2(px - ivec2(frame.gi_jitter.xy)) / float(GI_SCALE);
    ivec2 base = ivec2(floor(f));
    ivec2 cell = clamp(base, ivec2(0), size - 1);
    own = traced_pixel(cell) == px;
    spec = vec4(0.0);
    if (own) {
        if (SPECULAR_REDUCED) spec = imageLoad(specular_low, cell);
        return SPLIT ? imageLoad(diffuse_resolved, cell) : imageLoad(diffuse_low, cell);
    }
    vec2 t = f - vec2(base);
    float plane = 0.5 * frame.voxel_origin.w;
    vec4 sum = vec4(0.0), nearest = vec4(0.0), spec_sum = vec4(0.0), spec_nearest = vec4(0.0);
    float total = 0.0, closest = 1e30, spec_total = 0.0, spec_closest = 1e30;
    for (int i = 0; i < 4; i++) {
        ivec2 o = ivec2(i & 1, i >> 1);
        ivec2 q = clamp(base + o, ivec2(0), size - 1);
        vec3 wq, nq;
        if (!surface_at(traced_pixel(q), wq, nq)) continue;
        vec4 g = SPLIT ? imageLoad(diffuse_resolved, q) : imageLoad(diffuse_low, q);
        vec4 s = SPECULAR_REDUCED ? imageLoad(specular_low, q) : vec4(0.0);
        float d = abs(dot(wq - world, n)) + plane * max(0.9 - dot(nq, n), 0.0) * 10.0;
        if (d < closest) {
            closest = d;
            nearest = g;
        }
        if (s.a > 0.0 && d < spec_closest) {
            spec_closest = d;
            spec_nearest = s;
        }
        if (dot(nq, n) < 0.9 || abs(dot(wq - world, n)) > plane) continue;
        float w = (o.x == 1 ? t.x : 1.0 - t.x) * (o.y == 1 ? t.y : 1.0 - t.y) + 1e-4;
        sum += w * g;
        total += w;
        spec_sum += w * s.a * s;
        spec_total += w * s.a;
    }
    spec = spec_total > 0.0 ? spec_sum / spec_total : spec_nearest;
    return total > 0.0 ? sum / total : nearest;
}

// The split set's gather at traced pixel `q` of `diffuse_low` (its surface at `world`, normal
// `n`): each quarter's mean over the 5×5 traced pixels around it of its class on the surface, and
// the quarters summed. The weights, 1, 2, 2, 2, 1 along each axis, give each of a class's turns
// (common/gather.glsl, split_turn) the same share. A quarter no neighbour on the surface traced (a
// silhouette, a one-pixel sliver) is stood in for by the others, scaled by the cone weight they
// hold against the set's.
vec4 split_resolved(ivec2 q, vec3 world, vec3 n) {
    ivec2 size = imageSize(diffuse_low);
    float plane = 0.5 * frame.voxel_origin.w;
    vec4 sums[SPLIT_CLASSES] = vec4[](vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0));
    float weights[SPLIT_CLASSES] = float[](0.0, 0.0, 0.0, 0.0);
    const int r = SPLIT_RADIUS, side = 2 * r + 1;
    for (int i = 0; i < side * side; i++) {
        ivec2 o = ivec2(i % side - r, i / side - r);
        ivec2 p = q + o;
        vec3 wp, np;
        if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, size))) continue;
        if (!surface_at(traced_pixel(p), wp, np) || dot(np, n) < 0.9 || abs(dot(wp - world, n)) > plane) continue;
        // 1, 2, 2, 2, 1 along each axis: a class's pixels at even offsets weigh 1 + 2 + 1, at odd
        // ones 2 + 2, and its blocks of either parity alike.
        float w = float((abs(o.x) == r ? 1 : 2) * (abs(o.y) == r ? 1 : 2));
        int c = split_class(p);
        sums[c] += w * imageLoad(diffuse_low, p);
        weights[c] += w;
    }
    vec4 sum = vec4(0.0);
    float held = 0.0, all = 0.0;
    for (int c = 0; c < SPLIT_CLASSES; c++) {
        float k = split_weight(c);
        all += k;
        if (weights[c] > 0.0) {
            sum += sums[c] / weights[c];
            held += k;
        }
    }
    return sum * (all / max(held, 1e-6));
}

// The diffuse gather at `px` (at `world`, normal `n`) resolved from the cones traced at the 3×3
// pixels around it, each with the set turned by its own angle (common/gather.glsl, cone_turn):
// the mean of those on the same surface (normal within ~25 degrees, position within half a
// voxel of this pixel's tangent plane, as `upsampled_gather` judges), this pixel's own always
// among them. A turned set leaves each pixel's light off by where its cones fell; nine turns
// together sample each cone's cell in nine directions (docs/design/cones.md).
// With SPLIT at full resolution, `split_resolved`.
vec4 resolved_gather(ivec2 px, vec3 world, vec3 n) {
    ivec2 size = ivec2(frame.viewport.xy);
    float plane = 0.5 * frame.voxel_origin.w;
    if (SPLIT && GI_SCALE == 1u) return split_resolved(px, world, n);
    vec4 sum = vec4(0.0);
    float total = 0.0;
    for (int i = 0; i < 9; i++) {
        ivec2 q = clamp(px + ivec2(i % 3 - 1, i / 3 - 1), ivec2(0), size - 1);
        vec3 wq, nq;
        if (!surface_at(q, wq, nq) || dot(nq, n) < 0.9 || abs(dot(wq - world, n)) > plane) continue;
        sum += ACCUMULATE ? imageLoad(history_out, q) : imageLoad(diffuse_low, q);
        total += 1.0;
    }
    return sum / max(total, 1.0);
}

// What a history pixel holds, beside its surface's packed normal (zero: nothing; background or
// GI off): a trace of its own, or, until it gets one, an estimate: the upsampled light averaged
// over the frames, whose traced pixels move through the block.
const uint SURFACE_TRACE = 0x80000000u;
const uint SURFACE_ESTIMATE = 0x40000000u;
// The weight of this frame's upsampled light in an estimate. Without the average, a pixel not yet
// traced would show each frame's upsampling from other traced pixels: at scale 8 the first 64
// frames after a cut would flicker and dot edges (docs/design/reduced-scale.md).
const float ESTIMATE_WEIGHT = 0.25;

// A unit normal in 30 bits (octahedral, 15 bits an axis); bits 30 and 31 are left for the flags.
uint pack_surface_normal(vec3 n) {
    n /= abs(n.x) + abs(n.y) + abs(n.z);
    vec2 p = n.z >= 0.0 ? n.xy : (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    uvec2 q = uvec2(round(clamp(p * 0.5 + 0.5, 0.0, 1.0) * 32767.0));
    return q.x | (q.y << 15);
}

vec3 unpack_surface_normal(uint w) {
    vec2 p = vec2(w & 0x7fffu, (w >> 15) & 0x7fffu) / 32767.0 * 2.0 - 1.0;
    vec3 n = vec3(p, 1.0 - abs(p.x) - abs(p.y));
    float t = max(-n.z, 0.0);
    n.xy += vec2(n.x >= 0.0 ? -t : t, n.y >= 0.0 ? -t : t);
    return normalize(n);
}

// The trace pixel `px` (at `world`, normal `n`) kept in the previous frame: bilinear over the
// four pixels around where the point was, of which only those that keep a trace of this
// surface count (their normal and tangent plane, as the upsampling tests them), or where none
// does, those that keep an estimate (`estimate` true); false where the point was off screen or
// no pixel there keeps either (disocclusion). The point moves by the
// difference of its two projections, whose rounding cancels when the camera stood still.
// Measured and not used: nearest-pixel reprojection (after a 35-degree turn the kept history is
// worse than none, 1.5% against 1.2%), and projecting the rebuilt position alone (a few
// hundredths of a pixel off, so resampling it every frame blurs a still view by 0.15%).
bool history_at(ivec2 px, vec3 world, vec3 n, out vec4 h, out vec4 hs, out bool estimate) {
    vec4 clip = frame.previous_view_proj * vec4(world, 1.0);
    vec4 now = frame.view_proj * vec4(world, 1.0);
    if (clip.w <= 0.0) return false;
    vec2 f = vec2(px) + (clip.xy / clip.w - now.xy / now.w) * 0.5 * frame.viewport.xy;
    ivec2 base = ivec2(floor(f));
    vec2 t = f - vec2(base);
    vec4 sum = vec4(0.0), spec_sum = vec4(0.0), guess = vec4(0.0);
    float total = 0.0, guessed = 0.0;
    for (int i = 0; i < 4; i++) {
        ivec2 o = ivec2(i & 1, i >> 1);
        ivec2 p = base + o;
        float w = (o.x == 1 ? t.x : 1.0 - t.x) * (o.y == 1 ? t.y : 1.0 - t.y);
        if (w <= 0.0 || any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, ivec2(frame.viewport.xy)))) continue;
        uvec4 s = imageLoad(surface_in, p);
        if ((s.w & (SURFACE_TRACE | SURFACE_ESTIMATE)) == 0u) continue;
        vec3 wp = uintBitsToFloat(s.xyz);
        if (dot(unpack_surface_normal(s.w), n) < 0.9 || abs(dot(wp - world, n)) > 0.5 * frame.voxel_origin.w) continue;
        vec4 g = imageLoad(history_in, p);
        if ((s.w & SURFACE_TRACE) != 0u) {
            sum += w * g;
            if (SPECULAR_REDUCED) spec_sum += w * imageLoad(specular_history_in, p);
            total += w;
        } else {
            guess += w * g;
            guessed += w;
        }
    }
    estimate = total <= 0.0;
    h = estimate ? guess / max(guessed, 1e-30) : sum / total;
    hs = spec_sum / max(total, 1e-30);
    return total > 0.0 || guessed > 0.0;
}

// With SPLIT, the trace pass's pixel for invocation pixel `p`: each quadrant of the workgroup's
// tile takes one class's pixels of the whole tile, so a SIMD group traces one quarter of the set.
ivec2 split_pixel(ivec2 p) {
    const int h = WORKGROUP_2D / 2;
    ivec2 tile = p / WORKGROUP_2D * WORKGROUP_2D, l = p - tile;
    return tile + 2 * (l % h) + l / h;
}

// The pixel of this invocation: the workgroup in tiles of 4 x 2, so that eight consecutive
// invocations (a SIMD group on lavapipe's 256-bit vectors) cover a compact patch, whose cones end
// after more nearly the same number of steps than those of a row of eight. Measured (lavapipe):
// the reduced trace at scale 8 (Cornell, 1280x720, 64^3) took 84-87 ms against 93-99 along rows,
// and full-resolution shading (Cornell 256^2, 128^3) 803-813 against 848-856 ms; the images of
// the two orders differ no more than two runs of either do (the voxelizer's atomic averages
// follow the order threads land: FLIP up to 0.001). On a GPU a warp of 32 covers 8 x 4 pixels
// either way.
ivec2 invocation_pixel() {
    const uint tiles_x = WORKGROUP_2D / 4;
    uint i = gl_LocalInvocationIndex, lane = i & 7u, tile = i >> 3u;
    uvec2 at = uvec2((tile % tiles_x) * 4u + (lane & 3u), (tile / tiles_x) * 2u + (lane >> 2u));
    return ivec2(gl_WorkGroupID.xy * WORKGROUP_2D + at);
}

void main() {
    ivec2 px = invocation_pixel();
    if (PASS == PASS_RESOLVE) {
        if (any(greaterThanEqual(px, imageSize(diffuse_low)))) return;
        vec3 world, n;
        bool on = frame.view.z > 0.5 && surface_at(traced_pixel(px), world, n);
        imageStore(diffuse_resolved, px, on ? split_resolved(px, world, n) : vec4(0.0));
        return;
    }
    if (PASS == PASS_TRACE) {
        if (SPLIT) px = split_pixel(px);
        if (any(greaterThanEqual(px, imageSize(diffuse_low)))) return;
        vec3 world, n;
        vec4 g = vec4(0.0), s = vec4(0.0);
        ivec2 traced = traced_pixel(px);
        if (frame.view.z > 0.5 && surface_at(traced, world, n)) {
            vec3 uvw = world_to_march(world);
            ConeParams p = frame_cone_params();
            // Split, the class and turn are the traced grid's (at full resolution, the pixel's).
            // Where a 3×3 resolve gathers the traced pixels (at full resolution, or from the
            // accumulated history), the whole set turns in ordered ninths of the traced pixel.
            g = SPLIT     ? gather_diffuse_split(uvw, n, p, px)
                : RESOLVE ? gather_diffuse_resolved(uvw, n, p, traced)
                          : gather_diffuse(uvw, n, p, traced);
            if (SPECULAR_REDUCED) {
                vec4 a = imageLoad(gbuffer_albedo, traced);
                Material m = materials[uint(a.w + 0.5)];
                vec3 f0 = specular_f0(m, a.rgb);
                if (max(f0.r, max(f0.g, f0.b)) > 0.0) {
                    s = vec4(specular_cone(m, uvw, n, normalize(frame.camera_pos.xyz - world), p), 1.0);
                }
            }
        }
        imageStore(diffuse_low, px, g);
        if (SPECULAR_REDUCED) imageStore(specular_low, px, s);
        return;
    }
    if (any(greaterThanEqual(px, imageSize(hdr)))) return;
    vec3 world, n;
    bool found = surface_at(px, world, n);
    bool given = (GI_SCALE > 1u || RESOLVE) && frame.view.z > 0.5;
    if (PASS == PASS_ACCUMULATE) {
        // This frame's gather (the traced pixel's own, the kept trace, or the upsampled light,
        // averaged with the kept estimate) into `history_out`, which the shading pass then reads.
        vec4 gathered = vec4(0.0), spec = vec4(0.0);
        uint holds = 0u;
        if (found && given) {
            bool own;
            gathered = upsampled_gather(px, world, n, own, spec);
            holds = own ? SURFACE_TRACE : SURFACE_ESTIMATE;
            vec4 h, hs;
            bool estimate;
            if (!own && frame.gi_jitter.z > 0.5 && history_at(px, world, n, h, hs, estimate)) {
                if (estimate) {
                    gathered = mix(h, gathered, ESTIMATE_WEIGHT);
                } else {
                    gathered = h;
                    // The specular cone looks along the reflected view: a trace from another
                    // camera position is of another direction. While the camera moves, this
                    // frame's upsampled traces stand in (on Sponza orbiting 0.5 degrees a frame,
                    // the kept traces are 12.7% off full resolution's indirect light;
                    // docs/design/reduced-scale.md).
                    if (frame.gi_jitter.w < 0.5) spec = hs;
                    holds = SURFACE_TRACE;
                }
            }
        }
        imageStore(history_out, px, gathered);
        if (SPECULAR_REDUCED) imageStore(specular_history_out, px, spec);
        uvec4 surface = uvec4(floatBitsToUint(world), pack_surface_normal(n) | holds);
        imageStore(surface_out, px, holds != 0u ? surface : uvec4(0u));
        return;
    }
    if (!found) {
        imageStore(hdr, px, vec4(0.0));
        return;
    }
    vec4 a = imageLoad(gbuffer_albedo, px);
    Material m = materials[uint(a.w + 0.5)];
    vec4 gathered = vec4(0.0), spec = vec4(0.0);
    if (given) {
        bool own;
        if (ACCUMULATE) {
            gathered = RESOLVE ? resolved_gather(px, world, n) : imageLoad(history_out, px);
            if (SPECULAR_REDUCED) spec = imageLoad(specular_history_out, px);
        } else if (RESOLVE) {
            gathered = resolved_gather(px, world, n);
        } else {
            gathered = upsampled_gather(px, world, n, own, spec);
        }
    }
    // Whether the cones were traced elsewhere is known when the shader is specialized
    // (shade_surface_given reads the gather only with GI on): as a runtime value, the cone code
    // it stands for would stay in this pass, and lavapipe, which runs a branch for every lane
    // whether or not one takes it, would pay for a cone's first steps at every pixel.
    const bool traced = GI_SCALE > 1u || RESOLVE;
    imageStore(hdr, px, vec4(shade_surface_given(m, a.rgb, n, world, traced, gathered, SPECULAR_REDUCED && traced, spec.rgb, px), 1.0));
}
