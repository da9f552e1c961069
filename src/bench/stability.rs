//! `vct bench --stability`: where each method fails, measured with its fix off and on.
//! 1. tessellation limit — recall against triangle size, with and without subdivision;
//! 2. raster cracks — recall against viewport scale (fragments sparser than voxels), with and
//!    without MSAA, and recall against triangle size for sub-voxel triangles;
//! 3. light leaking — radiance in a dark room behind a wall thinner than a voxel, with the
//!    thesis' isotropic filtering and with anisotropic voxels (the fix);
//! 5. self-illumination — indirect light a lone lit plane gives itself, against the cone offset.
//!
//! 4. temporal flicker — mean frame-to-frame change of a still view while the voxel volume
//!    slides (following a camera) or the light moves, with and without grid snapping and
//!    temporal filtering.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::Vec3;
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};

use super::charts::{self, Regime, Series};
use super::hostile::HostileRow;
use crate::error::{Error, Result};
use crate::gpu::Context;
use crate::reference::coverage::{Accuracy, RefGrid};
use crate::render::{ClipOptions, Follow, RenderOptions, Renderer, View};
use crate::scene::file::{Filter, GiFile};
use crate::scene::{Camera, Light, Scene};
use crate::voxel::headless::voxelize_in;
use crate::voxel::{Coverage, VoxelGrid, VoxelizeMethod, DEFAULT_LEVEL_SCALE, DEFAULT_NEIGHBOURS};

/// Recall, precision and IoU of `method` on `scene` in `grid` against the exact coverage.
pub fn voxel_accuracy(ctx: &Arc<Context>, scene: &Scene, method: VoxelizeMethod, grid: VoxelGrid) -> Result<Accuracy> {
    let run = voxelize_in(ctx, scene, method, grid, 1)?;
    let tris: Vec<_> = (0..scene.mesh.triangle_count()).map(|t| scene.mesh.triangle(t)).collect();
    let cov = RefGrid::matching(&grid).coverage(&tris, 1e-3);
    Ok(cov.accuracy(&run.occupied()))
}

fn recall(ctx: &Arc<Context>, scene: &Scene, method: VoxelizeMethod, grid: VoxelGrid) -> Result<f64> {
    Ok(voxel_accuracy(ctx, scene, method, grid)?.recall)
}

fn unit_grid(n: u32) -> VoxelGrid {
    VoxelGrid { origin: Vec3::ZERO, voxel: 1.0, dims: glam::UVec3::splat(n), warp: Default::default(), clip: None }
}

fn tess(subdivide: bool) -> VoxelizeMethod {
    VoxelizeMethod::Tess {
        level_scale: DEFAULT_LEVEL_SCALE,
        subdivide,
        min_level: true,
        neighbours: DEFAULT_NEIGHBOURS,
    }
}

/// Regime 1: a right triangle with legs of `size` voxels in a 128³ grid.
pub fn tessellation_limit(ctx: &Arc<Context>, sizes: &[f32]) -> Result<Regime> {
    let mut series = Vec::new();
    for subdivide in [false, true] {
        let mut points = Vec::new();
        for &s in sizes {
            let t = [Vec3::new(3.5, 3.5, 61.5), Vec3::new(3.5 + s, 3.5, 61.5), Vec3::new(3.5, 3.5 + s, 61.5)];
            let scene = Scene::from_triangles(&[(t, 0)], &[Vec3::splat(0.8)]);
            points.push((s as f64, recall(ctx, &scene, tess(subdivide), unit_grid(128))?));
        }
        series.push(Series {
            label: format!("tess, subdivision {}", if subdivide { "on (fix)" } else { "off" }),
            points,
        });
    }
    // The point voxelizer gives a large triangle as many points as its area asks for.
    let mut points = Vec::new();
    for &s in sizes {
        let t = [Vec3::new(3.5, 3.5, 61.5), Vec3::new(3.5 + s, 3.5, 61.5), Vec3::new(3.5, 3.5 + s, 61.5)];
        let scene = Scene::from_triangles(&[(t, 0)], &[Vec3::splat(0.8)]);
        points.push((s as f64, recall(ctx, &scene, VoxelizeMethod::points(), unit_grid(128))?));
    }
    series.push(Series { label: VoxelizeMethod::points().label(), points });
    Ok(Regime {
        name: "tess_limit".into(),
        title: "1. Large triangles: the tessellation level limit".into(),
        x: "triangle leg (voxels)".into(),
        y: "recall".into(),
        log_x: false,
        log_y: false,
        series,
    })
}

