//! Sparse voxel storage: a page table over the grid's bricks and a pool of brick slots
//! (GigaVoxels' brick pool, Crassin 2011 §4; the software path of the GRAPP 2020 sparse-texture
//! paper). The per-voxel textures (the voxel albedo, normal and emission, the injected radiance
//! and lit side, the bounce target) become pool atlases: a voxel lives in its brick's slot, and
//! a voxel outside every brick reads the empty slot 0. The voxelizers claim a brick's slot on
//! the first write into it (`shaders-glsl/common/bricks.glsl`), so the pool holds exactly the
//! bricks that hold an occupied voxel. Its capacity comes from a census: one voxelization into
//! a pool of no slots counts the bricks the scene needs (`voxel::build`). A frame that needs more
//! than the pool holds is an error naming both counts, never silent holes ([`Bricks::check`]).
//!
//! Dense storage (`--storage dense`) keeps every texture at the grid's extent; the shaders then
//! skip the table (specialization constant `SPARSE`). Resident storage (`--storage resident`,
//! Vulkan sparse residency where the device offers it) keeps the grid's extent too, so the
//! shaders read it as dense, but binds memory only to the sparse blocks that hold a brick the
//! census found ([`Residency`], `gpu::sparse`).

use std::sync::Arc;

use ash::vk;
use glam::UVec3;
use gpu_allocator::MemoryLocation;

use super::VoxelGrid;
use crate::config::{BRICK_REFUSED, BRICK_SHIFT, BRICK_SIZE};
use crate::error::{Error, Result};
use crate::gpu::{self, scope, Buffer, Context, Feature, FrameSlot, Image, ImageDesc, FRAMES_IN_FLIGHT};

/// Where the per-voxel textures live.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub enum Storage {
    /// For a grid fitted to the scene, resident where the device offers residency, else the
    /// pool; dense for a volume that moves with the camera, whose occupancy no census made at
    /// its first place bounds.
    #[default]
    Auto,
    /// Every texture over the whole grid.
    Dense,
    /// A page table and a pool of the occupied bricks (smaller on every scene measured,
    /// docs/design/storage.md).
    Sparse,
    /// Vulkan sparse residency: every texture at the grid's extent (read as dense, without a
    /// table), with memory bound only to the blocks that hold an occupied brick.
    Resident,
}

/// What resident storage needs of the device, besides one of [`RESIDENCY_UNBOUND`].
pub const RESIDENCY: [Feature; 3] =
    [Feature::SparseResidencyImage3D, Feature::ResidencyStandard3DBlockShape, Feature::SparseBindingQueue];

/// How unbound blocks come to read zero: the device's guarantee, or else one shared block of
/// zeros bound in their place (gpu::sparse).
pub const RESIDENCY_UNBOUND: [Feature; 2] = [Feature::ResidencyNonResidentStrict, Feature::SparseResidencyAliased];

/// Fails with an error naming what resident storage lacks on `ctx`'s device.
pub fn require_residency(ctx: &Context) -> Result<()> {
    let needed_by = "resident voxel storage (--storage resident)";
    ctx.require(&RESIDENCY, needed_by)?;
    if !RESIDENCY_UNBOUND.iter().any(|&f| ctx.info.features.has(f)) {
        return Err(Error::MissingFeature {
            device: ctx.info.name.clone(),
            feature: "residencyNonResidentStrict or sparseResidencyAliased",
            needed_by,
        });
    }
    Ok(())
}

/// The standard sparse block of a 3D image (Vulkan spec, "Standard Sparse Image Block
/// Shapes"): 64 KiB of texels of `texel_bytes` bytes.
pub fn standard_block(texel_bytes: usize) -> [u32; 3] {
    match texel_bytes {
        1 => [64, 32, 32],
        2 => [32, 32, 32],
        4 => [32, 32, 16],
        8 => [32, 16, 16],
        _ => [16, 16, 16],
    }
}

/// Whether `ctx`'s device offers resident storage.
pub fn residency_offered(ctx: &Context) -> bool {
    require_residency(ctx).is_ok()
}

