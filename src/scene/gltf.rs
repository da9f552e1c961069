//! glTF 2.0 loading (`.gltf` with its buffers and images, and `.glb`) through the `gltf` crate
//! (Khronos glTF 2.0 specification; lights from `KHR_lights_punctual`, emission strength from
//! `KHR_materials_emissive_strength`). The node hierarchy is flattened into world space; each
//! primitive's triangles join the draw of its material, as OBJ groups do (scene::obj).
//!
//! Spot, directional and point lights all load (a point light gets a cube shadow map).
//!
//! Units: glTF gives punctual lights in photometric units (candela for spot and point lights,
//! lux for directional ones) and vct in radiometric ones (W/sr, W/m²). One convention converts
//! them: 683 lm/W, the luminous efficacy of light at 555 nm (so 683 cd is 1 W/sr, 683 lux is
//! 1 W/m²), times the light's colour. glTF gives emission no unit; `emissiveFactor` times
//! `emissiveStrength` is taken as radiance in W/(m²·sr), as MTL `Ke` is.
//!
//! vct's materials hold one metallic, roughness and emission value each: a metallic-roughness or
//! emissive texture is folded into its factor by the texture's mean (with a warning naming it).
//! Everything the renderer does not take (skins, morph targets, other extensions, alpha modes,
//! orthographic cameras, lights beyond MAX_LIGHTS) is named in a warning; every malformed input (a
//! truncated .glb, an accessor past its buffer, a missing buffer or image) is an error naming the
//! file.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use glam::{Mat3, Mat4, Vec3, Vec4};
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Mode;
use gltf::Semantic;

use super::obj::{compute_normals, compute_tangents, decode_texture, ReadFn};
use super::{Aabb, Camera, Draw, Light, Material, Mesh, Texture, Vertex};
use crate::error::{Error, Result};

/// Lumens per watt: photometric glTF light units over vct's radiometric ones.
pub const LUMENS_PER_WATT: f32 = 683.0;

/// The extensions whose content vct reads.
const SUPPORTED_EXTENSIONS: [&str; 2] = ["KHR_lights_punctual", "KHR_materials_emissive_strength"];

/// Deeper node chains than this are taken as a cycle (which the format forbids).
const MAX_NODE_DEPTH: usize = 256;

/// What a glTF file gives a scene.
pub struct GltfScene {
    pub mesh: Mesh,
    pub materials: Vec<Material>,
    pub textures: Vec<Texture>,
    /// The first perspective camera of the scene's nodes.
    pub camera: Option<Camera>,
    /// The spot and directional lights of the scene's nodes, in node order.
    pub lights: Vec<Light>,
}

/// Whether `path` names a glTF file (`.gltf` or `.glb`).
pub fn is_gltf(path: &Path) -> bool {
    let ext = path.extension().and_then(|e| e.to_str()).map(|e| e.to_ascii_lowercase());
    matches!(ext.as_deref(), Some("gltf" | "glb"))
}

fn bad(path: &Path, what: impl std::fmt::Display) -> Error {
    Error::input(path, format!("malformed glTF: {what}"))
}

/// The bytes a URI names: a base64 `data:` URI, or a file relative to the glTF's folder.
fn read_uri(path: &Path, uri: &str, read: ReadFn) -> Result<(Vec<u8>, PathBuf)> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let (_, data) = rest
            .split_once(";base64,")
            .ok_or_else(|| bad(path, format!("data URI without base64: {}", &uri[..uri.len().min(40)])))?;
        use base64::Engine;
        let bytes = base64::engine::general_purpose::STANDARD
            .decode(data)
            .map_err(|e| bad(path, format!("data URI is not base64: {e}")))?;
        return Ok((bytes, path.to_path_buf()));
    }
    let name = percent_encoding::percent_decode_str(uri).decode_utf8_lossy().into_owned();
    let file = path.parent().unwrap_or(Path::new("")).join(name);
    let bytes = read(&file).map_err(|e| Error::Io { path: file.clone(), source: e })?;
    Ok((bytes, file))
}

