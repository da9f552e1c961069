//! `vct`: command-line front end. `vct render` renders a scene headlessly to PNG (and EXR),
//! `vct devices` lists the Vulkan devices and the features this renderer uses.

use std::path::{Path, PathBuf};

use anyhow::{bail, Context as _, Result};
use clap::{Args, Parser, Subcommand};

use vct::gpu::{Context, ContextOptions, Feature, Timing};
use vct::render::Renderer;
use vct::scene::Scene;

#[derive(Parser)]
#[command(name = "vct", version, about = "Voxel cone tracing global illumination on Vulkan (after Freed 2018)")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render a scene headlessly to PNG (and optionally linear EXR).
    Render(RenderArgs),
    /// List Vulkan devices, their drivers and the features vct uses.
    Devices,
}

#[derive(Args)]
struct GpuArgs {
    /// Use the first device whose name contains this text.
    #[arg(long)]
    device: Option<String>,
    /// Enable the Khronos validation layer (also: VCT_VALIDATION=1); messages fail the run.
    #[arg(long)]
    validation: bool,
}

#[derive(Args)]
struct RenderArgs {
    /// Scene file (.toml) or mesh (.obj); default: the embedded Cornell box.
    scene: Option<PathBuf>,
    /// Output PNG (tone-mapped).
    #[arg(long, default_value = "vct.png")]
    out: PathBuf,
    /// Also write the linear radiance as OpenEXR.
    #[arg(long)]
    exr: Option<PathBuf>,
    #[arg(long)]
    width: Option<u32>,
    #[arg(long)]
    height: Option<u32>,
    #[command(flatten)]
    gpu: GpuArgs,
}

fn load_scene(path: Option<&Path>) -> Result<Scene> {
    let scene = match path {
        Some(p) => Scene::load(p).with_context(|| format!("loading scene {}", p.display()))?,
        None => Scene::embedded_default().context("loading the embedded default scene")?,
    };
    for w in &scene.warnings {
        log::warn!("{w}");
    }
    Ok(scene)
}

fn open_device(args: &GpuArgs) -> Result<std::sync::Arc<Context>> {
    let ctx = Context::new(&ContextOptions::from_env(args.validation, args.device.clone()))
        .context("opening the Vulkan device")?;
    println!("device: {} ({}, {})", ctx.info.name, ctx.info.kind_name(), ctx.info.driver);
    Ok(ctx)
}

fn check_validation(ctx: &Context) -> Result<()> {
    let (e, w) = (ctx.validation.errors(), ctx.validation.warnings());
    if e + w > 0 {
        bail!("the validation layer reported {e} error(s) and {w} warning(s)");
    }
    Ok(())
}

fn print_timings(timings: &[Timing]) {
    println!("{:<16} {:>10}", "pass", "GPU ms");
    for t in timings {
        println!("{:<16} {:>10.3}", t.pass, t.ms);
    }
}

fn render(args: RenderArgs) -> Result<()> {
    let mut scene = load_scene(args.scene.as_deref())?;
    scene.set_size(args.width, args.height)?;
    let ctx = open_device(&args.gpu)?;
    let renderer = Renderer::new(&ctx, scene).context("creating the renderer")?;
    let timings = renderer.render().context("rendering")?;
    let frame = renderer.read_frame()?;
    print_timings(&timings);
    vct::output::write_png(&args.out, &frame)?;
    println!("wrote {}", args.out.display());
    if let Some(exr) = &args.exr {
        vct::output::write_exr(exr, &frame)?;
        println!("wrote {}", exr.display());
    }
    drop(renderer);
    check_validation(&ctx)
}

fn devices() -> Result<()> {
    let list = Context::list_devices().context("listing Vulkan devices")?;
    if list.is_empty() {
        bail!("no Vulkan devices found (is a driver such as mesa-vulkan-drivers installed?)");
    }
    for d in list {
        let v = d.api_version;
        println!(
            "{} [{}] Vulkan {}.{}.{}, driver {}",
            d.name,
            d.kind_name(),
            ash::vk::api_version_major(v),
            ash::vk::api_version_minor(v),
            ash::vk::api_version_patch(v),
            d.driver
        );
        println!("  maxTessellationGenerationLevel = {}", d.limits.max_tessellation_generation_level);
        for f in Feature::ALL {
            println!("  [{}] {}", if d.features.has(f) { "x" } else { " " }, f.name());
        }
    }
    Ok(())
}

fn main() {
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn")).init();
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Render(a) => render(a),
        Command::Devices => devices(),
    };
    if let Err(e) = result {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}
