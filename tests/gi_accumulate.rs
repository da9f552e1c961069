//! Screen-space accumulation of the reduced-resolution diffuse cones (`--gi-accumulate`): on a
//! still camera the image converges towards tracing every pixel (each pixel is traced once in
//! gi-scale² frames and keeps its trace), and after a jump cut the history is rejected where the
//! surface changed: the pixels a CPU ray cast finds disoccluded match a renderer that has no
//! history at all. Lavapipe, validation on.

mod common;

use common::difference;

use glam::Vec3;
use vct::reference::bvh::Bvh;
use vct::render::{FrameImages, RenderOptions, Renderer, View};
use vct::scene::{Camera, Scene};

const SIZE: u32 = 192;
const RES: u32 = 64;

/// The volume is kept while nothing it depends on changes, as in the viewer (the same image to
/// the bit, tests/reuse_volume.rs): what these tests judge is the screen-space history, and
/// rebuilding an unchanged volume every frame would take most of their time.
fn options(gi_scale: u32, gi_accumulate: bool) -> RenderOptions {
    RenderOptions {
        resolution: Some(RES),
        view: View::Diffuse,
        gi_scale,
        gi_accumulate,
        reuse_volume: true,
        ..Default::default()
    }
}

fn frame(r: &Renderer) -> FrameImages {
    r.render().unwrap();
    r.read_frame().unwrap()
}

fn scene() -> Scene {
    let mut scene = Scene::embedded_default().unwrap();
    scene.set_size(Some(SIZE), Some(SIZE)).unwrap();
    // Full resolution traces the whole set at every pixel, which is what accumulation converges
    // to (split among pixels, the set would be resolved over blocks: docs/design/reduced-scale.md).
    scene.settings.gi.split_cones = false;
    scene
}

#[test]
fn accumulation_converges_to_full_resolution_on_a_still_camera() {
    let ctx = common::context();
    let scene = scene();
    let full = frame(&Renderer::new(&ctx, scene.clone(), options(1, false)).unwrap());
    for scale in [2u32, 4, 8] {
        let r = Renderer::new(&ctx, scene.clone(), options(scale, true)).unwrap();
        let cycle = (scale * scale) as usize;
        let first = frame(&r);
        // Every pixel has been traced once after a cycle of frames; two more show it stays.
        let mut frames = vec![];
        for _ in 1..cycle + 2 {
            frames.push(frame(&r));
        }
        let last = frames.last().unwrap();
        let before_last = &frames[frames.len() - 2];
        let single = difference(&first, &full, |_| true);
        let converged = difference(last, &full, |_| true);
        let change = difference(last, before_last, |_| true);
        println!("gi-scale {scale}: against full resolution: first frame {single:.4}, after {} frames {converged:.4}; last change {change:.5}", cycle + 1);
        // Measured: 0.0127 -> 0.0004 at scale 2, 0.0409 -> 0.0004 at scale 4, 0.1152 -> 0.0004
        // at scale 8 (half-float rounding), and no change at all between the last two frames.
        assert!(converged < 0.002, "gi-scale {scale}: accumulated {converged:.4} from full resolution");
        assert!(
            single > 5.0 * converged,
            "gi-scale {scale}: accumulation gained nothing ({single:.4} -> {converged:.4})"
        );
        assert!(change < 1e-4, "gi-scale {scale}: a still view keeps changing by {change:.5} a frame");
    }
    common::assert_clean(&ctx);
}

/// The default camera turned by `deg` about the vertical through its target.
fn orbit(camera: &Camera, deg: f32) -> Camera {
    let rot = glam::Quat::from_rotation_y(deg.to_radians());
    Camera { eye: camera.target + rot * (camera.eye - camera.target), ..*camera }
}

