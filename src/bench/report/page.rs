//! The report's two pages, written from the data of [`super::Data`] alone: `README.md` (one
//! table per question, the stamp on top, the charts linked as SVG files) and `index.html` (the
//! same tables through pulldown-cmark, every chart inline as SVG; no script, and no font,
//! style or image from the network, so it works offline).
//!
//! The charts are drawn again from the data each time, so a page never shows a chart of other
//! figures than its tables.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::{keep_svg_charts, Data, SpeedRun, Stamp};
use crate::bench::accuracy::{trace_cost, AccuracyRow};
use crate::bench::charts::{self, Regime};
use crate::bench::{gi_scale, hostile, points, Results, Row};
use crate::error::{Error, Result};

/// One question the report answers: its table(s) in Markdown and its charts.
pub struct Section {
    /// The HTML anchor; a GPU section's carry `gpu-`.
    pub id: String,
    pub title: String,
    pub markdown: String,
    /// Chart files (SVG), relative to the report's folder.
    pub charts: Vec<PathBuf>,
}

/// The sections every report has, by id: the page test checks each is there and filled.
pub const SECTIONS: [&str; 10] =
    ["voxelizers", "passes", "tess-raster", "memory", "points", "gi-scale", "light", "trace", "stability", "hostile"];

/// The voxelizer that the storage modes ran with (the default one); `None` where the run
/// compared no storage modes.
fn default_voxelizer(r: &Results) -> Option<&str> {
    let stored = r.stored();
    r.rows.iter().find(|x| x.storage != stored).map(|x| x.voxelizer.as_str())
}

fn pass_ms(row: &Row, pass: &str) -> f64 {
    row.passes.iter().find(|t| t.pass == pass).map_or(0.0, |t| t.ms)
}

fn table(head: &[&str], rows: impl IntoIterator<Item = Vec<String>>) -> String {
    let mut s = format!("| {} |\n|{}\n", head.join(" | "), "---|".repeat(head.len()));
    for r in rows {
        let _ = writeln!(s, "| {} |", r.join(" | "));
    }
    s
}

fn voxelizers(r: &Results) -> String {
    let d = r.on_default_storage();
    let mut s = format!(
        "Every voxelizer on the default storage ({}): the voxelization's GPU time and the whole frame's \
         (median of the timed frames), the voxels against the exact triangle/box coverage (recall, \
         precision, IoU), and the frame's FLIP against the path-traced one-bounce reference ({} spp).\n\n",
        r.stored(),
        r.reference_spp
    );
    s += &table(
        &["scene", "voxelizer", "N", "voxelize ms", "frame ms", "recall", "precision", "IoU", "FLIP"],
        d.rows.iter().map(|x| {
            vec![
                x.scene.clone(),
                x.voxelizer.clone(),
                x.resolution.to_string(),
                format!("{:.2}", x.voxelize_ms),
                format!("{:.1}", x.total_ms),
                format!("{:.4}", x.recall),
                format!("{:.4}", x.precision),
                format!("{:.4}", x.iou),
                format!("{:.4}", x.flip),
            ]
        }),
    );
    s
}

fn passes(r: &Results) -> String {
    let d = r.on_default_storage();
    let voxelizer = default_voxelizer(r);
    let rows: Vec<&Row> = d.rows.iter().filter(|x| voxelizer.is_none_or(|v| x.voxelizer == v)).collect();
    let mut names: Vec<String> = Vec::new();
    for x in &rows {
        for t in &x.passes {
            if t.pass != "total" && !names.contains(&t.pass) {
                names.push(t.pass.clone());
            }
        }
    }
    let mut head = vec!["scene", "voxelizer", "N"];
    head.extend(names.iter().map(|n| n.as_str()));
    head.push("frame");
    let mut s =
        String::from("GPU milliseconds per pass of the default voxelizer's frame (median of the timed frames).\n\n");
    s += &table(
        &head,
        rows.iter().map(|x| {
            let mut v = vec![x.scene.clone(), x.voxelizer.clone(), x.resolution.to_string()];
            v.extend(names.iter().map(|n| format!("{:.2}", pass_ms(x, n))));
            v.push(format!("{:.1}", x.total_ms));
            v
        }),
    );
    s
}

