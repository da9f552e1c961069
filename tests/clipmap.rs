//! Clipmap cascades (voxel::clipmap; Wicked Engine's VXGI, Freed 2018 §2.3.2) against what they
//! must agree with: one level is the snapped volume that follows the camera, and where the finest
//! level holds the whole room, the levels agree with the fitted grid of the same voxels; where
//! it does not, the cones find the room's light in the coarser levels.

mod common;

use glam::Vec3;
use vct::render::{ClipOptions, Follow, FrameImages, RenderOptions, Renderer, View};
use vct::scene::Scene;
use vct::voxel::headless::voxelize_in;
use vct::voxel::{Coverage, VoxelizeMethod};

/// The Cornell box seen from inside, near its open front (a clipmap centres on the camera).
fn inside() -> Scene {
    let mut scene = Scene::embedded_default().unwrap();
    scene.camera.eye = Vec3::new(0.0, 2.75, 2.5);
    scene.camera.target = Vec3::new(0.0, 2.75, 0.0);
    scene.camera.fov_y_deg = 90.0;
    scene.camera.width = 96;
    scene.camera.height = 96;
    scene
}

fn options(res: u32, view: View) -> RenderOptions {
    RenderOptions { method: VoxelizeMethod::raster(Coverage::Msaa), resolution: Some(res), view, ..Default::default() }
}

fn clipped(levels: u32, res: u32, extent: Option<f32>, view: View) -> RenderOptions {
    RenderOptions { clipmap: Some(ClipOptions { levels, extent }), ..options(res, view) }
}

fn render(scene: &Scene, options: RenderOptions) -> FrameImages {
    let ctx = common::context();
    let r = Renderer::new(&ctx, scene.clone(), options).unwrap();
    r.render().unwrap();
    let f = r.read_frame().unwrap();
    drop(r);
    common::assert_clean(&ctx);
    f
}

fn mean(f: &FrameImages) -> f64 {
    let n = (f.width * f.height) as usize;
    (0..n).map(|p| (f.hdr[4 * p] + f.hdr[4 * p + 1] + f.hdr[4 * p + 2]) as f64).sum::<f64>() / n as f64
}

/// One level of --res voxels wider than the room holds it, centred on it and snapped to its
/// voxel: from a camera whose snapped following volume has the same corner, the two are the same
/// texels, so the same image (the clipmap's march against the grid's).
#[test]
fn one_level_is_the_snapped_following_volume() {
    let mut scene = inside();
    scene.camera.eye = Vec3::new(0.05, 2.8, 0.3);
    scene.camera.target = Vec3::new(0.05, 2.8, -2.0);
    let bounds = scene.mesh.bounds;
    let level = vct::voxel::clipmap::Clipmap::around(scene.camera.eye, 12.0, 32, 1, Some(&bounds)).unwrap();
    let grid = vct::voxel::VoxelGrid::around(scene.camera.eye, 12.0, 32, true).unwrap();
    assert!((level.origins[0] - grid.origin).abs().max_element() < 1e-5, "{:?} {}", level.origins[0], grid.origin);
    let follow = RenderOptions { follow: Some(Follow { extent: 12.0, snap: true }), ..options(32, View::Full) };
    let a = render(&scene, follow);
    let b = render(&scene, clipped(1, 32, Some(12.0), View::Full));
    let d = common::difference(&b, &a, |_| true);
    // The same texels; the clipmap's march orders its float operations otherwise.
    assert!(d < 1e-3, "one clipmap level differs from the snapped following volume by {d}");
}

