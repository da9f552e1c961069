//! `vct reference`: the scene path-traced on the CPU, the ground truth for image accuracy.

use std::path::PathBuf;

use anyhow::{bail, Result};
use clap::Args;

use vct::scene::Scene;

use crate::common::*;

#[derive(Args)]
pub struct ReferenceArgs {
    /// Scene file (.toml), mesh (.obj) or glTF 2.0 (.gltf, .glb); default: the embedded Cornell box.
    pub scene: Option<PathBuf>,
    /// Indirect bounces: 0 direct light only, 1 what cone tracing approximates, more for full GI.
    #[arg(long, default_value_t = 1)]
    pub bounces: u32,
    /// Samples per pixel.
    #[arg(long, default_value_t = 64)]
    pub spp: u32,
    #[arg(long)]
    pub width: Option<u32>,
    #[arg(long)]
    pub height: Option<u32>,
    #[arg(long, default_value = "reference.png")]
    pub out: PathBuf,
    /// Also write the linear radiance as OpenEXR.
    #[arg(long)]
    pub exr: Option<PathBuf>,
}

pub fn reference(args: ReferenceArgs) -> Result<()> {
    if !(0..=64).contains(&args.bounces) || !(1..=1 << 16).contains(&args.spp) {
        bail!("--bounces must be in 0..=64 and --spp in 1..=65536");
    }
    let mut scene = load_scene(args.scene.as_deref())?;
    scene.set_size(args.width, args.height)?;
    let (image, seconds) = render_reference(&scene, args.bounces, args.spp);
    println!(
        "path traced {}x{} at {} spp, {} bounce(s) in {seconds:.1} s; noise: mean standard error {:.5} ({:.2}% of the mean)",
        image.width,
        image.height,
        args.spp,
        args.bounces,
        image.std_error,
        100.0 * image.relative_noise
    );
    let frame = vct::render::FrameImages::from_linear(image.width, image.height, &image.radiance);
    vct::output::write_png(&args.out, &frame)?;
    println!("wrote {}", args.out.display());
    if let Some(exr) = &args.exr {
        vct::output::write_exr(exr, &frame)?;
        println!("wrote {}", exr.display());
    }
    Ok(())
}

/// Path-traces `scene` with a progress bar; returns the image and the seconds it took.
fn render_reference(scene: &Scene, bounces: u32, spp: u32) -> (vct::reference::pathtrace::RefImage, f64) {
    let bar = indicatif::ProgressBar::new(scene.camera.height as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template("path tracing {bar:40} {pos}/{len} rows, {eta} left")
            .expect("valid progress template"),
    );
    let start = std::time::Instant::now();
    let tracer = vct::reference::pathtrace::PathTracer::new(scene);
    let opts = vct::reference::pathtrace::RefOptions { bounces, spp, seed: 1, ..Default::default() };
    let image = tracer.render(opts, &|n| bar.inc(n));
    bar.finish_and_clear();
    (image, start.elapsed().as_secs_f64())
}
