//! OBJ/MTL loading through tobj: triangles grouped by material, vertex normals computed where
//! the file has none, tangents where a material has a normal map, textures decoded by the
//! `image` crate (albedo sRGB-decoded on the GPU). Bad geometry is dropped and reported.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use glam::{Vec2, Vec3};

use super::{Aabb, Draw, Material, Mesh, Texture, Vertex};
use crate::error::{Error, Result};

/// Reads a file named in the OBJ (the OBJ itself, its MTL, textures).
pub type ReadFn<'a> = &'a dyn Fn(&Path) -> std::io::Result<Vec<u8>>;

fn parse_floats(s: &str) -> Option<Vec3> {
    let v: Vec<f32> = s.split_whitespace().filter_map(|w| w.parse().ok()).collect();
    match v.len() {
        1 => Some(Vec3::splat(v[0])),
        3 => Some(Vec3::new(v[0], v[1], v[2])),
        _ => None,
    }
}

/// The perceptual roughness (GGX alpha = roughness², common/brdf.glsl) of a Phong exponent `ns`:
/// Walter et al. 2007 match the Phong lobe by alpha = sqrt(2 / (ns + 2)). (Taking that alpha
/// for the roughness itself would square it once more: the classic Cornell box's boxes, `Ns
/// 200`, would get alpha 0.0099 for the paper's 0.0995, a near mirror.)
pub fn roughness_of_phong(ns: f32) -> f32 {
    (2.0 / (ns.max(0.0) + 2.0)).sqrt().sqrt()
}

fn fmt_colour(v: Vec3) -> String {
    format!("{} {} {}", v.x, v.y, v.z)
}

/// Decodes an encoded image (PNG, JPEG, ...) into an RGBA8 texture; `path` names it.
pub(super) fn decode_texture(path: &Path, bytes: &[u8], srgb: bool) -> std::result::Result<Texture, String> {
    let rgba = image::load_from_memory(bytes).map_err(|e| e.to_string())?.to_rgba8();
    Ok(Texture { path: path.to_path_buf(), width: rgba.width(), height: rgba.height(), rgba: rgba.into_raw(), srgb })
}

fn load_texture(
    path: &Path,
    srgb: bool,
    read: ReadFn,
    textures: &mut Vec<Texture>,
    cache: &mut HashMap<(PathBuf, bool), usize>,
    warnings: &mut Vec<String>,
) -> Option<usize> {
    if let Some(&i) = cache.get(&(path.to_path_buf(), srgb)) {
        return Some(i);
    }
    let decoded = read(path).map_err(|e| e.to_string()).and_then(|bytes| decode_texture(path, &bytes, srgb));
    match decoded {
        Ok(texture) => {
            textures.push(texture);
            cache.insert((path.to_path_buf(), srgb), textures.len() - 1);
            Some(textures.len() - 1)
        }
        Err(e) => {
            warnings.push(format!("texture {}: {e}; using a flat colour", path.display()));
            None
        }
    }
}

