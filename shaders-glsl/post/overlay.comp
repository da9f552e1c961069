#version 460
// The viewer's on-screen overlay (render::overlay): lines of text in an 8x8 bitmap font (the
// public-domain font of the `font8x8` crate) over the tone-mapped frame. One thread per pixel
// copies the frame into the composite that is presented; inside a text cell holding a character
// it darkens the background and draws the glyph's set bits. The frame itself is left untouched,
// so screenshots (read from it) never contain the overlay.
#include "config.h"

layout(local_size_x = WORKGROUP_2D, local_size_y = WORKGROUP_2D) in;
layout(set = 0, binding = 0, rgba8) uniform readonly image2D frame_in;
layout(set = 0, binding = 1, rgba8) uniform writeonly image2D composite;
// 128 glyphs (ASCII), two words each: row r in byte r % 4 of word r / 4, bit c the column c.
layout(set = 0, binding = 2, std430) readonly buffer Font { uint glyphs[]; };
// OVERLAY_COLUMNS x OVERLAY_ROWS character codes, row-major; 0 is an empty cell.
layout(set = 0, binding = 3, std430) readonly buffer Text { uint cells[]; };
layout(push_constant) uniform Push { uint scale; uint rows; } push;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(frame_in)))) return;
    vec3 c = imageLoad(frame_in, p).rgb;
    int scale = int(max(push.scale, 1u));
    ivec2 q = p - ivec2(OVERLAY_MARGIN);
    ivec2 cell = q / (8 * scale);
    if (all(greaterThanEqual(q, ivec2(0))) && cell.x < OVERLAY_COLUMNS && cell.y < int(min(push.rows, OVERLAY_ROWS))) {
        uint ch = min(cells[cell.y * OVERLAY_COLUMNS + cell.x], 127u);
        if (ch != 0u) {
            c *= 0.3;
            ivec2 bit = (q % (8 * scale)) / scale;
            uint row = (glyphs[2u * ch + uint(bit.y) / 4u] >> (8u * (uint(bit.y) % 4u))) & 0xffu;
            if (((row >> uint(bit.x)) & 1u) != 0u) c = vec3(1.0);
        }
    }
    imageStore(composite, p, vec4(c, 1.0));
}
