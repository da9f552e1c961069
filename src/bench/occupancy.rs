//! Cost against occupancy: on one fixed grid, scenes
//! that occupy more and more of it — a closed room with 0, 2, 4, ... full-width shelves — timed
//! with the passes over the volume run over the occupied voxels and texels (the default) and
//! over every texel (`Work::Dense`). The first should grow with the occupied voxels; the second
//! stays at the grid's cost whatever the scene holds.

use std::sync::Arc;

use glam::{UVec3, Vec3};

use super::charts::{Regime, Series};
use crate::error::Result;
use crate::gpu::{timer::median, Context, Timing};
use crate::render::{RenderOptions, Renderer, Work};
use crate::scene::Scene;

/// A closed 2 m room (its six walls) with `shelves` horizontal shelves spanning it.
pub fn shelves(shelves: u32) -> Scene {
    let (a, b) = (Vec3::splat(-1.0), Vec3::splat(1.0));
    let v = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
    let quad = |p: [Vec3; 4]| [([p[0], p[1], p[2]], 0), ([p[0], p[2], p[3]], 0)];
    let mut tris = Vec::new();
    for axis in 0..3 {
        for side in [a[axis], b[axis]] {
            let c = |u: f32, w: f32| {
                let mut p = Vec3::ZERO;
                p[axis] = side;
                p[(axis + 1) % 3] = u;
                p[(axis + 2) % 3] = w;
                p
            };
            tris.extend(quad([c(-1.0, -1.0), c(1.0, -1.0), c(1.0, 1.0), c(-1.0, 1.0)]));
        }
    }
    for i in 0..shelves {
        let y = -1.0 + 2.0 * (i as f32 + 0.5) / shelves as f32;
        tris.extend(quad([v(-0.95, y, -0.95), v(-0.95, y, 0.95), v(0.95, y, 0.95), v(0.95, y, -0.95)]));
    }
    Scene::from_triangles(&tris, &[Vec3::splat(0.7)])
}

fn ms(passes: &[Timing], name: &str) -> f64 {
    passes.iter().find(|t| t.pass == name).map_or(0.0, |t| t.ms)
}

/// Inject + filter GPU time (median of `frames`) against occupied voxels on an `n`³ grid.
pub fn run(ctx: &Arc<Context>, n: u32, frames: u32, progress: &dyn Fn(&str)) -> Result<Regime> {
    let counts = [0u32, 2, 4, 8, 16, 32];
    let mut series: Vec<Series> = [("over occupied texels", Work::Occupied), ("over every texel", Work::Dense)]
        .iter()
        .map(|(label, _)| Series { label: format!("inject + filter, {label}"), points: Vec::new() })
        .collect();
    for &k in &counts {
        let mut scene = shelves(k);
        scene.set_size(Some(128), Some(128))?;
        for (s, work) in series.iter_mut().zip([Work::Occupied, Work::Dense]) {
            progress(&format!("occupancy: {k} shelves, {work:?}"));
            let options = RenderOptions { dims: Some(UVec3::splat(n)), work, ..Default::default() };
            let r = Renderer::new(ctx, scene.clone(), options)?;
            r.render()?;
            let runs: Vec<Vec<Timing>> = (0..frames.max(1)).map(|_| r.render()).collect::<Result<_>>()?;
            let passes = median(&runs);
            let occupied = crate::voxel::occupancy_of(&r.voxels.read_albedo()?).iter().filter(|&&o| o).count();
            s.points.push((occupied as f64, ms(&passes, "inject") + ms(&passes, "filter")));
        }
    }
    Ok(Regime {
        name: "occupancy".into(),
        title: format!("Cost against occupancy: a room with 0–32 shelves on one {n}³ grid"),
        x: "occupied voxels".into(),
        y: "inject + filter GPU ms".into(),
        log_x: false,
        log_y: false,
        series,
    })
}
