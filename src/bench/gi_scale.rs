//! Reduced-resolution indirect light on the bench (`--gi-scale`): the default configuration at
//! the first resolution with the diffuse cones traced at one pixel in 4, 16 and 64, with and
//! without accumulation over frames (`--gi-accumulate`; measured on a still camera after
//! gi-scale² frames, when it has converged), beside every pixel (the main sweep's row),
//! charted as frame time against image FLIP per scene.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::charts::{Regime, Series};
use super::{charts, Results, Row};
use crate::error::Result;

/// The scales `vct bench` runs beside 1 (every pixel).
pub const SCALES: [u32; 3] = [2, 4, 8];

/// One reduced-resolution configuration.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ScaleRow {
    pub scale: u32,
    /// Accumulated over frames (false where a results file does not say).
    #[serde(default)]
    pub accumulate: bool,
    pub row: Row,
}

/// The default configuration's row of the main sweep that `s` was measured beside.
fn full_resolution<'a>(r: &'a Results, s: &ScaleRow) -> Option<&'a Row> {
    let stored = r.stored();
    r.rows.iter().find(|x| {
        x.scene == s.row.scene
            && x.resolution == s.row.resolution
            && x.voxelizer == s.row.voxelizer
            && x.storage == stored
    })
}

/// Frame time against FLIP over the scales, two curves per scene (scale 1 first): upsampled
/// each frame, and accumulated.
pub fn chart(r: &Results) -> Regime {
    let mut scenes: Vec<String> = r.gi_scale_sweep.iter().map(|s| s.row.scene.clone()).collect();
    scenes.dedup();
    let scales = SCALES.map(|s| s.to_string()).join(", ");
    let series = scenes
        .into_iter()
        .flat_map(|scene| {
            [false, true].map(|accumulate| {
                let rows: Vec<&ScaleRow> =
                    (r.gi_scale_sweep.iter()).filter(|s| s.row.scene == scene && s.accumulate == accumulate).collect();
                let full = rows.first().and_then(|s| full_resolution(r, s));
                let points =
                    full.into_iter().chain(rows.iter().map(|s| &s.row)).map(|x| (x.total_ms, x.flip as f64)).collect();
                let how = if accumulate { ", accumulated" } else { "" };
                Series { label: format!("{scene}: GI scale 1, {scales}{how}"), points }
            })
        })
        .filter(|s| s.points.len() > 1)
        .collect();
    Regime {
        name: "gi_scale".into(),
        title: "Diffuse cones at one pixel in 1 / 4 / 16 / 64: frame time against FLIP".into(),
        x: "frame GPU ms".into(),
        y: "image FLIP against the path-traced reference".into(),
        log_x: false,
        log_y: false,
        series,
    }
}

pub fn draw(dir: &Path, r: &Results) -> Result<Vec<PathBuf>> {
    if r.gi_scale_sweep.is_empty() {
        return Ok(Vec::new());
    }
    charts::draw_named(dir, "gi_scale", &chart(r))
}

/// The sweep as a Markdown table, each scale beside every pixel.
pub fn summary(r: &Results) -> String {
    if r.gi_scale_sweep.is_empty() {
        return String::new();
    }
    let mut s = String::from(
        "\nDiffuse cones at a reduced resolution (`--gi-scale`), default configuration:\n\n\
         | scene | N | GI scale | accumulated | frame ms | shade ms | FLIP | FLIP at scale 1 |\n|---|---|---|---|---|---|---|---|\n",
    );
    for x in &r.gi_scale_sweep {
        let shade = |row: &Row| row.passes.iter().find(|t| t.pass == "shade").map_or(0.0, |t| t.ms);
        let full = full_resolution(r, x);
        s.push_str(&format!(
            "| {} | {} | {} | {} | {:.1} | {:.1} | {:.4} | {} |\n",
            x.row.scene,
            x.row.resolution,
            x.scale,
            if x.accumulate { "yes" } else { "no" },
            x.row.total_ms,
            shade(&x.row),
            x.row.flip,
            full.map_or("—".into(), |f| format!("{:.4} ({:.1} ms, shade {:.1})", f.flip, f.total_ms, shade(f)))
        ));
    }
    s
}
