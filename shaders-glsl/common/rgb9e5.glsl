// Shared-exponent RGB9E5 packing (as VK_FORMAT_E5B9G9R9_UFLOAT_PACK32), for HDR colours
// kept in R32UI images.
#ifndef VCT_RGB9E5_GLSL
#define VCT_RGB9E5_GLSL

uint encode_rgb9e5(vec3 c) {
    const float max_value = 65408.0;  // (2^9 - 1) / 2^9 * 2^16
    c = clamp(c, 0.0, max_value);
    float m = max(c.r, max(c.g, c.b));
    int e = max(-16, int(floor(log2(max(m, 1e-30))))) + 1;
    float scale = exp2(float(9 - e));
    if (uint(floor(m * scale + 0.5)) == 512u) { e += 1; scale *= 0.5; }
    uvec3 q = uvec3(floor(c * scale + 0.5));
    return q.r | (q.g << 9) | (q.b << 18) | (uint(e + 15) << 27);
}

vec3 decode_rgb9e5(uint v) {
    float scale = exp2(float(int(v >> 27) - 15 - 9));
    return vec3(float(v & 511u), float((v >> 9) & 511u), float((v >> 18) & 511u)) * scale;
}

#endif
