//! What the commands share: the scene, voxelizer and device options of `render`, `view` and
//! `voxelize` (clap derive) with the parsers that name a bad value, and the helpers that load a
//! scene, open the device and check the validation layer.

use std::path::{Path, PathBuf};

use anyhow::{bail, Context as _, Result};
use clap::Args;

use vct::gpu::{Context, ContextOptions, Timing};
use vct::scene::Scene;
use vct::voxel::bricks::Storage;
use vct::voxel::{Coverage, VoxelizeMethod};

pub fn load_scene(path: Option<&Path>) -> Result<Scene> {
    let scene = match path {
        Some(p) => Scene::load(p).with_context(|| format!("loading scene {}", p.display()))?,
        None => Scene::embedded_default().context("loading the embedded default scene")?,
    };
    for w in &scene.warnings {
        log::warn!("{w}");
    }
    Ok(scene)
}

pub fn open_device(args: &GpuArgs) -> Result<std::sync::Arc<Context>> {
    let ctx = Context::new(&ContextOptions::from_env(args.validation, args.device.clone()))
        .context("opening the Vulkan device")?;
    println!("device: {} ({}, {})", ctx.info.name, ctx.info.kind_name(), ctx.info.driver);
    Ok(ctx)
}

pub fn check_validation(ctx: &Context) -> Result<()> {
    let (e, w) = (ctx.validation.errors(), ctx.validation.warnings());
    if e + w > 0 {
        bail!("the validation layer reported {e} error(s) and {w} warning(s)");
    }
    Ok(())
}

pub fn print_timings(timings: &[Timing]) {
    println!("{:<16} {:>10}", "pass", "GPU ms");
    for t in timings {
        println!("{:<16} {:>10.3}", t.pass, t.ms);
    }
}

