//! Clipmap placement (Wicked Engine's VXGI; Freed 2018 §2.3.2): `levels` cubes of `res`³ voxels
//! around a point (the camera), each twice the extent of the one inside it and moving in steps
//! of 1/16 of its side (`STEPS_PER_SIDE`, whole voxels of its own), so that static geometry
//! voxelizes the same way in every frame and each level's mips group its voxels alike.
//!
//! Levels stay inside the scene. Centred on a camera near the scene's end, a level would spend
//! up to half its voxels on empty space beyond it (measured on Sponza: docs/design/clipmaps.md). So a level is moved, by steps, until it lies inside the scene's bounds, or, along
//! an axis where it is larger than they are, holds them and stays put; the coarsest holds the
//! whole scene wherever the camera is, and is no larger than that. A face of a level that lies beyond the scene is *open*:
//! no level holds anything beyond it, so a cone sample near it stays in that level instead of
//! moving out to the next (common/frame.glsl, `clip_inside`).
//!
//! The levels are stored stacked along z in one volume of `res × res × (levels · res)` texels
//! (level k in texels `k·res .. (k+1)·res` of z): the radiance mip chain of such a stack keeps
//! the levels apart (mip m halves each slab exactly, since `res` is a power of two), so the
//! filter and the sparse storage see one texel grid. This module is the placement: which world
//! box each level covers, and what the shaders are told of it (common/frame.glsl maps points to
//! levels, common/cone.glsl picks the level a cone sample reads; docs/design/clipmaps.md).

use glam::{BVec3, UVec3, Vec3, Vec4};

use super::lattice::{MAX_RESOLUTION, MIN_RESOLUTION};
use crate::error::{Error, Result};

/// Levels the viewer's layout key gives a clipmap.
pub const DEFAULT_LEVELS: u32 = 4;

/// Most clipmap levels (the stack's z extent is `levels · res` ≤ 8 · 512).
pub const MAX_LEVELS: u32 = crate::config::MAX_CLIP_LEVELS;

/// A level moves in steps of 1/16 of its side (4 voxels of 64, 2 of 32), not voxel by voxel.
/// A level's mips group its voxels in blocks aligned to its corner, so a step of one voxel
/// regroups every mip above 0 across the whole level, and the cones' light jumps: measured on a
/// slow pan across Sponza's atrium (4 levels of 64, 3 cm a frame), adjacent frames differed by
/// FLIP 0.0639 on average and 0.0900 at the steps with one-voxel steps, 0.0631 / 0.0816 with two,
/// and 0.0619 / 0.0629 with four, a fitted grid's 0.0610 / 0.0628 (docs/design/clipmaps.md). A step of 2^S voxels keeps mips up to S grouped alike; the price is a level
/// lagging the camera by up to one step, 1/16 of its reach.
pub const STEPS_PER_SIDE: u32 = 16;

