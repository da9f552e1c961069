//! `vct render`: a scene rendered headless to PNG (and linear EXR), with per-pass GPU times over
//! several frames, a moving or still camera, and `--res auto`, the cheapest grid that meets a
//! FLIP target against the path tracer.

use std::path::PathBuf;

use anyhow::{bail, Context as _, Result};
use clap::Args;

use vct::render::{RenderOptions, Renderer, Tracing, View};

use crate::common::*;

#[derive(Args)]
pub struct RenderArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Output PNG (tone-mapped).
    #[arg(long, default_value = "vct.png")]
    pub out: PathBuf,
    /// Also write the linear radiance as OpenEXR.
    #[arg(long)]
    pub exr: Option<PathBuf>,
    /// What to show: full|direct|indirect|diffuse|specular|ao|voxels|texels|radiance:LEVEL.
    #[arg(long, default_value = "full")]
    pub view: View,
    /// Direct light only: skip cone tracing.
    #[arg(long)]
    pub no_gi: bool,
    /// Where cone tracing runs: a fragment shader after a depth prepass, or compute over a G-buffer.
    #[arg(long, value_enum, default_value = "deferred", hide = true)]
    pub tracing: TracingArg,
    /// Write the per-pass GPU times as JSON.
    #[arg(long)]
    pub timings: Option<PathBuf>,
    /// Render this many frames and report each pass's median GPU time (the last frame is saved).
    #[arg(long, default_value_t = 1)]
    pub frames: u32,
    /// Submit the frames with up to this many in flight (1 or 2), as the viewer does, instead of
    /// waiting for each; prints the wall-clock time a frame beside the GPU times, which is what
    /// the overlap of the host's recording with the GPU's frame buys (docs/design/gpu.md).
    #[arg(long, value_name = "K", value_parser = clap::value_parser!(u32).range(1..=2), hide = true)]
    pub in_flight: Option<u32>,
    /// Keep the volume between frames while nothing it depends on changes, as `vct view` does,
    /// and, once a still view has traced every pixel (--gi-accumulate, gi-scale² frames), its
    /// traced light too (with --frames: the timings of a still view; --orbit for a moving one).
    #[arg(long, value_enum, default_value = "off", hide = true)]
    pub reuse_volume: OnOff,
    /// Turn the camera about its target by this many degrees a frame, about the vertical axis,
    /// after each frame (with --frames: the timings of a moving view, as the stability bench's
    /// orbiting camera moves).
    #[arg(long, value_name = "DEG", allow_negative_numbers = true, value_parser = orbit_degrees, hide = true)]
    pub orbit: Option<f32>,
    /// With --res auto: the largest FLIP against the path-traced reference the grid may give
    /// (0..1).
    #[arg(long, value_name = "F")]
    pub target_flip: Option<f32>,
    /// With --res auto and a target: samples a pixel of the reference (cached in --cache).
    #[arg(long, default_value_t = 64, value_parser = clap::value_parser!(u32).range(1..=65536), hide = true)]
    pub spp: u32,
    /// Where path-traced references are cached (shared with `vct bench`).
    #[arg(long, default_value = "bench/cache", hide = true)]
    pub cache: PathBuf,
    #[command(flatten)]
    pub gpu: GpuArgs,
}

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum TracingArg {
    Forward,
    Deferred,
}