/// Where the finest level holds the room, the clipmap renders what the fitted grid of the same
/// voxels does: a 32³ grid fitted to the 5.5 m room has voxels of 5.5/30 m on the lattice the
/// clipmap snaps to, so level 0 (64 of them around the camera) voxelizes the room alike. What
/// is left differs in the mips (they are grouped from other corners). Three levels must render
/// what one does: every face of level 0 lies beyond the room (open: `Clipmap::open`), so no
/// sample moves out to, or blends into, a coarser level (levels centred on the camera instead
/// differ by 0.4%).
#[test]
fn levels_agree_with_the_fitted_grid_where_the_finest_holds_the_room() {
    let scene = inside();
    let voxel = 5.5 / 30.0;
    let fitted = render(&scene, RenderOptions { dims: Some(glam::UVec3::splat(32)), ..options(32, View::Full) });
    let one = render(&scene, clipped(1, 64, Some(64.0 * voxel), View::Full));
    let three = render(&scene, clipped(3, 64, Some(64.0 * voxel), View::Full));
    let (d_fitted, d_levels) =
        (common::difference(&three, &fitted, |_| true), common::difference(&three, &one, |_| true));
    let ratio = mean(&three) / mean(&fitted);
    println!("three levels against the fitted grid: mean |diff| {d_fitted:.4}, mean ratio {ratio:.4}; against one level: {d_levels:.4}");
    assert!((ratio - 1.0).abs() < 0.03, "the clipmap's mean radiance is {ratio:.4} of the fitted grid's");
    assert!(d_fitted < 0.06, "three levels differ from the fitted grid by {d_fitted:.4} of its radiance");
    assert!(
        d_levels < 1e-3,
        "three levels differ from one by {d_levels:.4}: the coarse levels show where level 0 holds the room"
    );
    // A second bounce, gathered in voxel space from every level's occupied voxels, alike.
    let mut bounced = scene.clone();
    bounced.settings.gi.bounces = 2;
    let fitted2 = render(&bounced, RenderOptions { dims: Some(glam::UVec3::splat(32)), ..options(32, View::Full) });
    let three2 = render(&bounced, clipped(3, 64, Some(64.0 * voxel), View::Full));
    let (gain_fitted, gain_clip) = (mean(&fitted2) / mean(&fitted), mean(&three2) / mean(&three));
    println!("a second bounce brightens the fitted grid {gain_fitted:.4}x, the clipmap {gain_clip:.4}x");
    assert!(gain_fitted > 1.02, "the second bounce adds nothing to the fitted grid: {gain_fitted:.4}");
    assert!((gain_clip / gain_fitted - 1.0).abs() < 0.03, "bounces: clipmap {gain_clip:.4}x, fitted {gain_fitted:.4}x");
}

/// A moved lattice (`RenderOptions::lattice`; `vct bench --accuracy --lattices`) moves every
/// level alike: moved by a quarter of a shift in voxels of the coarsest of three levels, level 0
/// lies on the lattice of the fitted grid moved by the whole shift (the voxels of the test
/// above), off the unmoved one, and renders what that moved fitted grid renders.
#[test]
fn a_moved_lattice_moves_every_level_alike() {
    let ctx = common::context();
    let scene = inside();
    let voxel = 5.5 / 30.0;
    let shift = Vec3::new(0.37, -0.29, 0.18);
    let fitted = RenderOptions { dims: Some(glam::UVec3::splat(32)), ..options(32, View::Full) };
    let moved = RenderOptions { lattice: Some(shift), ..fitted };
    let clip = RenderOptions { lattice: Some(shift / 4.0), ..clipped(3, 64, Some(64.0 * voxel), View::Full) };
    let grid = |o: &RenderOptions, res: u32| vct::render::layout::grid_for(&ctx, &scene, o, res).unwrap();
    let levels = grid(&clip, 64).clip.unwrap();
    // Each level's corner in voxels of the fitted grid from its corner: whole voxels on the moved
    // lattice (the shaders find a level in whole voxels of level 0 from level 0's corner).
    let on = |origin: Vec3, of: &RenderOptions| (origin - grid(of, 32).origin) / voxel;
    for k in 0..3 {
        let at = on(levels.origins[k], &moved);
        assert!((at - at.round()).abs().max_element() < 1e-3, "level {k} is off the moved lattice: {at}");
    }
    let unmoved = on(levels.origins[0], &fitted);
    assert!((unmoved - unmoved.round()).abs().min_element() > 0.1, "level 0 stayed on the unmoved lattice: {unmoved}");
    let three = render(&scene, clip);
    let (d_moved, d_unmoved) = (
        common::difference(&three, &render(&scene, moved), |_| true),
        common::difference(&three, &render(&scene, fitted), |_| true),
    );
    println!(
        "three levels on a moved lattice against the fitted grid moved alike: {d_moved:.4}; unmoved: {d_unmoved:.4}"
    );
    assert!(
        d_moved < 0.06,
        "three levels differ from the fitted grid on their lattice by {d_moved:.4} of its radiance"
    );
    assert!(
        d_moved < 0.5 * d_unmoved,
        "the levels render the unmoved grid's image as closely ({d_unmoved:.4}) as the moved one's"
    );
    common::assert_clean(&ctx);
}

