//! The default scene's direct-light frame, checked against analytic values and CPU ray casts, plus
//! determinism. Runs on lavapipe with validation on.

mod common;

use glam::Vec3;
use vct::render::{FrameImages, RenderOptions, Renderer, View};
use vct::scene::{Light, Scene};

/// The direct-light frame (no cone tracing), small grid.
fn direct_only() -> RenderOptions {
    RenderOptions { view: View::Direct, gi: false, resolution: Some(32), ..Default::default() }
}

fn render_default() -> (Scene, FrameImages, std::sync::Arc<vct::gpu::Context>) {
    let ctx = common::context();
    let scene = Scene::embedded_default().unwrap();
    let renderer = Renderer::new(&ctx, scene.clone(), direct_only()).unwrap();
    let timings = renderer.render().unwrap();
    assert!(timings.iter().any(|t| t.pass == "shade"), "per-pass timings are reported");
    let frame = renderer.read_frame().unwrap();
    drop(renderer);
    common::assert_clean(&ctx);
    (scene, frame, ctx)
}

/// Reflected radiance of a Lambertian point lit by the spot light, from first principles.
fn analytic_radiance(scene: &Scene, p: Vec3, n: Vec3, albedo: Vec3) -> Vec3 {
    let Light::Spot { position, direction, intensity, inner_deg, outer_deg } = scene.lights[0] else {
        panic!("default scene has a spot light")
    };
    let to_light = position - p;
    let d2 = to_light.length_squared();
    let l = to_light.normalize();
    let angle = (-l).dot(direction).clamp(-1.0, 1.0).acos().to_degrees();
    let f = Light::spot_falloff(angle, inner_deg, outer_deg);
    albedo / std::f32::consts::PI * intensity * f * n.dot(l).max(0.0) / d2
}

fn lit(scene: &Scene, p: Vec3) -> bool {
    let Light::Spot { position, .. } = scene.lights[0] else { unreachable!() };
    let d = position - p;
    common::raycast(scene, p, d.normalize(), d.length() - 1e-3).is_none()
}

#[test]
fn default_scene_has_light_shadows_and_coloured_walls() {
    let (scene, frame, _ctx) = render_default();
    let (w, h) = (frame.width, frame.height);

    // Lit pixels exist and the image is not saturated everywhere.
    let lit_pixels = (0..w * h).filter(|i| frame.ldr[*i as usize * 4..][..3].iter().any(|&c| c > 40)).count();
    assert!(lit_pixels > (w * h / 4) as usize, "only {lit_pixels} lit pixels");

    // Floor pixels, classified by a CPU shadow ray towards the light.
    let (mut shadowed, mut lit_floor) = (Vec::new(), Vec::new());
    for y in (0..h).step_by(2) {
        for x in (0..w).step_by(2) {
            let (o, d) = scene.camera.ray(x as f32, y as f32);
            let Some((t, tri)) = common::raycast(&scene, o, d, 1e9) else { continue };
            let [a, b, c] = scene.mesh.triangle(tri);
            let n = (b - a).cross(c - a).normalize();
            let p = o + d * t;
            if n.y.abs() < 0.99 || p.y.abs() > 1e-3 {
                continue;
            }
            // Stay away from shadow edges (PCF softens a few texels).
            let around = [Vec3::X, -Vec3::X, Vec3::Z, -Vec3::Z].map(|o| lit(&scene, p + o * 0.08));
            let l = common::hdr(&frame, x, y).length();
            if lit(&scene, p) && around.iter().all(|&v| v) {
                lit_floor.push(l);
            } else if !lit(&scene, p) && around.iter().all(|&v| !v) {
                shadowed.push(l);
            }
        }
    }
    assert!(
        shadowed.len() > 20 && lit_floor.len() > 100,
        "{} shadowed, {} lit floor pixels",
        shadowed.len(),
        lit_floor.len()
    );
    let max_shadowed = shadowed.iter().cloned().fold(0.0, f32::max);
    let min_lit = lit_floor.iter().cloned().fold(f32::INFINITY, f32::min);
    assert!(max_shadowed < 0.05 * min_lit, "shadowed floor {max_shadowed} vs lit floor {min_lit}");

    // Left wall red, right wall green (sampled at mid height, mid depth).
    let (lx, ly) = common::pixel_of(&scene, Vec3::new(-2.75, 2.0, 0.0));
    let (rx, ry) = common::pixel_of(&scene, Vec3::new(2.75, 2.0, 0.0));
    let [r, g, b] = common::ldr(&frame, lx, ly);
    assert!(r > 2 * g.max(b) && r > 60, "left wall is not red: {:?}", [r, g, b]);
    let [r, g, b] = common::ldr(&frame, rx, ry);
    assert!(g > r.max(b) + 40, "right wall is not green: {:?}", [r, g, b]);
}

#[test]
fn direct_light_matches_analytic_values() {
    let (scene, frame, _ctx) = render_default();
    let white = Vec3::splat(0.73);
    let red = Vec3::new(0.65, 0.05, 0.05);
    // Floor points in full spot intensity; a left-wall point in the linear falloff zone.
    let points = [
        (Vec3::new(-2.3, 0.0, 1.2), Vec3::Y, white),
        (Vec3::new(-2.2, 0.0, 2.3), Vec3::Y, white),
        (Vec3::new(-1.0, 0.0, 2.5), Vec3::Y, white),
        (Vec3::new(-2.75, 3.6, 1.0), Vec3::X, red),
        (Vec3::new(-2.75, 1.0, 1.6), Vec3::X, red),
    ];
    check_points(&scene, &frame, &points, |q| lit(&scene, q), |q, n, albedo| analytic_radiance(&scene, q, n, albedo));
}

