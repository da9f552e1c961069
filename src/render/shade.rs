//! Shading pass (Freed 2018 §4.5): forward fragment shading of the visible surfaces (depth
//! EQUAL after the prepass): direct light, then indirect light by cone tracing the radiance
//! volume, into the linear HDR target.
//!
//! This is the thesis' forward path (`--tracing forward`); the default is the deferred compute
//! variant in `deferred.rs`, which measured faster (see `Tracing`).

use std::sync::Arc;

use ash::vk;

use super::radiance::RadianceVolume;
use super::shadow::ShadowPass;
use super::Targets;
use crate::error::Result;
use crate::gpu::{
    self, scope, shaders, Attachments, Binding, Context, DescriptorSet, GraphicsDesc, Pipeline, Sampler, Stage,
};
use crate::scene::gpu::{vertex_layout, SceneGpu};

pub struct ShadePass {
    ctx: Arc<Context>,
    pipeline: Pipeline,
    set: DescriptorSet,
    _shadow_sampler: Sampler,
}

impl ShadePass {
    /// `anisotropic`: cones sample the six directional chains (specialization constant).
    pub fn new(
        ctx: &Arc<Context>,
        scene: &SceneGpu,
        shadow: &ShadowPass,
        radiance: &RadianceVolume,
        bricks: &crate::voxel::bricks::Bricks,
        anisotropic: bool,
        grid: crate::gpu::GridSpec,
    ) -> Result<Self> {
        let sampled = vk::DescriptorType::COMBINED_IMAGE_SAMPLER;
        let frag = vk::ShaderStageFlags::FRAGMENT;
        let set = DescriptorSet::new(
            ctx,
            "shade inputs",
            &(0..5)
                .map(|b| Binding::new(b, sampled, frag))
                .chain([Binding::new(5, vk::DescriptorType::STORAGE_BUFFER, frag)])
                .collect::<Vec<_>>(),
        )?;
        let shadow_sampler = Sampler::shadow(ctx, "shadow sampler")?;
        set.write_sampled(0, shadow.map.view.raw, shadow_sampler.raw);
        radiance.write_to(&set, 1);
        set.write_buffer(5, vk::DescriptorType::STORAGE_BUFFER, &bricks.table);
        // Constants 3 and 4: whether any light is an area light (common/light.glsl), and whether
        // any material reflects specularly (common/shading.glsl).
        let spec =
            [bricks.spec(anisotropic as u32).as_slice(), &[scene.area_lights as u32, scene.specular as u32]].concat();
        let mut desc = GraphicsDesc::new(
            "shade",
            vec![
                Stage::new(vk::ShaderStageFlags::VERTEX, shaders::SCENE_SCENE_VERT).spec(&[0]),
                Stage::new(vk::ShaderStageFlags::FRAGMENT, shaders::SHADE_FORWARD_FRAG).spec(&spec).grid(grid),
            ],
        );
        desc.set_layouts = vec![scene.set.layout, scene.material_sets.layout, set.layout];
        desc.push_constant_size = 4;
        desc.vertex = Some(vertex_layout());
        desc.depth_format = Targets::DEPTH_FORMAT;
        desc.depth_test = true;
        desc.depth_write = false;
        desc.depth_compare = vk::CompareOp::EQUAL;
        desc.color_formats = vec![Targets::HDR_FORMAT];
        let pipeline = Pipeline::graphics(ctx, &desc)?;
        Ok(ShadePass { ctx: ctx.clone(), pipeline, set, _shadow_sampler: shadow_sampler })
    }

    /// Shades into `targets.hdr`, leaving it in GENERAL for the compute passes that follow.
    pub fn record(&self, cmd: vk::CommandBuffer, scene: &SceneGpu, targets: &Targets) {
        let ctx = &self.ctx;
        let depth_w = (
            vk::PipelineStageFlags2::EARLY_FRAGMENT_TESTS | vk::PipelineStageFlags2::LATE_FRAGMENT_TESTS,
            vk::AccessFlags2::DEPTH_STENCIL_ATTACHMENT_WRITE,
        );
        let depth_r = (
            vk::PipelineStageFlags2::EARLY_FRAGMENT_TESTS | vk::PipelineStageFlags2::LATE_FRAGMENT_TESTS,
            vk::AccessFlags2::DEPTH_STENCIL_ATTACHMENT_READ,
        );
        gpu::memory_barrier(ctx, cmd, depth_w, depth_r);
        gpu::image_barrier(
            ctx,
            cmd,
            &targets.hdr,
            vk::ImageLayout::UNDEFINED,
            vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
            scope::COMPUTE_RW,
            scope::COLOR_WRITE,
        );
        let att = Attachments {
            color: Some((&targets.hdr, vk::AttachmentLoadOp::CLEAR, [0.0, 0.0, 0.0, 0.0])),
            depth: Some((&targets.depth, vk::AttachmentLoadOp::LOAD)),
            width: targets.width,
            height: targets.height,
        };
        gpu::render(ctx, cmd, att, || {
            self.pipeline.bind(cmd, &[scene.set.raw]);
            self.pipeline.bind_set(cmd, 2, self.set.raw);
            scene.draw(cmd, self.pipeline.layout, true);
        });
        gpu::image_barrier(
            ctx,
            cmd,
            &targets.hdr,
            vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
            vk::ImageLayout::GENERAL,
            scope::COLOR_WRITE,
            scope::COMPUTE_RW,
        );
    }
}
