//! `vct bench --accuracy`: the GI model against path-traced references (docs/design/measurement.md): the scenes' own model, the study's variants, the
//! layouts (warped grids, clipmaps) with their lattice spreads and pans, and the per-cone split.

use std::path::Path;

use anyhow::{Context as _, Result};
use vct::gpu::Context;
use vct::scene::Scene;

use crate::bench_args::BenchArgs;
use crate::common::check_validation;

/// Pixels of each region the per-cone comparison traces (its reference draws `--spp` directions
/// at each): a region's mean light through a cell then has the noise of 256 × spp / cones draws.
const PER_CONE_PIXELS: usize = 256;

/// `vct bench --accuracy`: the GI model against path-traced references.
pub fn accuracy(
    ctx: &std::sync::Arc<Context>,
    args: &BenchArgs,
    scenes: Vec<(String, Scene)>,
    out: &Path,
) -> Result<()> {
    use vct::bench::accuracy;
    let resolutions = args.res.clone().unwrap_or(if args.quick { vec![32] } else { vec![128] });
    let spp = args.spp.unwrap_or(if args.quick { 16 } else { 1024 });
    let frames = args.frames.unwrap_or(if args.quick { 1 } else { 3 });
    let bar = indicatif::ProgressBar::new_spinner();
    bar.enable_steady_tick(std::time::Duration::from_millis(200));
    let progress = |m: &str| bar.set_message(m.to_string());
    let cache = out.parent().unwrap_or(Path::new(".")).join("cache");
    let start = std::time::Instant::now();
    let mut rows = Vec::new();
    let mut pans: Vec<String> = Vec::new();
    let mut cones = Vec::new();
    for (name, mut scene) in scenes {
        if let Some(b) = args.bounces {
            scene.settings.gi.bounces = b;
        }
        let default = scene.settings.gi.clone();
        let ref_bounces = args.ref_bounces.unwrap_or(default.bounces);
        let judged = accuracy::Judged::new(&name, scene, ref_bounces, spp, &cache, &progress)
            .with_context(|| format!("tracing the {name} references"))?;
        let variants = if args.study {
            accuracy::study_variants(&default)
                .into_iter()
                .map(|mut v| {
                    if args.bounces.is_some() {
                        v.gi.bounces = default.bounces;
                    }
                    v
                })
                .filter(|v| args.only.as_ref().is_none_or(|t| v.name.contains(t.as_str())))
                .collect()
        } else {
            let mut v = vec![accuracy::Variant::default_of(&default)];
            if args.layouts {
                let slopes = args.warp_slopes.clone().unwrap_or(vec![vct::voxel::warp::THESIS_END_SLOPE]);
                v.extend(slopes.into_iter().map(|s| accuracy::Variant::warped(&default, s)));
                let ratios = args.perspective_ratios.clone().unwrap_or(vec![vct::voxel::perspective::DEFAULT_RATIO]);
                v.extend(
                    ratios
                        .into_iter()
                        .map(|r| accuracy::Variant::warped_by(&default, vct::voxel::warp::WarpChoice::Perspective(r))),
                );
                let clips = args.clipmaps.clone().unwrap_or_default();
                v.extend(clips.into_iter().map(|(l, n)| accuracy::Variant::clipped(&default, l, n)));
            }
            v
        };
        for &res in &resolutions {
            let direct = accuracy::direct_frame(ctx, &judged, res)?;
            if args.per_cone {
                progress(&format!("{name} {res}³ cone by cone"));
                let rows = accuracy::per_cone::measure(ctx, &judged, &direct, &default, res, PER_CONE_PIXELS, spp)
                    .with_context(|| format!("measuring {name} at {res}³ cone by cone"))?;
                println!("{}", accuracy::per_cone::table(&rows));
                cones.extend(rows);
            }
            for v in &variants {
                // A clipmap's voxels are its own (LEVELSxRES), whatever `--res` says: measured once.
                if v.clipmap.is_some() && res != resolutions[0] {
                    continue;
                }
                progress(&format!("{name} {res}³ {}", v.name));
                let mut row = accuracy::measure(ctx, &judged, &direct, v, res, frames)
                    .with_context(|| format!("measuring {name} {} at {res}³", v.name))?;
                if args.pattern {
                    progress(&format!("{name} {res}³ {}: the flat-wall pattern", v.name));
                    row.pattern = Some(
                        accuracy::pattern::measure(ctx, &judged, v, res)
                            .with_context(|| format!("measuring {name} {}'s pattern at {res}³", v.name))?,
                    );
                }
                let regions = accuracy::region_log_error_text(&row.regions);
                let judged_ratios = row.regions.iter().filter(|g| g.judged).map(|g| g.ratio);
                let (lo, hi) = judged_ratios.fold((f32::MAX, f32::MIN), |(a, b), r| (a.min(r), b.max(r)));
                let pattern = row.pattern.map_or(String::new(), |p| format!("  pattern {:.2}%", 100.0 * p));
                println!(
                    "{:<20} {:<34} {:>4}³ {:>9.1} ms {:>7.1} MiB  FLIP {:.4} (direct only {:.4})  mean {:.3}  regions |ln| {regions} ({lo:.2}..{hi:.2}){pattern}",
                    name, v.name, res, row.frame_ms, row.memory_mib, row.flip, row.flip_direct_only, row.mean_ratio
                );
                if let (Some(k), None) = (args.lattices, v.warp) {
                    progress(&format!("{name} {res}³ {} on {k} lattices", v.name));
                    accuracy::measure_lattices(ctx, &judged, &direct, v, res, k, &mut row)
                        .with_context(|| format!("measuring {name} {} at {res}³ on other lattices", v.name))?;
                    let l = row.lattices.as_ref().expect("just measured");
                    println!(
                        "{:<20} {:<34} {:>4}³ on {k} lattices: FLIP {:.4} / {:.4} / {:.4}, mean {:.3} / {:.3} / {:.3}",
                        name,
                        v.name,
                        res,
                        l.flip[0],
                        l.flip[1],
                        l.flip[2],
                        l.mean_ratio[0],
                        l.mean_ratio[1],
                        l.mean_ratio[2]
                    );
                }
                if let Some(frames) = args.pan_frames {
                    let (mean, max) = accuracy::pan_flip(ctx, &judged, v, res, frames)
                        .with_context(|| format!("panning {name} {} at {res}³", v.name))?;
                    println!(
                        "{:<20} {:<34} {:>4}³ pan: adjacent-frame FLIP mean {mean:.4}, max {max:.4}",
                        name, v.name, res
                    );
                    pans.push(format!("{name},{},{res},{frames},{mean:.5},{max:.5}", v.name));
                }
                rows.push(row);
            }
        }
    }
    bar.finish_and_clear();
    let dir = out.join("accuracy");
    for f in accuracy::write(&dir, &rows, args.study)? {
        println!("wrote {}", f.display());
    }
    if !cones.is_empty() {
        let path = dir.join("per-cone.csv");
        std::fs::write(&path, accuracy::per_cone::csv(&cones))
            .with_context(|| format!("writing {}", path.display()))?;
        println!("wrote {}", path.display());
    }
    if !pans.is_empty() {
        let path = dir.join("pan.csv");
        let csv =
            format!("scene,variant,resolution,frames,adjacent_flip_mean,adjacent_flip_max\n{}\n", pans.join("\n"));
        std::fs::write(&path, csv).with_context(|| format!("writing {}", path.display()))?;
        println!("wrote {}", path.display());
    }
    println!("{}", accuracy::summary(&rows));
    println!("accuracy bench took {:.0} s", start.elapsed().as_secs_f64());
    check_validation(ctx)
}
