//! The thesis' perspective warp (Freed 2018 §4.6.2): the grid's texels divide the camera's view
//! frustum, small near the camera and large far from it, so their size on screen stays alike.
//!
//! The thesis maps a point through the camera's view and projection matrices to NDC and then
//! linearizes depth (its footnote 12). A linear depth under a perspective x and y bends every
//! plane (x/z against z), so a triangle is no longer flat among the texels, and no voxelizer could
//! then test it exactly. Here depth keeps its projective form, 1/d: the whole map is a projective
//! transformation, planes stay planes, and each voxelizer voxelizes the mapped triangle as it does
//! on an even grid (the geometry stage clips it at the apex's side first).
//!
//! The frustum's apex sits a distance e behind the eye, so that its near plane passes through
//! the eye, and its far plane lies at the depth D of the scene's farthest corner in front of the
//! eye; it holds the camera's frustum from the eye out to D. A texel at distance W from the apex
//! is W/e times a near one across and (W/e)² deep. `ratio` = e / (e + D), the near texels' width
//! over the far ones', sets the warp's strength as the function warp's end slope does (both 0.25
//! by default: the thesis' slope; towards 1 the frustum opens into a box). What lies outside the
//! frustum has no texels: light from behind the camera is lost (the thesis' frustum too).
//!
//! The shaders' copy is in `shaders-glsl/common/warp.glsl`; the exact coverage reference maps
//! triangles with its own code (`reference::coverage::RefPerspective`).

use glam::{DMat4, DVec3, DVec4, UVec3};

use super::grid::VoxelGrid;
pub use super::warp::{Perspective, DEFAULT_RATIO};
use super::warp::{Warp, WarpChoice};
use crate::error::{Error, Result};
use crate::scene::{Aabb, Camera};

/// A row of the world-to-texture map: `a · p + b`, as a 4-vector acting on (p, 1).
fn row(a: DVec3, b: f64) -> DVec4 {
    a.extend(b)
}

impl WarpChoice {
    /// `grid` (fitted to `bounds`) warped as chosen, its finest texels at `camera`: the
    /// perspective warp holds as many texels as the grid (`VoxelGrid::perspective_dims`).
    pub fn apply(
        &self,
        grid: VoxelGrid,
        camera: &crate::scene::Camera,
        bounds: &crate::scene::Aabb,
    ) -> Result<VoxelGrid> {
        match *self {
            WarpChoice::Function(s) => grid.warped(camera.eye, s),
            WarpChoice::Perspective(r) => {
                VoxelGrid::perspective(camera, bounds, VoxelGrid::perspective_dims(&grid, camera), r)
            }
        }
    }
}

impl VoxelGrid {
    /// The texel counts of a perspective grid holding as many texels as `fitted`: its longest axis
    /// across the image, the image's aspect up it (a power of two), and the rest in depth.
    pub fn perspective_dims(fitted: &VoxelGrid, camera: &Camera) -> UVec3 {
        let pow2 = |v: f64| 2f64.powf(v.max(1.0).log2().round()) as u32;
        let x = fitted.longest();
        let y = pow2(x as f64 * camera.height.max(1) as f64 / camera.width.max(1) as f64)
            .clamp(super::grid::MIN_RESOLUTION, x);
        let count = fitted.dims.as_dvec3().element_product();
        let z = pow2(count / (x as f64 * y as f64)).clamp(super::grid::MIN_RESOLUTION, x);
        UVec3::new(x, y, z)
    }

