//! CPU path tracer (rayon): the ground truth for image accuracy. Same scene, camera, light and
//! materials as the renderer (Lambert plus the same GGX specular lobe, MTL Kd as linear albedo,
//! emission), written independently of the GPU code. The point or directional light is sampled
//! by a shadow ray at every vertex (next-event estimation); the path continues by cosine-weighted
//! hemisphere sampling. `bounces` counts indirect bounces: 0 is direct light only, 1 is direct
//! plus one bounce — what voxel cone tracing approximates.

use glam::{Vec2, Vec3};
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};
use rayon::prelude::*;

use super::bvh::Bvh;
use crate::scene::{Light, Material, Scene, Texture};

#[derive(Clone, Copy, Debug)]
pub struct RefOptions {
    pub bounces: u32,
    pub spp: u32,
    pub seed: u64,
}

/// A rendered reference: linear radiance per pixel plus its noise.
pub struct RefImage {
    pub width: u32,
    pub height: u32,
    pub radiance: Vec<Vec3>,
    /// Mean over pixels of the standard error of the pixel mean (radiance units).
    pub std_error: f32,
    /// `std_error` over the mean radiance.
    pub relative_noise: f32,
}

pub struct PathTracer<'a> {
    scene: &'a Scene,
    bvh: Bvh,
    tri_material: Vec<u32>,
    /// sRGB-decoded albedo textures (linear RGB), indexed like `scene.textures`.
    textures: Vec<Vec<Vec3>>,
}

const PI: f32 = std::f32::consts::PI;

