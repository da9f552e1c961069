//! `vct bench --accuracy`: indirect light against the path tracer. For each scene it traces
//! (and caches) a reference with as many bounces as the renderer's frame and a direct-light-only
//! reference, splits the image into regions from a G-buffer of the reference's own primary hits
//! (material, normal and plane: one region per wall, box face or floor), and for every model
//! variant measures the frame's GPU time beside its accuracy — FLIP (over the image, and over
//! thirds of it by distance from the camera), the image's mean radiance over the reference's, and
//! each region's indirect light (full minus direct, on both sides) over the reference's. The
//! study's variants are the model choices the docs chart. `report` writes what it measured.

use crate::voxel::warp::WarpChoice;
use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

use glam::Vec3;
use serde::{Deserialize, Serialize};

use super::reference_cached;
use crate::error::Result;
use crate::gpu::{timer::median, Context, Timing};
use crate::reference::metrics;
use crate::reference::pathtrace::{PathTracer, PrimaryHit};
use crate::render::{Quality, RenderOptions, Renderer, View};
use crate::scene::file::{ConeSet, Filter, GiFile, Injection, LevelRule};
use crate::scene::Scene;
use crate::voxel::{Coverage, VoxelizeMethod};

pub mod pattern;
pub mod per_cone;
mod report;
pub mod trace_cost;
pub use report::{summary, write};

const LUMA: Vec3 = Vec3::new(0.2126, 0.7152, 0.0722);

/// Image regions: pixels grouped by what they see.
pub struct RegionMap {
    pub labels: Vec<String>,
    /// The region of each pixel (None: background, a region too small to judge, or a pixel on
    /// a region's border, where the renderer's and the reference's edges may differ).
    pub of_pixel: Vec<Option<usize>>,
}

/// Regions of a frame from its primary hits: the same material, normal (to about 4°) and
/// plane (to 1% of the scene's size); the border pixels of each are dropped, and regions under
/// `min_share` of the image are not judged.
pub fn regions(scene: &Scene, hits: &[Option<PrimaryHit>], min_share: f32) -> RegionMap {
    let (w, h) = (scene.camera.width as usize, scene.camera.height as usize);
    let size = scene.mesh.bounds.size().length().max(1e-6);
    let key = |hit: &PrimaryHit| {
        let n = hit.normal;
        let q = (n * 16.0).round();
        (hit.material, q.x as i32, q.y as i32, q.z as i32, (n.dot(hit.position) / (0.01 * size)).round() as i64)
    };
    let keys: Vec<_> = hits.iter().map(|h| h.as_ref().map(key)).collect();
    let mut index: HashMap<_, usize> = HashMap::new();
    let mut members: Vec<Vec<usize>> = Vec::new();
    let mut first_hit: Vec<PrimaryHit> = Vec::new();
    for y in 1..h.saturating_sub(1) {
        for x in 1..w.saturating_sub(1) {
            let i = y * w + x;
            let Some(k) = keys[i] else { continue };
            if [i - 1, i + 1, i - w, i + w].iter().any(|&j| keys[j] != Some(k)) {
                continue;
            }
            let r = *index.entry(k).or_insert_with(|| {
                members.push(Vec::new());
                first_hit.push(hits[i].expect("a key comes from a hit"));
                members.len() - 1
            });
            members[r].push(i);
        }
    }
    let min = ((w * h) as f32 * min_share).max(16.0) as usize;
    let mut order: Vec<usize> = (0..members.len()).filter(|&r| members[r].len() >= min).collect();
    order.sort_by_key(|&r| std::cmp::Reverse(members[r].len()));
    let mut of_pixel = vec![None; w * h];
    let mut labels = Vec::new();
    for (new, &r) in order.iter().enumerate() {
        for &i in &members[r] {
            of_pixel[i] = Some(new);
        }
        let hit = first_hit[r];
        let name = scene.materials.get(hit.material as usize).map(|m| m.name.as_str()).unwrap_or("?");
        let (face, axis) = facing(hit.normal);
        labels.push(format!("{name} {face} at {}={:.2}", ["x", "y", "z"][axis], hit.position[axis]));
    }
    RegionMap { labels, of_pixel }
}

