//! Voxel warping (Freed 2018 §4.6.1): a warped grid's voxelization against exact coverage in
//! warped space, where each texel is the box the reference finds by inverting the thesis' cubic
//! on its own (by bisection, not the renderer's Newton steps), for both exact voxelizers
//! (tessellation and conservative raster), on single triangles and on the Cornell box; and the
//! warp is really there (the texels differ from the even grid's). Lavapipe, validation on.

mod common;

use std::sync::Arc;

use glam::Vec3;
use vct::gpu::Context;
use vct::reference::coverage::{Accuracy, RefGrid};
use vct::scene::Scene;
use vct::voxel::headless::voxelize_in;
use vct::voxel::{Coverage, VoxelGrid, VoxelizeMethod};

fn methods() -> [VoxelizeMethod; 2] {
    [VoxelizeMethod::raster(Coverage::Conservative), VoxelizeMethod::tess()]
}

fn v(x: f32, y: f32, z: f32) -> Vec3 {
    Vec3::new(x, y, z)
}

/// Voxelizes `scene` on `grid`; returns the accuracy and the occupied voxels.
fn run(ctx: &Arc<Context>, scene: &Scene, method: VoxelizeMethod, grid: VoxelGrid) -> (Accuracy, usize) {
    let out = voxelize_in(ctx, scene, method, grid, 1).unwrap();
    common::assert_clean(ctx);
    let tris: Vec<_> = (0..scene.mesh.triangle_count()).map(|t| scene.mesh.triangle(t)).collect();
    let occupied = out.occupied();
    let a = RefGrid::matching(&grid).coverage(&tris, 1e-3).accuracy(&occupied);
    (a, occupied.iter().filter(|&&o| o).count())
}

#[test]
fn warped_voxelization_is_exact_in_warped_space() {
    let even = VoxelGrid {
        origin: Vec3::ZERO,
        voxel: 1.0,
        dims: glam::UVec3::splat(32),
        warp: Default::default(),
        clip: None,
    };
    // Off-centre along every axis, so each axis has its own two halves.
    let warped = even.warped(v(9.0, 21.0, 14.5), 0.25).unwrap();
    let probes: [(&str, Vec<[Vec3; 3]>); 3] = [
        ("general", vec![[v(3.3, 4.1, 5.7), v(27.2, 9.6, 12.9), v(11.8, 26.4, 21.3)]]),
        ("45° quad", {
            let q = [v(4.2, 4.4, 6.1), v(27.5, 4.4, 6.1), v(27.5, 22.1, 23.8), v(4.2, 22.1, 23.8)];
            vec![[q[0], q[1], q[2]], [q[0], q[2], q[3]]]
        }),
        ("partly outside", vec![[v(-20.3, 5.1, 9.7), v(20.2, -8.6, 14.4), v(12.9, 26.3, 16.1)]]),
    ];
    let ctx = common::context();
    for (name, tris) in &probes {
        let scene = Scene::from_triangles(&tris.iter().map(|t| (*t, 0)).collect::<Vec<_>>(), &[Vec3::splat(0.8)]);
        for method in methods() {
            let (a, count) = run(&ctx, &scene, method, warped);
            let (_, even_count) = run(&ctx, &scene, method, even);
            println!("{name} {}: warped {a:?} ({count} voxels, {even_count} unwarped)", method.label());
            assert!(a.recall >= 0.999 && a.precision >= 0.999, "{name} {}: {a:?}", method.label());
            assert_ne!(count, even_count, "{name} {}: the warp changed nothing", method.label());
        }
    }
}

#[test]
fn warped_cornell_box_is_exact_in_warped_space() {
    let scene = Scene::embedded_default().unwrap();
    let fitted = VoxelGrid::fit(&scene.mesh.bounds, 64).unwrap();
    // Focused inside the room, off its centre, where a viewer would stand.
    let b = scene.mesh.bounds;
    let focus = b.min + b.size() * Vec3::new(0.3, 0.6, 0.7);
    let warped = fitted.warped(focus, 0.25).unwrap();
    let ctx = common::context();
    for method in methods() {
        let (a, count) = run(&ctx, &scene, method, warped);
        println!("Cornell 64³ warped {}: {a:?} ({count} voxels)", method.label());
        assert!(a.recall >= 0.999 && a.precision >= 0.999, "{}: {a:?}", method.label());
    }
}

#[test]
fn the_grid_and_the_reference_place_warped_texels_alike() {
    // The renderer's warp (Newton's method) and the reference's (bisection of the thesis'
    // printed cubic) put every face of a 64-texel axis at the same place.
    let even = VoxelGrid {
        origin: Vec3::ZERO,
        voxel: 1.0,
        dims: glam::UVec3::splat(64),
        warp: Default::default(),
        clip: None,
    };
    let grid = even.warped(v(50.0, 3.0, 32.0), 0.1).unwrap();
    let faces = RefGrid::matching(&grid).faces();
    for (i, x) in faces[0].iter().enumerate().step_by(7) {
        let b = grid.texel_bounds(glam::UVec3::new(i.min(63) as u32, 0, 0));
        let want = if i == 64 { b.max.x } else { b.min.x };
        assert!((want as f64 - x).abs() < 1e-4, "face {i}: grid {want} against the reference {x}");
    }
    // Finest at the focus: texels there are 1.5 - 0.1/2 = 1.45 to a voxel of the even grid.
    let at = grid.texel_of(v(50.0, 3.0, 32.0));
    let b = grid.texel_bounds(at.as_uvec3());
    assert!(((b.max.x - b.min.x) - 1.0 / 1.45).abs() < 0.01, "texel at the focus {:?}", b);
}
