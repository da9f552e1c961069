//! `vct view`: the window running the whole frame every frame (keys: docs/guide/viewer.md).

use std::path::PathBuf;

use anyhow::{bail, Context as _, Result};
use clap::Args;

use vct::gpu::ContextOptions;
use vct::render::RenderOptions;

use crate::common::*;

#[derive(Args)]
pub struct ViewArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Wait for vertical blank (FIFO) or not (MAILBOX/IMMEDIATE where offered).
    #[arg(long, value_enum, default_value = "on")]
    pub vsync: OnOff,
    /// Render this many frames, then exit (automation and tests).
    #[arg(long)]
    pub frames: Option<u32>,
    /// Save the last frame to this PNG on exit.
    #[arg(long)]
    pub screenshot: Option<PathBuf>,
    /// Resize the window to WxH a third of the way through --frames.
    #[arg(long, value_parser = parse_size, hide = true)]
    pub resize_to: Option<(u32, u32)>,
    /// Soak test: move camera and light, switch voxelizer and resolution on a schedule, and
    /// compare GPU and host memory at frame 60 and 180 (use --frames 181 or more).
    #[arg(long, hide = true)]
    pub soak: bool,
    /// The on-screen overlay: FPS, per-pass GPU time, settings, voxel memory, the keys on H
    /// (key I toggles it; screenshots never contain it).
    #[arg(long, value_enum, default_value = "on")]
    pub overlay: OnOff,
    #[command(flatten)]
    pub gpu: GpuArgs,
}

pub fn view(args: ViewArgs) -> Result<()> {
    let scene = args.scene.load()?;
    let opts = ContextOptions::from_env(args.gpu.validation, args.gpu.device.clone());
    let report = vct::viewer::run(vct::viewer::ViewerOptions {
        scene,
        render: RenderOptions {
            // The viewer's defaults, from the frame time against FLIP chart (docs/design/reduced-scale.md): one pixel in 64 traces, so the cones cost
            // a third of the still frame at 1280x720 on lavapipe (scale 4: two thirds); a still
            // view converges to full resolution, and a moving one stays within 1.7% of it.
            gi_scale: args.scene.gi_scale.unwrap_or(8),
            gi_accumulate: args.scene.gi_accumulate.map_or(args.scene.gi_scale != Some(1), |a| a == OnOff::On),
            // A static scene's volume is built again only when the lights, grid or GI change.
            reuse_volume: true,
            ..args.scene.render_options()?
        },
        vsync: args.vsync == OnOff::On,
        overlay: args.overlay == OnOff::On,
        validation: opts.validation,
        device: opts.device,
        frames: args.frames,
        screenshot: args.screenshot,
        resize_to: args.resize_to,
        soak: args.soak,
    })
    .context("running the viewer")?;
    println!(
        "frames: {}; GPU memory allocated: {:.1} MiB at start, {:.1} MiB at end",
        report.frames,
        report.gpu_bytes_start as f64 / 1048576.0,
        report.gpu_bytes_end as f64 / 1048576.0
    );
    if let (Some((g0, h0)), Some((g1, h1))) = (report.soak_baseline, report.soak_end) {
        println!(
            "soak: GPU memory {:.2} MiB at frame {}, {:.2} MiB at the last same-settings frame; host resident {:.1} MiB, {:.1} MiB",
            g0 as f64 / 1048576.0,
            vct::viewer::SOAK_CYCLE,
            g1 as f64 / 1048576.0,
            h0 as f64 / 1048576.0,
            h1 as f64 / 1048576.0
        );
    }
    if report.validation_errors + report.validation_warnings > 0 {
        bail!(
            "the validation layer reported {} error(s) and {} warning(s)",
            report.validation_errors,
            report.validation_warnings
        );
    }
    Ok(())
}
