//! The voxel grid: cubic voxels, each axis with its own count, fitted to the scene bounds and
//! padded by one voxel on every side (Freed 2018 §4.1: the volume encloses the whole scene; it
//! need not be a cube — a long hall is modelled by a long box of voxels, not by the cube around
//! it).
//!
//! Every axis count is a power of two. The radiance volume's mip chain halves each axis exactly
//! at every level (Vulkan rounds odd extents down, and a level whose texels no longer cover
//! 2^L voxels would misplace every cone sample read from it), and the directional chains share
//! one atlas stacked along y (render::radiance) that stays aligned only while its blocks halve
//! exactly. A power of two per axis keeps a fitted grid within 2× of the bounds along each
//! axis; the mip chain ends where the shortest axis reaches one texel.

use glam::{UVec3, Vec3};

use super::clipmap::Clipmap;
use super::warp::Warp;
use ash::vk;

use crate::error::{Error, Result};
use crate::scene::Aabb;

/// The image extent of a grid's dims.
pub fn extent_of(dims: glam::UVec3) -> vk::Extent3D {
    vk::Extent3D { width: dims.x, height: dims.y, depth: dims.z }
}

pub use super::lattice::{lattice_shift_fits, MAX_RESOLUTION, MIN_RESOLUTION};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VoxelGrid {
    /// World position of the grid's minimum corner.
    pub origin: Vec3,
    /// Edge length of one voxel (world units).
    pub voxel: f32,
    /// Voxels along x, y and z (each a power of two in MIN_RESOLUTION..=MAX_RESOLUTION).
    pub dims: UVec3,
    /// How the texels spread over the box (`Warp::NONE`: evenly, `voxel` wide each).
    pub warp: Warp,
    /// A clipmap's levels, stacked along z (`voxel::clipmap`): `origin` and `voxel` are its
    /// finest level's, `dims` the stack's. `None`: one grid.
    pub clip: Option<Clipmap>,
}

fn check_axis(name: &'static str, n: u32) -> Result<()> {
    if !(MIN_RESOLUTION..=MAX_RESOLUTION).contains(&n) || !n.is_power_of_two() {
        return Err(Error::param(
            name,
            format!("{n} is not a power of two in {MIN_RESOLUTION}..={MAX_RESOLUTION} (mip levels halve every axis exactly)"),
        ));
    }
    Ok(())
}

fn check_bounds(bounds: &Aabb) -> Result<()> {
    if bounds.is_empty() || !bounds.min.is_finite() || !bounds.max.is_finite() {
        return Err(Error::param("scene", "the scene has no finite geometry to voxelize"));
    }
    Ok(())
}

impl VoxelGrid {
    /// The fitted grid with `longest` voxels along the bounds' longest axis: cubic voxels sized so
    /// that axis holds the bounds plus one voxel each side, and each other axis the smallest power
    /// of two that holds its extent plus that padding.
    pub fn fit(bounds: &Aabb, longest: u32) -> Result<Self> {
        check_axis("res", longest)?;
        check_bounds(bounds)?;
        let size = bounds.size();
        let voxel = size.max_element().max(1e-6) / (longest - 2) as f32;
        let need =
            |e: f32| (((e / voxel).ceil() as u32).saturating_add(2)).next_power_of_two().clamp(MIN_RESOLUTION, longest);
        let dims = UVec3::new(need(size.x), need(size.y), need(size.z));
        Ok(Self::centred(bounds, voxel, dims))
    }

    /// The grid of exactly `dims` voxels around `bounds`: the voxel is the smallest that fits the
    /// bounds plus one voxel of padding along every axis.
    pub fn fit_dims(bounds: &Aabb, dims: UVec3) -> Result<Self> {
        for (name, n) in [("dims (x)", dims.x), ("dims (y)", dims.y), ("dims (z)", dims.z)] {
            check_axis(name, n)?;
        }
        check_bounds(bounds)?;
        let size = bounds.size().max(Vec3::splat(1e-6));
        let voxel = (size / (dims - 2).as_vec3()).max_element();
        Ok(Self::centred(bounds, voxel, dims))
    }

    fn centred(bounds: &Aabb, voxel: f32, dims: UVec3) -> Self {
        VoxelGrid { origin: bounds.center() - dims.as_vec3() * voxel * 0.5, voxel, dims, warp: Warp::NONE, clip: None }
    }

    /// `dims` when given, else the fitted grid with `longest` voxels along the longest axis.
    pub fn choose(bounds: &Aabb, longest: u32, dims: Option<UVec3>) -> Result<Self> {
        match dims {
            Some(d) => Self::fit_dims(bounds, d),
            None => Self::fit(bounds, longest),
        }
    }

    /// A cube of `extent` world units around `centre` (a volume following the camera). With
    /// `snap` the origin moves in whole voxels (Freed 2018 §4.1), so the voxelization of static
    /// geometry does not change as the centre slides.
    pub fn around(centre: Vec3, extent: f32, resolution: u32, snap: bool) -> Result<Self> {
        check_axis("res", resolution)?;
        if !(extent.is_finite() && extent > 0.0 && centre.is_finite()) {
            return Err(Error::param("follow", format!("volume extent {extent} around {centre} is not usable")));
        }
        let voxel = extent / resolution as f32;
        let mut origin = centre - Vec3::splat(extent * 0.5);
        if snap {
            origin = (origin / voxel).floor() * voxel;
        }
        Ok(VoxelGrid { origin, voxel, dims: UVec3::splat(resolution), warp: Warp::NONE, clip: None })
    }

