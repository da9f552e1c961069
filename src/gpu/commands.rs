//! Small command-recording helpers shared by every pass: barriers (synchronization2),
//! dispatch by thread count, viewport setup, dynamic rendering, uploads and readbacks.

use std::sync::Arc;

use ash::vk;

use super::scope;
use gpu_allocator::MemoryLocation;

use super::{image::aspect_of, Buffer, Context, Image};
use crate::error::Result;

/// A global memory barrier.
pub fn memory_barrier(
    ctx: &Context,
    cmd: vk::CommandBuffer,
    src: (vk::PipelineStageFlags2, vk::AccessFlags2),
    dst: (vk::PipelineStageFlags2, vk::AccessFlags2),
) {
    let b = [vk::MemoryBarrier2::default()
        .src_stage_mask(src.0)
        .src_access_mask(src.1)
        .dst_stage_mask(dst.0)
        .dst_access_mask(dst.1)];
    unsafe { ctx.device.cmd_pipeline_barrier2(cmd, &vk::DependencyInfo::default().memory_barriers(&b)) };
}

/// A layout transition (and memory dependency) of a subresource range of a raw image.
#[allow(clippy::too_many_arguments)]
pub fn layout_barrier(
    ctx: &Context,
    cmd: vk::CommandBuffer,
    image: vk::Image,
    range: vk::ImageSubresourceRange,
    old: vk::ImageLayout,
    new: vk::ImageLayout,
    src: (vk::PipelineStageFlags2, vk::AccessFlags2),
    dst: (vk::PipelineStageFlags2, vk::AccessFlags2),
) {
    let b = [vk::ImageMemoryBarrier2::default()
        .src_stage_mask(src.0)
        .src_access_mask(src.1)
        .dst_stage_mask(dst.0)
        .dst_access_mask(dst.1)
        .old_layout(old)
        .new_layout(new)
        .src_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
        .dst_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
        .image(image)
        .subresource_range(range)];
    unsafe { ctx.device.cmd_pipeline_barrier2(cmd, &vk::DependencyInfo::default().image_memory_barriers(&b)) };
}

/// A layout transition (and memory dependency) over the given mips of an image.
#[allow(clippy::too_many_arguments)]
pub fn image_barrier_mips(
    ctx: &Context,
    cmd: vk::CommandBuffer,
    image: &Image,
    mips: std::ops::Range<u32>,
    old: vk::ImageLayout,
    new: vk::ImageLayout,
    src: (vk::PipelineStageFlags2, vk::AccessFlags2),
    dst: (vk::PipelineStageFlags2, vk::AccessFlags2),
) {
    let range = vk::ImageSubresourceRange {
        aspect_mask: aspect_of(image.desc.format),
        base_mip_level: mips.start,
        level_count: mips.end - mips.start,
        base_array_layer: 0,
        layer_count: image.desc.layers,
    };
    layout_barrier(ctx, cmd, image.raw, range, old, new, src, dst);
}

/// A layout transition over every mip of an image.
pub fn image_barrier(
    ctx: &Context,
    cmd: vk::CommandBuffer,
    image: &Image,
    old: vk::ImageLayout,
    new: vk::ImageLayout,
    src: (vk::PipelineStageFlags2, vk::AccessFlags2),
    dst: (vk::PipelineStageFlags2, vk::AccessFlags2),
) {
    image_barrier_mips(ctx, cmd, image, 0..image.desc.mip_levels, old, new, src, dst);
}

/// Discards a depth image's contents for a pass that clears and writes it, after the work in
/// `after` (which read it last).
pub fn discard_to_depth(ctx: &Context, cmd: vk::CommandBuffer, image: &Image, after: scope::Scope) {
    let (old, new) = (vk::ImageLayout::UNDEFINED, vk::ImageLayout::DEPTH_ATTACHMENT_OPTIMAL);
    image_barrier(ctx, cmd, image, old, new, after, scope::DEPTH_RW);
}

/// Discards an image's contents, zeroes every mip and leaves it in GENERAL, after the work in
/// `after` (the caller makes the clear visible to whatever comes next).
pub fn clear_to_general(ctx: &Context, cmd: vk::CommandBuffer, image: &Image, after: scope::Scope) {
    image_barrier(ctx, cmd, image, vk::ImageLayout::UNDEFINED, vk::ImageLayout::GENERAL, after, scope::CLEAR_WRITE);
    unsafe {
        ctx.device.cmd_clear_color_image(
            cmd,
            image.raw,
            vk::ImageLayout::GENERAL,
            &vk::ClearColorValue::default(),
            &[image.range()],
        )
    };
}

