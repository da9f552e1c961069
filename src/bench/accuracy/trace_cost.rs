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

/// The variants that take the default's trace apart.
pub fn variants(default: &GiFile) -> Vec<Variant> {
    let d = || default.clone();
    let v = |name: &str, gi: GiFile| Variant::model(&format!("trace: {name}"), gi);
    vec![
        v("default, fixed cones (no turn, no resolve)", GiFile { turn_cones: false, split_cones: false, ..d() }),
        v("default, isotropic chain (one fetch a step, not three)", GiFile { filter: Filter::Iso, ..d() }),
        v("default, no facing test (no moment fetch a step)", GiFile { facing: false, ..d() }),
        v("default, a whole texel a step (half the samples)", GiFile { step: 2.0 * default.step, ..d() }),
        v("default, no self clamp (coarser levels near the surface)", GiFile { self_clamp: false, ..d() }),
    ]
}

/// Whether a row belongs to the breakdown: a trace variant, the default or a preset.
fn charted(row: &AccuracyRow) -> bool {
    row.variant.starts_with("trace: ") || row.variant == "default" || row.variant.starts_with("quality ")
}

fn pass_ms(r: &AccuracyRow, pass: &str) -> f64 {
    r.passes.iter().find(|t| t.pass == pass).map_or(0.0, |t| t.ms)
}

/// The cones' time: the trace pass's, or where there is none (a set neither turned nor split,
/// traced by each pixel as it is shaded) the shading pass's.
fn trace_ms(r: &AccuracyRow) -> f64 {
    let t = pass_ms(r, "trace");
    if t > 0.0 {
        t
    } else {
        pass_ms(r, "shade pixels")
    }
}

/// The rows the breakdown shows: the presets and the trace variants of one scene and grid,
/// slowest trace first.
fn shown(rows: &[AccuracyRow]) -> Vec<&AccuracyRow> {
    let Some(first) = rows.iter().find(|r| r.variant.starts_with("trace: ")) else { return Vec::new() };
    let mut out: Vec<&AccuracyRow> =
        rows.iter().filter(|r| r.scene == first.scene && r.resolution == first.resolution && charted(r)).collect();
    out.sort_by(|a, b| trace_ms(b).total_cmp(&trace_ms(a)));
    out
}

/// The breakdown as a table: each row's cone tracing and shading times beside its FLIP.
pub fn table(rows: &[AccuracyRow]) -> String {
    let rows = shown(rows);
    let Some(first) = rows.first() else { return String::new() };
    let mut s = format!(
        "The cone trace of one frame taken apart ({}, {}³, the scene's own view): each row changes one thing, \
         timed on the same view (median GPU ms over the frames), its FLIP against the path-traced reference \
         beside it. `high` traces the whole set of sixteen cones at every pixel, the default a quarter of it, \
         `draft` the whole set at one pixel in four where its traced pixels lie too far apart to split it. The \
         shading pass holds the resolve.\n\n",
        first.scene, first.resolution
    );
    s += "| variant | cone tracing ms | shading ms | frame ms | FLIP |\n|---|---|---|---|---|\n";
    for r in rows {
        s += &format!(
            "| {} | {:.1} | {:.1} | {:.1} | {:.4} |\n",
            r.variant.trim_start_matches("trace: "),
            trace_ms(r),
            pass_ms(r, "shade pixels"),
            r.frame_ms,
            r.flip
        );
    }
    s
}

/// Draws the breakdown as `trace.png` and `.svg` in `dir`: one bar a row, its trace time, labelled
/// with its FLIP. Nothing where the rows hold no trace variants.
pub fn draw(dir: &Path, rows: &[AccuracyRow]) -> Result<Vec<PathBuf>> {
    let rows = shown(rows);
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
    let top = rows.iter().map(|r| trace_ms(r)).fold(1.0, f64::max) * 1.35;
    let mut chart = ChartBuilder::on(&root)
        .caption("Cone trace GPU time by variant (FLIP against the path tracer beside each)", ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(10)
        .build_cartesian_2d(0f64..top, -0.5f64..rows.len() as f64 - 0.5)?;
    chart.configure_mesh().x_desc("cone tracing ms").disable_y_mesh().y_labels(0).draw()?;
    chart.draw_series(rows.iter().enumerate().map(|(i, r)| {
        let y = (rows.len() - 1 - i) as f64;
        let c = if r.variant.starts_with("trace: ") { RGBColor(31, 119, 180) } else { RGBColor(214, 39, 40) };
        Rectangle::new([(0.0, y - 0.35), (trace_ms(r), y + 0.35)], c.filled())
    }))?;
    chart.draw_series(rows.iter().enumerate().map(|(i, r)| {
        let y = (rows.len() - 1 - i) as f64;
        let label = format!("{}  FLIP {:.4}", r.variant.trim_start_matches("trace: "), r.flip);
        Text::new(label, (trace_ms(r) + top * 0.01, y + 0.15), ("sans-serif", 12))
    }))?;
    root.present()
}