fn tess_raster(r: &Results) -> String {
    let d = r.on_default_storage();
    let pairs: Vec<Vec<String>> = d
        .rows
        .iter()
        .filter(|t| t.voxelizer == "tess")
        .filter_map(|t| {
            let m = d
                .rows
                .iter()
                .find(|x| x.voxelizer == "raster-msaa" && x.scene == t.scene && x.resolution == t.resolution)?;
            Some(vec![
                t.scene.clone(),
                t.resolution.to_string(),
                format!("{:.2}", t.voxelize_ms),
                format!("{:.2}", m.voxelize_ms),
                format!("{:.2}", t.voxelize_ms / m.voxelize_ms.max(1e-9)),
            ])
        })
        .collect();
    let mut s = String::from(
        "Tessellated voxelization's time over rasterized (4× MSAA) voxelization's, as the thesis' Table 5.2 \
         compares them.\n\n",
    );
    s += &table(&["scene", "N", "tess ms", "raster ms", "tess / raster"], pairs);
    s += "\nVoxelization time against the triangle count (the scene's triangles split in four, again and again):\n\n";
    s += &table(
        &["scene", "voxelizer", "triangles", "voxelize ms"],
        r.triangle_sweep.iter().map(|t| {
            vec![t.scene.clone(), t.voxelizer.clone(), t.triangles.to_string(), format!("{:.2}", t.voxelize_ms)]
        }),
    );
    s
}

fn memory(r: &Results) -> String {
    let voxelizer = default_voxelizer(r);
    let rows = r.rows.iter().filter(|x| voxelizer.is_some_and(|v| x.voxelizer == v));
    let mut s = String::from(
        "The default voxelizer on each storage the device offers: the volume's GPU memory (voxel textures, \
         radiance, lists) beside the bounding cube's at the same voxel size, the frame's time and its FLIP.\n\n",
    );
    s += &table(
        &["scene", "storage", "N", "grid", "memory MiB", "bounding cube MiB", "frame ms", "FLIP"],
        rows.map(|x| {
            vec![
                x.scene.clone(),
                x.storage.clone(),
                x.resolution.to_string(),
                x.dims.map(|d| d.to_string()).join("×"),
                format!("{:.1}", x.memory_mib),
                format!("{:.1}", x.cube_memory_mib),
                format!("{:.1}", x.total_ms),
                format!("{:.4}", x.flip),
            ]
        }),
    );
    s
}

/// The judged regions' ratio range of a row, e.g. `0.93–1.08`.
fn region_range(r: &AccuracyRow) -> String {
    let judged = r.regions.iter().filter(|g| g.judged).map(|g| g.ratio);
    let (lo, hi) = judged.fold((f32::INFINITY, f32::NEG_INFINITY), |(l, h), x| (l.min(x), h.max(x)));
    if lo.is_finite() {
        format!("{lo:.2}–{hi:.2}")
    } else {
        "–".into()
    }
}

/// This tree against the landed main (`scripts/speed-vs-main.sh`): per case, each binary's
/// median over its rounds of the frame's median GPU time, their ratio, and for this tree the
/// cone trace's and the mip filter's shares of its frame; the runs' wall clocks beside (they
/// include starting up and llvmpipe compiling each pipeline at its first dispatch).
fn speed(runs: &[SpeedRun]) -> String {
    fn median(mut v: Vec<f64>) -> f64 {
        v.sort_by(f64::total_cmp);
        match v.len() {
            0 => 0.0,
            n if n % 2 == 0 => 0.5 * (v[n / 2 - 1] + v[n / 2]),
            n => v[n / 2],
        }
    }
    let mut cases: Vec<&str> = Vec::new();
    for r in runs {
        if !cases.contains(&r.case.as_str()) {
            cases.push(&r.case);
        }
    }
    let of = |case: &str, binary: &str, f: &dyn Fn(&SpeedRun) -> f64| {
        median(runs.iter().filter(|r| r.case == case && r.binary == binary).map(f).collect())
    };
    let rounds = runs.iter().map(|r| r.round).max().unwrap_or(0);
    let mut s = format!(
        "This tree (`new`) against the landed main (`main`), both built on this machine and run alternately, \
         {rounds} rounds a case (`scripts/speed-vs-main.sh`): the median GPU time of a frame (over each run's \
         frames; the first frame, which also pays for llvmpipe compiling each pipeline, counts only in the \
         run's wall clock), and the ratio main / new. A share is \"–\" where the pass ran only in the frames \
         that built the volume (a still view keeps it).\n\n"
    );
    s += &table(
        &[
            "case",
            "main frame ms",
            "new frame ms",
            "main / new",
            "new: trace",
            "new: mip filter",
            "main run s",
            "new run s",
        ],
        cases.iter().map(|c| {
            let (b, n) = (of(c, "base", &|r| r.pass_ms("total")), of(c, "new", &|r| r.pass_ms("total")));
            // A pass that ran only in some frames (the volume's passes, where a still view keeps
            // the volume) has its median over those: no share of the frame's median.
            let share = |pass: &str| {
                let ms = of(c, "new", &|r| r.pass_ms(pass));
                if ms <= n {
                    format!("{:.1}%", 100.0 * ms / n.max(1e-9))
                } else {
                    "–".into()
                }
            };
            vec![
                c.to_string(),
                format!("{b:.1}"),
                format!("{n:.1}"),
                format!("{:.2}×", b / n.max(1e-9)),
                share("trace"),
                share("filter"),
                format!("{:.1}", of(c, "base", &|r| r.run_wall_ms) / 1e3),
                format!("{:.1}", of(c, "new", &|r| r.run_wall_ms) / 1e3),
            ]
        }),
    );
    s
}

