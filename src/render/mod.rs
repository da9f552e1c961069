//! The frame: each pass is one module with one struct (`new` + `record`), and
//! [`Renderer::record`] lists the frame's passes in order, top to bottom.

pub mod bounce;
pub mod deferred;
pub mod filter;
pub mod frame;
pub mod inject;
pub mod layout;
pub mod memory;
pub mod occupancy;
pub mod overlay;
pub mod prepass;
pub mod quality;
pub mod radiance;
pub mod shade;
pub mod shadow;
pub mod temporal;
pub mod tonemap;
pub mod volume_view;
pub mod voxel_view;

use std::sync::Arc;

use ash::vk;

use std::cell::Cell;

use crate::error::Result;
use crate::gpu::{self, Context, GpuTimer, Image, ImageDesc, Timing};
use crate::scene::file::Filter;
use crate::scene::gpu::FrameUniforms;
use crate::scene::gpu::SceneGpu;
use crate::scene::Scene;
use crate::voxel::bricks::Storage;
use crate::voxel::{VoxelGrid, VoxelVolume, VoxelizeMethod, Voxelizer};
use bounce::BouncePass;
use deferred::DeferredShadePass;
use filter::FilterPass;
use frame::FrameState;
pub use frame::View;
use inject::InjectPass;
use prepass::DepthPrepass;
pub use quality::Quality;
use radiance::{Chains, RadianceVolume};
use shade::ShadePass;
use shadow::ShadowPass;
use temporal::{Source, TemporalBlend};
use tonemap::TonemapPass;
use volume_view::VolumeViewPass;

/// The images a frame renders into.
pub struct Targets {
    pub width: u32,
    pub height: u32,
    pub depth: Image,
    /// Linear radiance.
    pub hdr: Image,
    /// Tone-mapped, gamma-encoded output.
    pub ldr: Image,
}

impl Targets {
    pub const DEPTH_FORMAT: vk::Format = vk::Format::D32_SFLOAT;
    pub const HDR_FORMAT: vk::Format = vk::Format::R32G32B32A32_SFLOAT;
    pub const LDR_FORMAT: vk::Format = vk::Format::R8G8B8A8_UNORM;

    /// Discards `hdr` and leaves it in GENERAL for a compute pass that writes every pixel.
    pub fn hdr_for_compute(&self, ctx: &Context, cmd: vk::CommandBuffer) {
        let rw = gpu::scope::COMPUTE_RW;
        gpu::image_barrier(ctx, cmd, &self.hdr, vk::ImageLayout::UNDEFINED, vk::ImageLayout::GENERAL, rw, rw);
    }

    /// Dispatches one compute thread per pixel (2D workgroups of WORKGROUP_2D²).
    pub fn dispatch_per_pixel(&self, ctx: &Context, cmd: vk::CommandBuffer) {
        let local = crate::config::WORKGROUP_2D;
        gpu::dispatch(ctx, cmd, [self.width, self.height, 1], [local, local, 1]);
    }

    pub fn new(ctx: &Arc<Context>, width: u32, height: u32) -> Result<Self> {
        let u = vk::ImageUsageFlags::TRANSFER_SRC;
        Ok(Targets {
            width,
            height,
            depth: Image::new(
                ctx,
                "depth",
                ImageDesc::d2(Self::DEPTH_FORMAT, width, height, vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT | u),
            )?,
            hdr: Image::new(
                ctx,
                "hdr radiance",
                ImageDesc::d2(
                    Self::HDR_FORMAT,
                    width,
                    height,
                    vk::ImageUsageFlags::COLOR_ATTACHMENT | vk::ImageUsageFlags::STORAGE | u,
                ),
            )?,
            ldr: Image::new(
                ctx,
                "ldr output",
                ImageDesc::d2(Self::LDR_FORMAT, width, height, vk::ImageUsageFlags::STORAGE | u),
            )?,
        })
    }
}

/// A rendered frame read back to the host.
pub struct FrameImages {
    pub width: u32,
    pub height: u32,
    /// Linear radiance, RGBA32F, row-major from the top.
    pub hdr: Vec<f32>,
    /// Tone-mapped sRGB-ish (gamma 2.2) RGBA8.
    pub ldr: Vec<u8>,
}

