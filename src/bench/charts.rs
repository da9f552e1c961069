//! The benchmark charts (plotters; each as PNG and SVG): voxelization time tess vs raster by
//! resolution (the thesis' Table 5.2 / Fig. 5.6), per-pass stacked bars (Fig. 5.2), speed
//! against accuracy with the Pareto front marked, and cost against triangle count.

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::prelude::*;

use super::accuracy::AccuracyRow;
use super::{Results, Row};
use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

const FONT_PATHS: [&str; 2] =
    ["/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", "/usr/share/fonts/dejavu/DejaVuSans.ttf"];

/// Registers DejaVu Sans as "sans-serif" for chart text (Debian/Ubuntu: fonts-dejavu-core).
pub(crate) fn ensure_font() -> Result<()> {
    static FONT: std::sync::OnceLock<std::result::Result<(), String>> = std::sync::OnceLock::new();
    FONT.get_or_init(|| {
        let bytes = FONT_PATHS.iter().find_map(|p| std::fs::read(p).ok()).ok_or_else(|| {
            format!("no chart font: install fonts-dejavu-core (looked for {})", FONT_PATHS.join(", "))
        })?;
        let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
        plotters::style::register_font("sans-serif", FontStyle::Normal, bytes)
            .map_err(|_| "invalid chart font".to_string())
    })
    .clone()
    .map_err(|m| Error::input(FONT_PATHS[0], m))
}

const PALETTE: [RGBColor; 6] = [
    RGBColor(214, 39, 40),
    RGBColor(31, 119, 180),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(140, 86, 75),
];

fn colour_of(voxelizer: &str) -> RGBColor {
    match voxelizer {
        "tess" => PALETTE[0],
        "raster-msaa" => PALETTE[1],
        "raster-none" => PALETTE[2],
        "points" => PALETTE[4],
        _ => PALETTE[3],
    }
}

/// One curve: a label and its (x, y) points.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Regime {
    pub name: String,
    pub title: String,
    pub x: String,
    pub y: String,
    pub log_x: bool,
    /// A logarithmic y axis (every value must be positive).
    pub log_y: bool,
    pub series: Vec<Series>,
}

pub(crate) type DrawResult<DB> = std::result::Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// The finite values' range, padded by a tenth of its span (at least 1e-3 each side); 0..1
/// where no value is finite. Plotters searches for ticks forever in an infinite range.
fn lin_range(values: impl Iterator<Item = f64>) -> std::ops::Range<f64> {
    let (lo, hi) =
        values.filter(|v| v.is_finite()).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(v), h.max(v)));
    if !lo.is_finite() {
        return 0.0..1.0;
    }
    let pad = ((hi - lo) * 0.1).max(1e-3);
    lo - pad..hi + pad
}

/// The positive finite values' range, widened ×0.7 and ×1.4 for a log axis; 0.1..1 where there
/// is none.
fn log_range(values: impl Iterator<Item = f64>) -> std::ops::Range<f64> {
    let (lo, hi) =
        values.filter(|v| *v > 0.0 && v.is_finite()).fold((f64::INFINITY, 0.0f64), |(l, h), v| (l.min(v), h.max(v)));
    if lo.is_finite() {
        lo * 0.7..hi * 1.4
    } else {
        0.1..1.0
    }
}

fn voxelize_time<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, r: &Results) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    let res: Vec<u32> = {
        let mut v: Vec<u32> = r.rows.iter().map(|x| x.resolution).collect();
        v.sort();
        v.dedup();
        v
    };
    let y = log_range(r.rows.iter().map(|x| x.voxelize_ms));
    let mut chart = ChartBuilder::on(&root)
        .caption(format!("Voxelization GPU time ({})", r.device), ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(0f64..(res.len() as f64 - 0.5).max(0.5), y.log_scale())?;
    chart
        .configure_mesh()
        .x_desc("voxel resolution N")
        .y_desc("ms (log)")
        .x_labels(res.len().max(1))
        .x_label_formatter(&|x| res.get(x.round() as usize).map(|n| format!("{n}³")).unwrap_or_default())
        .draw()?;
    let mut series: Vec<(String, String)> = r.rows.iter().map(|x| (x.scene.clone(), x.voxelizer.clone())).collect();
    series.sort();
    series.dedup();
    for (i, (scene, vox)) in series.iter().enumerate() {
        let pts: Vec<(f64, f64)> = r
            .rows
            .iter()
            .filter(|x| &x.scene == scene && &x.voxelizer == vox)
            .map(|x| (res.iter().position(|n| *n == x.resolution).unwrap_or(0) as f64, x.voxelize_ms))
            .collect();
        let c = colour_of(vox);
        let style = if i % 2 == 0 { c.stroke_width(2) } else { c.stroke_width(1) };
        chart
            .draw_series(LineSeries::new(pts.clone(), style))?
            .label(format!("{scene} {vox}"))
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], c));
        chart.draw_series(pts.iter().map(|p| Circle::new(*p, 3, c.filled())))?;
    }
    chart.configure_series_labels().background_style(WHITE.mix(0.8)).border_style(BLACK).draw()?;
    root.present()
}