    /// The perspective-warped grid of `dims` texels (x and y across the image, z in depth) over
    /// `camera`'s frustum out to the far side of `bounds`, with near texels `ratio` times as wide
    /// as far ones. The grid's box, which the cones march through in voxels of its own, holds
    /// the frustum's part inside the bounds.
    pub fn perspective(camera: &Camera, bounds: &Aabb, dims: UVec3, ratio: f32) -> Result<VoxelGrid> {
        let even = VoxelGrid::fit_dims(bounds, dims)?; // checks the counts and the bounds
        if !(ratio.is_finite() && (0.05..=0.95).contains(&ratio)) {
            return Err(Error::param(
                "warp-slope",
                format!("{ratio} is not in 0.05..=0.95 (the perspective warp's near texels' width over its far ones')"),
            ));
        }
        let eye = camera.eye.as_dvec3();
        let f = (camera.target - camera.eye).as_dvec3().normalize_or_zero();
        let r = f.cross(camera.up.as_dvec3()).normalize_or_zero();
        let u = r.cross(f);
        if !(eye.is_finite() && f != DVec3::ZERO && r != DVec3::ZERO && camera.fov_y_deg.is_finite()) {
            return Err(Error::param(
                "camera",
                "the perspective warp needs a finite camera with a view direction and an up vector across it",
            ));
        }
        let corners = (0..8).map(|i| {
            let pick = |bit: usize, lo: f32, hi: f32| if i & bit == 0 { lo } else { hi };
            DVec3::new(
                pick(1, bounds.min.x, bounds.max.x) as f64,
                pick(2, bounds.min.y, bounds.max.y) as f64,
                pick(4, bounds.min.z, bounds.max.z) as f64,
            )
        });
        let depth = corners.map(|c| (c - eye).dot(f)).fold(f64::NEG_INFINITY, f64::max);
        let size = bounds.size().max_element() as f64;
        if depth.is_nan() || depth <= 1e-3 * size {
            return Err(Error::param("warp", "the perspective warp needs scene geometry in front of the camera"));
        }
        let ratio64 = ratio as f64;
        let e = depth * ratio64 / (1.0 - ratio64);
        let apex = eye - f * e;
        // Wide enough to hold the camera's frustum at D from the eye, where it is widest.
        let ty = (0.5 * (camera.fov_y_deg as f64).to_radians()).tan() * (1.0 - ratio64);
        let aspect = camera.width.max(1) as f64 / camera.height.max(1) as f64;
        let tx = ty * aspect;
        let k = 1.0 / (1.0 / e - 1.0 / (e + depth));
        let along = row(f, -f.dot(apex));
        let world_to_texel = DMat4::from_cols(
            0.5 * along + (0.5 / tx) * row(r, -r.dot(apex)),
            0.5 * along + (0.5 / ty) * row(u, -u.dot(apex)),
            (k / e) * along - DVec4::new(0.0, 0.0, 0.0, k),
            along,
        )
        .transpose();
        // The cube around the frustum's part inside the bounds (padded by one even voxel).
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for w in [e, e + depth] {
            for (sx, sy) in [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)] {
                let p = apex + f * w + r * (sx * w * tx) + u * (sy * w * ty);
                lo = lo.min(p);
                hi = hi.max(p);
            }
        }
        let pad = even.voxel as f64;
        lo = lo.max(bounds.min.as_dvec3() - pad);
        hi = hi.min(bounds.max.as_dvec3() + pad);
        // Cubic voxels as the shaders march in, the box's shortest side over the fewest texels.
        let voxel = (hi - lo).max_element().max(1e-6 * size) / dims.min_element() as f64;
        let extent = dims.as_dvec3() * voxel;
        let origin = 0.5 * (lo + hi) - 0.5 * extent;
        let grid_to_world = DMat4::from_translation(origin) * DMat4::from_scale(extent);
        let to_texel = world_to_texel * grid_to_world;
        let warp = Perspective { to_texel, from_texel: to_texel.inverse(), near: e, ratio };
        Ok(VoxelGrid { origin: origin.as_vec3(), voxel: voxel as f32, dims, warp: Warp::Perspective(warp), clip: None })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn camera() -> Camera {
        Camera {
            eye: Vec3::new(1.0, 1.5, 4.0),
            target: Vec3::new(0.0, 1.0, 0.0),
            up: Vec3::Y,
            fov_y_deg: 50.0,
            width: 160,
            height: 90,
        }
    }

    fn room() -> Aabb {
        Aabb { min: Vec3::new(-3.0, 0.0, -6.0), max: Vec3::new(3.0, 3.0, 5.0) }
    }

    #[test]
    fn round_trip_is_exact() {
        let g = VoxelGrid::perspective(&camera(), &room(), UVec3::splat(64), 0.25).unwrap();
        let Warp::Perspective(p) = g.warp else { panic!("not perspective") };
        for i in 0..1000 {
            let t = DVec3::new((i % 10) as f64 / 9.0, ((i / 10) % 10) as f64 / 9.0, (i / 100) as f64 / 9.0);
            let x = p.inverse(t);
            let back = p.forward(x).expect("a texel's point lies in front of the apex");
            assert!((back - t).abs().max_element() < 1e-9, "{t} -> {x} -> {back}");
        }
    }