/// Where the final shading (and so the cone tracing) runs. Measured on lavapipe, 512×512,
/// 128³, median of 5 frames: Cornell box forward 254.0 ms (prepass 0.5 + shade 253.4) against
/// deferred 253.4 ms (G-buffer 7.5 + shade 245.9); Sponza forward 727.8 ms (13.5 + 714.3)
/// against deferred 375.6 ms (25.5 + 350.1). A fragment shader runs in 2×2 quads, and along
/// the edges of Sponza's many small triangles the helper lanes trace cones too; one compute
/// thread per pixel does not. Hence deferred is the default; forward is the thesis' choice.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Tracing {
    /// Fragment shader after a depth prepass (the thesis' choice).
    Forward,
    /// Compute shader over a G-buffer (the default).
    #[default]
    Deferred,
}

/// A voxel volume that follows a moving point (the camera) instead of fitting the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Follow {
    /// Edge length of the volume, world units.
    pub extent: f32,
    /// Move the volume in whole voxels.
    pub snap: bool,
}

/// Clipmap cascades around the camera (`voxel::clipmap`): `levels` levels of `--res` voxels
/// each, the finest `extent` wide (world units; `None`: `Clipmap::default_extent`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClipOptions {
    pub levels: u32,
    pub extent: Option<f32>,
}

/// What to render with: the voxelizer, the grid resolution, the view, GI on or off.
#[derive(Clone, Copy, Debug)]
pub struct RenderOptions {
    pub method: VoxelizeMethod,
    /// Voxels along the grid's longest axis; `None`: the scene's.
    pub resolution: Option<u32>,
    /// Voxels along each axis (overrides `resolution`); `None`: fitted to the scene's shape.
    pub dims: Option<glam::UVec3>,
    pub view: View,
    pub gi: bool,
    pub tracing: Tracing,
    /// A volume around a moving point; `None`: fitted to the scene.
    pub follow: Option<Follow>,
    /// Warp the grid, its finest texels at the camera: by the thesis' function (Freed 2018
    /// §4.6.1) or its perspective (§4.6.2; `voxel::warp`); `None`: even texels.
    pub warp: Option<crate::voxel::warp::WarpChoice>,
    /// Clipmap cascades around the camera instead of one grid; `None`: one grid.
    pub clipmap: Option<ClipOptions>,
    /// The fitted grid's lattice moved by this many voxels along each axis (each within ±0.5,
    /// which its padding holds), or a clipmap's levels by this many voxels of the coarsest
    /// (`Clipmap::on_lattice`): the same scene cut by other voxel boundaries, to measure how
    /// far an image's accuracy depends on where the lattice falls (`vct bench --accuracy
    /// --lattices`); `None`: centred on the scene (a clipmap: on the world's lattice).
    pub lattice: Option<glam::Vec3>,
    /// Shadow-map texels injection reads across a voxel (0: every texel of the map).
    pub inject_texels: f32,
    /// Which texels the passes over the volume visit.
    pub work: Work,
    /// Where the per-voxel textures live (voxel::bricks).
    pub storage: Storage,
    /// Slots of the sparse brick pool; `None`: as many as a census counts.
    pub bricks: Option<u32>,
    /// The diffuse cones run at one pixel in `gi_scale`² (1, 2, 4 or 8), upsampled edge-aware
    /// (deferred tracing only).
    pub gi_scale: u32,
    /// Accumulate the reduced-resolution diffuse cones over frames in screen space (the traced
    /// pixel moves through each block; the history follows the camera; `gi_scale` > 1).
    pub gi_accumulate: bool,
    /// With `gi_scale` > 1, the specular cone is traced with the diffuse cones at one pixel in
    /// `gi_scale`², upsampled and accumulated alike (each pixel applies its own Fresnel
    /// factor); off, every pixel traces its own. On: on Sponza the per-pixel specular cone takes
    /// 70% of the shading time (docs/design/reduced-scale.md).
    pub reduced_specular: bool,
    /// Keep last frame's voxels and radiance when nothing they depend on changed (the scene is
    /// static; the lights, the grid and the GI settings are as they were; no temporal filter
    /// still converging; a camera-independent voxelizer): the viewer's frame is then the
    /// G-buffer and the shading. When only the lights (or the GI settings) changed, the voxels
    /// are kept and the light's passes run. A still view that has traced every pixel since the
    /// last change (with accumulation, gi-scale² frames; else one) shades from what it traced
    /// without tracing (`deferred::DeferredShadePass::settled`). Off, every frame builds the volume again and
    /// traces (bench, render).
    pub reuse_volume: bool,
}

