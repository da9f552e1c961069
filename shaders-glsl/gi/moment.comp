#version 460
// The radiance moment's level 1 (common/cone.glsl, CONE_FLAG_FACING): the average over a texel's
// eight voxels of the luminance of the light each reflects times its lit side (the voxel normal
// turned towards the light, or the side it gathered bounced light on), and of its whole
// luminance. Emitted light leaves to every side and adds to the luminance only. The mip filter
// then averages it like the radiance. The moment has no level 0: the cones read it from level 1
// (images within FLIP 0.0001-0.003 of those with a level 0 blended in, docs/design/filtering.md),
// and a level 0 would take as much memory as the radiance's.
#include "config.h"
#include "rgb9e5.glsl"
#include "lit_side.glsl"
#define OCCUPIED_SET 0
#define OCCUPIED_BINDING 4
#include "listed.glsl"

layout(local_size_x = WORKGROUP_3D, local_size_y = WORKGROUP_3D, local_size_z = WORKGROUP_3D) in;
layout(set = 0, binding = 0, rgba16f) uniform readonly image3D radiance;
layout(set = 0, binding = 1, r32ui) uniform readonly uimage3D lit_side;
layout(set = 0, binding = 2, r32ui) uniform readonly uimage3D voxel_emission;
layout(set = 0, binding = 3, rgba16f) uniform writeonly image3D moment;
#define BRICKS_SET 0
#define BRICKS_BINDING 5
#include "bricks.glsl"
// One invocation per occupied texel of level 1 (the rest of the level is empty).
layout(constant_id = 0) const bool LISTED = false;

const vec3 LUMA = vec3(0.2126, 0.7152, 0.0722);

// Voxel `v`'s moment: xyz the luminance it reflects times its lit side, w its luminance.
vec4 voxel_moment(ivec3 v) {
    float total = dot(imageLoad(radiance, stored_at(v)).rgb, LUMA);
    uint side = imageLoad(lit_side, stored_at(v)).r;
    vec3 m = vec3(0.0);
    if (has_lit_side(side)) {
        vec3 n = lit_side_of(side);
        float emitted = dot(decode_rgb9e5(imageLoad(voxel_emission, stored_at(v)).r), LUMA);
        m = normalize(n) * max(total - emitted, 0.0);
    }
    return vec4(m, total);
}

void main() {
    ivec3 v;
    if (!listed_or_dense(LISTED, imageSize(moment), v)) return;
    vec4 sum = vec4(0.0);
    for (int i = 0; i < 8; i++) {
        sum += voxel_moment(2 * v + ivec3(i & 1, (i >> 1) & 1, i >> 2));
    }
    imageStore(moment, v, sum * 0.125);
}
