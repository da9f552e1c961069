//! The diffuse cone sets: a quadrature of the cosine-weighted hemisphere, as directions in the
//! surface's tangent frame (z along the normal) with weights and apertures (Freed 2018 §4.5.2
//! uses five cones of 45°; Crassin et al. 2011 six of 60°; Wicked Engine 16 to 32).
//!
//! Except for the thesis' own weighting, each cone stands for its cell of the hemisphere (the
//! directions nearer to it than to any other cone): its weight is the cell's projected solid
//! angle over π, so the weights sum to one and a uniform sky of radiance L gives exactly L, and
//! its aperture is that of a cone with the cell's solid angle, so the cones cover the
//! hemisphere without gaps or double counting. A small bright emitter seen by one cone then
//! counts by the share of the hemisphere that cone stands for, which the thesis' normalized
//! cosine weights overstate where the cones leave gaps.

use glam::Vec3;

use crate::config::MAX_CONES;
pub use crate::scene::file::ConeSet;

/// Mirrors `Cone` in `shaders-glsl/common/frame.glsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ConeGpu {
    /// xyz: direction in the tangent frame; w: weight.
    pub dir_weight: [f32; 4],
    /// x: tangent of the half aperture.
    pub shape: [f32; 4],
}

/// The layout's directions (unit, z along the normal).
fn directions(set: ConeSet) -> Vec<Vec3> {
    let ring = |count: usize, tilt_deg: f32| -> Vec<Vec3> {
        let t = tilt_deg.to_radians();
        let mut d = vec![Vec3::Z];
        for k in 0..count {
            let phi = std::f32::consts::TAU * k as f32 / count as f32;
            d.push(Vec3::new(t.sin() * phi.cos(), t.sin() * phi.sin(), t.cos()));
        }
        d
    };
    match set {
        ConeSet::Thesis5 | ConeSet::Thesis5Cells => ring(4, 45.0),
        ConeSet::Crassin6 => ring(5, 60.0),
        ConeSet::Fib8 => fibonacci_cosine(8),
        ConeSet::Fib16 => fibonacci_cosine(16),
        ConeSet::Fib32 => fibonacci_cosine(32),
    }
}

/// The cones of a layout with their half apertures scaled by `aperture`.
pub fn scaled(set: ConeSet, aperture: f32) -> Vec<ConeGpu> {
    cones(set)
        .into_iter()
        .map(|mut c| {
            c.shape[0] = (c.shape[0].atan() * aperture).min(1.5).tan();
            c
        })
        .collect()
}

/// The cones of a layout, weights summing to one.
pub fn cones(set: ConeSet) -> Vec<ConeGpu> {
    let dirs = directions(set);
    assert!(dirs.len() <= MAX_CONES as usize);
    if set == ConeSet::Thesis5 {
        let tilt = 45f32.to_radians();
        let w_sum = 1.0 + 4.0 * tilt.cos();
        let tan_half = (22.5f32).to_radians().tan();
        return dirs
            .iter()
            .map(|d| ConeGpu { dir_weight: [d.x, d.y, d.z, d.z / w_sum], shape: [tan_half, 0.0, 0.0, 0.0] })
            .collect();
    }
    let cells = hemisphere_cells(&dirs);
    dirs.iter()
        .zip(cells)
        .map(|(d, (solid_angle, projected))| {
            // A cone of half angle a spans 2π(1 − cos a) steradians.
            let cos_half = (1.0 - solid_angle / std::f32::consts::TAU).clamp(-1.0, 1.0);
            let tan_half = (1.0 - cos_half * cos_half).max(0.0).sqrt() / cos_half.max(1e-3);
            ConeGpu { dir_weight: [d.x, d.y, d.z, projected / std::f32::consts::PI], shape: [tan_half, 0.0, 0.0, 0.0] }
        })
        .collect()
}

/// The GPU buffer: the surfaces' set (half apertures scaled by `aperture`) padded to MAX_CONES
/// entries, then the voxel bounce's set, likewise.
pub fn buffer(surface: ConeSet, aperture: f32, bounce: ConeSet) -> Vec<ConeGpu> {
    let mut c = scaled(surface, aperture);
    c.resize(MAX_CONES as usize, ConeGpu::default());
    c.extend(cones(bounce));
    c.resize(2 * MAX_CONES as usize, ConeGpu::default());
    c
}

