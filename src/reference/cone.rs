//! CPU model of one voxel cone trace (Freed 2018 Listing 4.1 as `shaders-glsl/common/cone.glsl`
//! implements it), with Vulkan's sampling rules written out: trilinear filtering within a mip
//! level (texel centres at (i + 0.5)/n, clamp-to-border transparent black) and linear blending
//! between levels. Tests compare it with the GPU on a small synthetic volume.

use glam::{Vec3, Vec4};

/// A mip chain of RGBA volumes: `levels[l]` holds (n >> l)³ texels, x fastest.
pub struct MipVolume {
    pub n: u32,
    pub levels: Vec<Vec<Vec4>>,
}

#[derive(Clone, Copy, Debug)]
pub struct ConeParams {
    pub steps: i32,
    pub bias: f32,
    pub start: f32,
    pub lod_offset: f32,
    /// Step length over the sampled level's texel size.
    pub step: f32,
    /// Correct opacity for the step length (Crassin et al. 2011).
    pub opacity_correction: bool,
    /// Keep the sampled level's filter off the receiving surface.
    pub self_clamp: bool,
}

impl MipVolume {
    fn texel(&self, level: usize, x: i64, y: i64, z: i64) -> Vec4 {
        let n = (self.n >> level).max(1) as i64;
        if x < 0 || y < 0 || z < 0 || x >= n || y >= n || z >= n {
            return Vec4::ZERO;
        }
        self.levels[level][(x + n * (y + n * z)) as usize]
    }

    /// Trilinear sample of one level at normalized coordinates.
    pub fn sample_level(&self, level: usize, p: Vec3) -> Vec4 {
        let n = (self.n >> level).max(1) as f32;
        let q = p * n - 0.5;
        let b = q.floor();
        let f = q - b;
        let (bx, by, bz) = (b.x as i64, b.y as i64, b.z as i64);
        let mut acc = Vec4::ZERO;
        for corner in 0..8 {
            let (dx, dy, dz) = (corner & 1, (corner >> 1) & 1, corner >> 2);
            let w = if dx == 1 { f.x } else { 1.0 - f.x }
                * if dy == 1 { f.y } else { 1.0 - f.y }
                * if dz == 1 { f.z } else { 1.0 - f.z };
            acc += w * self.texel(level, bx + dx, by + dy, bz + dz);
        }
        acc
    }

    /// `textureLod` with a linear mip filter, the level clamped to the chain.
    pub fn sample(&self, p: Vec3, lod: f32) -> Vec4 {
        let max = (self.levels.len() - 1) as f32;
        let lod = lod.clamp(0.0, max);
        let (l0, t) = (lod.floor(), lod.fract());
        let a = self.sample_level(l0 as usize, p);
        if t == 0.0 {
            return a;
        }
        a * (1.0 - t) + self.sample_level((l0 as usize + 1).min(max as usize), p) * t
    }

    /// Accumulated (radiance, opacity) along a cone of half-aperture tangent `tan_half`;
    /// mirrors `trace_cone` in cone.glsl.
    pub fn trace_cone(&self, uvw: Vec3, normal: Vec3, dir: Vec3, tan_half: f32, p: ConeParams) -> Vec4 {
        let scale = 1.0 / self.n as f32;
        let start = uvw + p.bias * normal * scale;
        let mut dist = p.start;
        let rise = dir.dot(normal);
        let (mut color, mut alpha) = (Vec3::ZERO, 0.0f32);
        let mut i = 0;
        while i < p.steps && alpha < 0.95 {
            let diameter = (2.0 * dist * tan_half).max(1.0);
            let pos = start + dist * dir * scale;
            let mut l = diameter.log2() + p.lod_offset;
            if p.self_clamp {
                // The sample's trilinear filter stays off its own surface's texels.
                let height = p.bias + dist * rise;
                // A point on the surface; the blended level above must stay clear too.
                l = l.min(((height - 0.5) / 1.5).max(1.0).log2() - 1.0);
            }
            // No coarser than the chain's last level (the texel stops growing with the cone).
            let l = l.clamp(0.0, (self.levels.len() - 1) as f32);
            // Inside while the sample's filter reaches the volume: half a texel of its level.
            let reach = 0.5 * l.exp2() * scale;
            if pos.min_element() <= -reach || pos.max_element() >= 1.0 + reach {
                break;
            }
            let step = p.step * l.exp2();
            let mut s = self.sample(pos, l);
            if p.opacity_correction && s.w > 1e-6 {
                let a = 1.0 - (1.0 - s.w).max(0.0).powf(step / l.exp2());
                s = (s.truncate() * (a / s.w)).extend(a);
            }
            let a = 1.0 - alpha;
            color += s.truncate() * a;
            alpha += a * s.w;
            dist += step;
            i += 1;
        }
        if alpha >= 0.95 {
            return (color / alpha).extend(1.0);
        }
        color.extend(alpha)
    }
}
