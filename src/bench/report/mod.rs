//! `vct bench --report DIR`: the standard suite in one run, and the report written from its data.
//!
//! The suite: the voxelizer sweep (speed, voxel accuracy against the exact coverage, FLIP
//! against the path tracer, storage modes, point densities, GI scales), the indirect light of
//! the default model against path-traced references, the stability regimes and the
//! hostile-geometry set. Its data lands under `DIR/data/` (JSON and CSV, the charts as SVG),
//! beside `DIR/data/stamp.json` (date, commit, machine, driver, the command). [`page`] then
//! writes `DIR/README.md` and `DIR/index.html` from that data alone, so `--rewrite` redraws
//! the report without measuring. A GPU run's data in `DIR/gpu/` (`scripts/device-bench.sh`,
//! imported with `--gpu`) becomes a section of its own, stamped with its device.

pub mod page;

use std::path::{Path, PathBuf};
use std::sync::Arc;

use serde::{Deserialize, Serialize};

use super::accuracy::{self, AccuracyRow, Judged, Variant};
use super::charts::Regime;
use super::hostile::{self, HostileRow};
use super::stability;
use super::{BenchOptions, Results};
use crate::error::{Error, Result};
use crate::gpu::Context;
use crate::render::Quality;
use crate::scene::Scene;

/// Where and with what a run was measured.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Stamp {
    /// UTC date and time of the run's end.
    pub date: String,
    /// `git describe`-style commit of the tree measured (`+changes` when it had uncommitted
    /// changes; `unknown` outside a git checkout).
    pub commit: String,
    pub device: String,
    pub driver: String,
    /// The host's processor and its logical cores.
    pub cpu: String,
    pub cores: usize,
    /// The command line that measured it.
    pub command: String,
    /// `quick` (the CI variant) or `full`.
    pub suite: String,
    /// Wall-clock seconds the suite took.
    pub seconds: f64,
}

impl Stamp {
    /// The commit of the tree in the current folder, `+changes` where it has uncommitted
    /// changes to tracked files: taken when a run starts, since it measures the binary built
    /// from that tree.
    pub fn commit() -> String {
        let git = |args: &[&str]| {
            std::process::Command::new("git")
                .args(args)
                .output()
                .ok()
                .filter(|o| o.status.success())
                .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        };
        match (git(&["rev-parse", "--short=12", "HEAD"]), git(&["status", "--porcelain", "--untracked-files=no"])) {
            (Some(c), Some(dirty)) if !dirty.is_empty() => format!("{c}+changes"),
            (Some(c), _) => c,
            (None, _) => "unknown".into(),
        }
    }

    /// The stamp of a run on `ctx`, of the tree at `commit`, that took `seconds`.
    pub fn now(ctx: &Context, suite: &Suite, commit: String, seconds: f64) -> Stamp {
        let cpu = std::fs::read_to_string("/proc/cpuinfo")
            .ok()
            .and_then(|t| {
                t.lines()
                    .find(|l| l.starts_with("model name"))
                    .and_then(|l| l.split(':').nth(1))
                    .map(|s| s.trim().to_string())
            })
            .unwrap_or_else(|| std::env::consts::ARCH.to_string());
        Stamp {
            date: {
                let t = time::OffsetDateTime::now_utc();
                format!("{} {:02}:{:02}", t.date(), t.hour(), t.minute())
            },
            commit,
            device: ctx.info.name.clone(),
            driver: ctx.info.driver.clone(),
            cpu,
            cores: std::thread::available_parallelism().map_or(1, |n| n.get()),
            command: suite.command.clone(),
            suite: if suite.quick { "quick" } else { "full" }.into(),
            seconds,
        }
    }
}

