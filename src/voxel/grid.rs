//! The voxel grid: a cube of N³ voxels fitted to the scene bounds and padded by one voxel on
//! every side (Freed 2018 §4.1: the volume encloses the whole scene).

use glam::Vec3;

use crate::error::{Error, Result};
use crate::scene::Aabb;

pub const MIN_RESOLUTION: u32 = 16;
pub const MAX_RESOLUTION: u32 = 512;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VoxelGrid {
    /// World position of the grid's minimum corner.
    pub origin: Vec3,
    /// Edge length of one voxel (world units).
    pub voxel: f32,
    pub resolution: u32,
}

impl VoxelGrid {
    /// The grid of `resolution`³ voxels that holds `bounds` with one voxel of padding.
    pub fn fit(bounds: &Aabb, resolution: u32) -> Result<Self> {
        if !(MIN_RESOLUTION..=MAX_RESOLUTION).contains(&resolution) {
            return Err(Error::param("res", format!("{resolution} is outside {MIN_RESOLUTION}..={MAX_RESOLUTION}")));
        }
        if bounds.is_empty() || !bounds.min.is_finite() || !bounds.max.is_finite() {
            return Err(Error::param("scene", "the scene has no finite geometry to voxelize"));
        }
        let extent = bounds.size().max_element().max(1e-6);
        let voxel = extent / (resolution - 2) as f32;
        let origin = bounds.center() - Vec3::splat(voxel * resolution as f32 * 0.5);
        Ok(VoxelGrid { origin, voxel, resolution })
    }

    /// A grid of `extent` world units around `centre` (a volume following the camera). With
    /// `snap` the origin moves in whole voxels (Freed 2018 §4.1), so the voxelization of static
    /// geometry does not change as the centre slides.
    pub fn around(centre: Vec3, extent: f32, resolution: u32, snap: bool) -> Result<Self> {
        if !(MIN_RESOLUTION..=MAX_RESOLUTION).contains(&resolution) {
            return Err(Error::param("res", format!("{resolution} is outside {MIN_RESOLUTION}..={MAX_RESOLUTION}")));
        }
        if !(extent.is_finite() && extent > 0.0 && centre.is_finite()) {
            return Err(Error::param("follow", format!("volume extent {extent} around {centre} is not usable")));
        }
        let voxel = extent / resolution as f32;
        let mut origin = centre - Vec3::splat(extent * 0.5);
        if snap {
            origin = (origin / voxel).floor() * voxel;
        }
        Ok(VoxelGrid { origin, voxel, resolution })
    }

    /// Bytes of GPU memory for the voxel textures: albedo, normal, emission (R32UI each) and
    /// radiance with its mip chain (RGBA16F, 8/7 of the base level), its injection target, and
    /// the six directional chains from level 1 (each 1/8 × 8/7 of the base).
    pub fn memory_bytes(&self) -> u64 {
        let n3 = (self.resolution as u64).pow(3);
        3 * 4 * n3 + 8 * n3 * 8 / 7 + 8 * n3 + 6 * 8 * n3 / 7
    }

    pub fn voxel_count(&self) -> usize {
        (self.resolution as usize).pow(3)
    }

    /// Linear index of voxel (x, y, z), x fastest (the layout of a read-back 3D image).
    pub fn index(&self, x: u32, y: u32, z: u32) -> usize {
        let n = self.resolution as usize;
        x as usize + n * (y as usize + n * z as usize)
    }
}