/// The quality presets where the run measured them (`render::Quality`: rows "default" and
/// "quality NAME" at the grid that has both), fastest first, with the flat-wall pattern.
fn presets(all: &[AccuracyRow]) -> String {
    let mut rows: Vec<&AccuracyRow> = all
        .iter()
        .filter(|r| r.pattern.is_some() && (r.variant == "default" || r.variant.starts_with("quality ")))
        .collect();
    if rows.is_empty() {
        return String::new();
    }
    rows.sort_by(|a, b| a.scene.cmp(&b.scene).then(a.frame_ms.total_cmp(&b.frame_ms)));
    let mut s = String::from(
        "\nThe quality presets (`--quality`), each a point of the chart below: the frame's GPU time beside its \
         accuracy, and the flat-wall pattern, the frame's RMS departure on the flat regions from the converged \
         frame of the same settings (16 frames with the cone set turned further, averaged), a share of the \
         regions' mean light. `high` traces the whole set at every pixel, four times the cones of `default`: \
         the scale the others are read against.\n\n",
    );
    s += &table(
        &["scene", "N", "preset", "frame ms", "FLIP", "regions' indirect ratio", "flat-wall pattern"],
        rows.iter().map(|r| {
            vec![
                r.scene.clone(),
                r.resolution.to_string(),
                r.variant.trim_start_matches("quality ").to_string(),
                format!("{:.1}", r.frame_ms),
                format!("{:.4}", r.flip),
                region_range(r),
                r.pattern.map_or("–".into(), |p| format!("{:.2}%", 100.0 * p)),
            ]
        }),
    );
    s
}

fn light(all: &[AccuracyRow]) -> String {
    let rows: Vec<AccuracyRow> = all.iter().filter(|r| r.variant == "default").cloned().collect();
    let rows = &rows[..];
    let mut s = String::from(
        "The default model's frame against a path-traced reference of the same scene and bounces: LDR-FLIP \
         (lower is better), FLIP of the direct light alone for scale, the mean radiance over the reference's, \
         and the range of the judged regions' indirect light over the reference's.\n\n",
    );
    s += &table(
        &[
            "scene",
            "N",
            "frame ms",
            "memory MiB",
            "FLIP",
            "direct-only FLIP",
            "mean / reference",
            "regions' indirect ratio",
            "reference noise",
        ],
        rows.iter().map(|r| {
            vec![
                r.scene.clone(),
                r.resolution.to_string(),
                format!("{:.1}", r.frame_ms),
                format!("{:.1}", r.memory_mib),
                format!("{:.4}", r.flip),
                format!("{:.4}", r.flip_direct_only),
                format!("{:.3}", r.mean_ratio),
                region_range(r),
                format!("{:.2}%", 100.0 * r.reference_noise),
            ]
        }),
    );
    // Each region's ratio at each resolution, one row a scene and region.
    let mut resolutions: Vec<u32> = rows.iter().map(|r| r.resolution).collect();
    resolutions.sort_unstable();
    resolutions.dedup();
    let mut keys: Vec<(String, String)> = Vec::new();
    for r in rows {
        for g in &r.regions {
            let k = (r.scene.clone(), g.region.clone());
            if !keys.contains(&k) {
                keys.push(k);
            }
        }
    }
    let heads: Vec<String> = resolutions.iter().map(|n| format!("{n}³")).collect();
    let mut head = vec!["scene", "region"];
    head.extend(heads.iter().map(|h| h.as_str()));
    s += "\nEach region's indirect light over the reference's (in brackets: a region the reference leaves \
          too dark to judge):\n\n";
    s += &table(
        &head,
        keys.iter().map(|(scene, region)| {
            let mut v = vec![scene.clone(), region.clone()];
            for n in &resolutions {
                let g = rows
                    .iter()
                    .find(|r| &r.scene == scene && r.resolution == *n)
                    .and_then(|r| r.regions.iter().find(|g| &g.region == region));
                v.push(match g {
                    Some(g) if g.judged => format!("{:.2}", g.ratio),
                    Some(g) => format!("({:.2})", g.ratio),
                    None => "–".into(),
                });
            }
            v
        }),
    );
    s + &presets(all)
}