/// Checks an accessor before the crate reads it: its type, and its bytes inside its view and
/// buffer (the crate's reader assumes both, and asserts on them in debug builds).
fn check_accessor(
    path: &Path,
    acc: &gltf::Accessor,
    dims: &[Dimensions],
    types: &[DataType],
    buffers: &[Vec<u8>],
) -> Result<()> {
    let what = format!("accessor {}", acc.index());
    if !dims.contains(&acc.dimensions()) || !types.contains(&acc.data_type()) {
        return Err(bad(
            path,
            format!("{what} is {:?} {:?}, expected one of {dims:?} of {types:?}", acc.dimensions(), acc.data_type()),
        ));
    }
    if acc.sparse().is_some() {
        return Err(Error::input(path, format!("{what} is sparse; vct does not read sparse accessors")));
    }
    let view = acc.view().ok_or_else(|| bad(path, format!("{what} has no buffer view")))?;
    let size = acc.size();
    let stride = view.stride().unwrap_or(size);
    let buffer = &buffers[view.buffer().index()];
    let end_of_view = view.offset().checked_add(view.length());
    let need = acc
        .count()
        .checked_sub(1)
        .and_then(|n| n.checked_mul(stride))
        .and_then(|n| n.checked_add(size))
        .and_then(|n| n.checked_add(acc.offset()));
    match (need, end_of_view) {
        _ if stride < size => Err(bad(path, format!("{what}: stride {stride} under its element size {size}"))),
        (Some(n), Some(e)) if n <= view.length() && e <= buffer.len() => Ok(()),
        (None, _) if acc.count() == 0 => Err(bad(path, format!("{what} has no elements"))),
        _ => Err(bad(path, format!("{what} reaches past its buffer ({} bytes)", buffer.len()))),
    }
}

/// Loads every buffer: the .glb's binary chunk, or the URI's bytes.
fn load_buffers(path: &Path, doc: &gltf::Gltf, read: ReadFn) -> Result<Vec<Vec<u8>>> {
    let mut out = Vec::new();
    for b in doc.buffers() {
        let data = match b.source() {
            gltf::buffer::Source::Bin => doc
                .blob
                .clone()
                .ok_or_else(|| bad(path, format!("buffer {} names a binary chunk the file lacks", b.index())))?,
            gltf::buffer::Source::Uri(uri) => read_uri(path, uri, read)?.0,
        };
        if data.len() < b.length() {
            return Err(bad(path, format!("buffer {} holds {} bytes, {} declared", b.index(), data.len(), b.length())));
        }
        out.push(data);
    }
    Ok(out)
}

/// Decodes the images materials use, once each per colour space.
struct Images<'a> {
    path: &'a Path,
    read: ReadFn<'a>,
    buffers: &'a [Vec<u8>],
    textures: Vec<Texture>,
    cache: HashMap<(usize, bool), usize>,
}

impl Images<'_> {
    /// The encoded bytes of `image`, and a path naming it in messages.
    fn bytes(&self, image: &gltf::Image) -> Result<(Vec<u8>, PathBuf)> {
        match image.source() {
            gltf::image::Source::Uri { uri, .. } => read_uri(self.path, uri, self.read),
            gltf::image::Source::View { view, .. } => {
                let data = &self.buffers[view.buffer().index()];
                let end = view.offset().checked_add(view.length()).filter(|&e| e <= data.len());
                let end =
                    end.ok_or_else(|| bad(self.path, format!("image {} reaches past its buffer", image.index())))?;
                Ok((data[view.offset()..end].to_vec(), self.path.join(format!("image{}", image.index()))))
            }
        }
    }

    fn decode(&self, image: &gltf::Image, srgb: bool) -> Result<Texture> {
        let (bytes, file) = self.bytes(image)?;
        decode_texture(&file, &bytes, srgb)
            .map_err(|e| Error::input(self.path, format!("image {} ({}): {e}", image.index(), file.display())))
    }

    fn load(&mut self, info: &gltf::texture::Texture, srgb: bool) -> Result<usize> {
        let image = info.source();
        if let Some(&i) = self.cache.get(&(image.index(), srgb)) {
            return Ok(i);
        }
        let texture = self.decode(&image, srgb)?;
        self.textures.push(texture);
        self.cache.insert((image.index(), srgb), self.textures.len() - 1);
        Ok(self.textures.len() - 1)
    }

    /// The mean of a texture's channels (decoded from sRGB to linear when `srgb`).
    fn mean(&self, info: &gltf::texture::Texture, srgb: bool) -> Result<Vec4> {
        let t = self.decode(&info.source(), srgb)?;
        let decode = |c: u8| {
            let v = c as f32 / 255.0;
            match srgb {
                true if v > 0.04045 => ((v + 0.055) / 1.055).powf(2.4),
                true => v / 12.92,
                false => v,
            }
        };
        let mut sum = Vec4::ZERO;
        for px in t.rgba.chunks_exact(4) {
            sum += Vec4::new(decode(px[0]), decode(px[1]), decode(px[2]), px[3] as f32 / 255.0);
        }
        Ok(sum / (t.rgba.len() / 4).max(1) as f32)
    }
}

