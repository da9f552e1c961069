// Per-frame uniforms and scene bindings (set 0), mirrored by `scene::gpu::FrameUniforms`
// and `scene::gpu::MaterialGpu` in Rust. std140: only mat4 and vec4 members.
#ifndef VCT_FRAME_GLSL
#define VCT_FRAME_GLSL
#include "config.h"
#include "warp.glsl"

// One light (scene::gpu::LightGpu).
struct LightData {
    vec4 position;   // xyz: spot or point position; w: LIGHT_*
    vec4 direction;  // xyz: the way light travels (unit)
    vec4 color;      // rgb: intensity (W/sr; spot, point) or irradiance (W/m^2; directional)
    vec4 cone;       // x: inner, y: outer half-angle (radians); z: shadow texel size (uv); w: first shadow layer
    vec4 half_u;     // xyz: an area light's half edges (corners: position ± half_u ± half_v; its light
    vec4 half_v;     // leaves on the side half_u x half_v points to, which `direction` holds)
};

layout(set = 0, binding = 0) uniform FrameUniforms {
    mat4 view_proj;
    mat4 inv_view_proj;
    vec4 camera_pos;    // xyz
    vec4 viewport;      // xy: render size in pixels
    vec4 voxel_origin;  // xyz: voxel grid origin (world); w: voxel size
    vec4 voxel_grid;    // x: longest axis N; y: radiance mip levels; z: temporal blend factor (1 = off); w: first frame
    vec4 cone;          // x: max steps; y: bias along the normal (voxels); z: start distance (voxels); w: LOD offset
    vec4 cone_model;    // x: surface cones in `cones`; y: step (of a texel); z: CONE_FLAG_*; w: bounce cones (from MAX_CONES)
    vec4 view;          // x: VIEW_*; y: radiance level shown; z: GI on (1) or off (0); w: the cone
                        // set's turn phase (a share of a turn added at every pixel)
    vec4 history_shift; // xyz: this frame's grid origin in the previous frame's grid (voxels)
    vec4 voxel_dims;    // xyz: voxels along each axis
    vec4 aniso_atlas;   // the directional chains' atlas (render::radiance::AtlasLayout): x: the axis they are
                        // stacked along; y: one chain's pitch, z: the atlas' length, both over a chain's length
    vec4 light_count;   // x: lights in `lights`
    LightData lights[MAX_LIGHTS];
    mat4 light_layers[MAX_SHADOW_LAYERS]; // each shadow-map layer's world-to-clip (a point light's six
                                          // cube faces: +x, -x, +y, -y, +z, -z)
    mat4 previous_view_proj; // the previous frame's world-to-clip (screen-space accumulation)
    vec4 gi_jitter;          // xy: the pixel of each GI_SCALE block the diffuse cones trace this
                             // frame; z: a history to accumulate with (1) or none (0);
                             // w: the camera moved since the last frame (1)
    vec4 voxel_warp;         // the grid's warp (common/warp.glsl): xyz centre, w end slope (1: none)
    mat4 voxel_warp_proj;    // a perspective warp's grid fraction to texture fraction (homogeneous)
    mat4 voxel_warp_unproj;  // and back
    vec4 clip;               // a clipmap (voxel::clipmap): x levels (0: none), y a level's side (texels),
                             // z the blend band (of a level's side)
    vec4 clip_levels[MAX_CLIP_LEVELS]; // each level's minimum corner (xyz, voxels of level 0 from
                                       // voxel_origin) and its voxel over level 0's (w)
    vec4 clip_scene[2];      // the scene's bounds (minimum, maximum; voxels of level 0 from voxel_origin)
} frame;

// Whether the pipeline was built for a clipmap (voxel::clipmap): off, every clip_on() is false at
// compile time and the clipmap's code is compiled out.
layout(constant_id = CLIP_CONSTANT_ID) const bool CLIPPED = false;

// A clipmap's levels are stacked along z, level k in texels k N .. (k + 1) N; level k's voxel
// is 2^k of level 0's, and "grid coordinates" are voxels of level 0 from its corner, unbounded
// (the coarser levels reach beyond level 0 on every side).
bool clip_on() {
    return CLIPPED && frame.clip.x > 0.5;
}

int clip_count() {
    return int(frame.clip.x);
}

// How far grid point `g` lies inside level k's box (voxels of level 0; negative outside), from
// all its faces, or (`closed`) only from its closed ones: an open face, half a voxel of the level
// or more beyond the scene (voxel::clipmap::Clipmap::open), has nothing beyond it in any level,
// so a cone sample near it stays in level k and does not blend into the next.
float clip_inside(vec3 g, int k, bool closed) {
    vec4 l = frame.clip_levels[k];
    vec3 top = l.xyz + l.w * frame.clip.y, slack = vec3(0.499 * l.w);
    vec3 lo = g - l.xyz, hi = top - g;
    if (closed) {
        lo = mix(lo, vec3(1e30), lessThanEqual(l.xyz, frame.clip_scene[0].xyz - slack));
        hi = mix(hi, vec3(1e30), greaterThanEqual(top, frame.clip_scene[1].xyz + slack));
    }
    return min(min(min(lo.x, lo.y), lo.z), min(min(hi.x, hi.y), hi.z));
}

