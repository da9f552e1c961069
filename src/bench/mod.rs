//! `vct bench`: sweeps voxelizer × resolution × scene, timing warm frames with GPU timestamps
//! (median and spread per pass) and measuring accuracy beside every time — voxel recall,
//! precision and IoU against the exact coverage, FLIP and RMSE of the final image against a
//! path-traced one-bounce reference (cached on disk by a hash of scene and settings). Writes
//! `results.csv`, `results.json` and the charts of [`charts`].

pub mod accuracy;
pub mod auto;
pub mod charts;
pub mod gi_scale;
pub mod hostile;
pub mod occupancy;
pub mod points;
pub mod report;
pub mod stability;

use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::Vec3;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::gpu::{timer::median, Context, Timing};
use crate::output;
use crate::reference::coverage::{Accuracy, RefGrid};
use crate::reference::metrics;
use crate::reference::pathtrace::{PathTracer, RefOptions};
use crate::render::{RenderOptions, Renderer};
use crate::scene::{Draw, Mesh, Scene};
use crate::voxel::bricks::Storage;
use crate::voxel::{headless, occupancy_of, Coverage, VoxelizeMethod};

pub struct BenchOptions {
    /// (name, scene) pairs.
    pub scenes: Vec<(String, Scene)>,
    pub resolutions: Vec<u32>,
    pub warmup: u32,
    pub frames: u32,
    pub reference_spp: u32,
    /// Subdivision levels of the triangle-count sweep (each level splits every triangle in 4).
    pub subdivisions: u32,
    pub out_dir: PathBuf,
    pub cache_dir: PathBuf,
    /// Storage modes beside the default one, run with the default voxelizer where the device
    /// offers them (e.g. dense, to chart memory and time against FLIP per mode).
    pub compare_storage: Vec<Storage>,
    /// The point voxelizer's densities swept at the first resolution, with and without its
    /// refinement (points per voxel area).
    pub point_densities: Vec<f32>,
    /// GI scales run beside 1 with the default configuration at the first resolution.
    pub gi_scales: Vec<u32>,
}

impl BenchOptions {
    /// The standard sweep over `scenes` (the quick one for CI: 32³ and 64³, few frames, a
    /// 16-spp reference; the full one: 64³, 128³ and 256³, a 256-spp reference), with every
    /// storage mode the device offers beside the default.
    pub fn standard(scenes: Vec<(String, Scene)>, quick: bool, out_dir: PathBuf, cache_dir: PathBuf) -> BenchOptions {
        BenchOptions {
            scenes,
            resolutions: if quick { vec![32, 64] } else { vec![64, 128, 256] },
            warmup: if quick { 1 } else { 2 },
            frames: if quick { 3 } else { 5 },
            reference_spp: if quick { 16 } else { 256 },
            subdivisions: if quick { 2 } else { 4 },
            point_densities: if quick { points::QUICK_DENSITIES.to_vec() } else { points::DENSITIES.to_vec() },
            gi_scales: gi_scale::SCALES.to_vec(),
            out_dir,
            cache_dir,
            compare_storage: vec![Storage::Dense, Storage::Sparse, Storage::Resident],
        }
    }
}

/// One configuration's figures.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Row {
    pub scene: String,
    pub triangles: usize,
    pub voxelizer: String,
    pub resolution: u32,
    /// The fitted grid's voxels along x, y, z (zero where a results file lacks them).
    #[serde(default)]
    pub dims: [u32; 3],
    /// GPU memory of the voxel textures and radiance volumes, and over the bounding cube.
    #[serde(default)]
    pub memory_mib: f64,
    #[serde(default)]
    pub cube_memory_mib: f64,
    /// Where the per-voxel textures lived (dense where a results file does not say).
    #[serde(default = "dense_label")]
    pub storage: String,
    pub frames: u32,
    /// Median GPU ms per pass.
    pub passes: Vec<Timing>,
    pub total_ms: f64,
    pub total_min_ms: f64,
    pub total_max_ms: f64,
    pub voxelize_ms: f64,
    pub recall: f64,
    pub precision: f64,
    pub iou: f64,
    pub flip: f32,
    pub rmse: f64,
}

