//! The viewer's on-screen overlay: text (FPS, per-pass GPU time, the settings, voxel memory, the
//! key map) drawn over the tone-mapped frame in an 8×8 bitmap font (the `font8x8` crate's
//! public-domain font) by one compute pass (post/overlay.comp) into a composite image, which the
//! viewer presents. The frame is not written, so screenshots never contain the overlay.

use std::cell::Cell;
use std::sync::Arc;

use ash::vk;

use crate::config::{OVERLAY_COLUMNS, OVERLAY_ROWS, WORKGROUP_2D};
use crate::error::Result;
use crate::gpu::{
    self, scope, shaders, Binding, Buffer, Context, DescriptorSet, FrameBuffer, Image, ImageDesc, Pipeline, Stage,
};

pub struct OverlayPass {
    ctx: Arc<Context>,
    pipeline: Pipeline,
    set: DescriptorSet,
    _font: Buffer,
    text: FrameBuffer,
    rows: Cell<u32>,
    /// The frame with the text over it.
    pub composite: Image,
}

/// The font's 128 ASCII glyphs, two words each (post/overlay.comp).
fn font_words() -> Vec<u32> {
    font8x8::legacy::BASIC_LEGACY
        .iter()
        .flat_map(|g| [u32::from_le_bytes([g[0], g[1], g[2], g[3]]), u32::from_le_bytes([g[4], g[5], g[6], g[7]])])
        .collect()
}

impl OverlayPass {
    /// An overlay over `frame` (RGBA8, storage), the size of it. It reads that image only: make
    /// a new one when the frame's image is made anew.
    pub fn new(ctx: &Arc<Context>, frame: &Image) -> Result<Self> {
        let e = frame.desc.extent;
        let usage = vk::ImageUsageFlags::STORAGE | vk::ImageUsageFlags::TRANSFER_SRC;
        let composite =
            Image::new(ctx, "overlay composite", ImageDesc::d2(frame.desc.format, e.width, e.height, usage))?;
        let storage = vk::BufferUsageFlags::STORAGE_BUFFER;
        let font = Buffer::from_slice(ctx, "overlay font", storage, &font_words())?;
        let cells = (OVERLAY_COLUMNS * OVERLAY_ROWS) as u64 * 4;
        let text = FrameBuffer::new(ctx, "overlay text", cells, storage)?;
        let c = vk::ShaderStageFlags::COMPUTE;
        let set = DescriptorSet::new(
            ctx,
            "overlay",
            &[
                Binding::new(0, vk::DescriptorType::STORAGE_IMAGE, c),
                Binding::new(1, vk::DescriptorType::STORAGE_IMAGE, c),
                Binding::new(2, vk::DescriptorType::STORAGE_BUFFER, c),
                Binding::new(3, vk::DescriptorType::STORAGE_BUFFER, c),
            ],
        )?;
        set.write_storage(0, frame.view.raw);
        set.write_storage(1, composite.view.raw);
        set.write_buffer(2, vk::DescriptorType::STORAGE_BUFFER, &font);
        set.write_buffer(3, vk::DescriptorType::STORAGE_BUFFER, &text.buffer);
        let pipeline = Pipeline::compute(ctx, "overlay", Stage::new(c, shaders::POST_OVERLAY_COMP), &[set.layout], 8)?;
        Ok(OverlayPass { ctx: ctx.clone(), pipeline, set, _font: font, text, rows: Cell::new(0), composite })
    }

    /// The lines to draw (cut at the overlay's columns and rows; characters outside ASCII as '?').
    /// Frames recorded from now on draw them.
    pub fn set_text(&self, lines: &[String]) {
        let (cols, rows) = (OVERLAY_COLUMNS as usize, OVERLAY_ROWS as usize);
        let mut cells = vec![0u32; cols * rows];
        for (r, line) in lines.iter().take(rows).enumerate() {
            for (c, ch) in line.chars().take(cols).enumerate() {
                cells[r * cols + c] = if ch.is_ascii() && !ch.is_ascii_control() { ch as u32 } else { '?' as u32 };
            }
        }
        self.text.set(0, bytemuck::cast_slice(&cells));
        self.rows.set(lines.len().min(rows) as u32);
    }

    /// Glyphs `scale` times 8 pixels: one more for every 480 rows of the frame.
    pub fn scale(&self) -> u32 {
        1 + self.composite.desc.extent.height / 480
    }

    /// Composites the text over the frame (in GENERAL, written by compute); leaves the composite
    /// in GENERAL for the blit to the swapchain.
    pub fn record(&self, cmd: vk::CommandBuffer) {
        let ctx = &self.ctx;
        let rw = scope::COMPUTE_RW;
        self.text.record_upload(cmd);
        gpu::image_barrier(
            ctx,
            cmd,
            &self.composite,
            vk::ImageLayout::UNDEFINED,
            vk::ImageLayout::GENERAL,
            scope::ANY,
            rw,
        );
        self.pipeline.bind(cmd, &[self.set.raw]);
        self.pipeline.push(cmd, &[self.scale(), self.rows.get()]);
        let e = self.composite.desc.extent;
        gpu::dispatch(ctx, cmd, [e.width, e.height, 1], [WORKGROUP_2D, WORKGROUP_2D, 1]);
        gpu::memory_barrier(ctx, cmd, scope::COMPUTE_WRITE, scope::ANY);
    }
}