/// "+y", "-x", ... for the axis a normal most nearly follows (a "~" where it is tilted), and
/// that axis.
fn facing(n: Vec3) -> (String, usize) {
    let a = n.abs();
    let axis = if a.x >= a.y && a.x >= a.z {
        0
    } else if a.y >= a.z {
        1
    } else {
        2
    };
    let v = n[axis];
    let name = ["x", "y", "z"][axis];
    (format!("{}{name}{}", if v >= 0.0 { "+" } else { "-" }, if v.abs() < 0.99 { "~" } else { "" }), axis)
}

/// Mean linear radiance of each region.
pub fn region_means(map: &RegionMap, image: &[Vec3]) -> Vec<Vec3> {
    let mut sum = vec![(Vec3::ZERO, 0usize); map.labels.len()];
    for (p, r) in image.iter().zip(&map.of_pixel) {
        if let Some(r) = r {
            sum[*r].0 += *p;
            sum[*r].1 += 1;
        }
    }
    sum.into_iter().map(|(s, n)| s / n.max(1) as f32).collect()
}

/// A scene and the references it is judged against.
pub struct Judged {
    pub name: String,
    pub scene: Scene,
    /// Path-traced with the renderer's bounces.
    pub full: Vec<Vec3>,
    pub full_rgb: Vec<u8>,
    /// Path-traced direct light only (plus what emitters show the camera directly, and the
    /// reflected light of area-light emitters).
    pub direct: Vec<Vec3>,
    pub regions: RegionMap,
    /// Each pixel's third of the surface the camera sees, by distance (`distance_bands`).
    pub distance_band: Vec<Option<u8>>,
    /// The distances (m) that part the thirds.
    pub distance_edges: [f32; 2],
    pub noise: f32,
    pub bounces: u32,
}

/// Splits the pixels that see a surface into thirds by its distance from the camera, equal in
/// pixels: 0 near, 1 middle, 2 far (None: no surface). Returns each pixel's third and the two
/// distances that part them. A camera among a large scene's near detail and far walls
/// is judged in each third: a layout that spends its voxels
/// near the camera should gain in the near third and may pay in the far one.
pub fn distance_bands(distance: &[Option<f32>]) -> (Vec<Option<u8>>, [f32; 2]) {
    let mut sorted: Vec<f32> = distance.iter().flatten().copied().collect();
    sorted.sort_by(f32::total_cmp);
    let at = |q: usize| sorted.get(q * sorted.len() / 3).copied().unwrap_or(f32::INFINITY);
    let edges = [at(1), at(2)];
    let band = distance.iter().map(|d| d.map(|d| (d >= edges[0]) as u8 + (d >= edges[1]) as u8)).collect();
    (band, edges)
}

impl Judged {
    pub fn new(
        name: &str,
        scene: Scene,
        bounces: u32,
        spp: u32,
        cache: &Path,
        progress: &dyn Fn(&str),
    ) -> Result<Self> {
        let (full, info) = reference_cached(&scene, name, bounces, false, spp, cache, progress)?;
        // Direct light as the renderer counts it: an area light's reflection is direct.
        let area = scene.lights.iter().any(|l| l.is_mesh_emitter());
        let (direct, _) = reference_cached(&scene, name, 0, area, spp.min(64), cache, progress)?;
        let hits = PathTracer::new(&scene).primary_hits();
        let regions = regions(&scene, &hits, 0.004);
        let distance: Vec<Option<f32>> =
            hits.iter().map(|h| h.as_ref().map(|h| h.position.distance(scene.camera.eye))).collect();
        let (distance_band, distance_edges) = distance_bands(&distance);
        Ok(Judged {
            name: name.into(),
            full_rgb: metrics::tonemap(&full),
            full,
            direct,
            regions,
            distance_band,
            distance_edges,
            noise: info.relative_noise,
            scene,
            bounces,
        })
    }
}

/// One region's indirect light, renderer against reference.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct RegionRow {
    pub region: String,
    pub pixels: usize,
    pub reference: [f32; 3],
    pub vct: [f32; 3],
    /// Luminance ratio vct / reference.
    pub ratio: f32,
    /// Whether the ratio is judged (the worst region, the lattices' range): the region's
    /// reference indirect light is at least `JUDGED_SHARE` of the brightest region's. A region
    /// the reference leaves nearly dark (a face seen edge-on, a recess no bounce reaches) has a
    /// ratio of noise over nearly nothing: one of Sponza's read 10⁶.
    #[serde(default)]
    pub judged: bool,
}

