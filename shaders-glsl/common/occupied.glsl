// The compact list of occupied voxels (voxel::occupied; OPEngine's sparse voxel list): a count
// and the packed coordinates (x | y << 10 | z << 20: 10 bits each for x and y, 12 for z, which a
// clipmap's stack of levels needs) of every occupied voxel, appended by the
// voxelizers on a voxel's first write (voxel.glsl), so that passes over voxels run one
// invocation per occupied voxel (dispatched indirectly) instead of one per voxel of the grid.
// The mip levels' lists of occupied texels (gi/parents.comp) have the same layout.
#ifndef VCT_OCCUPIED_GLSL
#define VCT_OCCUPIED_GLSL

#ifndef OCCUPIED_SET
#define OCCUPIED_SET 1
#endif

layout(set = OCCUPIED_SET, binding = OCCUPIED_BINDING, std430) buffer Occupied {
    uint count;
    uint pad0, pad1, pad2;
    uint voxels[];
} occupied;

uint pack_voxel(ivec3 v) {
    return uint(v.x) | (uint(v.y) << 10) | (uint(v.z) << 20);
}

ivec3 unpack_voxel(uint p) {
    return ivec3(p & 1023u, (p >> 10) & 1023u, p >> 20);
}

#endif
