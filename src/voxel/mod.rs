//! Voxelization (Freed 2018 §4.1) three ways, as siblings behind [`VoxelizeMethod`]: the
//! tessellation path ([`tess`]), the rasterized path ([`raster`]) and sample points scattered
//! over the triangles ([`points`], Mavridis & Papaioannou 2011). Each declares the device
//! features it needs; all write the same [`VoxelVolume`].

pub mod binvox;
pub mod bricks;
pub mod clipmap;
pub mod grid;
pub mod headless;
pub mod lattice;
pub mod occupied;
pub mod perspective;
pub mod points;
pub mod raster;
pub mod subdivide;
pub mod tess;
pub mod volume;
pub mod warp;

use std::sync::Arc;

use ash::vk;

pub use grid::VoxelGrid;
pub use volume::{occupancy as occupancy_of, unpack_rgb, VoxelVolume};

use crate::error::Result;
use crate::gpu::{Binding, Context, DescriptorSet, Feature, FrameBuffer};
use crate::scene::gpu::SceneGpu;
use crate::scene::Scene;

/// How the rasterized path makes coverage conservative.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum Coverage {
    /// One sample per pixel: a fragment only where the triangle covers the pixel centre.
    None,
    /// Four samples: a fragment wherever any sample is covered (the thesis' MSAA method).
    Msaa,
    /// `VK_EXT_conservative_rasterization`, overestimating.
    Hardware,
    /// Conservative without the extension: the geometry shader grows the triangle by half a
    /// pixel diagonal and the fragment shader clips it to its bounding box (raster.geom).
    Conservative,
    /// Exact coverage by the fastest conservative path the device has: `Hardware` where it
    /// offers the extension, else `Conservative`. Both are exact on every mesh measured; on an
    /// NVIDIA H200 the extension voxelizes Sponza 7–16× faster than the geometry shader
    /// (docs/report/README.md). Resolved when the voxelizer is built ([`Coverage::on`]).
    Auto,
}

