#version 460
// Radiance injection, step 1 of 2 (Freed 2018 §4.3, Algorithm 2): one thread per (strided)
// shadow-map texel reconstructs the lit point from its depth, finds its voxel and marks it lit
// by this light: the light's bit in the voxel's lit_side word (bits 24..31, an atomic or).
// Step 2 (gi/resolve.comp) then runs once per occupied voxel and writes the light of every light
// whose bit is set. The value depends on the voxel and its bits alone (it is computed at the
// voxel centre), so which voxels a light lights does not depend on the other lights, and the
// result not on the order texels land. Measured (lavapipe, 64³, the images the same): the
// Cornell spot's injection (its 2048² map's 4.2M texels) takes 202-206 ms lighting at every
// texel, as Algorithm 2 does, and 148-150 ms marking; with a point light added, where lighting
// at every texel needs a second pass over every texel to gather the marked lights' light,
// 699-702 against 261-263 ms. Hoisting the per-texel matrix inverse to the host would save
// 4 ms more, not worth its uniforms.
#define VCT_OWN_PUSH
#include "frame.glsl"

layout(local_size_x = WORKGROUP_2D, local_size_y = WORKGROUP_2D) in;
// One layer, or a point or area light's six cube faces (one dispatch a layer: push.layer).
layout(set = 1, binding = 0) uniform sampler2DArray shadow_depth;
layout(set = 1, binding = 1, r32ui) uniform readonly uimage3D voxel_albedo;
layout(set = 1, binding = 2, r32ui) uniform uimage3D lit_side;
#define BRICKS_SET 1
#define BRICKS_BINDING 3
#include "bricks.glsl"
// One thread per `stride` x `stride` block of texels, reading its centre texel (render::inject:
// the stride keeps INJECT_TEXELS_PER_VOXEL texels per voxel where the map has more).
layout(push_constant) uniform Push { uint stride; uint light; uint layer; } push;

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

// Marks the voxel of lit point `p` in level `level` (0: the grid) lit by light `j`.
void inject_level(vec3 p, vec3 l_dir, int j, int level) {
    float scale = clip_on() ? frame.clip_levels[level].w : 1.0;
    ivec3 t = ivec3(0);  // where the voxel is stored
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
            t = at;
            a = b;
        } else if ((a >> 24) != 0u) {
            break;
        }
    }
    if ((a >> 24) == 0u) {
        ivec3 v = ivec3(floor(level_texel(world_to_grid(p) + l_dir * 0.25 * scale, level)));
        if (!in_level(v, level)) return;
        t = stored_at(v);
        a = imageLoad(voxel_albedo, t).r;
        if ((a >> 24) == 0u) return;
    }
    imageAtomicOr(lit_side, t, 1u << (24 + j));
}