/// Regime 2a: the Cornell box at 64³ rasterized at `scales` × the voxel resolution.
pub fn raster_cracks(ctx: &Arc<Context>, scales: &[f32]) -> Result<Regime> {
    let scene = Scene::embedded_default()?;
    let grid = VoxelGrid::fit(&scene.mesh.bounds, 64)?;
    let mut series = Vec::new();
    for coverage in [Coverage::None, Coverage::Msaa, Coverage::Conservative] {
        let mut points = Vec::new();
        for &s in scales {
            let m = VoxelizeMethod::Raster { coverage, viewport_scale: s, depth_span: true };
            points.push((s as f64, recall(ctx, &scene, m, grid)?));
        }
        series.push(Series { label: VoxelizeMethod::raster(coverage).label(), points });
    }
    Ok(Regime {
        name: "raster_cracks".into(),
        title: "2. Raster cracks: fragments sparser than voxels".into(),
        x: "viewport scale (pixels per voxel)".into(),
        y: "recall (Cornell, 64³)".into(),
        log_x: true,
        log_y: false,
        series,
    })
}

/// Regime 2b: 400 random triangles of a given size (voxels) in a 32³ grid.
pub fn subvoxel_triangles(ctx: &Arc<Context>, sizes: &[f32]) -> Result<Regime> {
    let mut series: Vec<Series> = Vec::new();
    let methods = [
        tess(true),
        VoxelizeMethod::raster(Coverage::Msaa),
        VoxelizeMethod::raster(Coverage::None),
        VoxelizeMethod::raster(Coverage::Conservative),
        VoxelizeMethod::points(),
    ];
    for m in methods {
        series.push(Series { label: m.label(), points: Vec::new() });
    }
    for &s in sizes {
        let mut rng = SmallRng::seed_from_u64(5);
        let mut tris = Vec::new();
        for _ in 0..400 {
            let c = Vec3::new(rng.gen_range(2.0..30.0), rng.gen_range(2.0..30.0), rng.gen_range(2.0..30.0));
            let mut corner =
                || c + Vec3::new(rng.gen::<f32>() - 0.5, rng.gen::<f32>() - 0.5, rng.gen::<f32>() - 0.5) * s;
            tris.push(([corner(), corner(), corner()], 0));
        }
        let scene = Scene::from_triangles(&tris, &[Vec3::splat(0.8)]);
        for (m, ser) in methods.iter().zip(&mut series) {
            ser.points.push((s as f64, recall(ctx, &scene, *m, unit_grid(32))?));
        }
    }
    Ok(Regime {
        name: "subvoxel".into(),
        title: "2. Small triangles and slivers".into(),
        x: "triangle size (voxels)".into(),
        y: "recall".into(),
        log_x: true,
        log_y: false,
        series,
    })
}

/// A lone square lit from above, seen from above: any indirect light on it is self-illumination.
pub fn lone_plane() -> Scene {
    let q =
        [Vec3::new(-1.0, 0.0, -1.0), Vec3::new(1.0, 0.0, -1.0), Vec3::new(1.0, 0.0, 1.0), Vec3::new(-1.0, 0.0, 1.0)];
    let mut scene = Scene::from_triangles(&[([q[0], q[2], q[1]], 0), ([q[0], q[3], q[2]], 0)], &[Vec3::splat(0.8)]);
    scene.lights =
        vec![Light::Directional { direction: Vec3::new(0.2, -1.0, 0.1).normalize(), irradiance: Vec3::splat(3.0) }];
    scene.camera = Camera {
        eye: Vec3::new(0.0, 2.5, 0.01),
        target: Vec3::ZERO,
        up: Vec3::Z,
        fov_y_deg: 30.0,
        width: 64,
        height: 64,
    };
    scene
}

