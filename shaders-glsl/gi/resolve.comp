#version 460
// Radiance injection, step 2 of 2 (Freed 2018 §4.3: the "transfer" of occlusion, and the light
// of Algorithm 2): one invocation per voxel the voxelizers listed (the target cleared first), or
// per voxel of the grid, writes its emitted radiance and opacity 1 for an occupied voxel (0
// elsewhere), plus the direct light it reflects from every light whose texels found it (step 1,
// gi/inject.comp, set their bits in lit_side): albedo/pi * E * |n.l| (Lambert, n the voxel's
// averaged normal, E at the voxel centre). It also records the lit side: the voxel normal
// turned towards the light that gives the most, which the anisotropic filter uses to keep a lit
// face dark when seen from behind (a Lambertian face reflects into its own hemisphere only),
// and around which the voxel-space bounce gathers.
#define VCT_OWN_PUSH
#include "frame.glsl"
// Whether any of the scene's lights is an area light; without one the polygon's code is compiled
// out of the light loop below (common/light.glsl).
layout(constant_id = 3) const bool AREA_LIGHTS = true;
#define VCT_AREA_LIGHTS AREA_LIGHTS
#include "light.glsl"
layout(set = 1, binding = 7) uniform sampler2DArrayShadow shadow_map;
#include "shadow.glsl"
#include "rgb9e5.glsl"
#include "lit_side.glsl"
#define OCCUPIED_SET 1
#define OCCUPIED_BINDING 3
#include "listed.glsl"

layout(local_size_x = WORKGROUP_3D, local_size_y = WORKGROUP_3D, local_size_z = WORKGROUP_3D) in;
layout(set = 1, binding = 0, r32ui) uniform readonly uimage3D voxel_albedo;
layout(set = 1, binding = 1, r32ui) uniform readonly uimage3D voxel_emission;
layout(set = 1, binding = 2, rgba16f) uniform writeonly image3D target;
layout(set = 1, binding = 5, r32ui) uniform readonly uimage3D voxel_normal;
layout(set = 1, binding = 6, r32ui) uniform uimage3D lit_side;
#define BRICKS_SET 1
#define BRICKS_BINDING 4
#include "bricks.glsl"

// Over the occupied voxels the voxelizers listed (the rest of the target cleared), or every voxel.
layout(constant_id = 0) const bool LISTED = false;
// Injection from the voxels (GiSettings::injection): no texels marked the voxel; it looks its
// lit side up in each light's shadow map itself.
layout(constant_id = 4) const bool FROM_VOXELS = false;

const float PI = 3.14159265358979;

// Whether the voxel next to `v` along the main axis of `side` (towards the light) is occupied,
// in the same grid or clipmap level.
bool first_toward_light_is_not(ivec3 v, vec3 side) {
    vec3 a = abs(side);
    ivec3 step = a.x >= a.y && a.x >= a.z ? ivec3(sign(side.x), 0, 0) : (a.y >= a.z ? ivec3(0, sign(side.y), 0) : ivec3(0, 0, sign(side.z)));
    ivec3 u = v + step;
    bool inside = clip_on() ? clip_in_level(u, v.z / int(frame.clip.y)) : voxel_in_grid(u);
    return inside && (imageLoad(voxel_albedo, stored_at(u)).r >> 24) != 0u;
}

void main() {
    ivec3 v;
    if (!listed_or_dense(LISTED, stored_grid(imageSize(target)), v)) return;
    // Sparse storage: a voxel outside every brick is the empty slot, which this leaves zero.
    ivec3 t = stored_at(v);
    uint a = imageLoad(voxel_albedo, t).r;
    if ((a >> 24) == 0u) {
        imageStore(target, t, vec4(0.0));
        return;
    }
    vec3 emission = decode_rgb9e5(imageLoad(voxel_emission, t).r);
    // From the voxels every light is a candidate until its lookup fails.
    uint lights = FROM_VOXELS ? (1u << uint(light_count())) - 1u : imageLoad(lit_side, t).r >> 24;
    // The lights' loop runs for no voxel of a SIMD group that none lit (a loop, not a branch: a
    // CPU driver runs a branch for every lane when any lane takes it).
    int count = lights != 0u ? light_count() : 0;
    vec3 normal = unpackUnorm4x8(imageLoad(voxel_normal, t).r).xyz * 2.0 - 1.0;
    vec3 albedo = unpackUnorm4x8(a).rgb;
    vec3 centre = texel_centre_world(v);
    bool oriented = length(normal) > 1e-3;
    vec3 unit = oriented ? normalize(normal) : vec3(0.0);
    vec3 reflected = vec3(0.0), brightest = vec3(0.0);
    float most = -1.0;
    for (int k = 0; k < count; k++) {
        if ((lights & (1u << k)) == 0u) continue;
        vec3 l;
        // The voxel's normal has no sign: the side facing the light's position (an area light
        // clips its polygon to that side's horizon).
        vec3 n = unit;
        if (dot(n, frame.lights[k].position.xyz - centre) < 0.0) n = -n;
        vec3 irradiance = light_incident(k, centre, n, l);
        float cos_theta = oriented ? abs(dot(n, l)) : 1.0;
        if (FROM_VOXELS) {
            // The voxel's surface on the side facing the light, half a voxel (of its clipmap level)
            // out from its centre (a voxel without a normal: its centre), in the light's shadow
            // map. Texels as wide as a voxel only: a warped texel, up to four grid voxels deep,
            // does not say where in it its surface lies (render::Renderer::new injects a warped
            // grid from the texels).
            vec3 side = oriented ? (dot(n, l) < 0.0 ? -n : n) : l;
            // Only the first occupied voxel met from the light, as the texels' walk finds it: a
            // wall on a voxel boundary lies in the voxels of both its sides, and the far one's
            // lit side is the wall's own lit face (the stability bench's two rooms: 770 voxels of
            // the dark room lit without this).
            if (oriented && first_toward_light_is_not(v, side)) {
                lights &= ~(1u << k);
                continue;
            }
            float half_voxel = 0.5 * frame.voxel_origin.w * (clip_on() ? frame.clip_levels[v.z / int(frame.clip.y)].w : 1.0);
            float seen = shadow_factor(k, centre + (oriented ? side * half_voxel : vec3(0.0)), side);
            if (seen <= 0.0) {
                lights &= ~(1u << k);
                continue;
            }
            irradiance *= seen;
        }
        vec3 r = albedo / PI * irradiance * cos_theta;
        reflected += r;
        float lum = dot(r, vec3(1.0));
        if (lum > most) {
            most = lum;
            brightest = l;
        }
    }
    imageStore(target, t, vec4(emission + reflected, 1.0));
    // The lights' bits stay; a voxel with no normal keeps none of a side (lit_side.glsl).
    if (lights != 0u) {
        vec3 side = oriented ? unit * (dot(normal, brightest) < 0.0 ? -1.0 : 1.0) : vec3(-1.0);
        imageStore(lit_side, t, uvec4(pack_lit_side(side, lights)));
    }
}
