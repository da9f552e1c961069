//! Issue "Windowed viewer": the viewer under Xvfb (lavapipe presenting through X11) runs N
//! frames with the validation layer on and no messages, its last frame matches the headless
//! render of the same scene and camera, and a resize recreates the swapchain cleanly.

use std::path::{Path, PathBuf};
use std::process::Command;

fn out(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("vct-viewer-{}-{name}", std::process::id()))
}

fn run(args: &[&str], under_x: bool) -> String {
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

#[test]
fn viewer_frames_match_the_headless_render() {
    let (shot, headless) = (out("shot.png"), out("headless.png"));
    let common = ["--res", "32", "--voxelizer", "raster", "--validation"];
    run(&[&["view", "--frames", "30", "--screenshot", shot.to_str().unwrap()][..], &common].concat(), true);
    run(&[&["render", "--out", headless.to_str().unwrap()][..], &common].concat(), false);
    let (a, b) = (load(&shot), load(&headless));
    assert_eq!(a.dimensions(), b.dimensions());
    let diffs: Vec<i32> = a.as_raw().iter().zip(b.as_raw()).map(|(x, y)| (*x as i32 - *y as i32).abs()).collect();
    let mean = diffs.iter().sum::<i32>() as f64 / diffs.len() as f64;
    let over = diffs.iter().filter(|&&d| d > 8).count() as f64 / diffs.len() as f64;
    println!("viewer vs headless: mean |Δ| {mean:.3}, share over 8: {over:.4}");
    assert!(mean < 1.0 && over < 0.01, "viewer and headless renders differ: mean {mean}, share over 8 {over}");
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
        &["view", "--soak", "--frames", "541", "--width", "64", "--height", "64", "--res", "16", "--validation"],
        true,
    );
    let line = text.lines().find(|l| l.starts_with("soak:")).unwrap_or_else(|| panic!("no soak report:\n{text}"));
    let mib: Vec<f64> = line.split_whitespace().filter_map(|w| w.parse().ok()).collect();
    let [gpu0, gpu1, host0, host1] = mib[..] else { panic!("{line}") };
    println!("{line}");
    assert!((gpu1 - gpu0).abs() < 0.01, "GPU memory grew: {line}");
    assert!(host1 - host0 < 16.0, "host memory grew: {line}");
}
