//! The point voxelizer (Mavridis & Papaioannou 2011) against the exact CPU coverage: recall grows
//! with the point density, precision is exact (a point lies on its triangle), the refinement fills
//! every voxel the camera sees (against a CPU ray cast through each pixel), a zero-area triangle
//! writes nothing. Lavapipe, validation on.

mod common;

use glam::Vec3;
use vct::bench::stability::voxel_accuracy;
use vct::reference::coverage::RefGrid;
use vct::scene::Scene;
use vct::voxel::headless::voxelize_in;
use vct::voxel::points::{PointSource, DEFAULT_POINT_DENSITY};
use vct::voxel::{VoxelGrid, VoxelizeMethod};

fn points(density: f32) -> VoxelizeMethod {
    VoxelizeMethod::Points { density, source: PointSource::Load, refine: false }
}

fn unit_grid(n: u32) -> VoxelGrid {
    VoxelGrid { origin: Vec3::ZERO, voxel: 1.0, dims: glam::UVec3::splat(n), warp: Default::default(), clip: None }
}

#[test]
fn recall_grows_with_density_and_precision_stays_exact_on_the_cornell_box() {
    let ctx = common::context();
    let scene = Scene::embedded_default().unwrap();
    let grid = VoxelGrid::fit(&scene.mesh.bounds, 64).unwrap();
    let sparse = voxel_accuracy(&ctx, &scene, points(0.25), grid).unwrap();
    let dense = voxel_accuracy(&ctx, &scene, points(DEFAULT_POINT_DENSITY), grid).unwrap();
    common::assert_clean(&ctx);
    println!("Cornell 64³: density 0.25 {sparse:?}; default {dense:?}");
    assert!(dense.recall > sparse.recall + 0.05, "recall does not grow with density: {sparse:?} -> {dense:?}");
    assert!(dense.recall >= 0.95, "default density: recall {:.4} < 0.95", dense.recall);
    for a in [sparse, dense] {
        assert!(a.precision >= 0.999, "a point wrote a voxel its triangle does not touch: {a:?}");
    }
}

#[test]
fn points_generated_on_the_gpu_cover_as_the_scattered_ones_do() {
    let ctx = common::context();
    let scene = Scene::embedded_default().unwrap();
    let grid = VoxelGrid::fit(&scene.mesh.bounds, 64).unwrap();
    let gpu = VoxelizeMethod::Points { density: DEFAULT_POINT_DENSITY, source: PointSource::Gpu, refine: false };
    let generated = voxel_accuracy(&ctx, &scene, gpu, grid).unwrap();
    let scattered = voxel_accuracy(&ctx, &scene, points(DEFAULT_POINT_DENSITY), grid).unwrap();
    common::assert_clean(&ctx);
    println!("Cornell 64³: generated {generated:?}; scattered {scattered:?}");
    assert_eq!(generated.precision, 1.0, "{generated:?}");
    assert!((generated.recall - scattered.recall).abs() < 0.01, "{generated:?} against {scattered:?}");
}

#[test]
fn every_voxel_a_point_writes_lies_on_its_triangle() {
    let ctx = common::context();
    // Oblique, so that points land in voxels the triangle only cuts a corner of.
    let t = [Vec3::new(2.3, 3.1, 4.7), Vec3::new(27.9, 9.4, 21.2), Vec3::new(6.6, 28.2, 11.9)];
    let scene = Scene::from_triangles(&[(t, 0)], &[Vec3::splat(0.8)]);
    for density in [0.5, 4.0, 32.0] {
        let a = voxel_accuracy(&ctx, &scene, points(density), unit_grid(32)).unwrap();
        println!("density {density}: {a:?}");
        assert_eq!(a.precision, 1.0, "density {density}: {a:?}");
    }
    common::assert_clean(&ctx);
}

#[test]
fn a_zero_area_triangle_writes_nothing() {
    let ctx = common::context();
    let real = [Vec3::new(4.5, 4.5, 8.5), Vec3::new(12.5, 4.5, 8.5), Vec3::new(4.5, 12.5, 8.5)];
    let line = [Vec3::new(20.5, 20.5, 20.5), Vec3::new(25.5, 25.5, 25.5), Vec3::new(30.5, 30.5, 30.5)];
    let point = [Vec3::splat(16.5); 3];
    let only = Scene::from_triangles(&[(real, 0)], &[Vec3::splat(0.8)]);
    let with = Scene::from_triangles(&[(real, 0), (line, 0), (point, 0)], &[Vec3::splat(0.8)]);
    // Points only: the two scenes frame different cameras, which a refinement would follow.
    let a = voxelize_in(&ctx, &only, points(DEFAULT_POINT_DENSITY), unit_grid(32), 1).unwrap();
    let b = voxelize_in(&ctx, &with, points(DEFAULT_POINT_DENSITY), unit_grid(32), 1).unwrap();
    let count = |o: Vec<bool>| o.iter().filter(|&&x| x).count();
    assert!(
        a.occupied() == b.occupied(),
        "the degenerate triangles wrote voxels: {} against {}",
        count(b.occupied()),
        count(a.occupied())
    );
    // Nothing but degenerate triangles, with the refinement too: an empty volume, no error.
    let none = Scene::from_triangles(&[(line, 0), (point, 0)], &[Vec3::splat(0.8)]);
    let c = voxelize_in(&ctx, &none, VoxelizeMethod::points(), unit_grid(32), 1).unwrap();
    assert_eq!(count(c.occupied()), 0, "degenerate triangles alone wrote voxels");
    common::assert_clean(&ctx);
}

#[test]
fn refinement_fills_the_holes_the_camera_would_see() {
    let ctx = common::context();
    let scene = Scene::embedded_default().unwrap();
    let grid = VoxelGrid::fit(&scene.mesh.bounds, 64).unwrap();
    let tris: Vec<_> = (0..scene.mesh.triangle_count()).map(|t| scene.mesh.triangle(t)).collect();
    let seen = RefGrid::matching(&grid).visible(&tris, &scene.camera, 1e-3);
    let exact = RefGrid::matching(&grid).coverage(&tris, 1e-3);
    // A quarter of a point per voxel area: most voxels get none.
    for (refine, lowest, highest) in [(false, 0.0, 0.5), (true, 0.99, 1.0)] {
        let method = VoxelizeMethod::Points { density: 0.25, source: PointSource::Load, refine };
        let run = voxelize_in(&ctx, &scene, method, grid, 1).unwrap();
        let (visible, all) = (seen.accuracy(&run.occupied()), exact.accuracy(&run.occupied()));
        println!(
            "refinement {refine}: visible recall {:.4} ({} voxels seen); {all:?}",
            visible.recall, visible.required
        );
        assert!(
            (lowest..=highest).contains(&visible.recall),
            "refinement {refine}: recall {:.4} of the voxels the camera sees",
            visible.recall
        );
        assert_eq!(all.precision, 1.0, "refinement {refine} wrote a voxel no triangle touches: {all:?}");
    }
    common::assert_clean(&ctx);
}
