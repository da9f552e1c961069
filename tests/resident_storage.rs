//! Sparse storage with residency: on a device with Vulkan sparse residency
//! (`sparseResidencyImage3D`, `residencyNonResidentStrict`) the per-voxel textures span the grid
//! with memory bound only to the blocks that hold a brick the census found
//! (voxel::bricks::Residency, gpu::sparse). They voxelize exactly, render the dense image, bind
//! what the memory report says, and a write outside the census' bricks is an error, never a silent
//! hole. On a device without residency (Mesa 22.3's lavapipe) asking for it is an error naming the
//! missing feature. Validation on.
//!
//! The tests that need residency report themselves skipped on a device without it; Mesa 25's
//! lavapipe offers it (`.ci/run` runs this file on it too, see scripts/lavapipe-residency.sh).

mod common;

use std::sync::Arc;

use glam::Vec3;
use vct::gpu::Context;
use vct::reference::coverage::RefGrid;
use vct::reference::metrics::flip;
use vct::render::{RenderOptions, Renderer};
use vct::scene::file::Filter;
use vct::scene::gpu::SceneGpu;
use vct::scene::Scene;
use vct::voxel::bricks::{residency_offered, Bricks, Storage, StorageRequest};
use vct::voxel::{occupancy_of, Coverage, VoxelGrid, VoxelVolume, VoxelizeMethod, Voxelizer};

/// The context, or `None` (and a note) when its device has no residency.
fn resident_context() -> Option<Arc<Context>> {
    let ctx = common::context();
    if residency_offered(&ctx) {
        Some(ctx)
    } else {
        println!("skipped: {} offers no sparse residency", ctx.info.name);
        None
    }
}

#[test]
fn resident_storage_on_a_device_without_residency_is_an_error_naming_the_feature() {
    let ctx = common::context();
    if residency_offered(&ctx) {
        println!("skipped: {} offers sparse residency", ctx.info.name);
        return;
    }
    let scene = Scene::embedded_default().unwrap();
    let options = RenderOptions { resolution: Some(16), storage: Storage::Resident, ..Default::default() };
    let Err(e) = Renderer::new(&ctx, scene, options) else { panic!("resident storage without residency") };
    let e = e.to_string();
    assert!(e.contains("resident voxel storage") && e.contains("lacks the feature"), "{e}");
    // Auto falls back to the brick pool.
    assert_eq!(Storage::Auto.resolve(&ctx, false), Storage::Sparse);
    common::assert_clean(&ctx);
}

#[test]
fn resident_voxels_are_exact_and_bind_only_the_census_blocks() {
    let Some(ctx) = resident_context() else { return };
    assert_eq!(Storage::Auto.resolve(&ctx, false), Storage::Resident);
    let cornell = Scene::embedded_default().unwrap();
    let hall = common::hall();
    for (name, scene, method) in [
        ("cornell 128³, raster", &cornell, VoxelizeMethod::raster(Coverage::Conservative)),
        ("cornell 128³, tess", &cornell, VoxelizeMethod::tess()),
        ("hall 128×32×64, raster", &hall, VoxelizeMethod::raster(Coverage::Conservative)),
    ] {
        // At 128 voxels the scenes leave blocks of 32×32×16 texels empty.
        let grid = VoxelGrid::fit(&scene.mesh.bounds, 128).unwrap();
        let scene_gpu = SceneGpu::new(&ctx, scene).unwrap();
        let request = StorageRequest { storage: Storage::Resident, ..Default::default() };
        let (volume, voxelizer) = vct::voxel::build(&ctx, scene, &scene_gpu, grid, method, request).unwrap();
        for _ in 0..2 {
            ctx.submit_and_wait("voxelize", |cmd| voxelizer.record(cmd, &scene_gpu, &volume)).unwrap();
            volume.bricks.check().unwrap();
        }
        let occupied = occupancy_of(&volume.read_albedo().unwrap());
        let triangles: Vec<[Vec3; 3]> = (0..scene.mesh.triangle_count()).map(|t| scene.mesh.triangle(t)).collect();
        let a = RefGrid::matching(&grid).coverage(&triangles, 1e-3).accuracy(&occupied);
        assert!(a.recall == 1.0 && a.precision == 1.0, "{name}: recall {} precision {}", a.recall, a.precision);
        // Each texture binds its census blocks, as the report counts them, and less than dense.
        let r = volume.bricks.residency.as_ref().expect("resident bricks");
        for img in volume.images() {
            assert_eq!(img.bytes, r.bound_bytes(grid.dims, img.desc.format), "{name}: {}", img.name);
            assert!(
                img.bytes < img.desc.texel_bytes(),
                "{name}: {} binds {} of {}",
                img.name,
                img.bytes,
                img.desc.texel_bytes()
            );
        }
        println!(
            "{name}: {} bricks, {} KiB a voxel texture of {} KiB dense",
            r.bricks.len(),
            volume.albedo.bytes >> 10,
            volume.albedo.desc.texel_bytes() >> 10
        );
    }
    common::assert_clean(&ctx);
}