impl Storage {
    /// What `Auto` means for a grid that moves or not, on `ctx`'s device: residency where the
    /// device offers it, else the brick pool; dense for a moving grid, whose occupancy no census
    /// at its first place bounds.
    pub fn resolve(self, ctx: &Context, moving: bool) -> Storage {
        match self {
            Storage::Auto if moving => Storage::Dense,
            Storage::Auto if residency_offered(ctx) => Storage::Resident,
            Storage::Auto => Storage::Sparse,
            s => s,
        }
    }

    pub fn label(self) -> &'static str {
        match self {
            Storage::Auto => "auto",
            Storage::Dense => "dense",
            Storage::Sparse => "sparse",
            Storage::Resident => "resident",
        }
    }
}

/// The bricks a census found occupied, which decide the blocks of memory a resident texture
/// binds: a block holds memory when one of these bricks lies in it (bricks are 2³ and block
/// sides even, so a brick never straddles two blocks).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Residency {
    /// Brick coordinates, in brick order.
    pub bricks: Vec<UVec3>,
    /// Each texture also holds the one block of zeros that its blocks without a brick share
    /// (a device whose unbound blocks do not read zero; gpu::sparse).
    pub shared_zero: bool,
}

impl Residency {
    /// From a census table (`pages`: nonzero where a brick was asked for).
    pub fn from_pages(grid: &VoxelGrid, pages: &[u32], shared_zero: bool) -> Self {
        let count = brick_count(grid);
        let bricks = pages
            .iter()
            .enumerate()
            .filter(|(_, &p)| p != 0)
            .map(|(i, _)| {
                let i = i as u32;
                UVec3::new(i % count.x, (i / count.x) % count.y, i / (count.x * count.y))
            })
            .collect();
        Residency { bricks, shared_zero }
    }

    /// The blocks of `shape` texels (one texel a voxel) that hold an occupied brick, each once.
    pub fn blocks(&self, shape: [u32; 3]) -> Vec<[u32; 3]> {
        let shape = UVec3::from(shape).max(UVec3::ONE);
        let mut blocks: Vec<[u32; 3]> = self.bricks.iter().map(|&b| ((b * BRICK_SIZE) / shape).into()).collect();
        blocks.sort_unstable_by_key(|b| (b[2], b[1], b[0]));
        blocks.dedup();
        blocks
    }

    /// The most voxels the bricks hold (the occupied list's room).
    pub fn voxel_room(&self) -> u64 {
        self.bricks.len() as u64 * (BRICK_SIZE as u64).pow(3)
    }

    /// Bytes a resident texture of `format` over a grid of `dims` binds: its standard blocks
    /// that hold a brick, and the shared block of zeros where the others need it.
    pub fn bound_bytes(&self, dims: UVec3, format: vk::Format) -> u64 {
        let texel = crate::gpu::image::texel_size(format);
        let shape = standard_block(texel);
        let blocks = self.blocks(shape).len() as u64;
        let all = (dims + UVec3::from(shape) - 1) / UVec3::from(shape);
        let shared = (self.shared_zero && blocks < all.as_u64vec3().element_product()) as u64;
        (blocks + shared) * UVec3::from(shape).as_u64vec3().element_product() * texel as u64
    }
}

/// How a volume stores its voxels, for [`super::build`].
#[derive(Clone, Copy, Debug, Default)]
pub struct StorageRequest {
    pub storage: Storage,
    /// Slots of a sparse pool; `None`: as many as the census counts.
    pub bricks: Option<u32>,
    /// The grid moves with the camera (resolves `Auto` to dense; a sparse pool gets headroom
    /// and claims its bricks every frame).
    pub moving: bool,
}

impl StorageRequest {
    /// The storage this request gets on `ctx`'s device: `Auto` with a pool size given is the
    /// pool, else as [`Storage::resolve`] says.
    pub fn resolve(&self, ctx: &Context) -> Storage {
        match self.storage {
            Storage::Auto if self.bricks.is_some() && !self.moving => Storage::Sparse,
            s => s.resolve(ctx, self.moving),
        }
    }
}