/// Mean indirect over mean direct radiance on the lone plane, cone model `gi` with its offset
/// set to `bias` voxels.
pub fn self_illumination_ratio(ctx: &Arc<Context>, gi: &GiFile, bias: f32, resolution: u32) -> Result<f64> {
    let mean = |view: View| -> Result<f64> {
        let mut scene = lone_plane();
        scene.settings.gi = gi.clone();
        scene.settings.gi.bias = bias;
        let o = RenderOptions {
            method: VoxelizeMethod::raster(Coverage::Msaa),
            resolution: Some(resolution),
            view,
            ..Default::default()
        };
        let r = Renderer::new(ctx, scene, o)?;
        r.render()?;
        let f = r.read_frame()?;
        let px: Vec<f32> = f.hdr.chunks_exact(4).map(|p| p[1]).collect();
        Ok(px.iter().map(|&v| v as f64).sum::<f64>() / px.len() as f64)
    };
    Ok(mean(View::Indirect)? / mean(View::Direct)?.max(1e-9))
}

/// Regime 5: self-illumination against the cone offset, with the thesis' cone model (where the
/// offset is the only fix) and with the default one (the self clamp: cones sample no level
/// finer than their distance from the surface allows).
pub fn self_illumination(ctx: &Arc<Context>, biases: &[f32]) -> Result<Regime> {
    let mut series = Vec::new();
    for (model, gi) in [("thesis", GiFile::thesis()), ("default", GiFile::default())] {
        for res in [32, 64] {
            let points = biases
                .iter()
                .map(|&b| Ok((b as f64, self_illumination_ratio(ctx, &gi, b, res)?)))
                .collect::<Result<_>>()?;
            series.push(Series { label: format!("{model} {res}³"), points });
        }
    }
    Ok(Regime {
        name: "self_illumination".into(),
        title: "5. Self-illumination of a lone lit plane".into(),
        x: "cone offset along the normal (voxels)".into(),
        y: "indirect / direct (truth: 0)".into(),
        log_x: false,
        log_y: false,
        series,
    })
}

/// Two rooms side by side (x < 0 lit by a spot light, x > 0 dark) divided by a wall of zero
/// thickness, the camera in the dark room.
pub fn two_rooms() -> Scene {
    let c = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
    let quad = |a: Vec3, b: Vec3, cc: Vec3, d: Vec3| [([a, b, cc], 0usize), ([a, cc, d], 0usize)];
    let mut tris = Vec::new();
    tris.extend(quad(c(-2., 0., -1.), c(2., 0., -1.), c(2., 0., 1.), c(-2., 0., 1.))); // floor
    tris.extend(quad(c(-2., 2., -1.), c(-2., 2., 1.), c(2., 2., 1.), c(2., 2., -1.))); // ceiling
    tris.extend(quad(c(-2., 0., -1.), c(-2., 2., -1.), c(2., 2., -1.), c(2., 0., -1.))); // back
    tris.extend(quad(c(-2., 0., 1.), c(2., 0., 1.), c(2., 2., 1.), c(-2., 2., 1.))); // front
    tris.extend(quad(c(-2., 0., -1.), c(-2., 0., 1.), c(-2., 2., 1.), c(-2., 2., -1.))); // left
    tris.extend(quad(c(2., 0., -1.), c(2., 2., -1.), c(2., 2., 1.), c(2., 0., 1.))); // right
    tris.extend(quad(c(0., 0., -1.), c(0., 2., -1.), c(0., 2., 1.), c(0., 0., 1.))); // divider
    let mut scene = Scene::from_triangles(&tris, &[Vec3::splat(0.75)]);
    scene.lights = vec![Light::Spot {
        position: c(-1.0, 1.95, 0.0),
        direction: Vec3::NEG_Y,
        intensity: Vec3::splat(20.0),
        inner_deg: 60.0,
        outer_deg: 70.0,
    }];
    scene.camera = Camera {
        eye: c(1.9, 1.6, 0.9),
        target: c(0.3, 0.4, -0.6),
        up: Vec3::Y,
        fov_y_deg: 70.0,
        width: 64,
        height: 64,
    };
    scene
}

