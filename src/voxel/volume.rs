//! The voxel textures the voxelizers write: albedo+opacity and normal, each RGBA8 packed in an
//! R32UI 3D storage image (atomic running average, count in the alpha byte), and emitted
//! radiance (RGB9E5 in R32UI, atomic max). Cleared and rebuilt every frame. Stored dense or
//! in a brick pool ([`super::bricks`]).

use std::sync::Arc;

use ash::vk;

use super::bricks::{Bricks, Storage};
pub use super::grid::extent_of;
use super::occupied::OccupiedVoxels;
use super::VoxelGrid;
use crate::error::{Error, Result};
use crate::gpu::{self, scope, Context, Image, ImageDesc};

pub const VOXEL_FORMAT: vk::Format = vk::Format::R32_UINT;

pub struct VoxelVolume {
    ctx: Arc<Context>,
    pub grid: VoxelGrid,
    pub albedo: Image,
    pub normal: Image,
    pub emission: Image,
    /// Every voxel the voxelizers wrote, each once (appended on its first write).
    pub occupied: OccupiedVoxels,
    /// Where each voxel is stored (every per-voxel texture, these and the radiance volume's
    /// injected light and lit side, shares the layout).
    pub bricks: Bricks,
}

/// Stages and accesses of the voxelizers' writes, for barriers.
pub fn voxel_write_scope() -> (vk::PipelineStageFlags2, vk::AccessFlags2) {
    (
        vk::PipelineStageFlags2::VERTEX_SHADER
            | vk::PipelineStageFlags2::TESSELLATION_EVALUATION_SHADER
            | vk::PipelineStageFlags2::FRAGMENT_SHADER,
        vk::AccessFlags2::SHADER_STORAGE_READ | vk::AccessFlags2::SHADER_STORAGE_WRITE,
    )
}

/// The three voxel textures, in the order [`VoxelVolume::images`] gives them.
pub const VOXEL_TEXTURES: [&str; 3] = ["voxel albedo", "voxel normal", "voxel emission"];

/// Each voxel texture's image, of `extent` texels (the grid's, or a brick pool's).
pub fn voxel_desc(extent: vk::Extent3D) -> ImageDesc {
    let usage = vk::ImageUsageFlags::STORAGE | vk::ImageUsageFlags::TRANSFER_DST | vk::ImageUsageFlags::TRANSFER_SRC;
    ImageDesc::d3_extent(VOXEL_FORMAT, extent, usage)
}

fn largest_device_heap(ctx: &Context) -> u64 {
    let props = unsafe { ctx.instance.get_physical_device_memory_properties(ctx.physical) };
    props.memory_heaps[..props.memory_heap_count as usize]
        .iter()
        .filter(|h| h.flags.contains(vk::MemoryHeapFlags::DEVICE_LOCAL))
        .map(|h| h.size)
        .max()
        .unwrap_or(0)
}

/// An error naming the grid when `need` bytes for it pass the device's largest heap (what
/// cannot be allocated at all, told before the allocator fails on one texture of it).
pub fn check_fits(ctx: &Context, grid: &VoxelGrid, need: u64) -> Result<()> {
    let heap = largest_device_heap(ctx);
    if need > heap {
        return Err(Error::param(
            "res",
            format!(
                "a {} grid needs {} MiB of GPU memory; the device's largest heap has {} MiB",
                grid.dims_label(),
                need >> 20,
                heap >> 20
            ),
        ));
    }
    Ok(())
}

/// An error naming the grid and storage when its occupied-voxel list, room for `voxels`, would
/// pass the device's largest storage buffer (lavapipe's is 128 MiB: a dense 512³ grid's list
/// needs 512 MiB; sparse storage sizes it by the occupied bricks).
fn check_list(ctx: &Context, grid: &VoxelGrid, voxels: u64) -> Result<()> {
    let bytes = crate::voxel::occupied::list_bytes(voxels);
    let limit = ctx.info.limits.max_storage_buffer_range as u64;
    if bytes > limit {
        return Err(Error::param(
            "storage",
            format!(
                "a {} grid lists up to {voxels} occupied voxels ({} MiB), past the device's largest storage buffer \
                 ({} MiB): use --storage sparse, whose list follows the occupied bricks, or a smaller grid",
                grid.dims_label(),
                bytes >> 20,
                limit >> 20
            ),
        ));
    }
    Ok(())
}

/// The three voxel textures in `bricks`' layout, after the heap check.
fn textures(ctx: &Arc<Context>, grid: &VoxelGrid, bricks: &Bricks) -> Result<[Image; 3]> {
    let desc = voxel_desc(bricks.extent(grid));
    check_fits(ctx, grid, VOXEL_TEXTURES.len() as u64 * bricks.bytes_of(&desc))?;
    let [a, n, e] = VOXEL_TEXTURES;
    Ok([bricks.image(a, desc)?, bricks.image(n, desc)?, bricks.image(e, desc)?])
}

impl VoxelVolume {
    /// The textures over `grid`, dense or in a pool of `capacity` brick slots (the empty slot
    /// included).
    pub fn new(ctx: &Arc<Context>, grid: VoxelGrid, storage: Storage, capacity: u32) -> Result<Self> {
        Self::stored(ctx, grid, Bricks::new(ctx, &grid, storage, capacity)?)
    }

