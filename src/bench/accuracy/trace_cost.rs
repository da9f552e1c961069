//! Where a pixel's time goes: the cone trace of the default frame taken apart by variants that
//! each change one thing (how many cones a pixel traces, how they turn, what a step reads, how
//! far a step goes), each timed on the same view with its accuracy against the path-traced
//! reference beside it. The rows are ordinary accuracy rows (`measure`), named "trace: …"; the
//! report tables and charts them ([`table`], [`draw`]).

use std::path::{Path, PathBuf};

use plotters::prelude::*;

use super::{AccuracyRow, Variant};
use crate::bench::charts::{ensure_font, DrawResult};
use crate::error::{Error, Result};
use crate::scene::file::{Filter, GiFile};

/// The variants that take the default's trace apart, each with the cones a traced pixel traces
/// over the cones a shaded pixel gets (the share of the whole set each pixel pays for).
pub fn variants(default: &GiFile) -> Vec<(Variant, f64)> {
    let d = || default.clone();
    let v = |name: &str, gi: GiFile| Variant::model(&format!("trace: {name}"), gi);
    vec![
        (v("default, fixed cones (no turn, no resolve)", GiFile { turn_cones: false, split_cones: false, ..d() }), 1.0),
        (v("default, isotropic chain (one fetch a step, not three)", GiFile { filter: Filter::Iso, ..d() }), 0.25),
        (v("default, no facing test (no moment fetch a step)", GiFile { facing: false, ..d() }), 0.25),
        (v("default, a whole texel a step (half the samples)", GiFile { step: 2.0 * default.step, ..d() }), 0.25),
        (v("default, no self clamp (coarser levels near the surface)", GiFile { self_clamp: false, ..d() }), 0.25),
    ]
}

/// The share of the whole cone set a shaded pixel pays for, by the row's variant: the trace rows'
/// own, and the presets': `quality high` every cone at every pixel; the default and `draft` a
/// quarter of the set at one pixel in the row's GI scale squared.
pub fn share_of(row: &AccuracyRow, default: &GiFile) -> Option<f64> {
    if let Some((_, s)) = variants(default).into_iter().find(|(v, _)| v.name == row.variant) {
        return Some(s);
    }
    let split = match row.variant.as_str() {
        "quality high" => 1.0,
        "default" | "quality draft" => 0.25,
        _ => return None,
    };
    Some(split / f64::from(row.gi_scale * row.gi_scale))
}

fn pass_ms(r: &AccuracyRow, pass: &str) -> f64 {
    r.passes.iter().find(|t| t.pass == pass).map_or(0.0, |t| t.ms)
}

/// The rows the breakdown shows: the presets and the trace variants of one scene and grid,
/// slowest trace first.
fn shown<'a>(rows: &'a [AccuracyRow], default: &GiFile) -> Vec<&'a AccuracyRow> {
    let Some(first) = rows.iter().find(|r| r.variant.starts_with("trace: ")) else { return Vec::new() };
    let mut out: Vec<&AccuracyRow> = rows
        .iter()
        .filter(|r| r.scene == first.scene && r.resolution == first.resolution && share_of(r, default).is_some())
        .collect();
    out.sort_by(|a, b| pass_ms(b, "trace").total_cmp(&pass_ms(a, "trace")));
    out
}

/// The breakdown as a table: each row's trace and shading times, the trace per pixel and per
/// cone, beside its FLIP.
pub fn table(rows: &[AccuracyRow], default: &GiFile) -> String {
    let rows = shown(rows, default);
    let Some(first) = rows.first() else { return String::new() };
    let pixels = f64::from(first.width.max(1) * first.height.max(1));
    let cones = crate::scene::cones::cones(default.cones).iter().filter(|c| c.dir_weight[3] > 0.0).count() as f64;
    let mut s = format!(
        "The trace of one frame taken apart ({}, {}³, {} × {} pixels, {cones} cones a set): each row changes one \
         thing, timed on the same view (median GPU ms over the frames), its FLIP against the path-traced reference \
         beside it. \"cones a pixel\" is what each shaded pixel pays for; \"µs a cone\" the trace over the cones \
         traced. The shading pass holds the resolve.\n\n",
        first.scene, first.resolution, first.width, first.height
    );
    s += "| variant | cones a pixel | trace ms | µs a cone | shading ms | frame ms | FLIP |\n|---|---|---|---|---|---|---|\n";
    for r in rows {
        let share = share_of(r, default).unwrap_or(1.0);
        let trace = pass_ms(r, "trace");
        s += &format!(
            "| {} | {:.2} | {:.1} | {:.3} | {:.1} | {:.1} | {:.4} |\n",
            r.variant.trim_start_matches("trace: "),
            share * cones,
            trace,
            1e3 * trace / (pixels * share * cones).max(1.0),
            pass_ms(r, "shade pixels"),
            r.frame_ms,
            r.flip
        );
    }
    s
}

/// Draws the breakdown as `trace.png` and `.svg` in `dir`: one bar a row, its trace time, labelled
/// with its FLIP. Nothing where the rows hold no trace variants.
pub fn draw(dir: &Path, rows: &[AccuracyRow], default: &GiFile) -> Result<Vec<PathBuf>> {
    let rows = shown(rows, default);
    if rows.is_empty() {
        return Ok(Vec::new());
    }
    ensure_font()?;
    let path = dir.join("trace");
    let size = (1100, 80 + 44 * rows.len() as u32);
    let err = |m: String| Error::input(&path, format!("drawing the chart: {m}"));
    bars(BitMapBackend::new(&path.with_extension("png"), size).into_drawing_area(), &rows)
        .map_err(|e| err(e.to_string()))?;
    bars(SVGBackend::new(&path.with_extension("svg"), size).into_drawing_area(), &rows)
        .map_err(|e| err(e.to_string()))?;
    Ok(vec![path.with_extension("png"), path.with_extension("svg")])
}

fn bars<DB: DrawingBackend>(root: DrawingArea<DB, plotters::coord::Shift>, rows: &[&AccuracyRow]) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    let top = rows.iter().map(|r| pass_ms(r, "trace")).fold(1.0, f64::max) * 1.35;
    let mut chart = ChartBuilder::on(&root)
        .caption("Cone trace GPU time by variant (FLIP against the path tracer beside each)", ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(10)
        .build_cartesian_2d(0f64..top, -0.5f64..rows.len() as f64 - 0.5)?;
    chart.configure_mesh().x_desc("trace ms").disable_y_mesh().y_labels(0).draw()?;
    chart.draw_series(rows.iter().enumerate().map(|(i, r)| {
        let y = (rows.len() - 1 - i) as f64;
        let c = if r.variant.starts_with("trace: ") { RGBColor(31, 119, 180) } else { RGBColor(214, 39, 40) };
        Rectangle::new([(0.0, y - 0.35), (pass_ms(r, "trace"), y + 0.35)], c.filled())
    }))?;
    chart.draw_series(rows.iter().enumerate().map(|(i, r)| {
        let y = (rows.len() - 1 - i) as f64;
        let label = format!("{}  FLIP {:.4}", r.variant.trim_start_matches("trace: "), r.flip);
        Text::new(label, (pass_ms(r, "trace") + top * 0.01, y + 0.15), ("sans-serif", 12))
    }))?;
    root.present()
}
