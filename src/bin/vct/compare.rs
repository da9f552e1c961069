//! `vct compare`: two images compared, FLIP on the tone-mapped images and RMSE on linear ones.

use std::path::PathBuf;

use anyhow::{bail, Context as _, Result};
use clap::Args;

#[derive(Args)]
pub struct CompareArgs {
    /// Reference image (PNG or EXR).
    pub reference: PathBuf,
    /// Test image (PNG or EXR), same size.
    pub test: PathBuf,
    /// Write the FLIP error map here.
    #[arg(long, default_value = "flip.png")]
    pub out: PathBuf,
}

pub fn compare(args: CompareArgs) -> Result<()> {
    let a = vct::output::read_frame(&args.reference)?;
    let b = vct::output::read_frame(&args.test)?;
    if (a.width, a.height) != (b.width, b.height) {
        bail!(
            "{} is {}x{} but {} is {}x{}",
            args.reference.display(),
            a.width,
            a.height,
            args.test.display(),
            b.width,
            b.height
        );
    }
    let (flip, map) = vct::reference::metrics::flip(&a.rgb8(), &b.rgb8(), a.width, a.height);
    println!("FLIP (tone-mapped): {flip:.5}");
    if !a.hdr.is_empty() && !b.hdr.is_empty() {
        println!("RMSE (linear radiance): {:.6}", vct::reference::metrics::rmse(&a.linear(), &b.linear()));
        let mean = |f: &vct::render::FrameImages| f.linear().iter().map(|p| p.element_sum() as f64).sum::<f64>();
        println!("mean radiance, test over reference: {:.4}", mean(&b) / mean(&a).max(1e-30));
    } else {
        println!("RMSE (linear radiance): n/a (give two EXR files)");
    }
    image::save_buffer(&args.out, &map, a.width, a.height, image::ColorType::Rgb8)
        .with_context(|| format!("writing {}", args.out.display()))?;
    println!("wrote {}", args.out.display());
    Ok(())
}