/// Mean radiance seen in the dark room (truth: 0, every path to the light is walled off).
/// `two_sided`: the rasterized voxelizer's depth span, which gives a wall lying on a voxel
/// boundary a voxel on each side (off: the thesis' one voxel per fragment). Cone model `gi`
/// with its filter set by `anisotropic`.
pub fn leak(ctx: &Arc<Context>, gi: &GiFile, two_sided: bool, anisotropic: bool, resolution: u32) -> Result<f64> {
    let o = RenderOptions {
        method: VoxelizeMethod::Raster { coverage: Coverage::Msaa, viewport_scale: 1.0, depth_span: two_sided },
        resolution: Some(resolution),
        ..Default::default()
    };
    let mut scene = two_rooms();
    scene.settings.gi = gi.clone();
    scene.settings.gi.filter = if anisotropic { Filter::Aniso } else { Filter::Iso };
    let r = Renderer::new(ctx, scene, o)?;
    r.render()?;
    let f = r.read_frame()?;
    Ok(f.hdr.chunks_exact(4).map(|p| p[1] as f64).sum::<f64>() / (f.hdr.len() / 4) as f64)
}

/// Regime 3: light leaking through a thin wall: the thesis' voxelization and filtering, a voxel
/// on each side of the wall (the fix), and that with anisotropic filtering, all with the thesis'
/// cone model; then the default model (anisotropic, self clamp, facing factor).
pub fn light_leaking(ctx: &Arc<Context>, resolutions: &[u32]) -> Result<Regime> {
    let mut series = Vec::new();
    let thesis = GiFile::thesis();
    let default = GiFile::default();
    for (label, gi, two_sided, aniso) in [
        ("one voxel per fragment, isotropic (thesis)", &thesis, false, false),
        ("a voxel on each side of the wall (fix)", &thesis, true, false),
        ("each side + anisotropic voxels", &thesis, true, true),
        ("each side, default cone model", &default, true, true),
    ] {
        let points =
            resolutions.iter().map(|&n| Ok((n as f64, leak(ctx, gi, two_sided, aniso, n)?))).collect::<Result<_>>()?;
        series.push(Series { label: label.into(), points });
    }
    Ok(Regime {
        name: "light_leaking".into(),
        title: "3. Light leaking through a wall thinner than a voxel".into(),
        x: "voxel resolution N".into(),
        y: "mean radiance in the dark room (truth: 0)".into(),
        log_x: true,
        log_y: true,
        series,
    })
}

/// Mean |a - b| over the mean of b, in percent (linear radiance).
fn relative_change(a: &[f32], b: &[f32]) -> f64 {
    let diff: f64 = a.iter().zip(b).map(|(x, y)| (*x as f64 - *y as f64).abs()).sum();
    let total: f64 = b.iter().map(|y| y.abs() as f64).sum();
    if total > 0.0 {
        100.0 * diff / total
    } else {
        0.0
    }
}

/// What moves between the frames of the flicker regime.
#[derive(Clone, Copy, Debug)]
pub enum Motion {
    /// A 4 m volume following a point that slides 3 cm a frame along x.
    Volume { snap: bool },
    /// The spot light turns 0.5° a frame.
    Light,
    /// The camera orbits its target by 0.5° a frame (the volume stays fitted).
    Camera,
}

/// How the flicker regime's volume lays out its voxels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Layout {
    /// One grid: fitted to the scene, or the 4 m volume that slides.
    Even,
    /// Warped (Freed 2018 §4.6.1 or §4.6.2), its finest texels following the moving point or
    /// camera.
    Warped(crate::voxel::warp::WarpChoice),
    /// Clipmap levels of 32³ around the moving point (the finest 4 m, as the single sliding
    /// volume) or the camera (the coarsest holding the room).
    Clipmap(u32),
}

