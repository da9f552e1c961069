//! `vct`: the command-line front end. Each command's arguments and body live in its own module
//! (render, view, voxelize, reference, compare, bench); common.rs holds what they share. Errors
//! carry the file or flag they are about.
//!
//! Two tiers of help: `--help` shows the everyday options; the study knobs (hidden there) show
//! with `--help-all`.

mod accuracy;
mod bench;
mod bench_args;
mod common;
mod compare;
mod reference;
mod render;
mod view;
mod voxelize;

use anyhow::{bail, Context as _, Result};
use clap::{CommandFactory, Parser, Subcommand};

use vct::gpu::{Context, Feature};

/// Shown under each command's `--help`.
const MORE_HELP: &str = "Study and tuning options (cone sets, filters, coverage modes, ...): --help-all";

#[derive(Parser)]
#[command(name = "vct", version, about = "Voxel cone tracing global illumination on Vulkan (after Freed 2018)")]
#[command(after_help = MORE_HELP)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand)]
pub enum Command {
    /// Render a scene headlessly to PNG (and optionally linear EXR).
    #[command(after_help = MORE_HELP)]
    Render(render::RenderArgs),
    /// Voxelize a scene and measure it against exact triangle/box coverage.
    #[command(after_help = MORE_HELP)]
    Voxelize(voxelize::VoxelizeArgs),
    /// Open a window running the full GI frame every frame (H for the keys).
    #[command(after_help = MORE_HELP)]
    View(view::ViewArgs),
    /// Path-trace the scene on the CPU: the ground truth for image accuracy.
    Reference(reference::ReferenceArgs),
    /// Compare two images: FLIP on the tone-mapped images, RMSE on linear ones (EXR).
    Compare(compare::CompareArgs),
    /// Measure speed against accuracy (voxelizers, indirect light, stability), or write the report.
    #[command(after_help = MORE_HELP)]
    Bench(bench_args::BenchArgs),
    /// List Vulkan devices, their drivers and the features vct uses.
    Devices,
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

/// `--help-all`: the help of the command named on the line (or of `vct`), with the study knobs
/// that `--help` hides.
fn print_help_all(argv: &[String]) {
    let mut cli = Cli::command();
    let name = argv.iter().skip(1).find(|a| cli.find_subcommand(a.as_str()).is_some()).cloned();
    let cmd = match name {
        Some(n) => cli.find_subcommand_mut(&n).expect("found above").clone(),
        None => cli,
    };
    let mut cmd = cmd.mut_args(|a| a.hide(false)).after_help("");
    let _ = cmd.print_long_help();
}

fn main() {
    // Exit quietly when stdout is a closed pipe (`vct ... | head`), as Unix tools do, instead
    // of Rust's default of failing the next print.
    // SAFETY: restoring the default disposition of SIGPIPE before any thread starts.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn")).init();
    let argv: Vec<String> = std::env::args().collect();
    if argv.iter().any(|a| a == "--help-all") {
        print_help_all(&argv);
        return;
    }
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Render(a) => render::render(a),
        Command::Voxelize(a) => voxelize::voxelize(a),
        Command::View(a) => view::view(a),
        Command::Reference(a) => reference::reference(a),
        Command::Compare(a) => compare::compare(a),
        Command::Bench(a) => bench::bench(a),
        Command::Devices => devices(),
    };
    if let Err(e) = result {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}