/// Voxelization cost against triangle count (a scene subdivided k times).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct TriangleRow {
    pub scene: String,
    pub voxelizer: String,
    pub triangles: usize,
    pub voxelize_ms: f64,
}

#[derive(Clone, Serialize, Deserialize)]
pub struct Results {
    pub device: String,
    pub driver: String,
    pub warmup: u32,
    pub frames: u32,
    pub reference_spp: u32,
    pub reference_bounces: u32,
    pub references: Vec<ReferenceInfo>,
    pub rows: Vec<Row>,
    pub triangle_sweep: Vec<TriangleRow>,
    /// The point voxelizer at several densities (empty where a results file lacks it).
    #[serde(default)]
    pub density_sweep: Vec<points::DensityRow>,
    /// The diffuse cones at a reduced resolution (empty where a results file lacks it).
    #[serde(default)]
    pub gi_scale_sweep: Vec<gi_scale::ScaleRow>,
    /// The default storage on the device (`auto` resolved; where a results file
    /// does not say, its first rows ran the default: see [`Results::stored`]).
    #[serde(default)]
    pub default_storage: Option<String>,
}

impl Results {
    /// The rows of the default storage only: every voxelizer ran with it (the other modes ran
    /// the default voxelizer only).
    pub fn on_default_storage(&self) -> Results {
        let stored = self.stored();
        Results { rows: self.rows.iter().filter(|x| x.storage == stored).cloned().collect(), ..self.clone() }
    }

    /// The storage every voxelizer ran with (the other modes ran the default voxelizer only).
    pub fn stored(&self) -> &str {
        self.default_storage.as_deref().or(self.rows.first().map(|r| r.storage.as_str())).unwrap_or("sparse")
    }
}

#[derive(Clone, Serialize, Deserialize)]
pub struct ReferenceInfo {
    pub scene: String,
    pub path: PathBuf,
    pub relative_noise: f32,
}

fn dense_label() -> String {
    Storage::Dense.label().into()
}

/// The voxelizers a device can run: tessellation, rasterized with MSAA, without, and
/// conservative by a grown triangle, sample points at the default density, and
/// hardware-conservative rasterization where the extension is offered.
pub fn methods(ctx: &Context) -> Vec<VoxelizeMethod> {
    let mut m = vec![
        VoxelizeMethod::tess(),
        VoxelizeMethod::raster(Coverage::Msaa),
        VoxelizeMethod::raster(Coverage::None),
        VoxelizeMethod::raster(Coverage::Conservative),
        VoxelizeMethod::points(),
    ];
    if ctx.info.features.conservative_rasterization {
        m.push(VoxelizeMethod::raster(Coverage::Hardware));
    }
    m
}

/// Every triangle split into four at its edge midpoints, `levels` times.
pub fn subdivide_uniform(mesh: &Mesh, levels: u32) -> Mesh {
    let mut m = mesh.clone();
    for _ in 0..levels {
        let mut vertices = m.vertices.clone();
        let mut indices = Vec::with_capacity(m.indices.len() * 4);
        let mut draws = Vec::new();
        for d in &m.draws {
            let first = indices.len() as u32;
            for t in m.indices[d.first_index as usize..(d.first_index + d.index_count) as usize].chunks_exact(3) {
                let mid = |a: u32, b: u32, vs: &mut Vec<crate::scene::Vertex>| {
                    let (va, vb) = (vs[a as usize], vs[b as usize]);
                    let avg = |x: &[f32], y: &[f32]| x.iter().zip(y).map(|(p, q)| (p + q) * 0.5).collect::<Vec<f32>>();
                    let mut v = va;
                    v.pos.copy_from_slice(&avg(&va.pos, &vb.pos));
                    v.normal.copy_from_slice(&avg(&va.normal, &vb.normal));
                    v.uv.copy_from_slice(&avg(&va.uv, &vb.uv));
                    vs.push(v);
                    vs.len() as u32 - 1
                };
                let (a, b, c) = (t[0], t[1], t[2]);
                let (ab, bc, ca) = (mid(a, b, &mut vertices), mid(b, c, &mut vertices), mid(c, a, &mut vertices));
                indices.extend_from_slice(&[a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca]);
            }
            draws.push(Draw { first_index: first, index_count: indices.len() as u32 - first, material: d.material });
        }
        m = Mesh { vertices, indices, draws, bounds: m.bounds };
    }
    m
}

