//! Temporal filtering (Freed 2018 §4.7.2): level 0 of the radiance volume becomes
//! mix(previous, new, factor), the previous frame's level 0 reprojected when the volume moves
//! (`gi/blend.comp`). The new radiance is the injected light, or with several bounces each
//! bounce's result in turn; only a frame's last one blends with the history.
//!
//! Over the occupied voxels (`listed`), the blend runs on the occupied-voxel list after clearing
//! level 0: only occupied voxels keep light, with or without a history (a voxel its geometry
//! has left keeps none, so no light trails behind a moving volume).
//!
//! Level 0 and the history are stored as the per-voxel targets (voxel::bricks). With sparse
//! storage the grid is fixed, so the previous frame's voxel is this one's, in the same slot. With
//! one bounce and no temporal filter nothing is blended in: level 0 is the injected light itself
//! and this pass does not run (`RadianceVolume::level0`).

use std::sync::Arc;

use ash::vk;

use super::radiance::RadianceVolume;
use crate::error::Result;
use crate::gpu::{self, scope, shaders, Binding, Context, DescriptorSet, Image, Pipeline, Stage};
use crate::scene::gpu::SceneGpu;
use crate::voxel::occupied::OccupiedVoxels;

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
    /// Over the occupied voxels.
    listed: bool,
    /// Clear level 0 before a listed blend (not where the occupied set is fixed, see `new`).
    clear: bool,
}

impl TemporalBlend {
    /// `listed`: over the voxels of `voxels`' occupied list (its sources stored as its voxels).
    /// `fixed`: the list holds the same voxels every frame (a fitted grid: the scene is static),
    /// so the voxels it leaves unwritten stay as the volume was created, empty, and need no
    /// clear; a moving grid's would keep the light of voxels its geometry left.
    pub fn new(
        ctx: &Arc<Context>,
        scene: &SceneGpu,
        radiance: &RadianceVolume,
        voxels: &crate::voxel::VoxelVolume,
        listed: bool,
        fixed: bool,
    ) -> Result<Self> {
        let c = vk::ShaderStageFlags::COMPUTE;
        let storage = |b| Binding::new(b, vk::DescriptorType::STORAGE_IMAGE, c);
        let sources: Vec<&Image> = std::iter::once(&radiance.injected).chain(radiance.bounced.as_ref()).collect();
        let sets = DescriptorSet::new_many(
            ctx,
            "temporal blend",
            &[
                storage(0),
                storage(1),
                Binding::new(2, vk::DescriptorType::COMBINED_IMAGE_SAMPLER, c),
                Binding::new(3, vk::DescriptorType::STORAGE_BUFFER, c),
                Binding::new(4, vk::DescriptorType::STORAGE_BUFFER, c),
            ],
            sources.len() as u32,
        )?;
        let info = |view| vk::DescriptorImageInfo {
            sampler: vk::Sampler::null(),
            image_view: view,
            image_layout: vk::ImageLayout::GENERAL,
        };
        for (i, src) in sources.iter().enumerate() {
            sets.write_images_at(i, 0, vk::DescriptorType::STORAGE_IMAGE, &[info(src.view.raw)]);
            sets.write_images_at(i, 1, vk::DescriptorType::STORAGE_IMAGE, &[info(radiance.level0().view.raw)]);
            sets.write_images_at(
                i,
                2,
                vk::DescriptorType::COMBINED_IMAGE_SAMPLER,
                &[vk::DescriptorImageInfo { sampler: radiance.sampler.raw, ..info(radiance.history.view.raw) }],
            );
            sets.write_buffer_at(i, 3, vk::DescriptorType::STORAGE_BUFFER, &voxels.occupied.list);
            sets.write_buffer_at(i, 4, vk::DescriptorType::STORAGE_BUFFER, &voxels.bricks.table);
        }
        let pipeline = Pipeline::compute(
            ctx,
            "temporal blend",
            Stage::new(c, shaders::GI_BLEND_COMP).spec(&voxels.bricks.spec(listed as u32)),
            &[scene.set.layout, sets.layout],
            4,
        )?;
        Ok(TemporalBlend {
            ctx: ctx.clone(),
            pipeline,
            sets,
            dims: voxels.grid.dims.into(),
            listed,
            clear: listed && !fixed,
        })
    }

    /// Keeps the previous frame's level 0 for the blend to reproject (before the first blend).
    pub fn record_history(&self, cmd: vk::CommandBuffer, radiance: &RadianceVolume) {
        gpu::copy_level(&self.ctx, cmd, radiance.level0(), 0, &radiance.history);
    }

    /// Writes level 0 from `source`, mixed with the history when `history` (of `radiance`, over
    /// `occupied`'s voxels when listed).
    pub fn record(
        &self,
        cmd: vk::CommandBuffer,
        scene: &SceneGpu,
        radiance: &RadianceVolume,
        occupied: &OccupiedVoxels,
        source: Source,
        history: bool,
    ) {
        let set = match source {
            Source::Injected => self.sets.sets[0],
            Source::Bounced => self.sets.sets[1],
        };
        if self.clear {
            gpu::clear_mips(&self.ctx, cmd, radiance.level0(), 0..1, scope::ANY);
            gpu::memory_barrier(&self.ctx, cmd, scope::CLEAR_WRITE, scope::COMPUTE_RW);
        }
        self.pipeline.bind(cmd, &[scene.set.raw, set]);
        self.pipeline.push(cmd, &(history as u32));
        occupied.dispatch_or_dense(cmd, self.listed, self.dims);
        gpu::memory_barrier(&self.ctx, cmd, scope::COMPUTE_WRITE, scope::COMPUTE_RW);
    }
}
