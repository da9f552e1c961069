//! The scene file (TOML): mesh, camera, lights and render settings, in physical units.
//! Unknown or mistyped fields are errors that name the field and the file.

use serde::Deserialize;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// The mesh: an OBJ or glTF (.gltf, .glb) path, relative to the scene file. A glTF's
    /// camera and lights serve where this file gives none.
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

/// Cone-tracing and radiance settings (Freed 2018 §4.5.2 Listing 4.1, §4.7.2; the model's
/// choices and their measurements: docs/design/cones.md).
#[derive(Debug, Clone, PartialEq, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct GiFile {
    /// Maximum samples per cone (a cap: cones end when opaque or outside the volume).
    pub steps: u32,
    /// Cone start offset along the surface normal, in voxels (against self-illumination).
    pub bias: f32,
    /// Initial distance along the cone, in voxels.
    pub cone_start: f32,
    /// Added to the mip level each sample reads (after the level rule).
    pub lod_offset: f32,
    /// Weight of this frame's radiance against the previous frame's (1 = no temporal filter).
    pub temporal: f32,
    /// Radiance mip filtering.
    pub filter: Filter,
    /// The diffuse cone set.
    pub cones: ConeSet,
    /// Each diffuse cone's half aperture as a share of its set's (for the cell sets, of the cone
    /// that spans its cell's solid angle).
    pub aperture: f32,
    /// How the sampled level follows the cone diameter.
    pub level: LevelRule,
    /// Step length over the sampled level's texel size (Listing 4.1: 0.5, the cone's radius
    /// with texels as wide as the cone).
    pub step: f32,
    /// Correct each sample's opacity for the step length (Crassin et al. 2011).
    pub opacity_correction: bool,
    /// Read each directional chain as boxes along its own axis, their optical depths added by
    /// the cone's advance along each axis, opacity corrected for the step (common/cone.glsl; with
    /// the directional chains only: the isotropic chain is read as usual).
    pub chain_box: bool,
    /// Keep each sample's filter off the receiving surface (common/cone.glsl).
    pub self_clamp: bool,
    /// Hide light that leaves its surfaces away from the cone (the radiance moment volume).
    pub facing: bool,
    /// Light bounces: 1 gathers the injected direct light; each more adds a voxel-space pass.
    pub bounces: u32,
    /// The cone set of the voxel-space bounces (their light is gathered again by the surfaces,
    /// so a wider, cheaper set serves).
    pub bounce_cones: ConeSet,
    /// Emissive quads light the scene as area lights (`scene::area`: exact irradiance, shadow
    /// mapped) rather than through their voxels. Read when the scene loads.
    pub area_lights: bool,
    /// How injection finds the lit voxels: from the shadow map's texels, or from the voxels.
    pub injection: Injection,
    /// Turn the diffuse cone set about the normal by a different angle at each pixel
    /// (interleaved gradient noise, Jimenez 2014), so that neighbouring pixels sample their
    /// cones' cells in other directions: a cone reads its footprint round its axis, and where
    /// its cell's light lies off that axis (beside an occluder, below a spotlight's edge) a fixed
    /// set misses it at every pixel alike (docs/design/cones.md). Deferred shading
    /// at full resolution then resolves each pixel's gather from its neighbours on the same
    /// surface (3×3, or 5×5 per quarter with `split_cones`); at a reduced GI scale the upsampling
    /// mixes the turns, and forward shading leaves each pixel its own.
    pub turn_cones: bool,
    /// Split the diffuse cone set among each 2×2 block of pixels (with `turn_cones`, in deferred
    /// shading at full resolution): each pixel traces a quarter of the cones, and the resolve
    /// takes, for each quarter, the mean of the 3×3 neighbours on the same surface that traced
    /// it, so every pixel still gathers the whole set, turned nine ways, at a quarter of the
    /// trace (interleaved sampling, Keller & Heidrich 2001; shade/deferred.comp).
    pub split_cones: bool,
    /// A diagnostic, not a model: the surfaces gather cone `k` of their set alone, with weight
    /// one, so the image's indirect light is that cone's radiance (`vct bench --accuracy
    /// --per-cone`). Not read from scene files.
    #[serde(skip)]
    pub only_cone: Option<u32>,
}

/// How injection finds the voxels a light lights (render::inject::from_voxels).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Deserialize, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Injection {
    /// Each shadow-map texel reconstructs its lit point and marks its voxel (Freed 2018 §4.3,
    /// Algorithm 2): the cost follows the map's texels, and a voxel no texel reaches (a surface
    /// the light grazes, or a grid finer than the map) stays dark; one a texel reaches is lit
    /// whole, across a shadow edge too.
    Texels,
    /// Each occupied voxel that is the first met from the light looks its lit side up in the
    /// shadow map (as surface shading does, with its PCF): the cost follows the occupied voxels
    /// (docs/design/injection.md), and a voxel across a shadow edge gets its lit side's share. A
    /// warped grid, whose texels are not a voxel wide, injects from the texels. The default,
    /// measured together with the sixteen-cone set (docs/design/cones.md).
    #[default]
    Voxels,
}

impl Injection {
    pub fn name(self) -> &'static str {
        match self {
            Injection::Texels => "texels",
            Injection::Voxels => "voxels",
        }
    }
}

impl std::str::FromStr for Injection {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        by_name(&[Injection::Texels, Injection::Voxels], Injection::name, "injection", s)
    }
}