/// Frame-to-frame change (mean |Δ| over the mean, %) of the indirect light of a Cornell view
/// (direct light does not depend on the voxels) over `frames` frames under `motion`, with the
/// diffuse cones at one pixel in `gi_scale`², accumulated over frames or not. With a moving
/// camera the change includes the view's own; full-resolution tracing (scale 1) is the bar.
/// Accumulation first gets gi_scale² still frames: it converges (once) before it is judged.
/// `layout` spreads the voxels (`Layout`).
pub fn flicker(
    ctx: &Arc<Context>,
    motion: Motion,
    temporal: f32,
    (gi_scale, gi_accumulate): (u32, bool),
    layout: Layout,
    frames: u32,
) -> Result<Vec<(f64, f64)>> {
    let mut scene = Scene::embedded_default()?;
    scene.camera.width = 96;
    scene.camera.height = 96;
    scene.settings.gi.temporal = temporal;
    let centre = Vec3::new(0.0, 2.75, 0.0);
    let o = RenderOptions {
        method: VoxelizeMethod::raster(Coverage::Msaa),
        resolution: Some(32),
        view: View::Indirect,
        follow: match (motion, layout) {
            (_, Layout::Clipmap(_)) => None,
            (Motion::Volume { snap }, _) => Some(Follow { extent: 4.0, snap }),
            _ => None,
        },
        gi_scale,
        gi_accumulate,
        warp: match layout {
            Layout::Warped(s) => Some(s),
            _ => None,
        },
        clipmap: match (motion, layout) {
            (Motion::Volume { .. }, Layout::Clipmap(levels)) => Some(ClipOptions { levels, extent: Some(4.0) }),
            (_, Layout::Clipmap(levels)) => Some(ClipOptions { levels, extent: None }),
            _ => None,
        },
        ..Default::default()
    };
    let mut r = Renderer::new(ctx, scene, o)?;
    if gi_accumulate {
        for _ in 0..gi_scale * gi_scale {
            r.render()?;
        }
    }
    let mut previous: Option<Vec<f32>> = None;
    let mut points = Vec::new();
    let turn = glam::Quat::from_rotation_y(0.5f32.to_radians());
    for f in 0..frames {
        match motion {
            Motion::Volume { .. } => r.follow(centre + Vec3::X * 0.03 * f as f32)?,
            Motion::Light => {
                if let Some(light) = r.scene.lights.first_mut() {
                    crate::viewer::camera::swing_light(light, 0.0, 0.5f32.to_radians());
                }
            }
            Motion::Camera => {
                let c = &mut r.scene.camera;
                c.eye = c.target + turn * (c.eye - c.target);
                let eye = c.eye;
                r.follow(eye)?; // a warp's finest texels follow the camera, as in the viewer
            }
        }
        r.render()?;
        let hdr: Vec<f32> = r.read_frame()?.hdr.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect();
        if let Some(p) = &previous {
            points.push((f as f64, relative_change(p, &hdr)));
        }
        previous = Some(hdr);
    }
    Ok(points)
}