/// Bytes of the table's header (`Bricks` in bricks.glsl: eight uints).
const HEADER_WORDS: usize = 8;
const HEADER: u64 = 4 * HEADER_WORDS as u64;

/// Bricks along each axis of `grid`.
pub fn brick_count(grid: &VoxelGrid) -> UVec3 {
    (grid.dims + UVec3::splat(BRICK_SIZE - 1)) >> BRICK_SHIFT
}

/// Bytes of the page table over `grid`.
pub fn table_bytes(grid: &VoxelGrid) -> u64 {
    HEADER + 4 * brick_count(grid).as_u64vec3().element_product()
}

/// The pool's slots along x, y, z for `capacity` slots (the empty one included): layers whose
/// sides are powers of two (bricks.glsl finds a slot by shifts), x = y or 2y, as many layers
/// as the capacity needs but no more than 2x; of those, the fewest slots (within ~2.5% of the
/// capacity from a few hundred up), then the most cubic.
pub fn pool_slots(capacity: u32) -> UVec3 {
    let c = capacity.max(1) as u64;
    (0..=12u32)
        .flat_map(|a| [(a, a), (a + 1, a)])
        .map(|(a, b)| UVec3::new(1 << a, 1 << b, c.div_ceil(1 << (a + b)) as u32))
        .filter(|s| s.z <= 2 * s.x)
        .min_by_key(|s| (s.as_u64vec3().element_product(), s.max_element()))
        .expect("candidate layouts")
}

/// The voxels `capacity` slots (the empty one included) hold, at most the grid's.
pub fn voxel_room(grid: &VoxelGrid, capacity: u32) -> u64 {
    (capacity.saturating_sub(1) as u64 * (BRICK_SIZE as u64).pow(3)).min(grid.voxel_count() as u64)
}

/// The pool atlases' extent in texels for `capacity` slots.
pub fn pool_extent(capacity: u32) -> vk::Extent3D {
    let s = pool_slots(capacity) * BRICK_SIZE;
    vk::Extent3D { width: s.x, height: s.y, depth: s.z }
}

/// What the last voxelization asked of the pool.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct BrickUse {
    /// Bricks that hold an occupied voxel (given a slot or refused).
    pub needed: u32,
    /// Slots for bricks (the empty slot not counted).
    pub capacity: u32,
    /// Claims that gave up waiting for another invocation's (never seen; an error if it happens).
    pub stalled: u32,
}

/// The page table, its header's read-back, and the pool's shape.
pub struct Bricks {
    ctx: Arc<Context>,
    pub storage: Storage,
    /// Header (next slot, capacity, pool shape, brick counts) and one entry per brick.
    pub table: Buffer,
    /// The header's read-back, one per frame in flight, used in turn (`current` the last).
    readback: Vec<Buffer>,
    current: FrameSlot,
    header: [u32; HEADER_WORDS],
    /// Bricks along each axis of the grid.
    pub count: UVec3,
    /// Slots in the pool, the empty slot 0 included (0 when dense).
    pub capacity: u32,
    /// The slots were given by [`Bricks::assign`] and stay from frame to frame (only bricks
    /// new to the grid are claimed); otherwise the table is emptied every frame.
    kept: bool,
    /// Resident storage: the bricks whose blocks hold memory.
    pub residency: Option<Residency>,
}