/// Bumped when the path tracer's estimator changes, so cached references are traced again.
const REFERENCE_VERSION: u32 = 2;
/// The same for its emitter sampling, which only scenes with emissive materials use (3: the
/// emitter drawn with one random number, not a fresh one per step of the search).
const EMITTER_SAMPLING_VERSION: u32 = 3;

/// The path-traced reference of `scene` with `bounces` bounces, from the cache when it is there.
pub fn reference_cached(
    scene: &Scene,
    name: &str,
    bounces: u32,
    area_lights_direct: bool,
    spp: u32,
    cache: &Path,
    progress: &dyn Fn(&str),
) -> Result<(Vec<Vec3>, ReferenceInfo)> {
    let mut h = DefaultHasher::new();
    let emits = scene.materials.iter().any(|m| m.emissive.max_element() > 0.0);
    let version = if emits { EMITTER_SAMPLING_VERSION } else { REFERENCE_VERSION };
    format!(
        "{version}|{:?}|{}|{}|{:?}|{:?}|{:?}|{spp}|{bounces}|{area_lights_direct}",
        scene.source,
        scene.mesh.triangle_count(),
        scene.mesh.vertices.len(),
        scene.camera,
        scene.lights,
        scene.materials.iter().map(|m| (m.albedo, m.emissive, m.specular, m.roughness)).collect::<Vec<_>>(),
    )
    .hash(&mut h);
    let kind = if area_lights_direct { "d" } else { "b" };
    let path = cache.join(format!("reference-{name}-{kind}{bounces}-{:016x}.exr", h.finish()));
    let noise_path = path.with_extension("noise");
    if let (Ok(frame), Ok(noise)) = (output::read_frame(&path), std::fs::read_to_string(&noise_path)) {
        if (frame.width, frame.height) == (scene.camera.width, scene.camera.height) {
            let relative_noise = noise.trim().parse().unwrap_or(f32::NAN);
            return Ok((frame.linear(), ReferenceInfo { scene: name.into(), path, relative_noise }));
        }
    }
    progress(&format!("path tracing the {name} reference ({bounces} bounce(s), {spp} spp)"));
    let img = PathTracer::new(scene).render(RefOptions { bounces, spp, seed: 1, area_lights_direct }, &|_| {});
    std::fs::create_dir_all(cache).map_err(|source| Error::Io { path: cache.to_path_buf(), source })?;
    output::write_exr(&path, &crate::render::FrameImages::from_linear(img.width, img.height, &img.radiance))?;
    std::fs::write(&noise_path, img.relative_noise.to_string())
        .map_err(|source| Error::Io { path: noise_path.clone(), source })?;
    Ok((img.radiance, ReferenceInfo { scene: name.into(), path, relative_noise: img.relative_noise }))
}

fn voxel_accuracy(scene: &Scene, renderer: &Renderer) -> Result<Accuracy> {
    let g = renderer.voxels.grid;
    let tris: Vec<_> = (0..scene.mesh.triangle_count()).map(|t| scene.mesh.triangle(t)).collect();
    let coverage = RefGrid::matching(&g).coverage(&tris, 1e-3);
    Ok(coverage.accuracy(&occupancy_of(&renderer.voxels.read_albedo()?)))
}