fn convert_material(
    m: &tobj::Material,
    obj: &Path,
    dir: &Path,
    read: ReadFn,
    textures: &mut Vec<Texture>,
    cache: &mut HashMap<(PathBuf, bool), usize>,
    warnings: &mut Vec<String>,
) -> Material {
    let albedo = m.diffuse.map(Vec3::from).unwrap_or(Vec3::splat(0.8));
    let emissive = m
        .emissive
        .map(Vec3::from)
        .or_else(|| m.unknown_param.get("Ke").and_then(|s| parse_floats(s)))
        .unwrap_or(Vec3::ZERO);
    let param = |k: &str| m.unknown_param.get(k).and_then(|s| s.trim().parse::<f32>().ok());
    // Roughness: PBR extension `Pr`, else from the Phong exponent.
    let roughness = param("Pr").or_else(|| m.shininess.map(roughness_of_phong)).unwrap_or(0.8).clamp(0.02, 1.0);
    let metallic = param("Pm").unwrap_or(0.0).clamp(0.0, 1.0);
    let specular = m.specular.map(Vec3::from).unwrap_or(Vec3::splat(0.04));
    let tex_path = |t: &String| dir.join(t.trim().replace('\\', "/"));
    let albedo_texture =
        m.diffuse_texture.as_ref().and_then(|t| load_texture(&tex_path(t), true, read, textures, cache, warnings));
    let normal_texture =
        m.normal_texture.as_ref().and_then(|t| load_texture(&tex_path(t), false, read, textures, cache, warnings));
    // A colour that makes no sense (NaN, infinite, negative, or a reflectance above 1) is
    // replaced, and the warning names the file, the material and the value: never a silent
    // black or dim surface.
    let mut sanitize = |key: &str, v: Vec3, most: f32| {
        let fixed = if v.is_finite() { v.clamp(Vec3::ZERO, Vec3::splat(most)) } else { Vec3::ZERO };
        if fixed != v {
            warnings.push(format!(
                "{} (its MTL): material '{}': {key} {} is not a usable colour (finite, non-negative{}); using {}",
                obj.display(),
                m.name,
                fmt_colour(v),
                if most.is_finite() { ", at most 1" } else { "" },
                fmt_colour(fixed)
            ));
        }
        fixed
    };
    let (albedo, emissive, specular) =
        (sanitize("Kd", albedo, 1.0), sanitize("Ke", emissive, f32::INFINITY), sanitize("Ks", specular, 1.0));
    Material {
        name: m.name.clone(),
        albedo,
        emissive,
        specular,
        roughness,
        metallic,
        albedo_texture,
        normal_texture,
        area_light: false,
    }
}

/// Rewrites colour lines tobj cannot take: `Kd r` means `Kd r r r` (the MTL format), and a line
/// with no or two numbers, which tobj 4 panics on, is dropped with a warning.
fn sanitize_mtl(text: &str, path: &Path, warnings: &mut Vec<String>) -> String {
    let mut out = String::with_capacity(text.len());
    for (n, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        let key = words.next().unwrap_or("");
        let rest: Vec<&str> = words.collect();
        if matches!(key, "Ka" | "Kd" | "Ks" | "Ke") && rest.iter().all(|w| w.parse::<f32>().is_ok()) {
            match rest.len() {
                1 => {
                    out.push_str(&format!("{key} {0} {0} {0}\n", rest[0]));
                    continue;
                }
                0 | 2 => {
                    warnings.push(format!(
                        "{}:{}: '{}' needs 1 or 3 values; ignored",
                        path.display(),
                        n + 1,
                        line.trim()
                    ));
                    continue;
                }
                _ => {}
            }
        }
        out.push_str(line);
        out.push('\n');
    }
    out
}

/// Finds the first face, line or point index that refers to no element: a relative (negative)
/// index reaching before the first position, texture coordinate or normal, or one no mesh could
/// use (>= 2^31). tobj 4 turns such indices into huge offsets and multiplies them unchecked,
/// which panics. Returns the line number and the index.
fn bad_index(text: &str) -> Option<(usize, i128)> {
    let mut counts = [0i128; 3]; // v, vt, vn so far
    for (n, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => counts[0] += 1,
            Some("vt") => counts[1] += 1,
            Some("vn") => counts[2] += 1,
            Some("f" | "l" | "p") => {
                for word in words {
                    for (k, c) in word.split('/').take(3).enumerate() {
                        let Ok(i) = c.parse::<i128>() else { continue };
                        if i >= 1 << 31 || (i < 0 && -i > counts[k]) {
                            return Some((n + 1, i));
                        }
                    }
                }
            }
            _ => {}
        }
    }
    None
}