impl Bricks {
    /// A table over `grid` for a pool of `capacity` slots (the empty one included); dense
    /// storage keeps a header-only table, bound but never read.
    pub fn new(ctx: &Arc<Context>, grid: &VoxelGrid, storage: Storage, capacity: u32) -> Result<Self> {
        let storage = storage.resolve(ctx, false);
        let (count, capacity) =
            if storage == Storage::Sparse { (brick_count(grid), capacity.max(1)) } else { (UVec3::ZERO, 0) };
        let slots = pool_slots(capacity);
        let limit = ctx.info.limits.max_image_dimension3_d / BRICK_SIZE;
        if storage == Storage::Sparse && slots.max_element() > limit {
            return Err(Error::param(
                "bricks",
                format!(
                    "a pool of {capacity} bricks needs {} slots along an axis; the device's 3D images hold {limit}",
                    slots.max_element()
                ),
            ));
        }
        let bytes = HEADER + 4 * count.as_u64vec3().element_product();
        let usage = vk::BufferUsageFlags::STORAGE_BUFFER
            | vk::BufferUsageFlags::TRANSFER_DST
            | vk::BufferUsageFlags::TRANSFER_SRC;
        let table = Buffer::new(ctx, "brick page table", bytes, usage, MemoryLocation::GpuOnly)?;
        let header = [1, capacity, slots.x.trailing_zeros(), slots.y.trailing_zeros(), count.x, count.y, count.z, 0];
        let readback = |i: usize| -> Result<Buffer> {
            let b = Buffer::new(
                ctx,
                &format!("brick count {i}"),
                HEADER,
                vk::BufferUsageFlags::TRANSFER_DST,
                MemoryLocation::GpuToCpu,
            )?;
            // Until the first voxelization is read back: no brick needed yet.
            b.write(0, bytemuck::cast_slice(&header));
            Ok(b)
        };
        let readback = (0..FRAMES_IN_FLIGHT).map(readback).collect::<Result<Vec<_>>>()?;
        Ok(Bricks {
            ctx: ctx.clone(),
            storage,
            table,
            readback,
            current: FrameSlot::default(),
            header,
            count,
            capacity,
            kept: false,
            residency: None,
        })
    }

    /// Resident storage over `grid`: memory for the blocks of the bricks a census asked for
    /// (`asked`: a census table, nonzero where a brick was asked for). The table keeps them
    /// marked, so the voxelizers refuse (and count) a write outside them instead of losing it
    /// to an unbound block (`claim_brick` in bricks.glsl with RESIDENT); passes that read the
    /// textures address them as dense and skip the table. The GPU must be idle.
    pub fn resident(ctx: &Arc<Context>, grid: &VoxelGrid, asked: &[u32]) -> Result<Self> {
        let mut b = Self::new(ctx, grid, Storage::Sparse, 1)?;
        let marks: Vec<u32> = asked.iter().map(|&a| (a != 0) as u32).collect();
        b.upload_pages(&marks)?;
        b.storage = Storage::Resident;
        b.residency = Some(Residency::from_pages(grid, asked, !crate::gpu::sparse::unbound_reads_zero(ctx)));
        b.kept = true;
        Ok(b)
    }

    pub fn sparse(&self) -> bool {
        self.storage == Storage::Sparse
    }

    /// The bricks that hold memory: the pool's slots (the empty one not counted), or the
    /// resident census' bricks; `None` when dense.
    pub fn stored_bricks(&self) -> Option<u64> {
        match &self.residency {
            _ if self.sparse() => Some(self.capacity.saturating_sub(1) as u64),
            Some(r) => Some(r.bricks.len() as u64),
            None => None,
        }
    }

    /// Bytes a per-voxel texture of `desc` (at [`Bricks::extent`]) holds: the blocks bound
    /// when resident, else all of it.
    pub fn bytes_of(&self, desc: &ImageDesc) -> u64 {
        let e = desc.extent;
        let dims = UVec3::new(e.width, e.height, e.depth);
        self.residency.as_ref().map_or(desc.texel_bytes(), |r| r.bound_bytes(dims, desc.format))
    }

    /// A per-voxel texture of `desc` (at [`Bricks::extent`]): bound block by block when
    /// resident, else whole.
    pub fn image(&self, name: &str, desc: ImageDesc) -> Result<Image> {
        match &self.residency {
            Some(r) => {
                let shape = crate::gpu::sparse::block_shape(&self.ctx, &desc)?;
                Image::resident(&self.ctx, name, desc, &r.blocks(shape))
            }
            None => Image::new(&self.ctx, name, desc),
        }
    }

    /// Specialization constants for a shader that includes bricks.glsl: its own constant 0
    /// (`first`), then SPARSE (constant 1) and RESIDENT (constant 2).
    pub fn spec(&self, first: u32) -> [u32; 3] {
        [first, self.sparse() as u32, (self.storage == Storage::Resident) as u32]
    }