    /// The textures over `grid` in `bricks`' layout.
    pub fn stored(ctx: &Arc<Context>, grid: VoxelGrid, bricks: Bricks) -> Result<Self> {
        check_list(ctx, &grid, bricks.voxel_room(&grid))?;
        let [albedo, normal, emission] = textures(ctx, &grid, &bricks)?;
        Ok(VoxelVolume {
            ctx: ctx.clone(),
            grid,
            albedo,
            normal,
            emission,
            occupied: OccupiedVoxels::new(ctx, bricks.voxel_room(&grid))?,
            bricks,
        })
    }

    /// Re-sizes the brick pool to `capacity` slots (the empty one included): new textures, table
    /// and list, the list's pipeline kept (the GPU must be idle; rebind the voxelizer after).
    /// A CPU driver keeps some memory of every pipeline it compiles, so the census reuses it.
    pub fn resize_pool(&mut self, capacity: u32) -> Result<()> {
        let bricks = Bricks::new(&self.ctx, &self.grid, self.bricks.storage, capacity)?;
        self.rebrick(bricks)
    }

    /// Stores the textures in `bricks`' layout from here on: new textures and list, the list's
    /// pipeline kept (the GPU must be idle; rebind the voxelizer after).
    pub fn rebrick(&mut self, bricks: Bricks) -> Result<()> {
        let ctx = &self.ctx;
        check_list(ctx, &self.grid, bricks.voxel_room(&self.grid))?;
        [self.albedo, self.normal, self.emission] = textures(ctx, &self.grid, &bricks)?;
        self.occupied.resize(bricks.voxel_room(&self.grid))?;
        self.bricks = bricks;
        Ok(())
    }

    /// Clears the textures to zero (empty) and the list of occupied voxels, and makes them ready
    /// for the voxelizers' atomics.
    pub fn record_clear(&self, cmd: vk::CommandBuffer) {
        let ctx = &self.ctx;
        for img in [&self.albedo, &self.normal, &self.emission] {
            gpu::clear_to_general(ctx, cmd, img, scope::ANY);
        }
        self.occupied.record_reset(cmd);
        self.bricks.record_reset(cmd);
        gpu::memory_barrier(ctx, cmd, scope::CLEAR_WRITE, voxel_write_scope());
        gpu::memory_barrier(ctx, cmd, scope::TRANSFER_WRITE, voxel_write_scope());
    }

    /// Orders one voxelization draw's writes before the next's (a clipmap's levels share the
    /// occupied list's count and the brick table).
    pub fn record_between_draws(&self, cmd: vk::CommandBuffer) {
        gpu::memory_barrier(&self.ctx, cmd, voxel_write_scope(), voxel_write_scope());
    }

    /// Makes the voxelizers' writes visible to the compute and transfer work that follows, and
    /// writes the occupied list's dispatch arguments.
    pub fn record_finish(&self, cmd: vk::CommandBuffer) {
        let after = (
            vk::PipelineStageFlags2::COMPUTE_SHADER
                | vk::PipelineStageFlags2::ALL_TRANSFER
                | vk::PipelineStageFlags2::ALL_GRAPHICS,
            vk::AccessFlags2::SHADER_STORAGE_READ | vk::AccessFlags2::TRANSFER_READ,
        );
        gpu::memory_barrier(&self.ctx, cmd, voxel_write_scope(), after);
        self.occupied.record_args(cmd);
        self.bricks.record_readback(cmd);
    }

    /// Reads back a per-voxel texture stored in this volume's layout (a voxel texture, or the
    /// radiance volume's injected light or lit side) as the dense grid, x fastest.
    pub fn read_dense(&self, image: &Image) -> Result<Vec<u8>> {
        let bytes = gpu::read_image(&self.ctx, image, vk::ImageLayout::GENERAL, 0)?;
        if !self.bricks.sparse() {
            return Ok(bytes);
        }
        let texel = crate::gpu::image::texel_size(image.desc.format);
        let pages = self.bricks.read_pages()?;
        Ok(super::bricks::scatter(&self.grid, &pages, image.desc.extent, &bytes, texel))
    }

    /// Reads back the packed albedo texture (RGBA8 per voxel; alpha = sample count, 0 = empty).
    pub fn read_albedo(&self) -> Result<Vec<u32>> {
        Ok(bytemuck::pod_collect_to_vec(&self.read_dense(&self.albedo)?))
    }

    pub fn read_normal(&self) -> Result<Vec<u32>> {
        Ok(bytemuck::pod_collect_to_vec(&self.read_dense(&self.normal)?))
    }

    /// The textures, for the memory report.
    pub fn images(&self) -> [&Image; 3] {
        [&self.albedo, &self.normal, &self.emission]
    }
}

/// Occupancy from a read-back packed texture: a voxel is filled when its count is non-zero.
pub fn occupancy(packed: &[u32]) -> Vec<bool> {
    packed.iter().map(|&v| v >> 24 != 0).collect()
}

/// The RGB of a packed voxel, in [0, 1].
pub fn unpack_rgb(v: u32) -> [f32; 3] {
    [(v & 0xff) as f32 / 255.0, ((v >> 8) & 0xff) as f32 / 255.0, ((v >> 16) & 0xff) as f32 / 255.0]
}