const PASSES: [&str; 7] = ["voxelize", "shadow map", "inject", "filter", "gbuffer", "shade", "tonemap"];

fn passes_stacked<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, r: &Results) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    let rows: Vec<&Row> = r.rows.iter().collect();
    let top = rows
        .iter()
        .map(|x| x.passes.iter().filter(|t| t.pass != "total").map(|t| t.ms).sum::<f64>())
        .fold(1.0, f64::max)
        * 1.1;
    let mut chart = ChartBuilder::on(&root)
        .caption("GPU time per pass", ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(-0.5f64..rows.len() as f64 - 0.5, 0f64..top)?;
    chart
        .configure_mesh()
        .y_desc("ms")
        .x_labels(rows.len().max(1))
        .x_label_style(("sans-serif", 10))
        .x_desc("scene, voxelizer, N")
        .x_label_formatter(&|x| {
            rows.get(x.round() as usize)
                .map(|r| {
                    format!(
                        "{} {} {}",
                        &r.scene[..r.scene.len().min(3)],
                        r.voxelizer.trim_start_matches("raster-"),
                        r.resolution
                    )
                })
                .unwrap_or_default()
        })
        .draw()?;
    for (k, pass) in PASSES.iter().enumerate() {
        let c = PALETTE[k % PALETTE.len()].mix(if k >= PALETTE.len() { 0.5 } else { 1.0 });
        let bars: Vec<Rectangle<(f64, f64)>> = rows
            .iter()
            .enumerate()
            .map(|(i, row)| {
                let below: f64 = PASSES[..k]
                    .iter()
                    .map(|p| row.passes.iter().find(|t| t.pass == *p).map(|t| t.ms).unwrap_or(0.0))
                    .sum();
                let h = row.passes.iter().find(|t| t.pass == *pass).map(|t| t.ms).unwrap_or(0.0);
                Rectangle::new([(i as f64 - 0.35, below), (i as f64 + 0.35, below + h)], c.filled())
            })
            .collect();
        chart
            .draw_series(bars)?
            .label(*pass)
            .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 12, y + 5)], c.filled()));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()?;
    root.present()
}

/// Indices of the Pareto-optimal points: no other point is both faster and at least as good.
pub fn pareto(points: &[(f64, f64)], higher_is_better: bool) -> Vec<usize> {
    let better = |a: f64, b: f64| if higher_is_better { a >= b } else { a <= b };
    let mut front: Vec<usize> = (0..points.len())
        .filter(|&i| {
            !points.iter().enumerate().any(|(j, q)| {
                j != i && q.0 <= points[i].0 && better(q.1, points[i].1) && (q.0 < points[i].0 || q.1 != points[i].1)
            })
        })
        .collect();
    front.sort_by(|&a, &b| points[a].0.total_cmp(&points[b].0));
    front
}