/// Runs the whole sweep; `progress(step, message)` reports each configuration.
pub fn run(ctx: &Arc<Context>, opts: &BenchOptions, progress: &dyn Fn(&str)) -> Result<Results> {
    let methods = methods(ctx);
    let mut rows = Vec::new();
    let mut references = Vec::new();
    let mut density_sweep = Vec::new();
    let mut gi_scale_sweep = Vec::new();
    for (name, scene) in &opts.scenes {
        let (reference, info) = reference_cached(scene, name, 1, false, opts.reference_spp, &opts.cache_dir, progress)?;
        references.push(info);
        let default_method = RenderOptions::default().method.on(&ctx.info.features);
        // The default storage for every voxelizer; the others (those the device offers) with the
        // default voxelizer.
        let stored = Storage::default().resolve(ctx, false);
        let offered = |s: Storage| s != Storage::Resident || crate::voxel::bricks::residency_offered(ctx);
        let configs: Vec<(VoxelizeMethod, Storage)> = methods
            .iter()
            .map(|&m| (m, stored))
            .chain(opts.compare_storage.iter().filter(|&&s| s != stored && offered(s)).map(|&s| (default_method, s)))
            .collect();
        for &res in &opts.resolutions {
            for &(method, storage) in &configs {
                progress(&format!("{name} {} {res}³, {} storage", method.label(), storage.label()));
                let options = RenderOptions { method, resolution: Some(res), storage, ..Default::default() };
                rows.push(measure(ctx, opts, name, scene, &reference, options)?);
            }
        }
        // The point voxelizer's density, with and without refinement, at the first resolution.
        if let Some(&res) = opts.resolutions.first() {
            for &refine in &[false, true] {
                for &density in &opts.point_densities {
                    let source = crate::voxel::points::DEFAULT_POINT_SOURCE;
                    let method = VoxelizeMethod::Points { density, source, refine };
                    progress(&format!("{name} points at {density} per voxel area, refinement {refine}, {res}³"));
                    let options =
                        RenderOptions { method, resolution: Some(res), storage: stored, ..Default::default() };
                    let row = measure(ctx, opts, name, scene, &reference, options)?;
                    density_sweep.push(points::DensityRow { density, refine, row });
                }
            }
            // The diffuse cones at a reduced resolution, the rest as the main sweep's default.
            for accumulate in [false, true] {
                for &scale in &opts.gi_scales {
                    let how = if accumulate { ", accumulated" } else { "" };
                    progress(&format!("{name} GI scale {scale}{how}, {res}³"));
                    let options = RenderOptions {
                        resolution: Some(res),
                        storage: stored,
                        gi_scale: scale,
                        gi_accumulate: accumulate,
                        ..Default::default()
                    };
                    let row = measure(ctx, opts, name, scene, &reference, options)?;
                    gi_scale_sweep.push(gi_scale::ScaleRow { scale, accumulate, row });
                }
            }
        }
    }
    // Cost against triangle count: the first scene subdivided 0..=k times, smallest resolution.
    let mut triangle_sweep = Vec::new();
    if let (Some((name, scene)), Some(&res)) = (opts.scenes.first(), opts.resolutions.first()) {
        for k in 0..=opts.subdivisions {
            let mut s = scene.clone();
            s.mesh = subdivide_uniform(&scene.mesh, k);
            let swept = [VoxelizeMethod::tess(), VoxelizeMethod::raster(Coverage::Msaa), VoxelizeMethod::points()];
            for method in &swept {
                progress(&format!("{name} ×4^{k} triangles, {}", method.label()));
                let run = headless::voxelize(ctx, &s, *method, res, opts.frames.max(1))?;
                triangle_sweep.push(TriangleRow {
                    scene: name.clone(),
                    voxelizer: method.label(),
                    triangles: s.mesh.triangle_count(),
                    voxelize_ms: run.gpu_ms,
                });
            }
        }
    }
    Ok(Results {
        device: ctx.info.name.clone(),
        driver: ctx.info.driver.clone(),
        warmup: opts.warmup,
        frames: opts.frames,
        reference_spp: opts.reference_spp,
        reference_bounces: 1,
        references,
        rows,
        default_storage: Some(Storage::default().resolve(ctx, false).label().into()),
        triangle_sweep,
        density_sweep,
        gi_scale_sweep,
    })
}

/// Renders `scene` with `options` (warm-up, then timed frames) and measures the frame against
/// the path-traced `reference` and the voxels against the exact coverage.
/// Renders `warmup` frames, then returns the GPU times of `frames` more. A fast device idles
/// while the next configuration is built and ramps its clocks up again (an H200: 345 MHz idle,
/// 1980 MHz at most; its 5-frame rows of a few ms ranged up to 2×), so both phases also last at
/// least 0.5 s and 0.25 s of wall clock (at most 1000 frames each). A CPU driver's frames take
/// longer than that.
pub fn timed_frames(renderer: &Renderer, warmup: u32, frames: u32) -> Result<Vec<Vec<Timing>>> {
    let started = std::time::Instant::now();
    let mut n = 0;
    while n < warmup || (started.elapsed().as_secs_f64() < 0.5 && n < 1000) {
        renderer.render()?;
        n += 1;
    }
    let (started, mut runs) = (std::time::Instant::now(), Vec::new());
    while runs.len() < frames.max(1) as usize || (started.elapsed().as_secs_f64() < 0.25 && runs.len() < 1000) {
        runs.push(renderer.render()?);
    }
    Ok(runs)
}

