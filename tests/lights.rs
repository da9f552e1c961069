//! Several lights per scene (up to MAX_LIGHTS, each with its own shadow-map layers, all
//! injected into one radiance volume and shaded in one pass): the image of a set of lights is
//! the sum of the images of its parts. In direct light exactly (to float rounding), and with
//! global illumination too, to half-float rounding, where the radiance model is linear in the
//! light (isotropic filter, no facing moment): injection lights the voxels each light's own
//! texels find, at each light's own stride. The default model keeps, per texel, one mean
//! direction of the light it reflects (the facing moment) and one lit side per voxel: a
//! direction is not a sum, so there two lights differ from the sum of each alone by a few
//! tenths of a percent (docs/design/injection.md).

mod common;

use glam::Vec3;
use vct::render::{FrameImages, RenderOptions, Renderer, View};
use vct::scene::file::Filter;
use vct::scene::{Light, Scene};

fn render(ctx: &std::sync::Arc<vct::gpu::Context>, lights: &[Light], view: View) -> FrameImages {
    render_with(ctx, lights, view, false)
}

/// `linear`: the isotropic filter without the facing moment.
fn render_with(ctx: &std::sync::Arc<vct::gpu::Context>, lights: &[Light], view: View, linear: bool) -> FrameImages {
    let mut scene = Scene::embedded_default().unwrap();
    scene.set_size(Some(96), Some(96)).unwrap();
    scene.lights = lights.to_vec();
    if linear {
        scene.settings.gi.filter = Filter::Iso;
        scene.settings.gi.facing = false;
    }
    let options = RenderOptions { resolution: Some(32), view, ..Default::default() };
    let r = Renderer::new(ctx, scene, options).unwrap();
    r.render().unwrap();
    r.read_frame().unwrap()
}

/// Mean absolute difference between `whole` and the sum of `parts`, over the mean of `whole`;
/// and the largest difference of one pixel channel over the mean.
fn sum_error(whole: &FrameImages, parts: &[FrameImages]) -> (f64, f64) {
    let (mut diff, mut total, mut worst) = (0.0f64, 0.0f64, 0.0f64);
    for i in 0..whole.hdr.len() {
        if i % 4 == 3 {
            continue;
        }
        let sum: f64 = parts.iter().map(|p| p.hdr[i] as f64).sum();
        let d = (whole.hdr[i] as f64 - sum).abs();
        diff += d;
        worst = worst.max(d);
        total += whole.hdr[i] as f64;
    }
    let mean = total / (whole.hdr.len() as f64 * 0.75);
    (diff / total, worst / mean)
}

fn spot(position: Vec3, intensity: Vec3) -> Light {
    Light::Spot { position, direction: -Vec3::Y, intensity, inner_deg: 40.0, outer_deg: 55.0 }
}

#[test]
fn two_lights_give_the_sum_of_each_alone() {
    let ctx = common::context();
    let a = Light::Point { position: Vec3::new(0.5, 3.5, 0.5), intensity: Vec3::splat(30.0) };
    let b = spot(Vec3::new(-1.0, 5.45, -0.5), Vec3::new(100.0, 60.0, 30.0));
    // Measured: direct 6e-9; linear GI 1.5e-5 (worst pixel 4e-4); default GI 3.7e-3.
    for (view, linear, bound) in [(View::Direct, false, 1e-5), (View::Full, true, 1e-4), (View::Full, false, 0.01)] {
        let both = render_with(&ctx, &[a, b], view, linear);
        let parts = [render_with(&ctx, &[a], view, linear), render_with(&ctx, &[b], view, linear)];
        let (mean, worst) = sum_error(&both, &parts);
        println!(
            "{view:?} (linear model {linear}): mean |both - (a + b)| {mean:.2e} of the mean, worst pixel {worst:.2e}"
        );
        assert!(mean < bound, "{view:?}: the two lights' image is not the sum of each alone: {mean:.2e}");
    }
    common::assert_clean(&ctx);
}

#[test]
fn eight_lights_render_as_the_sum_of_two_groups_of_four() {
    let ctx = common::context();
    let lights: Vec<Light> = (0..8)
        .map(|i| {
            let x = -2.0 + 0.55 * i as f32;
            let colour = Vec3::new(1.0 + i as f32, 8.0 - i as f32, 4.0) * 2.0;
            match i % 3 {
                0 => Light::Point { position: Vec3::new(x, 4.5, 1.0), intensity: colour },
                1 => spot(Vec3::new(x, 5.4, 0.0), colour * 3.0),
                _ => Light::Directional {
                    direction: Vec3::new(0.2 * x, -1.0, -0.3).normalize(),
                    irradiance: colour * 0.05,
                },
            }
        })
        .collect();
    let all = render(&ctx, &lights, View::Direct);
    let parts = [render(&ctx, &lights[..4], View::Direct), render(&ctx, &lights[4..], View::Direct)];
    let (mean, worst) = sum_error(&all, &parts);
    println!("eight lights: mean |all - (first four + last four)| {mean:.2e} of the mean, worst {worst:.2e}");
    assert!(mean < 1e-5, "{mean:.2e}");
    common::assert_clean(&ctx);
}
