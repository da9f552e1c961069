//! Scenes: a mesh with materials and textures, a camera, lights and settings, loaded from a
//! TOML scene file, a bare OBJ (framed automatically, one default light) or a glTF 2.0 file
//! (its own camera and lights where it has them). Units are
//! physical: metres, W/sr for spot intensity, W/m² for directional irradiance; MTL `Kd` is
//! linear albedo. The Cornell box of `assets/cornell-spot/` is embedded as the default.

pub mod area;
pub mod cones;
pub mod file;
pub mod gltf;
pub mod gpu;
pub mod light;
pub mod obj;

use std::path::{Path, PathBuf};

use glam::{Mat4, Vec3};

use crate::error::{Error, Result};
use file::{LightFile, SceneFile};
pub use light::Light;

/// Interleaved vertex as the GPU reads it (see `shaders-glsl/common/scene.glsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Vertex {
    pub pos: [f32; 3],
    pub normal: [f32; 3],
    pub uv: [f32; 2],
    pub tangent: [f32; 4],
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: Vec3,
    pub max: Vec3,
}

impl Aabb {
    pub const EMPTY: Aabb = Aabb { min: Vec3::splat(f32::INFINITY), max: Vec3::splat(f32::NEG_INFINITY) };
    pub fn grow(&mut self, p: Vec3) {
        self.min = self.min.min(p);
        self.max = self.max.max(p);
    }
    pub fn is_empty(&self) -> bool {
        !(self.min.cmple(self.max).all())
    }
    pub fn center(&self) -> Vec3 {
        (self.min + self.max) * 0.5
    }
    pub fn size(&self) -> Vec3 {
        self.max - self.min
    }
    /// Whether the two boxes share a point (touching counts).
    pub fn overlaps(&self, other: &Aabb) -> bool {
        self.min.cmple(other.max).all() && self.max.cmpge(other.min).all()
    }
    /// This box grown by `pad` on every side.
    pub fn grown(&self, pad: f32) -> Aabb {
        Aabb { min: self.min - Vec3::splat(pad), max: self.max + Vec3::splat(pad) }
    }
}

/// A contiguous index range drawn with one material.
#[derive(Clone, Copy, Debug)]
pub struct Draw {
    pub first_index: u32,
    pub index_count: u32,
    pub material: u32,
}

#[derive(Clone, Debug, Default)]
pub struct Mesh {
    pub vertices: Vec<Vertex>,
    pub indices: Vec<u32>,
    pub draws: Vec<Draw>,
    pub bounds: Aabb,
}

impl Default for Aabb {
    fn default() -> Self {
        Aabb::EMPTY
    }
}

impl Mesh {
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }
    /// The three corners of triangle `t`.
    pub fn triangle(&self, t: usize) -> [Vec3; 3] {
        let i = &self.indices[3 * t..3 * t + 3];
        [0, 1, 2].map(|k| Vec3::from(self.vertices[i[k] as usize].pos))
    }
}

#[derive(Clone, Debug)]
pub struct Material {
    pub name: String,
    /// Linear albedo (Lambertian BRDF = albedo / π).
    pub albedo: Vec3,
    /// Emitted radiance, W/(m² sr).
    pub emissive: Vec3,
    /// Reflectance at normal incidence for dielectrics (MTL `Ks`; zero means no specular lobe).
    pub specular: Vec3,
    pub roughness: f32,
    pub metallic: f32,
    pub albedo_texture: Option<usize>,
    pub normal_texture: Option<usize>,
    /// Its emission reaches the scene through `Light::Area`s (every triangle of it lies in one:
    /// `area::add_area_lights`), not through the voxels; the eye and the path tracer still see it.
    pub area_light: bool,
}

impl Material {
    pub fn default_grey() -> Self {
        Material {
            name: "default".into(),
            albedo: Vec3::splat(0.7),
            emissive: Vec3::ZERO,
            specular: Vec3::splat(0.04),
            roughness: 0.8,
            metallic: 0.0,
            albedo_texture: None,
            normal_texture: None,
            area_light: false,
        }
    }
}

#[derive(Clone, Debug)]
pub struct Texture {
    pub path: PathBuf,
    pub width: u32,
    pub height: u32,
    pub rgba: Vec<u8>,
    /// Colour data (decoded from sRGB by the sampler) rather than linear data (normal maps).
    pub srgb: bool,
}