/// Where the finest level holds only the camera's surroundings, the room's indirect light comes
/// from the coarser levels: it must still be there, near the fitted grid's, and not the dark of
/// a cone that found nothing.
#[test]
fn cones_find_the_rooms_light_in_the_coarser_levels() {
    let scene = inside();
    let fitted = mean(&render(&scene, options(64, View::Indirect)));
    // Four levels of 32: the finest under a metre wide around the camera, the coarsest the room.
    let clip = render(&scene, clipped(4, 32, None, View::Indirect));
    let ratio = mean(&clip) / fitted;
    println!("indirect light of four levels of 32 against the fitted 64³ grid: {ratio:.3}");
    assert!((0.8..1.25).contains(&ratio), "the clipmap's indirect light is {ratio:.3} of the fitted grid's");
    // The texel view colours each surface by its level: the room's surfaces lie beyond level 0.
    let levels = render(&scene, clipped(4, 32, None, View::Texels));
    let (x, y) = (levels.width / 2, levels.height / 2);
    let [r, g, _] = common::ldr(&levels, x, y);
    assert!(r > g / 2, "the back wall, 5 m from the camera, is coloured as level 0: {r} {g}");
}

/// Each level of the stack holds what its box voxelizes to alone, with every voxelizer: the
/// levels' draws write their own slabs, and what a voxelizer reads back while it writes (the
/// tessellation path's neighbour fill, the point path's refinement of empty voxels) is its own
/// level's.
#[test]
fn each_level_of_the_stack_is_its_box_voxelized_alone() {
    let ctx = common::context();
    let scene = inside();
    let clip = vct::voxel::clipmap::Clipmap::around(Vec3::new(0.3, 2.1, -0.4), 2.0, 32, 3, None).unwrap();
    // The point path scatters its points at a density per voxel area of level 0 for every level:
    // a level alone gets the same points at 4^k that density.
    let points = |k: u32| VoxelizeMethod::Points {
        density: vct::voxel::points::DEFAULT_POINT_DENSITY * 4f32.powi(k as i32),
        source: vct::voxel::points::PointSource::Load,
        refine: true,
    };
    let methods: [&dyn Fn(u32) -> VoxelizeMethod; 3] =
        [&|_| VoxelizeMethod::raster(Coverage::Auto), &|_| VoxelizeMethod::tess(), &points];
    for of_level in methods {
        let method = of_level(0);
        let stack = voxelize_in(&ctx, &scene, method, clip.stack_grid(), 1).unwrap().occupied();
        for k in 0..clip.levels {
            let alone = voxelize_in(&ctx, &scene, of_level(k), clip.level_grid(k), 1).unwrap().occupied();
            let n = 32usize.pow(3);
            let slab = &stack[k as usize * n..(k as usize + 1) * n];
            let differ = slab.iter().zip(&alone).filter(|(a, b)| a != b).count();
            let filled = alone.iter().filter(|&&o| o).count();
            assert!(filled > 100, "{} level {k}: only {filled} voxels", method.label());
            assert_eq!(
                differ,
                0,
                "{} level {k}: {differ} of {filled} voxels differ from the level alone",
                method.label()
            );
        }
    }
    common::assert_clean(&ctx);
}

/// What a clipmap cannot be combined with is refused with the option's name.
#[test]
fn clipmaps_refuse_what_does_not_apply() {
    let ctx = common::context();
    let scene = inside();
    let refused = |o: RenderOptions, scene: &Scene| Renderer::new(&ctx, scene.clone(), o).err().unwrap().to_string();
    let with = |o: RenderOptions| RenderOptions { clipmap: Some(ClipOptions { levels: 3, extent: None }), ..o };
    let follow = with(RenderOptions { follow: Some(Follow { extent: 4.0, snap: true }), ..options(32, View::Full) });
    assert!(refused(follow, &scene).contains("--follow"));
    let warp =
        with(RenderOptions { warp: Some(vct::voxel::warp::WarpChoice::Function(0.25)), ..options(32, View::Full) });
    assert!(refused(warp, &scene).contains("--warp"));
    let mut temporal = scene.clone();
    temporal.settings.gi.temporal = 0.5;
    assert!(refused(clipped(3, 32, None, View::Full), &temporal).contains("temporal"));
    assert!(refused(clipped(3, 48, None, View::Full), &scene).contains("res"));
    assert!(refused(clipped(3, 32, Some(f32::NAN), View::Full), &scene).contains("clipmap"));
    common::assert_clean(&ctx);
}