fn scatter_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    r: &Results,
    title: &str,
    y_desc: &str,
    value: fn(&Row) -> f64,
    higher_is_better: bool,
) -> DrawResult<DB> {
    let pts: Vec<(f64, f64)> = r.rows.iter().map(|x| (x.total_ms, value(x))).collect();
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(log_range(pts.iter().map(|p| p.0)).log_scale(), lin_range(pts.iter().map(|p| p.1)))?;
    chart.configure_mesh().x_desc("frame GPU ms (log)").y_desc(y_desc).draw()?;
    let front = pareto(&pts, higher_is_better);
    chart
        .draw_series(LineSeries::new(front.iter().map(|&i| pts[i]), BLACK.stroke_width(1)))?
        .label("Pareto front")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], BLACK));
    let mut labels: Vec<String> = r.rows.iter().map(|x| x.voxelizer.clone()).collect();
    labels.dedup();
    labels.sort();
    labels.dedup();
    for vox in labels {
        let c = colour_of(&vox);
        chart
            .draw_series(r.rows.iter().zip(&pts).filter(|(x, _)| x.voxelizer == vox).map(|(x, p)| {
                EmptyElement::at(*p)
                    + Circle::new((0, 0), 4, c.filled())
                    + Text::new(format!("{}", x.resolution), (5, -12), ("sans-serif", 10))
            }))?
            .label(vox.clone())
            .legend(move |(x, y)| Circle::new((x + 8, y), 4, c.filled()));
    }
    chart.configure_series_labels().background_style(WHITE.mix(0.8)).border_style(BLACK).draw()
}

fn speed_vs_accuracy<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, r: &Results) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    let panels = root.split_evenly((1, 2));
    scatter_panel(&panels[0], r, "Voxel IoU against exact coverage", "IoU (higher is better)", |x| x.iou, true)?;
    scatter_panel(
        &panels[1],
        r,
        "Image FLIP against path-traced reference",
        "FLIP (lower is better)",
        |x| x.flip as f64,
        false,
    )?;
    root.present()
}

fn cost_vs_triangles<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, r: &Results) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    let t = &r.triangle_sweep;
    let mut chart = ChartBuilder::on(&root)
        .caption("Voxelization cost against triangle count", ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(
            log_range(t.iter().map(|x| x.triangles as f64)).log_scale(),
            log_range(t.iter().map(|x| x.voxelize_ms)).log_scale(),
        )?;
    chart.configure_mesh().x_desc("triangles (log)").y_desc("voxelize ms (log)").draw()?;
    let mut voxelizers: Vec<String> = t.iter().map(|x| x.voxelizer.clone()).collect();
    voxelizers.sort();
    voxelizers.dedup();
    for vox in voxelizers {
        let c = colour_of(&vox);
        let pts: Vec<(f64, f64)> =
            t.iter().filter(|x| x.voxelizer == vox).map(|x| (x.triangles as f64, x.voxelize_ms)).collect();
        chart
            .draw_series(LineSeries::new(pts.clone(), c.stroke_width(2)))?
            .label(vox)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], c));
        chart.draw_series(pts.iter().map(|p| Circle::new(*p, 3, c.filled())))?;
    }
    chart.configure_series_labels().background_style(WHITE.mix(0.8)).border_style(BLACK).draw()?;
    root.present()
}

type Chart = fn(&Path, &Results) -> std::result::Result<(), String>;

macro_rules! both_backends {
    ($f:ident, $w:expr, $h:expr) => {
        |path: &Path, r: &Results| -> std::result::Result<(), String> {
            $f(BitMapBackend::new(&path.with_extension("png"), ($w, $h)).into_drawing_area(), r)
                .map_err(|e| e.to_string())?;
            $f(SVGBackend::new(&path.with_extension("svg"), ($w, $h)).into_drawing_area(), r).map_err(|e| e.to_string())
        }
    };
}

/// Draws the charts into `dir` (the tess/raster ratio beside `before`'s, where given); returns
/// the files written.
pub fn draw_all(dir: &Path, all: &Results, before: Option<&Results>) -> Result<Vec<PathBuf>> {
    ensure_font()?;
    // The voxelizer charts over the default storage; the storage charts over every mode.
    let stored = all.stored();
    let r = &all.on_default_storage();
    let charts: [(&str, Chart); 4] = [
        ("voxelize_time", both_backends!(voxelize_time, 900, 560)),
        ("passes_stacked", both_backends!(passes_stacked, 1000, 640)),
        ("speed_vs_accuracy", both_backends!(speed_vs_accuracy, 1300, 560)),
        ("cost_vs_triangles", both_backends!(cost_vs_triangles, 900, 560)),
    ];
    let mut files = Vec::new();
    for (name, draw) in charts {
        let path = dir.join(name);
        draw(&path, r).map_err(|m| Error::input(&path, format!("drawing the chart: {m}")))?;
        files.push(path.with_extension("png"));
        files.push(path.with_extension("svg"));
    }
    if all.rows.iter().any(|x| x.storage != stored) {
        for g in storage_regimes(all) {
            files.extend(draw_named(dir, &g.name, &g)?);
        }
    }
    let ratio = tess_ratio(all, before);
    if !ratio.series.is_empty() {
        files.extend(draw_named(dir, &ratio.name, &ratio)?);
    }
    Ok(files)
}