/// The one of `all` whose `name` is `s`, or an error naming `what` and the choices.
fn by_name<T: Copy>(all: &[T], name: fn(T) -> &'static str, what: &str, s: &str) -> Result<T, String> {
    all.iter().copied().find(|&t| name(t) == s).ok_or_else(|| {
        let names: Vec<_> = all.iter().map(|&t| name(t)).collect();
        format!("unknown {what} '{s}' ({})", names.join("|"))
    })
}

/// Radiance mip filtering.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Deserialize, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Filter {
    /// The thesis' 8-child average (§4.4).
    #[default]
    Iso,
    /// Six directional chains, composited front to back (Crassin et al. 2011).
    Aniso,
}

/// How a cone sample's mip level follows the cone's diameter D (voxels).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Deserialize, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum LevelRule {
    /// log2 D: texels as wide as the cone (Listing 4.1, Crassin et al. 2011).
    #[default]
    Diameter,
    /// log2 (D / √3): a trilinear sample of level L spreads over a box-then-tent filter of
    /// standard deviation 2^L / 2, which matches a disc-like cross-section of width D
    /// (standard deviation D / √12) at 2^L = D / √3.
    Footprint,
}

impl LevelRule {
    /// The offset this rule adds to log2 D.
    pub fn offset(self) -> f32 {
        match self {
            LevelRule::Diameter => 0.0,
            LevelRule::Footprint => -0.5 * 3f32.log2(),
        }
    }
}

/// A named diffuse cone layout (the directions and weights are built in `scene::cones`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ConeSet {
    /// The thesis: one cone along the normal and four tilted 45°, all 45° wide, weighted by the
    /// cosine of their axis and normalized (together they cover 38% of the hemisphere).
    #[default]
    Thesis5,
    /// The thesis' five directions with cell weights and apertures.
    Thesis5Cells,
    /// Crassin et al. 2011: one along the normal and five tilted 60°, cell weights.
    Crassin6,
    /// Eight directions spread by cosine density (a Fibonacci spiral), cell weights.
    Fib8,
    /// Sixteen, likewise.
    Fib16,
    /// Thirty-two, likewise.
    Fib32,
}

impl ConeSet {
    pub const ALL: [ConeSet; 6] =
        [ConeSet::Thesis5, ConeSet::Thesis5Cells, ConeSet::Crassin6, ConeSet::Fib8, ConeSet::Fib16, ConeSet::Fib32];

    pub fn name(self) -> &'static str {
        match self {
            ConeSet::Thesis5 => "thesis5",
            ConeSet::Thesis5Cells => "thesis5-cells",
            ConeSet::Crassin6 => "crassin6",
            ConeSet::Fib8 => "fib8",
            ConeSet::Fib16 => "fib16",
            ConeSet::Fib32 => "fib32",
        }
    }
}

impl std::str::FromStr for ConeSet {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        by_name(&ConeSet::ALL, ConeSet::name, "cone set", s)
    }
}

impl GiFile {
    /// The model's switches as the shaders' `CONE_FLAG_*` bits (common/config.h).
    pub fn cone_flags(&self) -> u32 {
        use crate::config::{
            CONE_FLAG_CHAIN_BOX, CONE_FLAG_FACING, CONE_FLAG_OPACITY_CORRECTION, CONE_FLAG_SELF_CLAMP, CONE_FLAG_TURN,
        };
        (if self.opacity_correction { CONE_FLAG_OPACITY_CORRECTION } else { 0 })
            | (if self.chain_box { CONE_FLAG_CHAIN_BOX } else { 0 })
            | (if self.self_clamp { CONE_FLAG_SELF_CLAMP } else { 0 })
            | (if self.facing { CONE_FLAG_FACING } else { 0 })
            | (if self.turn_cones { CONE_FLAG_TURN } else { 0 })
    }

    /// The model as the thesis has it (Listing 4.1, §4.4): the baseline of the accuracy study.
    pub fn thesis() -> Self {
        GiFile {
            steps: 48,
            bias: 1.5,
            cone_start: 1.0,
            lod_offset: 0.0,
            temporal: 1.0,
            filter: Filter::Iso,
            cones: ConeSet::Thesis5,
            aperture: 1.0,
            level: LevelRule::Diameter,
            step: 0.5,
            opacity_correction: false,
            chain_box: false,
            self_clamp: false,
            facing: false,
            bounces: 1,
            bounce_cones: ConeSet::Thesis5Cells,
            area_lights: false,
            injection: Injection::Texels,
            turn_cones: false,
            split_cones: false,
            only_cone: None,
        }
    }
}

impl Default for GiFile {
    /// The model the accuracy study chose (docs/design/cones.md): directional chains, levels
    /// matched to the cone's footprint, no filter reaching back into the receiving surface, light
    /// hidden where it faces away, sixteen narrow cones, injection from the voxels (measured
    /// together with the sixteen cones), and the cone set turned by pixel and split among 2×2
    /// pixels.
    fn default() -> Self {
        GiFile {
            steps: 256,
            filter: Filter::Aniso,
            cones: ConeSet::Fib16,
            aperture: 0.5,
            injection: Injection::Voxels,
            level: LevelRule::Footprint,
            self_clamp: true,
            facing: true,
            area_lights: true,
            turn_cones: true,
            split_cones: true,
            ..GiFile::thesis()
        }
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
    /// A point light (cube shadow map).
    Point {
        position: [f32; 3],
        /// W/sr in every direction.
        intensity: [f32; 3],
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