/// Clears mips `mips` of `image` (in GENERAL, contents of the other mips kept), ordered after
/// `after`; the caller orders the clear before what reads the image (scope::CLEAR_WRITE).
pub fn clear_mips(
    ctx: &Context,
    cmd: vk::CommandBuffer,
    image: &Image,
    mips: std::ops::Range<u32>,
    after: scope::Scope,
) {
    use vk::ImageLayout as L;
    image_barrier_mips(ctx, cmd, image, mips.clone(), L::GENERAL, L::GENERAL, after, scope::CLEAR_WRITE);
    let range =
        vk::ImageSubresourceRange { base_mip_level: mips.start, level_count: mips.end - mips.start, ..image.range() };
    unsafe { ctx.device.cmd_clear_color_image(cmd, image.raw, L::GENERAL, &vk::ClearColorValue::default(), &[range]) };
}

/// Copies mip `src_mip` of `src` into mip 0 of `dst` (same extent; both are in GENERAL before
/// and after, and in the transfer layouts during the copy), ordered after anything before it
/// and before compute shaders that sample `dst`.
pub fn copy_level(ctx: &Context, cmd: vk::CommandBuffer, src: &Image, src_mip: u32, dst: &Image) {
    use vk::ImageLayout as L;
    let (from, to) = (src_mip..src_mip + 1, 0..1);
    image_barrier_mips(
        ctx,
        cmd,
        src,
        from.clone(),
        L::GENERAL,
        L::TRANSFER_SRC_OPTIMAL,
        scope::ANY,
        scope::TRANSFER_READ,
    );
    image_barrier_mips(
        ctx,
        cmd,
        dst,
        to.clone(),
        L::GENERAL,
        L::TRANSFER_DST_OPTIMAL,
        scope::ANY,
        scope::TRANSFER_WRITE,
    );
    let layers = |mip| vk::ImageSubresourceLayers {
        aspect_mask: aspect_of(src.desc.format),
        mip_level: mip,
        base_array_layer: 0,
        layer_count: 1,
    };
    let region = [vk::ImageCopy {
        src_subresource: layers(src_mip),
        dst_subresource: layers(0),
        extent: dst.desc.extent,
        ..Default::default()
    }];
    unsafe {
        ctx.device.cmd_copy_image(cmd, src.raw, L::TRANSFER_SRC_OPTIMAL, dst.raw, L::TRANSFER_DST_OPTIMAL, &region)
    };
    image_barrier_mips(ctx, cmd, src, from, L::TRANSFER_SRC_OPTIMAL, L::GENERAL, scope::TRANSFER_READ, scope::ANY);
    image_barrier_mips(
        ctx,
        cmd,
        dst,
        to,
        L::TRANSFER_DST_OPTIMAL,
        L::GENERAL,
        scope::TRANSFER_WRITE,
        scope::COMPUTE_SAMPLED,
    );
}

/// Number of workgroups covering `threads` with groups of `local` threads per axis.
pub fn group_count(threads: [u32; 3], local: [u32; 3]) -> [u32; 3] {
    [threads[0].div_ceil(local[0]), threads[1].div_ceil(local[1]), threads[2].div_ceil(local[2])]
}

/// Dispatches enough workgroups of size `local` to cover `threads`.
pub fn dispatch(ctx: &Context, cmd: vk::CommandBuffer, threads: [u32; 3], local: [u32; 3]) {
    let g = group_count(threads, local);
    unsafe { ctx.device.cmd_dispatch(cmd, g[0], g[1], g[2]) };
}

/// Dispatches the workgroup counts held in `args` (a `VkDispatchIndirectCommand` at offset 0).
pub fn dispatch_indirect(ctx: &Context, cmd: vk::CommandBuffer, args: &Buffer) {
    unsafe { ctx.device.cmd_dispatch_indirect(cmd, args.raw, 0) };
}

