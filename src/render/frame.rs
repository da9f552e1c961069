//! Per-frame uniforms (`FrameUniforms`, laid out in `scene::gpu`), filled from the scene, and the
//! camera and light matrices they carry: a perspective shadow frustum for spot lights, an
//! orthographic one fitted to the scene bounds for directional lights (Freed 2018 §4.2).

use glam::{Mat4, Vec3, Vec4};

use crate::config;
pub use crate::scene::gpu::{FrameUniforms, LightGpu};
use crate::scene::{flip_y, Aabb, Camera, GiSettings, Light};
use crate::voxel::VoxelGrid;

/// What the frame shows besides the full image (the GI debug views).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum View {
    #[default]
    Full,
    Direct,
    Indirect,
    Diffuse,
    Specular,
    Ao,
    Voxels,
    /// The filtered radiance volume at one mip level.
    Radiance(u32),
    /// The texel size the cones sample at each surface, against an even grid's voxel (a warped
    /// grid, Freed 2018 Figure 5.7): green even, blue finer, red coarser.
    Texels,
}

impl std::str::FromStr for View {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Ok(match s {
            "full" => View::Full,
            "direct" => View::Direct,
            "indirect" => View::Indirect,
            "diffuse" => View::Diffuse,
            "specular" => View::Specular,
            "ao" => View::Ao,
            "voxels" => View::Voxels,
            "texels" => View::Texels,
            _ => match s.strip_prefix("radiance:").map(str::parse::<u32>) {
                Some(Ok(level)) => View::Radiance(level),
                _ => {
                    return Err(format!(
                        "unknown view '{s}' (full|direct|indirect|diffuse|specular|ao|voxels|texels|radiance:LEVEL)"
                    ))
                }
            },
        })
    }
}

impl View {
    pub fn code(self) -> u32 {
        match self {
            View::Full => config::VIEW_FULL,
            View::Direct => config::VIEW_DIRECT,
            View::Indirect => config::VIEW_INDIRECT,
            View::Diffuse => config::VIEW_DIFFUSE,
            View::Specular => config::VIEW_SPECULAR,
            View::Ao => config::VIEW_AO,
            View::Voxels => config::VIEW_VOXELS,
            View::Radiance(_) => config::VIEW_RADIANCE,
            View::Texels => config::VIEW_TEXELS,
        }
    }
    /// Views drawn by marching the voxel volume instead of shading the surfaces.
    pub fn is_volume(self) -> bool {
        matches!(self, View::Voxels | View::Radiance(_))
    }
    /// Views already in [0, 1] that skip the c/(c+1) tone curve.
    pub fn is_raw(self) -> bool {
        matches!(self, View::Ao | View::Voxels | View::Texels)
    }
}

/// Per-frame state beyond the scene: the voxel grid, GI settings and the view.
pub struct FrameState<'a> {
    pub grid: &'a VoxelGrid,
    pub mip_levels: u32,
    pub gi: &'a GiSettings,
    /// Cones in the surfaces' and in the voxel bounce's set (`scene::cones`).
    pub cone_count: u32,
    pub bounce_cone_count: u32,
    pub gi_on: bool,
    pub view: View,
    pub first_frame: bool,
    /// The previous frame's grid origin (a following volume moves it).
    pub previous_origin: Vec3,
    /// The previous frame's world-to-clip matrix (this frame's with no previous frame).
    pub previous_view_proj: Option<Mat4>,
    /// The reduced-resolution diffuse cones' traced pixel and history (render::deferred::Jitter).
    pub gi_jitter: Vec4,
}

pub use crate::scene::depth_range;

/// The six faces of a point light's cube shadow map at `position`: each a 90° frustum along
/// +x, -x, +y, -y, +z, -z (the layer of the same index), reaching the bounds' far side.
pub fn point_faces(position: Vec3, bounds: &Aabb) -> [Mat4; 6] {
    let (near, far) = depth_range(position, bounds);
    let proj = flip_y(Mat4::perspective_rh(std::f32::consts::FRAC_PI_2, 1.0, near.max(far * 2e-3), far));
    CUBE_AXES.map(|d| {
        let up = if d.y != 0.0 { Vec3::Z } else { Vec3::Y };
        proj * Mat4::look_at_rh(position, position + d, up)
    })
}