impl Coverage {
    /// `Auto` resolved for a device with these features; any other choice is kept.
    pub fn on(self, features: &crate::gpu::FeatureSet) -> Coverage {
        match self {
            Coverage::Auto if features.has(Feature::ConservativeRasterization) => Coverage::Hardware,
            Coverage::Auto => Coverage::Conservative,
            c => c,
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub enum VoxelizeMethod {
    Tess {
        /// Multiplies the thesis' tessellation levels (1.0 = the thesis).
        level_scale: f32,
        /// Split triangles whose levels pass the device limit when the scene loads.
        subdivide: bool,
        /// Keep levels >= 1 so triangles inside one voxel still write it.
        min_level: bool,
        /// Each evaluation point also fills the empty voxels around its own that the
        /// triangle meets (exact on thin and small triangles).
        neighbours: bool,
    },
    Raster {
        coverage: Coverage,
        /// Framebuffer resolution over voxel resolution (1 = one pixel per voxel; below 1 the
        /// fragments are sparser than the voxels and leave cracks).
        viewport_scale: f32,
        /// Write every voxel layer the triangle spans within a pixel.
        depth_span: bool,
    },
    /// Sample points over each triangle, `density` per voxel area (at least one a triangle),
    /// from `source`; `refine`: the pixels the camera sees fill the voxels the points left empty.
    Points { density: f32, source: points::PointSource, refine: bool },
}

/// Default tessellation level scale: the thesis' levels. Alone they miss voxels along
/// diagonals (recall 0.947 on the Cornell box at 128³; scale 3 gives 0.994 at 2.6× the time);
/// with the neighbour fill below, every voxel a triangle touches lies next to a sample, and
/// scale 1 is exact (docs/design/voxelizers.md).
pub const DEFAULT_LEVEL_SCALE: f32 = 1.0;

/// The tessellation path fills the empty voxels around each evaluation point that its
/// triangle meets: recall 1.000 on the Cornell box and the hostile set, where sampling alone
/// keeps 0.74–0.95.
pub const DEFAULT_NEIGHBOURS: bool = true;

impl VoxelizeMethod {
    pub fn tess() -> Self {
        VoxelizeMethod::Tess {
            level_scale: DEFAULT_LEVEL_SCALE,
            subdivide: true,
            min_level: true,
            neighbours: DEFAULT_NEIGHBOURS,
        }
    }
    pub fn points() -> Self {
        VoxelizeMethod::Points {
            density: points::DEFAULT_POINT_DENSITY,
            source: points::DEFAULT_POINT_SOURCE,
            refine: true,
        }
    }
    pub fn raster(coverage: Coverage) -> Self {
        VoxelizeMethod::Raster { coverage, viewport_scale: 1.0, depth_span: true }
    }

    /// The method as it runs on a device with these features (`Coverage::Auto` resolved).
    pub fn on(self, features: &crate::gpu::FeatureSet) -> Self {
        match self {
            VoxelizeMethod::Raster { coverage, viewport_scale, depth_span } => {
                VoxelizeMethod::Raster { coverage: coverage.on(features), viewport_scale, depth_span }
            }
            m => m,
        }
    }

    /// The device features this method needs.
    pub fn required_features(&self) -> Vec<Feature> {
        match self {
            VoxelizeMethod::Tess { .. } => vec![Feature::TessellationShader, Feature::VertexPipelineStoresAndAtomics],
            VoxelizeMethod::Raster { coverage, .. } => {
                let mut f = vec![Feature::GeometryShader, Feature::FragmentStoresAndAtomics];
                match coverage {
                    Coverage::Msaa => f.push(Feature::NoAttachmentMsaa4),
                    Coverage::Hardware => f.push(Feature::ConservativeRasterization),
                    // Auto falls back to the geometry shader, which needs nothing more.
                    Coverage::None | Coverage::Conservative | Coverage::Auto => {}
                }
                f
            }
            VoxelizeMethod::Points { refine, .. } => {
                let mut f = vec![Feature::VertexPipelineStoresAndAtomics];
                if *refine {
                    f.push(Feature::FragmentStoresAndAtomics);
                }
                f
            }
        }
    }

    /// The next method in the viewer's cycle (V): raster, tessellation, points.
    pub fn next(&self) -> Self {
        match self {
            VoxelizeMethod::Raster { .. } => VoxelizeMethod::tess(),
            VoxelizeMethod::Tess { .. } => VoxelizeMethod::points(),
            VoxelizeMethod::Points { .. } => VoxelizeMethod::raster(Coverage::Auto),
        }
    }

    /// What the method is called in errors, e.g. "the tessellation voxelizer".
    pub fn noun(&self) -> &'static str {
        match self {
            VoxelizeMethod::Tess { .. } => "the tessellation voxelizer",
            VoxelizeMethod::Raster { .. } => "the rasterized voxelizer",
            VoxelizeMethod::Points { .. } => "the point voxelizer",
        }
    }

    /// A short label, e.g. `tess`, `raster-msaa`.
    pub fn label(&self) -> String {
        match self {
            VoxelizeMethod::Tess { .. } => "tess".into(),
            VoxelizeMethod::Raster { coverage, .. } => match coverage {
                Coverage::None => "raster-none".into(),
                Coverage::Msaa => "raster-msaa".into(),
                Coverage::Hardware => "raster-hw".into(),
                Coverage::Conservative => "raster-conservative".into(),
                Coverage::Auto => "raster-auto".into(),
            },
            VoxelizeMethod::Points { .. } => "points".into(),
        }
    }
}

/// Mirrors `VoxelParams` in `shaders-glsl/common/voxel.glsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct VoxelParams {
    pub origin_size: [f32; 4],
    pub grid: [u32; 4],
    pub tess: [f32; 4],
    pub dims: [u32; 4],
    /// World to clip space of the view the point voxelizer refines (points::Refine).
    pub camera: [[f32; 4]; 4],
    /// The grid's warp (`warp::Warp::gpu`).
    pub warp: [f32; 4],
    /// A perspective warp's grid fraction to texture fraction (`warp::Warp::proj`).
    pub warp_proj: [[f32; 4]; 4],
}

/// A voxelizer's parameters and the uniform buffer that holds them.
pub struct ParamsUbo {
    params: VoxelParams,
    buffer: FrameBuffer,
}

impl ParamsUbo {
    /// Moves the grid (the volume follows the camera) or its warp's focus; the voxel size stays.
    pub fn set_origin(&mut self, grid: &VoxelGrid) {
        self.params.origin_size = grid.origin.extend(grid.voxel).into();
        self.params.warp = grid.warp.gpu().into();
        self.params.warp_proj = grid.warp.proj().to_cols_array_2d();
        self.buffer.set(std::mem::offset_of!(VoxelParams, origin_size), bytemuck::bytes_of(&self.params.origin_size));
        self.buffer.set(std::mem::offset_of!(VoxelParams, warp), bytemuck::bytes_of(&self.params.warp));
        self.buffer.set(std::mem::offset_of!(VoxelParams, warp_proj), bytemuck::bytes_of(&self.params.warp_proj));
    }