/// Tessellated over rasterized (MSAA) voxelization time against the resolution, one curve per
/// scene, and the same from `before`, an earlier run, where given
/// (two runs of different code, side by side).
pub fn tess_ratio(r: &Results, before: Option<&Results>) -> Regime {
    let curves = |r: &Results, suffix: &str| -> Vec<Series> {
        let stored = r.stored();
        let of = |scene: &str, method: &str, n: u32| {
            r.rows
                .iter()
                .find(|x| x.scene == scene && x.voxelizer == method && x.resolution == n && x.storage == stored)
                .map(|x| x.voxelize_ms)
        };
        let mut scenes: Vec<&str> = r.rows.iter().map(|x| x.scene.as_str()).collect();
        scenes.dedup();
        scenes
            .into_iter()
            .map(|scene| {
                let mut n: Vec<u32> = r.rows.iter().filter(|x| x.scene == scene).map(|x| x.resolution).collect();
                n.sort();
                n.dedup();
                let points = n
                    .into_iter()
                    .filter_map(|n| Some((n as f64, of(scene, "tess", n)? / of(scene, "raster-msaa", n)?)))
                    .collect();
                Series { label: format!("{scene}{suffix}"), points }
            })
            .collect()
    };
    let mut series = curves(r, "");
    if let Some(b) = before {
        series.extend(curves(b, ", before"));
    }
    series.retain(|s| !s.points.is_empty());
    let n = series.iter().flat_map(|s| s.points.iter().map(|p| p.0));
    let (lo, hi) = n.fold((f64::INFINITY, 0.0f64), |(l, h), x| (l.min(x), h.max(x)));
    if hi > 0.0 {
        series.push(Series { label: "the issue's target, 8×".into(), points: vec![(lo, 8.0), (hi, 8.0)] });
    }
    Regime {
        name: "tess_over_raster".into(),
        title: format!("Tessellated over rasterized (MSAA) voxelization time ({})", r.device),
        x: "voxels along the longest axis".into(),
        y: "tess ms / raster-msaa ms".into(),
        log_x: true,
        log_y: true,
        series,
    }
}

/// Memory and frame time against FLIP, one curve per scene and storage mode (the default
/// voxelizer's rows: the only one every mode runs), over the resolutions.
pub fn storage_regimes(r: &Results) -> Vec<Regime> {
    // The default voxelizer depends on the device that ran (`Coverage::Auto`): it is the one
    // with rows in a storage mode other than the default's.
    let stored = r.stored();
    let Some(method) = r.rows.iter().find(|x| x.storage != stored).map(|x| x.voxelizer.clone()) else {
        return Vec::new();
    };
    let rows: Vec<&super::Row> = r.rows.iter().filter(|x| x.voxelizer == method).collect();
    let mut keys: Vec<(String, String)> = rows.iter().map(|x| (x.scene.clone(), x.storage.clone())).collect();
    keys.sort();
    keys.dedup();
    let series = |y: fn(&super::Row) -> f64| -> Vec<Series> {
        keys.iter()
            .map(|(scene, storage)| {
                let mut points: Vec<(f64, f64)> = rows
                    .iter()
                    .filter(|x| &x.scene == scene && &x.storage == storage)
                    .map(|x| (x.flip as f64, y(x)))
                    .collect();
                points.sort_by(|a, b| a.0.total_cmp(&b.0));
                Series { label: format!("{scene}, {storage}"), points }
            })
            .collect()
    };
    let regime = |name: &str, y_label: &str, y: fn(&super::Row) -> f64| Regime {
        name: name.into(),
        title: format!("{y_label} against FLIP to the path tracer, per storage ({method}, N = {:?})", {
            let mut n: Vec<u32> = rows.iter().map(|x| x.resolution).collect();
            n.sort();
            n.dedup();
            n
        }),
        x: "FLIP against the path-traced reference".into(),
        y: y_label.into(),
        log_x: false,
        log_y: true,
        series: series(y),
    };
    vec![
        regime("storage_memory_vs_flip", "GPU memory MiB", |x| x.memory_mib),
        regime("storage_time_vs_flip", "frame GPU ms", |x| x.total_ms),
    ]
}

