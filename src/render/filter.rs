//! Radiance filtering (Freed 2018 §4.4): the isotropic chain above level 0 (level 1 from level
//! 0, which is stored as the per-voxel textures, in the brick pool with sparse storage), one
//! compute dispatch per level, each texel the average of its 8 children, with a barrier
//! between levels; the radiance moment (level 1 from the radiance and each voxel's lit side,
//! then the same average); optionally also six directional (anisotropic) chains (Crassin et
//! al. 2011). Only the chains the model reads are built (`radiance::Chains`).
//!
//! With `listed` every level's dispatch runs over that level's occupied texels
//! ([`ParentLists`], built from the occupied voxels), not over every texel: an empty texel's
//! filtered value is zero, so the result is the dense filter's exactly, at a cost that follows
//! the scene's occupied voxels. The levels are cleared first, and the lists rebuilt, unless
//! the grid is fixed: then the occupied set is the same every frame.

use std::sync::Arc;

use ash::vk;

use super::occupancy::ParentLists;
use super::radiance::RadianceVolume;
use crate::config::WORKGROUP_3D;
use crate::error::Result;
use crate::gpu::{self, scope, shaders, Binding, Context, DescriptorSet, Pipeline, Stage};
use crate::voxel::occupied::OccupiedVoxels;
use crate::voxel::VoxelVolume;

pub struct FilterPass {
    ctx: Arc<Context>,
    pipeline: Pipeline,
    aniso_pipeline: Pipeline,
    moment_pipeline: Pipeline,
    /// Set `l - 1` builds directional level `l` (of every direction).
    aniso_sets: DescriptorSet,
    /// `offsets[d][m]`: where chain `d` starts at chain mip `m` (atlas texels along its stacking axis).
    offsets: Vec<Vec<u32>>,
    /// Set `l - 1` reads level `l - 1` and writes level `l` of the radiance; set
    /// `levels - 1 + l - 1` does so for the moment.
    sets: DescriptorSet,
    moment_set: DescriptorSet,
    /// Level 0's extent (voxels along each axis).
    dims: [u32; 3],
    levels: u32,
    /// Over the occupied texels of each level (`None`: over every texel).
    parents: Option<ParentLists>,
    /// Clear what the listed dispatches leave unwritten each frame (not where the occupied set
    /// is fixed: see TemporalBlend::new).
    clear: bool,
    /// A clipmap level's extent along z, its levels stacked along z (0: one grid).
    slab: u32,
}

/// gi/filter_aniso.comp's push constants (its `Push` block, field for field).
#[repr(C)]
#[derive(Clone, Copy, Default, bytemuck::Pod, bytemuck::Zeroable)]
struct AnisoPush {
    direction: u32,
    /// 1: level 1, every chain from level 0 (`base_at`); 0: one chain's level from the one below.
    base: u32,
    axis: u32,
    src_at: u32,
    dst_at: u32,
    size: [u32; 3],
    slab: u32,
    base_at: [u32; 6],
}

// A listed dispatch has one WORKGROUP_1D-sized group per WORKGROUP_1D listed texels, and the
// filters' groups are WORKGROUP_3D³.
const _: () = assert!(WORKGROUP_3D * WORKGROUP_3D * WORKGROUP_3D == crate::config::WORKGROUP_1D);

fn storage_info(view: vk::ImageView) -> vk::DescriptorImageInfo {
    vk::DescriptorImageInfo { sampler: vk::Sampler::null(), image_view: view, image_layout: vk::ImageLayout::GENERAL }
}