    /// Points the next draws at level `k` of `clip` (its box, in slab `k` of the stack), as one
    /// grid of its own: the voxelizers write a level as they write a grid.
    fn set_level(&self, clip: &clipmap::Clipmap, k: u32) {
        let level = clip.level_grid(k);
        let origin_size: [f32; 4] = level.origin.extend(level.voxel).into();
        let mut grid = self.params.grid;
        grid[2] = k * clip.res;
        self.buffer.set(std::mem::offset_of!(VoxelParams, origin_size), bytemuck::bytes_of(&origin_size));
        self.buffer.set(std::mem::offset_of!(VoxelParams, grid), bytemuck::bytes_of(&grid));
    }

    /// The camera a refinement sees this frame.
    pub fn set_camera(&self, view_proj: glam::Mat4) {
        let m = view_proj.to_cols_array_2d();
        self.buffer.set(std::mem::offset_of!(VoxelParams, camera), bytemuck::bytes_of(&m));
    }

    /// Uploads the parameters in the command stream (frames in flight read their own).
    pub fn record_upload(&self, cmd: vk::CommandBuffer) {
        self.buffer.record_upload(cmd);
    }

    /// The parameters the next voxelization reads; the camera only if `camera` (a voxelizer
    /// that looks through it).
    fn key(&self, camera: bool) -> Vec<u8> {
        let mut k = self.buffer.contents();
        if !camera {
            let at = std::mem::offset_of!(VoxelParams, camera);
            k[at..at + std::mem::size_of::<[[f32; 4]; 4]>()].fill(0);
        }
        k
    }
}

/// Set 2 of every voxelizer: their parameters and the volume's storage images.
pub(crate) fn voxel_set(
    ctx: &Arc<Context>,
    volume: &VoxelVolume,
    params: &VoxelParams,
) -> Result<(DescriptorSet, ParamsUbo)> {
    let g = vk::ShaderStageFlags::ALL_GRAPHICS;
    let set = DescriptorSet::new(
        ctx,
        "voxelize",
        &[
            Binding::new(0, vk::DescriptorType::UNIFORM_BUFFER, g),
            Binding::new(1, vk::DescriptorType::STORAGE_IMAGE, g),
            Binding::new(2, vk::DescriptorType::STORAGE_IMAGE, g),
            Binding::new(3, vk::DescriptorType::STORAGE_IMAGE, g),
            Binding::new(4, vk::DescriptorType::STORAGE_BUFFER, g),
            Binding::new(5, vk::DescriptorType::STORAGE_BUFFER, g),
        ],
    )?;
    let size = std::mem::size_of::<VoxelParams>() as u64;
    let buffer = FrameBuffer::new(ctx, "voxel params", size, vk::BufferUsageFlags::UNIFORM_BUFFER)?;
    buffer.set_pod(params);
    set.write_buffer(0, vk::DescriptorType::UNIFORM_BUFFER, &buffer.buffer);
    write_volume(&set, volume);
    Ok((set, ParamsUbo { params: *params, buffer }))
}

/// Points set 2 at `volume`'s textures, list and page table.
fn write_volume(set: &DescriptorSet, volume: &VoxelVolume) {
    set.write_storage(1, volume.albedo.view.raw);
    set.write_storage(2, volume.normal.view.raw);
    set.write_storage(3, volume.emission.view.raw);
    set.write_buffer(4, vk::DescriptorType::STORAGE_BUFFER, &volume.occupied.list);
    set.write_buffer(5, vk::DescriptorType::STORAGE_BUFFER, &volume.bricks.table);
}

pub(crate) fn params_for(
    grid: &VoxelGrid,
    flags: u32,
    viewport_scale: f32,
    level_scale: f32,
    max_level: f32,
) -> VoxelParams {
    let grid = &grid.voxelized();
    VoxelParams {
        origin_size: grid.origin.extend(grid.voxel).into(),
        grid: [grid.longest(), flags, 0, 0],
        dims: grid.dims.extend(0).into(),
        tess: [level_scale, max_level, viewport_scale, 0.0],
        camera: glam::Mat4::IDENTITY.to_cols_array_2d(),
        warp: grid.warp.gpu().into(),
        warp_proj: grid.warp.proj().to_cols_array_2d(),
    }
}

/// One of the three voxelizers, ready to record.
#[allow(clippy::large_enum_variant)] // one per renderer
pub enum Voxelizer {
    Tess(tess::TessVoxelizer),
    Raster(raster::RasterVoxelizer),
    Points(points::PointsVoxelizer),
}

impl Voxelizer {
    pub fn new(
        ctx: &Arc<Context>,
        scene: &Scene,
        scene_gpu: &SceneGpu,
        volume: &VoxelVolume,
        method: VoxelizeMethod,
    ) -> Result<Self> {
        let method = method.on(&ctx.info.features);
        ctx.require(&method.required_features(), method.noun())?;
        Ok(match method {
            VoxelizeMethod::Tess { level_scale, subdivide, min_level, neighbours } => Voxelizer::Tess(
                tess::TessVoxelizer::new(ctx, scene, scene_gpu, volume, level_scale, subdivide, min_level, neighbours)?,
            ),
            VoxelizeMethod::Raster { coverage, viewport_scale, depth_span } => Voxelizer::Raster(
                raster::RasterVoxelizer::new(ctx, scene_gpu, volume, coverage, viewport_scale, depth_span)?,
            ),
            VoxelizeMethod::Points { density, source, refine } => {
                Voxelizer::Points(points::PointsVoxelizer::new(ctx, scene, scene_gpu, volume, density, source, refine)?)
            }
        })
    }