/// World size of one shadow-map texel at the farthest scene point each of the light's layers
/// sees (injection's stride follows it), or None for a layer that sees nothing the light
/// lights. A point or area light's cube faces each have their own: a face's texel at depth d is
/// 2 d / resolution wide (90°), and the faces that look at near walls need fewer texels than
/// the one that looks down the room; an area light's faces wholly behind its quad see nothing
/// it lights (the classic Cornell box's quad: its upward face).
pub fn layer_texel_sizes(light: &Light, bounds: &Aabb, resolution: u32) -> Vec<Option<f32>> {
    let radius = bounds.size().length() * 0.5;
    let res = resolution as f32;
    match *light {
        Light::Directional { .. } => vec![Some(2.0 * radius * 1.01 / res)],
        Light::Spot { position, outer_deg, .. } => {
            let far = (bounds.center() - position).length() + radius;
            vec![Some(2.0 * far * ((outer_deg + 1.0).to_radians()).tan() / res)]
        }
        Light::Point { position: at, .. } | Light::Area { center: at, .. } => {
            let lit_side = light.lit_side();
            let corners: Vec<Vec3> = (0..8)
                .map(|i| {
                    let pick = |bit: usize, lo: f32, hi: f32| if i & bit == 0 { lo } else { hi };
                    let (lo, hi) = (bounds.min, bounds.max);
                    Vec3::new(pick(1, lo.x, hi.x), pick(2, lo.y, hi.y), pick(4, lo.z, hi.z))
                })
                .collect();
            CUBE_AXES
                .iter()
                .map(|&a| {
                    // The face's directions are a + s u + t v, |s|, |t| <= 1 (u, v the other
                    // axes): the largest cosine with the lit side is a.n + |u.n| + |v.n|.
                    if let Some(n) = lit_side {
                        if a.dot(n) + (n.abs().dot(Vec3::ONE) - a.dot(n).abs()) <= 0.0 {
                            return None;
                        }
                    }
                    let depth = corners.iter().map(|c| (*c - at).dot(a)).fold(f32::MIN, f32::max);
                    (depth > 0.0).then(|| 2.0 * depth / res)
                })
                .collect()
        }
    }
}

/// The axes of a cube shadow map's faces, in layer order (`point_faces`).
const CUBE_AXES: [Vec3; 6] = [Vec3::X, Vec3::NEG_X, Vec3::Y, Vec3::NEG_Y, Vec3::Z, Vec3::NEG_Z];

/// World-to-clip matrix of the light's shadow map (a point light's: its first cube face).
pub fn light_view_proj(light: &Light, bounds: &Aabb) -> Mat4 {
    let up_for = |d: Vec3| if d.y.abs() > 0.99 { Vec3::Z } else { Vec3::Y };
    match *light {
        Light::Point { position: at, .. } | Light::Area { center: at, .. } => point_faces(at, bounds)[0],
        Light::Spot { position, direction, outer_deg, .. } => {
            let view = Mat4::look_at_rh(position, position + direction, up_for(direction));
            let (near, far) = depth_range(position, bounds);
            let fov = (2.0 * outer_deg + 2.0).min(170.0).to_radians();
            flip_y(Mat4::perspective_rh(fov, 1.0, near.max(far * 2e-3), far)) * view
        }
        Light::Directional { direction, .. } => {
            let (center, radius) = if bounds.is_empty() {
                (Vec3::ZERO, 1.0)
            } else {
                (bounds.center(), (bounds.size().length() * 0.5).max(1e-3) * 1.01)
            };
            let eye = center - direction * radius * 2.0;
            let view = Mat4::look_at_rh(eye, center, up_for(direction));
            flip_y(Mat4::orthographic_rh(-radius, radius, -radius, radius, radius * 0.5, radius * 3.5)) * view
        }
    }
}

/// Shadow-map layers of a light: six cube faces for a point or area light, else one.
pub fn shadow_layers(light: &Light) -> u32 {
    if light.cube_origin().is_some() {
        6
    } else {
        1
    }
}

/// Each light's world-to-clip matrices, one per shadow-map layer, in light order.
fn layer_matrices(light: &Light, bounds: &Aabb) -> Vec<Mat4> {
    match light.cube_origin() {
        Some(at) => point_faces(at, bounds).to_vec(),
        None => vec![light_view_proj(light, bounds)],
    }
}