/// Loads an OBJ (and its MTL and textures) into one indexed mesh with a draw per material.
pub fn load_obj(path: &Path, read: ReadFn, warnings: &mut Vec<String>) -> Result<(Mesh, Vec<Material>, Vec<Texture>)> {
    let bytes = read(path).map_err(|e| Error::Io { path: path.to_path_buf(), source: e })?;
    if let Some((line, index)) = bad_index(&String::from_utf8_lossy(&bytes)) {
        return Err(Error::input(path, format!("malformed OBJ: index {index} on line {line} is out of range")));
    }
    let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
    let opts = tobj::LoadOptions { triangulate: true, single_index: true, ignore_points: true, ignore_lines: true };
    let mtl_warnings = std::cell::RefCell::new(Vec::new());
    let (models, materials) = tobj::load_obj_buf(&mut std::io::Cursor::new(&bytes), &opts, |mtl| {
        let p = dir.join(mtl);
        match read(&p) {
            Ok(b) => {
                let text = sanitize_mtl(&String::from_utf8_lossy(&b), &p, &mut mtl_warnings.borrow_mut());
                tobj::load_mtl_buf(&mut std::io::Cursor::new(text.into_bytes()))
            }
            Err(e) => {
                mtl_warnings.borrow_mut().push(format!("material library {}: {e}", p.display()));
                Err(tobj::LoadError::OpenFileFailed)
            }
        }
    })
    .map_err(|e| Error::input(path, format!("malformed OBJ: {e}")))?;
    warnings.extend(mtl_warnings.into_inner());
    let tobj_materials = match materials {
        Ok(m) => m,
        Err(e) => {
            warnings.push(format!("{}: materials not loaded ({e}); using a default grey", path.display()));
            Vec::new()
        }
    };

    let mut textures = Vec::new();
    let mut cache = HashMap::new();
    let mut mats: Vec<Material> = tobj_materials
        .iter()
        .map(|m| convert_material(m, path, &dir, read, &mut textures, &mut cache, warnings))
        .collect();
    let default_material = mats.len();
    mats.push(Material::default_grey());

    // Gather triangles per material; drop those with non-finite corners.
    let mut vertices: Vec<Vertex> = Vec::new();
    let mut per_material: Vec<Vec<u32>> = vec![Vec::new(); mats.len()];
    let (mut non_finite, mut degenerate) = (0usize, 0usize);
    let mut any_normals_missing = false;
    for model in &models {
        let m = &model.mesh;
        let base = vertices.len() as u32;
        let n = m.positions.len() / 3;
        let has_normals = m.normals.len() == m.positions.len();
        let has_uv = m.texcoords.len() / 2 == n;
        any_normals_missing |= !has_normals;
        for i in 0..n {
            let pos = [m.positions[3 * i], m.positions[3 * i + 1], m.positions[3 * i + 2]];
            let normal =
                if has_normals { [m.normals[3 * i], m.normals[3 * i + 1], m.normals[3 * i + 2]] } else { [0.0; 3] };
            // OBJ has v = 0 at the bottom of the image; Vulkan's row 0 is the top.
            let uv = if has_uv { [m.texcoords[2 * i], 1.0 - m.texcoords[2 * i + 1]] } else { [0.0; 2] };
            vertices.push(Vertex { pos, normal, uv, tangent: [0.0; 4] });
        }
        let mat = m.material_id.filter(|&id| id < tobj_materials.len()).unwrap_or(default_material);
        for tri in m.indices.chunks_exact(3) {
            let idx = [base + tri[0], base + tri[1], base + tri[2]];
            let p: Vec<Vec3> = idx.iter().map(|&i| Vec3::from(vertices[i as usize].pos)).collect();
            if !p.iter().all(|v| v.is_finite()) {
                non_finite += 1;
                continue;
            }
            if (p[1] - p[0]).cross(p[2] - p[0]).length_squared() == 0.0 {
                degenerate += 1;
            }
            per_material[mat].extend_from_slice(&idx);
        }
    }
    if non_finite > 0 {
        warnings
            .push(format!("{}: dropped {non_finite} triangle(s) with non-finite vertex coordinates", path.display()));
    }
    if degenerate > 0 {
        warnings.push(format!("{}: {degenerate} zero-area triangle(s) (kept; they cover nothing)", path.display()));
    }

    let mut indices = Vec::new();
    let mut draws = Vec::new();
    for (material, list) in per_material.into_iter().enumerate() {
        if list.is_empty() {
            continue;
        }
        draws.push(Draw {
            first_index: indices.len() as u32,
            index_count: list.len() as u32,
            material: material as u32,
        });
        indices.extend(list);
    }
    if any_normals_missing {
        compute_normals(&mut vertices, &indices);
    }
    for v in &mut vertices {
        let n = Vec3::from(v.normal);
        v.normal = if n.is_finite() && n.length_squared() > 0.0 { n.normalize().into() } else { [0.0, 1.0, 0.0] };
    }
    if mats.iter().any(|m| m.normal_texture.is_some()) {
        compute_tangents(&mut vertices, &indices);
    }
    let mut bounds = Aabb::EMPTY;
    for &i in &indices {
        bounds.grow(Vec3::from(vertices[i as usize].pos));
    }
    Ok((Mesh { vertices, indices, draws, bounds }, mats, textures))
}

