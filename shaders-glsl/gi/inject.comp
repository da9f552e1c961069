#version 460
// Radiance injection (Freed 2018 §4.3, Algorithm 2): one thread per (strided) shadow-map texel
// reconstructs the lit point from its depth, finds its voxel and writes the light that voxel
// reflects: albedo/pi * E * |n.l| (Lambert, n the voxel's averaged normal), plus emission.
// The value is computed at the voxel centre, so every texel that hits a voxel writes the same
// value: the result does not depend on which write lands last. It also records the lit side:
// the voxel normal turned towards the light, which the anisotropic filter uses to keep a lit
// face dark when seen from behind (a Lambertian face reflects into its own hemisphere only),
// and around which the voxel-space bounce gathers.
// With several lights each voxel must get the sum of what each light alone gives it, so which
// voxels a light lights must not depend on the others. The pass then runs twice over every
// light's texels: INJECT_MARK sets, for each voxel a light's texels find, that light's bit in
// the voxel's lit_side word (bits 24..31, an atomic or); INJECT_GATHER then writes, at each
// found voxel, the light of every light whose bit is set, the same value whichever texel lands
// last (the bits no longer change), its lit side facing the light that gives the most. One light
// needs no marks (INJECT_ONE): its texels are what finds its voxels.
#define VCT_OWN_PUSH
#include "frame.glsl"
// Whether any of the scene's lights is an area light (render::inject); without one the polygon's
// code is compiled out of the light loop below (common/light.glsl).
layout(constant_id = 3) const bool AREA_LIGHTS = true;
#define VCT_AREA_LIGHTS AREA_LIGHTS
#include "light.glsl"
#include "rgb9e5.glsl"
#include "lit_side.glsl"

layout(local_size_x = WORKGROUP_2D, local_size_y = WORKGROUP_2D) in;
// One layer, or a point or area light's six cube faces (one dispatch a layer: push.layer).
layout(set = 1, binding = 0) uniform sampler2DArray shadow_depth;
layout(set = 1, binding = 1, r32ui) uniform readonly uimage3D voxel_albedo;
layout(set = 1, binding = 2, r32ui) uniform readonly uimage3D voxel_normal;
layout(set = 1, binding = 3, r32ui) uniform readonly uimage3D voxel_emission;
layout(set = 1, binding = 4, rgba16f) uniform writeonly image3D target;
layout(set = 1, binding = 5, r32ui) uniform uimage3D lit_side;
#define BRICKS_SET 1
#define BRICKS_BINDING 6
#include "bricks.glsl"
// One thread per `stride` x `stride` block of texels, reading its centre texel (render::inject:
// the stride keeps INJECT_TEXELS_PER_VOXEL texels per voxel where the map has more).
layout(push_constant) uniform Push { uint stride; uint light; uint phase; uint layer; } push;

const float PI = 3.14159265358979;

vec4 unpack(uint p) {
    return vec4(float(p & 0xffu), float((p >> 8) & 0xffu), float((p >> 16) & 0xffu), float(p >> 24)) / 255.0;
}

// Grid point `g` in texels of level k (k = 0: the grid).
vec3 level_texel(vec3 g, int k) {
    return clip_on() ? clip_texel(g, k) : grid_to_texel(g);
}

// Whether texel `u` lies in level k (k = 0: the grid).
bool in_level(ivec3 u, int k) {
    return clip_on() ? clip_in_level(u, k) : voxel_in_grid(u);
}

void inject_level(vec3 p, vec3 l_dir, int j, int level);

void main() {
    int stride = int(push.stride);
    int j = int(push.light);
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy) * stride + stride / 2;
    ivec2 size = textureSize(shadow_depth, 0).xy;
    int layer = int(frame.lights[j].cone.w) + int(push.layer);
    if (any(greaterThanEqual(texel, size))) return;
    float depth = texelFetch(shadow_depth, ivec3(texel, layer), 0).r;
    if (depth >= 1.0) return;
    vec2 uv = (vec2(texel) + 0.5) / vec2(size);
    vec4 world = inverse(frame.light_layers[layer]) * vec4(uv * 2.0 - 1.0, depth, 1.0);
    vec3 p = world.xyz / world.w;
    // The lit point lies on a surface, but the shadow map's slope-scaled depth bias has pushed
    // it along the light ray behind that surface, by up to a few voxels where the light grazes.
    // Its voxel is the occupied one nearest the light in the first run of occupied voxels met
    // walking the ray back towards the light (INJECT_SEARCH_VOXELS at most), else the one just
    // behind the point: a wall thinner than a voxel must not light its far side.
    LightData li = frame.lights[j];
    // An area light lights only the side its face looks to: texels behind it (about half of
    // four cube faces; a face wholly behind is not dispatched) find nothing to light.
    if (uint(li.position.w) == LIGHT_AREA && dot(p - li.position.xyz, li.direction.xyz) <= 0.0) return;
    vec3 l_dir = uint(li.position.w) == LIGHT_DIRECTIONAL ? li.direction.xyz : normalize(p - li.position.xyz);
    // A clipmap's every level holding the point gets its light (a wide cone reads a coarse level
    // where finer ones also hold the point).
    for (int k = 0; k < (clip_on() ? clip_count() : 1); k++) inject_level(p, l_dir, j, k);
}

