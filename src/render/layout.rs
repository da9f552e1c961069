//! The volume's layout, one of four siblings: a grid fitted to the scene, a cube following the
//! camera (Freed 2018 §4.1), a warped grid (§4.6.1, §4.6.2) or clipmap levels around the camera
//! (Wicked Engine's VXGI; §2.3.2). Which grid a renderer's options ask for, and what each layout
//! cannot be combined with.

use super::{ClipOptions, RenderOptions};
use crate::error::Result;
use crate::gpu::Context;
use crate::scene::Scene;
use crate::voxel::clipmap::Clipmap;
use crate::voxel::VoxelGrid;

impl RenderOptions {
    /// Whether the volume moves with the camera (a following cube, a warp's focus, a clipmap).
    pub fn moving(&self) -> bool {
        self.follow.is_some() || self.warp.is_some() || self.clipmap.is_some()
    }
}

/// The grid `options` ask for over `scene`, `resolution` voxels along its longest axis (a
/// clipmap's: along each level's).
pub fn grid_for(ctx: &Context, scene: &Scene, options: &RenderOptions, resolution: u32) -> Result<VoxelGrid> {
    if let Some(c) = options.clipmap {
        if scene.settings.gi.temporal < 1.0 {
            // The history is kept texel by texel: each level scrolls on its own.
            return Err(crate::Error::param(
                "temporal",
                "temporal filtering of a clipmap is not supported: give --temporal 1",
            ));
        }
        return clipmap_grid(ctx, scene, options, c, resolution);
    }
    if let Some(shift) = options.lattice {
        if options.follow.is_some() || !crate::voxel::grid::lattice_shift_fits(shift) {
            return Err(crate::Error::param(
                "lattice",
                format!("{shift} moves a fitted grid by at most half a voxel along each axis (its padding)"),
            ));
        }
    }
    let grid = match (options.follow, options.dims) {
        (Some(_), Some(_)) => {
            return Err(crate::Error::param("dims", "a volume following the camera is a cube: give --res, not --dims"))
        }
        (Some(f), None) => VoxelGrid::around(scene.camera.eye, f.extent, resolution, f.snap)?,
        (None, dims) => {
            let grid = VoxelGrid::choose(&scene.mesh.bounds, resolution, dims)?;
            VoxelGrid { origin: grid.origin + options.lattice.unwrap_or_default() * grid.voxel, ..grid }
        }
    };
    if let (Some(crate::voxel::warp::WarpChoice::Perspective(_)), Some(_)) = (options.warp, options.follow) {
        return Err(crate::Error::param(
            "warp",
            "a perspective warp spans the camera's frustum: --follow does not apply",
        ));
    }
    let grid = match options.warp {
        Some(w) => w.apply(grid, &scene.camera, &scene.mesh.bounds)?,
        None => grid,
    };
    if options.warp.is_some() && scene.settings.gi.temporal < 1.0 {
        // The history is kept texel by texel: a warp that follows the camera moves every texel.
        return Err(crate::Error::param(
            "temporal",
            "temporal filtering of a warped volume is not supported: give --temporal 1",
        ));
    }
    Ok(grid)
}

/// The stack of a clipmap's levels around the scene's camera, checked against the options it
/// cannot be combined with and the device's 3D image limit.
fn clipmap_grid(
    ctx: &Context,
    scene: &Scene,
    options: &RenderOptions,
    c: ClipOptions,
    resolution: u32,
) -> Result<VoxelGrid> {
    let other = if options.follow.is_some() {
        Some("--follow")
    } else if options.dims.is_some() {
        Some("--dims")
    } else if options.warp.is_some() {
        Some("--warp")
    } else {
        None
    };
    if let Some(other) = other {
        return Err(crate::Error::param(
            "clipmap",
            format!("clipmap levels are cubes of --res voxels around the camera: {other} does not apply"),
        ));
    }
    let bounds = &scene.mesh.bounds;
    let extent = c.extent.unwrap_or_else(|| Clipmap::default_extent(bounds, resolution, c.levels));
    let mut clip = Clipmap::around(scene.camera.eye, extent, resolution, c.levels, Some(bounds))?;
    if let Some(shift) = options.lattice {
        clip = clip.on_lattice(scene.camera.eye, shift)?;
    }
    let grid = clip.stack_grid();
    let max = ctx.info.limits.max_image_dimension3_d;
    if grid.dims.z > max {
        return Err(crate::Error::param(
            "clipmap",
            format!(
                "{} levels of {resolution} voxels stack {} texels deep, beyond the device's 3D image limit {max}",
                c.levels, grid.dims.z
            ),
        ));
    }
    Ok(grid)
}
