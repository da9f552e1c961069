#version 460
// Temporal filtering (Freed 2018 §4.7.2): the radiance volume's level 0 becomes
// mix(previous, injected, factor); factor 1 (the default) keeps only this frame. When the
// volume follows the camera its grid moves, so the previous frame's radiance is reprojected:
// read (trilinearly) where this voxel's centre lay in the previous grid, from a copy of the
// previous level 0. Voxels new to the volume start from this frame alone. `source` is the
// injected radiance, or with several bounces each bounce's result; only the last one of a frame
// blends with the history (push constant `history`).
#define VCT_OWN_PUSH
#include "frame.glsl"

layout(local_size_x = WORKGROUP_3D, local_size_y = WORKGROUP_3D, local_size_z = WORKGROUP_3D) in;
layout(set = 1, binding = 0, rgba16f) uniform readonly image3D injected;
layout(set = 1, binding = 1, rgba16f) uniform writeonly image3D radiance;
layout(set = 1, binding = 2) uniform sampler3D history;
layout(push_constant) uniform Push { uint use_history; } push;
#define OCCUPIED_BINDING 3
#include "listed.glsl"
#define BRICKS_SET 1
#define BRICKS_BINDING 4
#include "bricks.glsl"
// Over the occupied voxels only (render::temporal): level 0 is cleared first.
layout(constant_id = 0) const bool LISTED = false;

void main() {
    ivec3 v;
    ivec3 size = ivec3(frame.voxel_dims.xyz);
    if (!listed_or_dense(LISTED, size, v)) return;
    ivec3 at = stored_at(v);
    vec4 now = imageLoad(injected, at);
    float factor = frame.voxel_grid.w > 0.5 || push.use_history == 0u ? 1.0 : frame.voxel_grid.z;
    if (factor < 1.0) {
        // A sparse grid is fixed (render::Renderer refuses a following one with temporal
        // filtering): the previous frame's voxel is this one, in the same slot.
        if (SPARSE) {
            now = mix(texelFetch(history, at, 0), now, factor);
        } else {
            vec3 previous = (vec3(v) + 0.5 + frame.history_shift.xyz) / vec3(size);
            bool inside = all(greaterThanEqual(previous, vec3(0.0))) && all(lessThanEqual(previous, vec3(1.0)));
            if (inside) now = mix(textureLod(history, previous, 0.0), now, factor);
        }
    }
    imageStore(radiance, at, now);
}