/// `n` directions over the hemisphere with density proportional to the cosine (a Fibonacci
/// spiral on the disc, lifted): each stands for about the same projected solid angle.
fn fibonacci_cosine(n: usize) -> Vec<Vec3> {
    let golden = std::f32::consts::PI * (3.0 - 5f32.sqrt());
    (0..n)
        .map(|i| {
            let r = ((i as f32 + 0.5) / n as f32).sqrt();
            let phi = golden * i as f32;
            Vec3::new(r * phi.cos(), r * phi.sin(), (1.0 - r * r).max(0.0).sqrt())
        })
        .collect()
}

/// Solid angle and projected solid angle (∫cos dω) of each direction's cell of the upper
/// hemisphere, integrated over a fine, even spiral of sample directions.
fn hemisphere_cells(dirs: &[Vec3]) -> Vec<(f32, f32)> {
    const SAMPLES: usize = 200_000;
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let mut cells = vec![(0.0f64, 0.0f64); dirs.len()];
    let d_omega = std::f64::consts::TAU / SAMPLES as f64;
    for i in 0..SAMPLES {
        // Uniform in z over [0, 1] is uniform in solid angle.
        let z = 1.0 - (i as f64 + 0.5) / SAMPLES as f64;
        let r = (1.0 - z * z).max(0.0).sqrt();
        let phi = golden * i as f64;
        let s = Vec3::new((r * phi.cos()) as f32, (r * phi.sin()) as f32, z as f32);
        let nearest = (0..dirs.len()).max_by(|&a, &b| s.dot(dirs[a]).total_cmp(&s.dot(dirs[b]))).unwrap_or(0);
        cells[nearest].0 += d_omega;
        cells[nearest].1 += d_omega * z;
    }
    cells.into_iter().map(|(a, b)| (a as f32, b as f32)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cell_weights_integrate_the_cosine_hemisphere() {
        for set in ConeSet::ALL {
            let cones = cones(set);
            let sum: f32 = cones.iter().map(|c| c.dir_weight[3]).sum();
            assert!((sum - 1.0).abs() < 1e-3, "{set:?}: weights sum to {sum}");
            for c in &cones {
                let d = Vec3::from_slice(&c.dir_weight[..3]);
                assert!((d.length() - 1.0).abs() < 1e-4 && d.z > 0.0, "{set:?}: direction {d}");
                assert!(c.shape[0] > 0.0 && c.shape[0].is_finite());
            }
        }
        // The thesis' five 45° cones cover 38% of the hemisphere's solid angle; cell apertures 100%.
        let solid = |set: ConeSet| -> f32 {
            cones(set)
                .iter()
                .map(|c| {
                    let cos = 1.0 / (1.0 + c.shape[0] * c.shape[0]).sqrt();
                    std::f32::consts::TAU * (1.0 - cos)
                })
                .sum::<f32>()
                / std::f32::consts::TAU
        };
        assert!((solid(ConeSet::Thesis5) - 0.38).abs() < 0.01, "{}", solid(ConeSet::Thesis5));
        for set in [ConeSet::Thesis5Cells, ConeSet::Crassin6, ConeSet::Fib8, ConeSet::Fib16, ConeSet::Fib32] {
            assert!((solid(set) - 1.0).abs() < 1e-3, "{set:?}: {}", solid(set));
        }
        // Cosine-spread directions stand for similar projected solid angles: equal areas of the
        // projected disk, though their cells on the sphere (nearest direction by angle) differ,
        // most at the horizon (measured 0.029..0.079 for fib16); none is degenerate.
        let w: Vec<f32> = cones(ConeSet::Fib16).iter().map(|c| c.dir_weight[3]).collect();
        let (lo, hi) = (w.iter().cloned().fold(1.0, f32::min), w.iter().cloned().fold(0.0, f32::max));
        assert!(hi < 3.0 * lo && lo > 0.25 / 16.0, "fib16 weights {lo}..{hi}");
    }
}