fn measure(
    ctx: &Arc<Context>,
    opts: &BenchOptions,
    name: &str,
    scene: &Scene,
    reference: &[Vec3],
    options: RenderOptions,
) -> Result<Row> {
    let res = options.resolution.unwrap_or(0);
    let renderer = Renderer::new(ctx, scene.clone(), options)?;
    // What ran (`Coverage::Auto` resolved for this device).
    let method = renderer.options.method;
    // Accumulation is judged once it has converged: every pixel traced once.
    let converge = if options.gi_accumulate { options.gi_scale.pow(2) } else { 0 };
    let runs = timed_frames(&renderer, opts.warmup.max(converge), opts.frames)?;
    let passes = median(&runs);
    let totals: Vec<f64> = runs.iter().filter_map(|r| r.iter().find(|t| t.pass == "total").map(|t| t.ms)).collect();
    let get = |p: &str| passes.iter().find(|t| t.pass == p).map(|t| t.ms).unwrap_or(0.0);
    let frame = renderer.read_frame()?;
    let (flip, _) = metrics::flip(&metrics::tonemap(reference), &frame.rgb8(), frame.width, frame.height);
    let rmse = metrics::rmse(reference, &frame.linear());
    let acc = voxel_accuracy(scene, &renderer)?;
    let memory = renderer.memory();
    Ok(Row {
        scene: name.into(),
        triangles: scene.mesh.triangle_count(),
        voxelizer: method.label(),
        resolution: res,
        dims: memory.dims,
        memory_mib: memory.mib(),
        cube_memory_mib: memory.cube_mib(),
        storage: renderer.voxels.bricks.storage.label().into(),
        frames: opts.frames,
        total_ms: get("total"),
        total_min_ms: totals.iter().cloned().fold(f64::INFINITY, f64::min),
        total_max_ms: totals.iter().cloned().fold(0.0, f64::max),
        voxelize_ms: get("voxelize"),
        passes,
        recall: acc.recall,
        precision: acc.precision,
        iou: acc.iou,
        flip,
        rmse,
    })
}

pub const CSV_HEADER: &str = "scene,triangles,voxelizer,resolution,frames,voxelize_ms,shadow_ms,inject_ms,filter_ms,gbuffer_ms,shade_ms,tonemap_ms,total_ms,total_min_ms,total_max_ms,recall,precision,iou,flip,rmse,dims,memory_mib,cube_memory_mib,storage";

/// Writes results.csv, results.json, summary.md and the charts into `dir`; `before`, an
/// earlier run, is drawn beside this one where a chart compares runs.
pub fn write(dir: &Path, results: &Results, before: Option<&Results>) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir).map_err(|source| Error::Io { path: dir.to_path_buf(), source })?;
    let mut csv = String::from(CSV_HEADER);
    csv.push('\n');
    for r in &results.rows {
        let p = |name: &str| r.passes.iter().find(|t| t.pass == name).map(|t| t.ms).unwrap_or(0.0);
        csv.push_str(&format!(
            "{},{},{},{},{},{:.3},{:.3},{:.3},{:.3},{:.3},{:.3},{:.3},{:.3},{:.3},{:.3},{:.5},{:.5},{:.5},{:.5},{:.6},{},{:.1},{:.1},{}\n",
            r.scene,
            r.triangles,
            r.voxelizer,
            r.resolution,
            r.frames,
            p("voxelize"),
            p("shadow map"),
            p("inject"),
            p("filter"),
            p("gbuffer"),
            p("shade"),
            p("tonemap"),
            r.total_ms,
            r.total_min_ms,
            r.total_max_ms,
            r.recall,
            r.precision,
            r.iou,
            r.flip,
            r.rmse,
            r.dims.map(|d| d.to_string()).join("x"),
            r.memory_mib,
            r.cube_memory_mib,
            r.storage
        ));
    }
    let write = |name: &str, text: &str| -> Result<PathBuf> {
        let path = dir.join(name);
        std::fs::write(&path, text).map_err(|source| Error::Io { path: path.clone(), source })?;
        Ok(path)
    };
    let mut files = vec![write("results.csv", &csv)?];
    let json =
        serde_json::to_string_pretty(results).map_err(|e| Error::input(dir.join("results.json"), e.to_string()))?;
    files.push(write("results.json", &json)?);
    files.push(write("summary.md", &summary(results))?);
    files.extend(draw(dir, results, before)?);
    Ok(files)
}