fn frame(ctx: &Arc<Context>, scene: &Scene, storage: Storage) -> (Vec<u8>, Renderer) {
    let options = RenderOptions { resolution: Some(64), storage, ..Default::default() };
    let r = Renderer::new(ctx, scene.clone(), options).unwrap();
    r.render().unwrap();
    (r.read_frame().unwrap().ldr, r)
}

// At 64 voxels every block of these scenes holds a brick: the memory saved shows at 128, above.
#[test]
fn resident_and_dense_storage_render_the_same_image_and_the_report_counts_the_bound_blocks() {
    let Some(ctx) = resident_context() else { return };
    let mut cornell = Scene::embedded_default().unwrap();
    cornell.set_size(Some(96), Some(96)).unwrap();
    let mut bounced = cornell.clone();
    bounced.settings.gi.bounces = 2;
    bounced.settings.gi.temporal = 0.5;
    let mut iso = cornell.clone();
    iso.settings.gi.filter = Filter::Iso;
    let mut hall = common::hall();
    hall.set_size(Some(160), Some(120)).unwrap();
    for (name, scene) in [
        ("cornell", &cornell),
        ("cornell, 2 bounces, temporal", &bounced),
        ("cornell, isotropic", &iso),
        ("hall", &hall),
    ] {
        let (w, h) = (scene.camera.width, scene.camera.height);
        let (resident, r) = frame(&ctx, scene, Storage::Resident);
        // The report's rows are the images the renderer holds: the per-voxel ones (at the
        // grid's extent) with the memory bound to them.
        let report = r.memory();
        let d = r.voxels.grid.dims;
        for img in r.voxels.images().into_iter().chain(r.radiance.images()) {
            let row = report
                .rows
                .iter()
                .find(|x| x.name == img.name)
                .unwrap_or_else(|| panic!("{name}: no row {}", img.name));
            let e = img.desc.extent;
            let per_voxel = [e.width, e.height, e.depth] == d.to_array();
            let want = if per_voxel { img.bytes } else { img.desc.texel_bytes() };
            assert_eq!(row.bytes, want, "{name}: {}", img.name);
        }
        drop(r);
        let (dense, _) = frame(&ctx, scene, Storage::Dense);
        let (f, _) = flip(&dense, &resident, w, h);
        println!("{name}: FLIP resident vs dense {f:.5}, {:.1} MiB", report.mib());
        assert!(f <= 0.005, "{name}: resident and dense storage differ, FLIP {f}");
    }
    common::assert_clean(&ctx);
}

#[test]
fn a_write_outside_the_census_bricks_is_an_error_not_a_hole() {
    let Some(ctx) = resident_context() else { return };
    let scene = Scene::embedded_default().unwrap();
    let grid = VoxelGrid::fit(&scene.mesh.bounds, 32).unwrap();
    let scene_gpu = SceneGpu::new(&ctx, &scene).unwrap();
    let method = VoxelizeMethod::raster(Coverage::Conservative);
    // A census through the pool, then every other brick of it dropped.
    let sparse = StorageRequest { storage: Storage::Sparse, ..Default::default() };
    let (pool, _) = vct::voxel::build(&ctx, &scene, &scene_gpu, grid, method, sparse).unwrap();
    let mut asked = pool.bricks.read_pages().unwrap();
    drop(pool);
    let census = asked.iter().filter(|&&a| a != 0).count();
    let mut kept = 0;
    for a in asked.iter_mut().filter(|a| **a != 0) {
        kept += 1;
        if kept % 2 == 0 {
            *a = 0;
        }
    }
    let volume = VoxelVolume::stored(&ctx, grid, Bricks::resident(&ctx, &grid, &asked).unwrap()).unwrap();
    let voxelizer = Voxelizer::new(&ctx, &scene, &scene_gpu, &volume, method).unwrap();
    ctx.submit_and_wait("voxelize", |cmd| voxelizer.record(cmd, &scene_gpu, &volume)).unwrap();
    let Err(e) = volume.bricks.check() else { panic!("half the census bricks held the Cornell box") };
    let e = e.to_string();
    let dropped = census / 2;
    assert!(e.contains(&format!("into {dropped} bricks")) && e.contains("outside the blocks"), "{e}");
    drop((voxelizer, volume));
    common::assert_clean(&ctx);
}