    /// The most voxels this layout can hold: the grid's, or the pool's slots' (each
    /// occupied voxel lies in a brick with a slot, so the occupied list needs no more room).
    pub fn voxel_room(&self, grid: &VoxelGrid) -> u64 {
        match &self.residency {
            _ if self.sparse() => voxel_room(grid, self.capacity),
            Some(r) => r.voxel_room(),
            None => grid.voxel_count() as u64,
        }
    }

    /// The extent of every per-voxel texture: the grid's when dense, the pool's when sparse.
    pub fn extent(&self, grid: &VoxelGrid) -> vk::Extent3D {
        if self.sparse() {
            pool_extent(self.capacity)
        } else {
            super::grid::extent_of(grid.dims)
        }
    }

    /// Before the voxelizers claim: empties the table (no brick has a slot; the next one given
    /// out is 1), or with assigned slots resets only the count of slots given out.
    pub fn record_reset(&self, cmd: vk::CommandBuffer) {
        let ctx = &self.ctx;
        gpu::memory_barrier(ctx, cmd, scope::ANY, scope::TRANSFER_WRITE);
        gpu::update_buffer(ctx, cmd, &self.table, bytemuck::cast_slice(&self.header));
        if self.sparse() && !self.kept {
            gpu::fill_buffer_at(ctx, cmd, &self.table, HEADER, vk::WHOLE_SIZE, 0);
        }
    }

    /// Gives every brick the census asked for (`asked`: a census table, nonzero where a brick
    /// was asked for) a slot in brick order, 1, 2, ..., and keeps them from frame to frame: a
    /// static scene's fitted grid needs the same bricks every frame, so the voxelizers claim
    /// nothing after this, and bricks near each other in the grid sit near each other in the
    /// pool. The GPU must be idle.
    pub fn assign(&mut self, asked: &[u32]) -> Result<()> {
        let mut next = 1u32;
        let pages: Vec<u32> = asked
            .iter()
            .map(|&a| {
                if a == 0 {
                    return 0;
                }
                next += 1;
                next - 1
            })
            .collect();
        if next > self.capacity {
            return Err(Error::param(
                "bricks",
                format!("the census asked for {} bricks; the pool holds {}", next - 1, self.capacity.saturating_sub(1)),
            ));
        }
        self.upload_pages(&pages)?;
        self.header[0] = next;
        self.kept = true;
        Ok(())
    }

    /// Writes the table's entries (the GPU must be idle).
    fn upload_pages(&self, pages: &[u32]) -> Result<()> {
        let staging = Buffer::from_slice(&self.ctx, "brick pages", vk::BufferUsageFlags::TRANSFER_SRC, pages)?;
        let ctx = &self.ctx;
        ctx.submit_and_wait("brick slots", |cmd| {
            gpu::memory_barrier(ctx, cmd, scope::ANY, scope::TRANSFER_WRITE);
            gpu::copy_buffer_at(ctx, cmd, &staging, &self.table, HEADER, staging.size);
        })
    }

    /// Copies the header to the host after the voxelizers' writes (made visible to transfers
    /// by the caller's barrier), for [`Bricks::check`], into the next read-back buffer (the
    /// other may belong to a frame still in flight, which the host reads).
    pub fn record_readback(&self, cmd: vk::CommandBuffer) {
        let i = self.current.advance();
        gpu::memory_barrier(
            &self.ctx,
            cmd,
            (vk::PipelineStageFlags2::ALL_COMMANDS, vk::AccessFlags2::MEMORY_WRITE),
            scope::TRANSFER_READ,
        );
        gpu::copy_buffer(&self.ctx, cmd, &self.table, &self.readback[i], HEADER);
        gpu::memory_barrier(&self.ctx, cmd, scope::TRANSFER_WRITE, scope::HOST_READ);
    }

    /// The pool's use in the last voxelization (sparse storage only; call after it finished).
    pub fn usage(&self) -> BrickUse {
        self.usage_of(self.current.last())
    }

    /// The pool's use in the voxelization recorded before the last: with frames in flight,
    /// the one whose frame the next frame's fence has seen finish.
    pub fn settled_usage(&self) -> BrickUse {
        self.usage_of(self.current.settled())
    }

