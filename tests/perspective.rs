//! The perspective warp (Freed 2018 §4.6.2, made projective: voxel::perspective): its voxelization
//! against exact coverage among its texels, where the reference clips and maps each triangle with
//! its own code (reference::coverage), for both exact voxelizers, on triangles in view, reaching
//! behind the camera (clipped at the apex's side) and leaving the frustum, and on the Cornell box
//! (its indirect light against the path tracer: tests/accuracy.rs). Lavapipe, validation on.

mod common;

use glam::{UVec3, Vec3};
use vct::reference::coverage::RefGrid;
use vct::render::{Follow, RenderOptions, Renderer};
use vct::scene::{Camera, Scene};
use vct::voxel::headless::voxelize_in;
use vct::voxel::warp::WarpChoice;
use vct::voxel::{Coverage, VoxelGrid, VoxelizeMethod};

fn v(x: f32, y: f32, z: f32) -> Vec3 {
    Vec3::new(x, y, z)
}

#[test]
fn perspective_voxelization_is_exact_among_the_texels() {
    let camera = Camera {
        eye: v(0.0, 1.0, 6.0),
        target: v(0.5, 0.8, 0.0),
        up: Vec3::Y,
        fov_y_deg: 60.0,
        width: 160,
        height: 90,
    };
    let probes: [(&str, Vec<[Vec3; 3]>); 3] = [
        ("in view", vec![[v(-2.3, 0.1, -1.7), v(2.2, 0.6, -3.9), v(0.4, 2.9, 0.3)]]),
        // A floor from behind the camera to far ahead: clipped where it passes the apex.
        ("behind the camera", vec![[v(-3.0, 0.0, 12.0), v(3.5, 0.05, 11.0), v(0.2, -0.1, -4.0)]]),
        ("leaving the frustum", vec![[v(-9.0, 0.4, -2.0), v(1.0, 0.7, -3.0), v(0.5, 1.9, 1.0)]]),
    ];
    let ctx = common::context();
    for (name, tris) in &probes {
        let mut scene = Scene::from_triangles(&tris.iter().map(|t| (*t, 0)).collect::<Vec<_>>(), &[Vec3::splat(0.8)]);
        // The far plane beyond the probes' bounds, as a scene around them would put it.
        scene.mesh.bounds.grow(v(-4.0, -1.0, -6.0));
        scene.mesh.bounds.grow(v(4.0, 3.0, 13.0));
        scene.camera = camera;
        let grid = VoxelGrid::perspective(&camera, &scene.mesh.bounds, UVec3::splat(32), 0.25).unwrap();
        let tris: Vec<_> = (0..scene.mesh.triangle_count()).map(|t| scene.mesh.triangle(t)).collect();
        let reference = RefGrid::matching(&grid).coverage(&tris, 1e-3);
        assert!(reference.required.iter().any(|&r| r), "{name}: nothing of the probe among the texels");
        for method in [VoxelizeMethod::raster(Coverage::Conservative), VoxelizeMethod::tess()] {
            let out = voxelize_in(&ctx, &scene, method, grid, 1).unwrap();
            common::assert_clean(&ctx);
            let a = reference.accuracy(&out.occupied());
            println!("{name} {}: {a:?}", method.label());
            assert!(a.recall >= 0.999 && a.precision >= 0.999, "{name} {}: {a:?}", method.label());
        }
    }
}

#[test]
fn perspective_cornell_box_is_exact_among_the_texels() {
    let scene = Scene::embedded_default().unwrap();
    let fitted = VoxelGrid::fit(&scene.mesh.bounds, 64).unwrap();
    let grid = WarpChoice::Perspective(0.25).apply(fitted, &scene.camera, &scene.mesh.bounds).unwrap();
    let tris: Vec<_> = (0..scene.mesh.triangle_count()).map(|t| scene.mesh.triangle(t)).collect();
    let reference = RefGrid::matching(&grid).coverage(&tris, 1e-3);
    let ctx = common::context();
    for method in [VoxelizeMethod::raster(Coverage::Conservative), VoxelizeMethod::tess()] {
        let out = voxelize_in(&ctx, &scene, method, grid, 1).unwrap();
        common::assert_clean(&ctx);
        let a = reference.accuracy(&out.occupied());
        println!("Cornell, perspective {} {}: {a:?}", grid.dims_label(), method.label());
        assert!(a.recall >= 0.999 && a.precision >= 0.999, "{}: {a:?}", method.label());
    }
}

#[test]
fn perspective_refuses_what_does_not_apply() {
    let scene = Scene::embedded_default().unwrap();
    let ctx = common::context();
    let follow = RenderOptions {
        warp: Some(WarpChoice::Perspective(0.25)),
        follow: Some(Follow { extent: 4.0, snap: true }),
        ..Default::default()
    };
    let e = Renderer::new(&ctx, scene.clone(), follow).err().expect("--follow with a perspective warp").to_string();
    assert!(e.contains("follow"), "{e}");
    let strong = RenderOptions { warp: Some(WarpChoice::Perspective(1.0)), ..Default::default() };
    let e = Renderer::new(&ctx, scene, strong).err().expect("a ratio of 1").to_string();
    assert!(e.contains("warp-slope"), "{e}");
}