    /// Records the voxelization of the scene into `volume` (cleared first). A clipmap's levels
    /// are voxelized one after another, each as a grid of its own written into its slab of the
    /// stack (`voxel::clipmap`), every frame: a level is as cheap to voxelize whole as the part of
    /// it that scrolled in is to find, where a frame's voxelization is a few percent of it
    /// (docs/design/clipmaps.md).
    pub fn record(&self, cmd: vk::CommandBuffer, scene_gpu: &SceneGpu, volume: &VoxelVolume) {
        volume.record_clear(cmd);
        let params = self.params();
        // `within`: a clipmap level's box, whose draw needs only the triangles that meet it.
        let draw = |within: Option<&crate::scene::Aabb>| {
            params.record_upload(cmd);
            match self {
                Voxelizer::Tess(t) => t.record(cmd, scene_gpu, within),
                Voxelizer::Raster(r) => r.record(cmd, scene_gpu, within),
                Voxelizer::Points(p) => p.record(cmd, scene_gpu),
            }
        };
        match &volume.grid.clip {
            None => draw(None),
            Some(clip) => {
                for k in 0..clip.levels {
                    params.set_level(clip, k);
                    // Padded by a voxel of the level: a triangle on the box's face still writes.
                    let level = clip.level_grid(k);
                    draw(Some(&level.bounds().grown(level.voxel)));
                    // Earlier levels' writes before the next level's (the same textures, list
                    // and page table; a voxel of two levels is two texels, but the list's count
                    // and the pool's slots are shared).
                    volume.record_between_draws(cmd);
                }
                // What the next frame's key reads: level 0, as set_grid left it.
                params.set_level(clip, 0);
            }
        }
        volume.record_finish(cmd);
    }