    /// The grid warped by the thesis' function (Freed 2018 §4.6.1) with its finest texels at
    /// `focus` (world; clamped into the box) and slope `end_slope` at the faces.
    pub fn warped(self, focus: Vec3, end_slope: f32) -> Result<Self> {
        let centre = (focus - self.origin) / (self.dims.as_vec3() * self.voxel);
        Ok(VoxelGrid { warp: Warp::function(centre, end_slope)?, ..self })
    }

    /// Whether the texels spread unevenly (shaders built for the grid then keep the warp's code).
    pub fn is_warped(&self) -> bool {
        !self.warp.is_none()
    }

    /// The grid one voxelization draw writes: the grid itself, or a clipmap's finest level (each
    /// level's draw moves it to its own box, `Voxelizer::record`).
    pub fn voxelized(&self) -> VoxelGrid {
        self.clip.map_or(*self, |c| c.level_grid(0))
    }

    /// How the shaders that map world space to the texels are specialized for this grid.
    pub fn spec(&self) -> crate::gpu::GridSpec {
        crate::gpu::GridSpec { warped: self.is_warped(), clipped: self.clip.is_some() }
    }

    /// The same warp following the view: a function warp's finest texels moved to `focus`, a
    /// perspective warp's frustum rebuilt around `camera`'s view of `bounds`.
    pub fn refocused(self, focus: Vec3, camera: &crate::scene::Camera, bounds: &Aabb) -> Result<Self> {
        match self.warp {
            Warp::None => Ok(self),
            Warp::Function(f) if f.is_none() => Ok(self),
            Warp::Function(f) => self.warped(focus, f.end_slope),
            Warp::Perspective(p) => VoxelGrid::perspective(camera, bounds, self.dims, p.ratio),
        }
    }

    /// Texel coordinates of world point `p` (texel v spans [v, v + 1)).
    pub fn texel_of(&self, p: Vec3) -> glam::DVec3 {
        let x = ((p - self.origin) / (self.dims.as_vec3() * self.voxel)).as_dvec3();
        self.warp.forward3(x) * self.dims.as_dvec3()
    }

    /// The world position of texture fraction `t` (the inverse of [`Self::texel_of`] over dims).
    pub fn world_of(&self, t: glam::DVec3) -> Vec3 {
        let size = (self.dims.as_vec3() * self.voxel).as_dvec3();
        (self.origin.as_dvec3() + self.warp.inverse3(t) * size).as_vec3()
    }

    /// The world box of texel `v` (a perspective texel, a frustum's cell: the box around it).
    pub fn texel_bounds(&self, v: UVec3) -> Aabb {
        let mut b = Aabb::EMPTY;
        for i in 0..8u32 {
            let corner = v + UVec3::new(i & 1, (i >> 1) & 1, (i >> 2) & 1);
            b.grow(self.world_of(corner.as_dvec3() / self.dims.as_dvec3()));
        }
        b
    }

    /// Voxels along the longest axis (the `--res` the grid answers to).
    pub fn longest(&self) -> u32 {
        self.dims.max_element()
    }

    /// Voxels along the shortest axis.
    pub fn shortest(&self) -> u32 {
        self.dims.min_element()
    }

    /// Mip levels of the radiance volume: until the shortest axis is one texel.
    pub fn mip_levels(&self) -> u32 {
        32 - self.shortest().leading_zeros()
    }

    /// `x×y×z`, for messages.
    pub fn dims_label(&self) -> String {
        format!("{}×{}×{}", self.dims.x, self.dims.y, self.dims.z)
    }

    pub fn voxel_count(&self) -> usize {
        self.dims.x as usize * self.dims.y as usize * self.dims.z as usize
    }

    /// The grid's world-space box.
    pub fn bounds(&self) -> Aabb {
        Aabb { min: self.origin, max: self.origin + self.dims.as_vec3() * self.voxel }
    }

    /// Linear index of voxel (x, y, z), x fastest (the layout of a read-back 3D image).
    pub fn index(&self, x: u32, y: u32, z: u32) -> usize {
        let (nx, ny) = (self.dims.x as usize, self.dims.y as usize);
        x as usize + nx * (y as usize + ny * z as usize)
    }

    /// The coordinates of linear index `i` (the inverse of [`Self::index`]).
    pub fn coords(&self, i: usize) -> UVec3 {
        let (nx, ny) = (self.dims.x as usize, self.dims.y as usize);
        UVec3::new((i % nx) as u32, ((i / nx) % ny) as u32, (i / (nx * ny)) as u32)
    }
}

/// A clipmap's levels as grids.
impl Clipmap {
    /// Level `k` as a grid of its own (what its voxelization pass is given).
    pub fn level_grid(&self, k: u32) -> VoxelGrid {
        VoxelGrid {
            origin: self.origins[k as usize],
            voxel: self.voxel(k),
            dims: UVec3::splat(self.res),
            warp: Warp::NONE,
            clip: None,
        }
    }

    /// The stack as the volume's grid: its finest level's origin and voxel, the stack's dims.
    pub fn stack_grid(&self) -> VoxelGrid {
        VoxelGrid { clip: Some(*self), dims: self.stack_dims(), ..self.level_grid(0) }
    }
}
