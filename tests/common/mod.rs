//! Shared test helpers: a validated Vulkan context, a CPU ray caster over a scene's triangles
//! (brute force, independent of the GPU code), pixel accessors, and small test geometry.
#![allow(dead_code)]

use std::sync::Arc;

use glam::Vec3;
use vct::gpu::{Context, ContextOptions};
use vct::render::FrameImages;
use vct::scene::Scene;

/// A context with the validation layer on (every test asks for it).
pub fn context() -> Arc<Context> {
    context_with(ContextOptions { validation: true, ..Default::default() })
}

/// A context with these options (validation on or off as they say).
pub fn context_with(options: ContextOptions) -> Arc<Context> {
    std::env::set_var("XDG_RUNTIME_DIR", std::env::var("XDG_RUNTIME_DIR").unwrap_or("/tmp".into()));
    // Validation messages go through `log`: show them with the failing test's output.
    let _ = env_logger::builder().is_test(true).filter_level(log::LevelFilter::Warn).try_init();
    Context::new(&options).expect("Vulkan context")
}

/// Fails the test if the validation layer said anything.
pub fn assert_clean(ctx: &Context) {
    assert_eq!(ctx.validation.errors(), 0, "validation errors (see log)");
    assert_eq!(ctx.validation.warnings(), 0, "validation warnings (see log)");
}

/// Closest hit of a ray against the scene's triangles (Möller–Trumbore): (t, triangle).
pub fn raycast(scene: &Scene, o: Vec3, d: Vec3, t_max: f32) -> Option<(f32, usize)> {
    let mut best: Option<(f32, usize)> = None;
    for tri in 0..scene.mesh.triangle_count() {
        let [a, b, c] = scene.mesh.triangle(tri);
        let (e1, e2) = (b - a, c - a);
        let p = d.cross(e2);
        let det = e1.dot(p);
        if det.abs() < 1e-9 {
            continue;
        }
        let inv = 1.0 / det;
        let s = o - a;
        let u = s.dot(p) * inv;
        if !(0.0..=1.0).contains(&u) {
            continue;
        }
        let q = s.cross(e1);
        let v = d.dot(q) * inv;
        if v < 0.0 || u + v > 1.0 {
            continue;
        }
        let t = e2.dot(q) * inv;
        if t > 1e-4 && t < t_max && best.is_none_or(|(bt, _)| t < bt) {
            best = Some((t, tri));
        }
    }
    best
}

pub fn hdr(frame: &FrameImages, x: u32, y: u32) -> Vec3 {
    let i = ((y * frame.width + x) * 4) as usize;
    Vec3::new(frame.hdr[i], frame.hdr[i + 1], frame.hdr[i + 2])
}

/// Mean |a - b| over the mean of `b` (RGB, linear), over the pixels `keep` selects.
pub fn difference(a: &FrameImages, b: &FrameImages, keep: impl Fn(usize) -> bool) -> f64 {
    let (mut diff, mut total) = (0.0f64, 0.0f64);
    for p in (0..(a.width * a.height) as usize).filter(|&p| keep(p)) {
        for c in 0..3 {
            diff += (a.hdr[4 * p + c] - b.hdr[4 * p + c]).abs() as f64;
            total += b.hdr[4 * p + c] as f64;
        }
    }
    diff / total.max(1e-12)
}

pub fn ldr(frame: &FrameImages, x: u32, y: u32) -> [u8; 3] {
    let i = ((y * frame.width + x) * 4) as usize;
    [frame.ldr[i], frame.ldr[i + 1], frame.ldr[i + 2]]
}

/// Pixel whose centre ray comes nearest to the world point `p` (pinhole projection).
pub fn pixel_of(scene: &Scene, p: Vec3) -> (u32, u32) {
    let c = &scene.camera;
    let f = (c.target - c.eye).normalize();
    let r = f.cross(c.up).normalize();
    let u = r.cross(f);
    let d = p - c.eye;
    let t = (c.fov_y_deg.to_radians() * 0.5).tan();
    let aspect = c.width as f32 / c.height as f32;
    let sx = d.dot(r) / d.dot(f) / (t * aspect);
    let sy = d.dot(u) / d.dot(f) / t;
    let x = ((sx + 1.0) * 0.5 * c.width as f32 - 0.5).round();
    let y = ((1.0 - sy) * 0.5 * c.height as f32 - 0.5).round();
    (x as u32, y as u32)
}

/// The twelve triangles (material 0) of the box from `min` to `max`, each face wound the same
/// way round.
pub fn box_triangles(min: Vec3, max: Vec3) -> Vec<([Vec3; 3], usize)> {
    let (a, b) = (min, max);
    let v = [
        Vec3::new(a.x, a.y, a.z),
        Vec3::new(b.x, a.y, a.z),
        Vec3::new(b.x, b.y, a.z),
        Vec3::new(a.x, b.y, a.z),
        Vec3::new(a.x, a.y, b.z),
        Vec3::new(b.x, a.y, b.z),
        Vec3::new(b.x, b.y, b.z),
        Vec3::new(a.x, b.y, b.z),
    ];
    let faces = [[0, 1, 2, 3], [4, 7, 6, 5], [0, 4, 5, 1], [3, 2, 6, 7], [0, 3, 7, 4], [1, 5, 6, 2]];
    faces.iter().flat_map(|f| [([v[f[0]], v[f[1]], v[f[2]]], 0), ([v[f[0]], v[f[2]], v[f[3]]], 0)]).collect()
}

/// A horizontal square of half side `half` at height `y`, its normal up or down.
pub fn horizontal_square(y: f32, half: f32, up: bool) -> [[Vec3; 3]; 2] {
    let s = half;
    let q = [Vec3::new(-s, y, -s), Vec3::new(s, y, -s), Vec3::new(s, y, s), Vec3::new(-s, y, s)];
    if up {
        [[q[0], q[2], q[1]], [q[0], q[3], q[2]]]
    } else {
        [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]
    }
}

/// A long, low hall open to the sky: a floor 8 m along x and 2 m deep, a back wall 1.2 m high
/// and three boxes, one slanted. Lit by the default sun, which reaches the floor and the boxes'
/// tops and bounces light onto the wall.
pub fn hall() -> Scene {
    let mut tris = box_triangles(Vec3::new(-4.0, -0.1, -1.0), Vec3::new(4.0, 0.0, 1.0));
    let wall = box_triangles(Vec3::new(-4.0, 0.0, -1.0), Vec3::new(4.0, 1.2, -0.9));
    tris.extend(wall.into_iter().map(|(t, _)| (t, 1)));
    for (x, h) in [(-2.5f32, 0.6f32), (0.0, 0.9), (2.5, 0.4)] {
        tris.extend(box_triangles(Vec3::new(x - 0.3, 0.0, -0.4), Vec3::new(x + 0.3, h, 0.2)));
    }
    // A slanted panel: its voxels cross layers within a pixel column.
    let p = [Vec3::new(-1.2, 0.05, 0.5), Vec3::new(-0.4, 0.7, 0.3), Vec3::new(-0.3, 0.1, 0.8)];
    tris.push((p, 2));
    Scene::from_triangles(&tris, &[Vec3::splat(0.75), Vec3::new(0.8, 0.3, 0.2), Vec3::new(0.2, 0.7, 0.3)])
}
