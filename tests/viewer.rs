//! The windowed viewer under Xvfb (lavapipe presenting through X11) runs N frames with the
//! validation layer on and no messages, its last frame matches the headless render of the same
//! scene and camera (also with two frames in flight under synchronization validation), and a resize
//! recreates the swapchain cleanly.

use std::path::{Path, PathBuf};
use std::process::Command;

fn out(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("vct-viewer-{}-{name}", std::process::id()))
}

fn run(args: &[&str], under_x: bool) -> String {
    run_with(args, under_x, &[])
}

fn run_with(args: &[&str], under_x: bool, env: &[(&str, &str)]) -> String {
    let bin = env!("CARGO_BIN_EXE_vct");
    let mut cmd = if under_x {
        let mut c = Command::new("xvfb-run");
        c.args(["-a", "-s", "-screen 0 1024x768x24", bin]);
        c
    } else {
        Command::new(bin)
    };
    let output = cmd
        .args(args)
        .env("XDG_RUNTIME_DIR", std::env::var("XDG_RUNTIME_DIR").unwrap_or("/tmp".into()))
        .env("MESA_SHADER_CACHE_DISABLE", "true")
        .envs(env.iter().copied())
        .output()
        .expect("run vct (is xvfb-run installed? `make test` installs it)");
    let text = format!("{}{}", String::from_utf8_lossy(&output.stdout), String::from_utf8_lossy(&output.stderr));
    assert!(output.status.success(), "vct {args:?} failed:\n{text}");
    assert!(!text.contains("[vulkan]"), "validation messages:\n{text}");
    text
}

fn load(p: &Path) -> image::RgbImage {
    image::open(p).unwrap_or_else(|e| panic!("{}: {e}", p.display())).to_rgb8()
}

/// Mean absolute difference of two 8-bit images, and the share of channels off by over 8.
fn difference(a: &Path, b: &Path) -> (f64, f64) {
    let (a, b) = (load(a), load(b));
    assert_eq!(a.dimensions(), b.dimensions());
    let diffs: Vec<i32> = a.as_raw().iter().zip(b.as_raw()).map(|(x, y)| (*x as i32 - *y as i32).abs()).collect();
    let mean = diffs.iter().sum::<i32>() as f64 / diffs.len() as f64;
    let over = diffs.iter().filter(|&&d| d > 8).count() as f64 / diffs.len() as f64;
    (mean, over)
}

/// The viewer's last frame against the headless render of the same scene and camera, with the
/// viewer's context made under `env`, both given `extra`.
fn viewer_matches_headless(name: &str, env: &[(&str, &str)], extra: &[&str]) {
    let (shot, headless) = (out(&format!("{name}-shot.png")), out(&format!("{name}-headless.png")));
    let common = [&["--res", "32", "--voxelizer", "raster", "--validation"][..], extra].concat();
    // The viewer's accumulation has traced every pixel once after gi-scale² (64) frames.
    let view = [&["view", "--frames", "72", "--screenshot", shot.to_str().unwrap()][..], &common].concat();
    run_with(&view, true, env);
    // The accumulated view converges to the whole set traced at every pixel: `--quality high`
    // (the default splits the set among pixels, which accumulation does not).
    let high = ["--quality", "high", "--out", headless.to_str().unwrap()];
    run(&[&["render"][..], &high, &common].concat(), false);
    let (mean, over) = difference(&shot, &headless);
    println!("viewer vs headless: mean |Δ| {mean:.3}, share over 8: {over:.4}");
    assert!(mean < 1.0 && over < 0.01, "viewer and headless renders differ: mean {mean}, share over 8 {over}");
}

#[test]
fn viewer_frames_match_the_headless_render() {
    viewer_matches_headless("plain", &[], &[]);
}

/// The viewer refocuses a warped grid on the camera every frame (Freed 2018 §4.6.1); a still
/// camera's frame is the headless render's.
#[test]
fn a_warped_grid_in_the_viewer_matches_the_headless_render() {
    viewer_matches_headless("warped", &[], &["--warp", "function"]);
}

/// The perspective warp is rebuilt around the camera every frame: a still camera's frame is the
/// headless render's.
#[test]
fn a_perspective_warp_in_the_viewer_matches_the_headless_render() {
    viewer_matches_headless("perspective", &[], &["--warp", "perspective"]);
}

/// The viewer recentres clipmap levels on the camera every frame; a still camera's frame is the
/// headless render's.
#[test]
fn clipmap_levels_in_the_viewer_match_the_headless_render() {
    viewer_matches_headless("clipmap", &[], &["--clipmap", "3"]);
}

/// The viewer keeps two frames in flight (the CPU records one while the GPU runs the one before,
/// which still reads the shared volumes and per-frame buffers), and synchronization validation
/// finds no hazard between them or within one.
#[test]
fn two_frames_in_flight_raise_no_synchronization_hazard() {
    assert_eq!(vct::gpu::FRAMES_IN_FLIGHT, 2);
    // The layer checks between submissions only when asked (Vulkan SDK 1.3.239: an alpha check).
    let submit = "VALIDATION_CHECK_ENABLE_SYNCHRONIZATION_VALIDATION_QUEUE_SUBMIT";
    viewer_matches_headless("sync", &[("VCT_VALIDATION", "sync"), ("VK_LAYER_ENABLES", submit)], &[]);
}

#[test]
fn resize_recreates_the_swapchain_cleanly() {
    let shot = out("resized.png");
    let text = run(
        &[
            "view",
            "--frames",
            "24",
            "--resize-to",
            "200x150",
            "--res",
            "16",
            "--voxelizer",
            "raster",
            "--validation",
            "--screenshot",
            shot.to_str().unwrap(),
        ],
        true,
    );
    assert!(text.contains("frames: 24"), "{text}");
    assert_eq!(load(&shot).dimensions(), (200, 150), "the last frame was not rendered at the new size");
}

#[test]
fn soak_keeps_gpu_and_host_memory_flat() {
    let text = run(
        &["view", "--soak", "--frames", "181", "--width", "64", "--height", "64", "--res", "16", "--validation"],
        true,
    );
    let line = text.lines().find(|l| l.starts_with("soak:")).unwrap_or_else(|| panic!("no soak report:\n{text}"));
    let mib: Vec<f64> = line.split_whitespace().filter_map(|w| w.parse().ok()).collect();
    let [gpu0, gpu1, host0, host1] = mib[..] else { panic!("{line}") };
    println!("{line}");
    assert!((gpu1 - gpu0).abs() < 0.01, "GPU memory grew: {line}");
    assert!(host1 - host0 < 16.0, "host memory grew: {line}");
}