/// What the suite measures.
pub struct Suite {
    /// The CI variant: small images and grids, few frames and samples (a few minutes on
    /// lavapipe).
    pub quick: bool,
    /// Scenes measured beside the embedded Cornell box (and, for the indirect light, its
    /// directional variant).
    pub scenes: Vec<(String, Scene)>,
    /// Where path-traced references are cached.
    pub cache: PathBuf,
    /// The command line, for the stamp.
    pub command: String,
}

/// The report's data, as the suite leaves it in `DIR/data/` (or a GPU run in `DIR/gpu/`).
pub struct Data {
    pub stamp: Option<Stamp>,
    pub sweep: Option<Results>,
    pub accuracy: Vec<AccuracyRow>,
    pub stability: Vec<Regime>,
    pub hostile: Vec<HostileRow>,
    /// This tree against the landed main, side by side (`scripts/speed-vs-main.sh`, imported with
    /// `--speed`).
    pub speed: Vec<SpeedRun>,
}

/// One `vct render` of `scripts/speed-vs-main.sh`: a case, the binary (`base`: the landed main;
/// `new`: this tree) and the round, with the run's wall clock and its per-pass median GPU times.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct SpeedRun {
    pub case: String,
    pub binary: String,
    pub round: u32,
    pub frames: u32,
    pub run_wall_ms: f64,
    pub timings: SpeedTimings,
}

/// The part of `vct render --timings` a speed run keeps.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct SpeedTimings {
    pub passes: Vec<PassMs>,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct PassMs {
    pub pass: String,
    pub ms: f64,
}

impl SpeedRun {
    /// The median GPU time of `pass` over the run's frames (0 where it has none).
    pub fn pass_ms(&self, pass: &str) -> f64 {
        self.timings.passes.iter().find(|p| p.pass == pass).map_or(0.0, |p| p.ms)
    }
}

fn read_json<T: serde::de::DeserializeOwned>(path: &Path) -> Result<Option<T>> {
    match std::fs::read_to_string(path) {
        Ok(text) => serde_json::from_str(&text)
            .map(Some)
            .map_err(|e| Error::input(path, format!("not the data a vct bench writes: {e}"))),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
        Err(source) => Err(Error::Io { path: path.to_path_buf(), source }),
    }
}

impl Data {
    /// Reads the data under `dir` (`data/` or `gpu/`); a part the run did not measure is empty.
    pub fn read(dir: &Path) -> Result<Data> {
        Ok(Data {
            stamp: read_json(&dir.join("stamp.json"))?,
            sweep: read_json(&dir.join("sweep/results.json"))?,
            accuracy: read_json(&dir.join("accuracy/accuracy.json"))?.unwrap_or_default(),
            stability: read_json(&dir.join("stability/stability.json"))?.unwrap_or_default(),
            hostile: read_json(&dir.join("stability/hostile.json"))?.unwrap_or_default(),
            speed: read_json(&dir.join("speed/speed.json"))?.unwrap_or_default(),
        })
    }

    pub fn is_empty(&self) -> bool {
        self.sweep.is_none()
            && self.accuracy.is_empty()
            && self.stability.is_empty()
            && self.hostile.is_empty()
            && self.speed.is_empty()
    }
}

