//! Shadow map pass (Freed 2018 §4.2): the scene's depth from the light into a D32 texture,
//! with a small slope-scaled depth bias (shading adds a normal offset; a large slope bias let
//! light under thin walls); read by shading (PCF) and later by radiance injection.

use std::sync::Arc;

use ash::vk;

use crate::error::Result;
use crate::gpu::{self, scope, shaders, Attachments, Context, GraphicsDesc, Image, ImageDesc, Pipeline, Stage};
use crate::scene::gpu::{vertex_layout, SceneGpu};

pub const SHADOW_FORMAT: vk::Format = vk::Format::D32_SFLOAT;

pub struct ShadowPass {
    ctx: Arc<Context>,
    pipeline: Pipeline,
    pub map: Image,
}

impl ShadowPass {
    pub fn new(ctx: &Arc<Context>, scene: &SceneGpu, resolution: u32) -> Result<Self> {
        let usage = vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT | vk::ImageUsageFlags::SAMPLED;
        let map = Image::new(ctx, "shadow map", ImageDesc::d2(SHADOW_FORMAT, resolution, resolution, usage))?;
        let mut desc = GraphicsDesc::new(
            "shadow map",
            vec![Stage::new(vk::ShaderStageFlags::VERTEX, shaders::SCENE_SCENE_VERT).spec(&[1])],
        );
        desc.set_layouts = vec![scene.set.layout];
        desc.push_constant_size = 4;
        desc.vertex = Some(vertex_layout());
        desc.depth_format = SHADOW_FORMAT;
        desc.depth_test = true;
        desc.depth_write = true;
        desc.depth_bias = Some((2.0, 1.0));
        let pipeline = Pipeline::graphics(ctx, &desc)?;
        // Ready for sampling from the start: a scene without a shadowed light never renders it,
        // but the shading passes still bind it.
        ctx.submit_and_wait("shadow map layout", |cmd| {
            gpu::image_barrier(
                ctx,
                cmd,
                &map,
                vk::ImageLayout::UNDEFINED,
                vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL,
                scope::NONE,
                scope::NONE,
            )
        })?;
        Ok(ShadowPass { ctx: ctx.clone(), pipeline, map })
    }

    /// Renders the shadow map and leaves it ready for sampling in fragment and compute shaders.
    pub fn record(&self, cmd: vk::CommandBuffer, scene: &SceneGpu) {
        let ctx = &self.ctx;
        let e = self.map.desc.extent;
        let sampled = (
            vk::PipelineStageFlags2::FRAGMENT_SHADER | vk::PipelineStageFlags2::COMPUTE_SHADER,
            vk::AccessFlags2::SHADER_SAMPLED_READ,
        );
        gpu::image_barrier(
            ctx,
            cmd,
            &self.map,
            vk::ImageLayout::UNDEFINED,
            vk::ImageLayout::DEPTH_ATTACHMENT_OPTIMAL,
            sampled,
            scope::DEPTH_RW,
        );
        let att = Attachments {
            color: None,
            depth: Some((&self.map, vk::AttachmentLoadOp::CLEAR)),
            width: e.width,
            height: e.height,
        };
        gpu::render(ctx, cmd, att, || {
            self.pipeline.bind(cmd, &[scene.set.raw]);
            scene.draw(cmd, self.pipeline.layout, false);
        });
        gpu::image_barrier(
            ctx,
            cmd,
            &self.map,
            vk::ImageLayout::DEPTH_ATTACHMENT_OPTIMAL,
            vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL,
            scope::DEPTH_RW,
            sampled,
        );
    }
}