/// The least share of the brightest region's indirect light at which a region's ratio is
/// judged (`RegionRow::judged`). Every region of both Cornell boxes holds 10% or more; the
/// regions it leaves out hold under 0.3%.
pub const JUDGED_SHARE: f32 = 0.01;

/// The judged regions' (`RegionRow::judged`) indirect-light error in one figure: the mean of
/// |ln(vct / reference)| over their pixels, so that a region at half and one at twice the
/// reference's light count alike, and a large region (Sponza's floor) counts as many times as it
/// has pixels. 0 where every region matches; 0.1 is about ±10% throughout. The worst region alone
/// (in the CSV) moves with one small face; this follows every region, for comparing variants
/// region by region. None where no region is judged.
pub fn region_log_error(regions: &[RegionRow]) -> Option<f32> {
    let judged = || regions.iter().filter(|g| g.judged && g.ratio > 0.0);
    let pixels: usize = judged().map(|g| g.pixels).sum();
    (pixels > 0).then(|| judged().map(|g| g.pixels as f32 * g.ratio.ln().abs()).sum::<f32>() / pixels as f32)
}

/// `region_log_error` as the summary and the console print it ("–" where no region is judged).
pub fn region_log_error_text(regions: &[RegionRow]) -> String {
    region_log_error(regions).map_or("–".to_string(), |e| format!("{e:.3}"))
}

/// One variant on one scene.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct AccuracyRow {
    pub scene: String,
    pub variant: String,
    pub resolution: u32,
    pub bounces: u32,
    pub frame_ms: f64,
    /// Each pass's median GPU time (ms) over the frames timed.
    #[serde(default)]
    pub passes: Vec<Timing>,
    /// The volume's memory (voxel textures, radiance, lists), MiB.
    pub memory_mib: f64,
    pub flip: f32,
    /// FLIP of the direct-light-only frame against the same reference.
    pub flip_direct_only: f32,
    /// Mean radiance (luminance) over the reference's.
    pub mean_ratio: f32,
    /// Mean FLIP over each third of the surface pixels by distance from the camera (near, middle,
    /// far; `Judged::distance_band`).
    #[serde(default)]
    pub flip_by_distance: [f32; 3],
    /// The distances (m) that part the thirds.
    #[serde(default)]
    pub distance_edges: [f32; 2],
    pub regions: Vec<RegionRow>,
    pub reference_noise: f32,
    /// The same variant on other placements of the lattice (`measure_lattices`).
    #[serde(default)]
    pub lattices: Option<LatticeSpread>,
    /// The flat-wall pattern: the frame's RMS departure from the converged frame of the same
    /// settings over the regions, a share of their mean ([`pattern::measure`]; where measured).
    #[serde(default)]
    pub pattern: Option<f32>,
    #[serde(skip)]
    pub flip_map: Vec<u8>,
    /// The reference's indirect light beside the renderer's (RGB8, twice as wide), tone-mapped
    /// alike after scaling by four so that dim light shows.
    #[serde(skip)]
    pub indirect_pair: Vec<u8>,
    #[serde(skip)]
    pub width: u32,
    #[serde(skip)]
    pub height: u32,
}

/// How a row's figures move when its lattice is moved by less than a voxel (a fitted grid's, or
/// a clipmap's by less than a voxel of its coarsest level, `Clipmap::on_lattice`): the
/// least, the mean and the most over the placements measured, the row's own among them.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct LatticeSpread {
    pub placements: u32,
    pub flip: [f32; 3],
    pub mean_ratio: [f32; 3],
    /// Each region's indirect-light ratio, as `row.regions`.
    pub region_ratio: Vec<[f32; 3]>,
}

fn spread(values: impl Iterator<Item = f32>) -> [f32; 3] {
    let (mut lo, mut hi, mut sum, mut n) = (f32::INFINITY, f32::NEG_INFINITY, 0.0, 0.0);
    for v in values {
        (lo, hi, sum, n) = (lo.min(v), hi.max(v), sum + v, n + 1.0);
    }
    [lo, sum / f32::max(n, 1.0), hi]
}

