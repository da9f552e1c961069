// The lit side of a voxel (radiance.lit_side, r32ui), written by injection (gi/inject.comp) and
// by the bounce (gi/bounce.comp): xyz the unit side its reflected light leaves from, 8 bits
// each; bits 24..31 the lights that reach it (the bounce's own side: bit 24). A voxel with no
// normal has lights but no side: xyz 0, which no unit vector packs to (it would be -1, -1, -1).
#ifndef VCT_LIT_SIDE_GLSL
#define VCT_LIT_SIDE_GLSL

bool has_lit_side(uint side) {
    return (side >> 24) != 0u && (side & 0xffffffu) != 0u;
}

// The side, not normalized (8 bits a component).
vec3 lit_side_of(uint side) {
    return vec3(float(side & 0xffu), float((side >> 8) & 0xffu), float((side >> 16) & 0xffu)) / 255.0 * 2.0 - 1.0;
}

uint pack_lit_side(vec3 side, uint lights) {
    uvec3 q = uvec3(round((side * 0.5 + 0.5) * 255.0));
    return q.x | (q.y << 8) | (q.z << 16) | (lights << 24);
}

#endif
