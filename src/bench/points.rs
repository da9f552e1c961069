//! The point voxelizer on the bench (Mavridis & Papaioannou 2011): its density swept, with
//! and without the refinement (§3.2), at the first resolution, and the paper's claim tested —
//! that a rough volume gives nearly the same diffuse light — by charting image FLIP against
//! voxel recall for every voxelizer beside the sweep.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::charts::{Regime, Series};
use super::{charts, Results, Row};
use crate::error::Result;

/// The densities `vct bench` sweeps (points per voxel area); `--quick` takes fewer.
pub const DENSITIES: [f32; 6] = [0.25, 0.5, 1.0, 2.0, 4.0, 8.0];
pub const QUICK_DENSITIES: [f32; 2] = [0.5, 4.0];

/// One point-voxelizer configuration of the sweep.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct DensityRow {
    pub density: f32,
    pub refine: bool,
    pub row: Row,
}

fn scenes(r: &Results) -> Vec<String> {
    let mut s: Vec<String> = r.density_sweep.iter().map(|d| d.row.scene.clone()).collect();
    s.dedup();
    s
}

fn refined(refine: bool) -> &'static str {
    if refine {
        "refined"
    } else {
        "points only"
    }
}

/// Recall against voxelization time over the densities, a curve per scene and refinement.
pub fn density_curve(r: &Results) -> Regime {
    let mut series = Vec::new();
    for scene in scenes(r) {
        for refine in [false, true] {
            let points: Vec<(f64, f64)> = (r.density_sweep.iter())
                .filter(|d| d.row.scene == scene && d.refine == refine)
                .map(|d| (d.row.voxelize_ms.max(1e-3), d.row.recall))
                .collect();
            if !points.is_empty() {
                series.push(Series { label: format!("{scene}, {}", refined(refine)), points });
            }
        }
    }
    Regime {
        name: "points_density".into(),
        title: "Point voxelizer: recall against time over the density".into(),
        x: "voxelize ms (log)".into(),
        y: "recall against exact coverage".into(),
        log_x: true,
        log_y: false,
        series,
    }
}

/// Image FLIP against voxel recall on `scene`: the density sweep (points only) as a curve, and
/// every voxelizer of the main sweep at the same resolution as a point.
pub fn flip_against_recall(r: &Results, scene: &str) -> Regime {
    let mut series = Vec::new();
    let sweep: Vec<&DensityRow> = r.density_sweep.iter().filter(|d| d.row.scene == scene && !d.refine).collect();
    if let Some(res) = sweep.first().map(|d| d.row.resolution) {
        let mut points: Vec<(f64, f64)> = sweep.iter().map(|d| (d.row.recall, d.row.flip as f64)).collect();
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        series.push(Series { label: "points over the density".into(), points });
        let stored = r.stored();
        for x in r.rows.iter().filter(|x| x.scene == scene && x.resolution == res && x.storage == stored) {
            series.push(Series { label: x.voxelizer.clone(), points: vec![(x.recall, x.flip as f64)] });
        }
    }
    Regime {
        name: format!("flip_against_recall_{scene}"),
        title: format!("{scene}: image FLIP against voxel recall (does a rough volume give the same light?)"),
        x: "voxel recall against exact coverage".into(),
        y: "image FLIP against the path-traced reference".into(),
        log_x: false,
        log_y: false,
        series,
    }
}

/// The sweep's two charts, where the run has a sweep.
pub fn draw(dir: &Path, r: &Results) -> Result<Vec<PathBuf>> {
    if r.density_sweep.is_empty() {
        return Ok(Vec::new());
    }
    let mut files = charts::draw_named(dir, "points_density", &density_curve(r))?;
    for scene in scenes(r) {
        let g = flip_against_recall(r, &scene);
        files.extend(charts::draw_named(dir, &g.name, &g)?);
    }
    Ok(files)
}

/// The sweep as a Markdown table.
pub fn summary(r: &Results) -> String {
    if r.density_sweep.is_empty() {
        return String::new();
    }
    let mut s = String::from(
        "\nPoint voxelizer over its density (points per voxel area), first resolution:\n\n\
         | scene | N | density | refinement | voxelize ms | frame ms | recall | precision | FLIP |\n\
         |---|---|---|---|---|---|---|---|---|\n",
    );
    for d in &r.density_sweep {
        let x = &d.row;
        s.push_str(&format!(
            "| {} | {} | {} | {} | {:.2} | {:.1} | {:.4} | {:.4} | {:.4} |\n",
            x.scene,
            x.resolution,
            d.density,
            refined(d.refine),
            x.voxelize_ms,
            x.total_ms,
            x.recall,
            x.precision,
            x.flip
        ));
    }
    s
}
