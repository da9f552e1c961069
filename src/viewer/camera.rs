//! Viewer camera control: fly (WASD, mouse-look with the right button, Q/E down/up, Shift
//! faster) or orbit around the scene centre (left-button drag, wheel to zoom); and swinging
//! the light's direction with the arrow keys.

use glam::{Quat, Vec3};

use crate::scene::{Aabb, Camera, Light};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    Fly,
    Orbit,
}

/// Keys and mouse state the controller reads each frame.
#[derive(Clone, Debug, Default)]
pub struct Input {
    pub forward: f32,
    pub right: f32,
    pub up: f32,
    pub fast: bool,
    /// Accumulated mouse motion (pixels) while a look/orbit button was held.
    pub look: (f32, f32),
    /// Accumulated wheel lines.
    pub zoom: f32,
    /// Light swing (yaw, pitch), in units of the swing speed.
    pub light: (f32, f32),
}

pub struct CameraController {
    pub mode: Mode,
    yaw: f32,
    pitch: f32,
    centre: Vec3,
    radius: f32,
    speed: f32,
}

fn forward_of(yaw: f32, pitch: f32) -> Vec3 {
    Vec3::new(yaw.sin() * pitch.cos(), pitch.sin(), -yaw.cos() * pitch.cos())
}

const LOOK_RAD_PER_PIXEL: f32 = 0.004;
const LIGHT_RAD_PER_S: f32 = 0.8;

impl CameraController {
    pub fn new(camera: &Camera, bounds: &Aabb) -> Self {
        let f = (camera.target - camera.eye).normalize();
        let size = if bounds.is_empty() { 1.0 } else { bounds.size().length() };
        let centre = if bounds.is_empty() { camera.target } else { bounds.center() };
        CameraController {
            mode: Mode::Fly,
            yaw: f.x.atan2(-f.z),
            pitch: f.y.clamp(-1.0, 1.0).asin(),
            centre,
            radius: (camera.eye - centre).length().max(1e-3),
            speed: size * 0.25,
        }
    }

    pub fn toggle_mode(&mut self, camera: &Camera) {
        self.mode = match self.mode {
            Mode::Fly => Mode::Orbit,
            Mode::Orbit => Mode::Fly,
        };
        self.radius = (camera.eye - self.centre).length().max(1e-3);
    }

    /// Moves the camera by `input` over `dt` seconds and clears the accumulated motion.
    pub fn update(&mut self, camera: &mut Camera, input: &mut Input, dt: f32) {
        let limit = 89.0f32.to_radians();
        match self.mode {
            Mode::Fly => {
                self.yaw += input.look.0 * LOOK_RAD_PER_PIXEL;
                self.pitch = (self.pitch - input.look.1 * LOOK_RAD_PER_PIXEL).clamp(-limit, limit);
                let f = forward_of(self.yaw, self.pitch);
                let r = f.cross(Vec3::Y).normalize();
                let speed = self.speed * if input.fast { 4.0 } else { 1.0 } * dt;
                camera.eye += (f * input.forward + r * input.right + Vec3::Y * input.up) * speed;
                camera.target = camera.eye + f;
            }
            Mode::Orbit => {
                self.yaw -= input.look.0 * LOOK_RAD_PER_PIXEL;
                self.pitch = (self.pitch + input.look.1 * LOOK_RAD_PER_PIXEL).clamp(-limit, limit);
                self.radius = (self.radius * 0.9f32.powf(input.zoom) - input.forward * self.speed * dt).max(1e-3);
                let f = forward_of(self.yaw, self.pitch);
                camera.eye = self.centre - f * self.radius;
                camera.target = self.centre;
            }
        }
        camera.up = Vec3::Y;
        input.look = (0.0, 0.0);
        input.zoom = 0.0;
    }
}

/// Turns the light's direction by `yaw`/`pitch` radians (about the vertical, then the
/// horizontal axis), keeping it off the poles.
pub fn swing_light(light: &mut Light, yaw: f32, pitch: f32) {
    let turn = |d: Vec3| {
        let d = Quat::from_rotation_y(yaw) * d;
        let side = d.cross(Vec3::Y).normalize_or(Vec3::X);
        let turned = Quat::from_axis_angle(side, pitch) * d;
        // Never onto a pole (the tilt axis would vanish), but always allowed away from one.
        if turned.y.abs() > 0.9999 && turned.y.abs() > d.y.abs() {
            d
        } else {
            turned.normalize()
        }
    };
    match light {
        Light::Spot { direction, .. } | Light::Directional { direction, .. } => *direction = turn(*direction),
        // A point light shines every way, an area light is a quad of the mesh: nothing to swing.
        Light::Point { .. } | Light::Area { .. } => {}
    }
}

/// The per-second light swing for this frame.
pub fn light_step(input: &Input, dt: f32) -> (f32, f32) {
    (input.light.0 * LIGHT_RAD_PER_S * dt, input.light.1 * LIGHT_RAD_PER_S * dt)
}