/// Draws every chart of a sweep into `dir` (as [`write`] does): the voxelizers', the storage
/// modes', the point densities' and the GI scales'.
pub fn draw(dir: &Path, results: &Results, before: Option<&Results>) -> Result<Vec<PathBuf>> {
    let mut files = charts::draw_all(dir, results, before)?;
    let r = &results.on_default_storage();
    files.extend(points::draw(dir, r)?);
    files.extend(gi_scale::draw(dir, r)?);
    Ok(files)
}

/// Reads a results.json written by [`write`].
pub fn read_results(path: &Path) -> Result<Results> {
    let text = std::fs::read_to_string(path).map_err(|source| Error::Io { path: path.to_path_buf(), source })?;
    let r: Results =
        serde_json::from_str(&text).map_err(|e| Error::input(path, format!("not a vct results file: {e}")))?;
    if r.rows.is_empty() {
        return Err(Error::input(path, "the run measured no configuration: nothing to draw".to_string()));
    }
    Ok(r)
}

/// The results as Markdown tables (`summary.md` of a run).
pub fn summary(r: &Results) -> String {
    let mut s = format!(
        "Device: {} ({}). {} warm-up and {} timed frames per configuration, at least 0.5 s and 0.25 s \
         of them (median; frame min–max shown). Image reference: path traced, 1 bounce, {} spp.\n\n",
        r.device, r.driver, r.warmup, r.frames, r.reference_spp
    );
    for reference in &r.references {
        s.push_str(&format!(
            "- {} reference noise: {:.2}% (mean standard error over mean)\n",
            reference.scene,
            100.0 * reference.relative_noise
        ));
    }
    s.push_str(
        "\n| scene | voxelizer | storage | N | memory MiB | voxelize ms | frame ms (min–max) | recall | precision | IoU | FLIP | RMSE |\n",
    );
    s.push_str("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for x in &r.rows {
        s.push_str(&format!(
            "| {} | {} | {} | {} | {:.1} | {:.2} | {:.1} ({:.1}–{:.1}) | {:.4} | {:.4} | {:.4} | {:.4} | {:.4} |\n",
            x.scene,
            x.voxelizer,
            x.storage,
            x.resolution,
            x.memory_mib,
            x.voxelize_ms,
            x.total_ms,
            x.total_min_ms,
            x.total_max_ms,
            x.recall,
            x.precision,
            x.iou,
            x.flip,
            x.rmse
        ));
    }
    s.push_str("\nTess/raster (MSAA) voxelization time ratio:\n\n| scene | N | tess ms | raster ms | ratio |\n|---|---|---|---|---|\n");
    let stored = r.stored();
    for t in r.rows.iter().filter(|x| x.voxelizer == "tess" && x.storage == stored) {
        if let Some(m) = r.rows.iter().find(|x| {
            x.voxelizer == "raster-msaa" && x.storage == stored && x.scene == t.scene && x.resolution == t.resolution
        }) {
            s.push_str(&format!(
                "| {} | {} | {:.2} | {:.2} | {:.1} |\n",
                t.scene,
                t.resolution,
                t.voxelize_ms,
                m.voxelize_ms,
                t.voxelize_ms / m.voxelize_ms.max(1e-9)
            ));
        }
    }
    s.push_str("\nVoxelization cost against triangle count:\n\n| scene | voxelizer | triangles | voxelize ms |\n|---|---|---|---|\n");
    for t in &r.triangle_sweep {
        s.push_str(&format!("| {} | {} | {} | {:.2} |\n", t.scene, t.voxelizer, t.triangles, t.voxelize_ms));
    }
    s.push_str(&points::summary(r));
    s.push_str(&gi_scale::summary(r));
    s
}