/// Fills the first `bytes` of `buffer` with `value` (a transfer write).
pub fn fill_buffer(ctx: &Context, cmd: vk::CommandBuffer, buffer: &Buffer, bytes: u64, value: u32) {
    fill_buffer_at(ctx, cmd, buffer, 0, bytes, value);
}

/// Fills `bytes` (a multiple of 4, or `vk::WHOLE_SIZE`) of `buffer` from `offset` with `value`.
pub fn fill_buffer_at(ctx: &Context, cmd: vk::CommandBuffer, buffer: &Buffer, offset: u64, bytes: u64, value: u32) {
    unsafe { ctx.device.cmd_fill_buffer(cmd, buffer.raw, offset, bytes, value) };
}

/// Writes `data` (at most 65536 bytes, a multiple of 4) into `buffer` at offset 0, in the
/// command stream (a transfer write).
pub fn update_buffer(ctx: &Context, cmd: vk::CommandBuffer, buffer: &Buffer, data: &[u8]) {
    unsafe { ctx.device.cmd_update_buffer(cmd, buffer.raw, 0, data) };
}

/// Copies the first `bytes` of `src` into `dst` from `offset` on.
pub fn copy_buffer_at(ctx: &Context, cmd: vk::CommandBuffer, src: &Buffer, dst: &Buffer, offset: u64, bytes: u64) {
    let region = [vk::BufferCopy { src_offset: 0, dst_offset: offset, size: bytes }];
    unsafe { ctx.device.cmd_copy_buffer(cmd, src.raw, dst.raw, &region) };
}

/// Copies the first `bytes` of `src` into `dst`.
pub fn copy_buffer(ctx: &Context, cmd: vk::CommandBuffer, src: &Buffer, dst: &Buffer, bytes: u64) {
    copy_buffer_at(ctx, cmd, src, dst, 0, bytes);
}

/// Reads a device-local buffer (with TRANSFER_SRC usage) back through a staging copy, after
/// all submitted work.
pub fn read_buffer(ctx: &Arc<Context>, buffer: &Buffer) -> Result<Vec<u8>> {
    let staging = Buffer::new(
        ctx,
        &format!("{} readback", buffer.name),
        buffer.size,
        vk::BufferUsageFlags::TRANSFER_DST,
        MemoryLocation::GpuToCpu,
    )?;
    ctx.submit_and_wait(&format!("read back {}", buffer.name), |cmd| {
        memory_barrier(ctx, cmd, scope::ANY, scope::TRANSFER_READ);
        copy_buffer(ctx, cmd, buffer, &staging, buffer.size);
        memory_barrier(ctx, cmd, scope::TRANSFER_WRITE, scope::HOST_READ);
    })?;
    Ok(staging.read().to_vec())
}

/// Sets a full-size viewport and scissor.
pub fn set_viewport(ctx: &Context, cmd: vk::CommandBuffer, width: u32, height: u32) {
    let viewport =
        vk::Viewport { x: 0.0, y: 0.0, width: width as f32, height: height as f32, min_depth: 0.0, max_depth: 1.0 };
    let scissor = vk::Rect2D { offset: vk::Offset2D::default(), extent: vk::Extent2D { width, height } };
    unsafe {
        ctx.device.cmd_set_viewport(cmd, 0, &[viewport]);
        ctx.device.cmd_set_scissor(cmd, 0, &[scissor]);
    }
}

