//! Bad input that loads: degenerate, duplicate, tiny-scale and very many triangles render without
//! validation errors, and what remains is drawn correctly.

mod common;

use glam::Vec3;
use vct::render::{RenderOptions, Renderer, View};
use vct::scene::Scene;
use vct::voxel::{Coverage, VoxelizeMethod};

fn render(scene: Scene, method: VoxelizeMethod) -> (vct::render::FrameImages, Vec<String>) {
    let ctx = common::context();
    let o = RenderOptions { method, resolution: Some(32), view: View::Full, ..Default::default() };
    let r = Renderer::new(&ctx, scene, o).unwrap();
    r.render().unwrap();
    let f = r.read_frame().unwrap();
    let notes = r.notes.clone();
    drop(r);
    common::assert_clean(&ctx);
    (f, notes)
}

fn quad(y: f32, s: f32) -> [([Vec3; 3], usize); 2] {
    let q = [Vec3::new(-s, y, -s), Vec3::new(s, y, -s), Vec3::new(s, y, s), Vec3::new(-s, y, s)];
    [([q[0], q[2], q[1]], 0), ([q[0], q[3], q[2]], 0)]
}

#[test]
fn zero_area_and_duplicate_triangles_do_not_change_the_image() {
    let clean = Scene::from_triangles(&quad(0.0, 1.0), &[Vec3::splat(0.7)]);
    let mut tris = quad(0.0, 1.0).to_vec();
    tris.extend(quad(0.0, 1.0)); // duplicates
    tris.push(([Vec3::ZERO, Vec3::X * 0.5, Vec3::X], 0)); // zero area
    tris.push(([Vec3::new(0.3, 0.0, 0.3); 3], 0)); // a point
    let mut messy = Scene::from_triangles(&tris, &[Vec3::splat(0.7)]);
    messy.camera = clean.camera;
    for method in [VoxelizeMethod::tess(), VoxelizeMethod::raster(Coverage::Msaa)] {
        let (a, _) = render(clean.clone(), method);
        let (b, _) = render(messy.clone(), method);
        let worst = a.ldr.iter().zip(&b.ldr).map(|(x, y)| (*x as i32 - *y as i32).abs()).max().unwrap();
        assert!(
            worst <= 2,
            "{}: duplicates and degenerate triangles changed the image by up to {worst}",
            method.label()
        );
    }
}

#[test]
fn a_sub_millimetre_scene_is_rendered_with_a_warning() {
    let scene = Scene::from_triangles(&quad(0.0, 0.005), &[Vec3::splat(0.7)]);
    let (f, notes) = render(scene, VoxelizeMethod::raster(Coverage::Msaa));
    assert!(notes.iter().any(|n| n.contains("mm across")), "{notes:?}");
    assert!(f.hdr.chunks_exact(4).any(|p| p[0] > 0.0), "nothing rendered");
}

#[test]
fn a_million_tiny_triangles_render() {
    let mut tris = Vec::with_capacity(1_000_000);
    // A watertight 1000 × 500 grid of cells, two triangles each, over the same square as `quad`.
    let (nx, nz) = (1000, 500);
    let p = |i: usize, j: usize| Vec3::new(i as f32 / nx as f32 * 2.0 - 1.0, 0.0, j as f32 / nz as f32 * 2.0 - 1.0);
    for i in 0..nx {
        for j in 0..nz {
            tris.push(([p(i, j), p(i, j + 1), p(i + 1, j)], 0));
            tris.push(([p(i + 1, j), p(i, j + 1), p(i + 1, j + 1)], 0));
        }
    }
    let scene = Scene::from_triangles(&tris, &[Vec3::splat(0.7)]);
    assert_eq!(scene.mesh.triangle_count(), 1_000_000);
    let mut plain = Scene::from_triangles(&quad(0.0, 1.0), &[Vec3::splat(0.7)]);
    plain.camera = scene.camera;
    let lit = |f: &vct::render::FrameImages| f.hdr.chunks_exact(4).filter(|p| p[0] > 0.0).count();
    let (reference, _) = render(plain, VoxelizeMethod::raster(Coverage::Msaa));
    for method in [VoxelizeMethod::raster(Coverage::Msaa), VoxelizeMethod::tess()] {
        let (f, _) = render(scene.clone(), method);
        let (n, want) = (lit(&f), lit(&reference));
        assert!(
            want > 1000 && n.abs_diff(want) < want / 50,
            "{}: {n} lit pixels, the plain plane has {want}",
            method.label()
        );
    }
}
