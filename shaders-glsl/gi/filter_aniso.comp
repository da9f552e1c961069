#version 460
// Anisotropic radiance filtering (Crassin et al. 2011 §5; the thesis' future work): six mip
// chains, one per axis direction. A parent voxel seen along +X composites its two children
// front to back along X (premultiplied: c = c_front + (1 - a_front) c_back), then averages
// the four columns. A wall one voxel thick thus stays opaque when seen face-on, where the
// isotropic 8-child average halves its opacity per level (light leaks and dims).
// Building level 1 from level 0, a lit voxel's light counts only in the directions its lit
// side faces (inject.comp records it): a Lambertian face reflects into its own hemisphere, so
// a wall lit on one side is opaque and dark seen from the other, even where its voxel is the
// only one (the radiance-level counterpart of the thesis' §6 anisotropic voxels).
// A surface lying on a voxel face is written into the voxels of both its sides
// (voxelize/raster.frag: a thin wall keeps its light on its side), and injection lights only the
// one on the light's side; the other holds the surface from behind, dark. Face-on it is hidden
// behind the lit voxel, or hides it from the dark side, which is what it is there for. But the
// chains that see the face edge-on average the two side by side: the far voxel doubled the
// surface's thickness and halved its light (radiance r/2 at opacity 1 in a parent, against r/2
// at 1/2 for a surface inside one layer), so a cone grazing a lit wall gathered half its light.
// So, building level 1, a dark unlit child behind a lit neighbour's face counts as empty in the
// chains along that face: the surface is one voxel thick edge-on wherever it lies. Measured
// (docs/benchmarks.md, "Resolution"): the Cornell spot's floor at 256³, whose walls the fitted
// grid puts on voxel faces, 0.73 -> 0.85 of the reference's indirect light, as on every lattice
// moved by under a voxel; Sponza's three views within 0.0003 FLIP.
// The chains live in one atlas (render::radiance::AtlasLayout): each reads and writes its own
// block, stacked along one axis.
#include "config.h"
#include "lit_side.glsl"
#define OCCUPIED_SET 0
#define OCCUPIED_BINDING 3
#include "listed.glsl"

layout(local_size_x = WORKGROUP_3D, local_size_y = WORKGROUP_3D, local_size_z = WORKGROUP_3D) in;
layout(set = 0, binding = 0, rgba16f) uniform readonly image3D src;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image3D dst;
layout(set = 0, binding = 2, r32ui) uniform readonly uimage3D lit_side;
#define BRICKS_SET 0
#define BRICKS_BINDING 4
#include "bricks.glsl"
// One invocation per occupied texel of the level (as filter.comp).
layout(constant_id = 0) const bool LISTED = false;
// direction: the way the cone travels, 0 +X, 1 -X, 2 +Y, 3 -Y, 4 +Z, 5 -Z; base: src is level 0
// (stored as the per-voxel targets, like lit_side);
// axis: the one the atlas stacks its chains along; src_at, dst_at: where the chain starts along
// it in src and dst (texels); size: the level's extent; slab: a clipmap level's extent along z
// at level 0, the levels stacked along z (0: one grid).
layout(push_constant) uniform Push {
    uint direction;
    uint base;
    uint axis;
    uint src_at;
    uint dst_at;
    uint size_x, size_y, size_z;
    uint slab;
} push;

// The texel of the chain's block at `v` (the chain starting at `at` along the stacking axis).
ivec3 in_block(ivec3 v, uint at) {
    v[push.axis] += int(at);
    return v;
}

// Whether level-0 voxel `v` lies behind a lit face across an axis other than `axis`: a
// neighbour there is lit, and its lit side looks away from `v` along that axis more than along
// any other.
bool behind_lit_face(ivec3 v, int axis) {
    ivec3 grid = stored_grid(imageSize(lit_side));
    for (int k = 1; k <= 2; k++) {
        int b = (axis + k) % 3;
        for (int s = -1; s <= 1; s += 2) {
            ivec3 nb = v;
            nb[b] += s;
            if (any(lessThan(nb, ivec3(0))) || any(greaterThanEqual(nb, grid))) continue;
            if (push.slab != 0u && nb.z / int(push.slab) != v.z / int(push.slab)) continue;  // another level
            uint side = imageLoad(lit_side, stored_at(nb)).r;
            if (!has_lit_side(side)) continue;
            vec3 n = lit_side_of(side), m = abs(n);
            if (n[b] * float(s) > 0.0 && m[b] >= max(m.x, max(m.y, m.z))) return true;
        }
    }
    return false;
}

// The child at `v` as seen by a cone travelling along `dir`: its light only where the light
// leaves towards the cone (against `dir`), with a soft edge for grazing normals. `first`: where
// the parent's first child (its even corner) is stored; its 2³ children share one brick, so
// they lie next to it (bricks.glsl), and the page table is read once a parent.
vec4 child(ivec3 v, vec3 dir, ivec3 first) {
    if (push.base == 0u) return imageLoad(src, in_block(v, push.src_at));
    vec4 c = imageLoad(src, first + (v & 1));
    uint side = imageLoad(lit_side, first + (v & 1)).r;
    // The far voxel of a surface on a voxel face: edge-on it adds no thickness (header).
    if ((side >> 24) == 0u && c.a > 0.0 && max(c.r, max(c.g, c.b)) == 0.0 && behind_lit_face(v, int(push.direction / 2u)))
        return vec4(0.0);
    if (!has_lit_side(side)) return c;
    vec3 n = lit_side_of(side);
    return vec4(c.rgb * clamp(1.0 - 4.0 * dot(n, dir), 0.0, 1.0), c.a);
}

void main() {
    ivec3 v;
    if (!listed_or_dense(LISTED, ivec3(push.size_x, push.size_y, push.size_z), v)) return;
    int axis = int(push.direction / 2u);
    bool positive = (push.direction & 1u) == 0u;
    ivec3 step = ivec3(0);
    step[axis] = 1;
    vec3 dir = vec3(step) * (positive ? 1.0 : -1.0);
    ivec3 u = ivec3(0), w = ivec3(0);
    u[(axis + 1) % 3] = 1;
    w[(axis + 2) % 3] = 1;
    vec4 sum = vec4(0.0);
    ivec3 first = push.base != 0u ? stored_at(2 * v) : ivec3(0);
    for (int i = 0; i < 4; i++) {
        ivec3 base = 2 * v + u * (i & 1) + w * (i >> 1);
        vec4 near = child(positive ? base : base + step, dir, first);
        vec4 far = child(positive ? base + step : base, dir, first);
        sum += near + (1.0 - near.a) * far;
    }
    imageStore(dst, in_block(v, push.dst_at), sum * 0.25);
}
