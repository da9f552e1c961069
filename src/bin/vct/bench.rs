//! `vct bench`: the voxelizer sweep, the stability regimes, cost against occupancy, the indirect
//! light against the path tracer (accuracy.rs) and the report of the standard suite.

use std::path::{Path, PathBuf};

use anyhow::{Context as _, Result};

use vct::scene::Scene;

use crate::accuracy;
use crate::bench_args::BenchArgs;
use crate::common::*;

/// `--report DIR`: the standard suite and the report from its data (or, with --rewrite, the
/// report from the data already there); --gpu imports a GPU run first, --speed the timings against
/// the landed main.
fn report(dir: &Path, args: &BenchArgs, scenes: Vec<(String, Scene)>) -> Result<()> {
    if let Some(run) = &args.gpu_run {
        for f in vct::bench::report::import_gpu(run, dir).context("importing the GPU run")? {
            println!("imported {}", f.display());
        }
    }
    if let Some(runs) = &args.speed {
        let f = vct::bench::report::import_speed(runs, dir).context("importing the speed runs")?;
        println!("imported {}", f.display());
    }
    let files = if args.rewrite {
        vct::bench::report::page::write(dir).context("writing the report")?
    } else {
        let ctx = open_device(&args.gpu)?;
        let bar = indicatif::ProgressBar::new_spinner();
        bar.enable_steady_tick(std::time::Duration::from_millis(200));
        let suite = vct::bench::report::Suite {
            quick: args.quick,
            scenes,
            cache: PathBuf::from("bench/cache"),
            command: std::env::args().skip(1).collect::<Vec<_>>().join(" "),
        };
        let files = vct::bench::report::run(&ctx, dir, suite, &|m| bar.set_message(m.to_string()))
            .context("running the report's suite")?;
        bar.finish_and_clear();
        check_validation(&ctx)?;
        files
    };
    for f in files {
        println!("wrote {}", f.display());
    }
    Ok(())
}

