// Triangle/box overlap by separating axes (Akenine-Möller 2001), for the rasterized
// voxelizer's per-voxel test. The box is centred at the origin with half-size h.
#ifndef VCT_TRIBOX_GLSL
#define VCT_TRIBOX_GLSL

bool separated_on(vec3 axis, vec3 v0, vec3 v1, vec3 v2, vec3 h) {
    float p0 = dot(axis, v0), p1 = dot(axis, v1), p2 = dot(axis, v2);
    float r = dot(h, abs(axis));
    return min(p0, min(p1, p2)) > r || max(p0, max(p1, p2)) < -r;
}

bool triangle_box_overlap(vec3 v0, vec3 v1, vec3 v2, vec3 h) {
    if (any(greaterThan(min(v0, min(v1, v2)), h)) || any(lessThan(max(v0, max(v1, v2)), -h))) return false;
    vec3 e0 = v1 - v0, e1 = v2 - v1, e2 = v0 - v2;
    if (separated_on(cross(e0, e1), v0, v1, v2, h)) return false;
    vec3 edges[3] = vec3[](e0, e1, e2);
    for (int i = 0; i < 3; i++) {
        if (separated_on(vec3(0.0, -edges[i].z, edges[i].y), v0, v1, v2, h)) return false;
        if (separated_on(vec3(edges[i].z, 0.0, -edges[i].x), v0, v1, v2, h)) return false;
        if (separated_on(vec3(-edges[i].y, edges[i].x, 0.0), v0, v1, v2, h)) return false;
    }
    return true;
}

#endif