#[derive(Clone, Copy, Debug)]
pub struct Camera {
    pub eye: Vec3,
    pub target: Vec3,
    pub up: Vec3,
    /// Full vertical field of view, degrees.
    pub fov_y_deg: f32,
    pub width: u32,
    pub height: u32,
}

/// Vulkan clip space has y pointing down; this flips glam's y-up projections.
pub fn flip_y(proj: Mat4) -> Mat4 {
    Mat4::from_scale(Vec3::new(1.0, -1.0, 1.0)) * proj
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

impl Camera {
    /// World to clip space, with depth planes around `bounds` ([`depth_range`]).
    pub fn view_proj(&self, bounds: &Aabb) -> Mat4 {
        let (near, far) = depth_range(self.eye, bounds);
        self.proj(near, far) * self.view()
    }
    pub fn view(&self) -> Mat4 {
        Mat4::look_at_rh(self.eye, self.target, self.up)
    }
    pub fn proj(&self, near: f32, far: f32) -> Mat4 {
        let aspect = self.width as f32 / self.height as f32;
        flip_y(Mat4::perspective_rh(self.fov_y_deg.to_radians(), aspect, near, far))
    }
    /// World-space ray (origin, unit direction) through the centre of pixel (x, y).
    pub fn ray(&self, x: f32, y: f32) -> (Vec3, Vec3) {
        let f = (self.target - self.eye).normalize();
        let r = f.cross(self.up).normalize();
        let u = r.cross(f);
        let t = (self.fov_y_deg.to_radians() * 0.5).tan();
        let aspect = self.width as f32 / self.height as f32;
        let sx = ((x + 0.5) / self.width as f32 * 2.0 - 1.0) * t * aspect;
        let sy = (1.0 - (y + 0.5) / self.height as f32 * 2.0) * t;
        (self.eye, (f + r * sx + u * sy).normalize())
    }
}

pub use file::GiFile as GiSettings;

#[derive(Clone, Debug)]
pub struct Settings {
    pub voxel_resolution: u32,
    pub shadow_resolution: u32,
    pub gi: GiSettings,
}

#[derive(Clone, Debug)]
pub struct Scene {
    /// Where the scene came from (file path, or `<embedded>/...`).
    pub source: PathBuf,
    pub mesh: Mesh,
    pub materials: Vec<Material>,
    pub textures: Vec<Texture>,
    pub camera: Camera,
    /// The lights that cast shadow-mapped direct light (at most MAX_LIGHTS, each with its own
    /// shadow map). Emissive
    /// materials light the scene besides, through the radiance volume.
    pub lights: Vec<Light>,
    pub settings: Settings,
    /// Problems that did not stop loading (missing textures, dropped triangles, ...).
    pub warnings: Vec<String>,
}

/// The embedded default scene: the Cornell box lit by a spot light.
pub const EMBEDDED_DIR: &str = "<embedded>/cornell-spot";
const EMBEDDED: [(&str, &[u8]); 4] = [
    ("scene.toml", include_bytes!("../../assets/cornell-spot/scene.toml")),
    ("scene-directional.toml", include_bytes!("../../assets/cornell-spot/scene-directional.toml")),
    ("cornell.obj", include_bytes!("../../assets/cornell-spot/cornell.obj")),
    ("cornell.mtl", include_bytes!("../../assets/cornell-spot/cornell.mtl")),
];

/// Reads a file, from the embedded assets when the path is under [`EMBEDDED_DIR`].
pub fn read_file(path: &Path) -> std::io::Result<Vec<u8>> {
    if let Ok(rest) = path.strip_prefix(EMBEDDED_DIR) {
        let name = rest.to_string_lossy();
        return EMBEDDED
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, b)| b.to_vec())
            .ok_or_else(|| std::io::Error::new(std::io::ErrorKind::NotFound, "not among the embedded assets"));
    }
    std::fs::read(path)
}

/// Loads a scene from files held in memory (`(name, bytes)`, names relative to one folder),
/// starting at `entry` (a `.toml` or `.obj` name). Used by the fuzz target and its corpus test.
pub fn load_from_memory(files: &[(&str, &[u8])], entry: &str) -> Result<Scene> {
    let root = Path::new("<memory>");
    let read = |p: &Path| -> std::io::Result<Vec<u8>> {
        let name = p.strip_prefix(root).unwrap_or(p).to_string_lossy().replace('\\', "/");
        files
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, b)| b.to_vec())
            .ok_or_else(|| std::io::Error::new(std::io::ErrorKind::NotFound, "no such file in memory"))
    };
    Scene::load_with(&root.join(entry), &read)
}

