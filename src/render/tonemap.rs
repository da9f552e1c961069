//! Tone mapping pass (Freed 2018 Algorithm 3): c/(c+1) and gamma 2.2 from the linear HDR
//! target into the 8-bit output image, in compute.

use std::sync::Arc;

use ash::vk;

use super::Targets;
use crate::error::Result;
use crate::gpu::{self, scope, shaders, Binding, Context, DescriptorSet, Pipeline, Stage};

pub struct TonemapPass {
    ctx: Arc<Context>,
    pipeline: Pipeline,
    set: DescriptorSet,
}

impl TonemapPass {
    pub fn new(ctx: &Arc<Context>, targets: &Targets) -> Result<Self> {
        let c = vk::ShaderStageFlags::COMPUTE;
        let set = DescriptorSet::new(
            ctx,
            "tonemap",
            &[
                Binding::new(0, vk::DescriptorType::STORAGE_IMAGE, c),
                Binding::new(1, vk::DescriptorType::STORAGE_IMAGE, c),
            ],
        )?;
        set.write_storage(0, targets.hdr.view.raw);
        set.write_storage(1, targets.ldr.view.raw);
        let pipeline = Pipeline::compute(ctx, "tonemap", Stage::new(c, shaders::POST_TONEMAP_COMP), &[set.layout], 4)?;
        Ok(TonemapPass { ctx: ctx.clone(), pipeline, set })
    }

    /// `raw`: the HDR target already holds [0, 1] values (skip the c/(c+1) curve).
    pub fn record(&self, cmd: vk::CommandBuffer, targets: &Targets, raw: bool) {
        let ctx = &self.ctx;
        let rw = (
            vk::PipelineStageFlags2::COMPUTE_SHADER | vk::PipelineStageFlags2::ALL_TRANSFER,
            vk::AccessFlags2::MEMORY_READ | vk::AccessFlags2::MEMORY_WRITE,
        );
        gpu::image_barrier(
            ctx,
            cmd,
            &targets.ldr,
            vk::ImageLayout::UNDEFINED,
            vk::ImageLayout::GENERAL,
            rw,
            scope::COMPUTE_WRITE,
        );
        self.pipeline.bind(cmd, &[self.set.raw]);
        self.pipeline.push(cmd, &(raw as u32));
        targets.dispatch_per_pixel(ctx, cmd);
        gpu::memory_barrier(ctx, cmd, scope::COMPUTE_WRITE, rw);
    }
}