fn convert_material(m: &gltf::Material, images: &mut Images, warnings: &mut Vec<String>) -> Result<Material> {
    let name = m.name().map(str::to_owned).unwrap_or_else(|| format!("material {}", m.index().unwrap_or(0)));
    let path = images.path;
    let mut notes: Vec<String> = Vec::new();
    let pbr = m.pbr_metallic_roughness();
    let base = pbr.base_color_factor();
    let mut metallic = pbr.metallic_factor();
    let mut roughness = pbr.roughness_factor();
    let mut emissive = Vec3::from(m.emissive_factor()) * m.emissive_strength().unwrap_or(1.0);
    let uses = |notes: &mut Vec<String>, info: &gltf::texture::Info, what: &str| {
        if info.tex_coord() != 0 {
            notes.push(format!("{what} reads texture coordinates {}; vct reads set 0", info.tex_coord()));
        }
    };
    let albedo_texture = match pbr.base_color_texture() {
        Some(info) => {
            uses(&mut notes, &info, "base colour texture");
            Some(images.load(&info.texture(), true)?)
        }
        None => None,
    };
    let normal_texture = match m.normal_texture() {
        Some(info) => Some(images.load(&info.texture(), false)?),
        None => None,
    };
    if let Some(info) = pbr.metallic_roughness_texture() {
        uses(&mut notes, &info, "metallic-roughness texture");
        let mean = images.mean(&info.texture(), false)?;
        roughness *= mean.y;
        metallic *= mean.z;
        notes.push(format!(
            "the metallic-roughness texture is folded into its factors by its mean (roughness {roughness:.3}, metallic {metallic:.3}): vct's materials hold one value each"
        ));
    }
    if let Some(info) = m.emissive_texture() {
        uses(&mut notes, &info, "emissive texture");
        let mean = images.mean(&info.texture(), true)?;
        emissive *= mean.truncate();
        notes.push(format!(
            "the emissive texture is folded into the emissive factor by its mean ({:.3} {:.3} {:.3}): vct's materials emit one radiance each",
            emissive.x, emissive.y, emissive.z
        ));
    }
    match m.alpha_mode() {
        gltf::material::AlphaMode::Opaque => {}
        mode => notes.push(format!("alpha mode {mode:?} is drawn opaque")),
    }
    let albedo = Vec3::new(base[0], base[1], base[2]);
    warnings.extend(notes.into_iter().map(|n| format!("{}: material '{name}': {n}", path.display())));
    Ok(Material {
        name,
        albedo,
        emissive,
        // glTF's dielectric: F0 = 0.04.
        specular: Vec3::splat(0.04),
        roughness: roughness.clamp(0.02, 1.0),
        metallic: metallic.clamp(0.0, 1.0),
        albedo_texture,
        normal_texture,
        area_light: false,
    })
}

/// The glTF default material (specification §3.9.6): white, fully metallic and rough.
fn default_material() -> Material {
    Material {
        name: "glTF default".into(),
        albedo: Vec3::ONE,
        emissive: Vec3::ZERO,
        specular: Vec3::splat(0.04),
        roughness: 1.0,
        metallic: 1.0,
        albedo_texture: None,
        normal_texture: None,
        area_light: false,
    }
}

/// Triangles of a primitive's index list under its mode (strips and fans unrolled).
fn triangles(mode: Mode, idx: &[u32]) -> Vec<[u32; 3]> {
    match mode {
        Mode::Triangles => idx.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
        Mode::TriangleStrip => (2..idx.len())
            .map(|i| if i % 2 == 0 { [idx[i - 2], idx[i - 1], idx[i]] } else { [idx[i - 1], idx[i - 2], idx[i]] })
            .collect(),
        Mode::TriangleFan => (2..idx.len()).map(|i| [idx[0], idx[i - 1], idx[i]]).collect(),
        _ => Vec::new(),
    }
}

/// Everything gathered while walking the nodes.
struct Walk<'a> {
    path: &'a Path,
    buffers: &'a [Vec<u8>],
    vertices: Vec<Vertex>,
    /// Whether each vertex's tangent came from the file.
    has_tangent: Vec<bool>,
    per_material: Vec<Vec<u32>>,
    camera: Option<Camera>,
    lights: Vec<Light>,
    non_finite: usize,
    ignored: Vec<String>,
}

