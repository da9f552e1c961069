//! CPU path tracer (rayon): the ground truth for image accuracy. Same scene, camera, lights and
//! materials as the renderer (Lambert plus the same GGX specular lobe, MTL Kd as linear albedo,
//! emission), written independently of the GPU code.
//!
//! Light arrives two ways, each sampled where it is cheap (Veach 1997):
//! - the scene's light (spot, directional or point) by a shadow ray at every vertex (next-event
//!   estimation);
//! - emissive triangles both by a shadow ray to a point on an emitter (chosen by power) and by
//!   the BSDF-sampled path hitting them, the two combined by multiple importance sampling
//!   (power heuristic), so a small bright quad such as the classic Cornell box's light converges.
//!
//! The path continues by sampling the BSDF: cosine-weighted for the Lambert lobe, GGX normal
//! distribution for the specular lobe, chosen by their reflectances.
//!
//! `bounces` counts indirect bounces of the scene's light: 0 is direct light only, 1 is direct
//! plus one bounce, what single-bounce cone tracing approximates. Emitted light is counted by
//! the same path length: it reaches the camera directly at 0 bounces, lights a surface at 1 (as
//! the renderer's cones gather it), and so on.

use glam::{Vec2, Vec3};
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};
use rayon::prelude::*;

use super::bvh::Bvh;
use crate::scene::{Light, Material, Scene, Texture};

#[derive(Clone, Copy, Debug, Default)]
pub struct RefOptions {
    pub bounces: u32,
    pub spp: u32,
    pub seed: u64,
    /// At the path's last vertex, also the light of emitters that the renderer lights the
    /// scene with as area lights (`Material::area_light`), reflected there: with `bounces` 0,
    /// direct light as the renderer counts it (an area light's reflection is direct light).
    pub area_lights_direct: bool,
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

/// An orthonormal tangent frame (t, b) around the unit normal `n`, continuous except where n.z
/// changes sign (Duff et al. 2017, "Building an Orthonormal Basis, Revisited"). The cone sets are
/// laid out in this frame (the renderer builds the same, `tangent_frame` in common/cone.glsl), so
/// a per-cone comparison splits the hemisphere as the renderer does.
pub fn tangent_frame(n: Vec3) -> (Vec3, Vec3) {
    let s = if n.z >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (s + n.z);
    let c = n.x * n.y * a;
    (Vec3::new(1.0 + s * n.x * n.x * a, s * c, -s * n.x), Vec3::new(c, s + n.y * n.y * a, -n.y))
}

/// What the camera ray through a pixel's centre hits first (a G-buffer on the CPU).
#[derive(Clone, Copy, Debug)]
pub struct PrimaryHit {
    pub material: u32,
    /// Geometric normal, turned towards the camera.
    pub normal: Vec3,
    pub position: Vec3,
}

pub struct PathTracer<'a> {
    scene: &'a Scene,
    bvh: Bvh,
    tri_material: Vec<u32>,
    /// sRGB-decoded albedo textures (linear RGB), indexed like `scene.textures`.
    textures: Vec<Vec<Vec3>>,
    emitters: Emitters,
}

const PI: f32 = std::f32::consts::PI;
const LUMA: Vec3 = Vec3::new(0.2126, 0.7152, 0.0722);

/// Emissive triangles, chosen with probability proportional to their power (area × luminance).
struct Emitters {
    tris: Vec<u32>,
    /// Running sum of power, normalized to end at 1.
    cdf: Vec<f32>,
    /// Total power (area × luminance) over all emitters.
    total: f32,
}

impl Emitters {
    fn new(scene: &Scene, tri_material: &[u32]) -> Self {
        let mut tris = Vec::new();
        let mut cdf = Vec::new();
        let mut total = 0.0f32;
        for (t, &m) in tri_material.iter().enumerate() {
            let le = scene.materials[m as usize].emissive.dot(LUMA);
            let [a, b, c] = scene.mesh.triangle(t);
            let area = 0.5 * (b - a).cross(c - a).length();
            if le > 0.0 && area > 0.0 && area.is_finite() {
                total += le * area;
                tris.push(t as u32);
                cdf.push(total);
            }
        }
        for c in &mut cdf {
            *c /= total.max(1e-30);
        }
        Emitters { tris, cdf, total }
    }

    /// Area density of sampling a point on an emitter of luminance `le`.
    fn pdf_area(&self, le: f32) -> f32 {
        le / self.total
    }
}

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
        Light::Point { position, intensity } => {
            let to = position - p;
            let d2 = to.length_squared().max(1e-12);
            (intensity / d2, to / d2.sqrt(), d2.sqrt())
        }
        // Its emitter's triangles are sampled instead (`emitter_sample`).
        Light::Area { center, .. } => (Vec3::ZERO, (center - p).normalize_or_zero(), 0.0),
    }
}

