//! Radiance filtering (Freed 2018 §4.4): the full mip chain of the radiance volume, one
//! compute dispatch per level, each voxel the average of its 8 children, with a barrier
//! between levels; optionally also six directional (anisotropic) chains (Crassin et al. 2011).

use std::sync::Arc;

use ash::vk;

use super::radiance::RadianceVolume;
use crate::config::WORKGROUP_3D;
use crate::error::Result;
use crate::gpu::{self, scope, shaders, Binding, Context, DescriptorSet, Pipeline, Stage};

pub struct FilterPass {
    ctx: Arc<Context>,
    pipeline: Pipeline,
    aniso_pipeline: Pipeline,
    /// Set `d * (levels - 1) + l - 1` builds directional level `l` of direction `d`.
    aniso_sets: DescriptorSet,
    /// Set `l - 1` reads level `l - 1` and writes level `l`.
    sets: DescriptorSet,
    resolution: u32,
    levels: u32,
}

impl FilterPass {
    pub fn new(ctx: &Arc<Context>, volume: &RadianceVolume) -> Result<Self> {
        let c = vk::ShaderStageFlags::COMPUTE;
        let storage = |b| Binding::new(b, vk::DescriptorType::STORAGE_IMAGE, c);
        let sets =
            DescriptorSet::new_many(ctx, "mip filter", &[storage(0), storage(1)], volume.levels.saturating_sub(1))?;
        let storage_info = |view| vk::DescriptorImageInfo {
            sampler: vk::Sampler::null(),
            image_view: view,
            image_layout: vk::ImageLayout::GENERAL,
        };
        for level in 1..volume.levels {
            let set = level as usize - 1;
            sets.write_images_at(
                set,
                0,
                vk::DescriptorType::STORAGE_IMAGE,
                &[storage_info(volume.radiance.mip_view(level - 1))],
            );
            sets.write_images_at(
                set,
                1,
                vk::DescriptorType::STORAGE_IMAGE,
                &[storage_info(volume.radiance.mip_view(level))],
            );
        }
        let pipeline = Pipeline::compute(ctx, "mip filter", Stage::new(c, shaders::GI_FILTER_COMP), &[sets.layout], 0)?;
        let per_dir = volume.levels.saturating_sub(1);
        let aniso_sets =
            DescriptorSet::new_many(ctx, "anisotropic mip filter", &[storage(0), storage(1), storage(2)], 6 * per_dir)?;
        for (d, chain) in volume.aniso.iter().enumerate() {
            for level in 1..volume.levels {
                let set = d * per_dir as usize + level as usize - 1;
                let src = if level == 1 { volume.radiance.mip_view(0) } else { chain.mip_view(level - 2) };
                aniso_sets.write_images_at(set, 0, vk::DescriptorType::STORAGE_IMAGE, &[storage_info(src)]);
                aniso_sets.write_images_at(
                    set,
                    1,
                    vk::DescriptorType::STORAGE_IMAGE,
                    &[storage_info(chain.mip_view(level - 1))],
                );
                aniso_sets.write_images_at(
                    set,
                    2,
                    vk::DescriptorType::STORAGE_IMAGE,
                    &[storage_info(volume.lit_side.view.raw)],
                );
            }
        }
        let aniso_pipeline = Pipeline::compute(
            ctx,
            "anisotropic mip filter",
            Stage::new(c, shaders::GI_FILTER_ANISO_COMP),
            &[aniso_sets.layout],
            8,
        )?;
        Ok(FilterPass {
            ctx: ctx.clone(),
            pipeline,
            aniso_pipeline,
            aniso_sets,
            sets,
            resolution: volume.radiance.desc.extent.width,
            levels: volume.levels,
        })
    }

    /// Builds the isotropic chain and, when `anisotropic`, the six directional chains.
    pub fn record(&self, cmd: vk::CommandBuffer, anisotropic: bool) {
        let (w, r) = (scope::COMPUTE_WRITE, scope::COMPUTE_RW);
        for level in 1..self.levels {
            self.pipeline.bind(cmd, &[self.sets.sets[level as usize - 1]]);
            let n = (self.resolution >> level).max(1);
            gpu::dispatch(&self.ctx, cmd, [n, n, n], [WORKGROUP_3D; 3]);
            gpu::memory_barrier(&self.ctx, cmd, w, r);
        }
        if anisotropic {
            let per_dir = self.levels as usize - 1;
            for level in 1..self.levels {
                let n = (self.resolution >> level).max(1);
                for d in 0..6u32 {
                    self.aniso_pipeline.bind(cmd, &[self.aniso_sets.sets[d as usize * per_dir + level as usize - 1]]);
                    self.aniso_pipeline.push(cmd, &[d, (level == 1) as u32]);
                    gpu::dispatch(&self.ctx, cmd, [n, n, n], [WORKGROUP_3D; 3]);
                }
                gpu::memory_barrier(&self.ctx, cmd, w, r);
            }
        }
        // The cones sample the whole chain in the fragment stage (and the volume view in compute).
        let sampled = (
            vk::PipelineStageFlags2::FRAGMENT_SHADER | vk::PipelineStageFlags2::COMPUTE_SHADER,
            vk::AccessFlags2::SHADER_SAMPLED_READ,
        );
        gpu::memory_barrier(&self.ctx, cmd, w, sampled);
    }
}
