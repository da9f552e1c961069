//! Sparse storage: the per-voxel textures in a pool of the occupied 2³ bricks behind a page table
//! (voxel::bricks). The pool holds exactly the bricks that hold an occupied voxel, with the
//! tessellation and raster voxelizers, on a cube and on a non-cubic grid; sparse and dense
//! storage render the same image; a pool too small is an error naming both counts. Lavapipe,
//! validation on.

mod common;

use std::collections::HashSet;
use std::sync::Arc;

use glam::{UVec3, Vec3};
use vct::gpu::Context;
use vct::reference::coverage::RefGrid;
use vct::reference::metrics::flip;
use vct::render::{RenderOptions, Renderer};
use vct::scene::file::Filter;
use vct::scene::gpu::SceneGpu;
use vct::scene::Scene;
use vct::voxel::bricks::{brick_count, Storage, StorageRequest};
use vct::voxel::{occupancy_of, Coverage, VoxelGrid, VoxelizeMethod};

/// Occupancy and page table of one sparse voxelization, and the dense one's occupancy.
fn voxelize_both(
    ctx: &Arc<Context>,
    scene: &Scene,
    grid: VoxelGrid,
    method: VoxelizeMethod,
) -> (Vec<bool>, Vec<u32>, Vec<bool>) {
    let scene_gpu = SceneGpu::new(ctx, scene).unwrap();
    let run = |storage| {
        let (volume, voxelizer) =
            vct::voxel::build(ctx, scene, &scene_gpu, grid, method, StorageRequest { storage, ..Default::default() })
                .unwrap();
        ctx.submit_and_wait("voxelize", |cmd| voxelizer.record(cmd, &scene_gpu, &volume)).unwrap();
        volume.bricks.check().unwrap();
        let pages = if volume.bricks.sparse() { volume.bricks.read_pages().unwrap() } else { Vec::new() };
        (occupancy_of(&volume.read_albedo().unwrap()), pages)
    };
    let (sparse, pages) = run(Storage::Sparse);
    let (dense, _) = run(Storage::Dense);
    (sparse, pages, dense)
}

#[test]
fn the_pool_holds_every_occupied_brick_and_no_other() {
    let ctx = common::context();
    let cornell = Scene::embedded_default().unwrap();
    let hall = common::hall();
    let cases = [
        ("cornell 64³, raster", &cornell, 64, VoxelizeMethod::raster(Coverage::Conservative)),
        ("cornell 64³, tess", &cornell, 64, VoxelizeMethod::tess()),
        ("hall 64×16×32, raster", &hall, 64, VoxelizeMethod::raster(Coverage::Conservative)),
        ("hall 64×16×32, tess", &hall, 64, VoxelizeMethod::tess()),
    ];
    for (name, scene, res, method) in cases {
        let grid = VoxelGrid::fit(&scene.mesh.bounds, res).unwrap();
        let (occupied, pages, dense) = voxelize_both(&ctx, scene, grid, method);
        // Through the pool the voxelizer stays exact, and stores what dense storage stores.
        let triangles: Vec<[Vec3; 3]> = (0..scene.mesh.triangle_count()).map(|t| scene.mesh.triangle(t)).collect();
        let a = RefGrid::matching(&grid).coverage(&triangles, 1e-3).accuracy(&occupied);
        assert!(a.recall == 1.0 && a.precision == 1.0, "{name}: recall {} precision {}", a.recall, a.precision);
        assert!(occupied == dense, "{name}: sparse and dense occupancy differ");
        // Bricks with an occupied voxel, from the read-back occupancy.
        let count = brick_count(&grid);
        let d = grid.dims;
        let mut want = vec![false; count.element_product() as usize];
        for (i, &o) in occupied.iter().enumerate() {
            if o {
                let i = i as u32;
                let v = UVec3::new(i % d.x, (i / d.x) % d.y, i / (d.x * d.y)) / vct::config::BRICK_SIZE;
                want[((v.z * count.y + v.y) * count.x + v.x) as usize] = true;
            }
        }
        assert_eq!(pages.len(), want.len());
        let mut slots = HashSet::new();
        for (b, (&s, &w)) in pages.iter().zip(&want).enumerate() {
            assert_eq!(s != 0, w, "{name}: brick {b} has slot {s}, occupied {w}");
            if s != 0 {
                assert!(slots.insert(s), "{name}: slot {s} given twice");
            }
        }
        let n = slots.len() as u32;
        assert!(slots.iter().all(|&s| (1..=n).contains(&s)), "{name}: slots are not 1..={n}");
        // The census gave them in brick order, and the frame kept them.
        let order: Vec<u32> = pages.iter().copied().filter(|&s| s != 0).collect();
        assert!(order.windows(2).all(|w| w[0] < w[1]), "{name}: slots out of brick order");
        println!("{name}: {n} of {} bricks ({:.1}%)", want.len(), 100.0 * n as f64 / want.len() as f64);
        assert!(n > 0 && (n as usize) < want.len() / 2, "{name}: {n} bricks of {}", want.len());
    }
    common::assert_clean(&ctx);
}