// Lights the voxel of lit point `p` in level `level` (0: the grid).
void inject_level(vec3 p, vec3 l_dir, int j, int level) {
    float scale = clip_on() ? frame.clip_levels[level].w : 1.0;
    ivec3 v = ivec3(-1), t = ivec3(0);  // the voxel, and where it is stored
    uint a = 0u;
    // In voxel units, from a quarter voxel before the point, one voxel at a time: a step no
    // longer than a voxel cannot jump over a wall's voxel layer. Mostly two loads: the surface's
    // voxel and the empty one before it.
    // A warped grid's texels are up to warp_peak() to a grid voxel: steps that long at most; a
    // clipmap level's are `scale` voxels of level 0.
    vec3 walk = l_dir * scale / warp_peak();
    vec3 g = world_to_grid(p) - walk * 0.25;
    for (int i = 0; i <= INJECT_SEARCH_VOXELS; i++, g -= walk) {
        ivec3 u = ivec3(floor(level_texel(g, level)));
        if (!in_level(u, level)) break;
        ivec3 at = stored_at(u);
        uint b = imageLoad(voxel_albedo, at).r;
        if ((b >> 24) != 0u) {
            v = u;
            t = at;
            a = b;
        } else if ((a >> 24) != 0u) {
            break;
        }
    }
    if ((a >> 24) == 0u) {
        v = ivec3(floor(level_texel(world_to_grid(p) + l_dir * 0.25 * scale, level)));
        if (!in_level(v, level)) return;
        t = stored_at(v);
        a = imageLoad(voxel_albedo, t).r;
        if ((a >> 24) == 0u) return;
    }
    if (push.phase == INJECT_MARK) {
        imageAtomicOr(lit_side, t, 1u << (24 + j));
        return;
    }
    uint lights = push.phase == INJECT_ONE ? 1u << j : imageLoad(lit_side, t).r >> 24;
    vec3 centre = texel_centre_world(v);
    vec3 normal = unpack(imageLoad(voxel_normal, t).r).xyz * 2.0 - 1.0;
    vec3 albedo = unpack(a).rgb;
    bool oriented = length(normal) > 1e-3;
    vec3 reflected = vec3(0.0), brightest = vec3(0.0);
    float most = -1.0;
    for (int k = 0; k < light_count(); k++) {
        if ((lights & (1u << k)) == 0u) continue;
        vec3 l;
        // The voxel's normal has no sign: the side facing the light's position (an area light
        // clips its polygon to that side's horizon).
        vec3 n = oriented ? normalize(normal) : vec3(0.0);
        if (dot(n, frame.lights[k].position.xyz - centre) < 0.0) n = -n;
        vec3 irradiance = light_incident(k, centre, n, l);
        float cos_theta = oriented ? abs(dot(n, l)) : 1.0;
        vec3 r = albedo / PI * irradiance * cos_theta;
        reflected += r;
        float lum = dot(r, vec3(1.0));
        if (lum > most) {
            most = lum;
            brightest = l;
        }
    }
    vec3 emission = decode_rgb9e5(imageLoad(voxel_emission, t).r);
    imageStore(target, t, vec4(emission + reflected, 1.0));
    // The lights' bits stay (every gathering texel reads them); a voxel with no normal keeps
    // none of a side (lit_side.glsl).
    vec3 side = oriented ? normalize(normal) * (dot(normal, brightest) < 0.0 ? -1.0 : 1.0) : vec3(-1.0);
    imageStore(lit_side, t, uvec4(pack_lit_side(side, lights)));
}