/// Area-weighted vertex normals, for vertices whose normal the file left out (zero).
pub(super) fn compute_normals(vertices: &mut [Vertex], indices: &[u32]) {
    let missing: Vec<bool> = vertices.iter().map(|v| Vec3::from(v.normal) == Vec3::ZERO).collect();
    let mut acc = vec![Vec3::ZERO; vertices.len()];
    for t in indices.chunks_exact(3) {
        let p = |k: usize| Vec3::from(vertices[t[k] as usize].pos);
        let n = (p(1) - p(0)).cross(p(2) - p(0));
        for &i in t {
            acc[i as usize] += n;
        }
    }
    for (i, v) in vertices.iter_mut().enumerate() {
        if missing[i] {
            v.normal = acc[i].normalize_or_zero().into();
        }
    }
}

/// Per-vertex tangents from UV derivatives (Lengyel's method), handedness in `w`.
pub(super) fn compute_tangents(vertices: &mut [Vertex], indices: &[u32]) {
    let mut tan = vec![Vec3::ZERO; vertices.len()];
    let mut bit = vec![Vec3::ZERO; vertices.len()];
    for t in indices.chunks_exact(3) {
        let v = |k: usize| &vertices[t[k] as usize];
        let (p0, p1, p2) = (Vec3::from(v(0).pos), Vec3::from(v(1).pos), Vec3::from(v(2).pos));
        let (w0, w1, w2) = (Vec2::from(v(0).uv), Vec2::from(v(1).uv), Vec2::from(v(2).uv));
        let (e1, e2, d1, d2) = (p1 - p0, p2 - p0, w1 - w0, w2 - w0);
        let det = d1.x * d2.y - d2.x * d1.y;
        if det.abs() < 1e-12 {
            continue;
        }
        let r = 1.0 / det;
        let s = (e1 * d2.y - e2 * d1.y) * r;
        let b = (e2 * d1.x - e1 * d2.x) * r;
        for &i in t {
            tan[i as usize] += s;
            bit[i as usize] += b;
        }
    }
    for (i, v) in vertices.iter_mut().enumerate() {
        let n = Vec3::from(v.normal);
        let t = (tan[i] - n * n.dot(tan[i])).normalize_or_zero();
        let t = if t == Vec3::ZERO { n.any_orthonormal_vector() } else { t };
        let w = if n.cross(t).dot(bit[i]) < 0.0 { -1.0 } else { 1.0 };
        v.tangent = [t.x, t.y, t.z, w];
    }
}

#[cfg(test)]
mod tests {
    use super::roughness_of_phong;

    /// Walter et al. 2007: alpha = sqrt(2 / (ns + 2)), and vct's GGX takes alpha = roughness².
    #[test]
    fn a_phong_exponent_maps_to_walters_alpha() {
        for ns in [0.0f32, 1.0, 10.0, 200.0, 1000.0] {
            let alpha = roughness_of_phong(ns).powi(2);
            assert!((alpha - (2.0 / (ns + 2.0)).sqrt()).abs() < 1e-6, "Ns {ns}: alpha {alpha}");
        }
        assert_eq!(roughness_of_phong(0.0), 1.0);
        assert!((roughness_of_phong(200.0).powi(2) - 0.0995).abs() < 1e-4);
    }
}