fn frame(ctx: &Arc<Context>, scene: &Scene, storage: Storage, gi: bool) -> Vec<u8> {
    let options = RenderOptions { resolution: Some(64), storage, gi, ..Default::default() };
    let r = Renderer::new(ctx, scene.clone(), options).unwrap();
    r.render().unwrap();
    r.read_frame().unwrap().ldr
}

#[test]
fn sparse_and_dense_storage_render_the_same_image() {
    let ctx = common::context();
    let mut cornell = Scene::embedded_default().unwrap();
    cornell.set_size(Some(96), Some(96)).unwrap();
    let mut bounced = cornell.clone();
    bounced.settings.gi.bounces = 2;
    let mut iso = cornell.clone();
    iso.settings.gi.filter = Filter::Iso;
    let mut hall = common::hall();
    hall.set_size(Some(160), Some(120)).unwrap();
    for (name, scene) in
        [("cornell", &cornell), ("cornell, 2 bounces", &bounced), ("cornell, isotropic", &iso), ("hall", &hall)]
    {
        let (w, h) = (scene.camera.width, scene.camera.height);
        let sparse = frame(&ctx, scene, Storage::Sparse, true);
        let dense = frame(&ctx, scene, Storage::Dense, true);
        let (f, _) = flip(&dense, &sparse, w, h);
        println!("{name}: FLIP sparse vs dense {f:.5}");
        // Within half of FLIP 0.01; the atomic averages' order alone moves a frame by ~0.001.
        assert!(f <= 0.005, "{name}: sparse and dense storage differ, FLIP {f}");
        // Not an empty agreement: the indirect light the pool carries changes the picture by
        // several times the bound (least under the hall's open sky).
        let (g, _) = flip(&frame(&ctx, scene, Storage::Sparse, false), &sparse, w, h);
        assert!(g >= 3.0 * 0.005, "{name}: GI changes the image by FLIP {g} only");
    }
    common::assert_clean(&ctx);
}

#[test]
fn a_full_pool_is_an_error_naming_both_counts() {
    let ctx = common::context();
    let scene = Scene::embedded_default().unwrap();
    let options = RenderOptions { resolution: Some(32), bricks: Some(16), ..Default::default() };
    let r = Renderer::new(&ctx, scene.clone(), options).unwrap();
    let Err(e) = r.render() else { panic!("a 16-brick pool held the Cornell box") };
    let e = e.to_string();
    assert!(e.contains("brick pool is full") && e.contains("holds 16"), "{e}");
    drop(r);
    // The census' pool holds the scene, frame after frame.
    let r = Renderer::new(&ctx, scene, RenderOptions { resolution: Some(32), ..Default::default() }).unwrap();
    for _ in 0..2 {
        r.render().unwrap();
    }
    let u = r.voxels.bricks.usage();
    assert_eq!(u.needed, u.capacity);
    drop(r);
    common::assert_clean(&ctx);
}
