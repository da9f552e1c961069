//! Exact voxel coverage on the CPU (rayon): a voxel is covered when its box intersects a
//! triangle, by the separating-axis triangle/box test of Akenine-Möller (2001). Faces that lie
//! exactly on voxel boundaries are judged fairly with two sets: *required* voxels meet the
//! triangle when shrunk by `eps` voxels, *allowed* voxels meet it when grown by `eps`.
//! A face lying exactly in a plane between two voxel layers requires neither layer alone, but
//! it does require one of the two: each such cell gives a required *pair*.
//! Recall = share of required voxels and pairs the GPU filled; precision = share of GPU voxels
//! that are allowed; IoU = |GPU ∩ allowed| / |GPU ∪ required|.
//!
//! A warped grid (Freed 2018 §4.6.1) warps each axis on its own, so its voxels are still boxes,
//! each of its own size: the reference finds their faces by inverting the thesis' cubic by
//! bisection (its own code, not `voxel::warp`'s), and `eps` is then a fraction of each voxel.
//! A perspective-warped grid (§4.6.2) is a projective map, under which a triangle stays a
//! triangle: the reference clips each triangle at the map's apex side and maps it among the
//! texels with its own code, reading the grid's matrix as plain numbers, and covers it there as
//! on an even grid of unit voxels.

use glam::{DVec3, Vec3};
use rayon::prelude::*;

/// The grid the reference works on: `dims` cubes of edge `voxel` along x, y and z from `origin`
/// (world units), or with `warp`, boxes whose faces the warp places.
#[derive(Clone, Copy, Debug)]
pub struct RefGrid {
    pub origin: Vec3,
    pub voxel: f32,
    pub dims: [u32; 3],
    pub warp: Option<RefWarp>,
    pub perspective: Option<RefPerspective>,
}

/// A projective map of world space onto texel coordinates (texel v spans [v, v + 1)):
/// t = (M p).xyz / (M p).w, defined where (M p).w exceeds `clip` (no texel lies nearer).
#[derive(Clone, Copy, Debug)]
pub struct RefPerspective {
    pub world_to_texel: glam::DMat4,
    pub clip: f64,
}

impl RefPerspective {
    /// The triangles among the texels: each clipped at w = clip (the part beyond, a triangle
    /// or a quad, as one or two triangles), then divided by w.
    pub fn map(&self, triangles: &[[Vec3; 3]]) -> Vec<[Vec3; 3]> {
        let mut out = Vec::with_capacity(triangles.len());
        for t in triangles {
            let h: Vec<glam::DVec4> = t.iter().map(|p| self.world_to_texel * p.as_dvec3().extend(1.0)).collect();
            let mut poly = Vec::with_capacity(4);
            for i in 0..3 {
                let (a, b) = (h[i], h[(i + 1) % 3]);
                let (da, db) = (a.w - self.clip, b.w - self.clip);
                if da >= 0.0 {
                    poly.push(a);
                }
                if (da >= 0.0) != (db >= 0.0) {
                    poly.push(a + (b - a) * (da / (da - db)));
                }
            }
            let texel = |q: glam::DVec4| (q.truncate() / q.w).as_vec3();
            for k in 1..poly.len().saturating_sub(1) {
                out.push([texel(poly[0]), texel(poly[k]), texel(poly[k + 1])]);
            }
        }
        out
    }
}

/// The thesis' warp (§4.6.1) with its peak at grid fraction `centre` and slope `end_slope` at
/// the faces: each side of the centre is the half of w(x) = αx + (3 − 3α)x² + (2α − 2)x³ below
/// x = 1/2, scaled to that side's length.
#[derive(Clone, Copy, Debug)]
pub struct RefWarp {
    pub centre: [f64; 3],
    pub end_slope: f64,
}

impl RefWarp {
    fn thesis(&self, x: f64) -> f64 {
        let a = self.end_slope;
        a * x + (3.0 - 3.0 * a) * x * x + (2.0 * a - 2.0) * x * x * x
    }

    /// The texture fraction of grid fraction `x` in [0, 1] along `axis`.
    fn forward(&self, x: f64, axis: usize) -> f64 {
        let c = self.centre[axis];
        if x < c {
            2.0 * c * self.thesis(x / (2.0 * c))
        } else if x >= 1.0 {
            1.0
        } else {
            1.0 - 2.0 * (1.0 - c) * self.thesis((1.0 - x) / (2.0 * (1.0 - c)))
        }
    }