/// Which texels the mip filters visit.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Work {
    /// The occupied texels of each level, from lists built on the GPU, dispatched indirectly.
    #[default]
    Occupied,
    /// Every texel of each level (for comparison).
    Dense,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            // Exact and the fastest: hardware conservative rasterization where the device has
            // it, else the geometry shader's (docs/design/voxelizers.md; docs/report/README.md).
            method: VoxelizeMethod::raster(crate::voxel::Coverage::Auto),
            resolution: None,
            dims: None,
            view: View::Full,
            gi: true,
            tracing: Tracing::default(),
            follow: None,
            warp: None,
            clipmap: None,
            lattice: None,
            inject_texels: crate::config::INJECT_TEXELS_PER_VOXEL,
            work: Work::default(),
            storage: Storage::default(),
            bricks: None,
            gi_scale: 1,
            gi_accumulate: false,
            reduced_specular: true,
            reuse_volume: false,
        }
    }
}

pub struct Renderer {
    pub ctx: Arc<Context>,
    pub scene: Scene,
    pub options: RenderOptions,
    pub scene_gpu: SceneGpu,
    pub voxels: VoxelVolume,
    voxelizer: Voxelizer,
    shadow: ShadowPass,
    pub radiance: RadianceVolume,
    inject: InjectPass,
    temporal: TemporalBlend,
    filter: FilterPass,
    bounce: Option<BouncePass>,
    prepass: DepthPrepass,
    shade: ShadePass,
    deferred: Option<DeferredShadePass>,
    volume_view: VolumeViewPass,
    tonemap: TonemapPass,
    pub targets: Targets,
    timer: GpuTimer,
    frame_index: Cell<u64>,
    /// A share of a whole turn added to every pixel's turn of the cone set
    /// (`GiFile::turn_cones`; `FrameUniforms::view.w`): frames of several phases averaged are the
    /// converged frame the flat-wall pattern is measured against (`bench::accuracy::pattern`).
    pub turn_phase: Cell<f32>,
    /// The grid origin of the last submitted frame, for the temporal blend's reprojection.
    previous_origin: Cell<glam::Vec3>,
    /// This frame's camera (world to clip), and the last submitted frame's, for the screen-space
    /// accumulation's reprojection.
    view_proj: Cell<glam::Mat4>,
    previous_view_proj: Cell<Option<glam::Mat4>>,
    /// Whether this frame keeps last frame's volume ([`volume_key`]).
    volume_kept: Kept,
    /// Whether this frame keeps last frame's voxels ([`Voxelizer::key`]): a turning light
    /// needs new shadow maps, injection and filtering, but not new voxels.
    voxels_kept: Kept,
    /// Whether this frame's uniforms, but the screen-space jitter and history, are the last
    /// frame's: with the volume kept, a still view's traced light is then too
    /// ([`deferred::DeferredShadePass::settle`]).
    traced_kept: Kept,
    /// Problems worth telling the user (coarse shadow map, subdivided triangles).
    pub notes: Vec<String>,
}

/// What something a frame builds depended on when it was last built, and whether this frame
/// keeps it (`RenderOptions::reuse_volume`).
#[derive(Default)]
struct Kept {
    key: std::cell::RefCell<Option<Vec<u8>>>,
    kept: Cell<bool>,
}

impl Kept {
    /// This frame's key: what was built is kept when `reuse` and the key is the last one.
    fn update(&self, key: Vec<u8>, reuse: bool) {
        let mut last = self.key.borrow_mut();
        self.kept.set(reuse && last.as_ref() == Some(&key));
        *last = Some(key);
    }

    fn get(&self) -> bool {
        self.kept.get()
    }
}

/// What a frame's volume depends on, from its uniforms: all but the camera (unless the voxelizer
/// sees through it, `camera`: points with refinement) and the screen-space state.
fn volume_key(u: &FrameUniforms, camera: bool) -> Vec<u8> {
    let mut k = *u;
    if !camera {
        k.view_proj = glam::Mat4::ZERO;
        k.inv_view_proj = glam::Mat4::ZERO;
        k.camera_pos = glam::Vec4::ZERO;
    }
    k.viewport = glam::Vec4::ZERO;
    k.view = glam::Vec4::ZERO;
    k.previous_view_proj = glam::Mat4::ZERO;
    k.gi_jitter = glam::Vec4::ZERO;
    bytemuck::bytes_of(&k).to_vec()
}

