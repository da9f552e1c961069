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
    return 6.2831853 * fract(52.9829189 * fract(dot(vec2(px), vec2(0.06711056, 0.00583715))));
}

// Returns the cosine-weighted mean incoming radiance (rgb) and occlusion (a) around `n` at `uvw`
// with the cones `first` .. `first + count` of `cones` (the surface set, or the voxel bounce set),
// the set turned about `n` by `turn` radians.
vec4 gather_cones(vec3 uvw, vec3 n, ConeParams p, int first, int count, float turn) {
    vec3 t0, b0;
    tangent_frame(n, t0, b0);
    vec3 t = cos(turn) * t0 + sin(turn) * b0, b = cos(turn) * b0 - sin(turn) * t0;
    vec4 sum = vec4(0.0);
    for (int i = first; i < first + count; i++) {
        vec4 dw = cones[i].dir_weight;
        vec3 dir = normalize(t * dw.x + b * dw.y + n * dw.z);
        sum += dw.w * trace_frame_cone(uvw, n, dir, cones[i].shape.x, p);
    }
    return sum;
}

// The surfaces' gather (the diffuse cone set) at pixel `px`.
vec4 gather_diffuse(vec3 uvw, vec3 n, ConeParams p, ivec2 px) {
    return gather_cones(uvw, n, p, 0, int(frame.cone_model.x), cone_turn(px));
}

// The voxel-space bounce's gather (its own, cheaper set, after the surfaces' in `cones`).
vec4 gather_bounce(vec3 uvw, vec3 n, ConeParams p) {
    return gather_cones(uvw, n, p, MAX_CONES, int(frame.cone_model.w), 0.0);
}

#endif
