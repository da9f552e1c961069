//! Fitted grids: each axis of the voxel grid gets its own (power-of-two) count fitted to the
//! scene's bounds, with cubic voxels. A non-cubic grid is checked against exact coverage, survives
//! the binvox round trip, renders the same image as the bounding cube at the same voxel size, and
//! bad dims are errors naming them. Lavapipe, validation on.

mod common;

use std::sync::Arc;

use glam::{UVec3, Vec3};
use vct::gpu::Context;
use vct::reference::coverage::RefGrid;
use vct::reference::metrics::flip;
use vct::render::radiance::Chains;
use vct::render::{RenderOptions, Renderer};
use vct::scene::Scene;
use vct::voxel::bricks::Storage;
use vct::voxel::headless::voxelize_in;
use vct::voxel::{binvox, Coverage, VoxelGrid, VoxelizeMethod};

fn triangles(scene: &Scene) -> Vec<[Vec3; 3]> {
    (0..scene.mesh.triangle_count()).map(|t| scene.mesh.triangle(t)).collect()
}

#[test]
fn fitted_grid_follows_the_scene_shape_and_holds_its_bounds() {
    let scene = common::hall();
    let g = VoxelGrid::fit(&scene.mesh.bounds, 64).unwrap();
    // 8 m over 62 voxels: 0.129 m; 1.3 m needs 13 voxels, 2 m 18 (with padding).
    assert_eq!(g.dims, UVec3::new(64, 16, 32), "{}", g.dims_label());
    let b = g.bounds();
    let pad = scene.mesh.bounds.min - b.min;
    assert!(pad.min_element() >= g.voxel * 0.99, "padding {pad} under a voxel {}", g.voxel);
    assert!((b.max - scene.mesh.bounds.max).min_element() >= g.voxel * 0.99);
    assert_eq!(g.mip_levels(), 5, "the chain ends where the shortest axis is one texel");
    // Every axis is a power of two; the shortest is 16.
    let e = VoxelGrid::fit_dims(&scene.mesh.bounds, UVec3::new(64, 48, 16)).unwrap_err().to_string();
    assert!(e.contains("dims (y)") && e.contains("48"), "{e}");
    // Too few voxels on a short axis: the voxel grows until the bounds fit.
    let tight = VoxelGrid::fit_dims(&scene.mesh.bounds, UVec3::new(64, 16, 16)).unwrap();
    assert!(tight.voxel > g.voxel && (tight.bounds().min - scene.mesh.bounds.min).min_element() <= 0.0);
}

#[test]
fn non_cubic_grid_is_exact_against_coverage_and_round_trips_binvox() {
    let ctx = common::context();
    let scene = common::hall();
    let tris = triangles(&scene);
    for (dims, method) in [
        (None, VoxelizeMethod::raster(Coverage::Conservative)),
        (None, VoxelizeMethod::tess()),
        (Some(UVec3::new(32, 16, 64)), VoxelizeMethod::raster(Coverage::Conservative)),
    ] {
        let grid = VoxelGrid::choose(&scene.mesh.bounds, 64, dims).unwrap();
        let run = voxelize_in(&ctx, &scene, method, grid, 1).unwrap();
        let occupied = run.occupied();
        let a = RefGrid::matching(&grid).coverage(&tris, 1e-3).accuracy(&occupied);
        println!("{} {}: {a:?}", grid.dims_label(), method.label());
        assert!(a.recall >= 0.999 && a.precision >= 0.999, "{} {}: {a:?}", grid.dims_label(), method.label());
        assert!(a.occupied > 400, "too little geometry for the test to mean much");
        let path = std::env::temp_dir().join(format!("vct-fitted-{}.binvox", grid.dims_label()));
        binvox::write(&path, &grid, &occupied).unwrap();
        let (back, back_occupied) = binvox::read(&path).unwrap();
        assert_eq!(back.dims, grid.dims);
        assert!((back.voxel - grid.voxel).abs() < 1e-6 && back.origin.distance(grid.origin) < 1e-5);
        assert!(back_occupied == occupied, "binvox round trip changed the voxels");
    }
    common::assert_clean(&ctx);
}

fn render(ctx: &Arc<Context>, scene: &Scene, dims: Option<UVec3>, gi: bool) -> (Vec<u8>, VoxelGrid) {
    let options = RenderOptions { resolution: Some(64), dims, gi, ..Default::default() };
    let r = Renderer::new(ctx, scene.clone(), options).unwrap();
    r.render().unwrap();
    (r.read_frame().unwrap().ldr, r.voxels.grid)
}

