//! `vct`: the command-line front end. Subcommands: `render` (headless PNG/EXR), `voxelize`
//! (voxel accuracy against the exact coverage), `view` (window), `reference` (path tracer),
//! `compare` (FLIP/RMSE), `bench` (speed against accuracy, stability) and `devices`. The
//! arguments are in args.rs; anyhow errors carry the file or flag they are about.

use std::path::{Path, PathBuf};

mod accuracy;
mod args;
mod bench_args;

use anyhow::{bail, Context as _, Result};
use clap::Parser;

use args::*;
use bench_args::BenchArgs;

use vct::gpu::{Context, ContextOptions, Feature, Timing};
use vct::reference::coverage::RefGrid;
use vct::render::{RenderOptions, Renderer, Tracing};
use vct::scene::Scene;
use vct::voxel::{headless, VoxelGrid};

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
        gi_scale: args.scene.gi_scale.unwrap_or(1),
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

fn voxelize(args: VoxelizeArgs) -> Result<()> {
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

fn view(args: ViewArgs) -> Result<()> {
    let scene = args.scene.load()?;
    let opts = ContextOptions::from_env(args.gpu.validation, args.gpu.device.clone());
    let report = vct::viewer::run(vct::viewer::ViewerOptions {
        scene,
        render: RenderOptions {
            // The viewer's defaults, from the frame time against FLIP chart (docs/benchmarks.md,
            // "Diffuse cones at a reduced resolution"): one pixel in 64 traces, so the cones cost
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

fn reference(args: ReferenceArgs) -> Result<()> {
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

fn compare(args: CompareArgs) -> Result<()> {
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

fn bench(args: BenchArgs) -> Result<()> {
    let before = args.baseline.as_deref().map(vct::bench::read_results).transpose()?;
    if let Some(dir) = &args.replot {
        let results = vct::bench::read_results(&dir.join("results.json"))?;
        for f in vct::bench::write(dir, &results, before.as_ref())? {
            println!("wrote {}", f.display());
        }
        return Ok(());
    }
    let mut scenes = Vec::new();
    if !args.given_only {
        scenes.push(("cornell".to_string(), Scene::embedded_default()?));
    }
    if args.accuracy && !args.given_only {
        let directional = Path::new(vct::scene::EMBEDDED_DIR).join("scene-directional.toml");
        scenes.push(("cornell-directional".to_string(), load_scene(Some(&directional))?));
    }
    for p in &args.scenes {
        let name = p.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "scene".into());
        scenes.push((name, load_scene(Some(p))?));
    }
    if args.quick {
        for (_, s) in &mut scenes {
            s.set_size(Some(128), Some(128))?;
        }
    }
    let ctx = open_device(&args.gpu)?;
    let slug: String =
        ctx.info.name.chars().map(|c| if c.is_ascii_alphanumeric() { c.to_ascii_lowercase() } else { '-' }).collect();
    let date = time::OffsetDateTime::now_utc().date();
    let out = args.out.clone().unwrap_or_else(|| PathBuf::from(format!("bench/{date}-{}", slug.trim_matches('-'))));
    if args.accuracy {
        return accuracy::accuracy(&ctx, &args, scenes, &out);
    }
    if args.occupancy {
        let n = args.res.as_ref().and_then(|r| r.first().copied()).unwrap_or(if args.quick { 64 } else { 128 });
        let frames = args.frames.unwrap_or(if args.quick { 2 } else { 5 });
        let bar = indicatif::ProgressBar::new_spinner();
        bar.enable_steady_tick(std::time::Duration::from_millis(200));
        let g = vct::bench::occupancy::run(&ctx, n, frames, &|m| bar.set_message(m.to_string()))?;
        bar.finish_and_clear();
        std::fs::create_dir_all(&out).with_context(|| format!("creating {}", out.display()))?;
        println!("{}", g.title);
        for s in &g.series {
            let pts: Vec<String> = s.points.iter().map(|(x, y)| format!("{x:.0} voxels: {y:.1} ms")).collect();
            println!("  {:<40} {}", s.label, pts.join("  "));
        }
        for f in vct::bench::charts::draw_regime(&out, &g)? {
            println!("wrote {}", f.display());
        }
        let json = out.join("occupancy.json");
        std::fs::write(&json, serde_json::to_string_pretty(&g)?)
            .with_context(|| format!("writing {}", json.display()))?;
        println!("wrote {}", json.display());
        return check_validation(&ctx);
    }
    if args.stability {
        let bar = indicatif::ProgressBar::new_spinner();
        bar.enable_steady_tick(std::time::Duration::from_millis(200));
        let regimes = vct::bench::stability::run(&ctx, args.quick, &|m| bar.set_message(m.to_string()))?;
        bar.finish_and_clear();
        std::fs::create_dir_all(&out).with_context(|| format!("creating {}", out.display()))?;
        for g in &regimes {
            println!("{}", g.title);
            for s in &g.series {
                let pts: Vec<String> = s.points.iter().map(|(x, y)| format!("{}: {y:.4}", *x as f32)).collect();
                println!("  {:<32} {}", s.label, pts.join("  "));
            }
            for f in vct::bench::charts::draw_regime(&out, g)? {
                println!("wrote {}", f.display());
            }
        }
        let json = out.join("stability.json");
        std::fs::write(&json, serde_json::to_string_pretty(&regimes)?)
            .with_context(|| format!("writing {}", json.display()))?;
        println!("wrote {}", json.display());
        let bar = indicatif::ProgressBar::new_spinner();
        bar.enable_steady_tick(std::time::Duration::from_millis(200));
        let methods = vct::bench::methods(&ctx);
        let resolutions = args.res.clone().unwrap_or(if args.quick { vec![64] } else { vec![64, 128, 256] });
        let mut hostile = Vec::new();
        for &res in &resolutions {
            let rows = vct::bench::hostile::run(&ctx, &methods, res, &|m| bar.set_message(format!("{m}, {res}³")))
                .context("voxelizing the hostile-geometry set")?;
            hostile.extend(rows);
        }
        bar.finish_and_clear();
        println!("Hostile geometry (assets/hostile/):\n{}", vct::bench::hostile::table(&hostile));
        let json = out.join("hostile.json");
        std::fs::write(&json, serde_json::to_string_pretty(&hostile)?)
            .with_context(|| format!("writing {}", json.display()))?;
        println!("wrote {}", json.display());
        return check_validation(&ctx);
    }
    let opts = vct::bench::BenchOptions {
        scenes,
        resolutions: args.res.clone().unwrap_or(if args.quick { vec![32, 64] } else { vec![64, 128, 256] }),
        warmup: if args.quick { 1 } else { 2 },
        frames: args.frames.unwrap_or(if args.quick { 3 } else { 5 }),
        reference_spp: args.spp.unwrap_or(if args.quick { 16 } else { 256 }),
        subdivisions: if args.quick { 2 } else { 4 },
        point_densities: if args.quick {
            vct::bench::points::QUICK_DENSITIES.to_vec()
        } else {
            vct::bench::points::DENSITIES.to_vec()
        },
        gi_scales: vct::bench::gi_scale::SCALES.to_vec(),
        out_dir: out.clone(),
        cache_dir: out.parent().unwrap_or(Path::new(".")).join("cache"),
        compare_storage: if args.compare_storage == OnOff::On {
            use vct::voxel::bricks::Storage;
            vec![Storage::Dense, Storage::Sparse, Storage::Resident]
        } else {
            vec![]
        },
    };
    for &r in &opts.resolutions {
        vct::voxel::VoxelGrid::fit(&vct::scene::Aabb { min: glam::Vec3::ZERO, max: glam::Vec3::ONE }, r)?;
    }
    let bar = indicatif::ProgressBar::new_spinner();
    bar.enable_steady_tick(std::time::Duration::from_millis(200));
    let start = std::time::Instant::now();
    let results = vct::bench::run(&ctx, &opts, &|m| bar.set_message(m.to_string())).context("benchmarking")?;
    bar.finish_and_clear();
    println!(
        "{:<10} {:<12} {:>5} {:>12} {:>12} {:>8} {:>8} {:>8} {:>8}",
        "scene", "voxelizer", "N", "voxelize ms", "frame ms", "recall", "prec.", "IoU", "FLIP"
    );
    for r in &results.rows {
        println!(
            "{:<10} {:<12} {:>5} {:>12.2} {:>12.2} {:>8.4} {:>8.4} {:>8.4} {:>8.4}",
            r.scene, r.voxelizer, r.resolution, r.voxelize_ms, r.total_ms, r.recall, r.precision, r.iou, r.flip
        );
    }
    for f in vct::bench::write(&out, &results, before.as_ref())? {
        println!("wrote {}", f.display());
    }
    println!("bench took {:.0} s", start.elapsed().as_secs_f64());
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
    // Exit quietly when stdout is a closed pipe (`vct ... | head`), as Unix tools do, instead
    // of Rust's default of failing the next print.
    // SAFETY: restoring the default disposition of SIGPIPE before any thread starts.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn")).init();
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Render(a) => render(a),
        Command::Voxelize(a) => voxelize(a),
        Command::View(a) => view(a),
        Command::Reference(a) => reference(a),
        Command::Compare(a) => compare(a),
        Command::Bench(a) => bench(a),
        Command::Devices => devices(),
    };
    if let Err(e) = result {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}
