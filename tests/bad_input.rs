//! Bad input gives a clear error (or a warning) naming the file or parameter, never a panic:
//! malformed scene files, broken OBJs, missing files and textures, absurd sizes.

use std::path::{Path, PathBuf};
use std::process::Command;

use vct::scene::Scene;

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("vct-bad-input-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

const TRIANGLE_OBJ: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn load_err(path: &Path) -> String {
    match Scene::load(path) {
        Ok(_) => panic!("{} loaded without error", path.display()),
        Err(e) => e.to_string(),
    }
}

#[test]
fn scene_file_with_unknown_field_names_field_and_file() {
    let d = temp_dir("field");
    write(&d, "tri.obj", TRIANGLE_OBJ);
    let p = write(&d, "scene.toml", "mesh = \"tri.obj\"\n[camera]\neye = [0, 0, 3]\ntarget = [0, 0, 0]\nfov = 40\n");
    let e = load_err(&p);
    assert!(e.contains("scene.toml") && e.contains("fov"), "{e}");
}

#[test]
fn scene_file_with_wrong_type_or_truncation_is_an_error() {
    let d = temp_dir("type");
    write(&d, "tri.obj", TRIANGLE_OBJ);
    let p = write(&d, "a.toml", "mesh = \"tri.obj\"\n[voxels]\nresolution = \"high\"\n");
    let e = load_err(&p);
    assert!(e.contains("a.toml") && e.contains("resolution"), "{e}");
    let p = write(&d, "b.toml", "mesh = \"tri.obj\"\n[camera]\neye = [0, 0,");
    assert!(load_err(&p).contains("b.toml"));
    let p = write(&d, "c.toml", "mesh = \"tri.obj\"\n[[light]]\nkind = \"spot\"\nposition = [0, 1, 0]\ndirection = [0, 0, 0]\nintensity = [1, 1, 1]\ninner_deg = 10\nouter_deg = 20\n");
    let e = load_err(&p);
    assert!(e.contains("c.toml") && e.contains("light.direction"), "{e}");
}

#[test]
fn obj_with_out_of_range_indices_names_the_file() {
    let d = temp_dir("index");
    let p = write(&d, "oob.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
    let e = load_err(&p);
    assert!(e.contains("oob.obj") && e.contains("out of bounds"), "{e}");
    let p = write(&d, "neg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -7\n");
    assert!(load_err(&p).contains("neg.obj"));
    // Relative texture/normal indices before the first element, and huge ones, overflow
    // tobj's index arithmetic (it panics): they must be refused before tobj reads them.
    for (name, face) in [("vt.obj", "f 1/-4 2/1 3/1"), ("vn.obj", "f 1//1 2//1 3//-9"), ("big.obj", "f 1 2 4294967296")]
    {
        let p = write(&d, name, &format!("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n{face}\n"));
        let e = load_err(&p);
        assert!(e.contains(name) && e.contains("line 6") && e.contains("out of range"), "{e}");
    }
}

#[test]
fn obj_with_garbage_lines_is_an_error_naming_the_file_or_loads_what_remains() {
    let d = temp_dir("garbage");
    let p = write(&d, "garbage.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv x y z\n%%% not obj\nf 1 2 3\n");
    match Scene::load(&p) {
        Err(e) => assert!(e.to_string().contains("garbage.obj"), "{e}"),
        Ok(s) => assert_eq!(s.mesh.triangle_count(), 1),
    }
}

#[test]
fn obj_with_non_finite_vertices_drops_those_triangles_with_a_warning() {
    let d = temp_dir("nan");
    let p = write(&d, "nan.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv nan 0 0\nv inf 1 1\nf 1 2 3\nf 1 4 5\n");
    let s = Scene::load(&p).unwrap();
    assert_eq!(s.mesh.triangle_count(), 1);
    assert!(s.mesh.bounds.min.is_finite() && s.mesh.bounds.max.is_finite());
    assert!(s.warnings.iter().any(|w| w.contains("nan.obj") && w.contains("non-finite")), "{:?}", s.warnings);
}

#[test]
fn missing_obj_names_the_path() {
    let d = temp_dir("missing");
    let p = write(&d, "scene.toml", "mesh = \"nowhere/absent.obj\"\n");
    let e = load_err(&p);
    assert!(e.contains("absent.obj"), "{e}");
    assert!(load_err(&d.join("also-absent.obj")).contains("also-absent.obj"));
}

#[test]
fn missing_or_broken_texture_is_a_warning_and_a_flat_colour() {
    let d = temp_dir("texture");
    write(&d, "m.mtl", "newmtl a\nKd 0.5 0.5 0.5\nmap_Kd nope.png\nnewmtl b\nKd 0.2 0.2 0.2\nmap_Kd fake.png\n");
    write(&d, "fake.png", "this is not an image");
    let p = write(&d, "tex.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\nusemtl b\nf 1 3 2\n");
    let s = Scene::load(&p).unwrap();
    assert!(s.warnings.iter().any(|w| w.contains("nope.png")), "{:?}", s.warnings);
    assert!(s.warnings.iter().any(|w| w.contains("fake.png")), "{:?}", s.warnings);
    assert!(s.materials.iter().all(|m| m.albedo_texture.is_none()));
}

fn vct(args: &[&str]) -> (i32, String) {
    let out =
        Command::new(env!("CARGO_BIN_EXE_vct")).args(args).env("XDG_RUNTIME_DIR", "/tmp").output().expect("run vct");
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!stderr.contains("panicked"), "vct panicked: {stderr}");
    (out.status.code().unwrap_or(-1), stderr)
}

#[test]
fn cli_reports_bad_input_without_panicking() {
    let d = temp_dir("cli");
    let p = write(&d, "broken.toml", "mesh = 3\n");
    let (code, err) = vct(&["render", p.to_str().unwrap(), "--out", d.join("x.png").to_str().unwrap()]);
    assert_eq!(code, 1);
    assert!(err.contains("broken.toml"), "{err}");
    let (code, err) = vct(&["render", "--width", "0", "--out", d.join("y.png").to_str().unwrap()]);
    assert_eq!(code, 1);
    assert!(err.contains("width"), "{err}");
    let (code, err) = vct(&["render", "--width", "100000", "--out", d.join("z.png").to_str().unwrap()]);
    assert_eq!(code, 1);
    assert!(err.contains("width"), "{err}");
    let (code, err) = vct(&["render", d.join("scene.txt").to_str().unwrap()]);
    assert_eq!(code, 1);
    assert!(err.contains("scene.txt"), "{err}");
    // A warped volume keeps no temporal history; the cube view draws an even grid.
    let (code, err) =
        vct(&["render", "--warp", "function", "--temporal", "0.5", "--out", d.join("v.png").to_str().unwrap()]);
    assert_eq!(code, 1);
    assert!(err.contains("temporal") && err.contains("warped"), "{err}");
    let (code, err) = vct(&["voxelize", "--warp", "function", "--view", d.join("u.png").to_str().unwrap()]);
    assert_eq!(code, 1);
    assert!(err.contains("--warp"), "{err}");
    let (code, err) = vct(&["voxelize", "--warp", "function", "--export", d.join("u.binvox").to_str().unwrap()]);
    assert_eq!(code, 1);
    assert!(err.contains("--warp") && err.contains("binvox"), "{err}");
    for (flag, value) in [
        ("--temporal", "0"),
        ("--temporal", "NaN"),
        ("--cone-bias", "20"),
        ("--cone-bias", "x"),
        ("--warp-slope", "0"),
        ("--warp-slope", "1.5"),
        ("--warp-slope", "inf"),
        ("--warp", "sideways"),
        ("--in-flight", "0"),
        ("--in-flight", "3"),
        ("--coverage", "exact"),
        ("--orbit", "NaN"),
        ("--injection", "pixels"),
        ("--orbit", "270"),
    ] {
        let (code, err) = vct(&["render", flag, value, "--out", d.join("w.png").to_str().unwrap()]);
        assert_eq!(code, 2, "{flag} {value}: {err}");
        assert!(err.contains(flag), "{flag} {value}: {err}");
    }
}

#[test]
fn cli_rejects_absurd_voxel_resolutions_and_empty_scenes() {
    let d = temp_dir("res");
    let out = d.join("x.png");
    for res in ["0", "8", "513", "100000"] {
        let (code, err) = vct(&["voxelize", "--res", res, "--voxelizer", "raster", "--view", out.to_str().unwrap()]);
        assert_eq!(code, 1, "--res {res}");
        assert!(err.contains("res") && err.contains(res), "--res {res}: {err}");
    }
    // Each axis of a fitted grid is a power of two (mip levels halve it exactly).
    let (code, err) = vct(&["voxelize", "--dims", "100,64,64", "--view", out.to_str().unwrap()]);
    assert_eq!(code, 1, "--dims 100,64,64: {err}");
    assert!(err.contains("dims (x)") && err.contains("100"), "{err}");
    let (code, err) = vct(&["voxelize", "--dims", "64,64", "--view", out.to_str().unwrap()]);
    assert_eq!(code, 2, "--dims 64,64: {err}");
    assert!(err.contains("--dims"), "{err}");
    // --res auto and its target, and the brick pool.
    let o = out.to_str().unwrap();
    for (args, code, says) in [
        (&["voxelize", "--res", "auto", "--view", o][..], 1, "--res auto"),
        (&["render", "--res", "many", "--out", o][..], 2, "--res"),
        (&["render", "--target-flip", "0.1", "--out", o][..], 1, "--target-flip"),
        (&["render", "--res", "auto", "--target-flip", "2", "--out", o][..], 1, "--target-flip"),
        (&["render", "--res", "auto", "--dims", "64,64,64", "--out", o][..], 1, "--dims"),
        (&["render", "--bricks", "0", "--out", o][..], 2, "--bricks"),
        (&["render", "--res", "32", "--bricks", "4", "--out", o][..], 1, "brick pool is full"),
        // The point voxelizer's density: positive, finite, and not so many points that the
        // buffer would pass MAX_POINTS.
        (&["voxelize", "--voxelizer", "points", "--point-density", "0", "--view", o][..], 1, "--point-density"),
        (&["voxelize", "--voxelizer", "points", "--point-density", "NaN", "--view", o][..], 1, "--point-density"),
        (
            &["voxelize", "--voxelizer", "points", "--point-density", "1000", "--res", "512", "--view", o][..],
            1,
            "point-density",
        ),
        // A dense 512³ grid's occupied-voxel list passes lavapipe's largest storage buffer.
        (&["voxelize", "--res", "512", "--storage", "dense", "--view", o][..], 1, "largest storage buffer"),
    ] {
        let (c, err) = vct(args);
        assert_eq!(c, code, "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
    }
    let empty = write(&d, "empty.obj", "# nothing here\nv 0 0 0\n");
    let (code, err) = vct(&["render", empty.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert_eq!(code, 1);
    assert!(err.contains("no finite geometry"), "{err}");
}

#[test]
fn fuzz_corpus_and_mutations_load_without_panicking() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/corpus/scene_input");
    let mut inputs: Vec<Vec<u8>> =
        std::fs::read_dir(&dir).unwrap().map(|e| std::fs::read(e.unwrap().path()).unwrap()).collect();
    assert!(inputs.len() >= 3);
    // Cheap deterministic mutations: truncations and byte flips of every corpus file.
    for seed in inputs.clone() {
        for cut in (0..seed.len()).step_by(37) {
            inputs.push(seed[..cut].to_vec());
            let mut flipped = seed.clone();
            flipped[cut] ^= 0x5a;
            inputs.push(flipped);
        }
    }
    for input in &inputs {
        vct::scene::fuzz_scene_input(input);
    }
}
