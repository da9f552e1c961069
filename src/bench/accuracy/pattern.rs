//! The flat-wall pattern: how far one frame's light on the scene's flat regions departs from the
//! light the same settings converge to. A cone set turned by pixel (`GiFile::turn_cones`) reads
//! each cone's cell in another direction at each pixel, and what the resolve leaves of those
//! differences shows on a flat wall as grain or streaks; the path-traced reference has only its
//! own noise there. The converged frame averages frames whose turns are moved by an even share
//! of a whole turn each (`Renderer::turn_phase`), so each pixel sees its cells from every side.
//! The figure is the RMS over the regions' pixels of (frame − converged) / the region's mean:
//! a share of the light, 0.01 being a pattern of 1%.

use std::sync::Arc;

use glam::Vec3;

use super::{lum, Judged, RegionMap, Variant};
use crate::error::Result;
use crate::gpu::Context;
use crate::render::{RenderOptions, Renderer};
use crate::scene::Scene;

/// Frames averaged into the converged frame.
pub const PHASES: u32 = 16;

/// The pattern of `variant` on `j` at `resolution`: the RMS departure of its frame (phase 0)
/// from the mean of `PHASES` turned frames, over the judged image's regions (every region is
/// one flat face: material, normal and plane), relative to each region's mean luminance.
pub fn measure(ctx: &Arc<Context>, j: &Judged, variant: &Variant, resolution: u32) -> Result<f32> {
    let (scene, options) = variant.setup(&j.scene, resolution);
    of_frames(ctx, scene, options, &j.regions)
}

/// The pattern of `scene` rendered with `options` over `regions` (as `measure`).
pub fn of_frames(ctx: &Arc<Context>, scene: Scene, options: RenderOptions, regions: &RegionMap) -> Result<f32> {
    let r = Renderer::new(ctx, scene, options)?;
    let mut first = Vec::new();
    let mut sum: Vec<Vec3> = Vec::new();
    for k in 0..PHASES {
        r.turn_phase.set(k as f32 / PHASES as f32);
        r.render()?;
        let frame = r.read_frame()?.linear();
        if k == 0 {
            sum = vec![Vec3::ZERO; frame.len()];
            first = frame.clone();
        }
        for (s, p) in sum.iter_mut().zip(&frame) {
            *s += *p;
        }
    }
    let converged: Vec<Vec3> = sum.iter().map(|s| *s / PHASES as f32).collect();
    Ok(relative_rms(&regions.of_pixel, regions.labels.len(), &first, &converged))
}

/// RMS over the pixels of `regions` of the luminance difference between `frame` and `converged`,
/// each relative to its region's mean luminance in `converged`.
fn relative_rms(of_pixel: &[Option<usize>], regions: usize, frame: &[Vec3], converged: &[Vec3]) -> f32 {
    let mut mean = vec![(0.0f64, 0usize); regions];
    for (c, r) in converged.iter().zip(of_pixel) {
        if let Some(r) = r {
            mean[*r].0 += lum(*c) as f64;
            mean[*r].1 += 1;
        }
    }
    let (mut sq, mut n) = (0.0f64, 0usize);
    for ((f, c), r) in frame.iter().zip(converged).zip(of_pixel) {
        let Some(r) = r else { continue };
        let m = mean[*r].0 / mean[*r].1.max(1) as f64;
        if m <= 1e-9 {
            continue;
        }
        let d = (lum(*f) - lum(*c)) as f64 / m;
        sq += d * d;
        n += 1;
    }
    (sq / n.max(1) as f64).sqrt() as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_rms_is_relative_to_each_regions_mean_and_skips_unjudged_pixels() {
        // Region 0 at 1.0 with a ±0.1 ripple, region 1 at 10.0 with ±1.0: 10% in both; the
        // unjudged pixel's difference does not count.
        let converged = [1.0, 1.0, 10.0, 10.0, 5.0].map(Vec3::splat);
        let frame = [1.1, 0.9, 11.0, 9.0, 50.0].map(Vec3::splat);
        let of_pixel = [Some(0), Some(0), Some(1), Some(1), None];
        let rms = relative_rms(&of_pixel, 2, &frame, &converged);
        assert!((rms - 0.1).abs() < 1e-5, "{rms}");
    }
}