impl Renderer {
    pub fn new(ctx: &Arc<Context>, scene: Scene, mut options: RenderOptions) -> Result<Self> {
        // The options say what runs (labels, timings, the viewer's overlay).
        options.method = options.method.on(&ctx.info.features);
        let resolution = options.resolution.unwrap_or(scene.settings.voxel_resolution);
        let grid = layout::grid_for(ctx, &scene, &options, resolution)?;
        let scene_gpu = SceneGpu::new(ctx, &scene)?;
        let targets = Targets::new(ctx, scene.camera.width, scene.camera.height)?;
        // Light lives in occupied voxels only: a voxel the temporal blend would leave lit after
        // its geometry left it (a trail behind a moving volume) stays dark.
        let listed = options.work == Work::Occupied;
        let request = crate::voxel::bricks::StorageRequest {
            storage: options.storage,
            bricks: options.bricks,
            moving: options.moving(),
        };
        let sparse = request.resolve(ctx) == Storage::Sparse;
        if sparse && options.follow.is_some() && scene.settings.gi.temporal < 1.0 {
            // The history is stored as level 0: in a moving pool its slots change every frame.
            return Err(crate::Error::param(
                "temporal",
                "temporal filtering of a volume following the camera needs --storage dense (auto picks it)",
            ));
        }
        // The whole set before any of it is allocated (all but the pool, whose size the census
        // tells), and again with the pool.
        let bounces = scene.settings.gi.bounces > 1;
        let temporal = scene.settings.gi.temporal < 1.0;
        let chains = Chains::read_by(scene.settings.gi.filter, matches!(options.view, View::Radiance(_)));
        let need = |pool: Option<u32>, resident: Option<&crate::voxel::bricks::Residency>| {
            let layout = memory::Layout { bounces, listed, pool, resident, temporal, chains };
            memory::MemoryReport::for_grid(&grid, &layout).bytes
        };
        crate::voxel::volume::check_fits(ctx, &grid, need(sparse.then_some(1), None))?;
        let (voxels, voxelizer) = crate::voxel::build(ctx, &scene, &scene_gpu, grid, options.method, request)?;
        let pool = sparse.then_some(voxels.bricks.capacity);
        crate::voxel::volume::check_fits(ctx, &grid, need(pool, voxels.bricks.residency.as_ref()))?;
        let shadow = ShadowPass::new(ctx, &scene_gpu, scene.settings.shadow_resolution, &scene.lights)?;
        let gi = &scene.settings.gi;
        let aniso = gi.filter == Filter::Aniso;
        let radiance = RadianceVolume::new(ctx, &voxels, gi.bounces > 1, temporal, chains)?;
        let occupied = &voxels.occupied;
        // Each light's own strides, one a layer, from its own shadow texels: a light's
        // injection must not depend on the other lights.
        let res = scene.settings.shadow_resolution;
        let texels: Vec<Vec<Option<f32>>> =
            scene.lights.iter().map(|l| frame::layer_texel_sizes(l, &scene.mesh.bounds, res)).collect();
        let strides = (texels.iter())
            .map(|layers| {
                (layers.iter())
                    .map(|t| t.map(|t| inject::injection_stride(t, grid.voxel, options.inject_texels)))
                    .collect()
            })
            .collect();
        let from_voxels = inject::from_voxels(scene.settings.gi.injection, grid.is_warped());
        let inject = InjectPass::new(ctx, &scene_gpu, &shadow, &voxels, &radiance, strides, listed, from_voxels)?;
        // A fitted grid over the static scene lists the same voxels every frame.
        let fixed = options.follow.is_none() && options.clipmap.is_none();
        let temporal = TemporalBlend::new(ctx, &scene_gpu, &radiance, &voxels, listed, fixed)?;
        let filter = FilterPass::new(ctx, &radiance, &voxels, occupied, listed, fixed)?;
        let bounce = (gi.bounces > 1)
            .then(|| BouncePass::new(ctx, &scene_gpu, &voxels, &radiance, occupied, aniso))
            .transpose()?;
        let prepass = DepthPrepass::new(ctx, &scene_gpu)?;
        let grid_spec = voxels.grid.spec();
        let shade = ShadePass::new(ctx, &scene_gpu, &shadow, &radiance, &voxels.bricks, aniso, grid_spec)?;
        let deferred = match options.tracing {
            Tracing::Deferred => {
                let (s, acc) = (options.gi_scale, options.gi_accumulate);
                Some(DeferredShadePass::new(
                    ctx,
                    &scene_gpu,
                    &shadow,
                    &radiance,
                    &voxels.bricks,
                    &targets,
                    &quality::traced_model(&scene, &options),
                    s,
                    acc,
                    options.reduced_specular,
                    grid_spec,
                )?)
            }
            Tracing::Forward if options.gi_scale != 1 || options.gi_accumulate => {
                return Err(crate::Error::param("gi-scale", "tracing at a reduced resolution needs --tracing deferred"))
            }
            Tracing::Forward => None,
        };
        let volume_view = VolumeViewPass::new(ctx, &scene_gpu, &voxels, &radiance, &targets)?;
        let tonemap = TonemapPass::new(ctx, &targets)?;
        let timer = GpuTimer::new(ctx, 16)?;
        let mut notes = voxelizer.notes();
        if grid.voxel < 1e-3 {
            notes.push(format!(
                "voxels are {:.3} mm across: the scene is tiny for a {} grid (units are metres) — a lower resolution would do",
                grid.voxel * 1e3,
                grid.dims_label()
            ));
        }
        // Injection from the texels misses the voxels no texel lands in (from the voxels, none).
        let texel = texels.iter().flatten().flatten().copied().fold(0.0, f32::max);
        if !from_voxels && texel > 0.7 * grid.voxel {
            notes.push(format!(
                "shadow map too coarse for the grid: a texel covers up to {texel:.4} m, a voxel {:.4} m; lit voxels may be missed during injection (raise shadow.resolution)",
                grid.voxel
            ));
        }
        let origin = voxels.grid.origin;
        Ok(Renderer {
            ctx: ctx.clone(),
            scene,
            options,
            scene_gpu,
            voxels,
            voxelizer,
            shadow,
            radiance,
            inject,
            temporal,
            filter,
            bounce,
            prepass,
            shade,
            deferred,
            volume_view,
            tonemap,
            targets,
            timer,
            frame_index: Cell::new(0),
            turn_phase: Cell::new(0.0),
            previous_origin: Cell::new(origin),
            view_proj: Cell::new(glam::Mat4::IDENTITY),
            previous_view_proj: Cell::new(None),
            volume_kept: Kept::default(),
            voxels_kept: Kept::default(),
            traced_kept: Kept::default(),
            notes,
        })
    }