impl FilterPass {
    /// `listed`: filter over the occupied texels of each level (fed by `occupied`); `fixed`: the
    /// same texels every frame (as TemporalBlend::new).
    pub fn new(
        ctx: &Arc<Context>,
        volume: &RadianceVolume,
        voxels: &VoxelVolume,
        occupied: &OccupiedVoxels,
        listed: bool,
        fixed: bool,
    ) -> Result<Self> {
        let c = vk::ShaderStageFlags::COMPUTE;
        let storage = |b| Binding::new(b, vk::DescriptorType::STORAGE_IMAGE, c);
        let list = |b| Binding::new(b, vk::DescriptorType::STORAGE_BUFFER, c);
        let (st, sb) = (vk::DescriptorType::STORAGE_IMAGE, vk::DescriptorType::STORAGE_BUFFER);
        let dims: [u32; 3] = voxels.grid.dims.into();
        let bricks = voxels.bricks.stored_bricks();
        let parents = listed.then(|| ParentLists::new(ctx, dims, volume.levels, occupied, bricks)).transpose()?;
        // Level l's list (the occupied voxels' own list stands in when the dispatch is dense:
        // the binding must hold a buffer).
        let level_list = |level: u32| parents.as_ref().map_or(&occupied.list, |p| &p.levels[level as usize - 1].list);
        let per_chain = volume.levels.saturating_sub(1);
        let sets =
            DescriptorSet::new_many(ctx, "mip filter", &[storage(0), storage(1), list(2), list(3)], 2 * per_chain)?;
        // Both chains start at level 1 (their mip 0): the isotropic one's is filtered from level
        // 0, stored as the per-voxel targets; the moment's is written by gi/moment.comp.
        for (k, chain, first) in [(0, &volume.chain, 0), (1, &volume.moment, 1)] {
            if chain.desc.mip_levels + 1 < volume.levels {
                continue; // the isotropic chain, unallocated: never built
            }
            for level in first + 1..volume.levels {
                let set = k * per_chain as usize + level as usize - 1;
                let src = if level == 1 { volume.level0().view.raw } else { chain.mip_view(level - 2) };
                sets.write_images_at(set, 0, st, &[storage_info(src)]);
                sets.write_images_at(set, 1, st, &[storage_info(chain.mip_view(level - 1))]);
                sets.write_buffer_at(set, 2, sb, level_list(level));
                sets.write_buffer_at(set, 3, sb, &voxels.bricks.table);
            }
        }
        let pipeline = Pipeline::compute(
            ctx,
            "mip filter",
            Stage::new(c, shaders::GI_FILTER_COMP).spec(&voxels.bricks.spec(listed as u32)),
            &[sets.layout],
            4,
        )?;

        let moment_set = DescriptorSet::new(
            ctx,
            "radiance moment",
            &[storage(0), storage(1), storage(2), storage(3), list(4), list(5)],
        )?;
        moment_set.write_images(0, st, &[storage_info(volume.level0().view.raw)]);
        moment_set.write_storage(1, volume.lit_side.view.raw);
        moment_set.write_storage(2, voxels.emission.view.raw);
        moment_set.write_images(3, st, &[storage_info(volume.moment.mip_view(0))]);
        moment_set.write_buffer(4, sb, level_list(1));
        moment_set.write_buffer(5, sb, &voxels.bricks.table);
        let stored = voxels.bricks.spec(listed as u32);
        let moment_pipeline = Pipeline::compute(
            ctx,
            "radiance moment",
            Stage::new(c, shaders::GI_MOMENT_COMP).spec(&stored),
            &[moment_set.layout],
            0,
        )?;

        let aniso_sets = DescriptorSet::new_many(
            ctx,
            "anisotropic mip filter",
            &[storage(0), storage(1), storage(2), list(3), list(4)],
            per_chain,
        )?;
        for level in (1..volume.levels).filter(|_| volume.chains.directional) {
            let set = level as usize - 1;
            let src = if level == 1 { volume.level0().view.raw } else { volume.aniso.mip_view(level - 2) };
            aniso_sets.write_images_at(set, 0, st, &[storage_info(src)]);
            aniso_sets.write_images_at(set, 1, st, &[storage_info(volume.aniso.mip_view(level - 1))]);
            aniso_sets.write_images_at(set, 2, st, &[storage_info(volume.lit_side.view.raw)]);
            aniso_sets.write_buffer_at(set, 3, sb, level_list(level));
            aniso_sets.write_buffer_at(set, 4, sb, &voxels.bricks.table);
        }
        // Where each chain's block starts at each chain mip (src of level l is mip l - 2).
        let offsets = (0..6).map(|d| (0..per_chain).map(|m| volume.atlas.offset(d, m)).collect()).collect();
        let aniso_pipeline = Pipeline::compute(
            ctx,
            "anisotropic mip filter",
            Stage::new(c, shaders::GI_FILTER_ANISO_COMP).spec(&stored),
            &[aniso_sets.layout],
            std::mem::size_of::<AnisoPush>() as u32,
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
            dims,
            levels: volume.levels,
            parents,
            clear: listed && !fixed,
            slab: voxels.grid.clip.map_or(0, |c| c.res),
        })
    }

    /// Whether the filters run over the occupied texels of each level.
    pub fn is_listed(&self) -> bool {
        self.parents.is_some()
    }

    /// One invocation per texel of `level`, or per occupied texel (level 0: `occupied`'s).
    fn dispatch_level(&self, cmd: vk::CommandBuffer, level: u32, occupied: &OccupiedVoxels) {
        let list = match &self.parents {
            Some(p) if level > 0 => &p.levels[level as usize - 1],
            _ => occupied,
        };
        list.dispatch_or_dense(cmd, self.parents.is_some(), self.dims.map(|n| (n >> level).max(1)));
    }

    /// Builds the isotropic chain above level 0 (where `volume` has one: the cones of the
    /// isotropic model and the radiance view read it; the directional model's cones read only
    /// level 0), the moment
    /// (when `moment`) and, when `anisotropic`, the six directional chains; `occupied` is this
    /// frame's list of occupied voxels (its dispatch arguments written); `first_frame`: the
    /// renderer's first (the parent lists of a fixed occupied set are built then only).
    pub fn record(
        &self,
        cmd: vk::CommandBuffer,
        volume: &RadianceVolume,
        occupied: &OccupiedVoxels,
        anisotropic: bool,
        moment: bool,
        first_frame: bool,
    ) {
        let isotropic = volume.chains.isotropic;
        let (w, r) = (scope::COMPUTE_WRITE, scope::COMPUTE_RW);
        let per_chain = self.levels as usize - 1;
        // A fixed occupied set has the same parents every frame: they are listed once.
        let relist = self.clear || first_frame;
        if let Some(p) = self.parents.as_ref().filter(|_| relist) {
            // What the listed dispatches leave unwritten must be empty.
            let ctx = &self.ctx;
            if self.clear {
                if volume.chains.isotropic {
                    gpu::clear_mips(ctx, cmd, &volume.chain, 0..volume.chain.desc.mip_levels, scope::ANY);
                }
                gpu::clear_mips(ctx, cmd, &volume.moment, 0..volume.moment.desc.mip_levels, scope::ANY);
                gpu::clear_mips(ctx, cmd, &volume.aniso, 0..volume.aniso.desc.mip_levels, scope::ANY);
            }
            p.record(cmd, occupied);
            gpu::memory_barrier(ctx, cmd, scope::CLEAR_WRITE, r);
        }
        if moment {
            self.moment_pipeline.bind(cmd, &[self.moment_set.raw]);
            self.dispatch_level(cmd, 1, occupied);
            gpu::memory_barrier(&self.ctx, cmd, w, r);
        }
        if !isotropic && self.parents.is_none() && volume.chains.isotropic {
            // Unbuilt levels read as empty, as the listed path's clear leaves them.
            gpu::clear_mips(&self.ctx, cmd, &volume.chain, 0..volume.chain.desc.mip_levels, scope::ANY);
            gpu::memory_barrier(&self.ctx, cmd, scope::CLEAR_WRITE, r);
        }
        for level in 1..self.levels {
            if isotropic {
                self.pipeline.bind(cmd, &[self.sets.sets[level as usize - 1]]);
                self.pipeline.push(cmd, &[(level == 1) as u32]);
                self.dispatch_level(cmd, level, occupied);
            }
            if moment && level > 1 {
                self.pipeline.bind(cmd, &[self.sets.sets[per_chain + level as usize - 1]]);
                self.pipeline.push(cmd, &[0u32]);
                self.dispatch_level(cmd, level, occupied);
            }
            gpu::memory_barrier(&self.ctx, cmd, w, r);
        }
        if anisotropic {
            let axis = volume.atlas.axis as u32;
            for level in 1..self.levels {
                self.aniso_pipeline.bind(cmd, &[self.aniso_sets.sets[level as usize - 1]]);
                let size = volume.atlas.chain_at(level - 1);
                let m = level as usize - 1;
                // Level 1: one dispatch builds every chain (gi/filter_aniso.comp, filter_base).
                let directions = if level == 1 { 0..1 } else { 0..6 };
                for d in directions {
                    let push = AnisoPush {
                        direction: d as u32,
                        base: (level == 1) as u32,
                        axis,
                        src_at: if level == 1 { 0 } else { self.offsets[d][m - 1] },
                        dst_at: self.offsets[d][m],
                        size: size.into(),
                        slab: self.slab,
                        base_at: std::array::from_fn(|c| if level == 1 { self.offsets[c][0] } else { 0 }),
                    };
                    self.aniso_pipeline.push(cmd, &push);
                    self.dispatch_level(cmd, level, occupied);
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