/// The images the indirect-light run kept (`indirect-*.png`: the reference's indirect light
/// beside the renderer's; `flip-*.png`: the FLIP map), linked in the order of their names.
fn light_images(dir: &Path, d: &Path) -> Result<String> {
    let mut names: Vec<String> = std::fs::read_dir(d)
        .map_err(|source| Error::Io { path: d.to_path_buf(), source })?
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".png") && (n.starts_with("indirect-") || n.starts_with("flip-")))
        .collect();
    names.sort_by_key(|n| {
        (n.trim_start_matches("indirect-").trim_start_matches("flip-").to_string(), n.starts_with("flip-"))
    });
    let rel = d.strip_prefix(dir).unwrap_or(d);
    let mut s = String::new();
    if !names.is_empty() {
        s += "\nThe indirect light alone, the reference's (left) beside vct's (right), both scaled by four and \
              tone-mapped alike, and the FLIP map of the whole frame:\n\n";
    }
    for n in names {
        let _ = writeln!(s, "![{}]({}/{n})\n", n.trim_end_matches(".png"), rel.display());
    }
    Ok(s)
}

/// A regime's points as a table: x down, one column a series; a regime of many series (the
/// flicker's cases over frames) as one row a series, with its mean and its most over x.
fn regime_table(g: &Regime) -> String {
    let table = if g.series.len() > 6 {
        let rows = g.series.iter().map(|s| {
            let ys: Vec<f64> = s.points.iter().map(|p| p.1).filter(|y| y.is_finite()).collect();
            let mean = ys.iter().sum::<f64>() / ys.len().max(1) as f64;
            let most = ys.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            vec![s.label.clone(), format!("{mean:.4}"), format!("{most:.4}")]
        });
        table(&["case", "mean", &format!("most over {}", g.x)], rows)
    } else {
        let mut xs: Vec<f64> = g.series.iter().flat_map(|s| s.points.iter().map(|p| p.0)).collect();
        xs.sort_by(f64::total_cmp);
        xs.dedup();
        let mut head = vec![g.x.as_str()];
        head.extend(g.series.iter().map(|s| s.label.as_str()));
        let rows = xs.iter().map(|&x| {
            // Shortest text that reads back as the f32 the x was measured at (0.2, not 0.2000000029...).
            let mut v = vec![format!("{}", x as f32)];
            for s in &g.series {
                v.push(s.points.iter().find(|p| p.0 == x).map_or("–".into(), |p| format!("{:.4}", p.1)));
            }
            v
        });
        table(&head, rows)
    };
    format!("**{}** ({})\n\n{table}", g.title, g.y)
}

fn svg_of(dir: &Path, stem: &str) -> Option<PathBuf> {
    let p = dir.join(format!("{stem}.svg"));
    p.is_file().then_some(p)
}

