//! Frames in flight without a window: frames submitted through a `gpu::FrameRing` of two slots
//! (`Renderer::submit_in_flight`, `vct render --in-flight 2`), each recorded while the one before
//! still runs, give the image of frames waited for one by one, while the camera moves every frame
//! and the screen-space accumulation reads each frame's history from the frame before.
//! Synchronization validation, with its check between submissions, finds no hazard. Lavapipe.

mod common;

use common::difference;
use vct::gpu::{ContextOptions, FrameRing};
use vct::render::{RenderOptions, Renderer};
use vct::scene::Scene;

#[test]
fn two_headless_frames_in_flight_match_frames_waited_for() {
    // The layer checks between submissions only when asked (Vulkan SDK 1.3.239: an alpha check).
    std::env::set_var("VK_LAYER_ENABLES", "VALIDATION_CHECK_ENABLE_SYNCHRONIZATION_VALIDATION_QUEUE_SUBMIT");
    let ctx = common::context_with(ContextOptions { validation: true, sync_validation: true, ..Default::default() });
    let mut scene = Scene::embedded_default().unwrap();
    scene.set_size(Some(96), Some(96)).unwrap();
    let options = RenderOptions {
        resolution: Some(32),
        gi_scale: 2,
        gi_accumulate: true,
        reuse_volume: true,
        ..Default::default()
    };
    let mut waited = Renderer::new(&ctx, scene.clone(), options).unwrap();
    let mut flying = Renderer::new(&ctx, scene, options).unwrap();
    let mut ring = FrameRing::new(&ctx, 2).unwrap();
    assert!(FrameRing::new(&ctx, 3).is_err(), "more slots than the renderer's per-frame copies");
    let mut timed = 0;
    for frame in 0..8 {
        // The camera moves while the frame before may still read the uniforms.
        let step = glam::Vec3::new(0.02 * frame as f32, 0.0, 0.0);
        waited.scene.camera.eye += step;
        flying.scene.camera.eye += step;
        waited.render().unwrap();
        timed += flying.submit_in_flight(&mut ring).unwrap().len().min(1);
    }
    ring.wait_idle().unwrap();
    // Every frame but the first two returned the GPU times of the frame two before it, the one
    // whose slot it waited for.
    assert_eq!(timed, 6);
    let (a, b) = (waited.read_frame().unwrap(), flying.read_frame().unwrap());
    let d = difference(&a, &b, |_| true);
    println!("two in flight against each waited for, after 8 moving frames: {d:.2e}");
    assert!(d < 1e-4, "frames in flight render differently: {d}");
    // The accumulation's history mattered: a renderer's first frame from the same camera differs.
    let mut fresh_scene = Scene::embedded_default().unwrap();
    fresh_scene.set_size(Some(96), Some(96)).unwrap();
    fresh_scene.camera = flying.scene.camera;
    let fresh = Renderer::new(&ctx, fresh_scene, options).unwrap();
    fresh.render().unwrap();
    assert!(difference(&b, &fresh.read_frame().unwrap(), |_| true) > 1e-4, "no history was used");
    common::assert_clean(&ctx);
}
