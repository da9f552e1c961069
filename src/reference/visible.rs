//! The voxels a camera sees, on the CPU: one ray through each pixel centre (the BVH of the path
//! tracer), and the voxel its nearest hit lies in. It judges the point voxelizer's refinement
//! (Mavridis & Papaioannou 2011 §3.2), which promises no holes where the camera looks. A hit
//! within `eps` voxels of a voxel face requires one of the two voxels beside the face (a pair,
//! as the exact coverage judges faces on boundaries); one near an edge or corner requires none.

use glam::{DVec3, Vec3};

use super::bvh::Bvh;
use super::coverage::{Coverage, RefGrid};
use crate::scene::Camera;

impl RefGrid {
    /// The voxels `camera` sees of `triangles` at its pixel centres, as a coverage whose
    /// recall is the share of them a volume holds (every voxel is allowed: this judges recall
    /// only; the exact coverage judges precision).
    pub fn visible(&self, triangles: &[[Vec3; 3]], camera: &Camera, eps: f64) -> Coverage {
        let len = self.dims.iter().map(|&d| d as usize).product();
        let mut required = vec![false; len];
        let mut pairs = Vec::new();
        let bvh = Bvh::new(triangles.to_vec());
        let n = DVec3::from(self.dims.map(|d| d as f64));
        // The voxel that grid coordinate `x` along `a` lies in (a warped grid's by its faces).
        let faces = if self.perspective.is_some() {
            std::array::from_fn(|a| (0..=self.dims[a]).map(f64::from).collect())
        } else {
            self.faces()
        };
        let cell = |v: DVec3| {
            DVec3::from(std::array::from_fn::<f64, 3, _>(|a| faces[a].partition_point(|&f| f <= v[a]) as f64 - 1.0))
        };
        for y in 0..camera.height {
            for x in 0..camera.width {
                let (o, d) = camera.ray(x as f32, y as f32);
                let Some(hit) = bvh.intersect(o, d, 0.0, f32::INFINITY, false) else { continue };
                let at_hit = o + d * hit.t;
                let q = match self.perspective {
                    // A perspective grid's texels are unit cells among the texels (coverage.rs).
                    Some(p) => {
                        let h = p.world_to_texel * at_hit.as_dvec3().extend(1.0);
                        if h.w <= p.clip {
                            continue;
                        }
                        h.truncate() / h.w
                    }
                    None => ((at_hit - self.origin) / self.voxel).as_dvec3(),
                };
                let (lo, hi) = (cell(q - eps), cell(q + eps));
                if lo.cmplt(DVec3::ZERO).any() || hi.cmpge(n).any() {
                    continue;
                }
                let at = |v: DVec3| self.index(v.x as u32, v.y as u32, v.z as u32);
                match (hi - lo).element_sum() as u32 {
                    0 => required[at(lo)] = true,
                    1 => pairs.push((at(lo), at(hi))),
                    _ => {}
                }
            }
        }
        pairs.sort_unstable();
        pairs.dedup();
        Coverage { dims: self.dims, required, allowed: vec![true; len], pairs }
    }
}