/// One axis of a level `e` wide (voxel `v`, step `s`) over a scene from `lo` to `hi`, its corner
/// at `follow` when following the camera: the corner that keeps it inside the scene, with half
/// a voxel to spare, or, where it is wider than the scene, holds the scene, centred on it.
fn place(follow: f32, lo: f32, hi: f32, v: f32, s: f32, e: f32) -> f32 {
    // The corners whose faces lie half a voxel or more beyond the scene's ends: on the voxel
    // lattice for a level that holds the scene (it stays put), on the step lattice otherwise.
    let below = |step: f32| ((lo - 0.5 * v) / step).floor() * step;
    let above = |step: f32| ((hi + 0.5 * v) / step).ceil() * step - e;
    let (low, high) = (below(v), above(v));
    if low >= high {
        return (((lo + hi - e) * 0.5 / v).round() * v).clamp(high, low);
    }
    let (low, high) = (below(s), above(s));
    follow.clamp(low.min(high), low.max(high))
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Clipmap {
    /// Voxels along each axis of every level (a power of two).
    pub res: u32,
    /// Number of levels (1 = a single snapped volume).
    pub levels: u32,
    /// Edge of one voxel of level 0 (world units); level k's is `voxel0 · 2^k`.
    pub voxel0: f32,
    /// World position of each level's minimum corner (`levels` entries used).
    pub origins: [Vec3; MAX_LEVELS as usize],
    /// The scene's bounds the levels stay in (None: they follow the centre wherever it goes).
    pub scene: Option<crate::scene::Aabb>,
    /// Where the levels' lattices start (world units): every level's corner lies on its step
    /// lattice through this point, so the levels stay whole voxels of level 0 apart. Zero by
    /// default; `on_lattice` moves it by under a voxel of the coarsest level, to measure how far
    /// an image depends on where the voxel boundaries fall (`vct bench --accuracy --lattices`).
    pub lattice: Vec3,
}

impl Clipmap {
    /// `levels` levels of `res`³ voxels around `centre`, the finest `extent0` world units wide,
    /// each kept inside `scene` (or holding it) when given.
    pub fn around(
        centre: Vec3,
        extent0: f32,
        res: u32,
        levels: u32,
        scene: Option<&crate::scene::Aabb>,
    ) -> Result<Self> {
        if !(MIN_RESOLUTION..=MAX_RESOLUTION).contains(&res) || !res.is_power_of_two() {
            return Err(Error::param(
                "res",
                format!("{res} is not a power of two in {MIN_RESOLUTION}..={MAX_RESOLUTION} (a clipmap level's side)"),
            ));
        }
        if !(1..=MAX_LEVELS).contains(&levels) {
            return Err(Error::param("clipmap", format!("{levels} levels is not in 1..={MAX_LEVELS}")));
        }
        if !(extent0.is_finite() && extent0 > 0.0 && centre.is_finite()) {
            return Err(Error::param("clipmap", format!("finest extent {extent0} around {centre} is not usable")));
        }
        if let Some(b) = scene.filter(|b| b.is_empty() || !(b.min.is_finite() && b.max.is_finite())) {
            return Err(Error::param(
                "clipmap",
                format!("the scene's bounds {b:?} hold no finite box to place levels in"),
            ));
        }
        let mut c = Clipmap {
            res,
            levels,
            voxel0: extent0 / res as f32,
            origins: [Vec3::ZERO; MAX_LEVELS as usize],
            scene: scene.copied(),
            lattice: Vec3::ZERO,
        };
        c.recentre(centre);
        Ok(c)
    }

    /// The same levels with their lattices moved by `shift` voxels of the coarsest level (each
    /// within ±0.5), placed again around `centre`: the coarsest moves by the shift (it keeps half
    /// a voxel to spare and a voxel for its lattice, `default_extent`), each finer level by
    /// `shift · 2^(levels-1-k)` of its own voxels, a different fraction of a voxel at each level.
    pub fn on_lattice(mut self, centre: Vec3, shift: Vec3) -> Result<Self> {
        if !super::lattice::lattice_shift_fits(shift) {
            return Err(Error::param(
                "lattice",
                format!("{shift} moves clipmap levels by at most half a voxel of the coarsest along each axis"),
            ));
        }
        self.lattice = shift * self.voxel(self.levels - 1);
        self.recentre(centre);
        Ok(self)
    }

    /// Moves every level to `centre` in steps of its own (`step`), and then (with the scene's
    /// bounds), along each axis, by steps until it lies inside the scene, or, where it is larger
    /// than the scene, to a place that holds the scene, where it stays: a level holding all of
    /// the scene along an axis gains nothing by following the camera along it.
    pub fn recentre(&mut self, centre: Vec3) {
        // Placed in coordinates whose origin is the lattice's, then moved back.
        let o = self.lattice;
        for k in 0..self.levels {
            let (v, s, e) = (self.voxel(k), self.step(k), self.extent(k));
            let follow = ((centre - o - Vec3::splat(0.5 * e)) / s).floor() * s;
            self.origins[k as usize] = o + match self.scene {
                None => follow,
                Some(b) => Vec3::from_array(std::array::from_fn(|a| {
                    place(follow[a], b.min[a] - o[a], b.max[a] - o[a], v, s, e)
                })),
            };
        }
    }

    /// How far level `k` moves at a time: 1/STEPS_PER_SIDE of its side, in whole voxels.
    pub fn step(&self, k: u32) -> f32 {
        self.voxel(k) * (self.res / STEPS_PER_SIDE).max(1) as f32
    }

    /// Which faces of level `k` lie beyond the scene, half a voxel of the level or more (its
    /// minimum faces, its maximum faces): open faces, beyond which no level holds anything.
    /// The shaders test the same (common/frame.glsl, `clip_inside`).
    pub fn open(&self, k: u32) -> (BVec3, BVec3) {
        let Some(b) = self.scene else { return (BVec3::FALSE, BVec3::FALSE) };
        let (v, o) = (self.voxel(k), self.origins[k as usize]);
        let slack = Vec3::splat(0.5 * v - 1e-3 * v);
        (o.cmple(b.min - slack), (o + Vec3::splat(self.extent(k))).cmpge(b.max + slack))
    }

    /// Voxel edge of level `k`.
    pub fn voxel(&self, k: u32) -> f32 {
        self.voxel0 * (1u32 << k) as f32
    }

    /// World extent of level `k` (each side).
    pub fn extent(&self, k: u32) -> f32 {
        self.voxel(k) * self.res as f32
    }

    /// The finest level's extent for `levels` levels of `res` voxels over a scene of `bounds`:
    /// the coarsest holds the whole scene wherever the camera is (the levels stay in the scene),
    /// with half a voxel to spare on every side and up to a voxel more for its lattice, so its
    /// voxel is the scene's longest side over `res - 3` (a surface outside every level gets no
    /// indirect light). Levels are no larger than that: what lies beyond the scene is empty.
    pub fn default_extent(bounds: &crate::scene::Aabb, res: u32, levels: u32) -> f32 {
        let longest = bounds.size().max_element().max(1e-6);
        let coarsest = longest * res as f32 / res.saturating_sub(3).max(1) as f32;
        coarsest / (1u32 << levels.clamp(1, MAX_LEVELS).saturating_sub(1)) as f32
    }

    /// For the shaders (`FrameUniforms::clip`, `clip_levels`, `clip_scene`; common/frame.glsl):
    /// the level count, a level's side in texels and the blend band (of a level's side); each
    /// level's minimum corner in voxels of level 0 from level 0's, with its voxel over level 0's;
    /// and the scene's bounds in the same units (unbounded without them: no face is open).
    pub fn gpu(&self) -> (Vec4, [Vec4; MAX_LEVELS as usize], [Vec4; 2]) {
        let mut levels = [Vec4::ZERO; MAX_LEVELS as usize];
        for k in 0..self.levels {
            let at = (self.origins[k as usize] - self.origins[0]) / self.voxel0;
            levels[k as usize] = at.round().extend((1u32 << k) as f32);
        }
        let scene = match self.scene {
            Some(b) => [b.min, b.max].map(|p| ((p - self.origins[0]) / self.voxel0).extend(0.0)),
            None => [Vec4::splat(-1e30), Vec4::splat(1e30)],
        };
        (Vec4::new(self.levels as f32, self.res as f32, crate::config::CLIP_BLEND_BAND, 0.0), levels, scene)
    }

    /// The texel extent of the stack that holds every level.
    pub fn stack_dims(&self) -> UVec3 {
        UVec3::new(self.res, self.res, self.res * self.levels)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_nest_and_double() {
        let c = Clipmap::around(Vec3::new(1.3, -2.7, 0.4), 4.0, 32, 5, None).unwrap();
        for k in 0..5 {
            assert!((c.extent(k) - 4.0 * (1 << k) as f32).abs() < 1e-4);
        }
        for k in 1..5 {
            let (inner, outer) = (c.level_grid(k - 1).bounds(), c.level_grid(k).bounds());
            // Each level holds the one inside it (snapping moves each by under one of its voxels).
            assert!(outer.min.cmple(inner.min).all() && outer.max.cmpge(inner.max).all(), "level {k}");
        }
        assert_eq!(c.stack_dims(), UVec3::new(32, 32, 160));
    }

    #[test]
    fn snapping_moves_each_level_in_whole_voxels_of_its_own() {
        let mut c = Clipmap::around(Vec3::ZERO, 8.0, 16, 4, None).unwrap();
        let before = c.origins;
        for step in 1..200 {
            c.recentre(Vec3::new(0.013, 0.007, -0.021) * step as f32);
            for k in 0..4 {
                let moved = (c.origins[k as usize] - before[k as usize]) / c.voxel(k);
                assert!((moved - moved.round()).abs().max_element() < 1e-3, "level {k} moved {moved}");
            }
        }
        // A coarse level moves less often than a fine one.
        let moves = |k: usize| {
            let mut c = Clipmap::around(Vec3::ZERO, 8.0, 16, 4, None).unwrap();
            let mut last = c.origins[k];
            let mut n = 0;
            for step in 1..400 {
                c.recentre(Vec3::X * 0.01 * step as f32);
                n += (c.origins[k] != last) as u32;
                last = c.origins[k];
            }
            n
        };
        assert!(moves(0) > moves(1) && moves(1) > moves(2), "{} {} {}", moves(0), moves(1), moves(2));
    }

    /// A long hall, like Sponza's atrium (34.8 × 15 × 22 m).
    fn hall() -> crate::scene::Aabb {
        crate::scene::Aabb { min: Vec3::new(-17.4, 0.0, -11.0), max: Vec3::new(17.4, 15.0, 11.0) }
    }

    /// Cameras over the hall and beyond it, from a fixed sequence.
    fn cameras() -> impl Iterator<Item = Vec3> {
        let b = hall();
        (0..400u32).map(move |i| {
            let f = |s: u32| ((i.wrapping_mul(2654435761).wrapping_add(s) % 1000) as f32 / 999.0) * 1.3 - 0.15;
            b.min + b.size() * Vec3::new(f(1), f(7), f(13))
        })
    }

    #[test]
    fn the_default_extent_holds_the_scene_and_the_shaders_get_each_level_in_level_0_voxels() {
        let bounds = hall();
        let eye = Vec3::new(-13.0, 2.0, 0.0);
        let e = Clipmap::default_extent(&bounds, 64, 4);
        // The coarsest level's voxel is the hall's length over 61, not twice the farthest
        // distance from the camera: the levels stay in the scene.
        assert!((e * 8.0 / 64.0 - 34.8 / 61.0).abs() < 1e-4, "{e}");
        let c = Clipmap::around(eye, e, 64, 4, Some(&bounds)).unwrap();
        let coarsest = c.level_grid(3).bounds();
        assert!(coarsest.min.cmple(bounds.min).all() && coarsest.max.cmpge(bounds.max).all(), "{coarsest:?}");
        let (head, levels, scene) = c.gpu();
        assert_eq!(scene[0].truncate(), (bounds.min - c.origins[0]) / c.voxel0);
        assert_eq!((head.x, head.y), (4.0, 64.0));
        for k in 0..4 {
            let l = levels[k as usize];
            assert_eq!(l.w, (1 << k) as f32);
            // Whole voxels of level 0 (each level snaps to its own voxel, a multiple of level 0's).
            let back = c.origins[0] + l.truncate() * c.voxel0;
            assert!((back - c.origins[k as usize]).abs().max_element() < 1e-3 * c.voxel(k), "level {k}");
        }
        assert_eq!(levels[4], Vec4::ZERO);
        // The stack as the volume's grid: level 0's corner and voxel, every level's texels.
        let g = c.stack_grid();
        assert_eq!((g.origin, g.voxel, g.dims), (c.origins[0], c.voxel0, UVec3::new(64, 64, 256)));
        assert_eq!(g.voxelized().dims, UVec3::splat(64));
    }

    /// Wherever the camera is (inside the hall, near its ends, beyond it), the coarsest level
    /// holds the whole hall; every level lies inside the hall or holds it along each axis, with
    /// less than a voxel (plus the half voxel to spare) beyond it; the levels still nest; and a
    /// face is open exactly when it lies beyond the hall. The same holds with the lattices moved
    /// by under a voxel of the coarsest (`on_lattice`), each level's corner then on its own
    /// voxel lattice through the moved origin and whole voxels of level 0 from level 0's.
    #[test]
    fn levels_stay_in_the_scene_and_nest() {
        let b = hall();
        let e = Clipmap::default_extent(&b, 32, 4);
        let shifts = [Vec3::ZERO, Vec3::new(0.31, -0.47, 0.12), Vec3::new(-0.5, 0.5, 0.23)];
        for (eye, shift) in cameras().zip(shifts.iter().cycle()) {
            let c = Clipmap::around(Vec3::ZERO, e, 32, 4, Some(&b)).unwrap().on_lattice(eye, *shift).unwrap();
            assert_eq!(c.lattice, *shift * c.voxel(3));
            let (_, levels, _) = c.gpu();
            for k in 0..4 {
                let on = (c.origins[k as usize] - c.lattice) / c.voxel(k);
                assert!((on - on.round()).abs().max_element() < 1e-3, "{eye} {shift}: level {k} off its lattice: {on}");
                let back = c.origins[0] + levels[k as usize].truncate() * c.voxel0;
                assert!(
                    (back - c.origins[k as usize]).abs().max_element() < 1e-3 * c.voxel0,
                    "{eye} {shift}: level {k}"
                );
            }
            let top = c.level_grid(3).bounds();
            assert!(top.min.cmple(b.min).all() && top.max.cmpge(b.max).all(), "{eye}: {top:?}");
            for k in 0..4 {
                let (v, box_k) = (c.voxel(k), c.level_grid(k).bounds());
                let (open_lo, open_hi) = c.open(k);
                let (open_lo, open_hi): ([bool; 3], [bool; 3]) = (open_lo.into(), open_hi.into());
                for a in 0..3 {
                    let (lo, hi) = (box_k.min[a], box_k.max[a]);
                    if hi - lo < b.max[a] - b.min[a] {
                        // Inside: no further out than its steps need.
                        let out = 0.5 * v + c.step(k) + 1e-4;
                        assert!(lo > b.min[a] - out && hi < b.max[a] + out, "{eye} level {k} axis {a}");
                    } else {
                        // Holding the scene: both faces open.
                        assert!(open_lo[a] && open_hi[a], "{eye} level {k} axis {a}: {lo} {hi}");
                    }
                    assert_eq!(open_lo[a], lo <= b.min[a] - 0.499 * v, "{eye} level {k} axis {a}");
                    assert_eq!(open_hi[a], hi >= b.max[a] + 0.499 * v, "{eye} level {k} axis {a}");
                }
                if k > 0 {
                    let inner = c.level_grid(k - 1).bounds();
                    assert!(box_k.min.cmple(inner.min).all() && box_k.max.cmpge(inner.max).all(), "{eye}: level {k}");
                }
            }
        }
        // A camera in the middle of the hall sees the levels centred on it (Wicked Engine's
        // placement), its finest level closed on every side.
        let mut c = Clipmap::around(Vec3::ZERO, e, 32, 4, Some(&b)).unwrap();
        c.recentre(Vec3::new(0.0, 7.5, 0.0));
        let fine = c.level_grid(0).bounds();
        assert!(((fine.min + fine.max) * 0.5 - Vec3::new(0.0, 7.5, 0.0)).abs().max_element() <= c.step(0));
        assert_eq!(c.open(0), (BVec3::FALSE, BVec3::FALSE));
    }

    /// Inside the scene a level moves in whole steps of its own, 1/16 of its side (so its mips
    /// group its voxels alike wherever it is); along an axis where it holds the scene it stays.
    #[test]
    fn levels_in_the_scene_move_in_whole_steps_or_stay() {
        let b = hall();
        let mut c = Clipmap::around(Vec3::ZERO, 6.0, 64, 4, Some(&b)).unwrap();
        assert!((c.step(0) - 4.0 * c.voxel(0)).abs() < 1e-6);
        let before = c.origins;
        for eye in cameras() {
            c.recentre(eye);
            for k in 0..4 {
                let moved = (c.origins[k as usize] - before[k as usize]) / c.step(k);
                for a in 0..3 {
                    if c.extent(k) > b.max[a] - b.min[a] + c.voxel(k) {
                        assert_eq!(c.origins[k as usize][a], before[k as usize][a], "level {k} axis {a} moved");
                    } else {
                        assert!((moved[a] - moved[a].round()).abs() < 1e-3, "level {k} moved {moved}");
                    }
                }
            }
        }
    }

    #[test]
    fn bad_parameters_name_themselves() {
        assert!(Clipmap::around(Vec3::ZERO, 4.0, 48, 4, None).unwrap_err().to_string().contains("res"));
        assert!(Clipmap::around(Vec3::ZERO, 4.0, 32, 0, None).unwrap_err().to_string().contains("clipmap"));
        assert!(Clipmap::around(Vec3::ZERO, f32::NAN, 32, 4, None).unwrap_err().to_string().contains("clipmap"));
        let c = Clipmap::around(Vec3::ZERO, 4.0, 32, 4, None).unwrap();
        for bad in [Vec3::new(0.0, 0.6, 0.0), Vec3::splat(f32::NAN)] {
            assert!(c.on_lattice(Vec3::ZERO, bad).unwrap_err().to_string().contains("lattice"), "{bad}");
        }
        let empty = crate::scene::Aabb::EMPTY;
        assert!(Clipmap::around(Vec3::ZERO, 4.0, 32, 4, Some(&empty)).unwrap_err().to_string().contains("bounds"));
    }
}