/// The pixels of view `b` whose surface view `a` did not see (off its screen, or another
/// surface in front of or behind it by more than `gap`), by a CPU ray cast of both views.
fn disoccluded(scene: &Scene, a: &Camera, b: &Camera, gap: f32) -> Vec<bool> {
    let tris: Vec<_> = (0..scene.mesh.triangle_count()).map(|t| scene.mesh.triangle(t)).collect();
    let normals: Vec<Vec3> = tris.iter().map(|[p, q, r]| (*q - *p).cross(*r - *p).normalize()).collect();
    let bvh = Bvh::new(tris);
    let hit = |cam: &Camera, x: u32, y: u32| {
        let (o, d) = cam.ray(x as f32, y as f32);
        bvh.intersect(o, d, 0.0, f32::INFINITY, false).map(|h| (o + d * h.t, normals[h.tri as usize]))
    };
    let to_a = a.view_proj(&scene.mesh.bounds);
    let (w, h) = (SIZE, SIZE);
    (0..w * h)
        .map(|i| {
            let Some((wb, nb)) = hit(b, i % w, i / w) else { return false };
            let clip = to_a * wb.extend(1.0);
            let p = (glam::Vec2::new(clip.x, clip.y) / clip.w * 0.5 + 0.5) * glam::Vec2::new(w as f32, h as f32);
            // Off a's screen, or too near its border to call.
            if clip.w <= 0.0 || p.x < 0.0 || p.y < 0.0 || p.x >= w as f32 || p.y >= h as f32 {
                return true;
            }
            match hit(a, p.x as u32, p.y as u32) {
                None => true,
                Some((wa, _)) => (wa - wb).dot(nb).abs() > gap,
            }
        })
        .collect()
}

#[test]
fn a_jump_cut_rejects_the_history_where_the_surface_changed() {
    let ctx = common::context();
    // The set unturned: turned by pixel (the default), a pixel of the mask's edge (where the CPU
    // and the rasterizer part at a silhouette) that takes the history in one frame and an estimate
    // in the other differs by the turn's spread (0.008-0.010 measured), which hides the leak this
    // test looks for.
    let mut scene = scene();
    scene.settings.gi.turn_cones = false;
    let scale = 2;
    let cycle = scale * scale;
    let r = Renderer::new(&ctx, scene.clone(), options(scale, true)).unwrap();
    for _ in 0..2 * cycle {
        frame(&r);
    }
    let mut r = r;
    let a = r.scene.camera;
    let b = orbit(&a, 35.0);
    r.scene.camera = b;
    let cut = frame(&r);
    let mut at_b = scene.clone();
    at_b.camera = b;
    // Its first frame has no history, and its traced pixels are the cut frame's (2 cycles on).
    let fresh = frame(&Renderer::new(&ctx, at_b.clone(), options(scale, true)).unwrap());
    let full = frame(&Renderer::new(&ctx, at_b.clone(), options(1, false)).unwrap());
    let voxel = r.voxels.grid.voxel;
    let new = disoccluded(&scene, &a, &b, 2.0 * voxel);
    let count = new.iter().filter(|&&d| d).count();
    let lit = |p: usize| cut.hdr[4 * p] + cut.hdr[4 * p + 1] + cut.hdr[4 * p + 2] > 0.0;
    let seen = |p: usize| !new[p] && lit(p);
    let rejected = difference(&cut, &fresh, |p| new[p]);
    let kept = difference(&cut, &full, seen);
    let without = difference(&fresh, &full, seen);
    println!(
        "jump cut (35 degrees): {count} disoccluded pixels, cut against no history there {rejected:.5}; \
         elsewhere against full resolution: {kept:.4} with the history, {without:.4} without"
    );
    assert!(count > 500, "the cut reveals surfaces: {count} pixels");
    // Measured 0.0008-0.0021 (pixels where the CPU and the rasterizer part at a silhouette);
    // with the surface test off, 0.011.
    assert!(rejected < 0.004, "history leaked into disoccluded pixels: {rejected:.4}");
    assert!(kept < without, "the reprojected history helped nowhere: {kept:.4} against {without:.4}");
    common::assert_clean(&ctx);
}