    /// Uploads this frame's uniforms from the scene's camera and light.
    pub fn update_uniforms(&self) {
        let s = &self.scene;
        let state = FrameState {
            grid: &self.voxels.grid,
            mip_levels: self.radiance.levels,
            gi: &s.settings.gi,
            cone_count: self.scene_gpu.cone_count,
            bounce_cone_count: self.scene_gpu.bounce_cone_count,
            gi_on: self.options.gi,
            view: self.options.view,
            first_frame: self.frame_index.get() == 0,
            previous_origin: self.previous_origin.get(),
            previous_view_proj: self.previous_view_proj.get(),
            gi_jitter: self.deferred.as_ref().map_or(glam::Vec4::ZERO, |d| d.jitter_uniform()),
        };
        let mut u = FrameUniforms::new(&s.camera, &s.lights, &s.mesh.bounds, s.settings.shadow_resolution, &state);
        // Whether the camera moved since the last frame: the accumulated specular cone, which
        // depends on where the camera looks from, keeps no history then.
        u.gi_jitter.w = (self.previous_view_proj.get() != Some(u.view_proj)) as u32 as f32;
        u.view.w = self.turn_phase.get();
        self.scene_gpu.uniforms.set_pod(&u);
        self.voxelizer.set_camera(u.view_proj);
        self.view_proj.set(u.view_proj);
        let reuse = self.options.reuse_volume;
        // A temporal filter still converging changes the volume every frame.
        let volume = volume_key(&u, self.voxelizer.sees_camera());
        self.volume_kept.update(volume, reuse && s.settings.gi.temporal >= 1.0);
        // A clipmap's levels each snap on their own: their every corner keys the voxels.
        let mut voxels = self.voxelizer.key();
        if let Some(c) = &self.voxels.grid.clip {
            voxels.extend_from_slice(bytemuck::bytes_of(&c.origins));
        }
        self.voxels_kept.update(voxels, reuse);
        if let Some(d) = &self.deferred {
            let mut k = u;
            k.previous_view_proj = glam::Mat4::ZERO;
            k.gi_jitter = glam::Vec4::ZERO;
            self.traced_kept.update(bytemuck::bytes_of(&k).to_vec(), reuse);
            d.settle(self.traced_kept.get() && self.volume_kept.get());
        }
    }

