//! Quality presets (`--quality`): named points of the report's speed-against-accuracy chart
//! (docs/report, the light section), each measured against the path-traced references there.
//! A preset sets how the diffuse cones are spread over the pixels; the scene's model (its cone
//! set, filter, bounces) stays the scene's.
//!
//! - `high`: every pixel traces the whole set, turned by one of nine ordered turns, and each
//!   pixel resolves its gather from its 3×3 neighbours: nine turns of the set everywhere.
//! - `default`: the set split among each 2×2 block of traced pixels (`GiFile::split_cones`): a
//!   quarter of the trace, each gather resolved per quarter from its 5×5 neighbours; and the
//!   traced pixels as far apart as the voxels allow ([`auto_scale`]), upsampled edge-aware.
//! - `draft`: as `default`, the traced pixels twice as far apart; where they then lie more than
//!   half a voxel apart each traced pixel traces the whole set ([`traced_model`]), so on a
//!   view whose voxels are about a pixel wide (the Cornell box at 256², 128³) it costs what
//!   `default` costs, at a worse FLIP (the report's light section).
//!
//! Why the traced pixels may lie half a voxel apart: the indirect light is read from the voxels,
//! and what changes within a voxel is the trilinear filter's blend, which the upsampling's
//! bilinear blend follows; a traced pixel every voxel or more would miss what changes from one
//! voxel to the next.

use glam::Vec3;

use super::RenderOptions;
use crate::scene::file::GiFile;
use crate::scene::Scene;

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Quality {
    Draft,
    #[default]
    Default,
    High,
}

impl Quality {
    pub const ALL: [Quality; 3] = [Quality::Draft, Quality::Default, Quality::High];

    pub fn name(self) -> &'static str {
        match self {
            Quality::Draft => "draft",
            Quality::Default => "default",
            Quality::High => "high",
        }
    }

    /// The preset's model: the scene's, with the cones spread as the preset says.
    pub fn gi(self, scene: &GiFile) -> GiFile {
        GiFile { split_cones: self != Quality::High, ..scene.clone() }
    }

    /// The reduced scale the diffuse cones are traced at (`RenderOptions::gi_scale`) for `scene`
    /// on a grid of `voxels` along its longest axis.
    pub fn gi_scale(self, scene: &Scene, voxels: u32) -> u32 {
        match self {
            Quality::High => 1,
            Quality::Default => auto_scale(scene, voxels),
            Quality::Draft => (2 * auto_scale(scene, voxels)).min(8),
        }
    }
}

/// The GI scale (1, 2, 4 or 8) that puts the traced pixels at most half a voxel apart where the
/// voxels look smallest: at the corner of the scene's bounds farthest from the camera, a voxel
/// of `voxels` along the longest axis spans `p` pixels, and the scale is the largest power of two
/// no more than p / 2. The Cornell box at 256² and 128³ from its own camera: 1; from inside the
/// room at 1280×720 and 64³: 4.
pub fn auto_scale(scene: &Scene, voxels: u32) -> u32 {
    let b = &scene.mesh.bounds;
    let voxel = b.size().max_element() / voxels.max(1) as f32;
    let far = (0..8)
        .map(|i| {
            let corner = Vec3::new(
                if i & 1 == 0 { b.min.x } else { b.max.x },
                if i & 2 == 0 { b.min.y } else { b.max.y },
                if i & 4 == 0 { b.min.z } else { b.max.z },
            );
            corner.distance(scene.camera.eye)
        })
        .fold(0.0f32, f32::max);
    let c = &scene.camera;
    let pixel = 2.0 * far * (0.5 * c.fov_y_deg.to_radians()).tan() / c.height.max(1) as f32;
    let span = voxel / pixel.max(1e-9);
    let mut s = 1;
    while s < 8 && (2 * s) as f32 <= 0.5 * span {
        s *= 2;
    }
    s
}

impl std::str::FromStr for Quality {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Quality::ALL
            .into_iter()
            .find(|q| q.name() == s)
            .ok_or_else(|| format!("unknown quality '{s}' (draft, default or high)"))
    }
}

/// The model the deferred trace runs: the scene's, with the cone set split among the traced
/// pixels only where they lie at most half a voxel apart ([`auto_scale`]): the split set's
/// resolve spans 5×5 traced pixels, which then stay within 2.5 voxels, about a cone's own
/// footprint; farther apart (a `--gi-scale` given beyond it) each traced pixel traces the whole
/// set. Measured (the diffuse view against the whole set at every pixel): from inside the
/// Cornell box at 640×360, 64³, scale 2 within reach, split 4.0% of the mean, the whole set
/// upsampled 11.1% (tests/gi_scale.rs); from outside at 256², 64³, a voxel two pixels, split at
/// scale 4 spans seven voxels: 11.4%.
pub fn traced_model(scene: &Scene, options: &RenderOptions) -> GiFile {
    let voxels = options.resolution.unwrap_or(scene.settings.voxel_resolution);
    let within = options.gi_scale <= auto_scale(scene, voxels);
    GiFile { split_cones: scene.settings.gi.split_cones && within, ..scene.settings.gi.clone() }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_scale_keeps_traced_pixels_within_half_a_voxel_where_voxels_look_smallest() {
        let mut s = Scene::embedded_default().unwrap();
        s.set_size(Some(256), Some(256)).unwrap();
        assert_eq!(auto_scale(&s, 128), 1, "the demo view: a voxel is about one pixel far away");
        s.camera.eye = Vec3::new(0.0, 2.75, 2.5);
        s.set_size(Some(1280), Some(720)).unwrap();
        // Farthest corner 6.7 m away: a pixel there is 0.67 cm, a 64³ voxel 8.6 cm, 13 pixels.
        assert_eq!(auto_scale(&s, 64), 4);
        assert_eq!(auto_scale(&s, 512), 1);
        assert_eq!(Quality::High.gi_scale(&s, 64), 1);
        assert_eq!(Quality::Draft.gi_scale(&s, 64), 8);
    }
}
