//! The viewer keeps last frame's volume when nothing it depends on changed
//! (`RenderOptions::reuse_volume`). A still frame then runs no volume pass and no trace and
//! shows the same image; turning the light builds the volume again from the voxels it kept, and
//! the frame matches a renderer that builds every frame. Lavapipe, validation on.

mod common;

use common::difference;
use vct::render::{RenderOptions, Renderer};
use vct::scene::Scene;

fn passes(r: &Renderer) -> Vec<String> {
    r.render().unwrap().into_iter().map(|t| t.pass).collect()
}

#[test]
fn a_kept_volume_skips_its_passes_and_a_turned_light_builds_it_again() {
    let ctx = common::context();
    let mut scene = Scene::embedded_default().unwrap();
    scene.set_size(Some(96), Some(96)).unwrap();
    let options = RenderOptions { resolution: Some(32), reuse_volume: true, ..Default::default() };
    let mut r = Renderer::new(&ctx, scene.clone(), options).unwrap();
    let volume = ["voxelize", "shadow map", "inject", "filter"];
    let first = passes(&r);
    assert!(volume.iter().all(|p| first.iter().any(|q| q == p)), "{first:?}");
    let built = r.read_frame().unwrap();
    // The first frame's flag in the uniforms changes once: the second frame builds it too.
    passes(&r);
    let kept = passes(&r);
    assert!(volume.iter().all(|p| !kept.iter().any(|q| q == p)), "a still frame rebuilt the volume: {kept:?}");
    // The traced light is kept too: the split set's partial gathers are what tracing would write.
    assert!(first.iter().any(|q| q == "trace") && !kept.iter().any(|q| q == "trace"), "{first:?} {kept:?}");
    let still = r.read_frame().unwrap();
    let same = difference(&still, &built, |_| true);
    assert!(same < 1e-6, "the kept volume shades differently: {same}");
    // Moving the camera keeps the volume (a rasterizing voxelizer does not see the camera).
    r.scene.camera.eye += glam::Vec3::new(0.1, 0.0, 0.0);
    let moved = passes(&r);
    assert!(!moved.iter().any(|q| q == "voxelize"), "{moved:?}");
    assert!(moved.iter().any(|q| q == "trace"), "the camera moved and nothing was traced: {moved:?}");
    // Turning the light builds it again, as a renderer that builds every frame does, from the
    // voxels it kept: a light does not change them.
    let light = r.scene.lights.first_mut().unwrap();
    vct::viewer::camera::swing_light(light, 0.3, 0.1);
    let turned = passes(&r);
    assert!(turned.iter().any(|q| q == "inject"), "the light turned and nothing was injected: {turned:?}");
    assert!(!turned.iter().any(|q| q == "voxelize"), "the light turned and the voxels were rebuilt: {turned:?}");
    let reused = r.read_frame().unwrap();
    let mut fresh_scene = scene;
    fresh_scene.camera = r.scene.camera;
    fresh_scene.lights = r.scene.lights.clone();
    let fresh = Renderer::new(&ctx, fresh_scene, RenderOptions { reuse_volume: false, ..options }).unwrap();
    fresh.render().unwrap();
    let rebuilt = difference(&reused, &fresh.read_frame().unwrap(), |_| true);
    println!("kept volume against the first frame {same:.2e}; after the light turned, against a fresh renderer {rebuilt:.2e}");
    assert!(rebuilt < 1e-4, "after the light turned the image is not a fresh renderer's: {rebuilt}");
    assert!(difference(&reused, &still, |_| true) > 0.01, "turning the light changed nothing");
    common::assert_clean(&ctx);
}
