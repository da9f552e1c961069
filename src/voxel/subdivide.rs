//! Splits, when the scene loads, exactly those triangles a voxelizer cannot take whole, by
//! longest-edge bisection: for the tessellation path, those whose levels would pass the device's
//! `maxTessellationGenerationLevel` (Freed 2018 §4.1.2 names the problem: such triangles leave
//! holes) or the lower patch-balance bound of `tess.rs` (the level formulas are those of
//! `shaders-glsl/voxelize/tess.tesc`); for the point path generating on the GPU, those that
//! need more points than a triangle's slots (Mavridis & Papaioannou 2011 split big triangles
//! at load, rather than amplify them at run time).

use glam::{Vec2, Vec3, Vec4};

use super::VoxelGrid;
use crate::scene::{Draw, Mesh, Vertex};

/// The tessellation levels the control shader computes: ([outer; 3], inner), before clamping.
pub fn tess_levels(p: [Vec3; 3], grid: &VoxelGrid, scale: f32) -> ([f32; 3], f32) {
    let q = p.map(|v| (v - grid.origin) / grid.voxel);
    let outer = [(q[2] - q[1]), (q[0] - q[2]), (q[1] - q[0])].map(|e| e.abs().max_element() * scale);
    let (a, b, c) = ((q[2] - q[1]).length(), (q[0] - q[2]).length(), (q[1] - q[0]).length());
    let s = 0.5 * (a + b + c);
    let area = (s * (s - a) * (s - b) * (s - c)).max(0.0).sqrt();
    let inner = 2.0 * area / a.min(b).min(c).max(1e-12) * scale;
    (outer, inner)
}

fn midpoint(a: &Vertex, b: &Vertex) -> Vertex {
    let mix3 = |x: [f32; 3], y: [f32; 3]| ((Vec3::from(x) + Vec3::from(y)) * 0.5).into();
    Vertex {
        pos: mix3(a.pos, b.pos),
        normal: mix3(a.normal, b.normal),
        uv: ((Vec2::from(a.uv) + Vec2::from(b.uv)) * 0.5).into(),
        tangent: ((Vec4::from(a.tangent) + Vec4::from(b.tangent)) * 0.5).into(),
    }
}

/// The mesh with every triangle that needs a level above `max_level` bisected until none does;
/// returns it with the number of original triangles that were split.
pub fn subdivide_for_tessellation(mesh: &Mesh, grid: &VoxelGrid, scale: f32, max_level: f32) -> (Mesh, usize) {
    // Margin: the GPU computes in f32 and rounds levels up.
    let limit = (max_level - 0.5).max(1.0);
    subdivide_until(mesh, |p| {
        let (outer, inner) = tess_levels(p, grid, scale);
        outer.iter().all(|&l| l <= limit) && inner <= limit
    })
}

/// The mesh with every triangle that `fits` refuses bisected along its longest edge until
/// every piece fits; returns it with the number of original triangles that were split.
/// `fits` must accept every triangle small enough (the bisection halves the area each time).
pub fn subdivide_until(mesh: &Mesh, fits: impl Fn([Vec3; 3]) -> bool) -> (Mesh, usize) {
    let fits = |v: &[Vertex; 3]| fits(v.map(|x| Vec3::from(x.pos)));
    let mut vertices = mesh.vertices.clone();
    let mut indices = Vec::with_capacity(mesh.indices.len());
    let mut draws = Vec::with_capacity(mesh.draws.len());
    let mut split = 0;
    for draw in &mesh.draws {
        let first = indices.len() as u32;
        let range = draw.first_index as usize..(draw.first_index + draw.index_count) as usize;
        for tri in mesh.indices[range].chunks_exact(3) {
            let mut stack = vec![[tri[0], tri[1], tri[2]]];
            let mut was_split = false;
            while let Some(t) = stack.pop() {
                let v = t.map(|i| vertices[i as usize]);
                if fits(&v) {
                    indices.extend_from_slice(&t);
                    continue;
                }
                was_split = true;
                // Bisect the longest edge (k, k+1).
                let len = |i: usize| Vec3::from(v[i].pos).distance(Vec3::from(v[(i + 1) % 3].pos));
                let k = (0..3).max_by(|&a, &b| len(a).total_cmp(&len(b))).unwrap_or(0);
                let (a, b, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
                let m = vertices.len() as u32;
                vertices.push(midpoint(&vertices[a as usize], &vertices[b as usize]));
                stack.push([a, m, c]);
                stack.push([m, b, c]);
            }
            split += was_split as usize;
        }
        draws.push(Draw { first_index: first, index_count: indices.len() as u32 - first, material: draw.material });
    }
    (Mesh { vertices, indices, draws, bounds: mesh.bounds }, split)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Aabb;

    #[test]
    fn splits_only_triangles_beyond_the_limit_and_keeps_the_surface() {
        let v = |x: f32, y: f32| Vertex { pos: [x, y, 0.5], normal: [0.0, 0.0, 1.0], ..Default::default() };
        let mesh = Mesh {
            vertices: vec![v(0.0, 0.0), v(100.0, 0.0), v(0.0, 100.0), v(0.0, 0.0), v(1.0, 0.0), v(0.0, 1.0)],
            indices: vec![0, 1, 2, 3, 4, 5],
            draws: vec![Draw { first_index: 0, index_count: 6, material: 0 }],
            bounds: Aabb { min: Vec3::ZERO, max: Vec3::new(100.0, 100.0, 1.0) },
        };
        let grid = VoxelGrid {
            origin: Vec3::ZERO,
            voxel: 1.0,
            dims: glam::UVec3::splat(128),
            warp: Default::default(),
            clip: None,
        };
        let (out, split) = subdivide_for_tessellation(&mesh, &grid, 1.0, 64.0);
        assert_eq!(split, 1, "only the big triangle is split");
        let area = |m: &Mesh| -> f32 {
            (0..m.triangle_count())
                .map(|t| {
                    let [a, b, c] = m.triangle(t);
                    (b - a).cross(c - a).length() * 0.5
                })
                .sum()
        };
        assert!((area(&out) - area(&mesh)).abs() < 1e-2);
        for t in 0..out.triangle_count() {
            let (outer, inner) = tess_levels(out.triangle(t), &grid, 1.0);
            assert!(outer.iter().all(|&l| l <= 63.5) && inner <= 63.5);
        }
    }
}