fn regime_chart<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, g: &Regime) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    // Only finite points set the ranges (draw_named draws none without one): plotters searches
    // for ticks forever in an infinite range.
    let pts = || g.series.iter().flat_map(|s| s.points.iter().copied()).filter(|p| p.0.is_finite() && p.1.is_finite());
    let (xlo, xhi) = pts().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| (l.min(p.0), h.max(p.0)));
    fn builder<'a, 'b, DB: DrawingBackend>(area: &'a DrawingArea<DB, Shift>, title: &str) -> ChartBuilder<'a, 'b, DB> {
        let mut b = ChartBuilder::on(area);
        b.caption(title, ("sans-serif", 20)).margin(12).x_label_area_size(40).y_label_area_size(60);
        b
    }
    let yr = lin_range(pts().map(|p| p.1));
    macro_rules! body {
        ($chart:expr) => {{
            let mut chart = $chart;
            chart
                .configure_mesh()
                .x_desc(g.x.as_str())
                .y_desc(g.y.as_str())
                .x_label_formatter(&|v| format!("{}", (v * 1e4).round() / 1e4))
                .light_line_style(TRANSPARENT)
                .draw()?;
            for (i, s) in g.series.iter().enumerate() {
                let c = PALETTE[i % PALETTE.len()];
                chart
                    .draw_series(LineSeries::new(s.points.clone(), c.stroke_width(2)))?
                    .label(s.label.as_str())
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], c));
                chart.draw_series(s.points.iter().map(|p| Circle::new(*p, 3, c.filled())))?;
            }
            chart.configure_series_labels().background_style(WHITE.mix(0.8)).border_style(BLACK).draw()?;
        }};
    }
    // Log axes label the measured x values themselves (plotters would label only powers of 10),
    // or 1, 2 and 5 times each power of 10 where there are too many to read.
    let xs = || {
        let mut v: Vec<f64> = pts().map(|p| p.0).collect();
        v.sort_by(f64::total_cmp);
        v.dedup();
        if v.len() <= 10 {
            return v;
        }
        let (lo, hi) = (xlo.max(1e-12).log10().floor() as i32, xhi.max(1e-12).log10().ceil() as i32);
        (lo..=hi)
            .flat_map(|e| [1.0, 2.0, 5.0].map(|m| m * 10f64.powi(e)))
            .filter(|x| (xlo * 0.8..=xhi * 1.25).contains(x))
            .collect()
    };
    let xp = ((xhi - xlo) * 0.05).max(1e-3);
    let ylog = log_range(pts().map(|p| p.1));
    match (g.log_x, g.log_y) {
        (true, true) => body!(builder(&root, &g.title)
            .build_cartesian_2d((xlo * 0.8..xhi * 1.25).log_scale().with_key_points(xs()), ylog.log_scale())?),
        (true, false) => body!(builder(&root, &g.title)
            .build_cartesian_2d((xlo * 0.8..xhi * 1.25).log_scale().with_key_points(xs()), yr)?),
        (false, true) => body!(builder(&root, &g.title).build_cartesian_2d(xlo - xp..xhi + xp, ylog.log_scale())?),
        (false, false) => body!(builder(&root, &g.title).build_cartesian_2d(xlo - xp..xhi + xp, yr)?),
    }
    root.present()
}

/// Draws one stability regime as `stability_<name>.png` and `.svg` in `dir`.
pub fn draw_regime(dir: &Path, g: &Regime) -> Result<Vec<PathBuf>> {
    draw_named(dir, &format!("stability_{}", g.name), g)
}

