//! The occupied texels of every mip level above 0 (render::filter runs the mip filters over
//! them), built on the GPU from the occupied voxels the voxelizers list.

use std::sync::Arc;

use ash::vk;
use gpu_allocator::MemoryLocation;

use crate::error::Result;
use crate::gpu::{self, scope, shaders, Binding, Buffer, Context, DescriptorSet, Pipeline, Stage};
use crate::voxel::occupied::{list_bytes, OccupiedVoxels, HEADER};

/// The occupied texels of every mip level above 0: level l's list holds the parents of level
/// l - 1's (level 0's is [`OccupiedVoxels`], from the resolve pass), each once (a bit set per
/// level marks the parents already listed; `gi/parents.comp`). The mip filters run over these
/// lists, so their work follows the occupied texels, not the grid.
pub struct ParentLists {
    ctx: Arc<Context>,
    /// `levels[l - 1]`: level l's list and its dispatch arguments.
    pub levels: Vec<OccupiedVoxels>,
    marks: Vec<Buffer>,
    /// Texels of each level (x, y, z), from level 1.
    sizes: Vec<[u32; 3]>,
    pipeline: Pipeline,
    /// Set `l - 1` reads level l - 1's list and writes level l's.
    sets: DescriptorSet,
}

/// Words of the bit set over `texels` texels.
fn mark_words(texels: u64) -> u64 {
    texels.div_ceil(32)
}

/// Room in each level's list, from level 1, for level-0 extent `dims` with `levels` mip levels:
/// every texel of the level, or with sparse storage no more than the pool's `bricks`. A texel
/// of a level whose texels are at least a brick wide holds whole bricks, and the voxelizers list
/// only voxels of claimed bricks (common/voxel.glsl), so such a level has at most one occupied
/// texel a brick.
pub fn parent_capacities(dims: [u32; 3], levels: u32, bricks: Option<u64>) -> Vec<u64> {
    (1..levels)
        .map(|l| {
            let texels: u64 = dims.iter().map(|&d| (d >> l).max(1) as u64).product();
            match bricks {
                Some(b) if 1u32 << l >= crate::config::BRICK_SIZE => texels.min(b),
                _ => texels,
            }
        })
        .collect()
}

/// Bytes of every level's list and bit set (as [`parent_capacities`]).
pub fn parent_list_bytes(dims: [u32; 3], levels: u32, bricks: Option<u64>) -> u64 {
    (1..levels)
        .zip(parent_capacities(dims, levels, bricks))
        .map(|(l, room)| {
            let texels: u64 = dims.iter().map(|&d| (d >> l).max(1) as u64).product();
            list_bytes(room) + 4 * mark_words(texels)
        })
        .sum()
}

impl ParentLists {
    /// Lists for the mip levels 1..`levels` of a level-0 extent `dims`, fed by `base`; `bricks`:
    /// the brick pool's claimable slots with sparse storage (see [`parent_capacities`]).
    pub fn new(
        ctx: &Arc<Context>,
        dims: [u32; 3],
        levels: u32,
        base: &OccupiedVoxels,
        bricks: Option<u64>,
    ) -> Result<Self> {
        let sizes: Vec<[u32; 3]> = (1..levels).map(|l| dims.map(|d| (d >> l).max(1))).collect();
        let texels = |s: &[u32; 3]| s.iter().map(|&d| d as u64).product::<u64>();
        let levels_: Vec<OccupiedVoxels> = parent_capacities(dims, levels, bricks)
            .into_iter()
            .map(|room| OccupiedVoxels::new(ctx, room))
            .collect::<Result<_>>()?;
        let usage = vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::TRANSFER_DST;
        let marks: Vec<Buffer> = sizes
            .iter()
            .map(|s| {
                Buffer::new(ctx, "occupied parent marks", 4 * mark_words(texels(s)), usage, MemoryLocation::GpuOnly)
            })
            .collect::<Result<_>>()?;
        let c = vk::ShaderStageFlags::COMPUTE;
        let b = |i| Binding::new(i, vk::DescriptorType::STORAGE_BUFFER, c);
        let sets = DescriptorSet::new_many(ctx, "occupied parents", &[b(0), b(1), b(2)], sizes.len() as u32)?;
        let st = vk::DescriptorType::STORAGE_BUFFER;
        for l in 0..sizes.len() {
            let src = if l == 0 { &base.list } else { &levels_[l - 1].list };
            sets.write_buffer_at(l, 0, st, src);
            sets.write_buffer_at(l, 1, st, &levels_[l].list);
            sets.write_buffer_at(l, 2, st, &marks[l]);
        }
        let pipeline =
            Pipeline::compute(ctx, "occupied parents", Stage::new(c, shaders::GI_PARENTS_COMP), &[sets.layout], 16)?;
        Ok(ParentLists { ctx: ctx.clone(), levels: levels_, marks, sizes, pipeline, sets })
    }

    /// Rebuilds every level's list from `base` (after its arguments are written).
    pub fn record(&self, cmd: vk::CommandBuffer, base: &OccupiedVoxels) {
        let ctx = &self.ctx;
        gpu::memory_barrier(ctx, cmd, scope::ANY, scope::TRANSFER_WRITE);
        for (list, marks) in self.levels.iter().zip(&self.marks) {
            gpu::fill_buffer(ctx, cmd, &list.list, HEADER, 0);
            gpu::fill_buffer(ctx, cmd, marks, vk::WHOLE_SIZE, 0);
        }
        gpu::memory_barrier(ctx, cmd, scope::TRANSFER_WRITE, scope::COMPUTE_RW);
        for (l, size) in self.sizes.iter().enumerate() {
            let src = if l == 0 { base } else { &self.levels[l - 1] };
            self.pipeline.bind(cmd, &[self.sets.sets[l]]);
            self.pipeline.push(cmd, &[size[0], size[1], size[2], 0]);
            src.dispatch(cmd);
            gpu::memory_barrier(ctx, cmd, scope::COMPUTE_WRITE, scope::COMPUTE_RW);
            self.levels[l].record_args(cmd);
        }
    }
}