pub fn render(args: RenderArgs) -> Result<()> {
    let auto = args.scene.method.res == Some(ResArg::Auto);
    if let Some(f) = args.target_flip {
        if !auto {
            bail!("--target-flip goes with --res auto");
        }
        if !(f.is_finite() && f > 0.0 && f < 1.0) {
            bail!("--target-flip must be in (0, 1), got {f}");
        }
    }
    if auto && args.scene.method.dims.is_some() {
        bail!("--res auto chooses the grid: give it without --dims");
    }
    let scene = args.scene.load()?;
    let ctx = open_device(&args.gpu)?;
    let tracing = match args.tracing {
        TracingArg::Forward => Tracing::Forward,
        TracingArg::Deferred => Tracing::Deferred,
    };
    let mut options = RenderOptions {
        resolution: if auto { None } else { args.scene.method.res()? },
        view: args.view,
        gi: !args.no_gi,
        tracing,
        gi_scale: match args.scene.gi_scale {
            Some(s) => s,
            None => {
                let dims = args.scene.method.dims.map(|d| d.max_element());
                let voxels = dims.or(args.scene.method.res()?).unwrap_or(scene.settings.voxel_resolution);
                args.scene.quality.gi_scale(&scene, voxels)
            }
        },
        gi_accumulate: args.scene.gi_accumulate == Some(OnOff::On),
        reuse_volume: args.reuse_volume == OnOff::On,
        ..args.scene.render_options()?
    };
    let mut choice = None;
    if auto {
        let name = args
            .scene
            .scene
            .as_deref()
            .and_then(|p| p.file_stem())
            .map_or("cornell".into(), |s| s.to_string_lossy().into_owned());
        let c = vct::bench::auto::choose(
            &ctx,
            &scene,
            &name,
            options,
            &vct::bench::auto::CANDIDATES,
            vct::bench::auto::Target { flip: args.target_flip, spp: args.spp, cache: &args.cache },
            &|m| eprintln!("{m}"),
        )
        .context("choosing the resolution (--res auto)")?;
        println!("{c}");
        options.resolution = Some(c.resolution);
        choice = Some(c);
    }
    let mut renderer = Renderer::new(&ctx, scene, options).context("creating the renderer")?;
    for n in &renderer.notes {
        println!("note: {n}");
    }
    if !(1..=10_000).contains(&args.frames) {
        bail!("--frames must be in 1..=10000, got {}", args.frames);
    }
    let turn = args.orbit.map(|deg| glam::Quat::from_rotation_y(deg.to_radians()));
    // After each frame, the camera turns (--orbit); a volume that follows it moves with it.
    let orbit = |r: &mut Renderer| -> Result<()> {
        if let Some(turn) = turn {
            let c = &mut r.scene.camera;
            c.eye = c.target + turn * (c.eye - c.target);
            let eye = c.eye;
            r.follow(eye).context("moving the camera (--orbit)")?;
        }
        Ok(())
    };
    let mut runs = Vec::new();
    let started = std::time::Instant::now();
    match args.in_flight {
        None => {
            for _ in 0..args.frames {
                runs.push(renderer.render().context("rendering")?);
                orbit(&mut renderer)?;
            }
        }
        Some(k) => {
            let mut ring = vct::gpu::FrameRing::new(&ctx, k as usize)?;
            for _ in 0..args.frames {
                runs.push(renderer.submit_in_flight(&mut ring).context("rendering")?);
                orbit(&mut renderer)?;
            }
            ring.wait_idle()?;
            // The last two frames, which no later frame waited for.
            runs.push(renderer.settled_timings()?);
            runs.push(renderer.timings()?);
            runs.retain(|t| !t.is_empty());
        }
    }
    let wall = started.elapsed().as_secs_f64() * 1e3 / args.frames as f64;
    let how = args.in_flight.map_or("each waited for".into(), |k| format!("{k} in flight"));
    println!("wall clock: {wall:.3} ms a frame over {} frames, {how}", args.frames);
    let timings = vct::gpu::timer::median(&runs);
    let frame = renderer.read_frame()?;
    print_timings(&timings);
    let memory = renderer.memory();
    println!("{memory}");
    if let Some(path) = &args.timings {
        let json = serde_json::json!({
            "device": ctx.info.name,
            "driver": ctx.info.driver,
            "voxelizer": renderer.options.method.label(),
            "tracing": format!("{:?}", options.tracing),
            "resolution": renderer.voxels.grid.voxelized().longest(),
            "dims": renderer.voxels.grid.dims.to_array(),
            "width": frame.width,
            "height": frame.height,
            "passes": timings,
            "memory": memory,
            "storage": renderer.voxels.bricks.storage.label(),
            "frames": args.frames,
            "in_flight": args.in_flight,
            "wall_ms_per_frame": wall,
            "auto": choice,
        });
        std::fs::write(path, serde_json::to_string_pretty(&json)?)
            .with_context(|| format!("writing {}", path.display()))?;
        println!("wrote {}", path.display());
    }
    vct::output::write_png(&args.out, &frame)?;
    println!("wrote {}", args.out.display());
    if let Some(exr) = &args.exr {
        vct::output::write_exr(exr, &frame)?;
        println!("wrote {}", exr.display());
    }
    drop(renderer);
    check_validation(&ctx)
}