    #[test]
    fn texels_span_the_camera_frustum() {
        let c = camera();
        let g = VoxelGrid::perspective(&c, &room(), UVec3::splat(64), 0.25).unwrap();
        // The eye is on the near face's centre; the view direction is the texel volume's z.
        let near = g.world_of(DVec3::new(0.5, 0.5, 0.0));
        assert!(near.distance(c.eye) < 1e-4, "near centre {near}");
        let ahead = g.world_of(DVec3::new(0.5, 0.5, 0.5));
        let dir = (c.target - c.eye).normalize();
        assert!((ahead - c.eye).normalize().dot(dir) > 0.99999, "{ahead}");
        // The far face lies at the depth of the room's farthest corner in front of the eye.
        let far = g.world_of(DVec3::new(0.5, 0.5, 1.0));
        let corners = [room().min, room().max, Vec3::new(3.0, 0.0, -6.0), Vec3::new(-3.0, 3.0, -6.0)];
        let depth = corners.iter().map(|k| (*k - c.eye).dot(dir)).fold(f32::MIN, f32::max);
        assert!(((far - c.eye).dot(dir) - depth).abs() < 1e-3, "{far} vs depth {depth}");
        // A point the camera sees (inside its frustum) lies inside the texels.
        let seen = c.eye + dir * 3.0 + Vec3::new(0.0, 0.5, 0.0);
        let t = g.warp.forward3(((seen - g.origin) / (g.voxel * g.dims.as_vec3())).as_dvec3());
        assert!(t.min_element() > 0.0 && t.max_element() < 1.0, "{t}");
    }

    #[test]
    fn planes_stay_planes_and_near_texels_are_finer() {
        let g = VoxelGrid::perspective(&camera(), &room(), UVec3::splat(64), 0.25).unwrap();
        let Warp::Perspective(p) = g.warp else { panic!() };
        // Three points on a line map to three points on a line.
        let (a, b) = (DVec3::new(0.2, 0.3, 0.4), DVec3::new(0.7, 0.5, 0.6));
        let (ta, tb, tm) = (p.forward(a).unwrap(), p.forward(b).unwrap(), p.forward(0.3 * a + 0.7 * b).unwrap());
        assert!((tm - ta).cross(tb - ta).length() < 1e-9 * (tb - ta).length_squared().max(1.0));
        // Lateral texel width grows linearly with the distance from the apex: near over far = ratio.
        let width =
            |z: f64| g.world_of(DVec3::new(0.5, 0.5, z)).distance(g.world_of(DVec3::new(0.5 + 1.0 / 64.0, 0.5, z)));
        assert!((width(0.0) / width(1.0) - 0.25).abs() < 1e-4, "{} / {}", width(0.0), width(1.0));
        assert!(p.peak_slope() > p.slope(DVec3::splat(0.5)));
        // The slope is the Jacobian's determinant's cube root, by finite differences.
        for x in [DVec3::new(0.4, 0.5, 0.3), DVec3::new(0.6, 0.45, 0.7), DVec3::new(0.5, 0.5, 0.5)] {
            let h = 1e-6;
            let d = |a: DVec3| (p.forward(x + a * h).unwrap() - p.forward(x - a * h).unwrap()) / (2.0 * h);
            let det = glam::DMat3::from_cols(d(DVec3::X), d(DVec3::Y), d(DVec3::Z)).determinant().abs();
            assert!((det.cbrt() / p.slope(x) - 1.0).abs() < 1e-5, "{x}: {} vs {}", det.cbrt(), p.slope(x));
        }
    }

    #[test]
    fn dims_hold_the_fitted_grids_texels() {
        let fitted = VoxelGrid { dims: UVec3::new(128, 64, 64), ..VoxelGrid::fit(&room(), 128).unwrap() };
        let wide = Camera { width: 640, height: 360, ..camera() };
        assert_eq!(VoxelGrid::perspective_dims(&fitted, &wide), UVec3::new(128, 64, 64));
        let square = Camera { width: 256, height: 256, ..camera() };
        let cube = VoxelGrid { dims: UVec3::splat(64), ..fitted };
        assert_eq!(VoxelGrid::perspective_dims(&cube, &square), UVec3::splat(64));
    }

    #[test]
    fn bad_input_is_refused() {
        assert!(VoxelGrid::perspective(&camera(), &room(), UVec3::splat(64), 1.0).is_err());
        assert!(VoxelGrid::perspective(&camera(), &room(), UVec3::new(64, 48, 64), 0.25).is_err());
        let away = Camera { target: Vec3::new(1.0, 1.5, 10.0), ..camera() };
        let behind = Aabb { min: Vec3::new(-1.0, 0.0, -3.0), max: Vec3::new(1.0, 1.0, -2.0) };
        assert!(VoxelGrid::perspective(&away, &behind, UVec3::splat(64), 0.25).is_err());
    }
}
