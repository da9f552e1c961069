//! Per-frame uniforms (mirrors `FrameUniforms` in `shaders-glsl/common/frame.glsl`) and the
//! camera and light matrices they carry: a perspective shadow frustum for spot lights, an
//! orthographic one fitted to the scene bounds for directional lights (Freed 2018 §4.2).

use glam::{Mat4, Vec3, Vec4};

use crate::config;
use crate::scene::{flip_y, Aabb, Camera, Light};

#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct FrameUniforms {
    pub view_proj: Mat4,
    pub light_view_proj: Mat4,
    pub camera_pos: Vec4,
    pub light_pos: Vec4,
    pub light_dir: Vec4,
    pub light_color: Vec4,
    pub light_cone: Vec4,
    pub viewport: Vec4,
}

/// Near and far planes that contain the scene bounds seen from `eye`.
pub fn depth_range(eye: Vec3, bounds: &Aabb) -> (f32, f32) {
    if bounds.is_empty() {
        return (0.01, 100.0);
    }
    let far = (bounds.center() - eye).length() + bounds.size().length() * 0.5;
    let far = far.max(1e-3) * 1.01;
    (far * 1e-3, far)
}

/// World-to-clip matrix of the light's shadow map.
pub fn light_view_proj(light: &Light, bounds: &Aabb) -> Mat4 {
    let up_for = |d: Vec3| if d.y.abs() > 0.99 { Vec3::Z } else { Vec3::Y };
    match *light {
        Light::Spot { position, direction, outer_deg, .. } => {
            let view = Mat4::look_at_rh(position, position + direction, up_for(direction));
            let (near, far) = depth_range(position, bounds);
            let fov = (2.0 * outer_deg + 2.0).min(170.0).to_radians();
            flip_y(Mat4::perspective_rh(fov, 1.0, near.max(far * 2e-3), far))
                * view
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

impl FrameUniforms {
    pub fn new(camera: &Camera, light: &Light, bounds: &Aabb, shadow_resolution: u32) -> Self {
        let (near, far) = depth_range(camera.eye, bounds);
        let (light_pos, light_dir, light_color, cone) = match *light {
            Light::Spot { position, direction, intensity, inner_deg, outer_deg } => (
                position.extend(config::LIGHT_SPOT as f32),
                direction,
                intensity,
                Vec4::new(inner_deg.to_radians(), outer_deg.to_radians(), 0.0, 0.0),
            ),
            Light::Directional { direction, irradiance } => {
                (Vec4::new(0.0, 0.0, 0.0, config::LIGHT_DIRECTIONAL as f32), direction, irradiance, Vec4::ZERO)
            }
        };
        FrameUniforms {
            view_proj: camera.proj(near, far) * camera.view(),
            light_view_proj: light_view_proj(light, bounds),
            camera_pos: camera.eye.extend(1.0),
            light_pos,
            light_dir: light_dir.normalize().extend(0.0),
            light_color: light_color.extend(0.0),
            light_cone: Vec4::new(cone.x, cone.y, 1.0 / shadow_resolution as f32, 0.0),
            viewport: Vec4::new(camera.width as f32, camera.height as f32, 0.0, 0.0),
        }
    }
}