#[test]
fn fitted_grid_renders_the_bounding_cubes_image() {
    let ctx = common::context();
    let mut scene = common::hall();
    scene.set_size(Some(160), Some(120)).unwrap();
    let (fitted, g) = render(&ctx, &scene, None, true);
    let (cube, c) = render(&ctx, &scene, Some(UVec3::splat(64)), true);
    assert_eq!(g.dims, UVec3::new(64, 16, 32));
    // Same voxel size, and the fitted grid's voxels are the cube's (whole voxels apart).
    assert!((g.voxel - c.voxel).abs() < 1e-6);
    let shift = (g.origin - c.origin) / g.voxel;
    assert!((shift - shift.round()).abs().max_element() < 1e-3, "lattices differ by {shift}");
    let (f, _) = flip(&cube, &fitted, 160, 120);
    println!("FLIP fitted vs cube: {f:.4} ({} vs {} voxels)", g.voxel_count(), c.voxel_count());
    // The cube's extra voxels are empty; only cones wider than the fitted grid's coarsest texel
    // (16 voxels) see a different level.
    assert!(f <= 0.005, "fitted and cube images differ: FLIP {f}");
    // The agreement means something: indirect light (weak under an open sky) changes the
    // picture by several times the bound.
    let (direct, _) = render(&ctx, &scene, None, false);
    let (d, _) = flip(&fitted, &direct, 160, 120);
    println!("FLIP fitted vs direct only: {d:.4}");
    assert!(d >= 3.0 * 0.005, "GI barely changes the image (FLIP {d}): the comparison is empty");
    common::assert_clean(&ctx);
}

#[test]
fn memory_report_adds_up_and_matches_what_is_allocated() {
    let ctx = common::context();
    let scene = common::hall();
    let options = RenderOptions { resolution: Some(64), storage: Storage::Sparse, ..Default::default() };
    let sparse = Renderer::new(&ctx, scene.clone(), options).unwrap();
    sparse.render().unwrap();
    let s = sparse.memory();
    check_rows(&sparse, &s);
    // The pool's slots (the census' bricks and the empty one) at 4 B a voxel texel.
    let slots = sparse.voxels.bricks.capacity as u64;
    assert_eq!(slots, sparse.voxels.bricks.usage().needed as u64 + 1);
    let voxel = s.rows.iter().find(|r| r.name == "voxel albedo").unwrap();
    let [x, y, z] = voxel.extent;
    assert!((x * y * z) as u64 >= slots * 8 && voxel.bytes == 4 * (x * y * z) as u64);
    let table = s.rows.iter().find(|r| r.name == "brick page table").unwrap();
    assert_eq!(table.bytes, 32 + 4 * (32 * 8 * 16));
    drop(sparse);
    let dense = RenderOptions { resolution: Some(64), storage: Storage::Dense, ..Default::default() };
    let r = Renderer::new(&ctx, scene.clone(), dense).unwrap();
    let m = r.memory();
    check_rows(&r, &m);
    assert!(s.bytes < m.bytes, "sparse {} B, dense {} B", s.bytes, m.bytes);
    assert_eq!(s.cube_bytes, m.cube_bytes, "the cube column is the dense cube either way");
    assert_eq!(m.dims, [64, 16, 32]);
    // By hand: 32768 voxels; R32UI albedo 4 B each. The default (directional) model reads the
    // isotropic volume's level 0 only: RGBA16F, 8 B a voxel, and with one bounce and no temporal
    // filter that is the injected light itself. Its six chains of 32 × 8 × 16
    // (four mips) are stacked along x, each followed by a separator of 8 texels (one at the
    // coarsest mip): 5 × 40 + 32 = 232 texels long.
    let row = |name| m.rows.iter().find(|r| r.name == name).unwrap();
    assert_eq!(m.rows[0].bytes, 4 * 32768);
    assert_eq!(row("injected radiance").bytes, 8 * 32768);
    assert!(m.rows.iter().all(|r| r.name != "radiance level 0"));
    assert_eq!(row("radiance chain").bytes, 8, "the isotropic chain is not read: one texel");
    assert_eq!(row("radiance directional chains").extent, [232, 8, 16]);
    assert_eq!(row("radiance directional chains").bytes, 8 * (232 * 8 * 16 + 116 * 4 * 8 + 58 * 2 * 4 + 29 * 2));
    // Over the cube, level 0 is 64³ and the chain three levels longer.
    assert_eq!(m.rows[0].cube_bytes, 4 * 64 * 64 * 64);
    println!("{m}");
    assert!(m.cube_bytes >= 7 * m.bytes, "the hall fills an eighth of its cube: {} vs {}", m.bytes, m.cube_bytes);
    // A cubic grid is its own cube.
    let c = vct::render::memory::MemoryReport::for_grid(
        &VoxelGrid::fit_dims(&scene.mesh.bounds, UVec3::splat(32)).unwrap(),
        &vct::render::memory::Layout {
            bounces: true,
            listed: true,
            pool: None,
            resident: None,
            temporal: true,
            chains: Chains::ALL,
        },
    );
    assert_eq!(c.bytes, c.cube_bytes);
    common::assert_clean(&ctx);
}

