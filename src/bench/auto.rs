//! `vct render --res auto [--target-flip F]`: the resolution a scene needs. With a target, the
//! cheapest grid whose image meets it against the cached path-traced reference (grids tried
//! from the coarsest up: memory and time grow with the resolution, so the first that meets F is
//! the cheapest); without one, a resolution from the scene's size at AUTO_VOXELS_PER_METRE.
//! "Model no more than a scene needs", with the error measured, not assumed.

use std::path::Path;
use std::sync::Arc;

use serde::Serialize;

use crate::error::Result;
use crate::gpu::Context;
use crate::reference::metrics;
use crate::render::{RenderOptions, Renderer};
use crate::scene::Scene;

/// The grids `--res auto` tries, coarsest first (voxels along the longest axis).
pub const CANDIDATES: [u32; 5] = [16, 32, 64, 128, 256];

/// The error target and the reference it is measured against.
#[derive(Clone, Copy, Debug)]
pub struct Target<'a> {
    /// The largest FLIP allowed; `None`: a resolution from the scene's size.
    pub flip: Option<f32>,
    /// Samples a pixel of the path-traced reference.
    pub spp: u32,
    /// Where references are cached.
    pub cache: &'a Path,
}

/// One grid tried.
#[derive(Clone, Debug, Serialize)]
pub struct Tried {
    pub resolution: u32,
    pub dims: [u32; 3],
    pub flip: f32,
    /// GPU time of one warm frame.
    pub frame_ms: f64,
    pub memory_mib: f64,
}

/// What `--res auto` chose, and why.
#[derive(Clone, Debug, Serialize)]
pub struct Choice {
    pub resolution: u32,
    /// The target, and whether the choice meets it (without a target: `None`, and not measured).
    pub target: Option<f32>,
    pub met: bool,
    pub tried: Vec<Tried>,
    pub reason: String,
}

/// The resolution from the scene's size alone: its longest extent at AUTO_VOXELS_PER_METRE,
/// rounded up to a power of two within the candidates.
pub fn from_size(scene: &Scene) -> u32 {
    let metres = scene.mesh.bounds.size().max_element();
    let want = (metres * crate::config::AUTO_VOXELS_PER_METRE).ceil().max(1.0) as u32;
    want.next_power_of_two().clamp(CANDIDATES[0], CANDIDATES[CANDIDATES.len() - 1])
}

/// Renders `scene` with `options` at each of `candidates` (coarsest first; the CLI's:
/// [`CANDIDATES`]) until one meets the target against the path-traced reference; `name`
/// names the scene in the cache. The choice is the first that meets the target, else the one
/// closest to it (said so in `reason`).
pub fn choose(
    ctx: &Arc<Context>,
    scene: &Scene,
    name: &str,
    options: RenderOptions,
    candidates: &[u32],
    target: Target,
    progress: &dyn Fn(&str),
) -> Result<Choice> {
    let Target { flip: target, spp, cache } = target;
    let Some(target) = target else {
        let n = from_size(scene);
        let metres = scene.mesh.bounds.size().max_element();
        return Ok(Choice {
            resolution: n,
            target: None,
            met: false,
            tried: Vec::new(),
            reason: format!(
                "no --target-flip: {n} voxels along the scene's longest axis ({metres:.2} m at {} voxels a metre, a power of two in {}..={}); the error is not measured",
                crate::config::AUTO_VOXELS_PER_METRE,
                CANDIDATES[0],
                CANDIDATES[CANDIDATES.len() - 1]
            ),
        });
    };
    let bounces = scene.settings.gi.bounces;
    let (reference, _) = super::reference_cached(scene, name, bounces, false, spp, cache, progress)?;
    let reference = metrics::tonemap(&reference);
    let mut tried = Vec::new();
    for &n in candidates {
        progress(&format!("--res auto: {n}"));
        let r = Renderer::new(ctx, scene.clone(), RenderOptions { resolution: Some(n), dims: None, ..options })?;
        r.render()?;
        let passes = r.render()?;
        let frame = r.read_frame()?;
        let (flip, _) = metrics::flip(&reference, &frame.rgb8(), frame.width, frame.height);
        let t = Tried {
            resolution: n,
            dims: r.voxels.grid.dims.into(),
            flip,
            frame_ms: passes.iter().find(|t| t.pass == "total").map_or(0.0, |t| t.ms),
            memory_mib: r.memory().mib(),
        };
        tried.push(t);
        if flip <= target {
            return Ok(Choice {
                resolution: n,
                target: Some(target),
                met: true,
                reason: format!("the coarsest grid whose image meets FLIP {target} against the reference"),
                tried,
            });
        }
    }
    let best = tried.iter().min_by(|a, b| a.flip.total_cmp(&b.flip)).expect("candidates tried");
    Ok(Choice {
        resolution: best.resolution,
        target: Some(target),
        met: false,
        reason: format!(
            "no grid meets FLIP {target} (the model's error does not fall below {:.4} with voxels alone): the closest",
            best.flip
        ),
        tried,
    })
}

impl std::fmt::Display for Choice {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        if !self.tried.is_empty() {
            writeln!(f, "{:>6} {:>13} {:>8} {:>10} {:>10}", "res", "dims", "FLIP", "frame ms", "MiB")?;
            for t in &self.tried {
                let [x, y, z] = t.dims;
                writeln!(
                    f,
                    "{:>6} {:>13} {:>8.4} {:>10.1} {:>10.1}",
                    t.resolution,
                    format!("{x}×{y}×{z}"),
                    t.flip,
                    t.frame_ms,
                    t.memory_mib
                )?;
            }
        }
        write!(f, "--res auto: {} — {}", self.resolution, self.reason)
    }
}