/// The fuzz target's body: `data` split at "\n----\n" into scene.toml, mesh.obj and mesh.mtl,
/// loaded both as a scene file and as a bare OBJ, and `data` whole as a binary glTF (.glb) and
/// a glTF's JSON. Must return, never panic or hang.
pub fn fuzz_scene_input(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    let mut parts = text.splitn(3, "\n----\n");
    let (toml, obj, mtl) = (parts.next().unwrap_or(""), parts.next().unwrap_or(""), parts.next().unwrap_or(""));
    let files: [(&str, &[u8]); 5] = [
        ("scene.toml", toml.as_bytes()),
        ("mesh.obj", obj.as_bytes()),
        ("mesh.mtl", mtl.as_bytes()),
        ("scene.glb", data),
        ("scene.gltf", data),
    ];
    for entry in ["scene.toml", "mesh.obj", "scene.glb", "scene.gltf"] {
        if let Ok(scene) = load_from_memory(&files, entry) {
            // What loads must be usable: finite bounds or empty, indices in range.
            let n = scene.mesh.vertices.len() as u32;
            assert!(scene.mesh.indices.iter().all(|&i| i < n), "index out of range after loading");
            assert!(
                scene.mesh.bounds.is_empty()
                    || (scene.mesh.bounds.min.is_finite() && scene.mesh.bounds.max.is_finite())
            );
        }
    }
}

pub const MAX_IMAGE_SIZE: u32 = 16384;

fn check_finite(path: &Path, field: &str, v: &[f32]) -> Result<()> {
    if v.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(Error::input(path, format!("{field} must be finite, got {v:?}")))
    }
}

fn check_direction(path: &Path, field: &str, v: [f32; 3]) -> Result<Vec3> {
    check_finite(path, field, &v)?;
    let d = Vec3::from(v);
    if d.length_squared() < 1e-12 {
        return Err(Error::input(path, format!("{field} must not be the zero vector")));
    }
    Ok(d.normalize())
}

fn check_nonneg(path: &Path, field: &str, v: [f32; 3]) -> Result<Vec3> {
    check_finite(path, field, &v)?;
    if v.iter().any(|x| *x < 0.0) {
        return Err(Error::input(path, format!("{field} must not be negative, got {v:?}")));
    }
    Ok(Vec3::from(v))
}

/// Checks an image size given by a scene file or the command line.
pub fn check_image_size(width: u32, height: u32) -> Result<()> {
    for (name, v) in [("width", width), ("height", height)] {
        if v == 0 || v > MAX_IMAGE_SIZE {
            return Err(Error::param(
                if name == "width" { "width" } else { "height" },
                format!("{v} is outside 1..={MAX_IMAGE_SIZE}"),
            ));
        }
    }
    Ok(())
}

impl Scene {
    /// The embedded Cornell box (spot light).
    pub fn embedded_default() -> Result<Scene> {
        Scene::load(&Path::new(EMBEDDED_DIR).join("scene.toml"))
    }

    /// Loads a scene file (`.toml`) or a bare OBJ (`.obj`).
    pub fn load(path: &Path) -> Result<Scene> {
        Self::load_with(path, &read_file)
    }

    /// As [`Scene::load`], reading every file (scene, OBJ, MTL, textures) through `read`.
    pub fn load_with(path: &Path, read: obj::ReadFn) -> Result<Scene> {
        let ext = path.extension().and_then(|e| e.to_str()).map(|e| e.to_ascii_lowercase());
        let scene = match ext.as_deref() {
            Some("obj") => Self::from_obj(path, read),
            Some("gltf" | "glb") => Self::from_gltf(path, read),
            Some("toml") => Self::from_toml(path, read),
            _ => Err(Error::input(path, "expected a scene file (.toml), a mesh (.obj) or a glTF file (.gltf, .glb)")),
        }?;
        check_values(&scene)?;
        let mut scene = scene;
        if scene.settings.gi.area_lights {
            area::add_area_lights(&mut scene);
        }
        Ok(scene)
    }