/// The scene, image size and voxelization method (shared by `render` and `view`).
#[derive(Args)]
pub struct SceneArgs {
    /// Scene file (.toml), mesh (.obj) or glTF 2.0 (.gltf, .glb); default: the embedded Cornell box.
    pub scene: Option<PathBuf>,
    #[arg(long)]
    pub width: Option<u32>,
    #[arg(long)]
    pub height: Option<u32>,
    #[command(flatten)]
    pub method: MethodArgs,
    /// Voxelize a cube of this edge (world units) around the camera instead of the whole scene.
    #[arg(long, value_name = "EXTENT")]
    pub follow: Option<f32>,
    /// With --follow: move the volume continuously instead of in whole voxels.
    #[arg(long, hide = true)]
    pub no_snap: bool,
    #[command(flatten)]
    pub warp: WarpArgs,
    /// Clipmap cascades around the camera: LEVELS nested cubes of --res voxels each, each twice
    /// the extent of the one inside it and snapped to its own voxel (1..=8).
    #[arg(long, value_name = "LEVELS", value_parser = clap::value_parser!(u32).range(1..=8))]
    pub clipmap: Option<u32>,
    /// With --clipmap: the finest level's edge (world units); default: the coarsest level holds
    /// the whole scene around the camera.
    #[arg(long, value_name = "EXTENT", value_parser = clip_extent, requires = "clipmap")]
    pub clip_extent: Option<f32>,
    /// With --injection texels: shadow-map texels injection reads across a voxel (0: every texel
    /// of the map).
    #[arg(long, value_name = "TEXELS", default_value_t = vct::config::INJECT_TEXELS_PER_VOXEL, value_parser = inject_texels, hide = true)]
    pub inject_texels: f32,
    /// Quality preset, a point of the report's speed-against-accuracy chart: high (every pixel
    /// traces the whole cone set), default (the set split among 2×2 traced pixels, a quarter of
    /// the trace; `render` traces at most half a voxel apart and upsamples), draft (`render`: the
    /// traced pixels twice as far apart). Flags given beside it override it.
    #[arg(long, default_value = "default")]
    pub quality: vct::render::Quality,
    /// Trace the diffuse cones at one pixel in 1, 4, 16 or 64 (1|2|4|8), upsampled edge-aware on the
    /// G-buffer's depth and normal (deferred tracing; the specular cone too, see --gi-specular).
    /// Default: for `render` the preset's (--quality: traced pixels at most half a voxel apart), 8
    /// for `view`.
    #[arg(long)]
    pub gi_scale: Option<u32>,
    /// Accumulate those reduced-resolution cones over frames in screen space: the traced pixel
    /// moves through each block, the history follows the camera and is rejected where the
    /// surface changed; a still view becomes full-resolution tracing after gi-scale² frames
    /// (needs --gi-scale 2, 4 or 8). Default: off for `render` (one frame has no history; give
    /// --frames), on for `view`.
    #[arg(long, value_enum)]
    pub gi_accumulate: Option<OnOff>,
    /// With --gi-scale 2, 4 or 8: trace the specular cone with the diffuse cones, upsampled and
    /// accumulated alike (reduced), or at every pixel (full).
    #[arg(long, value_enum, default_value = "reduced", hide = true)]
    pub gi_specular: SpecularArg,
    /// Mip filtering over the occupied texels of each level, or over every texel (dense).
    #[arg(long, value_enum, default_value = "occupied", hide = true)]
    pub work: WorkArg,
    /// Cone start offset along the normal, in voxels (0..=16; overrides the scene's gi.bias;
    /// too small lets a lit surface light itself).
    #[arg(long, value_name = "VOXELS", value_parser = cone_bias, hide = true)]
    pub cone_bias: Option<f32>,
    /// Temporal blend factor: this frame's weight against the reprojected previous frames
    /// (0.01..=1, 1 = off; overrides the scene's gi.temporal).
    #[arg(long, value_name = "FACTOR", value_parser = temporal, hide = true)]
    pub temporal: Option<f32>,
    /// Radiance mip filtering: the thesis' isotropic 8-child average, or six directional chains
    /// (overrides the scene's gi.filter).
    #[arg(long, value_enum, hide = true)]
    pub filter: Option<FilterArg>,
    /// Light bounces, 1..=8: each beyond the first adds a voxel-space gather (overrides gi.bounces).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=8))]
    pub bounces: Option<u32>,
    /// Diffuse cone set: thesis5|thesis5-cells|crassin6|fib8|fib16|fib32 (overrides gi.cones).
    #[arg(long, hide = true)]
    pub cones: Option<vct::scene::file::ConeSet>,
    /// Turn the diffuse cone set about the normal by a different angle at each pixel, resolved
    /// over 3×3 pixels (on|off; overrides gi.turn_cones, on by default).
    #[arg(long, value_enum, hide = true)]
    pub turn_cones: Option<OnOff>,
    /// Split the turned cone set among each 2×2 block of pixels, each tracing a quarter of it,
    /// resolved per quarter over 3×3 pixels (on|off; overrides gi.split_cones).
    #[arg(long, value_enum, hide = true)]
    pub split_cones: Option<OnOff>,
    /// How injection finds the lit voxels: texels (each shadow-map texel finds its voxel; Freed
    /// 2018 Algorithm 2) or voxels (each occupied voxel first met from the light looks itself up
    /// in the shadow maps: the cost follows the voxels; a warped grid injects from the texels)
    /// (overrides gi.injection).
    #[arg(long, hide = true)]
    pub injection: Option<vct::scene::file::Injection>,
}

pub fn float_in(text: &str, lo: f32, hi: f32) -> std::result::Result<f32, String> {
    let v: f32 = text.parse().map_err(|e| format!("{e}"))?;
    if v.is_finite() && (lo..=hi).contains(&v) {
        Ok(v)
    } else {
        Err(format!("must be in {lo}..={hi}"))
    }
}

pub fn warp_slope(text: &str) -> std::result::Result<f32, String> {
    float_in(text, 0.05, 1.0)
}

pub fn perspective_ratio(text: &str) -> std::result::Result<f32, String> {
    float_in(text, 0.05, 0.95)
}

/// How the grid's texels spread over its box.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum WarpArg {
    None,
    Function,
    Perspective,
}

#[derive(clap::Args, Debug, Clone)]
pub struct WarpArgs {
    /// Spread the texels unevenly: `function` warps each axis by the thesis' cubic (Freed 2018
    /// §4.6.1), finest at the camera (1.5 - s/2 texels to an even grid's voxel) and coarsest at
    /// the grid's faces (s, --warp-slope); `perspective` divides the camera's frustum (§4.6.2,
    /// made projective), near texels s times as wide as far ones; `none`, even texels.
    #[arg(long, value_enum, default_value = "none")]
    pub warp: WarpArg,
    /// With --warp function: the slope at the grid's faces, 0.05..=1 (the thesis' 0.25); with
    /// --warp perspective, the near texels' width over the far ones', 0.05..=0.95.
    #[arg(long, value_name = "SLOPE", default_value_t = vct::voxel::warp::THESIS_END_SLOPE, value_parser = warp_slope)]
    pub warp_slope: f32,
}

