//! glTF 2.0 scenes (scene::gltf): the Cornell spot scene written as glTF
//! (`scripts/gltf-cornell.py`: its mesh under two nodes whose transforms cancel, the camera and
//! the spot light as nodes, the light in candela) must load as the OBJ + TOML scene does and
//! render the same picture; malformed files are errors naming the file; and values a file may
//! carry that make no picture are errors or warnings naming the file and the value.

mod common;

use std::path::{Path, PathBuf};

use glam::Vec3;
use vct::render::{RenderOptions, Renderer};
use vct::scene::{Light, Scene};

const GLTF: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/gltf/cornell-spot.gltf");
const GLB: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/gltf/cornell-spot.glb");
const BIN: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/gltf/cornell-spot.bin");

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("vct-gltf-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn load_err(path: &Path) -> String {
    match Scene::load(path) {
        Ok(_) => panic!("{} loaded without error", path.display()),
        Err(e) => e.to_string(),
    }
}

/// Each triangle as its sorted corners (rounded to 10 µm) and its material's albedo.
fn triangles(s: &Scene) -> Vec<([[i64; 3]; 3], [i64; 3])> {
    let q = |v: Vec3| (v * 1e5).round().as_i64vec3().to_array();
    let mut out = Vec::new();
    for d in &s.mesh.draws {
        let albedo = q(s.materials[d.material as usize].albedo);
        for t in (d.first_index / 3)..((d.first_index + d.index_count) / 3) {
            let mut c = s.mesh.triangle(t as usize).map(q);
            c.sort();
            out.push((c, albedo));
        }
    }
    out.sort();
    out
}

#[test]
fn gltf_and_glb_load_as_the_obj_scene() {
    let obj = Scene::embedded_default().unwrap();
    for path in [GLTF, GLB] {
        let g = Scene::load(Path::new(path)).unwrap();
        assert!(g.warnings.is_empty(), "{path}: {:?}", g.warnings);
        // The hierarchy's transforms cancel: the same triangles with the same albedos.
        assert_eq!(triangles(&g), triangles(&obj), "{path}");
        let (a, b) = (g.camera, obj.camera);
        assert!(a.eye.distance(b.eye) < 1e-4, "{path}: eye {} against {}", a.eye, b.eye);
        let dir = |c: &vct::scene::Camera| (c.target - c.eye).normalize();
        assert!(dir(&a).dot(dir(&b)) > 0.99999, "{path}: view direction");
        assert!(a.up.dot(b.up) > 0.99999, "{path}: up");
        assert!((a.fov_y_deg - b.fov_y_deg).abs() < 1e-3, "{path}: fov {}", a.fov_y_deg);
        assert_eq!(a.width as f32 / a.height as f32, 1.0, "{path}: aspect");
        // 68,300 cd at 683 lm/W is the TOML's 100 W/sr.
        match (g.lights.as_slice(), obj.lights.as_slice()) {
            (
                [Light::Spot { position, direction, intensity, inner_deg, outer_deg }],
                [Light::Spot { position: p, direction: d, intensity: i, inner_deg: id, outer_deg: od }],
            ) => {
                assert!(position.distance(*p) < 1e-4 && direction.dot(*d) > 0.99999, "{path}: spot placement");
                assert!((*intensity - *i).abs().max_element() < 1e-3, "{path}: intensity {intensity}");
                assert!((inner_deg - id).abs() < 1e-3 && (outer_deg - od).abs() < 1e-3, "{path}: angles");
            }
            other => panic!("{path}: lights {other:?}"),
        }
        // KHR_materials_emissive_strength: the light quad's Ke 40.
        let emitters: Vec<Vec3> = g.materials.iter().map(|m| m.emissive).filter(|e| e.max_element() > 0.0).collect();
        assert_eq!(emitters, vec![Vec3::splat(40.0)], "{path}");
    }
}