/// What moves in [`under_motion`].
#[derive(Clone, Copy, Debug)]
enum Motion {
    /// The camera orbits its target by 0.5° a frame.
    Camera,
    /// The spot light turns 0.5° a frame.
    Light,
}

/// Over `frames` frames of `motion` after gi-scale² still ones (96², 32³, the indirect light):
/// the mean difference from full-resolution tracing of accumulated and of plain upsampled light,
/// and the mean change from frame to frame of full resolution and of accumulation.
fn under_motion(ctx: &std::sync::Arc<vct::gpu::Context>, motion: Motion, scale: u32, frames: u32) -> [f64; 4] {
    let mut scene = Scene::embedded_default().unwrap();
    scene.set_size(Some(96), Some(96)).unwrap();
    // Full resolution traces the whole set at every pixel, as in `scene`.
    scene.settings.gi.split_cones = false;
    let o = |gi_scale, gi_accumulate| RenderOptions {
        resolution: Some(32),
        view: View::Indirect,
        gi_scale,
        gi_accumulate,
        reuse_volume: true,
        ..Default::default()
    };
    let mut renderers: Vec<Renderer> = [o(1, false), o(scale, true), o(scale, false)]
        .into_iter()
        .map(|o| Renderer::new(ctx, scene.clone(), o).unwrap())
        .collect();
    let turn = glam::Quat::from_rotation_y(0.5f32.to_radians());
    let [mut error, mut plain, mut change_full, mut change] = [0.0; 4];
    let mut previous: Option<Vec<FrameImages>> = None;
    let still = scale * scale;
    for f in 0..still + frames {
        for r in renderers.iter_mut().filter(|_| f >= still) {
            match motion {
                Motion::Camera => {
                    let c = &mut r.scene.camera;
                    c.eye = c.target + turn * (c.eye - c.target);
                }
                Motion::Light => {
                    let light = r.scene.lights.first_mut().unwrap();
                    vct::viewer::camera::swing_light(light, 0.0, 0.5f32.to_radians());
                }
            }
        }
        let images: Vec<FrameImages> = renderers.iter().map(frame).collect();
        if f >= still {
            error += difference(&images[1], &images[0], |_| true);
            plain += difference(&images[2], &images[0], |_| true);
            if let Some(p) = &previous {
                change_full += difference(&images[0], &p[0], |_| true);
                change += difference(&images[1], &p[1], |_| true);
            }
        }
        previous = Some(images);
    }
    let (n, m) = (frames as f64, (frames - 1) as f64);
    [error / n, plain / n, change_full / m, change / m]
}

#[test]
fn accumulation_under_a_moving_camera_and_a_turning_light_is_as_stable_as_full_resolution() {
    let ctx = common::context();
    for motion in [Motion::Camera, Motion::Light] {
        let [error, plain, change_full, change] = under_motion(&ctx, motion, 4, 10);
        println!(
            "{motion:?}, gi-scale 4: from full resolution: accumulated {error:.4}, upsampled {plain:.4}; \
             change a frame: full resolution {change_full:.4}, accumulated {change:.4}"
        );
        // Measured: camera 0.024 against 0.146, change 0.019 against 0.022 a frame; light
        // 0.015 against 0.146, change 0.0013 against 0.0053 (it shows the light a few frames late).
        assert!(
            error < 0.5 * plain,
            "{motion:?}: accumulation is no closer to full resolution: {error:.4} against {plain:.4}"
        );
        assert!(
            change < 1.2 * change_full,
            "{motion:?}: accumulation flickers: {change:.4} against {change_full:.4} a frame"
        );
    }
    common::assert_clean(&ctx);
}

