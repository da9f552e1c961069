//! `vct bench`'s arguments (clap derive): the voxelizer sweep, the stability regimes, cost
//! against occupancy and the accuracy harness against the path tracer, with their options.

use std::path::PathBuf;

use clap::Args;

use crate::common::*;

#[derive(Args)]
pub struct BenchArgs {
    /// Run the standard suite (voxelizers, indirect light against the path tracer, stability,
    /// hostile geometry) and write the report into DIR: README.md (one table per question,
    /// stamped with machine, driver and commit), index.html (every chart inline, offline) and
    /// the data under DIR/data/. With --quick, the CI variant (a few minutes on lavapipe).
    #[arg(long, value_name = "DIR", conflicts_with_all = ["accuracy", "stability", "occupancy", "replot"])]
    pub report: Option<PathBuf>,
    /// With --report: write README.md and index.html again from the data already in DIR,
    /// without measuring.
    #[arg(long, requires = "report")]
    pub rewrite: bool,
    /// With --report: import a GPU run's data (the folder scripts/device-bench.sh returns) into
    /// DIR/gpu/, its own section of the report.
    #[arg(long = "gpu", value_name = "RUN", requires = "report")]
    pub gpu_run: Option<PathBuf>,
    /// With --report: import the side-by-side timings of this tree against the landed main
    /// (the JSON scripts/speed-vs-main.sh writes) into DIR/data/speed/, the report's speed section.
    #[arg(long, value_name = "RUNS", requires = "report")]
    pub speed: Option<PathBuf>,
    /// Extra scenes (.toml, .obj, .gltf or .glb) besides the embedded Cornell box.
    pub scenes: Vec<PathBuf>,
    /// A short run for CI: Cornell at 32³ and 64³, 128×128, few frames, a 16-spp reference.
    #[arg(long)]
    pub quick: bool,
    /// Redraw the charts and summary of an earlier run from DIR/results.json.
    #[arg(long, value_name = "DIR")]
    pub replot: Option<PathBuf>,
    /// An earlier run's results.json, drawn beside this run's in the tess/raster ratio chart
    /// ("before").
    #[arg(long, value_name = "RESULTS.json", hide = true)]
    pub baseline: Option<PathBuf>,
    /// Measure where each method fails (tessellation limit, raster cracks, small triangles,
    /// light leaking, temporal flicker, self-illumination) instead of the speed/accuracy sweep.
    #[arg(long)]
    pub stability: bool,
    /// Cost against occupancy: inject + filter time on one grid (--res, default 128) for scenes
    /// that occupy more and more of it, over the occupied texels and over every texel.
    #[arg(long)]
    pub occupancy: bool,
    /// Output folder; default bench/<date>-<device>.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Timed frames per configuration (after the warm-up).
    #[arg(long)]
    pub frames: Option<u32>,
    /// Reference samples per pixel.
    #[arg(long)]
    pub spp: Option<u32>,
    /// Voxel resolutions, e.g. 64,128,256.
    #[arg(long, value_delimiter = ',')]
    pub res: Option<Vec<u32>>,
    /// Also run the default voxelizer with the other storage modes the device offers (dense, the
    /// brick pool, residency), and chart memory and frame time against FLIP per mode (on|off).
    #[arg(long, value_enum, default_value = "on", hide = true)]
    pub compare_storage: OnOff,
    /// Indirect light against the path tracer instead of the voxelizer sweep: FLIP, mean radiance
    /// and per-region indirect light of the default model (the embedded Cornell box under its spot
    /// and its directional light, plus the scenes given).
    #[arg(long)]
    pub accuracy: bool,
    /// With --accuracy: every variant of the GI model study, not only the scene's own model.
    #[arg(long, requires = "accuracy")]
    pub study: bool,
    /// With --accuracy: each scene also on warped grids of the same voxels, by the thesis'
    /// function (Freed 2018 §4.6.1) and by perspective (§4.6.2), beside its fitted grid
    /// (docs/design/warping.md).
    #[arg(long, requires = "accuracy", conflicts_with = "study")]
    pub layouts: bool,
    /// With --layouts: the warp's end slopes, e.g. 0.75,0.5,0.25 (each 0.05..=1; default: the
    /// thesis' 0.25).
    #[arg(long, requires = "layouts", value_delimiter = ',', value_parser = warp_slope, hide = true)]
    pub warp_slopes: Option<Vec<f32>>,
    /// With --layouts: the perspective warp's near-over-far texel widths, e.g. 0.5,0.25 (each
    /// 0.05..=0.95; default: 0.25).
    #[arg(long, requires = "layouts", value_delimiter = ',', value_parser = perspective_ratio, hide = true)]
    pub perspective_ratios: Option<Vec<f32>>,
    /// With --layouts: clipmaps to measure beside the fitted grid, each LEVELSxRES, e.g. 2x64,4x64
    /// (none by default).
    #[arg(long, requires = "layouts", value_delimiter = ',', value_parser = clip_layout)]
    pub clipmaps: Option<Vec<(u32, u32)>>,
    /// With --layouts: also slide each variant's camera sideways 3 cm a frame for this many
    /// frames and report the FLIP between adjacent frames (level seams, voxels regrouping;
    /// pan.csv).
    #[arg(long, requires = "layouts", value_name = "FRAMES", value_parser = clap::value_parser!(u32).range(2..=240), hide = true)]
    pub pan_frames: Option<u32>,
    /// With --accuracy: also measure each fitted grid and clipmap on this many placements of its
    /// lattice in all (its own and others moved by under a voxel; a clipmap's by under a voxel of
    /// its coarsest level), and report the spread of FLIP, mean radiance and each region's
    /// ratio: how far the figures depend on where voxel boundaries fall. Warped grids are
    /// measured once.
    #[arg(long, requires = "accuracy", value_name = "K", value_parser = clap::value_parser!(u32).range(2..=64), hide = true)]
    pub lattices: Option<u32>,
    /// With --accuracy: also split each region's indirect light among the diffuse cones of the
    /// scene's model, the renderer's (each cone drawn alone) beside the path tracer's light
    /// through the same cells of the hemisphere (per-cone.csv; docs/design/cones.md).
    #[arg(long, requires = "accuracy", conflicts_with_all = ["layouts", "study"], hide = true)]
    pub per_cone: bool,
    /// With --accuracy: also measure each variant's flat-wall pattern, its frame's RMS departure
    /// from the mean of 16 frames with the cone set turned further (a share of the regions' mean).
    #[arg(long, requires = "accuracy", hide = true)]
    pub pattern: bool,
    /// With --study: only the variants whose name contains this text.
    #[arg(long, requires = "study", value_name = "TEXT", hide = true)]
    pub only: Option<String>,
    /// With --accuracy: light bounces of the renderer (overrides the scenes' gi.bounces).
    #[arg(long, requires = "accuracy", value_parser = clap::value_parser!(u32).range(1..=8))]
    pub bounces: Option<u32>,
    /// Only the scenes given, without the embedded Cornell box (and, with --accuracy, its
    /// directional variant).
    #[arg(long, requires = "scenes")]
    pub given_only: bool,
    /// With --accuracy: bounces of the path-traced reference (default: the renderer's).
    #[arg(long, requires = "accuracy", value_parser = clap::value_parser!(u32).range(0..=64), hide = true)]
    pub ref_bounces: Option<u32>,
    #[command(flatten)]
    pub gpu: GpuArgs,
}
