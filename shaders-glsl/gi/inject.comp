#version 460
// Radiance injection (Freed 2018 §4.3, Algorithm 2): one thread per (strided) shadow-map texel
// reconstructs the lit point from its depth, finds its voxel and writes the light that voxel
// reflects: albedo/pi * E * |n.l| (Lambert, n the voxel's averaged normal), plus emission.
// The value is computed at the voxel centre, so every texel that hits a voxel writes the same
// value: the result does not depend on which write lands last. It also records the lit side:
// the voxel normal turned towards the light, which the anisotropic filter uses to keep a lit
// face dark when seen from behind (a Lambertian face reflects into its own hemisphere only),
// and around which the voxel-space bounce gathers.
// With several lights the pass runs once per light over its own shadow-map layers; the voxel a
// texel finds gets the light of every light (this one seen by its texel, each other one where
// its shadow map sees the voxel's lit face), so each write is the same whichever light's texel
// lands last, and the lit side faces the light that gives the most.
#define VCT_OWN_PUSH
#include "frame.glsl"
#include "light.glsl"
#include "rgb9e5.glsl"

layout(local_size_x = WORKGROUP_2D, local_size_y = WORKGROUP_2D) in;
// One layer, or a point light's six cube faces (the dispatch's z).
layout(set = 1, binding = 0) uniform sampler2DArray shadow_depth;
layout(set = 1, binding = 1, r32ui) uniform readonly uimage3D voxel_albedo;
layout(set = 1, binding = 2, r32ui) uniform readonly uimage3D voxel_normal;
layout(set = 1, binding = 3, r32ui) uniform readonly uimage3D voxel_emission;
layout(set = 1, binding = 4, rgba16f) uniform writeonly image3D target;
layout(set = 1, binding = 5, r32ui) uniform writeonly uimage3D lit_side;
#define BRICKS_SET 1
#define BRICKS_BINDING 6
#include "bricks.glsl"
// One thread per `stride` x `stride` block of texels, reading its centre texel (render::inject:
// the stride keeps INJECT_TEXELS_PER_VOXEL texels per voxel where the map has more).
layout(push_constant) uniform Push { uint stride; uint light; } push;

const float PI = 3.14159265358979;

vec4 unpack(uint p) {
    return vec4(float(p & 0xffu), float((p >> 8) & 0xffu), float((p >> 16) & 0xffu), float(p >> 24)) / 255.0;
}

// Whether light `k`'s shadow map sees point `q` (one texel, depth compared).
bool sees(int k, vec3 q) {
    int layer;
    vec4 clip = shadow_view_proj(k, q, layer) * vec4(q, 1.0);
    if (clip.w <= 0.0) return false;
    vec3 ndc = clip.xyz / clip.w;
    vec2 uv = ndc.xy * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) return false;
    ivec2 size = textureSize(shadow_depth, 0).xy;
    return ndc.z <= texelFetch(shadow_depth, ivec3(ivec2(uv * vec2(size)), layer), 0).r + 1e-4;
}

void main() {
    int stride = int(push.stride);
    int j = int(push.light);
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy) * stride + stride / 2;
    ivec2 size = textureSize(shadow_depth, 0).xy;
    int layer = int(frame.lights[j].cone.w) + int(gl_GlobalInvocationID.z);
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
    vec3 l_dir = uint(li.position.w) == LIGHT_DIRECTIONAL ? li.direction.xyz : normalize(p - li.position.xyz);
    float step = 0.25 * frame.voxel_origin.w;
    ivec3 v = ivec3(-1), t = ivec3(0);  // the voxel, and where it is stored
    uint a = 0u;
    // In voxel units, from a quarter voxel before the point, one voxel at a time: a step no
    // longer than a voxel cannot jump over a wall's voxel layer. Mostly two loads: the surface's
    // voxel and the empty one before it.
    vec3 g = world_to_voxel(p) - l_dir * 0.25;
    for (int i = 0; i <= INJECT_SEARCH_VOXELS; i++, g -= l_dir) {
        ivec3 u = ivec3(floor(g));
        if (!voxel_in_grid(u)) break;
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
        v = ivec3(floor(world_to_voxel(p + l_dir * step)));
        if (!voxel_in_grid(v)) return;
        t = stored_at(v);
        a = imageLoad(voxel_albedo, t).r;
        if ((a >> 24) == 0u) return;
    }
    vec3 centre = frame.voxel_origin.xyz + (vec3(v) + 0.5) * frame.voxel_origin.w;
    vec3 normal = unpack(imageLoad(voxel_normal, t).r).xyz * 2.0 - 1.0;
    vec3 albedo = unpack(a).rgb;
    bool oriented = length(normal) > 1e-3;
    vec3 reflected = vec3(0.0), brightest = vec3(0.0);
    float most = -1.0;
    for (int k = 0; k < light_count(); k++) {
        vec3 l;
        vec3 irradiance = light_incident(k, centre, l);
        // Another light: where its shadow map sees the voxel's face towards it (moved out of the
        // surface by most of a voxel, clear of the shadow map's own bias).
        vec3 side = oriented ? normalize(normal) * (dot(normal, l) < 0.0 ? -1.0 : 1.0) : l;
        if (k != j && !sees(k, centre + side * 0.75 * frame.voxel_origin.w)) continue;
        float cos_theta = oriented ? abs(dot(normalize(normal), l)) : 1.0;
        vec3 r = albedo / PI * irradiance * cos_theta;
        reflected += r;
        float lum = dot(r, vec3(1.0));
        if (lum > most) {
            most = lum;
            brightest = l;
        }
    }
    vec3 l = brightest;
    vec3 emission = decode_rgb9e5(imageLoad(voxel_emission, t).r);
    imageStore(target, t, vec4(emission + reflected, 1.0));
    if (length(normal) > 1e-3) {
        vec3 side = normalize(normal) * (dot(normal, l) < 0.0 ? -1.0 : 1.0);
        uvec3 q = uvec3(round((side * 0.5 + 0.5) * 255.0));
        imageStore(lit_side, t, uvec4(q.x | (q.y << 8) | (q.z << 16) | (1u << 24)));
    }
}