    /// The grid fraction where texture fraction `t` begins, by bisection.
    fn face(&self, t: f64, axis: usize) -> f64 {
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        for _ in 0..64 {
            let mid = 0.5 * (lo + hi);
            if self.forward(mid, axis) < t {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }
}

/// Separating-axis test of a triangle against the box centred at the origin with half-size `h`.
pub fn triangle_box_overlap(v: [DVec3; 3], h: DVec3) -> bool {
    let [v0, v1, v2] = v;
    // Box face normals: the triangle's bounding box against the box.
    for a in 0..3 {
        let (lo, hi) = (v0[a].min(v1[a]).min(v2[a]), v0[a].max(v1[a]).max(v2[a]));
        if lo > h[a] || hi < -h[a] {
            return false;
        }
    }
    let e = [v1 - v0, v2 - v1, v0 - v2];
    // Triangle normal.
    let n = e[0].cross(e[1]);
    let r = h.x * n.x.abs() + h.y * n.y.abs() + h.z * n.z.abs();
    if n.dot(v0).abs() > r {
        return false;
    }
    // The nine cross products of box axes and triangle edges.
    for edge in e {
        for axis in [DVec3::X, DVec3::Y, DVec3::Z] {
            let a = axis.cross(edge);
            if a == DVec3::ZERO {
                continue;
            }
            let p = [a.dot(v0), a.dot(v1), a.dot(v2)];
            let (lo, hi) = (p[0].min(p[1]).min(p[2]), p[0].max(p[1]).max(p[2]));
            let r = h.x * a.x.abs() + h.y * a.y.abs() + h.z * a.z.abs();
            if lo > r || hi < -r {
                return false;
            }
        }
    }
    true
}

/// Exact coverage as two bit sets over the grid (index `x + nx*(y + ny*z)`).
#[derive(Clone, Debug)]
pub struct Coverage {
    pub dims: [u32; 3],
    pub required: Vec<bool>,
    pub allowed: Vec<bool>,
    /// Voxel pairs on either side of a face that lies in a layer boundary: one must be filled.
    pub pairs: Vec<(usize, usize)>,
}

/// The face of `faces` nearest `x`.
fn nearest_face(faces: &[f64], x: f64) -> usize {
    let i = faces.partition_point(|&f| f < x).min(faces.len() - 1);
    if i > 0 && x - faces[i - 1] < faces[i] - x {
        i - 1
    } else {
        i
    }
}

/// If the triangle (voxel units) lies in the plane of face k along `axis` (within `eps` of the
/// voxels there), returns (axis, k).
fn boundary_plane(p: &[DVec3; 3], faces: &[Vec<f64>; 3], eps: f64) -> Option<(usize, i64)> {
    (0..3).find_map(|a| {
        let f = &faces[a];
        let k = nearest_face(f, p[0][a]);
        let size = 0.5 * (f[(k + 1).min(f.len() - 1)] - f[k.saturating_sub(1)]);
        p.iter().all(|v| (v[a] - f[k]).abs() <= eps * 0.5 * size).then_some((a, k as i64))
    })
}

impl RefGrid {
    /// The same grid as a renderer's (its origin, voxel size and dims, read as plain numbers).
    pub fn matching(grid: &crate::voxel::VoxelGrid) -> Self {
        use crate::voxel::warp::Warp;
        let (mut warp, mut perspective) = (None, None);
        match grid.warp {
            Warp::Function(w) if w.end_slope < 1.0 => {
                warp = Some(RefWarp { centre: w.centre.as_dvec3().into(), end_slope: w.end_slope as f64 })
            }
            Warp::Perspective(p) => {
                // World to grid fraction, the grid's map to texture fractions, then to texels.
                let size = grid.dims.as_dvec3() * grid.voxel as f64;
                let to_fraction =
                    glam::DMat4::from_scale(1.0 / size) * glam::DMat4::from_translation(-grid.origin.as_dvec3());
                let world_to_texel = glam::DMat4::from_scale(grid.dims.as_dvec3()) * p.to_texel * to_fraction;
                perspective = Some(RefPerspective { world_to_texel, clip: 0.5 * p.near });
            }
            _ => {}
        }
        RefGrid { origin: grid.origin, voxel: grid.voxel, dims: grid.dims.into(), warp, perspective }
    }

    /// The faces of the voxels along each axis, in voxels of the unwarped grid (0, 1, .., n
    /// unwarped).
    pub fn faces(&self) -> [Vec<f64>; 3] {
        std::array::from_fn(|a| {
            let n = self.dims[a];
            (0..=n)
                .map(|i| match self.warp {
                    Some(w) => w.face(i as f64 / n as f64, a) * n as f64,
                    None => i as f64,
                })
                .collect()
        })
    }

    pub fn index(&self, x: u32, y: u32, z: u32) -> usize {
        let [nx, ny, _] = self.dims;
        x as usize + nx as usize * (y as usize + ny as usize * z as usize)
    }

    /// Voxels each triangle touches; `eps` is the fairness margin in voxels (e.g. 0.001).
    pub fn coverage(&self, triangles: &[[Vec3; 3]], eps: f64) -> Coverage {
        if let Some(p) = self.perspective {
            let among = RefGrid { origin: Vec3::ZERO, voxel: 1.0, dims: self.dims, warp: None, perspective: None };
            return among.coverage(&p.map(triangles), eps);
        }
        let n = self.dims.map(|d| d as i64);
        let len = self.dims.iter().map(|&d| d as usize).product();
        let faces = self.faces();
        // The voxels whose extent along `a` reaches [lo, hi].
        let span = |lo: f64, hi: f64, a: usize| {
            let f = &faces[a];
            let first = f.partition_point(|&x| x < lo) as i64 - 1;
            let last = f.partition_point(|&x| x <= hi) as i64 - 1;
            (first.clamp(0, n[a] - 1), last.clamp(0, n[a] - 1))
        };
        // Voxel (x, y, z): its centre and half size.
        let cell = |x: i64, y: i64, z: i64| {
            let lo = DVec3::new(faces[0][x as usize], faces[1][y as usize], faces[2][z as usize]);
            let hi = DVec3::new(faces[0][x as usize + 1], faces[1][y as usize + 1], faces[2][z as usize + 1]);
            (0.5 * (lo + hi), 0.5 * (hi - lo))
        };
        // Per triangle: (voxel, required) hits and boundary-face pairs.
        type Hits = (Vec<(usize, bool)>, Vec<(usize, usize)>);
        let per_triangle: Vec<Hits> = triangles
            .par_iter()
            .map(|t| {
                // Triangle in voxel units; skip non-finite input.
                let p: [DVec3; 3] = t.map(|v| ((v - self.origin) / self.voxel).as_dvec3());
                if p.iter().any(|v| !v.is_finite()) {
                    return (Vec::new(), Vec::new());
                }
                // Grown by eps of the largest voxel (a warped grid's are up to 1/0.05 wide).
                let lo = p[0].min(p[1]).min(p[2]) - 20.0 * eps;
                let hi = p[0].max(p[1]).max(p[2]) + 20.0 * eps;
                if (0..3).any(|a| hi[a] < 0.0 || lo[a] > n[a] as f64) {
                    return (Vec::new(), Vec::new());
                }
                let s = |a: usize| span(lo[a], hi[a], a);
                let ((x0, x1), (y0, y1), (z0, z1)) = (s(0), s(1), s(2));
                let plane = boundary_plane(&p, &faces, eps);
                let mut pairs = Vec::new();
                let normal = (p[1] - p[0]).cross(p[2] - p[0]);
                let mut out = Vec::new();
                for z in z0..=z1 {
                    for y in y0..=y1 {
                        for x in x0..=x1 {
                            // eps is of the voxel's own size (a voxel of an unwarped grid is 1).
                            let (c, half) = cell(x, y, z);
                            // Cheap plane rejection before the full test.
                            let reach = half * (1.0 + 2.0 * eps);
                            let rn = reach.x * normal.x.abs() + reach.y * normal.y.abs() + reach.z * normal.z.abs();
                            if normal.dot(p[0] - c).abs() > rn {
                                continue;
                            }
                            let v = p.map(|q| q - c);
                            if !triangle_box_overlap(v, reach) {
                                continue;
                            }
                            let required = triangle_box_overlap(v, half * (1.0 - 2.0 * eps));
                            let here = self.index(x as u32, y as u32, z as u32);
                            out.push((here, required));
                            // The face lies on this voxel's lower face: pair it with the voxel below,
                            // when the face overlaps the cell's interior.
                            if let Some((a, k)) = plane {
                                let c = [x, y, z];
                                if c[a] == k && k > 0 {
                                    let (mut centre, mut h) = cell(x, y, z);
                                    h *= 1.0 - 2.0 * eps;
                                    h[a] = 2.0 * eps * half[a];
                                    centre[a] = faces[a][k as usize];
                                    if triangle_box_overlap(p.map(|q| q - centre), h) {
                                        let mut below = c;
                                        below[a] -= 1;
                                        pairs.push((
                                            self.index(below[0] as u32, below[1] as u32, below[2] as u32),
                                            here,
                                        ));
                                    }
                                }
                            }
                        }
                    }
                }
                (out, pairs)
            })
            .collect();
        let mut required = vec![false; len];
        let mut allowed = vec![false; len];
        let mut pairs = Vec::new();
        for (list, p) in per_triangle {
            for (i, req) in list {
                allowed[i] = true;
                required[i] |= req;
            }
            pairs.extend(p);
        }
        pairs.sort_unstable();
        pairs.dedup();
        // A pair already satisfied by a required voxel adds nothing.
        pairs.retain(|&(a, b)| !required[a] && !required[b]);
        Coverage { dims: self.dims, required, allowed, pairs }
    }
}

/// Accuracy of a voxelization against the exact coverage.
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct Accuracy {
    pub recall: f64,
    pub precision: f64,
    pub iou: f64,
    pub occupied: usize,
    /// Required voxels plus required pairs.
    pub required: usize,
}

impl Coverage {
    pub fn accuracy(&self, occupied: &[bool]) -> Accuracy {
        assert_eq!(occupied.len(), self.required.len(), "grids differ in size");
        let (mut hit_req, mut req, mut occ, mut occ_allowed, mut union) = (0usize, 0usize, 0usize, 0usize, 0usize);
        for ((&o, &r), &a) in occupied.iter().zip(&self.required).zip(&self.allowed) {
            req += r as usize;
            occ += o as usize;
            hit_req += (o && r) as usize;
            occ_allowed += (o && a) as usize;
            union += (o || r) as usize;
        }
        let hit_pairs = self.pairs.iter().filter(|&&(a, b)| occupied[a] || occupied[b]).count();
        let ratio = |a: usize, b: usize| if b == 0 { 1.0 } else { a as f64 / b as f64 };
        Accuracy {
            recall: ratio(hit_req + hit_pairs, req + self.pairs.len()),
            precision: ratio(occ_allowed, occ),
            iou: ratio(occ_allowed, union),
            occupied: occ,
            required: req + self.pairs.len(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(n: u32) -> RefGrid {
        RefGrid { origin: Vec3::ZERO, voxel: 1.0, dims: [n; 3], warp: None, perspective: None }
    }

    #[test]
    fn sat_agrees_with_simple_cases() {
        let h = DVec3::splat(0.5);
        let tri = |a: [f64; 3], b: [f64; 3], c: [f64; 3]| [DVec3::from(a), DVec3::from(b), DVec3::from(c)];
        assert!(triangle_box_overlap(tri([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]), h));
        assert!(!triangle_box_overlap(tri([2.0, 2.0, 2.0], [3.0, 2.0, 2.0], [2.0, 3.0, 2.0]), h));
        // Passes beside the box corner: bounding boxes overlap, an edge axis separates.
        assert!(!triangle_box_overlap(tri([0.9, -0.2, 0.0], [1.5, 0.6, 0.0], [1.5, -0.2, 0.0]), h));
        // Large triangle whose plane cuts through the box.
        assert!(triangle_box_overlap(tri([-5.0, -5.0, 0.2], [5.0, -5.0, 0.2], [0.0, 5.0, -0.2]), h));
    }

    #[test]
    fn axis_aligned_square_on_a_voxel_boundary_is_fair() {
        // The square z = 2 lies on the face between layers 1 and 2: neither layer is required,
        // both are allowed.
        let g = grid(4);
        let q = [Vec3::new(0.2, 0.2, 2.0), Vec3::new(3.8, 0.2, 2.0), Vec3::new(3.8, 3.8, 2.0)];
        let c = g.coverage(&[q], 1e-3);
        assert_eq!(c.required.iter().filter(|&&r| r).count(), 0);
        // 10 cells under the triangle plus 3 touched only at a corner by the hypotenuse.
        assert_eq!(c.allowed.iter().filter(|&&r| r).count(), 2 * 13);
        // ...but each of the 10 cells under it requires one of its two layers.
        assert_eq!(c.pairs.len(), 10);
        let mut occupied = vec![false; 64];
        for &(below, _) in &c.pairs {
            occupied[below] = true;
        }
        assert_eq!(c.accuracy(&occupied).recall, 1.0);
        assert_eq!(c.accuracy(&[false; 64]).recall, 0.0);
        // Inside a layer, every voxel under the triangle is required.
        let q = [Vec3::new(0.2, 0.2, 2.5), Vec3::new(3.8, 0.2, 2.5), Vec3::new(3.8, 3.8, 2.5)];
        let c = g.coverage(&[q], 1e-3);
        assert_eq!(c.required.iter().filter(|&&r| r).count(), 10);
    }

    #[test]
    fn accuracy_figures() {
        let c = Coverage {
            dims: [4, 1, 1],
            required: vec![true, true, false, false],
            allowed: vec![true, true, true, false],
            pairs: vec![],
        };
        let a = c.accuracy(&[true, false, true, true]);
        assert!((a.recall - 0.5).abs() < 1e-12);
        assert!((a.precision - 2.0 / 3.0).abs() < 1e-12);
        assert!((a.iou - 2.0 / 4.0).abs() < 1e-12);
    }
}