    /// Records one whole frame. The passes, in order:
    pub fn record(&self, cmd: vk::CommandBuffer) {
        let t = &self.timer;
        let (scene, targets) = (&self.scene_gpu, &self.targets);
        t.reset(cmd);
        // The uniforms travel in the command stream: earlier frames may still be running.
        scene.uniforms.record_upload(cmd);
        t.span(cmd, "total", || {
            if !self.volume_kept.get() {
                self.record_volume(cmd);
            }
            if self.options.view.is_volume() {
                t.span(cmd, "volume view", || self.volume_view.record(cmd, scene, targets));
            } else if let Some(d) = &self.deferred {
                t.span(cmd, "gbuffer", || d.record_gbuffer(cmd, scene, targets));
                t.span(cmd, "shade", || d.record_shade(cmd, scene, targets, t));
            } else {
                t.span(cmd, "depth prepass", || self.prepass.record(cmd, scene, targets));
                t.span(cmd, "shade", || self.shade.record(cmd, scene, targets));
            }
            t.span(cmd, "tonemap", || self.tonemap.record(cmd, targets, self.options.view.is_raw()));
        });
    }

    /// The frame's volume: voxelize (unless the voxels are kept), shadow maps, injection, mip
    /// filtering and bounces.
    fn record_volume(&self, cmd: vk::CommandBuffer) {
        let t = &self.timer;
        let scene = &self.scene_gpu;
        if !self.voxels_kept.get() {
            t.span(cmd, "voxelize", || self.voxelizer.record(cmd, scene, &self.voxels));
        }
        let light = !self.scene.lights.is_empty();
        if light {
            t.span(cmd, "shadow map", || self.shadow.record(cmd, scene));
        }
        let gi = &self.scene.settings.gi;
        let (temporal, bounces, aniso) = (gi.temporal < 1.0, gi.bounces.max(1), gi.filter == Filter::Aniso);
        let moment = gi.facing;
        t.span(cmd, "inject", || {
            self.inject.record(cmd, scene, &self.radiance, &self.voxels.occupied, light);
            let temporal = temporal && self.radiance.has_history();
            if temporal {
                self.temporal.record_history(cmd, &self.radiance);
            }
            // Without a blend or bounces, level 0 is the injected light itself.
            if self.radiance.radiance.is_some() {
                let history = temporal && bounces == 1;
                self.temporal.record(cmd, scene, &self.radiance, &self.voxels.occupied, Source::Injected, history);
            }
        });
        let first = self.frame_index.get() == 0;
        let filter = || self.filter.record(cmd, &self.radiance, &self.voxels.occupied, aniso, moment, first);
        t.span(cmd, "filter", filter);
        if let Some(b) = &self.bounce {
            t.span(cmd, "bounces", || {
                for k in 1..bounces {
                    b.record(cmd, scene, &self.radiance, &self.voxels.occupied);
                    let last = temporal && k + 1 == bounces;
                    self.temporal.record(cmd, scene, &self.radiance, &self.voxels.occupied, Source::Bounced, last);
                    filter();
                }
            });
        }
    }

    /// Renders one frame and waits for it; returns the GPU time of each pass.
    pub fn render(&self) -> Result<Vec<Timing>> {
        self.update_uniforms();
        self.ctx.submit_and_wait("frame", |cmd| self.record(cmd))?;
        self.frame_recorded();
        self.voxels.bricks.check()?;
        self.timings()
    }

    /// Records one frame into `ring` and submits it without waiting for it (frames in flight,
    /// as the viewer runs them). Returns the GPU times of the frame two before, which the ring
    /// has seen finish (empty for the first two frames).
    pub fn submit_in_flight(&self, ring: &mut gpu::FrameRing) -> Result<Vec<Timing>> {
        let mut settled = (Ok(Vec::new()), Ok(()));
        ring.frame(|cmd| settled = self.record_in_flight(cmd))?;
        self.frame_recorded();
        settled.1?;
        settled.0
    }