/// The lobes of a surface point: Lambert albedo and the specular F0.
struct Lobes {
    diffuse: Vec3,
    f0: Vec3,
    roughness: f32,
    /// Probability of sampling the specular lobe.
    p_spec: f32,
}

impl Lobes {
    fn new(m: &Material, albedo: Vec3) -> Self {
        let diffuse = albedo * (1.0 - m.metallic);
        let f0 = m.specular.lerp(albedo, m.metallic);
        let (d, s) = (diffuse.dot(LUMA).max(0.0), if f0.max_element() > 0.0 { f0.dot(LUMA).max(1e-3) } else { 0.0 });
        let p_spec = if d + s > 0.0 { s / (d + s) } else { 0.0 };
        Lobes { diffuse, f0, roughness: m.roughness, p_spec }
    }

    fn alpha(&self) -> f32 {
        self.roughness * self.roughness
    }

    fn ggx_d(&self, n_h: f32) -> f32 {
        let a2 = self.alpha() * self.alpha();
        let dd = n_h * n_h * (a2 - 1.0) + 1.0;
        a2 / (PI * dd * dd)
    }

    /// Diffuse plus GGX specular BRDF (the renderer's model: UE4's D, G and F).
    fn brdf(&self, n: Vec3, v: Vec3, l: Vec3) -> Vec3 {
        let n_l = n.dot(l);
        if n_l <= 0.0 {
            return Vec3::ZERO;
        }
        let diffuse = self.diffuse / PI;
        if self.f0.max_element() <= 0.0 {
            return diffuse;
        }
        let n_v = n.dot(v).max(1e-4);
        let h = (l + v).normalize();
        let r = self.roughness;
        let k = (r + 1.0) * (r + 1.0) / 8.0;
        let g = n_v / (n_v * (1.0 - k) + k) * n_l / (n_l * (1.0 - k) + k);
        let f = self.f0 + (Vec3::ONE - self.f0) * (1.0 - h.dot(v).clamp(0.0, 1.0)).powi(5);
        diffuse + self.ggx_d(n.dot(h).max(0.0)) * g * f / (4.0 * n_l * n_v)
    }

    /// Solid-angle density of [`Lobes::sample`] choosing `l`.
    fn pdf(&self, n: Vec3, v: Vec3, l: Vec3) -> f32 {
        let n_l = n.dot(l);
        if n_l <= 0.0 {
            return 0.0;
        }
        let mut pdf = (1.0 - self.p_spec) * n_l / PI;
        if self.p_spec > 0.0 {
            let h = (l + v).normalize();
            let v_h = v.dot(h).max(1e-6);
            pdf += self.p_spec * self.ggx_d(n.dot(h).max(0.0)) * n.dot(h).max(0.0) / (4.0 * v_h);
        }
        pdf
    }

    /// A direction drawn from the lobes (None below the horizon).
    fn sample(&self, n: Vec3, v: Vec3, rng: &mut SmallRng) -> Option<Vec3> {
        let (t, b) = n.any_orthonormal_pair();
        let u = Vec2::new(rng.gen(), rng.gen());
        let l = if rng.gen::<f32>() < self.p_spec {
            // GGX half vector: tan²θ = α² ξ / (1 − ξ).
            let a = self.alpha();
            let cos2 = (1.0 - u.x) / (1.0 + (a * a - 1.0) * u.x);
            let (cos_t, sin_t) = (cos2.sqrt(), (1.0 - cos2).max(0.0).sqrt());
            let phi = 2.0 * PI * u.y;
            let h = t * sin_t * phi.cos() + b * sin_t * phi.sin() + n * cos_t;
            2.0 * v.dot(h) * h - v
        } else {
            let r = u.x.sqrt();
            let phi = 2.0 * PI * u.y;
            t * r * phi.cos() + b * r * phi.sin() + n * (1.0 - u.x).max(0.0).sqrt()
        };
        (n.dot(l) > 0.0).then(|| l.normalize())
    }
}

/// Power-heuristic weight of a sample drawn with density `a` against another strategy's `b`.
fn power_heuristic(a: f32, b: f32) -> f32 {
    let (a2, b2) = (a * a, b * b);
    if a2 + b2 > 0.0 {
        a2 / (a2 + b2)
    } else {
        0.0
    }
}

