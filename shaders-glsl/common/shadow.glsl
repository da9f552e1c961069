// Shadow-map lookups (render::shadow): the fraction of a light reaching a point, filtered by
// 3x3 bilinear PCF in four comparisons, the lookup moved along the normal (normal-offset
// shadows). Shared by surface shading (common/shading.glsl) and by injection from the voxels
// (gi/resolve.comp). The includer binds `shadow_map` (sampler2DArrayShadow: one layer a light,
// a point or area light's six).
#ifndef VCT_SHADOW_GLSL
#define VCT_SHADOW_GLSL
#include "frame.glsl"
#include "light.glsl"

// Pair `k` of the PCF kernel along one axis (shadow_factor), for the lookup's texel fraction `f`:
// its two texels' weights are a = (k == 0 ? 1 - f : 1) and b = (k == r ? f : 1); returns where
// between them one bilinear comparison weighs them alike, b / (a + b), and their sum.
vec2 pcf_pair(int k, float f) {
    float a = k == 0 ? 1.0 - f : 1.0, b = k == PCF_RADIUS ? f : 1.0;
    return vec2(b / (a + b), a + b);
}

// Fraction of the light reaching `p` on a surface with normal `n` (3x3 PCF). The lookup point
// moves SHADOW_NORMAL_OFFSET shadow texels along the normal (normal-offset shadows), so the
// rasterizer's slope-scaled depth bias can stay small: a large one lets light under a thin
// wall where it meets the floor (the stability bench, regime 3).
float shadow_factor(int j, vec3 p, vec3 n) {
    // World size of one shadow texel at p: 2 w / (P00 * resolution), P00 the length of the
    // projection's first row (the view is a rotation).
    int layer;
    mat4 vp = shadow_view_proj(j, p, layer);
    vec4 clip = vp * vec4(p, 1.0);
    float p00 = length(vec3(vp[0][0], vp[1][0], vp[2][0]));
    float texel = frame.lights[j].cone.z;
    float texel_world = 2.0 * clip.w * texel / p00;
    vec3 q = p + n * (SHADOW_NORMAL_OFFSET * texel_world);
    // The offset point may lie across a cube edge: its own face then.
    vp = shadow_view_proj(j, q, layer);
    clip = vp * vec4(q, 1.0);
    if (clip.w <= 0.0) return 0.0;
    vec3 ndc = clip.xyz / clip.w;
    vec2 uv = ndc.xy * 0.5 + 0.5;
    // The (2r+1)^2 bilinear comparisons one texel apart weigh, along each axis, the 2r+2 texels
    // from floor(s) - r (s the lookup in texel units, less half a texel; f its fraction) by
    // 1-f, 1, ..., 1, f. Pairs of neighbouring texels are one bilinear comparison each, placed
    // between the two at the ratio of their weights and weighed by their sum: (r+1)^2
    // comparisons, the same filter (Castano 2013). Measured (lavapipe, Cornell 1280x720, 64^3,
    // scale 8): the shading pass took 71-72 ms with 9 comparisons, 58-62 with 4; the images are
    // the same (FLIP 0.00000-0.00001 on Cornell, Sponza and the classic box).
    vec2 s = uv / texel - 0.5;
    vec2 i0 = floor(s), f = s - i0;
    float lit = 0.0;
    for (int y = 0; y <= PCF_RADIUS; y++) {
        vec2 wy = pcf_pair(y, f.y);
        for (int x = 0; x <= PCF_RADIUS; x++) {
            vec2 wx = pcf_pair(x, f.x);
            vec2 at = (i0 + vec2(x, y) * 2.0 - float(PCF_RADIUS) + vec2(wx.x, wy.x) + 0.5) * texel;
            lit += wx.y * wy.y * texture(shadow_map, vec4(at, float(layer), ndc.z));
        }
    }
    return lit / float((2 * PCF_RADIUS + 1) * (2 * PCF_RADIUS + 1));
}

#endif