#[test]
fn gltf_cornell_renders_the_obj_scenes_picture() {
    let ctx = common::context();
    let options = RenderOptions { resolution: Some(32), ..Default::default() };
    let mut frames = Vec::new();
    // glTF's dielectric always reflects F0 = 0.04; the MTL's Ks 0 has no specular lobe. Given the
    // same, the two scenes must render the same picture.
    let mut obj = Scene::embedded_default().unwrap();
    for m in &mut obj.materials {
        m.specular = Vec3::splat(0.04);
    }
    for mut scene in [Scene::load(Path::new(GLTF)).unwrap(), obj] {
        scene.set_size(Some(64), Some(64)).unwrap();
        let r = Renderer::new(&ctx, scene, options).unwrap();
        r.render().unwrap();
        frames.push(r.read_frame().unwrap());
    }
    common::assert_clean(&ctx);
    let (g, o) = (&frames[0], &frames[1]);
    let (mut diff, mut sum) = (0.0f64, 0.0f64);
    for (a, b) in g.hdr.chunks_exact(4).zip(o.hdr.chunks_exact(4)) {
        for k in 0..3 {
            diff += (a[k] - b[k]).abs() as f64;
            sum += b[k] as f64;
        }
    }
    assert!(sum > 0.0);
    assert!(diff / sum < 0.01, "glTF against OBJ: mean absolute difference {:.3} of the mean", diff / sum);
}

#[test]
fn malformed_gltf_is_an_error_naming_the_file() {
    let d = temp_dir("malformed");
    let glb = std::fs::read(GLB).unwrap();
    // Truncated anywhere: an error naming the file, never a panic.
    for cut in [0, 11, 12, 20, 100, glb.len() / 2, glb.len() - 9, glb.len() - 1] {
        let p = d.join(format!("cut{cut}.glb"));
        std::fs::write(&p, &glb[..cut]).unwrap();
        let e = load_err(&p);
        assert!(e.contains(&format!("cut{cut}.glb")), "{e}");
    }
    // A header that declares fewer bytes than itself (the glTF crate's unchecked subtraction).
    let mut short = glb.clone();
    short[8..12].copy_from_slice(&11u32.to_le_bytes());
    let p = d.join("short-header.glb");
    std::fs::write(&p, &short).unwrap();
    assert!(load_err(&p).contains("short-header.glb"));
    let text = std::fs::read_to_string(GLTF).unwrap();
    std::fs::copy(BIN, d.join("cornell-spot.bin")).unwrap();
    let variant = |name: &str, from: &str, to: &str| {
        assert!(text.contains(from), "{from}");
        let p = d.join(name);
        std::fs::write(&p, text.replacen(from, to, 1)).unwrap();
        p
    };
    // A buffer whose file is missing: the error names it.
    let e = load_err(&variant("nobin.gltf", "\"uri\": \"cornell-spot.bin\"", "\"uri\": \"absent.bin\""));
    assert!(e.contains("absent.bin"), "{e}");
    // An accessor past the end of its buffer.
    let e = load_err(&variant("past.gltf", "\"count\": 6,", "\"count\": 60000,"));
    assert!(e.contains("past.gltf") && e.contains("accessor"), "{e}");
    // Broken JSON.
    let e = load_err(&variant("json.gltf", "\"asset\"", "\"broken\" \"asset\""));
    assert!(e.contains("json.gltf"), "{e}");
    // A POSITION accessor that does not exist (the glTF crate's validation indexes it unchecked).
    let e = load_err(&variant("noaccessor.gltf", "\"POSITION\": 0", "\"POSITION\": 999"));
    assert!(e.contains("noaccessor.gltf") && e.contains("999"), "{e}");
    // A required extension vct cannot read.
    let e = load_err(&variant(
        "required.gltf",
        "\"extensionsUsed\": [",
        "\"extensionsRequired\": [\"KHR_draco_mesh_compression\"], \"extensionsUsed\": [\"KHR_draco_mesh_compression\", ",
    ));
    assert!(e.contains("required.gltf") && e.contains("KHR_draco_mesh_compression"), "{e}");
}