impl Walk<'_> {
    fn ignore(&mut self, what: String) {
        if !self.ignored.contains(&what) {
            self.ignored.push(what);
        }
    }

    fn node(&mut self, node: &gltf::Node, parent: Mat4, depth: usize) -> Result<()> {
        if depth > MAX_NODE_DEPTH {
            return Err(bad(self.path, format!("node {} lies {MAX_NODE_DEPTH} levels deep (a cycle?)", node.index())));
        }
        let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
        if !world.is_finite() {
            return Err(bad(self.path, format!("node {} has a non-finite transform", node.index())));
        }
        if node.skin().is_some() {
            self.ignore("skinning (drawn in the bind pose)".into());
        }
        if let Some(mesh) = node.mesh() {
            for prim in mesh.primitives() {
                self.primitive(&prim, world)?;
            }
        }
        if let Some(cam) = node.camera() {
            self.camera_node(&cam, world);
        }
        if let Some(light) = node.light() {
            self.light_node(&light, world);
        }
        for child in node.children() {
            self.node(&child, world, depth + 1)?;
        }
        Ok(())
    }

    fn primitive(&mut self, prim: &gltf::Primitive, world: Mat4) -> Result<()> {
        let mode = prim.mode();
        if !matches!(mode, Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan) {
            self.ignore(format!("primitives of mode {mode:?} (only triangles are voxelized)"));
            return Ok(());
        }
        if prim.morph_targets().next().is_some() {
            self.ignore("morph targets (drawn in the base shape)".into());
        }
        let (path, buffers) = (self.path, self.buffers);
        let f32_only = [DataType::F32];
        let positions = prim.get(&Semantic::Positions).ok_or_else(|| bad(path, "a primitive has no POSITION"))?;
        check_accessor(path, &positions, &[Dimensions::Vec3], &f32_only, buffers)?;
        let normals = prim.get(&Semantic::Normals);
        if let Some(a) = &normals {
            check_accessor(path, a, &[Dimensions::Vec3], &f32_only, buffers)?;
        }
        let tangents = prim.get(&Semantic::Tangents);
        if let Some(a) = &tangents {
            check_accessor(path, a, &[Dimensions::Vec4], &f32_only, buffers)?;
        }
        let uvs = prim.get(&Semantic::TexCoords(0));
        if let Some(a) = &uvs {
            check_accessor(path, a, &[Dimensions::Vec2], &[DataType::F32, DataType::U8, DataType::U16], buffers)?;
        }
        if let Some(a) = prim.indices() {
            check_accessor(path, &a, &[Dimensions::Scalar], &[DataType::U8, DataType::U16, DataType::U32], buffers)?;
        }
        let reader = prim.reader(|b| buffers.get(b.index()).map(|v| v.as_slice()));
        let pos: Vec<[f32; 3]> = reader.read_positions().map(|i| i.collect()).unwrap_or_default();
        let n = pos.len();
        let attr = |len: usize, what: &str| {
            if len == n {
                Ok(())
            } else {
                Err(bad(path, format!("{what} has {len} elements for {n} positions")))
            }
        };
        let nrm: Vec<[f32; 3]> = reader.read_normals().map(|i| i.collect()).unwrap_or_default();
        let tan: Vec<[f32; 4]> = reader.read_tangents().map(|i| i.collect()).unwrap_or_default();
        let uv: Vec<[f32; 2]> = reader.read_tex_coords(0).map(|i| i.into_f32().collect()).unwrap_or_default();
        for (len, what, given) in [
            (nrm.len(), "NORMAL", normals.is_some()),
            (tan.len(), "TANGENT", tangents.is_some()),
            (uv.len(), "TEXCOORD_0", uvs.is_some()),
        ] {
            if given {
                attr(len, what)?;
            }
        }
        let idx: Vec<u32> = match reader.read_indices() {
            Some(i) => i.into_u32().collect(),
            None => (0..n as u32).collect(),
        };
        if let Some(&bad_index) = idx.iter().find(|&&i| i as usize >= n) {
            return Err(bad(path, format!("index {bad_index} past the primitive's {n} vertices")));
        }
        let normal_matrix = Mat3::from_mat4(world).inverse().transpose();
        let linear = Mat3::from_mat4(world);
        let flip = linear.determinant() < 0.0;
        let base = self.vertices.len() as u32;
        for (i, &p) in pos.iter().enumerate() {
            let p = world.transform_point3(Vec3::from(p));
            let normal = nrm.get(i).map(|&v| (normal_matrix * Vec3::from(v)).normalize_or_zero()).unwrap_or(Vec3::ZERO);
            let tangent = tan.get(i).map(|&t| {
                let d = (linear * Vec3::from([t[0], t[1], t[2]])).normalize_or_zero();
                [d.x, d.y, d.z, if flip { -t[3] } else { t[3] }]
            });
            self.has_tangent.push(tangent.is_some());
            self.vertices.push(Vertex {
                pos: p.into(),
                normal: normal.into(),
                uv: uv.get(i).copied().unwrap_or([0.0; 2]),
                tangent: tangent.unwrap_or([0.0; 4]),
            });
        }
        let material = prim.material().index().unwrap_or(self.per_material.len() - 1);
        for t in triangles(mode, &idx) {
            let t = if flip { [t[0], t[2], t[1]] } else { t };
            let corners = t.map(|i| Vec3::from(self.vertices[(base + i) as usize].pos));
            if !corners.iter().all(|c| c.is_finite()) {
                self.non_finite += 1;
                continue;
            }
            self.per_material[material].extend(t.map(|i| base + i));
        }
        Ok(())
    }

    fn camera_node(&mut self, cam: &gltf::Camera, world: Mat4) {
        match cam.projection() {
            gltf::camera::Projection::Perspective(p) if self.camera.is_none() => {
                let eye = world.transform_point3(Vec3::ZERO);
                let forward = world.transform_vector3(-Vec3::Z).normalize_or_zero();
                let up = world.transform_vector3(Vec3::Y).normalize_or_zero();
                let height = 512u32;
                let width = p
                    .aspect_ratio()
                    .filter(|a| a.is_finite() && *a > 0.0)
                    .map(|a| ((height as f32 * a).round() as u32).clamp(1, super::MAX_IMAGE_SIZE))
                    .unwrap_or(height);
                let fov = p.yfov().to_degrees();
                if forward == Vec3::ZERO || up == Vec3::ZERO || !(fov > 0.0 && fov < 180.0) {
                    self.ignore(format!("camera {}: a degenerate view or field of view {fov}°", cam.index()));
                    return;
                }
                self.camera = Some(Camera { eye, target: eye + forward, up, fov_y_deg: fov, width, height });
            }
            gltf::camera::Projection::Perspective(_) => {}
            gltf::camera::Projection::Orthographic(_) => self.ignore("orthographic cameras".into()),
        }
    }

    fn light_node(&mut self, light: &gltf::khr_lights_punctual::Light, world: Mat4) {
        use gltf::khr_lights_punctual::Kind;
        let colour = Vec3::from(light.color()) * light.intensity() / LUMENS_PER_WATT;
        let direction = world.transform_vector3(-Vec3::Z).normalize_or_zero();
        if !colour.is_finite() || colour.min_element() < 0.0 || direction == Vec3::ZERO {
            self.ignore(format!("light {}: colour {colour} or direction {direction} unusable", light.index()));
            return;
        }
        match light.kind() {
            Kind::Directional => self.lights.push(Light::Directional { direction, irradiance: colour }),
            Kind::Spot { inner_cone_angle, outer_cone_angle } => {
                // glTF allows outer angles up to 90°, which a spot's shadow frustum cannot hold.
                let outer = outer_cone_angle.to_degrees().clamp(0.0, 89.0);
                let inner = inner_cone_angle.to_degrees().clamp(0.0, outer);
                let position = world.transform_point3(Vec3::ZERO);
                self.lights.push(Light::Spot {
                    position,
                    direction,
                    intensity: colour,
                    inner_deg: inner,
                    outer_deg: outer,
                });
            }
            Kind::Point => {
                self.lights.push(Light::Point { position: world.transform_point3(Vec3::ZERO), intensity: colour })
            }
        }
    }
}