/// The `j`-th lattice placement, in voxels: 0 for the first (the grid's own), then the
/// additive recurrence of the plastic number in three dimensions (Roberts 2018's R3 sequence),
/// which spreads any number of placements evenly over the cube of shifts within ±0.5.
pub fn lattice_shift(j: u32) -> Vec3 {
    if j == 0 {
        return Vec3::ZERO;
    }
    // The generalized golden ratio of three dimensions: the positive root of x⁴ = x + 1.
    const G: f64 = 1.220_744_084_605_759_5;
    let r = |p: i32| ((j as f64 / G.powi(p)).fract() - 0.5) as f32;
    Vec3::new(r(1), r(2), r(3))
}

/// Measures `variant` (a fitted grid or a clipmap) again on `placements - 1` more placements of its lattice
/// and puts the spread of its figures, its own included, into `row`.
pub fn measure_lattices(
    ctx: &Arc<Context>,
    j: &Judged,
    direct: &(Vec<Vec3>, Vec<u8>),
    variant: &Variant,
    resolution: u32,
    placements: u32,
    row: &mut AccuracyRow,
) -> Result<()> {
    let mut rows = Vec::new();
    for k in 1..placements {
        let moved = Variant { lattice: Some(lattice_shift(k)), ..variant.clone() };
        rows.push(measure(ctx, j, direct, &moved, resolution, 1)?);
    }
    let all = || std::iter::once(&*row).chain(rows.iter());
    row.lattices = Some(LatticeSpread {
        placements,
        flip: spread(all().map(|r| r.flip)),
        mean_ratio: spread(all().map(|r| r.mean_ratio)),
        region_ratio: (0..row.regions.len()).map(|i| spread(all().map(|r| r.regions[i].ratio))).collect(),
    });
    Ok(())
}

/// A named change to the GI model, or to how the volume spreads its voxels.
#[derive(Clone)]
pub struct Variant {
    pub name: String,
    pub gi: GiFile,
    /// Warp the grid (`RenderOptions::warp`): the same voxels, finest at the camera.
    pub warp: Option<WarpChoice>,
    /// Clipmap levels around the camera instead of the fitted grid (`RenderOptions::clipmap`),
    /// and their voxels along each axis.
    pub clipmap: Option<(u32, u32)>,
    /// The lattice moved by this many voxels (a clipmap's: of its coarsest level;
    /// `RenderOptions::lattice`).
    pub lattice: Option<Vec3>,
    /// The diffuse cones traced at one pixel in this squared (`RenderOptions::gi_scale`; None: 1,
    /// or the preset's).
    pub gi_scale: Option<u32>,
    /// The quality preset whose GI scale the frame takes for the scene and grid, as `vct render`
    /// does (`render::Quality::gi_scale`; None: `gi_scale`).
    pub quality: Option<Quality>,
}

impl Variant {
    /// The GI model `gi`, named `name`, on the scene's fitted grid.
    pub fn model(name: &str, gi: GiFile) -> Self {
        Variant { name: name.into(), gi, warp: None, clipmap: None, lattice: None, gi_scale: None, quality: None }
    }

    /// The scene's own model on its own grid, as `vct render` renders it by default.
    pub fn default_of(gi: &GiFile) -> Self {
        Variant { quality: Some(Quality::Default), ..Self::model("default", gi.clone()) }
    }

    /// The scene's own model as quality preset `q` sets it (`render::Quality`), named
    /// "quality NAME".
    pub fn preset(q: Quality, gi: &GiFile) -> Self {
        Variant { quality: Some(q), ..Self::model(&format!("quality {}", q.name()), q.gi(gi)) }
    }

    /// The scene's own model with the voxels warped by the thesis' function (Freed 2018 §4.6.1)
    /// with end slope `s`, at the same voxel count.
    pub fn warped(gi: &GiFile, s: f32) -> Self {
        Self::warped_by(gi, WarpChoice::Function(s))
    }

    /// The scene's own model with the voxels warped as `warp` says (the function, §4.6.1, or the
    /// perspective, §4.6.2), at the same voxel count.
    pub fn warped_by(gi: &GiFile, warp: WarpChoice) -> Self {
        Variant { warp: Some(warp), ..Self::model(&warp.label(), gi.clone()) }
    }