/// The sections of one run's data in `dir/sub` (`data` or `gpu`), drawing their charts there.
pub fn sections(dir: &Path, sub: &str, data: &Data) -> Result<Vec<Section>> {
    let root = dir.join(sub);
    let prefix = if sub == "gpu" { "gpu-" } else { "" };
    let rel = |p: PathBuf| p.strip_prefix(dir).map(Path::to_path_buf).unwrap_or(p);
    let mut out = Vec::new();
    let mut push = |id: &str, title: &str, markdown: String, charts: Vec<Option<PathBuf>>| {
        out.push(Section {
            id: format!("{prefix}{id}"),
            title: title.into(),
            markdown,
            charts: charts.into_iter().flatten().map(rel).collect(),
        })
    };
    if let Some(r) = &data.sweep {
        let d = root.join("sweep");
        crate::bench::draw(&d, r, None)?;
        push(
            "voxelizers",
            "How fast is each voxelizer, and how exact?",
            voxelizers(r),
            vec![svg_of(&d, "speed_vs_accuracy"), svg_of(&d, "voxelize_time")],
        );
        push("passes", "Where does a frame's time go?", passes(r), vec![svg_of(&d, "passes_stacked")]);
        push(
            "tess-raster",
            "Tessellation against rasterization",
            tess_raster(r),
            vec![svg_of(&d, "tess_over_raster"), svg_of(&d, "cost_vs_triangles")],
        );
        push(
            "memory",
            "What does the volume cost in memory, and what does that buy?",
            memory(r),
            vec![svg_of(&d, "storage_memory_vs_flip"), svg_of(&d, "storage_time_vs_flip")],
        );
        push("points", "The point voxelizer over its density", points::summary(r), vec![svg_of(&d, "points_density")]);
        push(
            "gi-scale",
            "Indirect light traced at a reduced resolution",
            gi_scale::summary(r),
            vec![svg_of(&d, "gi_scale")],
        );
    }
    if !data.accuracy.is_empty() {
        let d = root.join("accuracy");
        std::fs::create_dir_all(&d).map_err(|source| Error::Io { path: d.clone(), source })?;
        // The chart: each scene's default at each grid and the presets, not the trace's parts.
        let charted: Vec<AccuracyRow> =
            data.accuracy.iter().filter(|r| !r.variant.starts_with("trace: ")).cloned().collect();
        charts::draw_accuracy(&d, &charted, charts::Cost::Time)?;
        let md = light(&data.accuracy) + &light_images(dir, &d)?;
        push("light", "Does the indirect light agree with the path tracer?", md, vec![svg_of(&d, "accuracy")]);
        let breakdown = trace_cost::table(&data.accuracy);
        if !breakdown.is_empty() {
            trace_cost::draw(&d, &data.accuracy)?;
            push("trace", "Where does a pixel's time go?", breakdown, vec![svg_of(&d, "trace")]);
        }
    }
    if !data.speed.is_empty() {
        push("speed", "Is it faster than the landed main?", speed(&data.speed), vec![]);
    }
    if !data.stability.is_empty() {
        let d = root.join("stability");
        let mut md = String::from(
            "Each regime drives one method towards where it fails, with its guard off and on (docs/design/stability.md).\n\n",
        );
        let mut figures = Vec::new();
        for g in &data.stability {
            charts::draw_regime(&d, g)?;
            md += &regime_table(g);
            md.push('\n');
            figures.push(svg_of(&d, &format!("stability_{}", g.name)));
        }
        push("stability", "Where does each method fail?", md, figures);
    }
    if !data.hostile.is_empty() {
        let md = format!(
            "Every voxelizer on meshes made to break voxelizers (assets/hostile/), against the exact coverage.\n\n{}",
            hostile::table(&data.hostile)
        );
        push("hostile", "Hostile geometry", md, vec![]);
    }
    keep_svg_charts(&root)?;
    Ok(out)
}

fn stamp_table(s: &Stamp) -> String {
    table(
        &["", ""],
        [
            vec!["commit".into(), format!("`{}`", s.commit)],
            vec!["date (UTC)".into(), s.date.clone()],
            vec!["device".into(), s.device.clone()],
            vec!["driver".into(), s.driver.clone()],
            vec!["host".into(), format!("{}, {} logical cores", s.cpu, s.cores)],
            vec!["suite".into(), format!("{} ({:.0} min)", s.suite, s.seconds / 60.0)],
            vec!["command".into(), format!("`{}`", s.command)],
        ],
    )
}

/// A GPU run's stamp: its own, or the device and driver its sweep recorded.
fn gpu_stamp(data: &Data) -> String {
    match (&data.stamp, &data.sweep) {
        (Some(s), _) => stamp_table(s),
        (None, Some(r)) => {
            table(&["", ""], [vec!["device".into(), r.device.clone()], vec!["driver".into(), r.driver.clone()]])
        }
        (None, None) => String::new(),
    }
}

/// The report's Markdown: stamp, contents, then every section with its charts linked.
fn markdown(head: &str, main: &[Section], gpu_head: &str, gpu: &[Section]) -> String {
    let mut s = String::from(head);
    for (level, list) in [("##", main), ("###", gpu)] {
        if level == "###" && !gpu.is_empty() {
            s += gpu_head;
        }
        for x in list {
            let _ = write!(s, "\n{level} {}\n\n{}\n", x.title, x.markdown);
            for c in &x.charts {
                let _ = writeln!(s, "![{}]({})\n", c.file_stem().unwrap_or_default().to_string_lossy(), c.display());
            }
        }
    }
    s
}