/// Attachments for one dynamic-rendering pass.
pub struct Attachments<'a> {
    pub color: Option<(&'a Image, vk::AttachmentLoadOp, [f32; 4])>,
    pub depth: Option<(&'a Image, vk::AttachmentLoadOp)>,
    pub width: u32,
    pub height: u32,
}

/// Begins dynamic rendering, runs `record`, ends it. Color is in COLOR_ATTACHMENT_OPTIMAL,
/// depth in DEPTH_ATTACHMENT_OPTIMAL; with neither, rendering has no attachments.
pub fn render(ctx: &Context, cmd: vk::CommandBuffer, a: Attachments, record: impl FnOnce()) {
    let color: Vec<_> = a
        .color
        .iter()
        .map(|(img, load, clear)| {
            vk::RenderingAttachmentInfo::default()
                .image_view(img.view.raw)
                .image_layout(vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL)
                .load_op(*load)
                .store_op(vk::AttachmentStoreOp::STORE)
                .clear_value(vk::ClearValue { color: vk::ClearColorValue { float32: *clear } })
        })
        .collect();
    render_multi(ctx, cmd, &color, a.depth, a.width, a.height, record);
}

/// Begins dynamic rendering with several colour attachments (already described) and an
/// optional depth attachment, runs `record`, ends it.
pub fn render_multi(
    ctx: &Context,
    cmd: vk::CommandBuffer,
    color: &[vk::RenderingAttachmentInfo],
    depth: Option<(&Image, vk::AttachmentLoadOp)>,
    width: u32,
    height: u32,
    record: impl FnOnce(),
) {
    render_depth_view(ctx, cmd, color, depth.map(|(img, load)| (img.view.raw, load)), width, height, record);
}

/// Renders into layer `layer` of the array image `depth` (cleared first), running `record`.
pub fn render_depth_layer(ctx: &Context, cmd: vk::CommandBuffer, depth: &Image, layer: u32, record: impl FnOnce()) {
    let e = depth.desc.extent;
    let view = depth.layer_views[layer as usize].raw;
    render_depth_view(ctx, cmd, &[], Some((view, vk::AttachmentLoadOp::CLEAR)), e.width, e.height, record);
}

fn render_depth_view(
    ctx: &Context,
    cmd: vk::CommandBuffer,
    color: &[vk::RenderingAttachmentInfo],
    depth: Option<(vk::ImageView, vk::AttachmentLoadOp)>,
    width: u32,
    height: u32,
    record: impl FnOnce(),
) {
    let depth = depth.map(|(view, load)| {
        vk::RenderingAttachmentInfo::default()
            .image_view(view)
            .image_layout(vk::ImageLayout::DEPTH_ATTACHMENT_OPTIMAL)
            .load_op(load)
            .store_op(vk::AttachmentStoreOp::STORE)
            .clear_value(vk::ClearValue { depth_stencil: vk::ClearDepthStencilValue { depth: 1.0, stencil: 0 } })
    });
    let area = vk::Rect2D { offset: vk::Offset2D::default(), extent: vk::Extent2D { width, height } };
    let mut info = vk::RenderingInfo::default().render_area(area).layer_count(1).color_attachments(color);
    if let Some(d) = depth.as_ref() {
        info = info.depth_attachment(d);
    }
    unsafe { ctx.device.cmd_begin_rendering(cmd, &info) };
    set_viewport(ctx, cmd, width, height);
    record();
    unsafe { ctx.device.cmd_end_rendering(cmd) };
}

/// Blits `src` (GENERAL, already written; left in GENERAL) onto a swapchain image and leaves
/// that image ready to present.
pub fn blit_to_present(ctx: &Context, cmd: vk::CommandBuffer, src: &Image, dst: vk::Image, extent: vk::Extent2D) {
    let range = vk::ImageSubresourceRange {
        aspect_mask: vk::ImageAspectFlags::COLOR,
        base_mip_level: 0,
        level_count: 1,
        base_array_layer: 0,
        layer_count: 1,
    };
    let none = (vk::PipelineStageFlags2::ALL_COMMANDS, vk::AccessFlags2::NONE);
    let e = src.desc.extent;
    let sub = vk::ImageSubresourceLayers {
        aspect_mask: vk::ImageAspectFlags::COLOR,
        mip_level: 0,
        base_array_layer: 0,
        layer_count: 1,
    };
    let blit = [vk::ImageBlit::default()
        .src_subresource(sub)
        .src_offsets([vk::Offset3D::default(), vk::Offset3D { x: e.width as i32, y: e.height as i32, z: 1 }])
        .dst_subresource(sub)
        .dst_offsets([
            vk::Offset3D::default(),
            vk::Offset3D { x: extent.width as i32, y: extent.height as i32, z: 1 },
        ])];
    image_barrier(
        ctx,
        cmd,
        src,
        vk::ImageLayout::GENERAL,
        vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
        scope::ANY,
        scope::TRANSFER_READ,
    );
    layout_barrier(
        ctx,
        cmd,
        dst,
        range,
        vk::ImageLayout::UNDEFINED,
        vk::ImageLayout::TRANSFER_DST_OPTIMAL,
        none,
        scope::TRANSFER_WRITE,
    );
    unsafe {
        ctx.device.cmd_blit_image(
            cmd,
            src.raw,
            vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
            dst,
            vk::ImageLayout::TRANSFER_DST_OPTIMAL,
            &blit,
            vk::Filter::NEAREST,
        )
    };
    layout_barrier(
        ctx,
        cmd,
        dst,
        range,
        vk::ImageLayout::TRANSFER_DST_OPTIMAL,
        vk::ImageLayout::PRESENT_SRC_KHR,
        scope::TRANSFER_WRITE,
        none,
    );
    image_barrier(
        ctx,
        cmd,
        src,
        vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
        vk::ImageLayout::GENERAL,
        scope::TRANSFER_READ,
        scope::ANY,
    );
}

/// A device-local buffer filled with `data` through a staging copy.
pub fn upload_buffer<T: bytemuck::Pod>(
    ctx: &Arc<Context>,
    name: &str,
    usage: vk::BufferUsageFlags,
    data: &[T],
) -> Result<Buffer> {
    let staging = Buffer::from_slice(ctx, &format!("{name} staging"), vk::BufferUsageFlags::TRANSFER_SRC, data)?;
    let buffer =
        Buffer::new(ctx, name, staging.size, usage | vk::BufferUsageFlags::TRANSFER_DST, MemoryLocation::GpuOnly)?;
    ctx.submit_and_wait(&format!("upload {name}"), |cmd| copy_buffer(ctx, cmd, &staging, &buffer, staging.size))?;
    Ok(buffer)
}

/// Uploads RGBA8 texels into mip 0 of a 2D image, builds its mip chain by blits, and leaves
/// every level in SHADER_READ_ONLY_OPTIMAL.
pub fn upload_texture(ctx: &Arc<Context>, image: &Image, rgba8: &[u8]) -> Result<()> {
    let staging =
        Buffer::from_slice(ctx, &format!("{} staging", image.name), vk::BufferUsageFlags::TRANSFER_SRC, rgba8)?;
    let shader_r = (vk::PipelineStageFlags2::FRAGMENT_SHADER, vk::AccessFlags2::SHADER_SAMPLED_READ);
    let levels = image.desc.mip_levels;
    ctx.submit_and_wait(&format!("upload {}", image.name), |cmd| unsafe {
        let d = &ctx.device;
        image_barrier(
            ctx,
            cmd,
            image,
            vk::ImageLayout::UNDEFINED,
            vk::ImageLayout::TRANSFER_DST_OPTIMAL,
            scope::NONE,
            scope::TRANSFER_WRITE,
        );
        let region = [vk::BufferImageCopy::default()
            .image_subresource(vk::ImageSubresourceLayers {
                aspect_mask: vk::ImageAspectFlags::COLOR,
                mip_level: 0,
                base_array_layer: 0,
                layer_count: 1,
            })
            .image_extent(image.desc.extent)];
        d.cmd_copy_buffer_to_image(cmd, staging.raw, image.raw, vk::ImageLayout::TRANSFER_DST_OPTIMAL, &region);
        for level in 1..levels {
            image_barrier_mips(
                ctx,
                cmd,
                image,
                level - 1..level,
                vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
                scope::TRANSFER_WRITE,
                scope::TRANSFER_READ,
            );
            let (s, t) = (image.extent_at(level - 1), image.extent_at(level));
            let sub = |m| vk::ImageSubresourceLayers {
                aspect_mask: vk::ImageAspectFlags::COLOR,
                mip_level: m,
                base_array_layer: 0,
                layer_count: 1,
            };
            let blit = [vk::ImageBlit::default()
                .src_subresource(sub(level - 1))
                .src_offsets([vk::Offset3D::default(), vk::Offset3D { x: s.width as i32, y: s.height as i32, z: 1 }])
                .dst_subresource(sub(level))
                .dst_offsets([vk::Offset3D::default(), vk::Offset3D { x: t.width as i32, y: t.height as i32, z: 1 }])];
            d.cmd_blit_image(
                cmd,
                image.raw,
                vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
                image.raw,
                vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                &blit,
                vk::Filter::LINEAR,
            );
        }
        if levels > 1 {
            image_barrier_mips(
                ctx,
                cmd,
                image,
                0..levels - 1,
                vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
                vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL,
                scope::TRANSFER_READ,
                shader_r,
            );
        }
        image_barrier_mips(
            ctx,
            cmd,
            image,
            levels - 1..levels,
            vk::ImageLayout::TRANSFER_DST_OPTIMAL,
            vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL,
            scope::TRANSFER_WRITE,
            shader_r,
        );
    })
}

/// Uploads every mip level of an image from `levels` (tightly packed texels) and leaves it in
/// `final_layout`.
pub fn upload_levels(
    ctx: &Arc<Context>,
    image: &Image,
    levels: &[Vec<u8>],
    final_layout: vk::ImageLayout,
) -> Result<()> {
    let all: Vec<u8> = levels.concat();
    let staging =
        Buffer::from_slice(ctx, &format!("{} staging", image.name), vk::BufferUsageFlags::TRANSFER_SRC, &all)?;
    let any = (vk::PipelineStageFlags2::ALL_COMMANDS, vk::AccessFlags2::MEMORY_READ);
    ctx.submit_and_wait(&format!("upload {}", image.name), |cmd| unsafe {
        image_barrier(
            ctx,
            cmd,
            image,
            vk::ImageLayout::UNDEFINED,
            vk::ImageLayout::TRANSFER_DST_OPTIMAL,
            scope::NONE,
            scope::TRANSFER_WRITE,
        );
        let mut offset = 0u64;
        let regions: Vec<_> = levels
            .iter()
            .enumerate()
            .map(|(m, data)| {
                let r = vk::BufferImageCopy::default()
                    .buffer_offset(offset)
                    .image_subresource(vk::ImageSubresourceLayers {
                        aspect_mask: aspect_of(image.desc.format),
                        mip_level: m as u32,
                        base_array_layer: 0,
                        layer_count: 1,
                    })
                    .image_extent(image.extent_at(m as u32));
                offset += data.len() as u64;
                r
            })
            .collect();
        ctx.device.cmd_copy_buffer_to_image(
            cmd,
            staging.raw,
            image.raw,
            vk::ImageLayout::TRANSFER_DST_OPTIMAL,
            &regions,
        );
        image_barrier(ctx, cmd, image, vk::ImageLayout::TRANSFER_DST_OPTIMAL, final_layout, scope::TRANSFER_WRITE, any);
    })
}

/// Copies one mip of an image (in `layout`, which it is left in) to host memory.
pub fn read_image(ctx: &Arc<Context>, image: &Image, layout: vk::ImageLayout, mip: u32) -> Result<Vec<u8>> {
    let e = image.extent_at(mip);
    let size = e.width as u64 * e.height as u64 * e.depth as u64 * super::image::texel_size(image.desc.format) as u64;
    let staging = Buffer::new(
        ctx,
        &format!("{} readback", image.name),
        size,
        vk::BufferUsageFlags::TRANSFER_DST,
        MemoryLocation::GpuToCpu,
    )?;
    ctx.submit_and_wait(&format!("read back {}", image.name), |cmd| unsafe {
        image_barrier_mips(
            ctx,
            cmd,
            image,
            mip..mip + 1,
            layout,
            vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
            scope::ANY,
            scope::TRANSFER_READ,
        );
        let region = [vk::BufferImageCopy::default()
            .image_subresource(vk::ImageSubresourceLayers {
                aspect_mask: aspect_of(image.desc.format),
                mip_level: mip,
                base_array_layer: 0,
                layer_count: 1,
            })
            .image_extent(e)];
        ctx.device.cmd_copy_image_to_buffer(
            cmd,
            image.raw,
            vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
            staging.raw,
            &region,
        );
        image_barrier_mips(
            ctx,
            cmd,
            image,
            mip..mip + 1,
            vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
            layout,
            scope::TRANSFER_READ,
            scope::ANY,
        );
        let host = [vk::MemoryBarrier2::default()
            .src_stage_mask(vk::PipelineStageFlags2::ALL_TRANSFER)
            .src_access_mask(vk::AccessFlags2::TRANSFER_WRITE)
            .dst_stage_mask(vk::PipelineStageFlags2::HOST)
            .dst_access_mask(vk::AccessFlags2::HOST_READ)];
        ctx.device.cmd_pipeline_barrier2(cmd, &vk::DependencyInfo::default().memory_barriers(&host));
    })?;
    Ok(staging.read().to_vec())
}