#[test]
fn unsupported_gltf_features_are_named_in_warnings_and_point_lights_load() {
    let d = temp_dir("unsupported");
    std::fs::copy(BIN, d.join("cornell-spot.bin")).unwrap();
    let text = std::fs::read_to_string(GLTF)
        .unwrap()
        .replacen("\"type\": \"spot\"", "\"type\": \"point\"", 1)
        .replacen("\"extensionsUsed\": [", "\"extensionsUsed\": [\"KHR_materials_clearcoat\", ", 1);
    let p = d.join("point.gltf");
    std::fs::write(&p, text).unwrap();
    let s = Scene::load(&p).unwrap();
    let all = s.warnings.join("\n");
    assert!(all.contains("KHR_materials_clearcoat") && all.contains("point.gltf"), "{all}");
    // The spot made a point light: 68,300 cd is 100 W/sr at its node.
    match s.lights.as_slice() {
        [Light::Point { position, intensity }] => {
            assert!(position.distance(Vec3::new(0.0, 5.45, 0.0)) < 1e-4, "{position}");
            assert!((*intensity - Vec3::splat(100.0)).abs().max_element() < 1e-3, "{intensity}");
        }
        other => panic!("lights {other:?}"),
    }
}

#[test]
fn a_scene_file_may_name_a_gltf_and_override_its_camera() {
    let d = temp_dir("toml");
    for f in ["cornell-spot.gltf", "cornell-spot.bin"] {
        std::fs::copy(Path::new(GLTF).with_file_name(f), d.join(f)).unwrap();
    }
    let p = d.join("scene.toml");
    std::fs::write(
        &p,
        "mesh = \"cornell-spot.gltf\"\n[camera]\neye = [0.0, 2.0, 9.0]\ntarget = [0.0, 2.0, 0.0]\nup = [0.0, 1.0, 0.0]\nfov_y_deg = 50.0\nwidth = 64\nheight = 48\n",
    )
    .unwrap();
    let s = Scene::load(&p).unwrap();
    assert_eq!((s.camera.width, s.camera.height, s.camera.fov_y_deg), (64, 48, 50.0));
    // No [[light]]: the glTF's spot.
    assert!(matches!(s.lights.as_slice(), [Light::Spot { .. }]), "{:?}", s.lights);
    assert_eq!(s.mesh.triangle_count(), Scene::embedded_default().unwrap().mesh.triangle_count());
}

#[test]
fn values_that_make_no_picture_are_named() {
    let d = temp_dir("values");
    let write = |name: &str, text: &str| {
        let p = d.join(name);
        std::fs::write(&p, text).unwrap();
        p
    };
    // Coordinates whose extent overflows single precision.
    let e = load_err(&write("huge.obj", "v -3e38 0 0\nv 3e38 0 0\nv 0 1 0\nf 1 2 3\n"));
    assert!(e.contains("huge.obj") && e.contains("overflows"), "{e}");
    // A camera whose up is the view direction.
    write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    let e = load_err(&write(
        "up.toml",
        "mesh = \"tri.obj\"\n[camera]\neye = [0.0, 5.0, 0.0]\ntarget = [0.0, 0.0, 0.0]\nup = [0.0, 1.0, 0.0]\nfov_y_deg = 40.0\nwidth = 64\nheight = 64\n",
    ));
    assert!(e.contains("up.toml") && e.contains("camera.up"), "{e}");
    // NaN, infinite and negative colours: a warning naming the file, the key and the value.
    write("c.mtl", "newmtl a\nKd nan 0.5 0.5\nnewmtl b\nKd 0.5 -1 0.5\nKe inf 0 0\nnewmtl c\nKd 2 2 2\n");
    let s = Scene::load(&write(
        "colours.obj",
        "mtllib c.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\nusemtl b\nf 1 3 2\nusemtl c\nf 2 1 3\n",
    ))
    .unwrap();
    let all = s.warnings.join("\n");
    for needle in ["colours.obj", "'a': Kd NaN", "'b': Kd 0.5 -1", "'b': Ke inf", "'c': Kd 2 2 2"] {
        assert!(all.contains(needle), "{needle} not in {all}");
    }
    assert!(s
        .materials
        .iter()
        .all(|m| m.albedo.is_finite() && m.albedo.max_element() <= 1.0 && m.emissive.is_finite()));
    // Emission beyond the GPU's half-float range.
    write("hot.mtl", "newmtl sun\nKd 0 0 0\nKe 1e6 1e6 1e6\n");
    let e = load_err(&write("hot.obj", "mtllib hot.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl sun\nf 1 2 3\n"));
    assert!(e.contains("hot.obj") && e.contains("'sun'") && e.contains("1000000"), "{e}");
}