/// The report adds up, and row by row matches the renderer's images: same extent and levels,
/// and the driver's allocation holds the texels with little more than alignment on top.
fn check_rows(r: &Renderer, m: &vct::render::memory::MemoryReport) {
    assert_eq!(m.bytes, m.rows.iter().map(|r| r.bytes).sum::<u64>());
    assert_eq!(m.cube_bytes, m.rows.iter().map(|r| r.cube_bytes).sum::<u64>());
    let images: Vec<_> = r.voxels.images().into_iter().chain(r.radiance.images()).collect();
    let table = r.voxels.bricks.stored_bricks().is_some() as usize;
    assert_eq!(images.len() + table + 2, m.rows.len(), "a row per image, the page table, the occupied lists");
    for (row, img) in m.rows.iter().zip(&images) {
        assert_eq!((row.name, row.extent, row.mips), (img.name.as_str(), img.desc.size(), img.desc.mip_levels));
        assert!(
            img.bytes >= row.bytes && img.bytes <= row.bytes + row.bytes / 8 + (64 << 10),
            "{}: {} vs {}",
            row.name,
            img.bytes,
            row.bytes
        );
    }
}

#[test]
fn the_heap_check_admits_what_allocates_and_names_what_cannot() {
    // Lavapipe reports a 2 GiB heap: a dense 256³ Cornell box (677 MiB) allocates, 512³ (5.4 GiB)
    // cannot and is told before the allocator fails on one texture of it.
    let ctx = common::context();
    let scene = Scene::embedded_default().unwrap();
    let big = RenderOptions { dims: Some(UVec3::splat(256)), storage: Storage::Dense, ..Default::default() };
    let r = Renderer::new(&ctx, scene.clone(), big).unwrap();
    assert!(r.memory().mib() > 600.0);
    drop(r);
    let huge = RenderOptions { dims: Some(UVec3::splat(512)), storage: Storage::Dense, ..Default::default() };
    let e = Renderer::new(&ctx, scene, huge).err().expect("a 512³ grid fitted the heap").to_string();
    assert!(e.contains("512×512×512") && e.contains("largest heap"), "{e}");
    common::assert_clean(&ctx);
}

/// The frame's HDR pixels with `work`.
fn hdr_with(ctx: &Arc<Context>, scene: &Scene, work: vct::render::Work, bounces: u32) -> Vec<f32> {
    let mut scene = scene.clone();
    scene.settings.gi.bounces = bounces;
    let r = Renderer::new(ctx, scene, RenderOptions { resolution: Some(32), work, ..Default::default() }).unwrap();
    r.render().unwrap();
    r.read_frame().unwrap().hdr
}

#[test]
fn mips_over_occupied_texels_equal_the_dense_filter() {
    // The listed filter visits only the occupied texels of each level (lists built on the GPU)
    // and clears the rest: its mips, and so the image, must be the dense filter's exactly. A
    // filter that missed texels (a short list, a wrong dispatch size) loses indirect light.
    let ctx = common::context();
    let mut hall = common::hall();
    hall.set_size(Some(96), Some(72)).unwrap();
    let mut cornell = Scene::embedded_default().unwrap();
    cornell.set_size(Some(96), Some(96)).unwrap();
    for (name, scene, bounces) in [("cornell", &cornell, 1), ("cornell, 2 bounces", &cornell, 2), ("hall", &hall, 1)] {
        let dense = hdr_with(&ctx, scene, vct::render::Work::Dense, bounces);
        let listed = hdr_with(&ctx, scene, vct::render::Work::Occupied, bounces);
        let diff = dense.iter().zip(&listed).map(|(a, b)| (a - b).abs()).fold(0.0f32, f32::max);
        assert!(diff <= 1e-6, "{name}: listed and dense filters differ by {diff}");
        let gi_off = {
            let mut s = scene.clone();
            s.settings.gi.bounces = bounces;
            let o = RenderOptions { resolution: Some(32), gi: false, ..Default::default() };
            let r = Renderer::new(&ctx, s, o).unwrap();
            r.render().unwrap();
            r.read_frame().unwrap().hdr
        };
        let gi = listed.iter().zip(&gi_off).map(|(a, b)| (a - b).abs()).fold(0.0f32, f32::max);
        assert!(gi > 0.01, "{name}: the cones gather nothing ({gi}), the comparison is empty");
    }
    common::assert_clean(&ctx);
}