/// A surface point of a path.
struct Vertex {
    p: Vec3,
    /// Geometric normal, facing the incoming ray.
    ng: Vec3,
    /// Shading normal, on the same side as `ng`.
    n: Vec3,
    material: u32,
    albedo: Vec3,
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
        let emitters = Emitters::new(scene, &tri_material);
        PathTracer { scene, bvh: Bvh::new(tris), tri_material, textures, emitters }
    }

    /// The surface point a ray hits, with its material inputs.
    fn hit(&self, o: Vec3, d: Vec3) -> Option<Vertex> {
        let mesh = &self.scene.mesh;
        let hit = self.bvh.intersect(o, d, 0.0, f32::INFINITY, false)?;
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
        let material = self.tri_material[t];
        let m = &self.scene.materials[material as usize];
        let mut albedo = m.albedo;
        if let Some(ti) = m.albedo_texture {
            albedo *= sample_texture(&self.scene.textures[ti], &self.textures[ti], uv);
        }
        Some(Vertex { p: o + d * hit.t, ng, n, material, albedo })
    }

    /// The first surface each pixel's centre ray meets (None where it sees nothing).
    pub fn primary_hits(&self) -> Vec<Option<PrimaryHit>> {
        let cam = &self.scene.camera;
        (0..cam.width * cam.height)
            .into_par_iter()
            .map(|i| {
                let (o, d) = cam.ray((i % cam.width) as f32, (i / cam.width) as f32);
                self.hit(o, d).map(|v| PrimaryHit { material: v.material, normal: v.ng, position: v.p })
            })
            .collect()
    }

    /// Light from a point on an emitter, drawn by power, reaching vertex `x` and reflected
    /// towards `v`, weighted against the BSDF sampling the same direction; `only_area`: the
    /// path ends here (no BSDF sample to weigh against), and only area-light emitters count.
    fn emitter_sample(
        &self,
        x: &Vertex,
        lobes: &Lobes,
        v: Vec3,
        eps: f32,
        only_area: bool,
        rng: &mut SmallRng,
    ) -> Vec3 {
        let e = &self.emitters;
        if e.tris.is_empty() {
            return Vec3::ZERO;
        }
        // One number for the whole search (drawing inside the predicate skewed the choice).
        let r = rng.gen::<f32>();
        let pick = e.cdf.partition_point(|&c| c < r).min(e.tris.len() - 1);
        let t = e.tris[pick] as usize;
        let [a, b, c] = self.scene.mesh.triangle(t);
        let (mut u, mut w) = (rng.gen::<f32>(), rng.gen::<f32>());
        if u + w > 1.0 {
            (u, w) = (1.0 - u, 1.0 - w);
        }
        let y = a + (b - a) * u + (c - a) * w;
        let ny = (b - a).cross(c - a).normalize_or_zero();
        let origin = x.p + x.ng * eps;
        let to = y - origin;
        let d2 = to.length_squared();
        if d2 <= eps * eps {
            return Vec3::ZERO;
        }
        let dist = d2.sqrt();
        let l = to / dist;
        let cos_y = ny.dot(l).abs();
        if cos_y <= 1e-6 || x.n.dot(l) <= 0.0 || x.ng.dot(l) <= 0.0 {
            return Vec3::ZERO;
        }
        if self.bvh.intersect(origin, l, 0.0, dist * (1.0 - 1e-4) - eps, true).is_some() {
            return Vec3::ZERO;
        }
        let m = &self.scene.materials[self.tri_material[t] as usize];
        if only_area && !m.area_light {
            return Vec3::ZERO;
        }
        let le = m.emissive;
        let pdf_light = e.pdf_area(le.dot(LUMA)) * d2 / cos_y;
        let weight = if only_area { 1.0 } else { power_heuristic(pdf_light, lobes.pdf(x.n, v, l)) };
        lobes.brdf(x.n, v, l) * x.n.dot(l) * le * weight / pdf_light
    }

    /// One path's radiance along the camera ray (o, d).
    fn radiance(&self, mut o: Vec3, mut d: Vec3, bounces: u32, area_direct: bool, rng: &mut SmallRng) -> Vec3 {
        let mesh = &self.scene.mesh;
        let scale = mesh.bounds.size().length().max(1e-3);
        let eps = 1e-4 * scale;
        let (mut l_sum, mut throughput) = (Vec3::ZERO, Vec3::ONE);
        // Density of the BSDF sample that made the current ray (None: the camera ray).
        let mut bsdf_pdf: Option<f32> = None;
        for bounce in 0..=bounces {
            // Origins are offset along the normal, so no minimum distance is needed (one would let
            // rays leaving near an edge pass through the adjacent face).
            let Some(x) = self.hit(o, d) else { break };
            let m = &self.scene.materials[x.material as usize];
            if m.emissive.max_element() > 0.0 {
                let weight = match bsdf_pdf {
                    None => 1.0,
                    Some(pdf) => {
                        let cos_y = x.ng.dot(-d).abs().max(1e-6);
                        let d2 = (x.p - o).length_squared();
                        power_heuristic(pdf, self.emitters.pdf_area(m.emissive.dot(LUMA)) * d2 / cos_y)
                    }
                };
                l_sum += throughput * m.emissive * weight;
            }
            let v = -d;
            let lobes = Lobes::new(m, x.albedo);
            // Next-event estimation towards the scene's lights.
            let origin = x.p + x.ng * eps;
            for light in &self.scene.lights {
                let (e, l, dist) = light_at(light, origin);
                if e.max_element() > 0.0 && x.n.dot(l) > 0.0 && x.ng.dot(l) > 0.0 {
                    let blocked = self.bvh.intersect(origin, l, 0.0, dist - eps, true).is_some();
                    if !blocked {
                        l_sum += throughput * lobes.brdf(x.n, v, l) * x.n.dot(l) * e;
                    }
                }
            }
            if bounce == bounces {
                if area_direct {
                    l_sum += throughput * self.emitter_sample(&x, &lobes, v, eps, true, rng);
                }
                break;
            }
            // An emitter seen from here is one bounce further along the path.
            l_sum += throughput * self.emitter_sample(&x, &lobes, v, eps, false, rng);
            let Some(next) = lobes.sample(x.n, v, rng) else { break };
            if next.dot(x.ng) <= 0.0 {
                break;
            }
            let pdf = lobes.pdf(x.n, v, next);
            if pdf <= 0.0 {
                break;
            }
            throughput *= lobes.brdf(x.n, v, next) * x.n.dot(next) / pdf;
            if throughput.max_element() <= 0.0 || !throughput.is_finite() {
                break;
            }
            bsdf_pdf = Some(pdf);
            (o, d) = (origin, next);
        }
        l_sum
    }

    /// The light arriving at the surface a pixel's centre ray meets, split among the cells of a
    /// cone set (`vct bench --accuracy --per-cone`). `cells` are unit directions in the surface's
    /// tangent frame (z along the normal; x and y as [`tangent_frame`] builds them), each standing
    /// for the directions nearer to it than to any other. Draws `samples` cosine-weighted
    /// directions and returns the surface's albedo and, for each cell, the radiance arriving along
    /// the draws that fall in it, summed and divided by `samples`: the cell's share of the
    /// cosine-weighted mean incoming radiance (E/π), which the cells' shares sum to. The arriving
    /// light is what `bounces - 1` further bounces bring (0: the direct light of the surfaces it
    /// meets, and their emission, except an area light's, which the renderer counts as direct).
    /// None where the ray meets nothing.
    pub fn incoming_by_cell(
        &self,
        pixel: (u32, u32),
        cells: &[Vec3],
        bounces: u32,
        samples: u32,
        seed: u64,
    ) -> Option<(Vec3, Vec<Vec3>)> {
        let (o, d) = self.scene.camera.ray(pixel.0 as f32, pixel.1 as f32);
        let x = self.hit(o, d)?;
        let eps = 1e-4 * self.scene.mesh.bounds.size().length().max(1e-3);
        let origin = x.p + x.ng * eps;
        let (t, b) = tangent_frame(x.n);
        let area_lights = self.scene.materials.iter().any(|m| m.area_light);
        let mut rng = SmallRng::seed_from_u64(seed);
        let mut sums = vec![Vec3::ZERO; cells.len()];
        for _ in 0..samples {
            // Cosine-weighted: a uniform point on the unit disc, lifted to the hemisphere.
            let (r, phi) = (rng.gen::<f32>().sqrt(), std::f32::consts::TAU * rng.gen::<f32>());
            let local = Vec3::new(r * phi.cos(), r * phi.sin(), (1.0 - r * r).max(0.0).sqrt());
            let dir = (t * local.x + b * local.y + x.n * local.z).normalize();
            if dir.dot(x.ng) <= 0.0 {
                continue;
            }
            let Some(cell) = (0..cells.len()).max_by(|&i, &j| local.dot(cells[i]).total_cmp(&local.dot(cells[j])))
            else {
                return Some((x.albedo, sums));
            };
            let mut l = self.radiance(origin, dir, bounces.saturating_sub(1), false, &mut rng);
            if let Some(y) = self.hit(origin, dir).filter(|_| area_lights) {
                let m = &self.scene.materials[y.material as usize];
                if m.area_light {
                    l -= m.emissive;
                }
            }
            sums[cell] += l;
        }
        Some((x.albedo, sums.into_iter().map(|s| s / samples.max(1) as f32).collect()))
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
                            let l = self.radiance(o, d, opts.bounces, opts.area_lights_direct, &mut rng);
                            sum += l;
                            let lum = l.dot(LUMA);
                            sum2 += lum * lum;
                        }
                        let mean = sum / spp as f32;
                        let lum = mean.dot(LUMA);
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
        let mean = pixels.iter().map(|p| p.0.dot(LUMA)).sum::<f32>() / n;
        RefImage {
            width: w,
            height: h,
            radiance: pixels.into_iter().map(|p| p.0).collect(),
            std_error,
            relative_noise: if mean > 0.0 { std_error / mean } else { 0.0 },
        }
    }
}