    /// `scene` with this variant's GI model, and the options that render it at `resolution`.
    pub fn setup(&self, scene: &Scene, resolution: u32) -> (Scene, RenderOptions) {
        let mut scene = scene.clone();
        scene.settings.gi = self.gi.clone();
        let mut options = RenderOptions {
            method: harness_method(),
            resolution: Some(self.clipmap.map_or(resolution, |(_, res)| res)),
            warp: self.warp,
            clipmap: self.clipmap.map(|(levels, _)| crate::render::ClipOptions { levels, extent: None }),
            lattice: self.lattice,
            gi_scale: match self.quality {
                Some(q) => q.gi_scale(&scene, resolution),
                None => self.gi_scale.unwrap_or(1),
            },
            ..Default::default()
        };
        if self.warp.is_some() || self.clipmap.is_some() {
            // A volume that follows the camera gets dense storage by default; this camera stands
            // still, and the brick pool the fitted grid gets here keeps the memory comparable.
            options.storage = crate::voxel::bricks::Storage::Sparse;
        }
        (scene, options)
    }

    /// The scene's own model on `levels` clipmap levels of `res`³ voxels around the camera
    /// (`voxel::clipmap`, its default extent), in place of the fitted grid.
    pub fn clipped(gi: &GiFile, levels: u32, res: u32) -> Self {
        Variant { clipmap: Some((levels, res)), ..Self::model(&format!("clipmap {levels}x{res}"), gi.clone()) }
    }
}

/// Indirect light: the full image minus the direct-light one.
fn indirect(full: &[Vec3], direct: &[Vec3]) -> Vec<Vec3> {
    full.iter().zip(direct).map(|(a, b)| *a - *b).collect()
}

fn scaled(img: &[Vec3], k: f32) -> Vec<Vec3> {
    img.iter().map(|p| p.max(Vec3::ZERO) * k).collect()
}

fn lum(v: Vec3) -> f32 {
    v.dot(LUMA)
}

fn mean_lum(img: &[Vec3]) -> f32 {
    img.iter().map(|p| lum(*p)).sum::<f32>() / img.len().max(1) as f32
}

/// A frame [`render_timed`] rendered.
pub struct Timed {
    /// Each pass's median GPU ms over the frames timed.
    pub passes: Vec<Timing>,
    /// The last frame's linear radiance and RGB8.
    pub linear: Vec<Vec3>,
    pub rgb: Vec<u8>,
    /// The volume's memory (bytes).
    pub memory: u64,
}

/// Renders `scene` with `options`: `frames` timed after one warm-up ([`super::timed_frames`]).
pub fn render_timed(ctx: &Arc<Context>, scene: &Scene, options: RenderOptions, frames: u32) -> Result<Timed> {
    let r = Renderer::new(ctx, scene.clone(), options)?;
    let runs = super::timed_frames(&r, 1, frames)?;
    let f = r.read_frame()?;
    Ok(Timed { passes: median(&runs), linear: f.linear(), rgb: f.rgb8(), memory: r.memory().bytes })
}

/// The voxelizer the harness renders with: the rasterized path (its coverage is exact on these
/// scenes, so the figures judge the light, not the voxels).
pub fn harness_method() -> VoxelizeMethod {
    VoxelizeMethod::raster(Coverage::Msaa)
}