#[test]
fn res_auto_picks_a_smaller_grid_for_a_looser_target() {
    use vct::bench::auto::{choose, from_size, Target};
    let ctx = common::context();
    let mut scene = Scene::embedded_default().unwrap();
    scene.set_size(Some(64), Some(64)).unwrap();
    let cache = std::env::temp_dir().join(format!("vct-auto-{}", std::process::id()));
    let o = RenderOptions::default();
    let n = [16, 32, 64];
    let at = |flip| Target { flip, spp: 16, cache: &cache };
    let pick = |target| choose(&ctx, &scene, "cornell-auto", o, &n, at(Some(target)), &|_| {}).unwrap();
    // A target no grid meets: every one is tried, and the closest is chosen and said so.
    let all = pick(1e-6);
    println!("{all}");
    assert!(!all.met && all.tried.len() == 3 && all.reason.contains("no grid meets"));
    let flips: Vec<f32> = all.tried.iter().map(|t| t.flip).collect();
    assert!(all.tried.windows(2).all(|w| w[0].memory_mib < w[1].memory_mib), "memory grows with the grid");
    // The coarsest grid is the least accurate here (else the search would have nothing to buy).
    let best = flips.iter().cloned().fold(f32::INFINITY, f32::min);
    assert!(flips[0] > best + 0.005, "16³ is as good as the finest: {flips:?}");
    // A loose target takes the coarsest grid; one at the best FLIP (plus the run-to-run
    // spread) a finer one.
    let loose = pick(flips.iter().cloned().fold(0.0, f32::max) + 0.01);
    assert!(loose.met && loose.resolution == 16 && loose.tried.len() == 1, "{loose}");
    let tight = pick(best + 0.002);
    println!("{tight}");
    assert!(tight.met && tight.resolution > loose.resolution, "{tight}");
    // Without a target: from the scene's size (5.5 m at 8 voxels a metre: 64), unmeasured.
    let sized = choose(&ctx, &scene, "cornell-auto", o, &n, at(None), &|_| {}).unwrap();
    assert_eq!((sized.resolution, sized.met, sized.tried.len()), (from_size(&scene), false, 0));
    assert_eq!(sized.resolution, 64);
    common::assert_clean(&ctx);
    let _ = std::fs::remove_dir_all(&cache);
}

/// A lattice shift (`RenderOptions::lattice`, `vct bench --accuracy --lattices`) moves the fitted
/// grid by that share of a voxel and nothing else, the scene still inside it; more than half a
/// voxel (its padding), a non-finite one or one for a volume following the camera is an error
/// naming it.
#[test]
fn a_lattice_shift_moves_the_fitted_grid_by_under_a_voxel() {
    use vct::render::layout::grid_for;
    let ctx = common::context();
    let scene = common::hall();
    let fitted = grid_for(&ctx, &scene, &RenderOptions::default(), 64).unwrap();
    let shift = Vec3::new(0.5, -0.25, -0.5);
    let moved = grid_for(&ctx, &scene, &RenderOptions { lattice: Some(shift), ..Default::default() }, 64).unwrap();
    assert_eq!((moved.dims, moved.voxel), (fitted.dims, fitted.voxel));
    assert!((moved.origin - fitted.origin - shift * fitted.voxel).abs().max_element() < 1e-5, "{moved:?}");
    let (b, s) = (moved.bounds(), scene.mesh.bounds);
    assert!(b.min.cmple(s.min).all() && b.max.cmpge(s.max).all(), "{b:?} does not hold {s:?}");
    for bad in [Vec3::new(0.0, 0.6, 0.0), Vec3::splat(f32::NAN)] {
        let e = grid_for(&ctx, &scene, &RenderOptions { lattice: Some(bad), ..Default::default() }, 64).unwrap_err();
        assert!(e.to_string().contains("lattice"), "{e}");
    }
    let follow = RenderOptions {
        lattice: Some(Vec3::ZERO),
        follow: Some(vct::render::Follow { extent: 4.0, snap: true }),
        ..Default::default()
    };
    assert!(grid_for(&ctx, &scene, &follow, 64).unwrap_err().to_string().contains("lattice"));
}