impl WarpArgs {
    /// The warp, if the grid is warped.
    pub fn choice(&self) -> Option<vct::voxel::warp::WarpChoice> {
        use vct::voxel::warp::WarpChoice;
        match self.warp {
            WarpArg::None => None,
            WarpArg::Function => Some(WarpChoice::Function(self.warp_slope)),
            WarpArg::Perspective => Some(WarpChoice::Perspective(self.warp_slope)),
        }
    }
}

/// `LEVELSxRES`: clipmap levels and their voxels along each axis.
pub fn clip_layout(text: &str) -> std::result::Result<(u32, u32), String> {
    let bad = || format!("'{text}' is not LEVELSxRES (e.g. 4x64)");
    let (l, n) = text.split_once('x').ok_or_else(bad)?;
    Ok((l.parse().map_err(|_| bad())?, n.parse().map_err(|_| bad())?))
}

pub fn clip_extent(text: &str) -> std::result::Result<f32, String> {
    float_in(text, 1e-4, 1e6)
}

pub fn cone_bias(text: &str) -> std::result::Result<f32, String> {
    float_in(text, 0.0, 16.0)
}

pub fn temporal(text: &str) -> std::result::Result<f32, String> {
    float_in(text, 0.01, 1.0)
}

pub fn orbit_degrees(text: &str) -> std::result::Result<f32, String> {
    float_in(text, -180.0, 180.0)
}

impl SceneArgs {
    pub fn follow(&self) -> Option<vct::render::Follow> {
        self.follow.map(|extent| vct::render::Follow { extent, snap: !self.no_snap })
    }

    /// The warp, if the grid is warped.
    pub fn warp(&self) -> Option<vct::voxel::warp::WarpChoice> {
        self.warp.choice()
    }

    pub fn clipmap(&self) -> Option<vct::render::ClipOptions> {
        self.clipmap.map(|levels| vct::render::ClipOptions { levels, extent: self.clip_extent })
    }

    /// The render options these arguments set, shared by `render` and `view`; the GI scale and
    /// its accumulation are left to each (their defaults differ).
    pub fn render_options(&self) -> Result<vct::render::RenderOptions> {
        Ok(vct::render::RenderOptions {
            method: self.method.method()?,
            resolution: self.method.res()?,
            dims: self.method.dims,
            follow: self.follow(),
            warp: self.warp(),
            clipmap: self.clipmap(),
            inject_texels: self.inject_texels,
            work: self.work.work(),
            storage: self.method.storage(),
            bricks: self.method.bricks,
            reduced_specular: self.gi_specular == SpecularArg::Reduced,
            ..Default::default()
        })
    }

    pub fn load(&self) -> Result<Scene> {
        let mut scene = load_scene(self.scene.as_deref())?;
        scene.set_size(self.width, self.height)?;
        if let Some(b) = self.cone_bias {
            scene.settings.gi.bias = b;
        }
        if let Some(t) = self.temporal {
            scene.settings.gi.temporal = t;
        }
        scene.settings.gi = self.quality.gi(&scene.settings.gi);
        let gi = &mut scene.settings.gi;
        if let Some(f) = self.filter {
            gi.filter = match f {
                FilterArg::Iso => vct::scene::file::Filter::Iso,
                FilterArg::Aniso => vct::scene::file::Filter::Aniso,
            };
        }
        if let Some(b) = self.bounces {
            gi.bounces = b;
        }
        if let Some(c) = self.cones {
            gi.cones = c;
        }
        if let Some(t) = self.turn_cones {
            gi.turn_cones = t == OnOff::On;
        }
        if let Some(t) = self.split_cones {
            gi.split_cones = t == OnOff::On;
        }
        if let Some(i) = self.injection {
            gi.injection = i;
        }
        Ok(scene)
    }
}

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum OnOff {
    On,
    Off,
}

fn inject_texels(s: &str) -> std::result::Result<f32, String> {
    match s.parse::<f32>() {
        Ok(v) if (0.0..=64.0).contains(&v) => Ok(v),
        _ => Err(format!("expected a number of texels in 0..=64, got '{s}'")),
    }
}