const STYLE: &str = "body{font-family:sans-serif;max-width:1200px;margin:2em auto;padding:0 1em;color:#222}\
table{border-collapse:collapse;margin:.5em 0 1em;font-size:.9em}th,td{border:1px solid #ccc;padding:.2em .5em;\
text-align:right}th{background:#f2f2f2}td:first-child,td:nth-child(2){text-align:left}\
figure{margin:1em 0}figure svg{max-width:100%;height:auto}figcaption{font-size:.8em;color:#666}\
code{background:#f4f4f4;padding:0 .2em}nav li{margin:.1em 0}";

fn html_of(markdown: &str) -> String {
    let mut html = String::new();
    let parser = pulldown_cmark::Parser::new_ext(markdown, pulldown_cmark::Options::ENABLE_TABLES);
    pulldown_cmark::html::push_html(&mut html, parser);
    html
}

/// A chart's SVG, ready to inline: its XML prolog dropped, sized by its view box.
fn inline_svg(path: &Path) -> Result<String> {
    let text = std::fs::read_to_string(path).map_err(|source| Error::Io { path: path.to_path_buf(), source })?;
    let start = text.find("<svg").ok_or_else(|| Error::input(path, "not an SVG image"))?;
    Ok(text[start..].to_string())
}

fn html(dir: &Path, title: &str, stamp: &str, main: &[Section], gpu_head: &str, gpu: &[Section]) -> Result<String> {
    let esc = |t: &str| t.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;");
    let mut s = format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{}</title><style>{STYLE}</style></head><body>\n",
        esc(title)
    );
    s += &html_of(stamp);
    s += "<nav><ul>\n";
    for x in main.iter().chain(gpu) {
        let _ = writeln!(s, "<li><a href=\"#{}\">{}</a></li>", x.id, esc(&x.title));
    }
    s += "</ul></nav>\n";
    for (level, list) in [(2, main), (3, gpu)] {
        if level == 3 && !gpu.is_empty() {
            s += &html_of(gpu_head);
        }
        for x in list {
            let _ = writeln!(s, "<section id=\"{}\"><h{level}>{}</h{level}>", x.id, esc(&x.title));
            s += &html_of(&x.markdown);
            for c in &x.charts {
                let name = c.file_stem().unwrap_or_default().to_string_lossy();
                let _ = writeln!(
                    s,
                    "<figure class=\"chart\" id=\"chart-{}{name}\">{}<figcaption>{name}</figcaption></figure>",
                    if level == 3 { "gpu-" } else { "" },
                    inline_svg(&dir.join(c))?
                );
            }
            s += "</section>\n";
        }
    }
    s += "</body></html>\n";
    Ok(s)
}

/// Writes `dir/README.md` and `dir/index.html` from the data in `dir/data/` (and `dir/gpu/`,
/// where present); returns the two files.
pub fn write(dir: &Path) -> Result<Vec<PathBuf>> {
    let data = Data::read(&dir.join("data"))?;
    if data.is_empty() {
        return Err(Error::input(dir.join("data"), "no report data here: run `vct bench --report DIR` first"));
    }
    let main = sections(dir, "data", &data)?;
    let gpu_data = Data::read(&dir.join("gpu"))?;
    let gpu = if gpu_data.is_empty() { Vec::new() } else { sections(dir, "gpu", &gpu_data)? };
    let title = "vct: speed and accuracy";
    let mut head = format!(
        "# {title}\n\nGenerated by `vct bench --report` from the data under [data/](data/); every figure in it \
         comes from the run stamped here. Accuracy is agreement with an exact reference: the exact \
         triangle/box coverage for voxels, a path-traced image for light. The page with every chart inline: \
         [index.html](index.html).\n\n"
    );
    if let Some(s) = &data.stamp {
        head += &stamp_table(s);
    }
    let gpu_head = format!(
        "\n## On a GPU\n\nFrom `scripts/device-bench.sh` on a lent GPU machine, its data under [gpu/](gpu/).\n\n{}",
        gpu_stamp(&gpu_data)
    );
    let md = markdown(&head, &main, &gpu_head, &gpu);
    let page = html(dir, title, &head, &main, &gpu_head, &gpu)?;
    let put = |name: &str, text: &str| -> Result<PathBuf> {
        let p = dir.join(name);
        std::fs::write(&p, text).map_err(|source| Error::Io { path: p.clone(), source })?;
        Ok(p)
    };
    Ok(vec![put("README.md", &md)?, put("index.html", &page)?])
}
