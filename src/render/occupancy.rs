//! The compact list of occupied voxels (OPEngine's sparse voxel list): the resolve pass appends
//! every occupied voxel with an atomic counter (`shaders-glsl/common/occupied.glsl`), and a
//! one-invocation pass turns the count into indirect dispatch arguments, so that the passes over
//! voxels (the voxel-space bounce) run one invocation per occupied voxel, not per grid voxel.

use std::sync::Arc;

use ash::vk;
use gpu_allocator::MemoryLocation;

use crate::error::Result;
use crate::gpu::{self, scope, shaders, Binding, Buffer, Context, DescriptorSet, Pipeline, Stage};

/// Bytes before the first voxel of the list (the count, padded to 16).
const HEADER: u64 = 16;

pub struct OccupiedVoxels {
    ctx: Arc<Context>,
    /// The count and the packed voxel coordinates (room for every voxel of the grid).
    pub list: Buffer,
    /// `VkDispatchIndirectCommand` for WORKGROUP_1D invocations per listed voxel.
    pub args: Buffer,
    pipeline: Pipeline,
    set: DescriptorSet,
}

/// Bytes of the list for a grid of `voxels` (room for every voxel).
pub fn list_bytes(voxels: u64) -> u64 {
    HEADER + 4 * voxels
}

impl OccupiedVoxels {
    pub fn new(ctx: &Arc<Context>, voxels: u64) -> Result<Self> {
        let storage = vk::BufferUsageFlags::STORAGE_BUFFER;
        let list = Buffer::new(
            ctx,
            "occupied voxels",
            list_bytes(voxels),
            storage | vk::BufferUsageFlags::TRANSFER_DST,
            MemoryLocation::GpuOnly,
        )?;
        let args = Buffer::new(
            ctx,
            "occupied dispatch",
            12,
            storage | vk::BufferUsageFlags::INDIRECT_BUFFER,
            MemoryLocation::GpuOnly,
        )?;
        let c = vk::ShaderStageFlags::COMPUTE;
        let b = |i| Binding::new(i, vk::DescriptorType::STORAGE_BUFFER, c);
        let set = DescriptorSet::new(ctx, "occupied dispatch", &[b(0), b(1)])?;
        set.write_buffer(0, vk::DescriptorType::STORAGE_BUFFER, &list);
        set.write_buffer(1, vk::DescriptorType::STORAGE_BUFFER, &args);
        let pipeline = Pipeline::compute(
            ctx,
            "occupied dispatch",
            Stage::new(c, shaders::GI_OCCUPIED_ARGS_COMP),
            &[set.layout],
            0,
        )?;
        Ok(OccupiedVoxels { ctx: ctx.clone(), list, args, pipeline, set })
    }

    /// Empties the list, before the pass that appends to it.
    pub fn record_reset(&self, cmd: vk::CommandBuffer) {
        gpu::memory_barrier(&self.ctx, cmd, scope::ANY, scope::TRANSFER_WRITE);
        gpu::fill_buffer(&self.ctx, cmd, &self.list, HEADER, 0);
        gpu::memory_barrier(&self.ctx, cmd, scope::TRANSFER_WRITE, scope::COMPUTE_RW);
    }

    /// Writes the dispatch arguments from the count (after the appending pass's barrier).
    pub fn record_args(&self, cmd: vk::CommandBuffer) {
        self.pipeline.bind(cmd, &[self.set.raw]);
        gpu::dispatch(&self.ctx, cmd, [1, 1, 1], [1, 1, 1]);
        let read = (
            vk::PipelineStageFlags2::DRAW_INDIRECT | vk::PipelineStageFlags2::COMPUTE_SHADER,
            vk::AccessFlags2::INDIRECT_COMMAND_READ | vk::AccessFlags2::SHADER_STORAGE_READ,
        );
        gpu::memory_barrier(&self.ctx, cmd, scope::COMPUTE_WRITE, read);
    }

    /// Dispatches the bound pipeline over the listed voxels.
    pub fn dispatch(&self, cmd: vk::CommandBuffer) {
        gpu::dispatch_indirect(&self.ctx, cmd, &self.args);
    }
}

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

/// Bytes of every level's list and bit set, from level 1, for level-0 extent `dims` with
/// `levels` mip levels.
pub fn parent_list_bytes(dims: [u32; 3], levels: u32) -> u64 {
    (1..levels)
        .map(|l| {
            let texels: u64 = dims.iter().map(|&d| (d >> l).max(1) as u64).product();
            list_bytes(texels) + 4 * mark_words(texels)
        })
        .sum()
}

impl ParentLists {
    /// Lists for the mip levels 1..`levels` of a level-0 extent `dims`, fed by `base`.
    pub fn new(ctx: &Arc<Context>, dims: [u32; 3], levels: u32, base: &OccupiedVoxels) -> Result<Self> {
        let sizes: Vec<[u32; 3]> = (1..levels).map(|l| dims.map(|d| (d >> l).max(1))).collect();
        let texels = |s: &[u32; 3]| s.iter().map(|&d| d as u64).product::<u64>();
        let levels_: Vec<OccupiedVoxels> =
            sizes.iter().map(|s| OccupiedVoxels::new(ctx, texels(s))).collect::<Result<_>>()?;
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
