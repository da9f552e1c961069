//! The hostile-geometry set (`assets/hostile/`, written by `scripts/hostile-meshes.py`): how
//! exact each voxelizer stays on the triangles real meshes are full of — slivers, needles,
//! sub-voxel triangles, fans of thin wedges, near-degenerate triangles and a dense scan-like
//! patch — as recall, precision and IoU against the exact triangle/box coverage
//! (`reference::coverage`), with the voxelization's GPU time beside each.

use std::path::PathBuf;
use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::error::Result;
use crate::gpu::Context;
use crate::reference::coverage::RefGrid;
use crate::scene::Scene;
use crate::voxel::headless::voxelize_in;
use crate::voxel::{VoxelGrid, VoxelizeMethod};

/// The set's meshes, by file stem.
pub const MESHES: [&str; 6] = ["slivers", "needles", "subvoxel", "fans", "near-degenerate", "scan"];

/// A mesh of the set in this checkout.
pub fn mesh_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/hostile").join(format!("{name}.obj"))
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct HostileRow {
    pub mesh: String,
    pub method: String,
    pub resolution: u32,
    pub triangles: usize,
    pub recall: f64,
    pub precision: f64,
    pub iou: f64,
    /// Median GPU time of clearing and voxelizing over three runs, milliseconds.
    pub voxelize_ms: f64,
}

/// Every method on every mesh at `resolution`³ (grid fitted to each mesh).
pub fn run(
    ctx: &Arc<Context>,
    methods: &[VoxelizeMethod],
    resolution: u32,
    progress: &dyn Fn(&str),
) -> Result<Vec<HostileRow>> {
    let mut rows = Vec::new();
    for name in MESHES {
        let scene = Scene::load(&mesh_path(name))?;
        let grid = VoxelGrid::fit(&scene.mesh.bounds, resolution)?;
        let tris: Vec<_> = (0..scene.mesh.triangle_count()).map(|t| scene.mesh.triangle(t)).collect();
        let exact = RefGrid::matching(&grid).coverage(&tris, 1e-3);
        for &m in methods {
            progress(&format!("hostile geometry: {name}, {}", m.label()));
            let run = voxelize_in(ctx, &scene, m, grid, 3)?;
            let a = exact.accuracy(&run.occupied());
            rows.push(HostileRow {
                mesh: name.into(),
                method: m.label(),
                resolution,
                triangles: tris.len(),
                recall: a.recall,
                precision: a.precision,
                iou: a.iou,
                voxelize_ms: run.gpu_ms,
            });
        }
    }
    Ok(rows)
}

/// A markdown table of the rows.
pub fn table(rows: &[HostileRow]) -> String {
    let mut s = String::from(
        "| mesh | triangles | method | N | recall | precision | IoU | voxelize ms |\n|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        s.push_str(&format!(
            "| {} | {} | {} | {} | {:.3} | {:.3} | {:.3} | {:.1} |\n",
            r.mesh, r.triangles, r.method, r.resolution, r.recall, r.precision, r.iou, r.voxelize_ms
        ));
    }
    s
}