// The finest level whose box holds grid point `g` (the coarsest if none does).
int clip_level_of(vec3 g) {
    int k = 0;
    while (k + 1 < clip_count() && clip_inside(g, k, false) < 0.0) k++;
    return k;
}

// Grid point `g` in level k's slab of the stack (texel coordinates).
vec3 clip_texel(vec3 g, int k) {
    vec4 l = frame.clip_levels[k];
    return (g - l.xyz) / l.w + vec3(0.0, 0.0, float(k) * frame.clip.y);
}

// Whether texel `v` lies in level k's slab.
bool clip_in_level(ivec3 v, int k) {
    int n = int(frame.clip.y);
    return all(greaterThanEqual(v, ivec3(0, 0, k * n))) && all(lessThan(v, ivec3(n, n, (k + 1) * n)));
}

// The extent a cone's march fraction is of: the grid's, or a clipmap's level 0.
vec3 march_dims() {
    return clip_on() ? vec3(frame.clip.y) : frame.voxel_dims.xyz;
}

// World position to unwarped grid coordinates (voxels of the even grid).
vec3 world_to_grid(vec3 p) {
    return (p - frame.voxel_origin.xyz) / frame.voxel_origin.w;
}

// Grid coordinates to texel coordinates (texel v spans [v, v + 1)), through the warp if any; in
// a clipmap, in the finest level that holds them.
vec3 grid_to_texel(vec3 g) {
    if (clip_on()) return clip_texel(g, clip_level_of(g));
    if (!warp_on(frame.voxel_warp)) return g;
    return warp_to_texture(g / frame.voxel_dims.xyz, frame.voxel_warp, frame.voxel_warp_proj) * frame.voxel_dims.xyz;
}

// World position to texel coordinates.
vec3 world_to_voxel(vec3 p) {
    return grid_to_texel(world_to_grid(p));
}

// World position to normalized texture coordinates [0, 1]^3.
vec3 world_to_uvw(vec3 p) {
    return world_to_voxel(p) / frame.voxel_dims.xyz;
}

// World position to the unwarped grid fraction [0, 1]^3 a cone marches in (common/cone.glsl
// warps each sample).
vec3 world_to_march(vec3 p) {
    return world_to_grid(p) / march_dims();
}

// The grid fraction of texel `v`'s centre.
vec3 texel_centre_march(ivec3 v) {
    if (clip_on()) {
        int k = v.z / int(frame.clip.y);
        vec4 l = frame.clip_levels[k];
        return (l.xyz + (vec3(v - ivec3(0, 0, k * int(frame.clip.y))) + 0.5) * l.w) / frame.clip.y;
    }
    vec3 w = (vec3(v) + 0.5) / frame.voxel_dims.xyz;
    return warp_on(frame.voxel_warp) ? warp_to_grid(w, frame.voxel_warp, frame.voxel_warp_unproj) : w;
}

// The world position of texel `v`'s centre.
vec3 texel_centre_world(ivec3 v) {
    return frame.voxel_origin.xyz + texel_centre_march(v) * march_dims() * frame.voxel_origin.w;
}

// Texels per grid voxel where they are finest (1 unwarped).
float warp_peak() {
    return warp_peak_slope(frame.voxel_warp);
}

// Whether voxel `v` lies inside the grid.
bool voxel_in_grid(ivec3 v) {
    return all(greaterThanEqual(v, ivec3(0))) && all(lessThan(v, ivec3(frame.voxel_dims.xyz)));
}

struct Material {
    vec4 albedo;    // rgb: linear albedo; a: metallic
    vec4 emissive;  // rgb: emitted radiance; a: roughness
    vec4 specular;  // rgb: F0 of the dielectric lobe (zero: no specular lobe)
    uvec4 tex;      // x: has albedo texture, y: has normal texture (HAS_TEXTURE / NO_TEXTURE);
                    // z: its emission reaches the scene through area lights, not its voxels
};

layout(set = 0, binding = 1, std430) readonly buffer Materials { Material materials[]; };

// The reflectance a material's voxels carry (`albedo`: its texture applied): the diffuse albedo
// plus the specular lobe's reflectance at normal incidence (F0), as direct shading reflects
// both. A voxel spreads what it reflects over every direction: a glossy surface's light is
// kept, in the wrong directions, instead of being lost (the classic Cornell box's boxes have
// Kd 0 and Ks 0.725: with the diffuse albedo alone their voxels would reflect nothing;
// docs/design/injection.md).
vec3 voxel_albedo_of(Material m, vec3 albedo) {
    float metallic = m.albedo.a;
    return min(albedo * (1.0 - metallic) + mix(m.specular.rgb, albedo, metallic), vec3(1.0));
}

// The radiance a material's voxels emit: none where area lights carry it (scene::area).
vec3 voxel_emission_of(Material m) {
    return m.tex.z != 0u ? vec3(0.0) : m.emissive.rgb;
}

// The diffuse cone set (scene::cones::ConeGpu): a cosine-weighted quadrature of the hemisphere.
struct Cone {
    vec4 dir_weight;  // xyz: direction in the tangent frame (z along the normal); w: weight
    vec4 shape;       // x: tan(half aperture)
};

layout(set = 0, binding = 2, std430) readonly buffer Cones { Cone cones[]; };

// The drawn material (passes that push something else define VCT_OWN_PUSH first).
#ifndef VCT_OWN_PUSH
layout(push_constant) uniform Push { uint material; } push;
#endif

#endif
