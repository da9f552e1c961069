//! One voxelization run without a window: builds the scene on the GPU, voxelizes it once with
//! a GPU timer around the pass, and reads the grid back (for `vct voxelize`, tests, benches).

use std::sync::Arc;

use super::bricks::{Storage, StorageRequest};
use super::{occupancy_of, VoxelGrid, VoxelizeMethod};
use crate::error::Result;
use crate::gpu::{Context, GpuTimer};
use crate::scene::gpu::SceneGpu;
use crate::scene::Scene;

pub struct VoxelRun {
    pub grid: VoxelGrid,
    /// Packed RGBA8 albedo per voxel (alpha = sample count; 0 = empty), x fastest.
    pub albedo: Vec<u32>,
    /// GPU time of clearing and voxelizing, milliseconds.
    pub gpu_ms: f64,
    pub notes: Vec<String>,
    /// Bricks the grid occupies and the pool's slots (sparse storage only).
    pub bricks: Option<super::bricks::BrickUse>,
    /// Where the textures lived (`Auto` resolved).
    pub storage: Storage,
    /// Resident storage: the bricks whose blocks held memory.
    pub residency: Option<super::bricks::Residency>,
}

impl VoxelRun {
    pub fn occupied(&self) -> Vec<bool> {
        occupancy_of(&self.albedo)
    }
}

/// Voxelizes `scene` on the grid fitted to it with `resolution` voxels along its longest axis,
/// with `method`, timing
/// `repeats` runs (the median time is reported, the last grid kept).
pub fn voxelize(
    ctx: &Arc<Context>,
    scene: &Scene,
    method: VoxelizeMethod,
    resolution: u32,
    repeats: u32,
) -> Result<VoxelRun> {
    voxelize_in(ctx, scene, method, VoxelGrid::fit(&scene.mesh.bounds, resolution)?, repeats)
}

/// As [`voxelize`], on a given grid (default storage).
pub fn voxelize_in(
    ctx: &Arc<Context>,
    scene: &Scene,
    method: VoxelizeMethod,
    grid: VoxelGrid,
    repeats: u32,
) -> Result<VoxelRun> {
    voxelize_stored(ctx, scene, method, grid, Storage::default(), None, repeats)
}

/// As [`voxelize_in`], with the given storage (a sparse pool of `bricks` slots, or sized by
/// its census).
pub fn voxelize_stored(
    ctx: &Arc<Context>,
    scene: &Scene,
    method: VoxelizeMethod,
    grid: VoxelGrid,
    storage: Storage,
    bricks: Option<u32>,
    repeats: u32,
) -> Result<VoxelRun> {
    let scene_gpu = SceneGpu::new(ctx, scene)?;
    let (volume, voxelizer) =
        super::build(ctx, scene, &scene_gpu, grid, method, StorageRequest { storage, bricks, moving: false })?;
    let timer = GpuTimer::new(ctx, 1)?;
    let mut times = Vec::new();
    for _ in 0..repeats.max(1) {
        ctx.submit_and_wait("voxelize", |cmd| {
            timer.reset(cmd);
            timer.span(cmd, "voxelize", || voxelizer.record(cmd, &scene_gpu, &volume));
        })?;
        times.push(timer.read()?[0].ms);
        volume.bricks.check()?;
    }
    times.sort_by(f64::total_cmp);
    Ok(VoxelRun {
        grid,
        albedo: volume.read_albedo()?,
        gpu_ms: times[times.len() / 2],
        notes: voxelizer.notes(),
        bricks: volume.bricks.sparse().then(|| volume.bricks.usage()),
        storage: volume.bricks.storage,
        residency: volume.bricks.residency.clone(),
    })
}