    fn from_toml(path: &Path, read: obj::ReadFn) -> Result<Scene> {
        let bytes = read(path).map_err(|e| Error::Io { path: path.to_path_buf(), source: e })?;
        let text = String::from_utf8(bytes).map_err(|_| Error::input(path, "scene file is not UTF-8 text"))?;
        let file: SceneFile =
            toml::from_str(&text).map_err(|e| Error::input(path, format!("invalid scene file: {e}")))?;
        let mesh_path = path.parent().unwrap_or(Path::new("")).join(&file.mesh);
        let mut warnings = Vec::new();
        let loaded = load_mesh(&mesh_path, read, &mut warnings)?;
        let (mesh, materials, textures) = (loaded.mesh, loaded.materials, loaded.textures);
        let camera = match &file.camera {
            Some(c) => {
                check_finite(path, "camera.eye", &c.eye)?;
                check_finite(path, "camera.target", &c.target)?;
                let up = check_direction(path, "camera.up", c.up)?;
                if !(c.fov_y_deg > 0.0 && c.fov_y_deg < 180.0) {
                    return Err(Error::input(
                        path,
                        format!("camera.fov_y_deg must be in (0, 180), got {}", c.fov_y_deg),
                    ));
                }
                check_image_size(c.width, c.height).map_err(|e| Error::input(path, format!("camera.{e}")))?;
                let view = Vec3::from(c.target) - Vec3::from(c.eye);
                if view.length_squared() < 1e-12 {
                    return Err(Error::input(path, "camera.eye and camera.target must differ"));
                }
                if view.normalize().cross(up).length() < 1e-4 {
                    return Err(Error::input(
                        path,
                        format!(
                            "camera.up {:?} is parallel to the view direction (eye to target): no image orientation",
                            c.up
                        ),
                    ));
                }
                Camera {
                    eye: c.eye.into(),
                    target: c.target.into(),
                    up,
                    fov_y_deg: c.fov_y_deg,
                    width: c.width,
                    height: c.height,
                }
            }
            None => loaded.camera.unwrap_or_else(|| frame_bounds(&mesh.bounds)),
        };
        let lights = match file.lights.as_slice() {
            [] if !loaded.lights.is_empty() => first_lights(&mesh_path, loaded.lights, &mut warnings),
            [] => default_lights(&mesh, &materials),
            given if given.len() > MAX_LIGHTS => {
                return Err(Error::input(
                    path,
                    format!("{} lights given; vct renders at most {MAX_LIGHTS}", given.len()),
                ))
            }
            given => given.iter().map(|l| convert_light(path, l)).collect::<Result<Vec<_>>>()?,
        };
        let settings = Settings {
            voxel_resolution: file.voxels.resolution,
            shadow_resolution: file.shadow.resolution,
            gi: file.gi.clone(),
        };
        check_settings(path, &settings)?;
        Ok(Scene { source: path.to_path_buf(), mesh, materials, textures, camera, lights, settings, warnings })
    }

    fn from_obj(path: &Path, read: obj::ReadFn) -> Result<Scene> {
        let mut warnings = Vec::new();
        let (mesh, materials, textures) = obj::load_obj(path, read, &mut warnings)?;
        let camera = frame_bounds(&mesh.bounds);
        let settings = Settings { voxel_resolution: 128, shadow_resolution: 2048, gi: GiSettings::default() };
        let lights = default_lights(&mesh, &materials);
        Ok(Scene { source: path.to_path_buf(), mesh, materials, textures, camera, lights, settings, warnings })
    }

    fn from_gltf(path: &Path, read: obj::ReadFn) -> Result<Scene> {
        let mut warnings = Vec::new();
        let g = gltf::load_gltf(path, read, &mut warnings)?;
        let camera = g.camera.unwrap_or_else(|| frame_bounds(&g.mesh.bounds));
        let lights = if g.lights.is_empty() {
            default_lights(&g.mesh, &g.materials)
        } else {
            first_lights(path, g.lights, &mut warnings)
        };
        let settings = Settings { voxel_resolution: 128, shadow_resolution: 2048, gi: GiSettings::default() };
        Ok(Scene {
            source: path.to_path_buf(),
            mesh: g.mesh,
            materials: g.materials,
            textures: g.textures,
            camera,
            lights,
            settings,
            warnings,
        })
    }