/// The indirect light of each scene's own model against its path-traced reference, at each
/// resolution: the default frame's accuracy figures. At `shown` (the scenes' own grid) also the
/// other quality presets (`render::Quality`, rows "quality NAME"), for all three the flat-wall
/// pattern (`accuracy::pattern`), and on the first scene the trace's breakdown
/// (`accuracy::trace_cost`, rows "trace: …").
#[allow(clippy::too_many_arguments)] // the suite's knobs
pub fn measure_light(
    ctx: &Arc<Context>,
    scenes: Vec<(String, Scene)>,
    resolutions: &[u32],
    shown: u32,
    spp: u32,
    frames: u32,
    cache: &Path,
    progress: &dyn Fn(&str),
) -> Result<Vec<AccuracyRow>> {
    let mut rows = Vec::new();
    for (k, (name, scene)) in scenes.into_iter().enumerate() {
        let gi = scene.settings.gi.clone();
        let judged = Judged::new(&name, scene, gi.bounces, spp, cache, progress)?;
        for &res in resolutions {
            progress(&format!("indirect light: {name} at {res}³"));
            let direct = accuracy::direct_frame(ctx, &judged, res)?;
            let mut variants = vec![Variant::default_of(&gi)];
            if res == shown {
                variants.extend(
                    Quality::ALL.into_iter().filter(|&q| q != Quality::Default).map(|q| Variant::preset(q, &gi)),
                );
            }
            let patterned = variants.len();
            if res == shown && k == 0 {
                variants.extend(accuracy::trace_cost::variants(&gi));
            }
            for (i, v) in variants.iter().enumerate() {
                progress(&format!("indirect light: {name} at {res}³, {}", v.name));
                let mut row = accuracy::measure(ctx, &judged, &direct, v, res, frames)?;
                if res == shown && i < patterned {
                    progress(&format!("indirect light: {name} at {res}³, {}: the flat-wall pattern", v.name));
                    row.pattern = Some(accuracy::pattern::measure(ctx, &judged, v, res)?);
                }
                rows.push(row);
            }
        }
    }
    Ok(rows)
}

/// Runs the suite on `ctx`, writes its data under `dir/data/` and the report from it; returns
/// the report's files.
pub fn run(ctx: &Arc<Context>, dir: &Path, suite: Suite, progress: &dyn Fn(&str)) -> Result<Vec<PathBuf>> {
    let start = std::time::Instant::now();
    let commit = Stamp::commit();
    let data = dir.join("data");
    let quick = suite.quick;
    let size = |mut s: Scene| -> Result<Scene> {
        if quick {
            s.set_size(Some(128), Some(128))?;
        }
        Ok(s)
    };
    let cornell = size(Scene::embedded_default()?)?;
    let directional = size(Scene::load(&Path::new(crate::scene::EMBEDDED_DIR).join("scene-directional.toml"))?)?;
    let mut given = Vec::new();
    for (name, s) in &suite.scenes {
        given.push((name.clone(), size(s.clone())?));
    }

    let mut sweep_scenes = vec![("cornell".to_string(), cornell.clone())];
    sweep_scenes.extend(given.iter().cloned());
    let sweep_dir = data.join("sweep");
    let options = BenchOptions::standard(sweep_scenes, quick, sweep_dir.clone(), suite.cache.clone());
    let results = super::run(ctx, &options, progress)?;
    super::write(&sweep_dir, &results, None)?;

    let mut light_scenes = vec![("cornell".to_string(), cornell), ("cornell-directional".to_string(), directional)];
    light_scenes.extend(given);
    let (resolutions, spp, frames) = if quick { (vec![32], 16, 1) } else { (vec![64, 128, 256], 2048, 3) };
    // The report shows the images (FLIP map, indirect light beside the reference's) of the
    // scenes' own grid, the middle resolution, and the presets there; the others' are not kept.
    let shown = resolutions[resolutions.len() / 2];
    let light = measure_light(ctx, light_scenes, &resolutions, shown, spp, frames, &suite.cache, progress)?;
    let imaged: Vec<AccuracyRow> = light
        .iter()
        .cloned()
        .map(|mut r| {
            if r.resolution != shown || r.variant != "default" {
                r.flip_map.clear();
            }
            r
        })
        .collect();
    accuracy::write(&data.join("accuracy"), &imaged, false)?;

    let regimes = stability::run(ctx, quick, progress)?;
    let mut rows = Vec::new();
    for &res in if quick { &[64][..] } else { &[64, 128, 256][..] } {
        rows.extend(hostile::run(ctx, &super::methods(ctx), res, progress)?);
    }
    stability::write(&data.join("stability"), &regimes, &rows)?;

    let stamp = Stamp::now(ctx, &suite, commit, start.elapsed().as_secs_f64());
    write_json(&data.join("stamp.json"), &stamp)?;
    keep_svg_charts(&data)?;
    page::write(dir)
}