fn srgb_to_linear(c: u8) -> f32 {
    let c = c as f32 / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

fn sample_texture(tex: &Texture, texels: &[Vec3], uv: Vec2) -> Vec3 {
    let x = ((uv.x.rem_euclid(1.0)) * tex.width as f32) as u32 % tex.width;
    let y = ((uv.y.rem_euclid(1.0)) * tex.height as f32) as u32 % tex.height;
    texels[(y * tex.width + x) as usize]
}

/// Irradiance on a surface facing the light, and the unit direction and distance to it.
fn light_at(light: &Light, p: Vec3) -> (Vec3, Vec3, f32) {
    match *light {
        Light::Directional { direction, irradiance } => (irradiance, -direction, f32::INFINITY),
        Light::Spot { position, direction, intensity, inner_deg, outer_deg } => {
            let to = position - p;
            let d2 = to.length_squared().max(1e-12);
            let l = to / d2.sqrt();
            let angle = (-l).dot(direction).clamp(-1.0, 1.0).acos().to_degrees();
            (intensity * Light::spot_falloff(angle, inner_deg, outer_deg) / d2, l, d2.sqrt())
        }
    }
}

/// Diffuse plus GGX specular BRDF (the renderer's model: UE4's D, G and F).
fn brdf(m: &Material, albedo: Vec3, n: Vec3, v: Vec3, l: Vec3) -> Vec3 {
    let n_l = n.dot(l);
    if n_l <= 0.0 {
        return Vec3::ZERO;
    }
    let diffuse = albedo * (1.0 - m.metallic) / PI;
    let f0 = m.specular.lerp(albedo, m.metallic);
    if f0.max_element() <= 0.0 {
        return diffuse;
    }
    let n_v = n.dot(v).max(1e-4);
    let h = (l + v).normalize();
    let r = m.roughness;
    let a2 = (r * r) * (r * r);
    let n_h = n.dot(h).max(0.0);
    let dd = n_h * n_h * (a2 - 1.0) + 1.0;
    let d = a2 / (PI * dd * dd);
    let k = (r + 1.0) * (r + 1.0) / 8.0;
    let g = n_v / (n_v * (1.0 - k) + k) * n_l / (n_l * (1.0 - k) + k);
    let f = f0 + (Vec3::ONE - f0) * (1.0 - h.dot(v).clamp(0.0, 1.0)).powi(5);
    diffuse + d * g * f / (4.0 * n_l * n_v)
}

fn cosine_sample(n: Vec3, u: Vec2) -> Vec3 {
    let (t, b) = n.any_orthonormal_pair();
    let r = u.x.sqrt();
    let phi = 2.0 * PI * u.y;
    (t * r * phi.cos() + b * r * phi.sin() + n * (1.0 - u.x).max(0.0).sqrt()).normalize()
}

impl<'a> PathTracer<'a> {
    pub fn new(scene: &'a Scene) -> Self {
        let mesh = &scene.mesh;
        let tris: Vec<[Vec3; 3]> = (0..mesh.triangle_count()).map(|t| mesh.triangle(t)).collect();
        let mut tri_material = vec![0u32; tris.len()];
        for d in &mesh.draws {
            for t in d.first_index / 3..(d.first_index + d.index_count) / 3 {
                tri_material[t as usize] = d.material;
            }
        }
        let textures = scene
            .textures
            .iter()
            .map(|t| {
                t.rgba
                    .chunks_exact(4)
                    .map(|p| Vec3::new(srgb_to_linear(p[0]), srgb_to_linear(p[1]), srgb_to_linear(p[2])))
                    .collect()
            })
            .collect();
        PathTracer { scene, bvh: Bvh::new(tris), tri_material, textures }
    }

    /// One path's radiance along the camera ray (o, d).
    fn radiance(&self, mut o: Vec3, mut d: Vec3, bounces: u32, rng: &mut SmallRng) -> Vec3 {
        let mesh = &self.scene.mesh;
        let scale = mesh.bounds.size().length().max(1e-3);
        let eps = 1e-4 * scale;
        let (mut l_sum, mut throughput) = (Vec3::ZERO, Vec3::ONE);
        for bounce in 0..=bounces {
            // Origins are offset along the normal, so no minimum distance is needed (one would let
            // rays leaving near an edge pass through the adjacent face).
            let Some(hit) = self.bvh.intersect(o, d, 0.0, f32::INFINITY, false) else { break };
            let t = hit.tri as usize;
            let idx = &mesh.indices[3 * t..3 * t + 3];
            let vtx = |k: usize| &mesh.vertices[idx[k] as usize];
            let w = Vec3::new(1.0 - hit.u - hit.v, hit.u, hit.v);
            let [a, b, c] = mesh.triangle(t);
            let mut ng = (b - a).cross(c - a).normalize_or_zero();
            let mut n =
                (Vec3::from(vtx(0).normal) * w.x + Vec3::from(vtx(1).normal) * w.y + Vec3::from(vtx(2).normal) * w.z)
                    .normalize_or(ng);
            let uv = Vec2::from(vtx(0).uv) * w.x + Vec2::from(vtx(1).uv) * w.y + Vec2::from(vtx(2).uv) * w.z;
            // Two-sided surfaces, as the renderer shades them.
            if ng.dot(d) > 0.0 {
                ng = -ng;
            }
            if n.dot(ng) < 0.0 {
                n = -n;
            }
            let m = &self.scene.materials[self.tri_material[t] as usize];
            let mut albedo = m.albedo;
            if let Some(ti) = m.albedo_texture {
                albedo *= sample_texture(&self.scene.textures[ti], &self.textures[ti], uv);
            }
            let p = o + d * hit.t;
            let v = -d;
            l_sum += throughput * m.emissive;
            // Next-event estimation towards the light.
            let origin = p + ng * eps;
            let (e, l, dist) = light_at(&self.scene.light, origin);
            if e.max_element() > 0.0 && n.dot(l) > 0.0 && ng.dot(l) > 0.0 {
                let blocked = self.bvh.intersect(origin, l, 0.0, dist - eps, true).is_some();
                if !blocked {
                    l_sum += throughput * brdf(m, albedo, n, v, l) * n.dot(l) * e;
                }
            }
            if bounce == bounces {
                break;
            }
            let next = cosine_sample(n, Vec2::new(rng.gen(), rng.gen()));
            if next.dot(ng) <= 0.0 {
                break;
            }
            // brdf * cos / pdf, with pdf = cos / pi.
            throughput *= brdf(m, albedo, n, v, next) * PI;
            if throughput.max_element() <= 0.0 {
                break;
            }
            (o, d) = (origin, next);
        }
        l_sum
    }

    /// Renders the scene's camera view; `progress` is called with each finished row count.
    pub fn render(&self, opts: RefOptions, progress: &(dyn Fn(u64) + Sync)) -> RefImage {
        let cam = &self.scene.camera;
        let (w, h) = (cam.width, cam.height);
        let spp = opts.spp.max(1);
        let rows: Vec<Vec<(Vec3, f32)>> = (0..h)
            .into_par_iter()
            .map(|y| {
                let row = (0..w)
                    .map(|x| {
                        let mut rng = SmallRng::seed_from_u64(
                            opts.seed ^ ((y as u64) << 32 | x as u64).wrapping_mul(0x9E3779B97F4A7C15),
                        );
                        let (mut sum, mut sum2) = (Vec3::ZERO, 0.0f32);
                        for _ in 0..spp {
                            let (jx, jy): (f32, f32) =
                                if spp == 1 { (0.0, 0.0) } else { (rng.gen::<f32>() - 0.5, rng.gen::<f32>() - 0.5) };
                            let (o, d) = cam.ray(x as f32 + jx, y as f32 + jy);
                            let l = self.radiance(o, d, opts.bounces, &mut rng);
                            sum += l;
                            let lum = l.dot(Vec3::new(0.2126, 0.7152, 0.0722));
                            sum2 += lum * lum;
                        }
                        let mean = sum / spp as f32;
                        let lum = mean.dot(Vec3::new(0.2126, 0.7152, 0.0722));
                        let var = if spp > 1 {
                            ((sum2 / spp as f32 - lum * lum) * spp as f32 / (spp - 1) as f32).max(0.0)
                        } else {
                            0.0
                        };
                        (mean, (var / spp as f32).sqrt())
                    })
                    .collect();
                progress(1);
                row
            })
            .collect();
        let pixels: Vec<(Vec3, f32)> = rows.into_iter().flatten().collect();
        let n = pixels.len().max(1) as f32;
        let std_error = pixels.iter().map(|p| p.1).sum::<f32>() / n;
        let mean = pixels.iter().map(|p| p.0.dot(Vec3::new(0.2126, 0.7152, 0.0722))).sum::<f32>() / n;
        RefImage {
            width: w,
            height: h,
            radiance: pixels.into_iter().map(|p| p.0).collect(),
            std_error,
            relative_noise: if mean > 0.0 { std_error / mean } else { 0.0 },
        }
    }
}
