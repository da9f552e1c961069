//! The CPU path tracer is the ground truth, so it is checked against analytic cases — a lit plane,
//! the white furnace, the spot-lit Cornell floor — and `vct compare` of an image with itself gives
//! FLIP 0.

mod common;

use glam::Vec3;
use vct::reference::pathtrace::{PathTracer, RefOptions};
use vct::scene::{Camera, Light, Scene};

fn trace(scene: &Scene, bounces: u32, spp: u32) -> vct::reference::pathtrace::RefImage {
    PathTracer::new(scene).render(RefOptions { bounces, spp, seed: 7, ..Default::default() }, &|_| {})
}

fn camera(eye: Vec3, target: Vec3, size: u32) -> Camera {
    Camera {
        eye,
        target,
        up: if (target - eye).normalize().y.abs() > 0.99 { Vec3::Z } else { Vec3::Y },
        fov_y_deg: 50.0,
        width: size,
        height: size,
    }
}

#[test]
fn lit_plane_has_the_analytic_radiance() {
    let q = [
        Vec3::new(-10.0, 0.0, -10.0),
        Vec3::new(10.0, 0.0, -10.0),
        Vec3::new(10.0, 0.0, 10.0),
        Vec3::new(-10.0, 0.0, 10.0),
    ];
    let mut scene = Scene::from_triangles(&[([q[0], q[2], q[1]], 0), ([q[0], q[3], q[2]], 0)], &[Vec3::splat(0.5)]);
    scene.lights = vec![Light::Directional {
        direction: Vec3::new(0.3, -1.0, 0.2).normalize(),
        irradiance: Vec3::new(2.0, 1.0, 0.5),
    }];
    scene.camera = camera(Vec3::new(0.0, 3.0, 0.5), Vec3::ZERO, 16);
    let cos = Vec3::new(0.3, -1.0, 0.2).normalize().y.abs();
    let want = Vec3::splat(0.5) / std::f32::consts::PI * Vec3::new(2.0, 1.0, 0.5) * cos;
    for bounces in [0, 1, 3] {
        let img = trace(&scene, bounces, 4);
        for p in &img.radiance {
            assert!(
                (*p - want).abs().max_element() < 1e-4 * want.max_element(),
                "{p} vs {want} with {bounces} bounce(s)"
            );
        }
    }
}

/// A closed box, every face white (albedo `rho`) and emitting `le`, seen from inside.
fn furnace(rho: f32) -> Scene {
    let tris = common::box_triangles(Vec3::splat(-1.0), Vec3::splat(1.0));
    let mut scene = Scene::from_triangles(&tris, &[Vec3::splat(rho)]);
    scene.materials[0].emissive = Vec3::ONE;
    scene.lights.clear();
    scene.camera = camera(Vec3::new(0.1, 0.2, 0.3), Vec3::new(0.5, -0.4, -0.9), 12);
    scene
}

#[test]
fn white_furnace_converges_to_the_geometric_series() {
    let rho = 0.5f32;
    let scene = furnace(rho);
    for bounces in [0u32, 1, 2, 8, 30] {
        // Every path sees emission 1 at each of its bounces + 1 vertices, scaled by rho^k.
        let want = (1.0 - rho.powi(bounces as i32 + 1)) / (1.0 - rho);
        // Light sampling with multiple importance makes each path's estimate noisy (BSDF
        // sampling alone would give every path exactly `want`), so the image mean is held to
        // the noise of 9216 paths and each pixel to that of 64.
        let img = trace(&scene, bounces, 64);
        let mean = img.radiance.iter().map(|p| p.x).sum::<f32>() / img.radiance.len() as f32;
        println!("{bounces} bounces: mean {mean} vs {want}");
        assert!((mean - want).abs() < 0.01 * want, "{bounces} bounces: mean {mean} vs {want}");
        for p in &img.radiance {
            assert!((p.x - want).abs() < 0.08 * want && (p.x - p.z).abs() < 1e-4, "{bounces} bounces: {p} vs {want}");
        }
    }
}

#[test]
fn spot_lit_cornell_floor_matches_the_analytic_direct_light() {
    let scene = Scene::embedded_default().unwrap();
    let Light::Spot { position, direction, intensity, inner_deg, outer_deg } = scene.lights[0] else { panic!() };
    check_floor(&scene, |p| {
        let to = position - p;
        let l = to.normalize();
        let angle = (-l).dot(direction).acos().to_degrees();
        intensity * Light::spot_falloff(angle, inner_deg, outer_deg) * l.y / to.length_squared()
    });
}

/// Traces `scene`'s direct light and checks the floor left of the boxes, in front of
/// everything (lit by the lights used here), against albedo/π times `irradiance(p)`, to 10⁻³.
fn check_floor(scene: &Scene, irradiance: impl Fn(Vec3) -> Vec3) {
    let img = trace(scene, 0, 1);
    let mut checked = 0;
    for y in (0..scene.camera.height).step_by(3) {
        for x in (0..scene.camera.width).step_by(3) {
            let (o, d) = scene.camera.ray(x as f32, y as f32);
            let t = -o.y / d.y;
            let p = o + d * t;
            if d.y >= 0.0 || !(-2.7..=-0.5).contains(&p.x) || !(1.2..=2.7).contains(&p.z) {
                continue;
            }
            let want = Vec3::splat(0.73) / std::f32::consts::PI * irradiance(p);
            let got = img.radiance[(y * scene.camera.width + x) as usize];
            assert!((got - want).length() < 1e-3 * want.length(), "pixel ({x},{y}) at {p}: {got} vs {want}");
            checked += 1;
        }
    }
    assert!(checked > 20, "only {checked} floor pixels checked");
}

#[test]
fn compare_of_an_image_with_itself_is_zero() {
    let dir = std::env::temp_dir().join(format!("vct-compare-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene = Scene::embedded_default().unwrap();
    let mut small = scene.clone();
    small.camera.width = 64;
    small.camera.height = 64;
    let img = trace(&small, 1, 4);
    let frame = vct::render::FrameImages::from_linear(64, 64, &img.radiance);
    let (png, exr) = (dir.join("a.png"), dir.join("a.exr"));
    vct::output::write_png(&png, &frame).unwrap();
    vct::output::write_exr(&exr, &frame).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_vct"))
        .args([
            "compare",
            exr.to_str().unwrap(),
            exr.to_str().unwrap(),
            "--out",
            dir.join("flip.png").to_str().unwrap(),
        ])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{text}{}", String::from_utf8_lossy(&out.stderr));
    assert!(
        text.contains("FLIP (tone-mapped): 0.00000") && text.contains("RMSE (linear radiance): 0.000000"),
        "{text}"
    );
    // And a different image is not zero.
    let (f, _) = vct::reference::metrics::flip(&frame.rgb8(), &vec![0u8; 64 * 64 * 3], 64, 64);
    assert!(f > 0.1, "FLIP against black: {f}");
}

#[test]
fn point_lit_cornell_floor_matches_the_analytic_direct_light() {
    let mut scene = Scene::embedded_default().unwrap();
    let (position, intensity) = (Vec3::new(-1.0, 4.0, 1.5), Vec3::splat(20.0));
    scene.lights = vec![Light::Point { position, intensity }];
    check_floor(&scene, |p| {
        let to = position - p;
        intensity * to.normalize().y / to.length_squared()
    });
}