/// Regime 4: temporal flicker.
pub fn temporal_flicker(ctx: &Arc<Context>, frames: u32) -> Result<Regime> {
    let full = (1, false);
    let warp = Layout::Warped(crate::voxel::warp::WarpChoice::Function(crate::voxel::warp::THESIS_END_SLOPE));
    let perspective =
        Layout::Warped(crate::voxel::warp::WarpChoice::Perspective(crate::voxel::perspective::DEFAULT_RATIO));
    let even = Layout::Even;
    let configs = [
        ("sliding volume", Motion::Volume { snap: false }, 1.0, full, even),
        ("sliding volume, snapped", Motion::Volume { snap: true }, 1.0, full, even),
        ("sliding volume, snapped, warped", Motion::Volume { snap: true }, 1.0, full, warp),
        ("sliding clipmap, 3 levels", Motion::Volume { snap: true }, 1.0, full, Layout::Clipmap(3)),
        ("sliding volume, temporal 0.2 (reprojected)", Motion::Volume { snap: false }, 0.2, full, even),
        ("sliding volume, snapped, temporal 0.2", Motion::Volume { snap: true }, 0.2, full, even),
        ("turning light", Motion::Light, 1.0, full, even),
        ("turning light, temporal 0.2", Motion::Light, 0.2, full, even),
        ("turning light, GI scale 2 accumulated", Motion::Light, 1.0, (2, true), even),
        ("turning light, GI scale 4 accumulated", Motion::Light, 1.0, (4, true), even),
        ("turning light, GI scale 8 accumulated", Motion::Light, 1.0, (8, true), even),
        ("orbiting camera", Motion::Camera, 1.0, full, even),
        ("orbiting camera, warped", Motion::Camera, 1.0, full, warp),
        ("orbiting camera, perspective warp", Motion::Camera, 1.0, full, perspective),
        ("orbiting camera, clipmap, 4 levels", Motion::Camera, 1.0, full, Layout::Clipmap(4)),
        ("orbiting camera, GI scale 2", Motion::Camera, 1.0, (2, false), even),
        ("orbiting camera, GI scale 2 accumulated", Motion::Camera, 1.0, (2, true), even),
        ("orbiting camera, GI scale 4", Motion::Camera, 1.0, (4, false), even),
        ("orbiting camera, GI scale 4 accumulated", Motion::Camera, 1.0, (4, true), even),
        ("orbiting camera, GI scale 8 accumulated", Motion::Camera, 1.0, (8, true), even),
    ];
    let series: Vec<Series> = configs
        .iter()
        .map(|(label, motion, t, gi, layout)| {
            Ok(Series { label: label.to_string(), points: flicker(ctx, *motion, *t, *gi, *layout, frames)? })
        })
        .collect::<Result<_>>()?;
    Ok(Regime {
        name: "temporal_flicker".into(),
        title: "4. Temporal flicker".into(),
        x: "frame".into(),
        y: "indirect light change from the previous frame (%)".into(),
        log_x: false,
        log_y: false,
        series,
    })
}

/// All measured regimes (`quick`: fewer points).
pub fn run(ctx: &Arc<Context>, quick: bool, progress: &dyn Fn(&str)) -> Result<Vec<Regime>> {
    let pick = |full: &[f32], q: &[f32]| if quick { q.to_vec() } else { full.to_vec() };
    progress("1. tessellation limit");
    let r1 = tessellation_limit(ctx, &pick(&[8.0, 16.0, 24.0, 32.0, 48.0, 64.0, 96.0, 120.0], &[16.0, 64.0, 120.0]))?;
    progress("2. raster cracks");
    let r2 = raster_cracks(ctx, &pick(&[0.25, 0.5, 0.75, 1.0, 2.0], &[0.5, 1.0]))?;
    progress("2. small triangles");
    let r2b = subvoxel_triangles(ctx, &pick(&[0.1, 0.2, 0.4, 0.7, 1.0, 2.0, 4.0], &[0.2, 2.0]))?;
    progress("3. light leaking");
    let r3 =
        light_leaking(ctx, &pick(&[16.0, 32.0, 64.0, 128.0], &[32.0]).iter().map(|&n| n as u32).collect::<Vec<_>>())?;
    progress("4. temporal flicker");
    let r4 = temporal_flicker(ctx, if quick { 6 } else { 24 })?;
    progress("5. self-illumination");
    let r5 = self_illumination(ctx, &pick(&[0.0, 0.25, 0.5, 1.0, 1.5, 2.0, 3.0], &[0.0, 1.5]))?;
    Ok(vec![r1, r2, r2b, r3, r4, r5])
}

/// Writes the regimes' charts (`stability_<name>.png` and `.svg`), `stability.json` and the
/// hostile-geometry rows' `hostile.json` into `dir`; returns the files written.
pub fn write(dir: &Path, regimes: &[Regime], hostile: &[HostileRow]) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir).map_err(|source| Error::Io { path: dir.to_path_buf(), source })?;
    let mut files = Vec::new();
    for g in regimes {
        files.extend(charts::draw_regime(dir, g)?);
    }
    for (name, json) in [
        ("stability.json", serde_json::to_string_pretty(regimes)),
        ("hostile.json", serde_json::to_string_pretty(hostile)),
    ] {
        let path = dir.join(name);
        let text = json.map_err(|e| Error::input(&path, e.to_string()))?;
        std::fs::write(&path, text).map_err(|source| Error::Io { path: path.clone(), source })?;
        files.push(path);
    }
    Ok(files)
}