pub fn parse_dims(s: &str) -> std::result::Result<glam::UVec3, String> {
    let v: Vec<u32> = s
        .split(',')
        .map(|p| p.trim().parse::<u32>().map_err(|_| format!("expected X,Y,Z (three whole numbers), got '{s}'")))
        .collect::<std::result::Result<_, _>>()?;
    match v[..] {
        [x, y, z] => Ok(glam::UVec3::new(x, y, z)),
        _ => Err(format!("expected X,Y,Z (three whole numbers), got '{s}'")),
    }
}

pub fn parse_size(s: &str) -> std::result::Result<(u32, u32), String> {
    let (w, h) = s.split_once('x').ok_or_else(|| format!("expected WxH, got '{s}'"))?;
    let parse = |v: &str| v.parse::<u32>().map_err(|_| format!("bad size '{s}'"));
    let (w, h) = (parse(w)?, parse(h)?);
    vct::scene::check_image_size(w, h).map_err(|e| e.to_string())?;
    Ok((w, h))
}

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum SpecularArg {
    Reduced,
    Full,
}

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum WorkArg {
    Occupied,
    Dense,
}

impl WorkArg {
    pub fn work(self) -> vct::render::Work {
        match self {
            WorkArg::Occupied => vct::render::Work::Occupied,
            WorkArg::Dense => vct::render::Work::Dense,
        }
    }
}

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum VoxelizerArg {
    Tess,
    Raster,
    Points,
}

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum PointSourceArg {
    Load,
    Gpu,
}

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum FilterArg {
    Iso,
    Aniso,
}

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum TracingArg {
    Forward,
    Deferred,
}

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum CoverageArg {
    Auto,
    Msaa,
    None,
    Hw,
    Conservative,
}