/// A regime's chart as `<stem>.png` and `.svg` in `dir`.
pub fn draw_named(dir: &Path, stem: &str, g: &Regime) -> Result<Vec<PathBuf>> {
    ensure_font()?;
    if !g.series.iter().flat_map(|s| &s.points).any(|p| p.0.is_finite() && p.1.is_finite()) {
        return Ok(Vec::new()); // nothing measured to draw (e.g. a sweep without its scale-1 rows)
    }
    let path = dir.join(stem);
    let err = |m: String| Error::input(&path, format!("drawing the chart: {m}"));
    regime_chart(BitMapBackend::new(&path.with_extension("png"), (900, 560)).into_drawing_area(), g)
        .map_err(|e| err(e.to_string()))?;
    regime_chart(SVGBackend::new(&path.with_extension("svg"), (900, 560)).into_drawing_area(), g)
        .map_err(|e| err(e.to_string()))?;
    Ok(vec![path.with_extension("png"), path.with_extension("svg")])
}

/// What an accuracy chart's x axis shows.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Cost {
    /// Frame GPU time.
    Time,
    /// The volume's memory.
    Memory,
}

/// The speed-against-accuracy chart of the GI study: one panel per scene, FLIP against the
/// path-traced reference over frame GPU time (or the volume's memory), each point a variant and
/// resolution, the Pareto front marked.
fn accuracy_chart<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    rows: &[AccuracyRow],
    cost: Cost,
) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    let mut scenes: Vec<&str> = rows.iter().map(|r| r.scene.as_str()).collect();
    scenes.dedup();
    scenes.sort();
    scenes.dedup();
    let cols = scenes.len().clamp(1, 2);
    let panels = root.split_evenly((scenes.len().div_ceil(cols).max(1), cols));
    for (scene, area) in scenes.iter().zip(panels.iter()) {
        let mine: Vec<&AccuracyRow> = rows.iter().filter(|r| r.scene == *scene).collect();
        let x = |r: &AccuracyRow| if cost == Cost::Time { r.frame_ms } else { r.memory_mib };
        let pts: Vec<(f64, f64)> = mine.iter().map(|r| (x(r), r.flip as f64)).collect();
        let mut chart = ChartBuilder::on(area)
            .caption(format!("{scene}: FLIP against the path tracer"), ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(log_range(pts.iter().map(|p| p.0)).log_scale(), lin_range(pts.iter().map(|p| p.1)))?;
        let x_desc = if cost == Cost::Time { "frame GPU ms (log)" } else { "volume memory, MiB (log)" };
        chart.configure_mesh().x_desc(x_desc).y_desc("FLIP (lower is better)").draw()?;
        let front = pareto(&pts, false);
        chart.draw_series(LineSeries::new(front.iter().map(|&i| pts[i]), BLACK.stroke_width(1)))?;
        chart.draw_series(mine.iter().zip(&pts).map(|(r, p)| {
            let c = if r.variant.starts_with("quality ") {
                PALETTE[2]
            } else if r.variant.starts_with("default") {
                PALETTE[0]
            } else {
                PALETTE[1]
            };
            EmptyElement::at(*p)
                + Circle::new((0, 0), 3, c.filled())
                + Text::new(format!("{} {}", r.variant, r.resolution), (4, -10), ("sans-serif", 9))
        }))?;
    }
    root.present()
}

/// Draws `accuracy.png` and `.svg` in `dir` (FLIP over frame time), or with `Cost::Memory`
/// `accuracy-memory.png` and `.svg` (FLIP over the volume's memory).
pub fn draw_accuracy(dir: &Path, rows: &[AccuracyRow], cost: Cost) -> Result<Vec<PathBuf>> {
    ensure_font()?;
    let path = dir.join(if cost == Cost::Time { "accuracy" } else { "accuracy-memory" });
    let err = |m: String| Error::input(&path, format!("drawing the chart: {m}"));
    let panels = {
        let mut s: Vec<&str> = rows.iter().map(|r| r.scene.as_str()).collect();
        s.sort();
        s.dedup();
        s.len().max(1)
    };
    let size = (1400, 520 * panels.div_ceil(2) as u32);
    accuracy_chart(BitMapBackend::new(&path.with_extension("png"), size).into_drawing_area(), rows, cost)
        .map_err(|e| err(e.to_string()))?;
    accuracy_chart(SVGBackend::new(&path.with_extension("svg"), size).into_drawing_area(), rows, cost)
        .map_err(|e| err(e.to_string()))?;
    Ok(vec![path.with_extension("png"), path.with_extension("svg")])
}