/// Measures `variant` on `j` at `resolution`; `direct` is the renderer's direct-light frame.
pub fn measure(
    ctx: &Arc<Context>,
    j: &Judged,
    direct: &(Vec<Vec3>, Vec<u8>),
    variant: &Variant,
    resolution: u32,
    frames: u32,
) -> Result<AccuracyRow> {
    let (scene, options) = variant.setup(&j.scene, resolution);
    let Timed { passes, linear: full, rgb, memory } = render_timed(ctx, &scene, options, frames)?;
    let ms = passes.iter().find(|t| t.pass == "total").map_or(0.0, |t| t.ms);
    let (w, h) = (scene.camera.width, scene.camera.height);
    let (flip, flip_map, per_pixel) = metrics::flip_values(&j.full_rgb, &rgb, w, h);
    let mut by_distance = [(0.0f32, 0usize); 3];
    for (v, b) in per_pixel.iter().zip(&j.distance_band) {
        if let Some(b) = b {
            by_distance[*b as usize].0 += v;
            by_distance[*b as usize].1 += 1;
        }
    }
    let (flip_direct_only, _) = metrics::flip(&j.full_rgb, &direct.1, w, h);
    let (ref_img, vct_img) = (indirect(&j.full, &j.direct), indirect(&full, &direct.0));
    let ref_ind = region_means(&j.regions, &ref_img);
    let vct_ind = region_means(&j.regions, &vct_img);
    let mut indirect_pair = Vec::with_capacity((6 * w * h) as usize);
    let (a, b) = (metrics::tonemap(&scaled(&ref_img, 4.0)), metrics::tonemap(&scaled(&vct_img, 4.0)));
    for y in 0..h as usize {
        let row = 3 * w as usize;
        indirect_pair.extend_from_slice(&a[y * row..(y + 1) * row]);
        indirect_pair.extend_from_slice(&b[y * row..(y + 1) * row]);
    }
    let counts = j.regions.of_pixel.iter().flatten().fold(vec![0usize; j.regions.labels.len()], |mut c, r| {
        c[*r] += 1;
        c
    });
    let brightest = ref_ind.iter().map(|&c| lum(c)).fold(0.0f32, f32::max);
    let regions = j
        .regions
        .labels
        .iter()
        .enumerate()
        .map(|(i, label)| RegionRow {
            region: label.clone(),
            pixels: counts[i],
            reference: ref_ind[i].into(),
            vct: vct_ind[i].into(),
            ratio: lum(vct_ind[i]) / lum(ref_ind[i]).max(1e-9),
            judged: lum(ref_ind[i]) >= JUDGED_SHARE * brightest,
        })
        .collect();
    Ok(AccuracyRow {
        scene: j.name.clone(),
        variant: variant.name.clone(),
        resolution,
        bounces: variant.gi.bounces,
        frame_ms: ms,
        passes,
        memory_mib: memory as f64 / (1u64 << 20) as f64,
        flip,
        flip_direct_only,
        mean_ratio: mean_lum(&full) / mean_lum(&j.full).max(1e-9),
        flip_by_distance: by_distance.map(|(s, n)| s / n.max(1) as f32),
        distance_edges: j.distance_edges,
        regions,
        reference_noise: j.noise,
        lattices: None,
        pattern: None,
        flip_map,
        indirect_pair,
        width: w,
        height: h,
    })
}

/// The renderer's direct-light frame of `j` (it does not depend on the GI model).
pub fn direct_frame(ctx: &Arc<Context>, j: &Judged, resolution: u32) -> Result<(Vec<Vec3>, Vec<u8>)> {
    let options = RenderOptions {
        method: harness_method(),
        resolution: Some(resolution),
        view: View::Direct,
        gi: false,
        ..Default::default()
    };
    let t = render_timed(ctx, &j.scene, options, 1)?;
    Ok((t.linear, t.rgb))
}

/// How much a slow pan changes the image where nothing in the scene moves (a seam at a clipmap
/// level's border travelling with the camera, voxels regrouped as a volume steps): the camera
/// slides sideways 3 cm a frame (as the stability bench's sliding volume) for `frames` frames,
/// the volume following it as the viewer's does, and each frame is judged by FLIP against the
/// one before. Returns the mean and the largest. A fitted grid's figure is what the view's own
/// motion changes.
pub fn pan_flip(ctx: &Arc<Context>, j: &Judged, variant: &Variant, resolution: u32, frames: u32) -> Result<(f64, f64)> {
    let (scene, options) = variant.setup(&j.scene, resolution);
    let mut r = Renderer::new(ctx, scene, options)?;
    let mut previous: Option<Vec<u8>> = None;
    let mut flips = Vec::new();
    for _ in 0..frames.max(2) {
        r.render()?;
        let rgb = r.read_frame()?.rgb8();
        if let Some(p) = &previous {
            flips.push(metrics::flip(p, &rgb, r.targets.width, r.targets.height).0 as f64);
        }
        previous = Some(rgb);
        let c = &mut r.scene.camera;
        let side = (c.target - c.eye).cross(c.up).normalize_or_zero() * 0.03;
        c.eye += side;
        c.target += side;
        let eye = c.eye;
        r.follow(eye)?;
    }
    let mean = flips.iter().sum::<f64>() / flips.len() as f64;
    Ok((mean, flips.iter().copied().fold(0.0, f64::max)))
}

