//! The lattice's bounds, below every layout: the voxel counts an axis may have, and how far a
//! lattice may be shifted from its placement (fitted grids and clipmaps alike).

use glam::Vec3;

pub const MIN_RESOLUTION: u32 = 16;
pub const MAX_RESOLUTION: u32 = 512;

/// Whether `shift` (voxels along each axis) moves a lattice by at most half a voxel: a fitted
/// grid's (its one voxel of padding holds it) or a clipmap's, in voxels of its coarsest level
/// (`Clipmap::on_lattice`). `RenderOptions::lattice`, `vct bench --accuracy --lattices`.
pub fn lattice_shift_fits(shift: Vec3) -> bool {
    shift.is_finite() && shift.abs().max_element() <= 0.5
}
