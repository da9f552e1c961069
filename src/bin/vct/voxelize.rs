//! `vct voxelize`: a scene voxelized by one method and measured against the exact triangle/box
//! coverage (recall, precision, IoU), with a .binvox export and a picture of the voxels.

use std::path::PathBuf;

use anyhow::{bail, Context as _, Result};
use clap::Args;

use vct::reference::coverage::RefGrid;
use vct::voxel::{headless, VoxelGrid};

use crate::common::*;

#[derive(Args)]
pub struct VoxelizeArgs {
    /// Scene file (.toml), mesh (.obj) or glTF 2.0 (.gltf, .glb); default: the embedded Cornell box.
    pub scene: Option<PathBuf>,
    #[command(flatten)]
    pub method: MethodArgs,
    /// The warp, its finest texels at the scene's camera.
    #[command(flatten)]
    pub warp: WarpArgs,
    /// Write the occupancy as a .binvox file.
    #[arg(long)]
    pub export: Option<PathBuf>,
    /// Render the voxels as shaded cubes from the scene camera to this PNG.
    #[arg(long)]
    pub view: Option<PathBuf>,
    #[command(flatten)]
    pub gpu: GpuArgs,
}

pub fn voxelize(args: VoxelizeArgs) -> Result<()> {
    let scene = load_scene(args.scene.as_deref())?;
    let method = args.method.method()?;
    let res = args.method.res()?.unwrap_or(scene.settings.voxel_resolution);
    let mut grid = VoxelGrid::choose(&scene.mesh.bounds, res, args.method.dims)?;
    if let Some(warp) = args.warp.choice() {
        if args.view.is_some() {
            // The cube view draws unit cubes of the even grid (render::voxel_view).
            bail!("--view draws the voxels as cubes of an even grid: give it without --warp (or use `vct render --warp function --view voxels`)");
        }
        if args.export.is_some() {
            // .binvox holds cubes of one size.
            bail!("--export writes a .binvox of even cubes, which cannot hold warped texels: give it without --warp");
        }
        grid = warp.apply(grid, &scene.camera, &scene.mesh.bounds).context("warping the grid")?;
    }
    let ctx = open_device(&args.gpu)?;
    let method = method.on(&ctx.info.features);
    let storage = args.method.storage();
    let run =
        headless::voxelize_stored(&ctx, &scene, method, grid, storage, args.method.bricks, 3).context("voxelizing")?;
    for n in &run.notes {
        println!("{n}");
    }
    let g = run.grid;
    println!("method: {}   grid: {}, voxel {:.4} m", method.label(), g.dims_label(), g.voxel);
    match g.warp {
        vct::voxel::warp::Warp::Function(w) if g.is_warped() => {
            let (focus, s) = (w.centre, w.end_slope);
            println!("warped (Freed 2018 §4.6.1): finest at grid fraction {focus:.3}, end slope {s}: texels {:.2}× to {s}× as fine as the voxel", w.peak_slope());
        }
        vct::voxel::warp::Warp::Perspective(p) => {
            println!("warped by perspective (Freed 2018 §4.6.2): near texels {} of the far ones' width, {:.2}× as fine as the box's voxel", p.ratio, p.peak_slope());
        }
        _ => {}
    }
    let pool = run.bricks.map(|b| b.capacity + 1);
    println!("storage: {}", run.storage.label());
    let layout = vct::render::memory::Layout {
        bounces: scene.settings.gi.bounces > 1,
        listed: true,
        pool,
        resident: run.residency.as_ref(),
        temporal: scene.settings.gi.temporal < 1.0,
        chains: vct::render::radiance::Chains::read_by(scene.settings.gi.filter, false),
    };
    println!("{}", vct::render::memory::MemoryReport::for_grid(&g, &layout));
    if let Some(b) = run.bricks {
        let all = vct::voxel::bricks::brick_count(&g).element_product();
        println!(
            "bricks of {s}³: {} of {all} occupied ({:.1}%), pool of {} slots",
            b.needed,
            100.0 * b.needed as f64 / all as f64,
            b.capacity,
            s = vct::config::BRICK_SIZE
        );
    }
    let occupied = run.occupied();
    println!("occupied voxels: {}", occupied.iter().filter(|&&o| o).count());
    println!("voxelize GPU time: {:.3} ms (median of 3)", run.gpu_ms);
    let triangles: Vec<_> = (0..scene.mesh.triangle_count()).map(|t| scene.mesh.triangle(t)).collect();
    let reference = RefGrid::matching(&g).coverage(&triangles, 1e-3);
    let a = reference.accuracy(&occupied);
    println!(
        "against exact coverage: recall {:.4}  precision {:.4}  IoU {:.4}  ({} required voxels)",
        a.recall, a.precision, a.iou, a.required
    );
    let cam = &scene.camera;
    let seen = RefGrid::matching(&g).visible(&triangles, cam, 1e-3).accuracy(&occupied);
    println!(
        "surfaces the camera sees ({}×{} pixel centres): recall {:.4}  ({} required voxels)",
        cam.width, cam.height, seen.recall, seen.required
    );
    if let Some(path) = &args.export {
        vct::voxel::binvox::write(path, &g, &occupied)?;
        println!("wrote {}", path.display());
    }
    if let Some(path) = &args.view {
        let frame = vct::render::voxel_view::render_voxels(&ctx, &scene, &run)?;
        vct::output::write_png(path, &frame)?;
        println!("wrote {}", path.display());
    }
    check_validation(&ctx)
}
