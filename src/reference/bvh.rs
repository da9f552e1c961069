//! Bounding volume hierarchy over triangles for the CPU path tracer: median split of centroids
//! along the longest axis, leaves of up to four triangles, Möller–Trumbore intersection.

use glam::Vec3;

#[derive(Clone, Copy)]
struct Node {
    min: Vec3,
    max: Vec3,
    /// Leaf: first triangle in `order`; inner: index of the left child (right = left + 1).
    first: u32,
    /// Triangles in a leaf; 0 for an inner node.
    count: u32,
}

pub struct Bvh {
    nodes: Vec<Node>,
    order: Vec<u32>,
    tris: Vec<[Vec3; 3]>,
}

/// A ray's nearest hit: distance, triangle, barycentrics of vertices 1 and 2.
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    pub t: f32,
    pub tri: u32,
    pub u: f32,
    pub v: f32,
}

const LEAF: usize = 4;

fn bounds(tris: &[[Vec3; 3]], ids: &[u32]) -> (Vec3, Vec3) {
    ids.iter().fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &i| {
        let t = &tris[i as usize];
        (lo.min(t[0]).min(t[1]).min(t[2]), hi.max(t[0]).max(t[1]).max(t[2]))
    })
}

impl Bvh {
    pub fn new(tris: Vec<[Vec3; 3]>) -> Self {
        let mut order: Vec<u32> = (0..tris.len() as u32).collect();
        let mut nodes = Vec::with_capacity(2 * tris.len() / LEAF + 1);
        let (lo, hi) = bounds(&tris, &order);
        nodes.push(Node { min: lo, max: hi, first: 0, count: order.len() as u32 });
        let mut stack = vec![0usize];
        while let Some(n) = stack.pop() {
            let Node { first, count, .. } = nodes[n];
            if count as usize <= LEAF {
                continue;
            }
            let ids = &mut order[first as usize..(first + count) as usize];
            let centroid = |i: &u32| (tris[*i as usize][0] + tris[*i as usize][1] + tris[*i as usize][2]) / 3.0;
            let (clo, chi) = ids
                .iter()
                .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(l, h), i| (l.min(centroid(i)), h.max(centroid(i))));
            let ext = chi - clo;
            let axis = if ext.x >= ext.y && ext.x >= ext.z {
                0
            } else if ext.y >= ext.z {
                1
            } else {
                2
            };
            let mid = ids.len() / 2;
            ids.select_nth_unstable_by(mid, |a, b| centroid(a)[axis].total_cmp(&centroid(b)[axis]));
            let left = nodes.len();
            for (f, c) in [(first, mid as u32), (first + mid as u32, count - mid as u32)] {
                let (lo, hi) = bounds(&tris, &order[f as usize..(f + c) as usize]);
                nodes.push(Node { min: lo, max: hi, first: f, count: c });
            }
            nodes[n].first = left as u32;
            nodes[n].count = 0;
            stack.push(left);
            stack.push(left + 1);
        }
        Bvh { nodes, order, tris }
    }

    fn slab(n: &Node, o: Vec3, inv: Vec3, t_max: f32) -> Option<f32> {
        let t0 = (n.min - o) * inv;
        let t1 = (n.max - o) * inv;
        let near = t0.min(t1).max_element().max(0.0);
        let far = t0.max(t1).min_element().min(t_max);
        (near <= far).then_some(near)
    }

    fn triangle(&self, i: u32, o: Vec3, d: Vec3) -> Option<(f32, f32, f32)> {
        let [a, b, c] = self.tris[i as usize];
        let (e1, e2) = (b - a, c - a);
        let p = d.cross(e2);
        let det = e1.dot(p);
        if det.abs() < 1e-12 {
            return None;
        }
        let inv = 1.0 / det;
        let s = o - a;
        let u = s.dot(p) * inv;
        if !(0.0..=1.0).contains(&u) {
            return None;
        }
        let q = s.cross(e1);
        let v = d.dot(q) * inv;
        if v < 0.0 || u + v > 1.0 {
            return None;
        }
        Some((e2.dot(q) * inv, u, v))
    }

    /// Nearest hit with `t_min < t < t_max`, or any hit when `any` (shadow rays).
    pub fn intersect(&self, o: Vec3, d: Vec3, t_min: f32, t_max: f32, any: bool) -> Option<Hit> {
        if self.tris.is_empty() {
            return None;
        }
        let inv = d.recip();
        let mut best: Option<Hit> = None;
        let mut limit = t_max;
        let mut stack = [0u32; 64];
        let mut sp = 1;
        while sp > 0 {
            sp -= 1;
            let n = &self.nodes[stack[sp] as usize];
            if Self::slab(n, o, inv, limit).is_none() {
                continue;
            }
            if n.count > 0 {
                for &i in &self.order[n.first as usize..(n.first + n.count) as usize] {
                    if let Some((t, u, v)) = self.triangle(i, o, d) {
                        if t > t_min && t < limit {
                            best = Some(Hit { t, tri: i, u, v });
                            if any {
                                return best;
                            }
                            limit = t;
                        }
                    }
                }
            } else if sp + 2 <= stack.len() {
                stack[sp] = n.first;
                stack[sp + 1] = n.first + 1;
                sp += 2;
            }
        }
        best
    }
}
