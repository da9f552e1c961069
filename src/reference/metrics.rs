//! Image accuracy: FLIP (NVIDIA's perceptual metric, via the `nv-flip` crate) on tone-mapped
//! 8-bit images and RMSE on linear radiance, plus the tone curve of Freed 2018 Algorithm 3
//! (c/(c+1), gamma 2.2) written out on the CPU.

use glam::Vec3;

/// c/(c+1) then gamma 2.2, to 8 bits (RGB, row-major).
pub fn tonemap(radiance: &[Vec3]) -> Vec<u8> {
    radiance
        .iter()
        .flat_map(|c| {
            let c = c.max(Vec3::ZERO);
            let t = c / (c + Vec3::ONE);
            t.to_array().map(|v| (v.powf(1.0 / 2.2) * 255.0).round().clamp(0.0, 255.0) as u8)
        })
        .collect()
}

/// Root-mean-square difference of two linear images (all channels).
pub fn rmse(a: &[Vec3], b: &[Vec3]) -> f64 {
    assert_eq!(a.len(), b.len(), "images differ in size");
    let sum: f64 = a.iter().zip(b).map(|(x, y)| (*x - *y).length_squared() as f64).sum();
    (sum / (3 * a.len().max(1)) as f64).sqrt()
}

/// Mean FLIP error of `test` against `reference` (both 8-bit RGB, same size) and the error map
/// coloured with the magma map (RGB8).
pub fn flip(reference: &[u8], test: &[u8], width: u32, height: u32) -> (f32, Vec<u8>) {
    let (mean, colour, _) = flip_values(reference, test, width, height);
    (mean, colour)
}

/// `flip`, and each pixel's FLIP error besides (row-major).
pub fn flip_values(reference: &[u8], test: &[u8], width: u32, height: u32) -> (f32, Vec<u8>, Vec<f32>) {
    let r = nv_flip::FlipImageRgb8::with_data(width, height, reference);
    let t = nv_flip::FlipImageRgb8::with_data(width, height, test);
    let map = nv_flip::flip(r, t, nv_flip::DEFAULT_PIXELS_PER_DEGREE);
    let mean = nv_flip::FlipPool::from_image(&map).mean();
    let colour = map.apply_color_lut(&nv_flip::magma_lut()).to_vec();
    (mean, colour, map.to_vec())
}
