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
// chains that see the face edge-on would average the two side by side: the far voxel would
// double the surface's thickness and halve its light (radiance r/2 at opacity 1 in a parent,
// against r/2 at 1/2 for a surface inside one layer), so a cone grazing a lit wall would gather
// half its light.
// So, building level 1, a dark unlit child behind a lit neighbour's face counts as empty in the
// chains along that face: the surface is one voxel thick edge-on wherever it lies. Measured
// (docs/design/filtering.md): the Cornell spot's floor at 256³, whose walls the fitted
// grid puts on voxel faces, 0.73 -> 0.85 of the reference's indirect light, as on every lattice
// moved by under a voxel; Sponza's three views within 0.0003 FLIP.
// Level 1 builds all six chains in one invocation a parent: each child is read, and searched
// for a lit face beside it, once rather than once a chain (searched once a chain, the pass takes
// five times as long on Sponza; docs/design/filtering.md).
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
// (stored as the per-voxel targets, like lit_side), and every direction is built, direction d's
// block starting at base_at[d] (direction and dst_at unused);
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
    uint base_at[6];
} push;

// The texel of the chain's block at `v` (the chain starting at `at` along the stacking axis).
ivec3 in_block(ivec3 v, uint at) {
    v[push.axis] += int(at);
    return v;
}

// The axes across which level-0 voxel `v` lies behind a lit face (bit b: across axis b): a
// neighbour there is lit, and its lit side looks away from `v` along that axis more than along
// any other.
uint lit_faces_beside(ivec3 v) {
    ivec3 grid = stored_grid(imageSize(lit_side));
    uint across = 0u;
    for (int b = 0; b < 3; b++) {
        for (int s = -1; s <= 1; s += 2) {
            ivec3 nb = v;
            nb[b] += s;
            if (any(lessThan(nb, ivec3(0))) || any(greaterThanEqual(nb, grid))) continue;
            if (push.slab != 0u && nb.z / int(push.slab) != v.z / int(push.slab)) continue;  // another level
            uint side = imageLoad(lit_side, stored_at(nb)).r;
            if (!has_lit_side(side)) continue;
            vec3 n = lit_side_of(side), m = abs(n);
            if (n[b] * float(s) > 0.0 && m[b] >= max(m.x, max(m.y, m.z))) across |= 1u << b;
        }
    }
    return across;
}

// One child of a level-1 parent: its light, lit side, and the axes whose chains leave it out
// (the far voxel of a surface on a voxel face: edge-on it adds no thickness; header).
struct Child {
    vec4 c;
    uint side;
    uint empty_along;  // bit a: empty in the chains along axis a
};

// Child `k` (offset (k & 1, k >> 1 & 1, k >> 2)) of parent `v`, whose first child (its even
// corner) is stored at `first`: its 2³ children share one brick, so they lie next to it
// (bricks.glsl), and the page table is read once a parent.
Child base_child(ivec3 v, int k, ivec3 first) {
    ivec3 o = ivec3(k & 1, (k >> 1) & 1, k >> 2);
    Child ch;
    ch.c = imageLoad(src, first + o);
    ch.side = imageLoad(lit_side, first + o).r;
    ch.empty_along = 0u;
    if ((ch.side >> 24) == 0u && ch.c.a > 0.0 && max(ch.c.r, max(ch.c.g, ch.c.b)) == 0.0) {
        // Behind a lit face across axis b: empty in the chains along the two other axes.
        uint across = lit_faces_beside(2 * v + o);
        for (int a = 0; a < 3; a++)
            if ((across & ~(1u << a)) != 0u) ch.empty_along |= 1u << a;
    }
    return ch;
}

// A level-1 child as seen by a cone travelling along `dir` (on `axis`): its light only where the
// light leaves towards the cone (against `dir`), with a soft edge for grazing normals.
vec4 seen(Child ch, int axis, vec3 dir) {
    if ((ch.empty_along & (1u << axis)) != 0u) return vec4(0.0);
    if (!has_lit_side(ch.side)) return ch.c;
    vec3 n = lit_side_of(ch.side);
    return vec4(ch.c.rgb * clamp(1.0 - 4.0 * dot(n, dir), 0.0, 1.0), ch.c.a);
}

// The chain travelling along `direction`: its axis, its unit direction, its step between a
// column's two children, and the two axes its 2 x 2 columns spread over.
void chain_frame(int direction, out int axis, out bool positive, out vec3 dir, out ivec3 step, out ivec3 u,
                 out ivec3 w) {
    axis = direction / 2;
    positive = (direction & 1) == 0;
    step = ivec3(0);
    step[axis] = 1;
    dir = vec3(step) * (positive ? 1.0 : -1.0);
    u = ivec3(0);
    w = ivec3(0);
    u[(axis + 1) % 3] = 1;
    w[(axis + 2) % 3] = 1;
}

// Child index of offset `o` in the parent's 2³.
int index_of(ivec3 o) {
    return o.x + 2 * o.y + 4 * o.z;
}

// Level 1 of all six chains from level 0.
void filter_base(ivec3 v) {
    ivec3 first = stored_at(2 * v);
    Child children[8];
    for (int k = 0; k < 8; k++) children[k] = base_child(v, k, first);
    for (int d = 0; d < 6; d++) {
        int axis;
        bool positive;
        vec3 dir;
        ivec3 step, u, w;
        chain_frame(d, axis, positive, dir, step, u, w);
        vec4 sum = vec4(0.0);
        for (int i = 0; i < 4; i++) {
            ivec3 base = u * (i & 1) + w * (i >> 1);
            vec4 near = seen(children[index_of(positive ? base : base + step)], axis, dir);
            vec4 far = seen(children[index_of(positive ? base + step : base)], axis, dir);
            sum += near + (1.0 - near.a) * far;
        }
        imageStore(dst, in_block(v, push.base_at[d]), sum * 0.25);
    }
}

void main() {
    ivec3 v;
    if (!listed_or_dense(LISTED, ivec3(push.size_x, push.size_y, push.size_z), v)) return;
    if (push.base != 0u) {
        filter_base(v);
        return;
    }
    int axis;
    bool positive;
    vec3 dir;
    ivec3 step, u, w;
    chain_frame(int(push.direction), axis, positive, dir, step, u, w);
    vec4 sum = vec4(0.0);
    for (int i = 0; i < 4; i++) {
        ivec3 base = 2 * v + u * (i & 1) + w * (i >> 1);
        vec4 near = imageLoad(src, in_block(positive ? base : base + step, push.src_at));
        vec4 far = imageLoad(src, in_block(positive ? base + step : base, push.src_at));
        sum += near + (1.0 - near.a) * far;
    }
    imageStore(dst, in_block(v, push.dst_at), sum * 0.25);
}
