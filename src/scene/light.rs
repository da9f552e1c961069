//! The scene's lights, in physical units: spot and point intensity in W/sr, directional
//! irradiance in W/m², an area light's radiance in W/(m²·sr) (an emissive quad of the mesh,
//! `scene::area`). Each has its own shadow map (render::shadow; Freed 2018 §4.2).

use glam::Vec3;

#[derive(Clone, Copy, Debug)]
pub enum Light {
    Spot {
        position: Vec3,
        direction: Vec3,
        intensity: Vec3,
        inner_deg: f32,
        outer_deg: f32,
    },
    Directional {
        direction: Vec3,
        irradiance: Vec3,
    },
    /// Light from a point in every direction, `intensity` W/sr (a cube shadow map).
    Point {
        position: Vec3,
        intensity: Vec3,
    },
    /// An emissive quad of the mesh (`area`): a parallelogram with corners `center ± half_u ±
    /// half_v`, emitting `radiance` W/(m²·sr) from the side `half_u × half_v` points to (a cube
    /// shadow map from its centre). The mesh keeps the quad's emission: the path tracer samples
    /// those triangles, not this light.
    Area {
        center: Vec3,
        half_u: Vec3,
        half_v: Vec3,
        radiance: Vec3,
    },
}

impl Light {
    /// Spot falloff: 1 inside `inner`, 0 beyond `outer`, linear in angle between.
    pub fn spot_falloff(angle_deg: f32, inner_deg: f32, outer_deg: f32) -> f32 {
        if outer_deg <= inner_deg {
            return if angle_deg <= outer_deg { 1.0 } else { 0.0 };
        }
        ((outer_deg - angle_deg) / (outer_deg - inner_deg)).clamp(0.0, 1.0)
    }

    /// Whether the light stands for emissive triangles of the mesh ([`Light::Area`]).
    pub fn is_mesh_emitter(&self) -> bool {
        matches!(self, Light::Area { .. })
    }

    /// An area light's lit side: the unit normal `half_u × half_v` points to.
    pub fn lit_side(&self) -> Option<Vec3> {
        match *self {
            Light::Area { half_u, half_v, .. } => Some(half_u.cross(half_v).normalize_or_zero()),
            _ => None,
        }
    }

    /// Where a point-like shadow map sits (a point light's position, an area light's centre).
    pub fn cube_origin(&self) -> Option<Vec3> {
        match *self {
            Light::Point { position, .. } => Some(position),
            Light::Area { center, .. } => Some(center),
            _ => None,
        }
    }
}