pub(crate) fn write_json<T: Serialize>(path: &Path, value: &T) -> Result<()> {
    let text = serde_json::to_string_pretty(value).map_err(|e| Error::input(path, e.to_string()))?;
    std::fs::write(path, text).map_err(|source| Error::Io { path: path.to_path_buf(), source })
}

/// Removes each chart's PNG where its SVG is beside it: the report inlines the SVG, and keeps
/// its data folder small enough to commit.
fn keep_svg_charts(dir: &Path) -> Result<()> {
    let entries = std::fs::read_dir(dir).map_err(|source| Error::Io { path: dir.to_path_buf(), source })?;
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            keep_svg_charts(&p)?;
        } else if p.extension().is_some_and(|x| x == "png") && p.with_extension("svg").is_file() {
            std::fs::remove_file(&p).map_err(|source| Error::Io { path: p.clone(), source })?;
        }
    }
    Ok(())
}

/// Copies the runs of `scripts/speed-vs-main.sh` (its JSON, `from`) into `dir/data/speed/`, the
/// report's speed section. Returns the file written.
pub fn import_speed(from: &Path, dir: &Path) -> Result<PathBuf> {
    let runs: Vec<SpeedRun> = read_json(from)?.ok_or_else(|| Error::input(from, "no such file"))?;
    if !runs.iter().any(|r| r.binary == "base") || !runs.iter().any(|r| r.binary == "new") {
        return Err(Error::input(from, "needs runs of both binaries, base and new (scripts/speed-vs-main.sh)"));
    }
    let dst = dir.join("data/speed/speed.json");
    std::fs::create_dir_all(dst.parent().expect("a file in data/speed"))
        .map_err(|source| Error::Io { path: dst.clone(), source })?;
    write_json(&dst, &runs)?;
    Ok(dst)
}

/// Copies a GPU run's data (the folder `scripts/device-bench.sh` returns, or one laid out as
/// `DIR/data/`) into `dir/gpu/`, found by file name: the voxelizer sweep's `results.json`, the
/// indirect light's `accuracy.json`, `stability.json` and `hostile.json`, and a `stamp.json`
/// where the run wrote one. Returns the files copied.
pub fn import_gpu(from: &Path, dir: &Path) -> Result<Vec<PathBuf>> {
    fn find(dir: &Path, name: &str) -> Option<PathBuf> {
        let mut entries: Vec<PathBuf> = std::fs::read_dir(dir).ok()?.flatten().map(|e| e.path()).collect();
        entries.sort();
        entries
            .iter()
            .find(|p| p.is_file() && p.file_name().is_some_and(|n| n == name))
            .cloned()
            .or_else(|| entries.iter().filter(|p| p.is_dir()).find_map(|p| find(p, name)))
    }
    let gpu = dir.join("gpu");
    let mut copied = Vec::new();
    for (name, to) in [
        ("results.json", "sweep/results.json"),
        ("accuracy.json", "accuracy/accuracy.json"),
        ("stability.json", "stability/stability.json"),
        ("hostile.json", "stability/hostile.json"),
        ("stamp.json", "stamp.json"),
    ] {
        let Some(src) = find(from, name) else { continue };
        let dst = gpu.join(to);
        std::fs::create_dir_all(dst.parent().expect("a file in gpu/"))
            .map_err(|source| Error::Io { path: gpu.clone(), source })?;
        std::fs::copy(&src, &dst).map_err(|source| Error::Io { path: src.clone(), source })?;
        copied.push(dst);
    }
    if copied.is_empty() {
        return Err(Error::input(
            from,
            "no results.json, accuracy.json or stability.json under it: not a vct bench run",
        ));
    }
    Data::read(&gpu)?;
    Ok(copied)
}
