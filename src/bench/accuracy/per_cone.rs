//! `vct bench --accuracy --per-cone`: where a region's indirect light goes wrong, cone by cone.
//!
//! Each diffuse cone stands for its cell of the hemisphere, weighted by the cell's projected
//! solid angle (`scene::cones`; Freed 2018 §4.5.2 gathers five cones, Wicked Engine 16–32), so
//! a surface's indirect light is albedo times the weighted sum of its cones' radiance. The
//! renderer draws the frame once per cone with that cone alone (`GiFile::only_cone`), and the
//! path tracer splits the same pixels' incoming light among the same cells
//! (`PathTracer::incoming_by_cell`): for each region and cone, the light the cone should bring
//! beside the light it brings. Each side sums over the cones to the region's indirect light
//! (the reference's, up to its noise; the renderer's, exactly, a specular cone's light spread
//! over the cones by their weights), so the table places a region's error among the directions
//! it arrives from, and the distance along each cone is what is left to look at.

use std::sync::Arc;

use glam::Vec3;
use rayon::prelude::*;
use serde::Serialize;

use super::{lum, render_timed, Judged, Variant};
use crate::error::Result;
use crate::gpu::Context;
use crate::reference::pathtrace::PathTracer;
use crate::scene::file::GiFile;

/// One cone's share of one region's indirect light.
#[derive(Clone, Debug, Serialize)]
pub struct ConeRow {
    pub scene: String,
    pub resolution: u32,
    pub region: String,
    pub cone: u32,
    /// The cone's direction above the surface (0: along it, 90: along the normal), degrees.
    pub elevation_deg: f32,
    /// Around the normal from the tangent frame's x axis, degrees.
    pub azimuth_deg: f32,
    /// The cone's weight (its cell's projected solid angle over π).
    pub weight: f32,
    /// The reference's light through the cone's cell: albedo times the cell's share of the
    /// cosine-weighted mean incoming radiance.
    pub reference: [f32; 3],
    /// The renderer's: albedo times the weight times the cone's radiance.
    pub vct: [f32; 3],
    /// Whether the region's ratio is judged in the region table (`RegionRow::judged`).
    pub judged: bool,
}

/// Up to `most` pixels of each region, spread evenly over it in scan order.
fn pixels_of_regions(j: &Judged, most: usize) -> Vec<Vec<usize>> {
    let mut all = vec![Vec::new(); j.regions.labels.len()];
    for (i, r) in j.regions.of_pixel.iter().enumerate() {
        if let Some(r) = r {
            all[*r].push(i);
        }
    }
    all.into_iter().map(|p| p.iter().step_by(p.len().div_ceil(most.max(1)).max(1)).copied().collect()).collect()
}