    /// A scene made in code: `triangles` with one flat material each (by index into
    /// `albedos`), framed by the default camera and lit by the default light.
    pub fn from_triangles(triangles: &[([Vec3; 3], usize)], albedos: &[Vec3]) -> Scene {
        let mut materials: Vec<Material> =
            albedos.iter().map(|&a| Material { albedo: a, specular: Vec3::ZERO, ..Material::default_grey() }).collect();
        if materials.is_empty() {
            materials.push(Material::default_grey());
        }
        let mut mesh = Mesh::default();
        for (m, _) in materials.iter().enumerate() {
            let first = mesh.indices.len() as u32;
            for (tri, _) in triangles.iter().filter(|(_, tm)| (*tm).min(materials.len() - 1) == m) {
                let n = (tri[1] - tri[0]).cross(tri[2] - tri[0]).normalize_or_zero();
                for p in tri {
                    mesh.indices.push(mesh.vertices.len() as u32);
                    mesh.vertices.push(Vertex { pos: (*p).into(), normal: n.into(), ..Default::default() });
                    mesh.bounds.grow(*p);
                }
            }
            let count = mesh.indices.len() as u32 - first;
            if count > 0 {
                mesh.draws.push(Draw { first_index: first, index_count: count, material: m as u32 });
            }
        }
        Scene {
            source: PathBuf::from("<code>"),
            camera: frame_bounds(&mesh.bounds),
            mesh,
            materials,
            textures: Vec::new(),
            lights: vec![default_light()],
            settings: Settings { voxel_resolution: 64, shadow_resolution: 1024, gi: GiSettings::default() },
            warnings: Vec::new(),
        }
    }

    /// Renders at this size instead of the scene's.
    pub fn set_size(&mut self, width: Option<u32>, height: Option<u32>) -> Result<()> {
        let (w, h) = (width.unwrap_or(self.camera.width), height.unwrap_or(self.camera.height));
        check_image_size(w, h)?;
        self.camera.width = w;
        self.camera.height = h;
        Ok(())
    }
}

/// A mesh file's content: an OBJ's, or a glTF's with its camera and lights.
struct LoadedMesh {
    mesh: Mesh,
    materials: Vec<Material>,
    textures: Vec<Texture>,
    camera: Option<Camera>,
    lights: Vec<Light>,
}

/// Loads the mesh a scene file names: OBJ, or glTF (`.gltf`, `.glb`).
fn load_mesh(path: &Path, read: obj::ReadFn, warnings: &mut Vec<String>) -> Result<LoadedMesh> {
    if gltf::is_gltf(path) {
        let g = gltf::load_gltf(path, read, warnings)?;
        return Ok(LoadedMesh {
            mesh: g.mesh,
            materials: g.materials,
            textures: g.textures,
            camera: g.camera,
            lights: g.lights,
        });
    }
    let (mesh, materials, textures) = obj::load_obj(path, read, warnings)?;
    Ok(LoadedMesh { mesh, materials, textures, camera: None, lights: Vec::new() })
}

/// Lights a scene may have, each with its own shadow map.
pub const MAX_LIGHTS: usize = crate::config::MAX_LIGHTS as usize;

/// The first MAX_LIGHTS of a file's lights, with a warning naming how many more it has.
fn first_lights(path: &Path, mut lights: Vec<Light>, warnings: &mut Vec<String>) -> Vec<Light> {
    if lights.len() > MAX_LIGHTS {
        warnings.push(format!(
            "{}: {} lights; vct renders the first {MAX_LIGHTS} (the other {} are not rendered)",
            path.display(),
            lights.len(),
            lights.len() - MAX_LIGHTS
        ));
        lights.truncate(MAX_LIGHTS);
    }
    lights
}

/// The largest emitted radiance the GPU stores: RGB9E5's largest value (the voxels' emission;
/// the radiance volume's half floats reach 65504).
pub const MAX_EMISSION: f32 = 65408.0;

/// Values a file may legally carry that make no picture: an error naming the file and the value.
fn check_values(scene: &Scene) -> Result<()> {
    let path = &scene.source;
    let b = &scene.mesh.bounds;
    if !(b.is_empty() || b.size().length().is_finite()) {
        return Err(Error::input(
            path,
            format!(
                "the scene's extent overflows single precision (coordinates from {} to {}): scale the model",
                b.min, b.max
            ),
        ));
    }
    for m in &scene.materials {
        if m.emissive.max_element() > MAX_EMISSION {
            return Err(Error::input(
                path,
                format!(
                    "material '{}' emits {} W/(m²·sr), beyond the {MAX_EMISSION} the GPU's half-float radiance holds: scale the emission (and the exposure)",
                    m.name, m.emissive
                ),
            ));
        }
    }
    Ok(())
}

