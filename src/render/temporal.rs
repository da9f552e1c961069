//! Temporal filtering (Freed 2018 §4.7.2): level 0 of the radiance volume becomes
//! mix(previous, new, factor), the previous frame's level 0 reprojected when the volume moves
//! (`gi/blend.comp`). The new radiance is the injected light, or with several bounces each
//! bounce's result in turn; only a frame's last one blends with the history.

use std::sync::Arc;

use ash::vk;

use super::radiance::RadianceVolume;
use crate::config::WORKGROUP_3D;
use crate::error::Result;
use crate::gpu::{self, scope, shaders, Binding, Context, DescriptorSet, Image, Pipeline, Stage};
use crate::scene::gpu::SceneGpu;

/// Which image a blend reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Source {
    Injected,
    Bounced,
}

pub struct TemporalBlend {
    ctx: Arc<Context>,
    pipeline: Pipeline,
    /// One set per [`Source`] (the bounced one only when the volume has that image).
    sets: DescriptorSet,
    /// Level 0's extent.
    dims: [u32; 3],
}

impl TemporalBlend {
    pub fn new(ctx: &Arc<Context>, scene: &SceneGpu, radiance: &RadianceVolume) -> Result<Self> {
        let c = vk::ShaderStageFlags::COMPUTE;
        let storage = |b| Binding::new(b, vk::DescriptorType::STORAGE_IMAGE, c);
        let sources: Vec<&Image> = std::iter::once(&radiance.injected).chain(radiance.bounced.as_ref()).collect();
        let sets = DescriptorSet::new_many(
            ctx,
            "temporal blend",
            &[storage(0), storage(1), Binding::new(2, vk::DescriptorType::COMBINED_IMAGE_SAMPLER, c)],
            sources.len() as u32,
        )?;
        let info = |view| vk::DescriptorImageInfo {
            sampler: vk::Sampler::null(),
            image_view: view,
            image_layout: vk::ImageLayout::GENERAL,
        };
        for (i, src) in sources.iter().enumerate() {
            sets.write_images_at(i, 0, vk::DescriptorType::STORAGE_IMAGE, &[info(src.view.raw)]);
            sets.write_images_at(i, 1, vk::DescriptorType::STORAGE_IMAGE, &[info(radiance.radiance.mip_view(0))]);
            sets.write_images_at(
                i,
                2,
                vk::DescriptorType::COMBINED_IMAGE_SAMPLER,
                &[vk::DescriptorImageInfo { sampler: radiance.sampler.raw, ..info(radiance.history.view.raw) }],
            );
        }
        let pipeline = Pipeline::compute(
            ctx,
            "temporal blend",
            Stage::new(c, shaders::GI_BLEND_COMP),
            &[scene.set.layout, sets.layout],
            4,
        )?;
        Ok(TemporalBlend { ctx: ctx.clone(), pipeline, sets, dims: radiance.radiance.desc.size() })
    }

    /// Keeps the previous frame's level 0 for the blend to reproject (before the first blend).
    pub fn record_history(&self, cmd: vk::CommandBuffer, radiance: &RadianceVolume) {
        gpu::copy_level(&self.ctx, cmd, &radiance.radiance, 0, &radiance.history);
    }

    /// Writes level 0 from `source`, mixed with the history when `history`.
    pub fn record(&self, cmd: vk::CommandBuffer, scene: &SceneGpu, source: Source, history: bool) {
        let set = match source {
            Source::Injected => self.sets.sets[0],
            Source::Bounced => self.sets.sets[1],
        };
        self.pipeline.bind(cmd, &[scene.set.raw, set]);
        self.pipeline.push(cmd, &(history as u32));
        gpu::dispatch(&self.ctx, cmd, self.dims, [WORKGROUP_3D; 3]);
        gpu::memory_barrier(&self.ctx, cmd, scope::COMPUTE_WRITE, scope::COMPUTE_RW);
    }
}
