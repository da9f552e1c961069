//! Clipmap placement (Wicked Engine's VXGI; Freed 2018 §2.3.2): `levels` cubes of `res`³ voxels
//! around a point (the camera), each twice the extent of the one inside it and snapped to its
//! own voxel size, so that as the point moves each level shifts in whole voxels of its own and
//! static geometry voxelizes the same way in every frame.
//!
//! The levels are stored stacked along z in one volume of `res × res × (levels · res)` texels
//! (level k in texels `k·res .. (k+1)·res` of z): the radiance mip chain of such a stack keeps
//! the levels apart (mip m halves each slab exactly, since `res` is a power of two), so the
//! filter and the sparse storage see one texel grid. This module is the placement only: which
//! world box each level covers, where a world point lands in the stack, and which level a cone
//! sample of a given footprint reads.

use glam::{UVec3, Vec3};

use super::grid::{VoxelGrid, MAX_RESOLUTION, MIN_RESOLUTION};
use crate::error::{Error, Result};

/// Most clipmap levels (the stack's z extent is `levels · res` ≤ 8 · 512).
pub const MAX_LEVELS: u32 = 8;

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
        }
    }

    /// The texel extent of the stack that holds every level.
    pub fn stack_dims(&self) -> UVec3 {
        UVec3::new(self.res, self.res, self.res * self.levels)
    }

    /// The finest level whose box holds `p` with `margin` world units to spare on every side;
    /// `None` outside the coarsest.
    pub fn finest_holding(&self, p: Vec3, margin: f32) -> Option<u32> {
        (0..self.levels).find(|&k| {
            let lo = self.origins[k as usize] + Vec3::splat(margin);
            let hi = self.origins[k as usize] + Vec3::splat(self.extent(k) - margin);
            p.cmpge(lo).all() && p.cmple(hi).all()
        })
    }

    /// Where a cone sample at `p` with footprint `diameter` reads: the finest level that holds
    /// the sample with its radius to spare, and the mip level within it that matches the
    /// footprint (`log2(diameter / voxel)`, at least 0). `None` outside the coarsest level.
    pub fn sample_level(&self, p: Vec3, diameter: f32) -> Option<(u32, f32)> {
        let k = self.finest_holding(p, diameter * 0.5)?;
        Some((k, (diameter / self.voxel(k)).log2().max(0.0)))
    }

    /// Texel coordinates of world point `p` in level `k`'s slab of the stack (texel v spans
    /// [v, v + 1)); z includes the slab's offset `k · res`.
    pub fn stack_texel(&self, k: u32, p: Vec3) -> Vec3 {
        let t = (p - self.origins[k as usize]) / self.voxel(k);
        t + Vec3::new(0.0, 0.0, (k * self.res) as f32)
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
    fn samples_read_the_finest_level_that_holds_them() {
        let c = Clipmap::around(Vec3::ZERO, 4.0, 32, 4).unwrap();
        assert_eq!(c.sample_level(Vec3::ZERO, c.voxel0), Some((0, 0.0)));
        // Outside level 0's box, level 1 answers; the footprint picks the mip within it.
        let p = Vec3::new(3.0, 0.0, 0.0);
        let (k, mip) = c.sample_level(p, 4.0 * c.voxel0).unwrap();
        assert_eq!(k, 1);
        assert!((mip - 1.0).abs() < 1e-5);
        // A wide cone near the finest level's face moves out to where its footprint fits.
        let (k, _) = c.sample_level(Vec3::new(1.9, 0.0, 0.0), 0.5).unwrap();
        assert!(k >= 1);
        assert_eq!(c.sample_level(Vec3::splat(100.0), 0.1), None);
        // The stack places a point in its level's slab.
        let t = c.stack_texel(2, c.origins[2] + Vec3::splat(c.voxel(2) * 0.5));
        assert!((t - Vec3::new(0.5, 0.5, 64.5)).abs().max_element() < 1e-4);
    }

    #[test]
    fn bad_parameters_name_themselves() {
        assert!(Clipmap::around(Vec3::ZERO, 4.0, 48, 4).unwrap_err().to_string().contains("res"));
        assert!(Clipmap::around(Vec3::ZERO, 4.0, 32, 0).unwrap_err().to_string().contains("clipmap"));
        assert!(Clipmap::around(Vec3::ZERO, f32::NAN, 32, 4).unwrap_err().to_string().contains("clipmap"));
    }
}