fn check_settings(path: &Path, s: &Settings) -> Result<()> {
    if !(16..=512).contains(&s.voxel_resolution) || !s.voxel_resolution.is_power_of_two() {
        return Err(Error::input(
            path,
            format!("voxels.resolution must be a power of two in 16..=512, got {}", s.voxel_resolution),
        ));
    }
    if !(64..=8192).contains(&s.shadow_resolution) {
        return Err(Error::input(path, format!("shadow.resolution must be in 64..=8192, got {}", s.shadow_resolution)));
    }
    let g = &s.gi;
    if !(1..=512).contains(&g.steps) {
        return Err(Error::input(path, format!("gi.steps must be in 1..=512, got {}", g.steps)));
    }
    if !(1..=8).contains(&g.bounces) {
        return Err(Error::input(path, format!("gi.bounces must be in 1..=8, got {}", g.bounces)));
    }
    for (name, v, lo, hi) in [
        ("gi.bias", g.bias, 0.0, 16.0),
        ("gi.cone_start", g.cone_start, 0.01, 16.0),
        ("gi.lod_offset", g.lod_offset, -4.0, 8.0),
        ("gi.temporal", g.temporal, 0.01, 1.0),
        ("gi.step", g.step, 0.05, 2.0),
        ("gi.aperture", g.aperture, 0.1, 2.0),
    ] {
        if !(v.is_finite() && (lo..=hi).contains(&v)) {
            return Err(Error::input(path, format!("{name} must be in {lo}..={hi}, got {v}")));
        }
    }
    Ok(())
}

fn convert_light(path: &Path, l: &LightFile) -> Result<Light> {
    Ok(match *l {
        LightFile::Spot { position, direction, intensity, inner_deg, outer_deg } => {
            check_finite(path, "light.position", &position)?;
            if !(0.0..90.0).contains(&outer_deg) || !(0.0..=outer_deg).contains(&inner_deg) {
                return Err(Error::input(
                    path,
                    format!(
                        "light angles must satisfy 0 <= inner_deg <= outer_deg < 90, got {inner_deg} and {outer_deg}"
                    ),
                ));
            }
            Light::Spot {
                position: position.into(),
                direction: check_direction(path, "light.direction", direction)?,
                intensity: check_nonneg(path, "light.intensity", intensity)?,
                inner_deg,
                outer_deg,
            }
        }
        LightFile::Point { position, intensity } => {
            check_finite(path, "light.position", &position)?;
            Light::Point { position: position.into(), intensity: check_nonneg(path, "light.intensity", intensity)? }
        }
        LightFile::Directional { direction, irradiance } => Light::Directional {
            direction: check_direction(path, "light.direction", direction)?,
            irradiance: check_nonneg(path, "light.irradiance", irradiance)?,
        },
    })
}

/// The lights a scene without any gets: none when its materials emit (the emitters light it,
/// as the classic Cornell box's ceiling quad does), else the default sun.
pub fn default_lights(mesh: &Mesh, materials: &[Material]) -> Vec<Light> {
    let emits = |d: &Draw| materials.get(d.material as usize).is_some_and(|m| m.emissive.max_element() > 0.0);
    if mesh.draws.iter().any(emits) {
        Vec::new()
    } else {
        vec![default_light()]
    }
}

/// The light a bare OBJ without emitters gets: sunlight from above, slightly from the front (+z).
pub fn default_light() -> Light {
    Light::Directional { direction: Vec3::new(-0.25, -1.0, -0.45).normalize(), irradiance: Vec3::splat(3.0) }
}

/// A camera in front of (+z) and a little above the bounds, framing all of them.
pub fn frame_bounds(b: &Aabb) -> Camera {
    let (center, radius) =
        if b.is_empty() { (Vec3::ZERO, 1.0) } else { (b.center(), (b.size().length() * 0.5).max(1e-3)) };
    let fov_y_deg = 45.0f32;
    let dist = radius / (fov_y_deg.to_radians() * 0.5).sin();
    let dir = Vec3::new(0.0, 0.25, 1.0).normalize();
    Camera { eye: center + dir * dist, target: center, up: Vec3::Y, fov_y_deg, width: 512, height: 512 }
}