    /// Records one frame while earlier ones may still run (the viewer's swapchain, or
    /// [`Self::submit_in_flight`]): first reads what the frame before the last left, which the
    /// caller's fence has seen finish — its GPU times, and whether its bricks fitted the pool —
    /// then uploads this frame's uniforms and records it. Call [`Self::frame_recorded`] once
    /// it is submitted.
    pub fn record_in_flight(&self, cmd: vk::CommandBuffer) -> (Result<Vec<Timing>>, Result<()>) {
        let settled = (self.settled_timings(), self.voxels.bricks.check_settled());
        self.update_uniforms();
        self.record(cmd);
        settled
    }

    /// Marks a frame as submitted (the next one may blend with its radiance).
    pub fn frame_recorded(&self) {
        self.frame_index.set(self.frame_index.get() + 1);
        self.previous_origin.set(self.voxels.grid.origin);
        self.previous_view_proj.set(Some(self.view_proj.get()));
    }

    /// Bytes of the voxel textures and radiance volumes at this grid, beside the bounding cube's.
    pub fn memory(&self) -> memory::MemoryReport {
        let b = &self.voxels.bricks;
        let layout = memory::Layout {
            bounces: self.radiance.bounced.is_some(),
            listed: self.filter.is_listed(),
            pool: b.sparse().then_some(b.capacity),
            resident: b.residency.as_ref(),
            temporal: self.radiance.has_history(),
            chains: self.radiance.chains,
        };
        memory::MemoryReport::for_grid(&self.voxels.grid, &layout)
    }

    /// The GPU time of each pass of the last frame (call after it finished).
    pub fn timings(&self) -> Result<Vec<Timing>> {
        self.timer.read()
    }

    /// The GPU time of each pass of the frame recorded before the last: with frames in
    /// flight, the one the next frame's fence has seen finish.
    pub fn settled_timings(&self) -> Result<Vec<Timing>> {
        self.timer.read_settled()
    }

    /// Centres a following volume or a clipmap's levels on `anchor`, and a warped grid's finest
    /// texels (no effect on a fitted, even grid).
    pub fn follow(&mut self, anchor: glam::Vec3) -> Result<()> {
        let mut grid = self.voxels.grid;
        if let Some(mut clip) = grid.clip {
            if !anchor.is_finite() {
                return Err(crate::Error::param("camera", format!("the clipmap's centre {anchor} is not finite")));
            }
            clip.recentre(anchor);
            grid = clip.stack_grid();
        }
        if let Some(f) = self.options.follow {
            grid = VoxelGrid { warp: grid.warp, ..VoxelGrid::around(anchor, f.extent, grid.longest(), f.snap)? };
        }
        grid = grid.refocused(anchor, &self.scene.camera, &self.scene.mesh.bounds)?;
        if grid != self.voxels.grid {
            self.voxels.grid = grid;
            self.voxelizer.set_grid(&grid);
        }
        Ok(())
    }

    /// Renders at a new size: the targets and the passes that write them are rebuilt.
    pub fn resize(&mut self, width: u32, height: u32) -> Result<()> {
        crate::scene::check_image_size(width, height)?;
        self.ctx.wait_idle()?;
        let ctx = self.ctx.clone();
        self.scene.camera.width = width;
        self.scene.camera.height = height;
        self.targets = Targets::new(&ctx, width, height)?;
        self.deferred = match self.options.tracing {
            Tracing::Deferred => Some(DeferredShadePass::new(
                &ctx,
                &self.scene_gpu,
                &self.shadow,
                &self.radiance,
                &self.voxels.bricks,
                &self.targets,
                &quality::traced_model(&self.scene, &self.options),
                self.options.gi_scale,
                self.options.gi_accumulate,
                self.options.reduced_specular,
                self.voxels.grid.spec(),
            )?),
            Tracing::Forward => None,
        };
        self.volume_view = VolumeViewPass::new(&ctx, &self.scene_gpu, &self.voxels, &self.radiance, &self.targets)?;
        self.tonemap = TonemapPass::new(&ctx, &self.targets)?;
        Ok(())
    }
    /// Reads the last frame's HDR and LDR images back to the host.
    pub fn read_frame(&self) -> Result<FrameImages> {
        let hdr = gpu::read_image(&self.ctx, &self.targets.hdr, vk::ImageLayout::GENERAL, 0)?;
        let ldr = gpu::read_image(&self.ctx, &self.targets.ldr, vk::ImageLayout::GENERAL, 0)?;
        Ok(FrameImages {
            width: self.targets.width,
            height: self.targets.height,
            hdr: bytemuck::cast_slice(&hdr).to_vec(),
            ldr,
        })
    }
}
