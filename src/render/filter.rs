//! Radiance filtering (Freed 2018 §4.4): the full mip chain of the radiance volume, one
//! compute dispatch per level, each voxel the average of its 8 children, with a barrier
//! between levels; the radiance moment (level 0 from the radiance and each voxel's lit side,
//! then the same average); optionally also six directional (anisotropic) chains (Crassin et
//! al. 2011).

use std::sync::Arc;

use ash::vk;

use super::radiance::RadianceVolume;
use crate::config::WORKGROUP_3D;
use crate::error::Result;
use crate::gpu::{self, scope, shaders, Binding, Context, DescriptorSet, Pipeline, Stage};
use crate::voxel::VoxelVolume;

pub struct FilterPass {
    ctx: Arc<Context>,
    pipeline: Pipeline,
    aniso_pipeline: Pipeline,
    moment_pipeline: Pipeline,
    /// Set `l - 1` builds directional level `l` (of every direction).
    aniso_sets: DescriptorSet,
    /// `offsets[d][m]`: where chain `d` starts at chain mip `m` (atlas texels along y).
    offsets: Vec<Vec<u32>>,
    /// Set `l - 1` reads level `l - 1` and writes level `l` of the radiance; set
    /// `levels - 1 + l - 1` does so for the moment.
    sets: DescriptorSet,
    moment_set: DescriptorSet,
    /// Level 0's extent (voxels along each axis).
    dims: [u32; 3],
    levels: u32,
}

fn storage_info(view: vk::ImageView) -> vk::DescriptorImageInfo {
    vk::DescriptorImageInfo { sampler: vk::Sampler::null(), image_view: view, image_layout: vk::ImageLayout::GENERAL }
}

impl FilterPass {
    pub fn new(ctx: &Arc<Context>, volume: &RadianceVolume, voxels: &VoxelVolume) -> Result<Self> {
        let c = vk::ShaderStageFlags::COMPUTE;
        let storage = |b| Binding::new(b, vk::DescriptorType::STORAGE_IMAGE, c);
        let st = vk::DescriptorType::STORAGE_IMAGE;
        let per_chain = volume.levels.saturating_sub(1);
        let sets = DescriptorSet::new_many(ctx, "mip filter", &[storage(0), storage(1)], 2 * per_chain)?;
        for (k, chain) in [&volume.radiance, &volume.moment].into_iter().enumerate() {
            for level in 1..volume.levels {
                let set = k * per_chain as usize + level as usize - 1;
                sets.write_images_at(set, 0, st, &[storage_info(chain.mip_view(level - 1))]);
                sets.write_images_at(set, 1, st, &[storage_info(chain.mip_view(level))]);
            }
        }
        let pipeline = Pipeline::compute(ctx, "mip filter", Stage::new(c, shaders::GI_FILTER_COMP), &[sets.layout], 0)?;

        let moment_set = DescriptorSet::new(ctx, "radiance moment", &(0..4).map(storage).collect::<Vec<_>>())?;
        moment_set.write_images(0, st, &[storage_info(volume.radiance.mip_view(0))]);
        moment_set.write_storage(1, volume.lit_side.view.raw);
        moment_set.write_storage(2, voxels.emission.view.raw);
        moment_set.write_images(3, st, &[storage_info(volume.moment.mip_view(0))]);
        let moment_pipeline =
            Pipeline::compute(ctx, "radiance moment", Stage::new(c, shaders::GI_MOMENT_COMP), &[moment_set.layout], 0)?;

        let aniso_sets =
            DescriptorSet::new_many(ctx, "anisotropic mip filter", &[storage(0), storage(1), storage(2)], per_chain)?;
        for level in 1..volume.levels {
            let set = level as usize - 1;
            let src = if level == 1 { volume.radiance.mip_view(0) } else { volume.aniso.mip_view(level - 2) };
            aniso_sets.write_images_at(set, 0, st, &[storage_info(src)]);
            aniso_sets.write_images_at(set, 1, st, &[storage_info(volume.aniso.mip_view(level - 1))]);
            aniso_sets.write_images_at(set, 2, st, &[storage_info(volume.lit_side.view.raw)]);
        }
        // Where each chain's block starts at each chain mip (src of level l is mip l - 2).
        let offsets = (0..6).map(|d| (0..per_chain).map(|m| volume.chain_offset(d, m)).collect()).collect();
        let aniso_pipeline = Pipeline::compute(
            ctx,
            "anisotropic mip filter",
            Stage::new(c, shaders::GI_FILTER_ANISO_COMP),
            &[aniso_sets.layout],
            16,
        )?;
        Ok(FilterPass {
            ctx: ctx.clone(),
            pipeline,
            aniso_pipeline,
            moment_pipeline,
            aniso_sets,
            offsets,
            sets,
            moment_set,
            dims: volume.radiance.desc.size(),
            levels: volume.levels,
        })
    }

    fn dispatch_level(&self, cmd: vk::CommandBuffer, level: u32) {
        gpu::dispatch(&self.ctx, cmd, self.dims.map(|n| (n >> level).max(1)), [WORKGROUP_3D; 3]);
    }

    /// Builds the isotropic chain, the moment (when `moment`) and, when `anisotropic`, the six
    /// directional chains.
    pub fn record(&self, cmd: vk::CommandBuffer, anisotropic: bool, moment: bool) {
        let (w, r) = (scope::COMPUTE_WRITE, scope::COMPUTE_RW);
        let per_chain = self.levels as usize - 1;
        if moment {
            self.moment_pipeline.bind(cmd, &[self.moment_set.raw]);
            self.dispatch_level(cmd, 0);
            gpu::memory_barrier(&self.ctx, cmd, w, r);
        }
        for level in 1..self.levels {
            self.pipeline.bind(cmd, &[self.sets.sets[level as usize - 1]]);
            self.dispatch_level(cmd, level);
            if moment {
                self.pipeline.bind(cmd, &[self.sets.sets[per_chain + level as usize - 1]]);
                self.dispatch_level(cmd, level);
            }
            gpu::memory_barrier(&self.ctx, cmd, w, r);
        }
        if anisotropic {
            for level in 1..self.levels {
                self.aniso_pipeline.bind(cmd, &[self.aniso_sets.sets[level as usize - 1]]);
                for d in 0..6 {
                    let src = if level == 1 { 0 } else { self.offsets[d][level as usize - 2] };
                    let dst = self.offsets[d][level as usize - 1];
                    self.aniso_pipeline.push(cmd, &[d as u32, (level == 1) as u32, src, dst]);
                    self.dispatch_level(cmd, level);
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