/// The crate's validation reads each primitive's POSITION accessor without checking that it
/// exists: a POSITION index past the accessors is refused here. JSON the
/// crate cannot read is left to its own error.
fn check_position_indices(path: &Path, bytes: &[u8]) -> Result<()> {
    let json = match bytes.starts_with(b"glTF") {
        true => match gltf::Glb::from_slice(bytes) {
            Ok(glb) => glb.json.into_owned(),
            Err(_) => return Ok(()),
        },
        false => bytes.to_vec(),
    };
    let Ok(root) = gltf::json::deserialize::from_slice::<gltf::json::Root>(&json) else { return Ok(()) };
    let positions = gltf::json::validation::Checked::Valid(gltf::json::mesh::Semantic::Positions);
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            if let Some(i) = prim.attributes.get(&positions).filter(|i| i.value() >= root.accessors.len()) {
                return Err(bad(
                    path,
                    format!(
                        "mesh {m} primitive {p}: POSITION names accessor {}, of {}",
                        i.value(),
                        root.accessors.len()
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// Loads a `.gltf` or `.glb`: the default scene's (or the first scene's) nodes, flattened.
pub fn load_gltf(path: &Path, read: ReadFn, warnings: &mut Vec<String>) -> Result<GltfScene> {
    let bytes = read(path).map_err(|e| Error::Io { path: path.to_path_buf(), source: e })?;
    // The crate subtracts the header's size from the length a .glb header declares without a
    // check: a declared length under 12 bytes is refused here.
    if bytes.starts_with(b"glTF") {
        let declared = bytes.get(8..12).map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]));
        if declared.is_none_or(|n| n < 12) {
            return Err(bad(path, format!("binary glTF header declares {declared:?} bytes, under its own 12")));
        }
    }
    check_position_indices(path, &bytes)?;
    let doc = gltf::Gltf::from_slice(&bytes).map_err(|e| bad(path, e))?;
    if let Some(ext) = doc.extensions_required().find(|e| !SUPPORTED_EXTENSIONS.contains(e)) {
        return Err(Error::input(path, format!("requires the extension {ext}, which vct does not read")));
    }
    let unread: Vec<&str> = doc.extensions_used().filter(|e| !SUPPORTED_EXTENSIONS.contains(e)).collect();
    if !unread.is_empty() {
        warnings.push(format!("{}: extensions not read: {}", path.display(), unread.join(", ")));
    }
    if doc.animations().next().is_some() {
        warnings.push(format!("{}: animations are not played (the scene is drawn as posed)", path.display()));
    }
    let buffers = load_buffers(path, &doc, read)?;
    let mut images = Images { path, read, buffers: &buffers, textures: Vec::new(), cache: HashMap::new() };
    let mut materials = Vec::new();
    for m in doc.materials() {
        materials.push(convert_material(&m, &mut images, warnings)?);
    }
    materials.push(default_material());
    let scene = doc.default_scene().or_else(|| doc.scenes().next()).ok_or_else(|| bad(path, "no scene"))?;
    let mut walk = Walk {
        path,
        buffers: &buffers,
        vertices: Vec::new(),
        has_tangent: Vec::new(),
        per_material: vec![Vec::new(); materials.len()],
        camera: None,
        lights: Vec::new(),
        non_finite: 0,
        ignored: Vec::new(),
    };
    for node in scene.nodes() {
        walk.node(&node, Mat4::IDENTITY, 0)?;
    }
    if walk.non_finite > 0 {
        warnings.push(format!(
            "{}: dropped {} triangle(s) with non-finite coordinates",
            path.display(),
            walk.non_finite
        ));
    }
    if !walk.ignored.is_empty() {
        warnings.push(format!("{}: not rendered: {}", path.display(), walk.ignored.join("; ")));
    }
    let Walk { mut vertices, has_tangent, per_material, camera, lights, .. } = walk;
    let mut indices = Vec::new();
    let mut draws = Vec::new();
    for (material, list) in per_material.into_iter().enumerate() {
        if !list.is_empty() {
            draws.push(Draw {
                first_index: indices.len() as u32,
                index_count: list.len() as u32,
                material: material as u32,
            });
            indices.extend(list);
        }
    }
    compute_normals(&mut vertices, &indices);
    for v in &mut vertices {
        let n = Vec3::from(v.normal);
        v.normal = if n.is_finite() && n.length_squared() > 0.0 { n.normalize().into() } else { [0.0, 1.0, 0.0] };
    }
    if materials.iter().any(|m| m.normal_texture.is_some()) && has_tangent.iter().any(|t| !t) {
        // Tangents from UV derivatives where the file gives none; the file's where it does.
        let given: Vec<[f32; 4]> = vertices.iter().map(|v| v.tangent).collect();
        compute_tangents(&mut vertices, &indices);
        for ((v, t), has) in vertices.iter_mut().zip(given).zip(has_tangent) {
            if has {
                v.tangent = t;
            }
        }
    }
    let mut bounds = Aabb::EMPTY;
    for &i in &indices {
        bounds.grow(Vec3::from(vertices[i as usize].pos));
    }
    Ok(GltfScene {
        mesh: Mesh { vertices, indices, draws, bounds },
        materials,
        textures: images.textures,
        camera,
        lights,
    })
}