/// The study's variants: the thesis' model, then each choice added in turn up to the default
/// (a staircase: every row differs from the one above by one choice), the cone sets on top of
/// the default, and the default with each of its choices undone or changed.
pub fn study_variants(default: &GiFile) -> Vec<Variant> {
    let v = Variant::model;
    // The step cap is no model choice: every variant gets the default's; nor are the lights
    // (area lights are chosen when the scene loads, and one direct frame serves all variants).
    let t =
        GiFile { bounces: default.bounces, steps: default.steps, area_lights: default.area_lights, ..GiFile::thesis() };
    let aniso = GiFile { filter: Filter::Aniso, ..t.clone() };
    let footprint = GiFile { level: LevelRule::Footprint, ..aniso.clone() };
    let clamp = GiFile { self_clamp: true, ..footprint.clone() };
    let facing = GiFile { facing: true, ..clamp.clone() };
    let mut out = vec![
        v("thesis", t.clone()),
        v("+ anisotropic", aniso),
        v("+ footprint level", footprint),
        v("+ self clamp", clamp),
        v("+ facing", facing.clone()),
    ];
    for (cones, aperture) in [
        (ConeSet::Thesis5, 0.7),
        (ConeSet::Thesis5Cells, 1.0),
        (ConeSet::Thesis5Cells, 0.6),
        (ConeSet::Crassin6, 1.0),
        (ConeSet::Crassin6, 0.6),
        (ConeSet::Fib8, 1.0),
        (ConeSet::Fib8, 0.7),
        (ConeSet::Fib8, 0.5),
        (ConeSet::Fib16, 0.5),
        (ConeSet::Fib16, 0.7),
        (ConeSet::Fib16, 1.0),
        (ConeSet::Fib32, 0.5),
        (ConeSet::Fib32, 1.0),
    ] {
        let gi = GiFile { cones, aperture, ..facing.clone() };
        if gi != *default {
            out.push(v(&format!("+ facing, {} x{aperture}", cones.name()), gi));
        }
    }
    out.push(v("default", default.clone()));
    let d = || default.clone();
    out.push(v("default, isotropic", GiFile { filter: Filter::Iso, ..d() }));
    out.push(v("default, diameter level", GiFile { level: LevelRule::Diameter, ..d() }));
    out.push(v("default, no self clamp", GiFile { self_clamp: false, ..d() }));
    out.push(v("default, no facing", GiFile { facing: false, ..d() }));
    out.push(v("default, opacity correction", GiFile { opacity_correction: true, ..d() }));
    out.push(v("default, chain boxes", GiFile { chain_box: true, ..d() }));
    out.push(v("default, step 0.25", GiFile { step: 0.25, ..d() }));
    out.push(v("default, step 1", GiFile { step: 1.0, ..d() }));
    out.push(v("default, bias 3", GiFile { bias: 3.0, ..d() }));
    let turn = if default.turn_cones { "default, cones fixed" } else { "default, cones turned by pixel" };
    out.push(v(turn, GiFile { turn_cones: !default.turn_cones, ..d() }));
    out.push(v("default, cones fib8", GiFile { cones: ConeSet::Fib8, ..d() }));
    out.push(Variant { gi_scale: Some(4), ..v("default, gi scale 4", d()) });
    out.extend(Quality::ALL.into_iter().filter(|&q| q != Quality::Default).map(|q| Variant::preset(q, default)));
    for injection in [Injection::Voxels, Injection::Texels] {
        if injection != default.injection {
            out.push(v(&format!("default, injection from {}", injection.name()), GiFile { injection, ..d() }));
        }
    }
    if default.bounces > 1 {
        for cones in ConeSet::ALL {
            if cones != default.bounce_cones {
                out.push(v(&format!("default, bounce cones {}", cones.name()), GiFile { bounce_cones: cones, ..d() }));
            }
        }
    }
    out
}