/// A glTF written here: a floor of 2 × 2 m with a 2 × 2 texel texture (red left, blue right;
/// roughness 1), a small green emitter beside it, a directional light of 1366 lux straight down
/// and a camera 3 m above looking down. Buffer and image travel in one base64 data URI; the image
/// is read through a buffer view.
fn textured_gltf(dir: &Path) -> PathBuf {
    use base64::Engine;
    let mut png = Vec::new();
    let texels = [255u8, 0, 0, 255, 0, 0, 255, 255, 255, 0, 0, 255, 0, 0, 255, 255];
    image::RgbaImage::from_raw(2, 2, texels.to_vec())
        .unwrap()
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    let mut bin: Vec<u8> = Vec::new();
    let mut put = |v: &[f32]| v.iter().for_each(|x| bin.extend(x.to_le_bytes()));
    // Floor (y = 0, uv from x and z) then the emitter (x 1.2..1.6, z -0.2..0.2).
    put(&[-1., 0., -1., 1., 0., -1., 1., 0., 1., -1., 0., 1.]);
    put(&[1.2, 0., -0.2, 1.6, 0., -0.2, 1.6, 0., 0.2, 1.2, 0., 0.2]);
    put(&[0., 1., 0.].repeat(8));
    put(&[0., 0., 1., 0., 1., 1., 0., 1.].repeat(2));
    let image_offset = bin.len();
    bin.extend(&png);
    bin.resize(bin.len().next_multiple_of(4), 0);
    // Each primitive indexes its own vertices.
    for t in [[0u16, 2, 1], [0, 3, 2], [0, 2, 1], [0, 3, 2]] {
        t.iter().for_each(|i| bin.extend(i.to_le_bytes()));
    }
    let index_offset = bin.len() - 24;
    let s = std::f32::consts::FRAC_1_SQRT_2;
    let down = serde_json::json!([-s, 0.0, 0.0, s]);
    let uri =
        format!("data:application/octet-stream;base64,{}", base64::engine::general_purpose::STANDARD.encode(&bin));
    let doc = serde_json::json!({
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional", "intensity": 1366.0}]}},
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [
            {"mesh": 0},
            {"camera": 0, "translation": [0.0, 3.0, 0.0], "rotation": down},
            {"extensions": {"KHR_lights_punctual": {"light": 0}}, "rotation": down}
        ],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 60f32.to_radians(), "aspectRatio": 1.0, "znear": 0.1}}],
        "meshes": [{"primitives": [
            {"attributes": {"POSITION": 0, "NORMAL": 2, "TEXCOORD_0": 4}, "indices": 6, "material": 0},
            {"attributes": {"POSITION": 1, "NORMAL": 3, "TEXCOORD_0": 5}, "indices": 7, "material": 1}
        ]}],
        "materials": [
            {"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0, "roughnessFactor": 1.0}},
            {"pbrMetallicRoughness": {"baseColorFactor": [0.0, 0.0, 0.0, 1.0], "metallicFactor": 0.0}, "emissiveFactor": [0.0, 1.0, 0.0]}
        ],
        "textures": [{"source": 0}],
        "images": [{"bufferView": 2, "mimeType": "image/png"}],
        "buffers": [{"uri": uri, "byteLength": bin.len()}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 96},
            {"buffer": 0, "byteOffset": 96, "byteLength": 160},
            {"buffer": 0, "byteOffset": image_offset, "byteLength": png.len()},
            {"buffer": 0, "byteOffset": index_offset, "byteLength": 24}
        ],
        "accessors": [
            {"bufferView": 0, "byteOffset": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1.0, 0.0, -1.0], "max": [1.0, 0.0, 1.0]},
            {"bufferView": 0, "byteOffset": 48, "componentType": 5126, "count": 4, "type": "VEC3", "min": [1.2, 0.0, -0.2], "max": [1.6, 0.0, 0.2]},
            {"bufferView": 1, "byteOffset": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
            {"bufferView": 1, "byteOffset": 48, "componentType": 5126, "count": 4, "type": "VEC3"},
            {"bufferView": 1, "byteOffset": 96, "componentType": 5126, "count": 4, "type": "VEC2"},
            {"bufferView": 1, "byteOffset": 128, "componentType": 5126, "count": 4, "type": "VEC2"},
            {"bufferView": 3, "byteOffset": 0, "componentType": 5123, "count": 6, "type": "SCALAR"},
            {"bufferView": 3, "byteOffset": 12, "componentType": 5123, "count": 6, "type": "SCALAR"}
        ]
    });
    let p = dir.join("textured.gltf");
    std::fs::write(&p, serde_json::to_string_pretty(&doc).unwrap()).unwrap();
    p
}

