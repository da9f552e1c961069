//! Reduced-resolution indirect light (`--gi-scale`): the diffuse cones traced at one pixel in 4 or
//! 16 and upsampled edge-aware agree with tracing every pixel on the Cornell box, and no light
//! crosses a silhouette: the pixels beside a depth edge (found by a CPU ray cast, not by the
//! renderer) match full resolution as well as the rest do. The specular cone traced with them
//! agrees with per-pixel tracing, and converges to it. Lavapipe, validation on.

mod common;

use common::difference;

use vct::reference::bvh::Bvh;
use vct::render::{FrameImages, RenderOptions, Renderer, View};
use vct::scene::Scene;

const SIZE: u32 = 256;

fn render(ctx: &std::sync::Arc<vct::gpu::Context>, scene: &Scene, gi_scale: u32) -> FrameImages {
    let options = RenderOptions { resolution: Some(64), view: View::Diffuse, gi_scale, ..Default::default() };
    let r = Renderer::new(ctx, scene.clone(), options).unwrap();
    r.render().unwrap();
    r.read_frame().unwrap()
}

/// The split set at a reduced scale (the default model; `vct render` picks the scale from the
/// voxels' size on screen): the traced pixels trace a quarter of the set each, and a pass of its
/// own resolves each quarter over their neighbours before the upsampling. From inside the Cornell
/// box at 640×360 and 64³ a voxel spans four pixels or more, and the traced pixels of scale 2 lie
/// within half a voxel. Against the whole set at every pixel (`--quality high`) the split set
/// stays closer than the whole set traced at the same pixels and upsampled: a resolve that lost a
/// quarter would be a quarter off.
#[test]
fn the_split_set_resolved_over_traced_pixels_matches_the_whole_set() {
    let ctx = common::context();
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/cornell-inside.toml");
    let mut scene = Scene::load(&path).unwrap();
    scene.set_size(Some(640), Some(360)).unwrap();
    assert!(scene.settings.gi.split_cones);
    assert_eq!(vct::render::quality::auto_scale(&scene, 64), 2);
    let mut whole = scene.clone();
    whole.settings.gi.split_cones = false;
    let full = render(&ctx, &whole, 1);
    let split = difference(&render(&ctx, &scene, 2), &full, |_| true);
    let plain = difference(&render(&ctx, &whole, 2), &full, |_| true);
    println!(
        "gi-scale 2: split and resolved {split:.4} of the mean from the whole set, the whole set upsampled {plain:.4}"
    );
    assert!(split < 0.06, "split {split:.4} from the whole set at every pixel");
    assert!(split < plain, "the resolve gained nothing ({split:.4} against {plain:.4})");
    common::assert_clean(&ctx);
}

/// Pixels with a 4-neighbour whose camera distance differs by more than 10% (or that sees
/// nothing where it sees something), and their neighbours: the silhouettes' two sides.
fn edge_pixels(scene: &Scene) -> Vec<bool> {
    let tris: Vec<_> = (0..scene.mesh.triangle_count()).map(|t| scene.mesh.triangle(t)).collect();
    let bvh = Bvh::new(tris);
    let (w, h) = (SIZE as usize, SIZE as usize);
    let depth: Vec<f32> = (0..w * h)
        .map(|i| {
            let (o, d) = scene.camera.ray((i % w) as f32, (i / w) as f32);
            bvh.intersect(o, d, 0.0, f32::INFINITY, false).map_or(f32::INFINITY, |hit| hit.t)
        })
        .collect();
    let mut edge = vec![false; w * h];
    for y in 0..h {
        for x in 0..w {
            let a = depth[y * w + x];
            for (nx, ny) in [(x + 1, y), (x, y + 1)] {
                if nx >= w || ny >= h {
                    continue;
                }
                let b = depth[ny * w + nx];
                if (a - b).abs() > 0.1 * a.min(b) || a.is_finite() != b.is_finite() {
                    edge[y * w + x] = true;
                    edge[ny * w + nx] = true;
                }
            }
        }
    }
    edge
}

#[test]
fn reduced_resolution_diffuse_light_matches_full_resolution_and_keeps_silhouettes() {
    let ctx = common::context();
    let mut scene = Scene::embedded_default().unwrap();
    // The set unturned: what is judged is the upsampling. Turned by pixel (the default), full
    // resolution resolves nine turns at each pixel and the upsampling mixes the four traced
    // pixels' (10% of the mean apart at scale 2).
    scene.settings.gi.turn_cones = false;
    scene.set_size(Some(SIZE), Some(SIZE)).unwrap();
    let edges = edge_pixels(&scene);
    let count = edges.iter().filter(|&&e| e).count();
    assert!(count > 100, "the test view has silhouettes: {count} edge pixels");
    // Measured, 256², 64³, the diffuse view: 1.0% of the mean over the image and 3.0% beside
    // the silhouettes at scale 2, 2.7% and 3.9% at scale 4. Plain bilinear upsampling (the
    // surface test off) gives 4.2% and 15.9% at scale 2: light crossing the silhouettes.
    let full = render(&ctx, &scene, 1);
    for scale in [2, 4] {
        let reduced = render(&ctx, &scene, scale);
        let all = difference(&reduced, &full, |_| true);
        let at_edges = difference(&reduced, &full, |p| edges[p]);
        println!("gi-scale {scale}: mean |reduced - full| {all:.4} of the mean; beside silhouettes ({count} pixels) {at_edges:.4}");
        assert!(all < 0.05, "gi-scale {scale}: {all:.4}");
        assert!(at_edges < 0.06, "gi-scale {scale}: light crosses silhouettes: {at_edges:.4}");
    }
    common::assert_clean(&ctx);
}