/// At each (point, normal, albedo): the pixel that sees the point must see it (within 0.1 m),
/// the exact point it sees must be `lit`, and its radiance must be `expected` within 3%.
fn check_points(
    scene: &Scene,
    frame: &FrameImages,
    points: &[(Vec3, Vec3, Vec3)],
    lit: impl Fn(Vec3) -> bool,
    expected: impl Fn(Vec3, Vec3, Vec3) -> Vec3,
) {
    for &(p, n, albedo) in points {
        let (x, y) = common::pixel_of(scene, p);
        // Recompute the exact point the pixel centre sees.
        let (o, d) = scene.camera.ray(x as f32, y as f32);
        let (t, _) = common::raycast(scene, o, d, 1e9).expect("pixel sees the scene");
        let q = o + d * t;
        assert!((q - p).length() < 0.1, "pixel ({x},{y}) sees {q}, not {p}");
        assert!(lit(q), "{q} should see the light");
        let expected = expected(q, n, albedo);
        let got = common::hdr(frame, x, y);
        let err = ((got - expected).length() / expected.length()).abs();
        println!("{q}: GPU {got}, analytic {expected}, rel. error {err:.4}");
        assert!(err < 0.03, "at {q} (pixel {x},{y}): GPU {got}, analytic {expected}, rel. error {err:.4}");
    }
}

#[test]
fn rendering_is_deterministic() {
    let ctx = common::context();
    let renderer = Renderer::new(&ctx, Scene::embedded_default().unwrap(), direct_only()).unwrap();
    renderer.render().unwrap();
    let a = renderer.read_frame().unwrap();
    renderer.render().unwrap();
    let b = renderer.read_frame().unwrap();
    assert!(a.hdr == b.hdr && a.ldr == b.ldr, "two renders of the same scene differ");
    drop(renderer);
    common::assert_clean(&ctx);
}

/// A point light (cube shadow map, six faces) in the Cornell box: direct light on the floor, the
/// ceiling, three walls (five different faces of the cube) against Kd/π · I · cos / d², and a
/// floor point the tall box hides from it in shadow.
#[test]
fn point_light_matches_analytic_values_on_every_face() {
    let ctx = common::context();
    let mut scene = Scene::embedded_default().unwrap();
    let (position, intensity) = (Vec3::new(0.5, 3.5, 0.5), Vec3::splat(30.0));
    scene.lights = vec![Light::Point { position, intensity }];
    let renderer = Renderer::new(&ctx, scene.clone(), direct_only()).unwrap();
    renderer.render().unwrap();
    let frame = renderer.read_frame().unwrap();
    drop(renderer);
    common::assert_clean(&ctx);
    let sees_light = |p: Vec3| {
        let d = position - p;
        common::raycast(&scene, p, d.normalize(), d.length() - 1e-3).is_none()
    };
    let white = Vec3::splat(0.73);
    let points = [
        (Vec3::new(-2.0, 0.0, 2.0), Vec3::Y, white),
        (Vec3::new(-1.5, 5.5, 1.5), -Vec3::Y, white),
        (Vec3::new(-2.75, 2.5, 1.5), Vec3::X, Vec3::new(0.65, 0.05, 0.05)),
        (Vec3::new(2.75, 3.0, 1.0), -Vec3::X, Vec3::new(0.12, 0.45, 0.15)),
        (Vec3::new(0.0, 4.0, -2.75), Vec3::Z, white),
    ];
    let expected = |q: Vec3, n: Vec3, albedo: Vec3| {
        let to = position - q;
        albedo / std::f32::consts::PI * intensity * n.dot(to.normalize()).max(0.0) / to.length_squared()
    };
    check_points(&scene, &frame, &points, sees_light, expected);
    // Behind the tall box, seen from the light: dark.
    let hidden = (0..frame.height)
        .flat_map(|y| (0..frame.width).map(move |x| (x, y)))
        .filter_map(|(x, y)| {
            let (o, d) = scene.camera.ray(x as f32, y as f32);
            let (t, tri) = common::raycast(&scene, o, d, 1e9)?;
            let [a, b, c] = scene.mesh.triangle(tri);
            let q = o + d * t;
            let hidden = (b - a).cross(c - a).normalize().y.abs() > 0.99
                && q.y.abs() < 1e-3
                && [Vec3::ZERO, Vec3::X * 0.1, -Vec3::X * 0.1, Vec3::Z * 0.1, -Vec3::Z * 0.1]
                    .iter()
                    .all(|&o| !sees_light(q + o));
            hidden.then(|| common::hdr(&frame, x, y).length())
        })
        .collect::<Vec<_>>();
    assert!(hidden.len() > 20, "{} hidden floor pixels", hidden.len());
    let brightest = hidden.iter().cloned().fold(0.0, f32::max);
    assert!(brightest < 0.01, "a floor pixel hidden from the point light has radiance {brightest}");
}