    fn usage_of(&self, i: usize) -> BrickUse {
        let h: &[u32] = bytemuck::cast_slice(&self.readback[i].read()[..HEADER as usize]);
        BrickUse { needed: h[0].saturating_sub(1), capacity: self.capacity.saturating_sub(1), stalled: h[7] }
    }

    /// An error when the last voxelization needed more bricks than the pool holds (its image
    /// then misses the refused bricks), or a claim gave up.
    pub fn check(&self) -> Result<()> {
        self.check_use(self.usage())
    }

    /// [`Bricks::check`] of [`Bricks::settled_usage`].
    pub fn check_settled(&self) -> Result<()> {
        self.check_use(self.settled_usage())
    }

    fn check_use(&self, u: BrickUse) -> Result<()> {
        if self.storage == Storage::Resident && u.needed > 0 {
            return Err(Error::param(
                "storage",
                format!(
                    "the voxelizer wrote into {} bricks of {BRICK_SIZE}³ voxels outside the blocks that resident storage \
                     bound for the census' {} (the scene or grid changed after the census)",
                    u.needed,
                    self.residency.as_ref().map_or(0, |r| r.bricks.len())
                ),
            ));
        }
        if !self.sparse() {
            return Ok(());
        }
        if u.needed > u.capacity {
            return Err(Error::param(
                "bricks",
                format!(
                    "the brick pool is full: the grid needs {} bricks of {BRICK_SIZE}³ voxels, the pool holds {} (raise --bricks, or leave it to the census)",
                    u.needed, u.capacity
                ),
            ));
        }
        if u.stalled > 0 {
            return Err(Error::param("bricks", format!("{} brick claims gave up waiting", u.stalled)));
        }
        Ok(())
    }

    /// The page table's entries (after all submitted work): 0 none, else the brick's slot.
    pub fn read_pages(&self) -> Result<Vec<u32>> {
        let bytes = gpu::read_buffer(&self.ctx, &self.table)?;
        Ok(bytemuck::cast_slice(&bytes[HEADER as usize..]).to_vec())
    }
}

/// The first texel of slot `s` in a pool of `slots` (`slot_texel` in bricks.glsl).
fn slot_origin(s: u32, slots: UVec3) -> UVec3 {
    UVec3::new(s % slots.x, (s / slots.x) % slots.y, s / (slots.x * slots.y)) * BRICK_SIZE
}

