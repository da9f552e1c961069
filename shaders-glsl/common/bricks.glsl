// Sparse voxel storage (voxel::bricks; the page table and brick pool of GigaVoxels, Crassin
// 2011 §4, and of the GRAPP 2020 sparse-texture paper's software path): the grid is cut into
// bricks of BRICK_SIZE³ voxels, a page table holds one entry per brick (0: no brick, else its
// slot in the pool), and each per-voxel texture is a pool atlas of slots. Slot 0 is a brick
// that stays empty: a voxel without a brick reads zero there. The voxelizers give a brick a
// slot on the first write into it (`claim_brick`), so the pool holds exactly the bricks that
// hold an occupied voxel. With SPARSE off (dense storage) a voxel is stored at its own
// coordinate and the table is not read. The includer defines BRICKS_SET and BRICKS_BINDING,
// and BRICKS_CLAIM where it allocates.
#ifndef VCT_BRICKS_GLSL
#define VCT_BRICKS_GLSL
#include "config.h"

layout(constant_id = 1) const bool SPARSE = false;
// Resident storage (Vulkan sparse residency): stored as dense, but memory only in the blocks of
// the bricks the census asked for, which the table marks with 1. The voxelizers refuse a write
// outside them and count its brick in `next` (an error for the frame) instead of losing it to
// an unbound block, where writes vanish.
layout(constant_id = 2) const bool RESIDENT = false;

layout(set = BRICKS_SET, binding = BRICKS_BINDING, std430)
#ifdef BRICKS_CLAIM
    coherent volatile
#else
    restrict readonly
#endif
    buffer Bricks {
    uint next;       // the next slot to give out (1 after the clear; slot 0 is the empty brick)
    uint capacity;   // slots in the pool, the empty one included
    uint pool_x;     // log2 of the pool atlas' slots along x (powers of two: a slot's place is
    uint pool_y;     // shifts and masks, not the integer divisions a CPU driver runs lane by lane)
    uint count_x;    // bricks along each axis of the grid
    uint count_y;
    uint count_z;
    uint stalled;    // claims that gave up waiting (BRICK_CLAIM_ITERATIONS): reported as an error
    uint page[];     // per brick, x fastest: 0 none, BRICK_LOCKED being claimed, BRICK_REFUSED pool full, else its slot
} bricks;

uint brick_index(ivec3 v) {
    uvec3 b = uvec3(v) >> BRICK_SHIFT;
    return (b.z * bricks.count_y + b.y) * bricks.count_x + b.x;
}

// Where slot `s` holds voxel `v` of its brick.
ivec3 slot_texel(uint s, ivec3 v) {
    uint x = bricks.pool_x, y = bricks.pool_y;
    uvec3 o = uvec3(s & ((1u << x) - 1u), (s >> x) & ((1u << y) - 1u), s >> (x + y));
    return ivec3(o << BRICK_SHIFT) + (v & ivec3(BRICK_SIZE - 1));
}

// The grid's extent, from a texture stored in this layout (`size`: its imageSize).
ivec3 stored_grid(ivec3 size) {
    return SPARSE ? ivec3(bricks.count_x, bricks.count_y, bricks.count_z) << BRICK_SHIFT : size;
}

// The texel that stores voxel `v` (inside the grid): its own coordinate when dense, in its
// brick's slot when sparse, or in the empty slot 0 where no brick holds it.
ivec3 stored_at(ivec3 v) {
    if (!SPARSE) return v;
    uint s = bricks.page[brick_index(v)];
    return slot_texel(s >= BRICK_REFUSED ? 0u : s, v);
}

#ifdef BRICKS_CLAIM
// The texel that stores voxel `v`, giving its brick a slot if it has none; false where the pool
// is full (the refused bricks are counted: `next` passes `capacity`, and the frame reports it).
// One loop with the claim inside: an invocation that finds the brick being claimed by another
// of its own subgroup retries after the claimer's branch, so lockstep execution cannot spin
// forever; BRICK_CLAIM_ITERATIONS bounds it in any case.
bool claim_brick(ivec3 v, out ivec3 texel) {
    texel = v;
    if (RESIDENT) {
        uint i = brick_index(v);
        uint s = bricks.page[i];
        if (s == 1u) return true;
        if (s == 0u && atomicCompSwap(bricks.page[i], 0u, BRICK_REFUSED) == 0u) atomicAdd(bricks.next, 1u);
        return false;
    }
    if (!SPARSE) return true;
    uint i = brick_index(v);
    for (int k = 0; k < BRICK_CLAIM_ITERATIONS; k++) {
        // An entry only ever goes 0 -> BRICK_LOCKED -> slot: a plain read that finds a slot
        // is final (most writes), and one that finds 0 or LOCKED only retries or claims.
        uint s = bricks.page[i];
        if (s == 0u && atomicCompSwap(bricks.page[i], 0u, BRICK_LOCKED) == 0u) {
            uint slot = atomicAdd(bricks.next, 1u);
            s = slot < bricks.capacity ? slot : BRICK_REFUSED;
            atomicExchange(bricks.page[i], s);
        }
        if (s == BRICK_REFUSED) return false;
        if (s != 0u && s != BRICK_LOCKED) {
            texel = slot_texel(s, v);
            return true;
        }
    }
    atomicAdd(bricks.stalled, 1u);
    return false;
}
#endif

#endif
