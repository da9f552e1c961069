//! The compact list of occupied voxels (OPEngine's sparse voxel list): the voxelizers append
//! each voxel when they first write it, with an atomic counter (`shaders-glsl/common/voxel.glsl`,
//! `occupied.glsl`), and a one-invocation pass turns the count into indirect dispatch arguments,
//! so that the passes over voxels (resolve, blend, moment, mips, bounces) run one invocation per
//! occupied voxel, not per grid voxel.

use std::sync::Arc;

use ash::vk;
use gpu_allocator::MemoryLocation;

use crate::error::Result;
use crate::gpu::{self, scope, shaders, Binding, Buffer, Context, DescriptorSet, Pipeline, Stage};

/// Bytes before the first voxel of the list (the count, padded to 16).
pub(crate) const HEADER: u64 = 16;

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

    /// A new list with room for `voxels` (the GPU must be idle).
    pub fn resize(&mut self, voxels: u64) -> Result<()> {
        let usage = vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::TRANSFER_DST;
        self.list = Buffer::new(&self.ctx, "occupied voxels", list_bytes(voxels), usage, MemoryLocation::GpuOnly)?;
        self.set.write_buffer(0, vk::DescriptorType::STORAGE_BUFFER, &self.list);
        Ok(())
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

    /// Dispatches the bound pipeline (a `common/listed.glsl` pass) over the listed voxels, or
    /// when not `listed` over every voxel of a grid of `dims`.
    pub fn dispatch_or_dense(&self, cmd: vk::CommandBuffer, listed: bool, dims: [u32; 3]) {
        if listed {
            self.dispatch(cmd);
        } else {
            let g = crate::config::WORKGROUP_3D;
            gpu::dispatch(&self.ctx, cmd, dims, [g; 3]);
        }
    }
}