#[test]
fn a_textured_gltf_with_an_emitter_and_a_sun_renders_the_expected_colours() {
    let d = temp_dir("textured");
    let mut scene = Scene::load(&textured_gltf(&d)).unwrap();
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    assert_eq!(scene.textures.len(), 1);
    // 1366 lux at 683 lm/W: 2 W/m² straight down; the emissive rectangle is an area light
    // (scene::area) of its radiance, centred on it.
    match scene.lights.as_slice() {
        [Light::Directional { direction, irradiance }, Light::Area { center, radiance, .. }] => {
            assert!(direction.distance(-Vec3::Y) < 1e-5 && (*irradiance - Vec3::splat(2.0)).abs().max_element() < 1e-5);
            assert!(center.distance(Vec3::new(1.4, 0.0, 0.0)) < 1e-5 && radiance.distance(Vec3::Y) < 1e-5);
        }
        other => panic!("lights {other:?}"),
    }
    scene.set_size(Some(64), Some(64)).unwrap();
    let ctx = common::context();
    let mut frames = Vec::new();
    for view in [vct::render::View::Direct, vct::render::View::Full] {
        let options = RenderOptions { resolution: Some(32), view, ..Default::default() };
        let r = Renderer::new(&ctx, scene.clone(), options).unwrap();
        r.render().unwrap();
        frames.push(r.read_frame().unwrap());
    }
    common::assert_clean(&ctx);
    // The camera looks down with world +x to the right and +z down the image; 3 tan 30° = 1.732 m
    // from the centre to the edge. Lambertian floor: albedo / π · 2 W/m².
    let pixel = |x: f32, z: f32| ((x / 1.732 * 32.0 + 31.5).round() as u32, (z / 1.732 * 32.0 + 31.5).round() as u32);
    let expected = 2.0 / std::f32::consts::PI;
    for (x, channel) in [(-0.5, 0), (0.5, 2)] {
        let (px, py) = pixel(x, -0.5);
        let c = common::hdr(&frames[0], px, py);
        assert!(
            (c[channel] / expected - 1.0).abs() < 0.06,
            "floor at x = {x}: {c}, expected {expected} in channel {channel}"
        );
        assert!(c[1] < 0.05 * expected && c[2 - channel] < 0.05 * expected, "floor at x = {x}: {c}");
    }
    let (px, py) = pixel(1.4, 0.0);
    let e = common::hdr(&frames[1], px, py);
    assert!((e.y - 1.0).abs() < 0.05 && e.x < 0.05 && e.z < 0.05, "emitter: {e}");
}
