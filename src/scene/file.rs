//! The scene file (TOML): mesh, camera, lights and render settings, in physical units.
//! Unknown or mistyped fields are errors that name the field and the file.

use serde::Deserialize;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// OBJ path, relative to the scene file.
    pub mesh: String,
    pub camera: Option<CameraFile>,
    #[serde(default, rename = "light")]
    pub lights: Vec<LightFile>,
    #[serde(default)]
    pub voxels: VoxelsFile,
    #[serde(default)]
    pub shadow: ShadowFile,
    #[serde(default)]
    pub gi: GiFile,
}

/// Cone-tracing and radiance settings (Freed 2018 §4.5.2 Listing 4.1, §4.7.2).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GiFile {
    /// Maximum samples per cone.
    pub steps: u32,
    /// Cone start offset along the surface normal, in voxels (against self-illumination).
    pub bias: f32,
    /// Initial cone height, in voxels.
    pub cone_start: f32,
    /// Added to the mip level each sample reads.
    pub lod_offset: f32,
    /// Weight of this frame's radiance against the previous frame's (1 = no temporal filter).
    pub temporal: f32,
}

impl Default for GiFile {
    fn default() -> Self {
        GiFile { steps: 48, bias: 1.5, cone_start: 1.0, lod_offset: 0.0, temporal: 1.0 }
    }
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraFile {
    pub eye: [f32; 3],
    pub target: [f32; 3],
    #[serde(default = "default_up")]
    pub up: [f32; 3],
    /// Full vertical field of view in degrees.
    #[serde(default = "default_fov")]
    pub fov_y_deg: f32,
    #[serde(default = "default_size")]
    pub width: u32,
    #[serde(default = "default_size")]
    pub height: u32,
}

fn default_up() -> [f32; 3] {
    [0.0, 1.0, 0.0]
}
fn default_fov() -> f32 {
    45.0
}
fn default_size() -> u32 {
    512
}

#[derive(Debug, Clone, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
pub enum LightFile {
    Spot {
        position: [f32; 3],
        direction: [f32; 3],
        /// W/sr on the axis.
        intensity: [f32; 3],
        inner_deg: f32,
        outer_deg: f32,
    },
    Directional {
        /// The way the light travels.
        direction: [f32; 3],
        /// W/m² on a plane perpendicular to `direction`.
        irradiance: [f32; 3],
    },
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VoxelsFile {
    #[serde(default = "default_voxel_res")]
    pub resolution: u32,
}

impl Default for VoxelsFile {
    fn default() -> Self {
        VoxelsFile { resolution: default_voxel_res() }
    }
}

fn default_voxel_res() -> u32 {
    128
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShadowFile {
    #[serde(default = "default_shadow_res")]
    pub resolution: u32,
}

impl Default for ShadowFile {
    fn default() -> Self {
        ShadowFile { resolution: default_shadow_res() }
    }
}

fn default_shadow_res() -> u32 {
    2048
}