#[test]
fn gi_scale_needs_deferred_tracing_and_takes_one_two_four_or_eight() {
    let ctx = common::context();
    let scene = Scene::embedded_default().unwrap();
    let forward = RenderOptions { gi_scale: 2, tracing: vct::render::Tracing::Forward, ..Default::default() };
    let e = Renderer::new(&ctx, scene.clone(), forward).err().expect("forward tracing at gi-scale 2");
    assert!(e.to_string().contains("gi-scale"), "{e}");
    for refused in [3, 16] {
        let o = RenderOptions { gi_scale: refused, ..Default::default() };
        let e = Renderer::new(&ctx, scene.clone(), o).err().unwrap_or_else(|| panic!("gi-scale {refused}"));
        assert!(e.to_string().contains("gi-scale"), "{e}");
    }
    let eight = RenderOptions { gi_scale: 8, gi_accumulate: true, ..Default::default() };
    Renderer::new(&ctx, scene, eight).expect("gi-scale 8, accumulated");
}

/// The specular cone traced with the diffuse cones (`reduced_specular`, the default at a GI
/// scale) on a glossy Cornell box: upsampled from one pixel in four it agrees with every pixel
/// tracing its own, and accumulated over a still view it becomes that; switched off, every pixel
/// traces its own again, exactly as at full resolution.
#[test]
fn the_specular_cone_at_the_gi_scale_agrees_with_per_pixel_tracing_and_converges_to_it() {
    let ctx = common::context();
    let mut scene = Scene::embedded_default().unwrap();
    scene.set_size(Some(128), Some(128)).unwrap();
    for m in &mut scene.materials {
        m.specular = glam::Vec3::splat(0.5);
        m.roughness = 0.3;
    }
    let timed = |options: RenderOptions, frames: usize| {
        let r = Renderer::new(&ctx, scene.clone(), options).unwrap();
        let mut timings = Vec::new();
        for _ in 0..frames {
            timings = r.render().unwrap();
        }
        (r.read_frame().unwrap(), timings)
    };
    let render = |options: RenderOptions, frames: usize| timed(options, frames).0;
    let base = RenderOptions { resolution: Some(32), view: View::Specular, ..Default::default() };
    let full = render(base, 1);
    let mean = full.hdr.chunks(4).map(|p| (p[0] + p[1] + p[2]) as f64).sum::<f64>() / (128.0 * 128.0 * 3.0);
    assert!(mean > 1e-3, "the glossy box reflects no indirect light: {mean}");
    let per_pixel = render(RenderOptions { gi_scale: 2, reduced_specular: false, ..base }, 1);
    let own = difference(&per_pixel, &full, |_| true);
    assert!(own < 1e-6, "per-pixel specular at gi-scale 2 differs from full resolution: {own}");
    let upsampled = render(RenderOptions { gi_scale: 2, ..base }, 1);
    let up = difference(&upsampled, &full, |_| true);
    let (accumulated, timings) = timed(RenderOptions { gi_scale: 2, gi_accumulate: true, ..base }, 8);
    // The shading pass's three dispatches are timed within it (the report, docs/report/README.md,
    // splits the viewer's frame by them).
    let ms = |pass: &str| timings.iter().find(|t| t.pass == pass).map(|t| t.ms).unwrap_or(f64::NAN);
    let parts = ["trace", "accumulate", "shade pixels"].map(ms);
    assert!(parts.iter().all(|&p| p > 0.0), "shading's dispatches untimed: {timings:?}");
    assert!(parts.iter().sum::<f64>() <= ms("shade") * 1.001, "shading's dispatches outside its span: {timings:?}");
    let acc = difference(&accumulated, &full, |_| true);
    println!(
        "specular view, gi-scale 2: per pixel {own:.2e}; upsampled {up:.4}; accumulated over 8 still frames {acc:.2e}"
    );
    // Measured (128², 32³, roughness 0.3): upsampled 5.9% of the mean, accumulated 3.5e-4 (the
    // history's 16-bit floats). A specular cone missing from the reduced pass gives 100%.
    assert!(up > 1e-4 && up < 0.1, "upsampled specular against per-pixel tracing: {up:.4}");
    assert!(acc < 1e-3, "accumulated specular did not converge to per-pixel tracing: {acc:.2e}");
    common::assert_clean(&ctx);
}
