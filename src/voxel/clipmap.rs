//! Clipmap placement (Wicked Engine's VXGI; Freed 2018 §2.3.2): `levels` cubes of `res`³ voxels
//! around a point (the camera), each twice the extent of the one inside it and snapped to its
//! own voxel size, so that as the point moves each level shifts in whole voxels of its own and
//! static geometry voxelizes the same way in every frame.
//!
//! The levels are stored stacked along z in one volume of `res × res × (levels · res)` texels
//! (level k in texels `k·res .. (k+1)·res` of z): the radiance mip chain of such a stack keeps
//! the levels apart (mip m halves each slab exactly, since `res` is a power of two), so the
//! filter and the sparse storage see one texel grid. This module is the placement: which world
//! box each level covers, and what the shaders are told of it (common/frame.glsl maps points to
//! levels, common/cone.glsl picks the level a cone sample reads; docs/design/clipmaps.md).

use glam::{UVec3, Vec3, Vec4};

use super::grid::{VoxelGrid, MAX_RESOLUTION, MIN_RESOLUTION};
use crate::error::{Error, Result};

/// Levels the viewer's layout key gives a clipmap.
pub const DEFAULT_LEVELS: u32 = 4;

/// Most clipmap levels (the stack's z extent is `levels · res` ≤ 8 · 512).
pub const MAX_LEVELS: u32 = crate::config::MAX_CLIP_LEVELS;

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
}

impl Clipmap {
    /// `levels` levels of `res`³ voxels around `centre`, the finest `extent0` world units wide.
    pub fn around(centre: Vec3, extent0: f32, res: u32, levels: u32) -> Result<Self> {
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
        let mut c = Clipmap { res, levels, voxel0: extent0 / res as f32, origins: [Vec3::ZERO; MAX_LEVELS as usize] };
        c.recentre(centre);
        Ok(c)
    }

    /// Moves every level to `centre`, each in whole voxels of its own size.
    pub fn recentre(&mut self, centre: Vec3) {
        for k in 0..self.levels {
            let v = self.voxel(k);
            let half = self.extent(k) * 0.5;
            self.origins[k as usize] = ((centre - Vec3::splat(half)) / v).floor() * v;
        }
    }

    /// Voxel edge of level `k`.
    pub fn voxel(&self, k: u32) -> f32 {
        self.voxel0 * (1u32 << k) as f32
    }

    /// World extent of level `k` (each side).
    pub fn extent(&self, k: u32) -> f32 {
        self.voxel(k) * self.res as f32
    }

    /// Level `k` as a grid of its own (what its voxelization pass is given).
    pub fn level_grid(&self, k: u32) -> VoxelGrid {
        VoxelGrid {
            origin: self.origins[k as usize],
            voxel: self.voxel(k),
            dims: UVec3::splat(self.res),
            warp: super::warp::Warp::NONE,
            clip: None,
        }
    }

    /// The finest level's extent for `levels` levels of `res` voxels over a scene of `bounds`
    /// seen from `eye`: the coarsest holds the whole scene around `eye`, with a voxel to spare
    /// for its snapping on every side (a surface outside every level gets no indirect light).
    /// Levels are no larger than that: what lies beyond the scene is empty.
    pub fn default_extent(bounds: &crate::scene::Aabb, eye: Vec3, res: u32, levels: u32) -> f32 {
        let far = (eye - bounds.min).max(bounds.max - eye).max_element().max(1e-6);
        let coarsest = 2.0 * far * res as f32 / res.saturating_sub(2).max(1) as f32;
        coarsest / (1u32 << levels.clamp(1, MAX_LEVELS).saturating_sub(1)) as f32
    }

    /// The stack as the volume's grid: its finest level's origin and voxel, the stack's dims.
    pub fn stack_grid(&self) -> VoxelGrid {
        VoxelGrid { clip: Some(*self), dims: self.stack_dims(), ..self.level_grid(0) }
    }

    /// For the shaders (`FrameUniforms::clip`, `clip_levels`; common/frame.glsl): the level
    /// count, a level's side in texels and the blend band (of a level's side); and each level's
    /// minimum corner in voxels of level 0 from level 0's, with its voxel over level 0's.
    pub fn gpu(&self) -> (Vec4, [Vec4; MAX_LEVELS as usize]) {
        let mut levels = [Vec4::ZERO; MAX_LEVELS as usize];
        for k in 0..self.levels {
            let at = (self.origins[k as usize] - self.origins[0]) / self.voxel0;
            levels[k as usize] = at.round().extend((1u32 << k) as f32);
        }
        (Vec4::new(self.levels as f32, self.res as f32, crate::config::CLIP_BLEND_BAND, 0.0), levels)
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
        let c = Clipmap::around(Vec3::new(1.3, -2.7, 0.4), 4.0, 32, 5).unwrap();
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
        let mut c = Clipmap::around(Vec3::ZERO, 8.0, 16, 4).unwrap();
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
            let mut c = Clipmap::around(Vec3::ZERO, 8.0, 16, 4).unwrap();
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

    #[test]
    fn the_default_extent_holds_the_scene_and_the_shaders_get_each_level_in_level_0_voxels() {
        let bounds = crate::scene::Aabb { min: Vec3::new(-15.0, 0.0, -6.0), max: Vec3::new(15.0, 12.0, 6.0) };
        let eye = Vec3::new(-13.0, 2.0, 0.0);
        let e = Clipmap::default_extent(&bounds, eye, 64, 4);
        let c = Clipmap::around(eye, e, 64, 4).unwrap();
        let coarsest = c.level_grid(3).bounds();
        assert!(coarsest.min.cmple(bounds.min).all() && coarsest.max.cmpge(bounds.max).all(), "{coarsest:?}");
        let (head, levels) = c.gpu();
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

    #[test]
    fn bad_parameters_name_themselves() {
        assert!(Clipmap::around(Vec3::ZERO, 4.0, 48, 4).unwrap_err().to_string().contains("res"));
        assert!(Clipmap::around(Vec3::ZERO, 4.0, 32, 0).unwrap_err().to_string().contains("clipmap"));
        assert!(Clipmap::around(Vec3::ZERO, f32::NAN, 32, 4).unwrap_err().to_string().contains("clipmap"));
    }
}