/// A pooled texture read back (`texel` bytes a texel, x fastest over `pool` texels) as the
/// dense grid it stores: each brick's voxels from its slot, zero where no brick has a slot.
pub fn scatter(grid: &VoxelGrid, pages: &[u32], pool: vk::Extent3D, pooled: &[u8], texel: usize) -> Vec<u8> {
    let count = brick_count(grid);
    let slots = UVec3::new(pool.width, pool.height, pool.depth) / BRICK_SIZE;
    let d = grid.dims;
    let mut dense = vec![0u8; d.as_u64vec3().element_product() as usize * texel];
    for (i, &s) in pages.iter().enumerate() {
        if s == 0 || s >= BRICK_REFUSED {
            continue;
        }
        let i = i as u32;
        let b = UVec3::new(i % count.x, (i / count.x) % count.y, i / (count.x * count.y)) * BRICK_SIZE;
        let o = slot_origin(s, slots);
        for z in 0..BRICK_SIZE {
            for y in 0..BRICK_SIZE {
                for x in 0..BRICK_SIZE {
                    let v = b + UVec3::new(x, y, z);
                    if v.cmpge(d).any() {
                        continue;
                    }
                    let p = o + UVec3::new(x, y, z);
                    let src = ((p.z * pool.height + p.y) * pool.width + p.x) as usize * texel;
                    let dst = ((v.z * d.y + v.y) * d.x + v.x) as usize * texel;
                    dense[dst..dst + texel].copy_from_slice(&pooled[src..src + texel]);
                }
            }
        }
    }
    dense
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pool_holds_its_capacity_in_near_cubic_layers() {
        for c in [1u32, 2, 7, 8, 9, 1000, 25126, 101845] {
            let s = pool_slots(c);
            assert!(s.x * s.y * s.z >= c, "{c}: {s}");
            assert!(s.x * s.y * (s.z - 1) < c, "{c}: a whole empty layer in {s}");
            assert!(s.x.is_power_of_two() && s.y.is_power_of_two() && s.x >= s.y, "{c}: {s}");
            assert!((s.x * s.y * s.z) as f64 <= c as f64 * 1.05 + 64.0, "{c}: {s} wastes slots");
        }
    }

    #[test]
    fn residency_binds_each_block_that_holds_a_census_brick_once() {
        let grid = VoxelGrid {
            origin: glam::Vec3::ZERO,
            voxel: 1.0,
            dims: UVec3::new(64, 32, 32),
            warp: Default::default(),
            clip: None,
        };
        let count = brick_count(&grid);
        let index = |b: UVec3| ((b.z * count.y + b.y) * count.x + b.x) as usize;
        let mut pages = vec![0u32; count.element_product() as usize];
        // Two bricks in the first 32×32×16 block, one in the block at x 32..64, z 16..32.
        for b in [UVec3::new(0, 0, 0), UVec3::new(15, 15, 7), UVec3::new(16, 3, 8)] {
            pages[index(b)] = BRICK_REFUSED;
        }
        let mut r = Residency::from_pages(&grid, &pages, false);
        assert_eq!(r.bricks, vec![UVec3::new(0, 0, 0), UVec3::new(15, 15, 7), UVec3::new(16, 3, 8)]);
        assert_eq!(r.voxel_room(), 3 * 8);
        assert_eq!(r.blocks(standard_block(4)), vec![[0, 0, 0], [1, 0, 1]]);
        // RGBA16F blocks are 32×16×16: the second brick (voxels 30..32, 30..32, 14..16) has one of its own.
        assert_eq!(r.blocks(standard_block(8)), vec![[0, 0, 0], [0, 1, 0], [1, 0, 1]]);
        assert_eq!(r.bound_bytes(grid.dims, vk::Format::R32_UINT), 2 * 65536);
        assert_eq!(r.bound_bytes(grid.dims, vk::Format::R16G16B16A16_SFLOAT), 3 * 65536);
        // Where unbound blocks need the shared block of zeros, each texture holds one more.
        r.shared_zero = true;
        assert_eq!(r.bound_bytes(grid.dims, vk::Format::R32_UINT), 3 * 65536);
        for t in [1, 2, 4, 8, 16] {
            let s = standard_block(t);
            assert_eq!(s.iter().product::<u32>() as usize * t, 65536, "{t} bytes a texel");
        }
    }

    #[test]
    fn scatter_places_each_brick_voxel_at_its_grid_coordinate() {
        let grid = VoxelGrid {
            origin: glam::Vec3::ZERO,
            voxel: 1.0,
            dims: UVec3::new(4, 2, 2),
            warp: Default::default(),
            clip: None,
        };
        // Bricks (2, 1, 1); brick 1 (x 2..4) in slot 1, brick 0 empty.
        let pool = pool_extent(2);
        let slots = pool_slots(2);
        let mut pooled = vec![0u8; (pool.width * pool.height * pool.depth) as usize];
        let o = slot_origin(1, slots);
        for z in 0..2 {
            for y in 0..2 {
                for x in 0..2 {
                    let p = o + UVec3::new(x, y, z);
                    pooled[((p.z * pool.height + p.y) * pool.width + p.x) as usize] = (1 + x + 2 * y + 4 * z) as u8;
                }
            }
        }
        let dense = scatter(&grid, &[0, 1], pool, &pooled, 1);
        for z in 0..2u32 {
            for y in 0..2u32 {
                for x in 0..4u32 {
                    let want = if x < 2 { 0 } else { (1 + (x - 2) + 2 * y + 4 * z) as u8 };
                    assert_eq!(dense[((z * 2 + y) * 4 + x) as usize], want, "voxel {x},{y},{z}");
                }
            }
        }
    }
}