    fn params(&self) -> &ParamsUbo {
        match self {
            Voxelizer::Tess(t) => &t.params,
            Voxelizer::Raster(r) => &r.params,
            Voxelizer::Points(p) => &p.params,
        }
    }

    /// Writes into `volume` from now on (same grid and storage; the GPU must be idle).
    fn rebind(&self, volume: &VoxelVolume) {
        match self {
            Voxelizer::Tess(t) => write_volume(&t.set, volume),
            Voxelizer::Raster(r) => write_volume(&r.set, volume),
            Voxelizer::Points(p) => write_volume(&p.set, volume),
        }
    }

    /// Moves the grid the voxelizer writes (same voxel size and resolution).
    pub fn set_grid(&mut self, grid: &VoxelGrid) {
        let params = match self {
            Voxelizer::Tess(t) => &mut t.params,
            Voxelizer::Raster(r) => &mut r.params,
            Voxelizer::Points(p) => &mut p.params,
        };
        // A clipmap's stack grid has its level 0's origin and voxel: the draws of level 0 read
        // what this writes (`Voxelizer::record` points each draw at its level).
        params.set_origin(grid);
    }

    /// The camera this frame is seen from (the point voxelizer's refinement writes what it sees).
    pub fn set_camera(&self, view_proj: glam::Mat4) {
        if let Voxelizer::Points(p) = self {
            p.params.set_camera(view_proj);
        }
    }

    /// What the next voxelization depends on besides the scene's geometry (fixed for a
    /// renderer): its parameters (the grid's place among them) and, for points refined where
    /// the camera looks, the camera. Equal keys make the same voxels.
    pub fn key(&self) -> Vec<u8> {
        self.params().key(self.sees_camera())
    }

    /// Whether the voxels depend on the camera (points refined where it looks).
    pub fn sees_camera(&self) -> bool {
        matches!(self, Voxelizer::Points(p) if p.refines())
    }