/// Until a pixel has a trace of its own it shows an estimate: the upsampled light averaged over
/// frames, whose traced pixels move through the block. Without it such a pixel would show each
/// frame's upsampling from other traced pixels, and at scale 8 the 64 frames after a cut would
/// flicker. Over the first half cycle of a still view at scale 8: the frame-to-frame change,
/// and the distance from full resolution.
#[test]
fn pixels_awaiting_their_own_trace_hold_a_steady_estimate() {
    let ctx = common::context();
    let scene = scene();
    let full = frame(&Renderer::new(&ctx, scene.clone(), options(1, false)).unwrap());
    let r = Renderer::new(&ctx, scene, options(8, true)).unwrap();
    let mut previous = frame(&r);
    let (mut change, mut error) = (0.0, 0.0);
    let frames = 32;
    for _ in 0..frames {
        let f = frame(&r);
        change += difference(&f, &previous, |_| true) / frames as f64;
        error += difference(&f, &full, |_| true) / frames as f64;
        previous = f;
    }
    println!("gi-scale 8, frames 2-33 of a still view: change a frame {change:.4}, from full resolution {error:.4}");
    // Measured: 0.0187 a frame and 0.0774 from full resolution; showing each frame's upsampling
    // instead, 0.0966 and 0.0889.
    assert!(change < 0.04, "pixels awaiting their own trace change by {change:.4} a frame");
    common::assert_clean(&ctx);
}

/// Whether a frame's timings include a pass.
fn ran(timings: &[vct::gpu::Timing], pass: &str) -> bool {
    timings.iter().any(|t| t.pass == pass)
}

#[test]
fn a_settled_still_view_skips_the_trace_and_shows_the_same_image() {
    let ctx = common::context();
    let scene = scene();
    let scale = 2u32;
    let cycle = (scale * scale) as usize;
    // Keeping the volume lets a still view settle; building it every frame never does (the same
    // volume to the bit, tests/reuse_volume.rs).
    let mut settling = Renderer::new(&ctx, scene.clone(), options(scale, true)).unwrap();
    let mut tracing =
        Renderer::new(&ctx, scene.clone(), RenderOptions { reuse_volume: false, ..options(scale, true) }).unwrap();
    let mut skipped = 0;
    for f in 0..2 * cycle + 2 {
        // A cut after the first frame, so that the traces of the cycle before settling are the
        // only ones of the view it settles on.
        if f == 1 {
            for r in [&mut settling, &mut tracing] {
                r.scene.camera = orbit(&r.scene.camera, 10.0);
            }
        }
        let t = settling.render().unwrap();
        assert!(ran(&tracing.render().unwrap(), "trace"), "frame {f}: a volume built every frame settles nothing");
        // The cycle of frames after the cut traces, and then every pixel holds its own trace.
        assert_eq!(ran(&t, "trace"), f <= cycle, "frame {f}: {t:?}");
        assert_eq!(ran(&t, "accumulate"), f <= cycle, "frame {f}");
        assert!(ran(&t, "shade pixels"), "frame {f}");
        skipped += !ran(&t, "trace") as u32;
    }
    let (a, b) = (settling.read_frame().unwrap(), tracing.read_frame().unwrap());
    let still = difference(&a, &b, |_| true);
    // Then the camera moves: the settled renderer traces again, from the history it last wrote.
    for f in 0..3 {
        for r in [&mut settling, &mut tracing] {
            r.scene.camera = orbit(&r.scene.camera, 2.0);
        }
        assert!(ran(&settling.render().unwrap(), "trace"), "moving frame {f}");
        tracing.render().unwrap();
    }
    let moved = difference(&settling.read_frame().unwrap(), &tracing.read_frame().unwrap(), |_| true);
    println!("{skipped} frames skipped the trace; against tracing every frame: still {still:.6}, moving {moved:.6}");
    // A history read from the wrong frame (its traces one jitter position short) or stale after
    // the move would differ by percents.
    assert!(still < 1e-6, "the settled view differs from tracing every frame: {still:.6}");
    assert!(moved < 1e-6, "after settling, the moving view differs from tracing every frame: {moved:.6}");
    common::assert_clean(&ctx);
}