/// Measures the scene's own model `gi` on `j` at `resolution`, cone by cone, over up to
/// `pixels` pixels a region, the reference drawing `samples` directions at each; `direct` is the
/// renderer's direct-light frame (`direct_frame`). The cone set is measured unturned
/// (`GiFile::turn_cones` off), so each cone keeps its cell at every pixel.
pub fn measure(
    ctx: &Arc<Context>,
    j: &Judged,
    direct: &(Vec<Vec3>, Vec<u8>),
    gi: &GiFile,
    resolution: u32,
    pixels: usize,
    samples: u32,
) -> Result<Vec<ConeRow>> {
    // The cells are the set's own, unturned at every pixel.
    let gi = &GiFile { turn_cones: false, ..gi.clone() };
    let cones = crate::scene::cones::scaled(gi.cones, gi.aperture);
    let dirs: Vec<Vec3> = cones.iter().map(|c| Vec3::from_slice(&c.dir_weight[..3])).collect();
    let picked = pixels_of_regions(j, pixels);
    let width = j.scene.camera.width as usize;

    // The reference: each picked pixel's light, cell by cell, times its albedo.
    let tracer = PathTracer::new(&j.scene);
    let reference: Vec<Vec<Vec3>> = picked
        .iter()
        .map(|region| {
            let per_pixel: Vec<Vec<Vec3>> = region
                .par_iter()
                .filter_map(|&i| {
                    let pixel = ((i % width) as u32, (i / width) as u32);
                    let seed = (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0x5eed;
                    let (albedo, cells) = tracer.incoming_by_cell(pixel, &dirs, j.bounces, samples, seed)?;
                    Some(cells.into_iter().map(|c| c * albedo).collect())
                })
                .collect();
            let n = per_pixel.len().max(1) as f32;
            (0..dirs.len()).map(|k| per_pixel.iter().map(|p| p[k]).sum::<Vec3>() / n).collect()
        })
        .collect();

    // The renderer: each cone alone, its indirect light (full minus direct) times its weight.
    let mut vct = vec![vec![Vec3::ZERO; dirs.len()]; picked.len()];
    for (k, cone) in cones.iter().enumerate() {
        let alone = Variant::model(&format!("cone {k}"), GiFile { only_cone: Some(k as u32), ..gi.clone() });
        let (scene, options) = alone.setup(&j.scene, resolution);
        let full = render_timed(ctx, &scene, options, 1)?.linear;
        for (r, region) in picked.iter().enumerate() {
            let sum: Vec3 = region.iter().map(|&i| full[i] - direct.0[i]).sum();
            vct[r][k] = sum / region.len().max(1) as f32 * cone.dir_weight[3];
        }
    }

    let reference_indirect = super::region_means(&j.regions, &super::indirect(&j.full, &j.direct));
    let brightest = reference_indirect.iter().map(|&c| lum(c)).fold(0.0f32, f32::max);
    let mut rows = Vec::new();
    for (r, label) in j.regions.labels.iter().enumerate() {
        for (k, d) in dirs.iter().enumerate() {
            rows.push(ConeRow {
                scene: j.name.clone(),
                resolution,
                region: label.clone(),
                cone: k as u32,
                elevation_deg: d.z.clamp(-1.0, 1.0).asin().to_degrees(),
                azimuth_deg: d.y.atan2(d.x).to_degrees(),
                weight: cones[k].dir_weight[3],
                reference: reference[r][k].into(),
                vct: vct[r][k].into(),
                judged: lum(reference_indirect[r]) >= super::JUDGED_SHARE * brightest,
            });
        }
    }
    Ok(rows)
}

/// The console's table: for each judged region, its light summed over the cones (reference,
/// renderer, ratio), then the cones from the largest shortfall or excess to the smallest.
pub fn table(rows: &[ConeRow]) -> String {
    let mut out = String::new();
    let mut start = 0;
    while start < rows.len() {
        let end = start + rows[start..].iter().take_while(|r| r.region == rows[start].region).count();
        let group = &rows[start..end];
        start = end;
        if !group[0].judged {
            continue;
        }
        let sum = |f: fn(&ConeRow) -> [f32; 3]| group.iter().map(|r| lum(Vec3::from(f(r)))).sum::<f32>();
        let (reference, vct) = (sum(|r| r.reference), sum(|r| r.vct));
        out += &format!(
            "{} {}³ {}: reference {reference:.4}, vct {vct:.4} ({:.3})\n",
            group[0].scene,
            group[0].resolution,
            group[0].region,
            vct / reference.max(1e-9)
        );
        let mut order: Vec<&ConeRow> = group.iter().collect();
        let gap = |r: &ConeRow| lum(Vec3::from(r.vct)) - lum(Vec3::from(r.reference));
        order.sort_by(|a, b| gap(b).abs().total_cmp(&gap(a).abs()));
        // A cone whose cell brings under 1% of the region's light has a ratio of noise over
        // nearly nothing; its gap says enough.
        for r in order {
            let (a, b) = (lum(Vec3::from(r.reference)), lum(Vec3::from(r.vct)));
            let ratio = if a >= 0.01 * reference { format!("{:.3}", b / a) } else { "–".into() };
            out += &format!(
                "  cone {:>2} (elevation {:>4.1}°, azimuth {:>6.1}°, weight {:.3}): reference {a:.4}, vct {b:.4} ({ratio}), gap {:+.4}\n",
                r.cone, r.elevation_deg, r.azimuth_deg, r.weight, b - a
            );
        }
    }
    out
}

/// The rows as CSV (one line per region and cone).
pub fn csv(rows: &[ConeRow]) -> String {
    let mut out = String::from(
        "scene,resolution,region,cone,elevation_deg,azimuth_deg,weight,ref_r,ref_g,ref_b,vct_r,vct_g,vct_b,judged\n",
    );
    for r in rows {
        out += &format!(
            "{},{},{},{},{:.2},{:.2},{:.5},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{}\n",
            r.scene,
            r.resolution,
            r.region,
            r.cone,
            r.elevation_deg,
            r.azimuth_deg,
            r.weight,
            r.reference[0],
            r.reference[1],
            r.reference[2],
            r.vct[0],
            r.vct[1],
            r.vct[2],
            r.judged
        );
    }
    out
}
