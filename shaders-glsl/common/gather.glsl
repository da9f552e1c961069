// Diffuse light gathered by the cone set (Freed 2018 §4.5.2; the set itself is built in
// scene/cones.rs): each cone of `cones` is a direction in the surface's tangent frame with its
// cosine weight, and the weighted sum of the cones' radiance is the cosine-weighted mean of the
// incoming radiance, so albedo times it is the outgoing diffuse radiance (albedo/pi * E). Shared
// by the surface shading and the voxel-space bounce pass. The includer binds `radiance_volume`
// (level 0, read by common/level0.glsl), the chain above it `radiance_chain`,
// the radiance moment `radiance_moment` and the directional chains' atlas `radiance_aniso`, and
// declares the ANISOTROPIC specialization constant.
#ifndef VCT_GATHER_GLSL
#define VCT_GATHER_GLSL
#include "frame.glsl"
#include "cone.glsl"

// The frame's cone parameters for a point on a surface.
ConeParams frame_cone_params() {
    return ConeParams(int(frame.cone.x), frame.cone.y, frame.cone.z, frame.cone.w, frame.voxel_dims.xyz,
                      frame.voxel_grid.y - 1.0, frame.cone_model.y, uint(frame.cone_model.z), 0.5,
                      frame.aniso_atlas.xyz, 0.0, frame.voxel_warp, 1.0, 0, frame.voxel_warp_proj);
}

vec4 trace_frame_cone(vec3 uvw, vec3 n, vec3 dir, float tan_half, ConeParams p) {
    const bool aniso = ANISOTROPIC;
    return trace_cone_filtered(radiance_volume, radiance_chain, radiance_moment, radiance_aniso, aniso, uvw, n, dir,
                               tan_half, p);
}

// The angle the surfaces' cone set turns by about the normal at pixel `px`: with CONE_FLAG_TURN,
// interleaved gradient noise (Jimenez 2014, "Next Generation Post Processing in Call of Duty:
// Advanced Warfare"), whose neighbouring values differ most, so that any few pixels together
// sample each cone's cell in several directions; else 0.
float cone_turn(ivec2 px) {
    if ((uint(frame.cone_model.z) & CONE_FLAG_TURN) == 0u) return 0.0;
    return 6.2831853 * fract(52.9829189 * fract(dot(vec2(px), vec2(0.06711056, 0.00583715))) + frame.view.w);
}

// Returns the cosine-weighted mean incoming radiance (rgb) and occlusion (a) around `n` at `uvw`
// with every `stride`-th cone of `first` .. `first + count` of `cones` (the surface set, or the
// voxel bounce set), the set turned about `n` by `turn` radians.
vec4 gather_cones(vec3 uvw, vec3 n, ConeParams p, int first, int count, int stride, float turn) {
    vec3 t0, b0;
    tangent_frame(n, t0, b0);
    vec3 t = cos(turn) * t0 + sin(turn) * b0, b = cos(turn) * b0 - sin(turn) * t0;
    vec4 sum = vec4(0.0);
    for (int i = first; i < first + count; i += stride) {
        vec4 dw = cones[i].dir_weight;
        vec3 dir = normalize(t * dw.x + b * dw.y + n * dw.z);
        sum += dw.w * trace_frame_cone(uvw, n, dir, cones[i].shape.x, p);
    }
    return sum;
}

// The surfaces' gather (the diffuse cone set) at pixel `px`.
vec4 gather_diffuse(vec3 uvw, vec3 n, ConeParams p, ivec2 px) {
    return gather_cones(uvw, n, p, 0, int(frame.cone_model.x), 1, cone_turn(px));
}

// The turn of the whole set at pixel `px` where a 3×3 resolve gathers it (with CONE_FLAG_TURN):
// ordered, the nine ninths of a turn on a 3×3 tile, so that every 3×3 window holds each once and
// the resolve gathers the same nine turns at every pixel of a flat wall.
float resolved_turn(ivec2 px) {
    if ((uint(frame.cone_model.z) & CONE_FLAG_TURN) == 0u) return 0.0;
    ivec2 m = px % 3;
    return 6.2831853 * fract(float((m.x + 3 * m.y) * 4 % 9) / 9.0 + frame.view.w);
}

// The gather of the whole set at `px` for a 3×3 resolve.
vec4 gather_diffuse_resolved(vec3 uvw, vec3 n, ConeParams p, ivec2 px) {
    return gather_cones(uvw, n, p, 0, int(frame.cone_model.x), 1, resolved_turn(px));
}

// A set split among each 2×2 block of pixels (GiFile::split_cones): pixel `px` traces the cones
// of its class, every SPLIT_CLASSES-th from the class's index. The Fibonacci sets interleave
// rise and turn along their index, so each class spans the hemisphere.
const int SPLIT_CLASSES = 4;

int split_class(ivec2 px) {
    return (px.x & 1) + 2 * (px.y & 1);
}


// The turn of a split set at pixel `px` (with CONE_FLAG_TURN): ordered, not noise. The blocks
// of 2×2 blocks take the four quarter turns (in Bayer order), and each class its own sixteenth on
// top, so that any 4×4 pixels hold every class at each of the four turns: the resolve's window
// (shade/deferred.comp), which weighs each class's blocks alike, then gathers the same sixteen
// turns of its quarter of the set at every pixel of a flat wall, and leaves no grain. Interleaved
// gradient noise instead (`cone_turn`) gives each window a random draw of turns, which shows as
// grain of 5% of the light on the Cornell box's walls (docs/design/cones.md).
float split_turn(ivec2 px) {
    if ((uint(frame.cone_model.z) & CONE_FLAG_TURN) == 0u) return 0.0;
    ivec2 b = (px >> 1) & 1;
    float quarter = float(b.y == 0 ? 2 * b.x : 3 - 2 * b.x);
    return 6.2831853 * fract(quarter / 4.0 + float(split_class(px)) / 16.0 + frame.view.w);
}

// The part of the set's gather (the partial sum) that pixel `px`'s class traces.
vec4 gather_diffuse_split(vec3 uvw, vec3 n, ConeParams p, ivec2 px) {
    int c = split_class(px);
    return gather_cones(uvw, n, p, c, int(frame.cone_model.x) - c, SPLIT_CLASSES, split_turn(px));
}

// The weight of class `c`'s cones (the whole set's sums to one).
float split_weight(int c) {
    float w = 0.0;
    for (int i = c; i < int(frame.cone_model.x); i += SPLIT_CLASSES) w += cones[i].dir_weight.w;
    return w;
}

// The voxel-space bounce's gather (its own, cheaper set, after the surfaces' in `cones`).
vec4 gather_bounce(vec3 uvw, vec3 n, ConeParams p) {
    return gather_cones(uvw, n, p, MAX_CONES, int(frame.cone_model.w), 1, 0.0);
}

#endif