    /// Notes for the user (e.g. how many triangles were subdivided).
    pub fn notes(&self) -> Vec<String> {
        match self {
            Voxelizer::Tess(t) => t.notes(),
            Voxelizer::Raster(_) => Vec::new(),
            Voxelizer::Points(p) => p.notes(),
        }
    }
}

/// Spare brick slots for a sparse volume that moves with the camera, as a fraction of the
/// census: the bricks it needs change as it moves, where a fitted grid over a static scene
/// needs the same bricks every frame.
pub const MOVING_POOL_HEADROOM: f64 = 0.25;

/// The volume over `grid` and its voxelizer. Sparse storage sizes the pool by a census: one
/// voxelization into a pool of no slots counts the bricks the scene occupies, and the pool
/// gets that many slots (plus MOVING_POOL_HEADROOM of them when the grid is `moving`), or
/// `bricks` slots when given. A fixed grid keeps the census' bricks from frame to frame, in
/// brick order ([`bricks::Bricks::assign`]). Resident storage binds memory for the census'
/// bricks ([`bricks::Bricks::resident`]). `Auto` storage is resolved for `moving` first.
pub fn build(
    ctx: &Arc<Context>,
    scene: &Scene,
    scene_gpu: &SceneGpu,
    grid: VoxelGrid,
    method: VoxelizeMethod,
    request: bricks::StorageRequest,
) -> Result<(VoxelVolume, Voxelizer)> {
    let bricks::StorageRequest { bricks, moving, .. } = request;
    let storage = request.resolve(ctx);
    let headroom = if moving { MOVING_POOL_HEADROOM } else { 0.0 };
    let sized = |n: u32| VoxelVolume::new(ctx, grid, storage, n + 1);
    match storage {
        bricks::Storage::Dense => {
            let volume = sized(0)?;
            let voxelizer = Voxelizer::new(ctx, scene, scene_gpu, &volume, method)?;
            return Ok((volume, voxelizer));
        }
        bricks::Storage::Resident if moving => {
            return Err(crate::Error::param(
                "storage",
                "resident storage binds the blocks a census of the fixed grid finds: a volume following the camera needs --storage dense or sparse",
            ))
        }
        bricks::Storage::Resident if bricks.is_some() => {
            return Err(crate::Error::param("bricks", "--bricks sizes the sparse brick pool; resident storage has none"))
        }
        bricks::Storage::Resident => return build_resident(ctx, scene, scene_gpu, grid, method),
        _ => {}
    }
    let mut volume = sized(bricks.unwrap_or(0))?;
    let voxelizer = Voxelizer::new(ctx, scene, scene_gpu, &volume, method)?;
    if bricks.is_some() {
        return Ok((volume, voxelizer));
    }
    let asked = census(ctx, scene_gpu, &volume, &voxelizer)?;
    let needed = volume.bricks.usage().needed;
    volume.resize_pool(needed + (needed as f64 * headroom).ceil() as u32 + 1)?;
    // A fixed grid keeps the census' bricks, in brick order; a moving one claims them anew.
    if !moving {
        volume.bricks.assign(&asked)?;
    }
    voxelizer.rebind(&volume);
    Ok((volume, voxelizer))
}

/// Voxelizes the scene into `volume`, a pool of no slots or a resident table of no bricks, and
/// returns its table: nonzero for each brick the scene asked for.
fn census(ctx: &Context, scene_gpu: &SceneGpu, volume: &VoxelVolume, voxelizer: &Voxelizer) -> Result<Vec<u32>> {
    ctx.submit_and_wait("brick census", |cmd| voxelizer.record(cmd, scene_gpu, volume))?;
    volume.bricks.read_pages()
}

/// Resident storage: a census through a table that binds no brick finds the bricks (the
/// voxelizer refuses and marks each one it meets, touching no texture), then the textures over
/// the whole grid get memory in the blocks that hold them, written as dense by the same
/// voxelizer (which refuses, and counts, a write outside the census' bricks).
fn build_resident(
    ctx: &Arc<Context>,
    scene: &Scene,
    scene_gpu: &SceneGpu,
    grid: VoxelGrid,
    method: VoxelizeMethod,
) -> Result<(VoxelVolume, Voxelizer)> {
    bricks::require_residency(ctx)?;
    let none = vec![0; bricks::brick_count(&grid).element_product() as usize];
    let mut volume = VoxelVolume::stored(ctx, grid, bricks::Bricks::resident(ctx, &grid, &none)?)?;
    let voxelizer = Voxelizer::new(ctx, scene, scene_gpu, &volume, method)?;
    let asked = census(ctx, scene_gpu, &volume, &voxelizer)?;
    volume.rebrick(bricks::Bricks::resident(ctx, &grid, &asked)?)?;
    voxelizer.rebind(&volume);
    Ok((volume, voxelizer))
}

pub(crate) fn flag(on: bool, bit: u32) -> u32 {
    if on {
        bit
    } else {
        0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gpu::FeatureSet;

    #[test]
    fn auto_coverage_takes_the_extension_only_where_offered() {
        let mut f = FeatureSet::default();
        assert_eq!(Coverage::Auto.on(&f), Coverage::Conservative);
        f.conservative_rasterization = true;
        assert_eq!(Coverage::Auto.on(&f), Coverage::Hardware);
        // An explicit choice is kept, and the label says what runs.
        assert_eq!(Coverage::Msaa.on(&f), Coverage::Msaa);
        assert_eq!(VoxelizeMethod::raster(Coverage::Auto).on(&f).label(), "raster-hw");
        assert_eq!(VoxelizeMethod::tess().on(&f), VoxelizeMethod::tess());
    }
}
