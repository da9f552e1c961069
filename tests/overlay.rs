//! The viewer's overlay pass (render::overlay): text drawn in the 8×8 font over a frame, into a
//! composite image, leaving the frame untouched. Checked texel by texel against the font's own
//! bitmaps, so a wrong bit order, row order, cell pitch or scale fails.

mod common;

use ash::vk;
use vct::gpu::{self, Image, ImageDesc};
use vct::render::overlay::OverlayPass;
use vct::render::Targets;

#[test]
fn overlay_draws_the_fonts_glyphs_over_a_frame_it_leaves_alone() {
    let ctx = common::context();
    let (w, h) = (96u32, 40u32);
    let usage = vk::ImageUsageFlags::STORAGE | vk::ImageUsageFlags::TRANSFER_DST | vk::ImageUsageFlags::TRANSFER_SRC;
    let frame = Image::new(&ctx, "test frame", ImageDesc::d2(Targets::LDR_FORMAT, w, h, usage)).unwrap();
    let overlay = OverlayPass::new(&ctx, &frame).unwrap();
    assert_eq!(overlay.scale(), 1);
    overlay.set_text(&["Ab".to_string(), "fps 7".to_string()]);
    ctx.submit_and_wait("overlay test", |cmd| {
        // A black frame (the clear), then the overlay over it.
        gpu::clear_to_general(&ctx, cmd, &frame, gpu::scope::NONE);
        gpu::memory_barrier(&ctx, cmd, gpu::scope::CLEAR_WRITE, gpu::scope::COMPUTE_RW);
        overlay.record(cmd);
    })
    .unwrap();
    let out = gpu::read_image(&ctx, &overlay.composite, vk::ImageLayout::GENERAL, 0).unwrap();
    let under = gpu::read_image(&ctx, &frame, vk::ImageLayout::GENERAL, 0).unwrap();
    common::assert_clean(&ctx);
    assert!(under.iter().all(|&v| v == 0), "the frame was written");
    let m = vct::config::OVERLAY_MARGIN;
    let lines = ["Ab", "fps 7"];
    for y in 0..h {
        for x in 0..w {
            let px = &out[((y * w + x) * 4) as usize..][..3];
            let lit = px.iter().all(|&v| v == 255);
            let (cx, cy) = ((x as i32 - m as i32).div_euclid(8), (y as i32 - m as i32).div_euclid(8));
            let ch = (x >= m && y >= m)
                .then(|| lines.get(cy as usize).and_then(|l| l.as_bytes().get(cx as usize)))
                .flatten();
            let want = ch.is_some_and(|&c| {
                let glyph = font8x8::legacy::BASIC_LEGACY[c as usize];
                (glyph[((y - m) % 8) as usize] >> ((x - m) % 8)) & 1 == 1
            });
            assert_eq!(lit, want, "pixel ({x}, {y}) in cell ({cx}, {cy}) {:?}", ch.map(|&c| c as char));
            if !lit {
                assert!(px.iter().all(|&v| v == 0), "pixel ({x}, {y}) should keep the black frame: {px:?}");
            }
        }
    }
}