/// How to voxelize (shared by every command that voxelizes).
#[derive(Args)]
pub struct MethodArgs {
    /// Voxelization method (default: rasterized with conservative coverage, exact and the
    /// fastest; docs/design/voxelizers.md).
    #[arg(long, value_enum, default_value = "raster")]
    pub voxelizer: VoxelizerArg,
    /// Rasterized path: coverage by 4x MSAA, none (pixel centres), conservative (the triangle
    /// grown by half a pixel in the geometry shader), hardware (VK_EXT_conservative_rasterization),
    /// or auto: exact, by the hardware where the device offers it, else the geometry shader.
    #[arg(long, value_enum, default_value = "auto", hide = true)]
    pub coverage: CoverageArg,
    /// Voxels along the scene's longest axis (a power of two, 16..512); the other axes are
    /// fitted to the scene's shape. Default: the scene's. `vct render` also takes `auto`: the
    /// cheapest grid that meets --target-flip against the path-traced reference, or without a
    /// target one from the scene's size.
    #[arg(long, value_parser = parse_res)]
    pub res: Option<ResArg>,
    /// Voxels along x, y and z (powers of two, 16..512), e.g. 256,128,128 (256,256,256: the
    /// bounding cube); overrides --res.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_dims)]
    pub dims: Option<glam::UVec3>,
    /// Tessellation path: multiplier on the thesis' tessellation levels.
    #[arg(long, default_value_t = vct::voxel::DEFAULT_LEVEL_SCALE, hide = true)]
    pub level_scale: f32,
    /// Tessellation path: do not split triangles past the level limit (shows the holes).
    #[arg(long, hide = true)]
    pub no_subdivide: bool,
    /// Tessellation path: let levels below 1 drop the triangle (shows the lost small triangles).
    #[arg(long, hide = true)]
    pub no_min_level: bool,
    /// Tessellation path: each evaluation point also fills the empty voxels around its own
    /// that the triangle meets (on|off; default: vct's).
    #[arg(long, value_enum, hide = true)]
    pub neighbours: Option<OnOff>,
    /// Point path: sample points per voxel area on each triangle (at least one a triangle).
    #[arg(long, default_value_t = vct::voxel::points::DEFAULT_POINT_DENSITY, hide = true)]
    pub point_density: f32,
    /// Point path: fill the voxels the points left empty where the camera looks, from the
    /// pixels it sees (Mavridis & Papaioannou 2011 §3.2; on|off).
    #[arg(long, value_enum, default_value = "on", hide = true)]
    pub refine: OnOff,
    /// Point path: scatter the points once when the volume is built (load), or generate them
    /// each frame in the vertex shader (gpu).
    #[arg(long, value_enum, default_value = "load", hide = true)]
    pub point_source: PointSourceArg,
    /// Rasterized path: framebuffer resolution over voxel resolution.
    #[arg(long, default_value_t = 1.0, hide = true)]
    pub viewport_scale: f32,
    /// Rasterized path: write only the voxel at each pixel centre's depth (the thesis' method).
    #[arg(long, hide = true)]
    pub no_depth_span: bool,
    /// Where the per-voxel textures live: a page table and a pool of the occupied 2³ bricks
    /// (sparse), the whole grid (dense), or the whole grid with memory bound only where a
    /// census found bricks (resident: Vulkan sparse residency, where the device offers it).
    /// auto: resident where offered, else sparse; dense for --follow (docs/design/storage.md).
    #[arg(long, value_enum, default_value = "auto")]
    pub storage: StorageArg,
    /// Sparse storage: brick slots in the pool (default: as many as a census of the scene
    /// counts; fewer is an error naming both counts).
    #[arg(long, value_name = "BRICKS", value_parser = clap::value_parser!(u32).range(1..=1 << 26), hide = true)]
    pub bricks: Option<u32>,
}

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum StorageArg {
    Auto,
    Sparse,
    Dense,
    Resident,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ResArg {
    Voxels(u32),
    Auto,
}

fn parse_res(s: &str) -> std::result::Result<ResArg, String> {
    if s == "auto" {
        return Ok(ResArg::Auto);
    }
    s.parse().map(ResArg::Voxels).map_err(|_| format!("'{s}' is neither a voxel count nor 'auto'"))
}

impl MethodArgs {
    /// The voxel count of --res (`auto` is for `vct render`).
    pub fn res(&self) -> Result<Option<u32>> {
        match self.res {
            None => Ok(None),
            Some(ResArg::Voxels(n)) => Ok(Some(n)),
            Some(ResArg::Auto) => bail!("--res auto is for vct render"),
        }
    }

    pub fn storage(&self) -> Storage {
        match self.storage {
            StorageArg::Auto => Storage::Auto,
            StorageArg::Sparse => Storage::Sparse,
            StorageArg::Dense => Storage::Dense,
            StorageArg::Resident => Storage::Resident,
        }
    }

    pub fn method(&self) -> Result<VoxelizeMethod> {
        if !(self.level_scale.is_finite() && self.level_scale > 0.0 && self.level_scale <= 16.0) {
            bail!("--level-scale must be in (0, 16], got {}", self.level_scale);
        }
        if !(self.viewport_scale.is_finite() && (0.125..=8.0).contains(&self.viewport_scale)) {
            bail!("--viewport-scale must be in 0.125..=8, got {}", self.viewport_scale);
        }
        Ok(match self.voxelizer {
            VoxelizerArg::Tess => VoxelizeMethod::Tess {
                level_scale: self.level_scale,
                subdivide: !self.no_subdivide,
                min_level: !self.no_min_level,
                neighbours: self.neighbours.map_or(vct::voxel::DEFAULT_NEIGHBOURS, |n| n == OnOff::On),
            },
            VoxelizerArg::Raster => VoxelizeMethod::Raster {
                coverage: match self.coverage {
                    CoverageArg::Auto => Coverage::Auto,
                    CoverageArg::Msaa => Coverage::Msaa,
                    CoverageArg::None => Coverage::None,
                    CoverageArg::Hw => Coverage::Hardware,
                    CoverageArg::Conservative => Coverage::Conservative,
                },
                viewport_scale: self.viewport_scale,
                depth_span: !self.no_depth_span,
            },
            VoxelizerArg::Points => {
                if !(self.point_density.is_finite() && self.point_density > 0.0 && self.point_density <= 1024.0) {
                    bail!("--point-density must be in (0, 1024] points per voxel area, got {}", self.point_density);
                }
                VoxelizeMethod::Points {
                    density: self.point_density,
                    source: match self.point_source {
                        PointSourceArg::Load => vct::voxel::points::PointSource::Load,
                        PointSourceArg::Gpu => vct::voxel::points::PointSource::Gpu,
                    },
                    refine: self.refine == OnOff::On,
                }
            }
        })
    }
}

#[derive(Args)]
pub struct GpuArgs {
    /// Use the first device whose name contains this text.
    #[arg(long)]
    pub device: Option<String>,
    /// Enable the Khronos validation layer (also: VCT_VALIDATION=1; VCT_VALIDATION=sync adds
    /// synchronization validation); messages fail the run.
    #[arg(long)]
    pub validation: bool,
}
