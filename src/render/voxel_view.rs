//! Voxel debug view (the thesis' Fig. 4.1/4.4): occupied voxels drawn as instanced cubes from
//! the scene camera, coloured by their averaged albedo, headlessly into an 8-bit image.

use std::sync::Arc;

use ash::vk;
use glam::{Mat4, Vec3, Vec4};

use super::{frame::depth_range, FrameImages};
use crate::error::Result;
use crate::gpu::{
    self, scope, shaders, Attachments, Buffer, Context, GraphicsDesc, Image, ImageDesc, Pipeline, Stage, VertexLayout,
};
use crate::scene::Scene;
use crate::voxel::headless::VoxelRun;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct CubePush {
    view_proj: Mat4,
    origin_size: Vec4,
    light_dir: Vec4,
}

const ATTRS: [vk::VertexInputAttributeDescription; 2] = [
    vk::VertexInputAttributeDescription { location: 0, binding: 0, format: vk::Format::R32_UINT, offset: 0 },
    vk::VertexInputAttributeDescription { location: 1, binding: 0, format: vk::Format::R32_UINT, offset: 4 },
];

/// Renders the occupied voxels of `run` as cubes seen from the scene's camera.
pub fn render_voxels(ctx: &Arc<Context>, scene: &Scene, run: &VoxelRun) -> Result<FrameImages> {
    let g = &run.grid;
    let mut instances: Vec<[u32; 2]> = Vec::new();
    for (i, &v) in run.albedo.iter().enumerate() {
        if v >> 24 != 0 {
            let c = g.coords(i);
            instances.push([c.x | (c.y << 10) | (c.z << 20), v]);
        }
    }
    let cam = &scene.camera;
    let (w, h) = (cam.width, cam.height);
    let color_format = vk::Format::R8G8B8A8_UNORM;
    let color = Image::new(
        ctx,
        "voxel view",
        ImageDesc::d2(color_format, w, h, vk::ImageUsageFlags::COLOR_ATTACHMENT | vk::ImageUsageFlags::TRANSFER_SRC),
    )?;
    let depth_format = vk::Format::D32_SFLOAT;
    let depth = Image::new(
        ctx,
        "voxel view depth",
        ImageDesc::d2(depth_format, w, h, vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT),
    )?;
    let buffer = Buffer::from_slice(
        ctx,
        "voxel instances",
        vk::BufferUsageFlags::VERTEX_BUFFER,
        if instances.is_empty() { &[[0u32; 2]] } else { &instances },
    )?;

    let mut desc = GraphicsDesc::new(
        "voxel view",
        vec![
            Stage::new(vk::ShaderStageFlags::VERTEX, shaders::DEBUG_VOXEL_CUBES_VERT),
            Stage::new(vk::ShaderStageFlags::FRAGMENT, shaders::DEBUG_VOXEL_CUBES_FRAG),
        ],
    );
    desc.push_constant_size = std::mem::size_of::<CubePush>() as u32;
    desc.vertex = Some(VertexLayout { stride: 8, attributes: &ATTRS });
    desc.instanced = true;
    desc.depth_format = depth_format;
    desc.depth_test = true;
    desc.depth_write = true;
    desc.color_formats = vec![color_format];
    let pipeline = Pipeline::graphics(ctx, &desc)?;

    let (near, far) = depth_range(cam.eye, &scene.mesh.bounds);
    let light = (cam.eye - cam.target).normalize() * 0.6 + Vec3::new(0.45, 0.75, 0.0);
    let push = CubePush {
        view_proj: cam.proj(near, far) * cam.view(),
        origin_size: g.origin.extend(g.voxel),
        light_dir: light.normalize().extend(0.0),
    };
    ctx.submit_and_wait("voxel view", |cmd| {
        gpu::image_barrier(
            ctx,
            cmd,
            &color,
            vk::ImageLayout::UNDEFINED,
            vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
            scope::NONE,
            scope::COLOR_WRITE,
        );
        gpu::discard_to_depth(ctx, cmd, &depth, scope::NONE);
        let att = Attachments {
            color: Some((&color, vk::AttachmentLoadOp::CLEAR, [0.05, 0.05, 0.07, 1.0])),
            depth: Some((&depth, vk::AttachmentLoadOp::CLEAR)),
            width: w,
            height: h,
        };
        gpu::render(ctx, cmd, att, || {
            pipeline.bind(cmd, &[]);
            pipeline.push(cmd, &push);
            unsafe {
                ctx.device.cmd_bind_vertex_buffers(cmd, 0, &[buffer.raw], &[0]);
                ctx.device.cmd_draw(cmd, 36, instances.len() as u32, 0, 0);
            }
        });
    })?;
    let ldr = gpu::read_image(ctx, &color, vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL, 0)?;
    Ok(FrameImages { width: w, height: h, hdr: Vec::new(), ldr })
}