impl FrameUniforms {
    /// `lights`: the shadowed lights (emitters light the scene besides); at most MAX_LIGHTS,
    /// with MAX_SHADOW_LAYERS layers in all (scene loading enforces both).
    pub fn new(camera: &Camera, lights: &[Light], bounds: &Aabb, shadow_resolution: u32, f: &FrameState) -> Self {
        let mut gpu_lights = [LightGpu::default(); config::MAX_LIGHTS as usize];
        let mut light_layers = [Mat4::IDENTITY; config::MAX_SHADOW_LAYERS as usize];
        let mut layer = 0usize;
        let texel = 1.0 / shadow_resolution as f32;
        let lights = &lights[..lights.len().min(gpu_lights.len())];
        for (g, light) in gpu_lights.iter_mut().zip(lights) {
            let first = layer as f32;
            *g = match *light {
                Light::Spot { position, direction, intensity, inner_deg, outer_deg } => LightGpu {
                    position: position.extend(config::LIGHT_SPOT as f32),
                    direction: direction.normalize().extend(0.0),
                    color: intensity.extend(0.0),
                    cone: Vec4::new(inner_deg.to_radians(), outer_deg.to_radians(), texel, first),
                    ..Default::default()
                },
                Light::Directional { direction, irradiance } => LightGpu {
                    position: Vec4::new(0.0, 0.0, 0.0, config::LIGHT_DIRECTIONAL as f32),
                    direction: direction.normalize().extend(0.0),
                    color: irradiance.extend(0.0),
                    cone: Vec4::new(0.0, 0.0, texel, first),
                    ..Default::default()
                },
                Light::Point { position, intensity } => LightGpu {
                    position: position.extend(config::LIGHT_POINT as f32),
                    direction: Vec4::new(0.0, -1.0, 0.0, 0.0),
                    color: intensity.extend(0.0),
                    cone: Vec4::new(0.0, 0.0, texel, first),
                    ..Default::default()
                },
                Light::Area { center, half_u, half_v, radiance } => LightGpu {
                    position: center.extend(config::LIGHT_AREA as f32),
                    direction: light.lit_side().unwrap_or_default().extend(0.0),
                    color: radiance.extend(0.0),
                    cone: Vec4::new(0.0, 0.0, texel, first),
                    half_u: half_u.extend(0.0),
                    half_v: half_v.extend(0.0),
                },
            };
            for m in layer_matrices(light, bounds) {
                if let Some(slot) = light_layers.get_mut(layer) {
                    *slot = m;
                }
                layer += 1;
            }
        }
        let view_proj = camera.view_proj(bounds);
        let level = match f.view {
            View::Radiance(l) => l.min(f.mip_levels.saturating_sub(1)),
            _ => 0,
        };
        let (clip, clip_levels, clip_scene) = f.grid.clip.map_or(Default::default(), |c| c.gpu());
        FrameUniforms {
            view_proj,
            inv_view_proj: view_proj.inverse(),
            camera_pos: camera.eye.extend(1.0),
            viewport: Vec4::new(camera.width as f32, camera.height as f32, 0.0, 0.0),
            voxel_origin: f.grid.origin.extend(f.grid.voxel),
            voxel_grid: Vec4::new(
                f.grid.longest() as f32,
                f.mip_levels as f32,
                f.gi.temporal,
                f.first_frame as u32 as f32,
            ),
            cone: Vec4::new(f.gi.steps as f32, f.gi.bias, f.gi.cone_start, f.gi.lod_offset + f.gi.level.offset()),
            cone_model: Vec4::new(f.cone_count as f32, f.gi.step, f.gi.cone_flags() as f32, f.bounce_cone_count as f32),
            view: Vec4::new(f.view.code() as f32, level as f32, f.gi_on as u32 as f32, 0.0),
            history_shift: ((f.grid.origin - f.previous_origin) / f.grid.voxel).extend(0.0),
            voxel_dims: f.grid.dims.as_vec3().extend(0.0),
            aniso_atlas: super::radiance::AtlasLayout::new(f.grid).uniform(),
            light_count: Vec4::new(lights.len() as f32, 0.0, 0.0, 0.0),
            lights: gpu_lights,
            light_layers,
            previous_view_proj: f.previous_view_proj.unwrap_or(view_proj),
            gi_jitter: f.gi_jitter,
            voxel_warp: f.grid.warp.gpu(),
            voxel_warp_proj: f.grid.warp.proj(),
            voxel_warp_unproj: f.grid.warp.unproj(),
            clip,
            clip_levels,
            clip_scene,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A ceiling quad's cube: its upward face is not read, and each other face's texel follows
    /// the depth it sees (the walls a metre away, the floor two).
    #[test]
    fn a_cube_faces_texels_follow_their_own_depth_and_the_area_lights_back_is_skipped() {
        let bounds = Aabb { min: Vec3::new(-1.0, 0.0, -1.0), max: Vec3::new(1.0, 2.0, 1.0) };
        let center = Vec3::new(0.0, 1.98, 0.0);
        // Wound to face down: half_u x half_v = -y.
        let area = Light::Area { center, half_u: Vec3::X * 0.2, half_v: Vec3::Z * 0.2, radiance: Vec3::ONE };
        let t = layer_texel_sizes(&area, &bounds, 1000);
        assert_eq!(t[2], None, "the face looking up sees only what lies behind the quad: {t:?}");
        assert!((t[3].unwrap() - 2.0 * 1.98 / 1000.0).abs() < 1e-6, "{t:?}");
        for face in [0, 1, 4, 5] {
            assert!((t[face].unwrap() - 2.0 / 1000.0).abs() < 1e-6, "{t:?}");
        }
        let point = Light::Point { position: center, intensity: Vec3::ONE };
        assert!(layer_texel_sizes(&point, &bounds, 1000).iter().all(|t| t.is_some()), "a point light lights every way");
    }
}
