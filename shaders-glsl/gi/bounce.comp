#version 460
// Multiple bounces in voxel space (Wicked Engine's VXGI, Part 4; Crassin et al. 2011 §6): each
// occupied voxel gathers the previous bounce's filtered radiance with the
// bounce cone set (gi.bounce_cones: wider, so cheaper, than the surfaces') around its lit side (the voxel normal turned towards the light, else the
// voxel normal) and adds albedo times it to its own direct light and emission. The result is
// the next bounce's level 0; the frame filters it again and shades from it. A voxel lit only by
// bounced light gets its gathering side recorded as its lit side, so the anisotropic filter
// keeps it dark seen from behind. One invocation per occupied voxel (common/occupied.glsl),
// dispatched indirectly: empty voxels stay as the pass's clear left them.
#include "frame.glsl"
#define OCCUPIED_BINDING 9
#include "occupied.glsl"
#define BRICKS_SET 1
#define BRICKS_BINDING 10
#include "bricks.glsl"

layout(local_size_x = WORKGROUP_1D) in;
layout(constant_id = 0) const bool ANISOTROPIC = false;
layout(set = 1, binding = 0, r32ui) uniform readonly uimage3D voxel_albedo;
layout(set = 1, binding = 1, r32ui) uniform readonly uimage3D voxel_normal;
layout(set = 1, binding = 2, r32ui) uniform uimage3D lit_side;
layout(set = 1, binding = 3, rgba16f) uniform readonly image3D injected;
layout(set = 1, binding = 4, rgba16f) uniform writeonly image3D bounced;
layout(set = 1, binding = 5) uniform sampler3D radiance_volume;
layout(set = 1, binding = 6) uniform sampler3D radiance_aniso;
layout(set = 1, binding = 7) uniform sampler3D radiance_moment;
layout(set = 1, binding = 8) uniform sampler3D radiance_chain;
#include "level0.glsl"

#include "gather.glsl"
#include "lit_side.glsl"

void main() {
    if (gl_GlobalInvocationID.x >= occupied.count) return;
    ivec3 v = unpack_voxel(occupied.voxels[gl_GlobalInvocationID.x]);
    ivec3 size = ivec3(frame.voxel_dims.xyz);
    ivec3 t = stored_at(v);
    uint a = imageLoad(voxel_albedo, t).r;
    vec4 own = imageLoad(injected, t);
    uint side = imageLoad(lit_side, t).r;
    bool lit = has_lit_side(side);
    // (A voxel normal packs as a side does.)
    vec3 n = lit_side_of(lit ? side : imageLoad(voxel_normal, t).r);
    if (dot(n, n) < 1e-6) {
        imageStore(bounced, t, own);
        return;
    }
    n = normalize(n);
    vec3 albedo = vec3(float(a & 0xffu), float((a >> 8) & 0xffu), float((a >> 16) & 0xffu)) / 255.0;
    vec3 uvw = texel_centre_march(v);
    // From a voxel's centre: its surface may lie half a voxel above it, with a second layer of
    // the same wall above that (a wall on a voxel boundary), so the cones start a voxel further
    // out and keep their filters 1.5 voxels clear (common/cone.glsl, self_clamp_level).
    ConeParams p = frame_cone_params();
    p.bias += 1.0;
    p.surface = 1.5;
    // A clipmap voxel's offsets are in its own level's texels.
    if (clip_on()) p.start_level = v.z / int(frame.clip.y);
    vec4 gathered = gather_bounce(uvw, n, p);
    // A voxel no light reaches directly has no lit side, and a mesh normal may point either way
    // (surfaces are two-sided): it gathers on both sides and keeps the brighter, the side its
    // light then leaves from.
    if (!lit) {
        vec4 back = gather_bounce(uvw, -n, p);
        if (dot(back.rgb, vec3(1.0)) > dot(gathered.rgb, vec3(1.0))) {
            gathered = back;
            n = -n;
        }
    }
    imageStore(bounced, t, vec4(own.rgb + albedo * gathered.rgb, own.a));
    if (!lit) {
        imageStore(lit_side, t, uvec4(pack_lit_side(n, 1u)));
    }
}