pub fn bench(args: BenchArgs) -> Result<()> {
    if let Some(dir) = &args.report {
        let mut scenes = Vec::new();
        for p in &args.scenes {
            let name = p.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "scene".into());
            scenes.push((name, load_scene(Some(p))?));
        }
        return report(dir, &args, scenes);
    }
    let before = args.baseline.as_deref().map(vct::bench::read_results).transpose()?;
    if let Some(dir) = &args.replot {
        let results = vct::bench::read_results(&dir.join("results.json"))?;
        for f in vct::bench::write(dir, &results, before.as_ref())? {
            println!("wrote {}", f.display());
        }
        return Ok(());
    }
    let mut scenes = Vec::new();
    if !args.given_only {
        scenes.push(("cornell".to_string(), Scene::embedded_default()?));
    }
    if args.accuracy && !args.given_only {
        let directional = Path::new(vct::scene::EMBEDDED_DIR).join("scene-directional.toml");
        scenes.push(("cornell-directional".to_string(), load_scene(Some(&directional))?));
    }
    for p in &args.scenes {
        let name = p.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "scene".into());
        scenes.push((name, load_scene(Some(p))?));
    }
    if args.quick {
        for (_, s) in &mut scenes {
            s.set_size(Some(128), Some(128))?;
        }
    }
    let ctx = open_device(&args.gpu)?;
    let slug: String =
        ctx.info.name.chars().map(|c| if c.is_ascii_alphanumeric() { c.to_ascii_lowercase() } else { '-' }).collect();
    let date = time::OffsetDateTime::now_utc().date();
    let out = args.out.clone().unwrap_or_else(|| PathBuf::from(format!("bench/{date}-{}", slug.trim_matches('-'))));
    if args.accuracy {
        return accuracy::accuracy(&ctx, &args, scenes, &out);
    }
    if args.occupancy {
        let n = args.res.as_ref().and_then(|r| r.first().copied()).unwrap_or(if args.quick { 64 } else { 128 });
        let frames = args.frames.unwrap_or(if args.quick { 2 } else { 5 });
        let bar = indicatif::ProgressBar::new_spinner();
        bar.enable_steady_tick(std::time::Duration::from_millis(200));
        let g = vct::bench::occupancy::run(&ctx, n, frames, &|m| bar.set_message(m.to_string()))?;
        bar.finish_and_clear();
        std::fs::create_dir_all(&out).with_context(|| format!("creating {}", out.display()))?;
        println!("{}", g.title);
        for s in &g.series {
            let pts: Vec<String> = s.points.iter().map(|(x, y)| format!("{x:.0} voxels: {y:.1} ms")).collect();
            println!("  {:<40} {}", s.label, pts.join("  "));
        }
        for f in vct::bench::charts::draw_regime(&out, &g)? {
            println!("wrote {}", f.display());
        }
        let json = out.join("occupancy.json");
        std::fs::write(&json, serde_json::to_string_pretty(&g)?)
            .with_context(|| format!("writing {}", json.display()))?;
        println!("wrote {}", json.display());
        return check_validation(&ctx);
    }
    if args.stability {
        let bar = indicatif::ProgressBar::new_spinner();
        bar.enable_steady_tick(std::time::Duration::from_millis(200));
        let regimes = vct::bench::stability::run(&ctx, args.quick, &|m| bar.set_message(m.to_string()))?;
        bar.finish_and_clear();
        for g in &regimes {
            println!("{}", g.title);
            for s in &g.series {
                let pts: Vec<String> = s.points.iter().map(|(x, y)| format!("{}: {y:.4}", *x as f32)).collect();
                println!("  {:<32} {}", s.label, pts.join("  "));
            }
        }
        let bar = indicatif::ProgressBar::new_spinner();
        bar.enable_steady_tick(std::time::Duration::from_millis(200));
        let methods = vct::bench::methods(&ctx);
        let resolutions = args.res.clone().unwrap_or(if args.quick { vec![64] } else { vec![64, 128, 256] });
        let mut hostile = Vec::new();
        for &res in &resolutions {
            let rows = vct::bench::hostile::run(&ctx, &methods, res, &|m| bar.set_message(format!("{m}, {res}³")))
                .context("voxelizing the hostile-geometry set")?;
            hostile.extend(rows);
        }
        bar.finish_and_clear();
        println!("Hostile geometry (assets/hostile/):\n{}", vct::bench::hostile::table(&hostile));
        for f in vct::bench::stability::write(&out, &regimes, &hostile)? {
            println!("wrote {}", f.display());
        }
        return check_validation(&ctx);
    }
    let cache = out.parent().unwrap_or(Path::new(".")).join("cache");
    let mut opts = vct::bench::BenchOptions::standard(scenes, args.quick, out.clone(), cache);
    if let Some(r) = &args.res {
        opts.resolutions = r.clone();
    }
    if let Some(f) = args.frames {
        opts.frames = f;
    }
    if let Some(spp) = args.spp {
        opts.reference_spp = spp;
    }
    if args.compare_storage == OnOff::Off {
        opts.compare_storage.clear();
    }
    for &r in &opts.resolutions {
        vct::voxel::VoxelGrid::fit(&vct::scene::Aabb { min: glam::Vec3::ZERO, max: glam::Vec3::ONE }, r)?;
    }
    let bar = indicatif::ProgressBar::new_spinner();
    bar.enable_steady_tick(std::time::Duration::from_millis(200));
    let start = std::time::Instant::now();
    let results = vct::bench::run(&ctx, &opts, &|m| bar.set_message(m.to_string())).context("benchmarking")?;
    bar.finish_and_clear();
    println!(
        "{:<10} {:<12} {:>5} {:>12} {:>12} {:>8} {:>8} {:>8} {:>8}",
        "scene", "voxelizer", "N", "voxelize ms", "frame ms", "recall", "prec.", "IoU", "FLIP"
    );
    for r in &results.rows {
        println!(
            "{:<10} {:<12} {:>5} {:>12.2} {:>12.2} {:>8.4} {:>8.4} {:>8.4} {:>8.4}",
            r.scene, r.voxelizer, r.resolution, r.voxelize_ms, r.total_ms, r.recall, r.precision, r.iou, r.flip
        );
    }
    for f in vct::bench::write(&out, &results, before.as_ref())? {
        println!("wrote {}", f.display());
    }
    println!("bench took {:.0} s", start.elapsed().as_secs_f64());
    check_validation(&ctx)
}
