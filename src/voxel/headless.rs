//! One voxelization run without a window: builds the scene on the GPU, voxelizes it once with
//! a GPU timer around the pass, and reads the grid back (for `vct voxelize`, tests, benches).

use std::sync::Arc;

use super::{occupancy_of, VoxelGrid, VoxelVolume, VoxelizeMethod, Voxelizer};
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

/// As [`voxelize`], on a given grid.
pub fn voxelize_in(
    ctx: &Arc<Context>,
    scene: &Scene,
    method: VoxelizeMethod,
    grid: VoxelGrid,
    repeats: u32,
) -> Result<VoxelRun> {
    let scene_gpu = SceneGpu::new(ctx, scene)?;
    let volume = VoxelVolume::new(ctx, grid)?;
    let voxelizer = Voxelizer::new(ctx, scene, &scene_gpu, &volume, method)?;
    let timer = GpuTimer::new(ctx, 1)?;
    let mut times = Vec::new();
    for _ in 0..repeats.max(1) {
        ctx.submit_and_wait("voxelize", |cmd| {
            timer.reset(cmd);
            timer.span(cmd, "voxelize", || voxelizer.record(cmd, &scene_gpu, &volume));
        })?;
        times.push(timer.read()?[0].ms);
    }
    times.sort_by(f64::total_cmp);
    Ok(VoxelRun { grid, albedo: volume.read_albedo()?, gpu_ms: times[times.len() / 2], notes: voxelizer.notes() })
}
