//! The windowed viewer (`vct view`): winit window, ash-window surface and swapchain, running
//! the same [`Renderer`] frame as `vct render` every frame, then blitting its output to the
//! swapchain image. Keys switch voxelizer, view, resolution, GI and temporal filtering; the
//! title shows FPS and per-pass GPU times. `--frames N --screenshot FILE` automates it.

pub mod camera;

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{DeviceEvent, DeviceId, ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::window::{Window, WindowId};

use crate::error::{Error, Result};
use crate::gpu::{self, Context, ContextOptions, FrameOutcome, Swapchain, Timing};
use crate::render::overlay::OverlayPass;
use crate::render::{RenderOptions, Renderer, View};
use crate::scene::Scene;
use camera::{light_step, swing_light, CameraController, Input, Mode};

pub const HELP: &str = "\
vct viewer keys:
  W A S D        fly forward / left / back / right (orbit mode: W/S zoom)
  Q E            fly down / up          Shift   faster
  right mouse    look around (fly)      left mouse  orbit (orbit mode)   wheel  zoom
  O              toggle fly / orbit around the scene centre
  arrow keys     swing the light's direction (the GI follows)
  V              switch voxelizer (rasterized / tessellation / points)
  X              voxel layout: fitted / warped, finest at the camera (Freed 2018 §4.6.1) /
                 warped by perspective, the camera's frustum (§4.6.2) / clipmap, levels around the camera
  C              cycle views: full, direct, indirect, diffuse, specular, ao, voxels, texels, radiance:0..3
  + / -          voxel resolution up / down (16..512)
  G              global illumination on / off
  R              diffuse cones at one pixel in 1 / 4 / 16 / 64 (GI scale 1, 2, 4, 8)
  P              accumulate those cones over frames on / off (GI scale 2, 4, 8)
  T              temporal filtering on / off
  I              on-screen overlay on / off (never in screenshots)
  F12            screenshot (vct-screenshot-N.png)
  H or F1        this help (also in the overlay)          Esc  quit";

pub struct ViewerOptions {
    pub scene: Scene,
    pub render: RenderOptions,
    pub vsync: bool,
    pub validation: bool,
    pub device: Option<String>,
    /// Exit after this many presented frames.
    pub frames: Option<u32>,
    /// Save the last frame here on exit.
    pub screenshot: Option<PathBuf>,
    /// Ask the window for this size a third of the way through `frames`.
    pub resize_to: Option<(u32, u32)>,
    /// Soak test: move camera and light every frame, switch voxelizer and resolution on the
    /// [`SOAK_CYCLE`] schedule, and compare memory at frames 60 and 180, 300, ... (same settings).
    pub soak: bool,
    /// Draw the on-screen overlay (FPS, pass times, settings, memory; the keys on H).
    pub overlay: bool,
}

/// What a run of the viewer did.
pub struct ViewerReport {
    pub frames: u32,
    pub validation_errors: u32,
    pub validation_warnings: u32,
    pub gpu_bytes_start: u64,
    pub gpu_bytes_end: u64,
    /// Soak runs: GPU bytes and resident host bytes at frame 60 and at the last of 180, 300, ...
    pub soak_baseline: Option<(u64, u64)>,
    pub soak_end: Option<(u64, u64)>,
}

/// Resident set size of this process in bytes (Linux), 0 where unknown.
pub fn resident_bytes() -> u64 {
    std::fs::read_to_string("/proc/self/statm")
        .ok()
        .and_then(|s| s.split_whitespace().nth(1).and_then(|p| p.parse::<u64>().ok()))
        .map(|pages| pages * 4096)
        .unwrap_or(0)
}

/// Soak schedule: the voxelizer moves to the next of its three every 20 frames and the resolution
/// flips every 30, so frames 60, 180, 300, ... run the same settings; memory is compared between
/// those frames. (A schedule three times as long, each switch as often, would spend six minutes
/// of `make test` on frames between the same switches.)
pub const SOAK_CYCLE: u32 = 60;

const VIEWS: [View; 12] = [
    View::Full,
    View::Direct,
    View::Indirect,
    View::Diffuse,
    View::Specular,
    View::Ao,
    View::Voxels,
    View::Texels,
    View::Radiance(0),
    View::Radiance(1),
    View::Radiance(2),
    View::Radiance(3),
];

/// Live state once the window exists. Fields drop in order: GPU objects before the window.
struct Running {
    renderer: Renderer,
    /// Made for the renderer's current output image; dropped whenever that is made anew.
    overlay: Option<OverlayPass>,
    show_overlay: bool,
    show_keys: bool,
    fps: f32,
    swapchain: Swapchain,
    ctx: Arc<Context>,
    window: Arc<Window>,
    camera: CameraController,
    input: Input,
    last_frame: Instant,
    title_at: Instant,
    title_frames: u32,
    last_timings: Vec<Timing>,
    screenshots: u32,
    gpu_bytes_start: u64,
}

struct App {
    options: ViewerOptions,
    running: Option<Running>,
    error: Option<Error>,
    frames: u32,
    report: Option<ViewerReport>,
    soak_baseline: Option<(u64, u64)>,
    soak_end: Option<(u64, u64)>,
}

fn key_axis(code: KeyCode, plus: KeyCode, minus: KeyCode, pressed: bool, axis: &mut f32) {
    if code == plus {
        *axis = if pressed { 1.0 } else { axis.min(0.0) };
    } else if code == minus {
        *axis = if pressed { -1.0 } else { axis.max(0.0) };
    }
}

/// The overlay's text: FPS and size; voxelizer, grid and storage; view, GI, temporal filter,
/// bounces and filter; voxel memory; each pass's GPU time; the key map on H.
fn overlay_lines(r: &Running) -> Vec<String> {
    let renderer = &r.renderer;
    let (o, gi) = (&renderer.options, &renderer.scene.settings.gi);
    let on = |b: bool| if b { "on" } else { "off" };
    let grid = &renderer.voxels.grid;
    let memory = renderer.memory();
    let mut lines = vec![
        format!("vct  {:.1} fps  {}x{}", r.fps, renderer.targets.width, renderer.targets.height),
        format!(
            "voxelizer {}  grid {}x{}x{}{}  storage {}",
            o.method.label(),
            grid.dims.x,
            grid.dims.y,
            grid.dims.z,
            match (o.warp, grid.clip) {
                (Some(w), _) => format!(" {}", w.label()),
                (_, Some(c)) => format!(" clipmap ({} levels of {}³)", c.levels, c.res),
                _ => String::new(),
            },
            renderer.voxels.bricks.storage.label()
        ),
        format!(
            "view {}  GI {} (scale {}{})  temporal {}  bounces {}  filter {}",
            format!("{:?}", o.view).to_lowercase(),
            on(o.gi),
            o.gi_scale,
            if o.gi_accumulate { ", accumulated" } else { "" },
            on(gi.temporal < 1.0),
            gi.bounces,
            format!("{:?}", gi.filter).to_lowercase()
        ),
        format!(
            "voxel memory {:.1} MiB ({:.0}% of the bounding cube's)",
            memory.bytes as f64 / (1 << 20) as f64,
            100.0 * memory.bytes as f64 / memory.cube_bytes.max(1) as f64
        ),
    ];
    let mut line = String::from("GPU ms:");
    for t in &r.last_timings {
        let item = format!("  {} {:.1}", t.pass, t.ms);
        if line.len() + item.len() > 60 {
            lines.push(std::mem::replace(&mut line, "       ".into()));
        }
        line.push_str(&item);
    }
    lines.push(line);
    if r.show_keys {
        lines.push(String::new());
        lines.extend(HELP.lines().map(str::to_owned));
    } else {
        lines.push("H: keys   I: overlay off".into());
    }
    lines
}

impl App {
    fn start(&mut self, event_loop: &ActiveEventLoop) -> Result<()> {
        let cam = self.options.scene.camera;
        let attrs =
            Window::default_attributes().with_title("vct").with_inner_size(PhysicalSize::new(cam.width, cam.height));
        let window =
            Arc::new(event_loop.create_window(attrs).map_err(|e| Error::Loader(format!("cannot open a window: {e}")))?);
        let display = raw_window_handle::HasDisplayHandle::display_handle(&*window)
            .map_err(|e| Error::Loader(format!("no display: {e}")))?
            .as_raw();
        let exts = ash_window::enumerate_required_extensions(display)
            .map_err(|r| Error::Vulkan { call: "enumerate_required_extensions", result: r })?;
        // SAFETY: ash-window returns pointers to 'static NUL-terminated extension names.
        let instance_extensions = exts.iter().map(|&p| unsafe { std::ffi::CStr::from_ptr(p) }).collect();
        let ctx = Context::new(&ContextOptions {
            instance_extensions,
            swapchain: true,
            ..ContextOptions::from_env(self.options.validation, self.options.device.clone())
        })?;
        println!("device: {} ({})", ctx.info.name, ctx.info.driver);
        let size = window.inner_size();
        let (w, h) = (size.width.max(1), size.height.max(1));
        let swapchain = Swapchain::new(&ctx, &*window, w, h, self.options.vsync)?;
        let mut scene = self.options.scene.clone();
        scene.camera.width = w;
        scene.camera.height = h;
        let camera = CameraController::new(&scene.camera, &scene.mesh.bounds);
        let renderer = Renderer::new(&ctx, scene, self.options.render)?;
        for n in &renderer.notes {
            println!("note: {n}");
        }
        println!("{HELP}");
        let now = Instant::now();
        self.running = Some(Running {
            gpu_bytes_start: ctx.allocated_bytes(),
            renderer,
            overlay: None,
            show_overlay: self.options.overlay,
            show_keys: false,
            fps: 0.0,
            swapchain,
            ctx,
            window,
            camera,
            input: Input::default(),
            last_frame: now,
            title_at: now,
            title_frames: 0,
            last_timings: Vec::new(),
            screenshots: 0,
        });
        Ok(())
    }

    fn fail(&mut self, event_loop: &ActiveEventLoop, e: Error) {
        self.error = Some(e);
        self.finish();
        event_loop.exit();
    }

    /// Saves the screenshot if asked and records the report; drops the GPU state.
    fn finish(&mut self) {
        if let Some(r) = self.running.take() {
            let _ = r.swapchain.wait_idle();
            if let (Some(path), None) = (&self.options.screenshot, &self.error) {
                if let Err(e) = r.renderer.read_frame().and_then(|f| crate::output::write_png(path, &f)) {
                    self.error = Some(e);
                } else {
                    println!("wrote {}", path.display());
                }
            }
            let ctx = r.ctx.clone();
            let gpu_bytes_end = ctx.allocated_bytes();
            let gpu_bytes_start = r.gpu_bytes_start;
            drop(r);
            self.report = Some(ViewerReport {
                frames: self.frames,
                validation_errors: ctx.validation.errors(),
                validation_warnings: ctx.validation.warnings(),
                gpu_bytes_start,
                gpu_bytes_end,
                soak_baseline: self.soak_baseline,
                soak_end: self.soak_end,
            });
        }
    }

    /// Rebuilds the renderer with new options (voxelizer or resolution), keeping camera and light.
    fn rebuild(r: &mut Running, options: RenderOptions) -> Result<()> {
        r.ctx.wait_idle()?;
        r.overlay = None;
        let scene = r.renderer.scene.clone();
        r.renderer = Renderer::new(&r.ctx, scene, options)?;
        for n in &r.renderer.notes {
            println!("note: {n}");
        }
        Ok(())
    }

    fn on_key(&mut self, code: KeyCode, pressed: bool, event_loop: &ActiveEventLoop) -> Result<()> {
        let Some(r) = self.running.as_mut() else { return Ok(()) };
        let i = &mut r.input;
        key_axis(code, KeyCode::KeyW, KeyCode::KeyS, pressed, &mut i.forward);
        key_axis(code, KeyCode::KeyD, KeyCode::KeyA, pressed, &mut i.right);
        key_axis(code, KeyCode::KeyE, KeyCode::KeyQ, pressed, &mut i.up);
        key_axis(code, KeyCode::ArrowRight, KeyCode::ArrowLeft, pressed, &mut i.light.0);
        key_axis(code, KeyCode::ArrowUp, KeyCode::ArrowDown, pressed, &mut i.light.1);
        if matches!(code, KeyCode::ShiftLeft | KeyCode::ShiftRight) {
            i.fast = pressed;
        }
        if !pressed {
            return Ok(());
        }
        let mut options = r.renderer.options;
        match code {
            KeyCode::Escape => event_loop.exit(),
            KeyCode::KeyH | KeyCode::F1 => {
                println!("{HELP}");
                r.show_keys = !r.show_keys;
            }
            KeyCode::KeyI => r.show_overlay = !r.show_overlay,
            KeyCode::KeyO => {
                r.camera.toggle_mode(&r.renderer.scene.camera);
                println!("camera: {}", if r.camera.mode == Mode::Fly { "fly" } else { "orbit" });
            }
            KeyCode::KeyV => {
                options.method = options.method.next();
                Self::rebuild(r, options)?;
                println!("voxelizer: {}", r.renderer.options.method.label());
            }
            KeyCode::KeyX => {
                // Fitted, warped, clipmap (a clipmap is a cube around the camera: not with a
                // following volume or given dims), and back.
                // The clipmap given on the command line, else DEFAULT_LEVELS at the default extent.
                let default =
                    crate::render::ClipOptions { levels: crate::voxel::clipmap::DEFAULT_LEVELS, extent: None };
                let clip = self.options.render.clipmap.unwrap_or(default);
                let cube = options.follow.is_none() && options.dims.is_none();
                use crate::voxel::warp::{WarpChoice, THESIS_END_SLOPE};
                (options.warp, options.clipmap) = match (options.warp, options.clipmap) {
                    (None, None) => (Some(WarpChoice::Function(THESIS_END_SLOPE)), None),
                    (Some(WarpChoice::Function(_)), _) if options.follow.is_none() => {
                        (Some(WarpChoice::Perspective(crate::voxel::perspective::DEFAULT_RATIO)), None)
                    }
                    (Some(_), _) if cube => (None, Some(clip)),
                    _ => (None, None),
                };
                let moving = options.warp.is_some() || options.clipmap.is_some();
                if moving && r.renderer.scene.settings.gi.temporal < 1.0 {
                    println!("voxel layout: warped and clipmap volumes need temporal filtering off (T)");
                    return Ok(());
                }
                let layout = match (options.warp, options.clipmap) {
                    (Some(WarpChoice::Function(_)), _) => {
                        "warped by the thesis' function (finest at the camera)".to_string()
                    }
                    (Some(WarpChoice::Perspective(_)), _) => "warped by perspective (the camera's frustum)".to_string(),
                    (_, Some(c)) => format!("clipmap ({} levels around the camera)", c.levels),
                    _ => "fitted".to_string(),
                };
                println!("voxel layout: {layout}");
                Self::rebuild(r, options)?;
            }
            KeyCode::Equal | KeyCode::NumpadAdd | KeyCode::Minus | KeyCode::NumpadSubtract => {
                let now = r.renderer.voxels.grid.voxelized().longest();
                let up = matches!(code, KeyCode::Equal | KeyCode::NumpadAdd);
                let next = if up { (now * 2).min(512) } else { (now / 2).max(16) };
                if next != now {
                    options.resolution = Some(next);
                    println!("voxel resolution: {next}³");
                    Self::rebuild(r, options)?;
                }
            }
            KeyCode::KeyC => {
                let at = VIEWS.iter().position(|v| *v == options.view).unwrap_or(0);
                options.view = VIEWS[(at + 1) % VIEWS.len()];
                r.renderer.options.view = options.view;
                println!("view: {:?}", options.view);
                // The directional model keeps no isotropic chain above level 0 until a view reads it.
                if matches!(options.view, View::Radiance(_)) && !r.renderer.radiance.chains.isotropic {
                    Self::rebuild(r, options)?;
                }
            }
            KeyCode::KeyR if options.tracing == crate::render::Tracing::Forward => {
                println!("GI scale: reduced-resolution tracing needs --tracing deferred");
            }
            KeyCode::KeyR => {
                options.gi_scale = match options.gi_scale {
                    1 => 2,
                    2 => 4,
                    4 => 8,
                    _ => 1,
                };
                // At full resolution every pixel is traced every frame: nothing to accumulate.
                options.gi_accumulate &= options.gi_scale > 1;
                println!("GI scale: {} (diffuse cones at one pixel in {})", options.gi_scale, options.gi_scale.pow(2));
                Self::rebuild(r, options)?;
            }
            KeyCode::KeyP if options.gi_scale == 1 => {
                println!("GI accumulation: needs a GI scale of 2, 4 or 8 (R)");
            }
            KeyCode::KeyP => {
                options.gi_accumulate = !options.gi_accumulate;
                println!("GI accumulation over frames: {}", if options.gi_accumulate { "on" } else { "off" });
                Self::rebuild(r, options)?;
            }
            KeyCode::KeyG => {
                r.renderer.options.gi = !options.gi;
                println!("global illumination: {}", if r.renderer.options.gi { "on" } else { "off" });
            }
            KeyCode::KeyT
                if (options.warp.is_some() || options.clipmap.is_some())
                    && r.renderer.scene.settings.gi.temporal >= 1.0 =>
            {
                println!("temporal filter: a warped or clipmap volume keeps no history (X: back to fitted)");
            }
            KeyCode::KeyT => {
                let gi = &mut r.renderer.scene.settings.gi;
                gi.temporal = if gi.temporal >= 1.0 { 0.2 } else { 1.0 };
                let on = gi.temporal < 1.0;
                println!("temporal filter: {}", if on { "on (0.2)" } else { "off" });
                // Without temporal filtering the renderer keeps no history: it needs one now.
                if on && !r.renderer.radiance.has_history() {
                    Self::rebuild(r, options)?;
                }
            }
            KeyCode::F12 => {
                r.swapchain.wait_idle()?;
                let path = PathBuf::from(format!("vct-screenshot-{}.png", r.screenshots));
                crate::output::write_png(&path, &r.renderer.read_frame()?)?;
                r.screenshots += 1;
                println!("wrote {}", path.display());
            }
            _ => {}
        }
        Ok(())
    }

    /// One soak frame: the camera circles the scene, the light swings, and the voxelizer and
    /// resolution change on a fixed schedule.
    fn soak_step(r: &mut Running, frame: u32) -> Result<()> {
        let b = r.renderer.scene.mesh.bounds;
        let angle = frame as f32 * 0.05;
        let radius = b.size().length() * 0.9;
        let cam = &mut r.renderer.scene.camera;
        cam.target = b.center();
        cam.eye = b.center() + glam::Vec3::new(angle.sin() * radius, b.size().y * 0.3, angle.cos() * radius);
        if let Some(light) = r.renderer.scene.lights.first_mut() {
            swing_light(light, 0.03, 0.02 * angle.cos());
        }
        if frame > 0 && frame.is_multiple_of(SOAK_CYCLE / 3) {
            let mut o = r.renderer.options;
            o.method = o.method.next();
            Self::rebuild(r, o)?;
        }
        if frame > 0 && frame.is_multiple_of(SOAK_CYCLE / 2) {
            let mut o = r.renderer.options;
            let n = r.renderer.voxels.grid.voxelized().longest();
            o.resolution = Some(if (frame / (SOAK_CYCLE / 2)) % 2 == 1 { n * 2 } else { n / 2 });
            Self::rebuild(r, o)?;
        }
        Ok(())
    }

    fn redraw(&mut self, event_loop: &ActiveEventLoop) -> Result<()> {
        let Some(r) = self.running.as_mut() else { return Ok(()) };
        let size = r.window.inner_size();
        if size.width == 0 || size.height == 0 {
            return Ok(()); // minimised: nothing to draw until restored
        }
        if (size.width, size.height) != (r.renderer.targets.width, r.renderer.targets.height) {
            r.swapchain.recreate(size.width, size.height)?;
            r.overlay = None;
            r.renderer.resize(size.width, size.height)?;
        }
        let now = Instant::now();
        let dt = (now - r.last_frame).as_secs_f32().min(0.25);
        r.last_frame = now;
        if self.options.soak {
            Self::soak_step(r, self.frames)?;
            // Frames 60, 180, 300, ... run the same voxelizer and resolution.
            if self.frames >= SOAK_CYCLE && (self.frames - SOAK_CYCLE).is_multiple_of(2 * SOAK_CYCLE) {
                let snapshot = Some((r.ctx.allocated_bytes(), resident_bytes()));
                if self.soak_baseline.is_none() {
                    self.soak_baseline = snapshot;
                } else {
                    self.soak_end = snapshot;
                }
            }
        }
        r.camera.update(&mut r.renderer.scene.camera, &mut r.input, dt);
        let eye = r.renderer.scene.camera.eye;
        r.renderer.follow(eye)?;
        let (yaw, pitch) = light_step(&r.input, dt);
        if yaw != 0.0 || pitch != 0.0 {
            if let Some(light) = r.renderer.scene.lights.first_mut() {
                swing_light(light, yaw, pitch);
            }
        }
        if r.show_overlay {
            if r.overlay.is_none() {
                r.overlay = Some(OverlayPass::new(&r.ctx, &r.renderer.targets.ldr)?);
            }
            if let Some(o) = &r.overlay {
                o.set_text(&overlay_lines(r));
            }
        }
        let overlay = r.overlay.as_ref().filter(|_| r.show_overlay);
        let (renderer, ctx) = (&r.renderer, &r.ctx);
        let mut timings = Ok(Vec::new());
        let mut bricks = Ok(());
        let mut recorded = false;
        let extent = r.swapchain.extent;
        let outcome = r.swapchain.frame(|cmd, image| {
            // The frame before the last may still run: read what the one before it left.
            (timings, bricks) = renderer.record_in_flight(cmd);
            recorded = true;
            match overlay {
                Some(o) => {
                    o.record(cmd);
                    gpu::blit_to_present(ctx, cmd, &o.composite, image, extent);
                }
                None => gpu::blit_to_present(ctx, cmd, &renderer.targets.ldr, image, extent),
            }
        })?;
        if recorded {
            r.renderer.frame_recorded();
        }
        if let Err(e) = bricks {
            if r.renderer.voxels.bricks.storage == crate::voxel::bricks::Storage::Resident {
                // Geometry outside the census' bricks: census again, and say so.
                println!("note: {e}; binding the bricks of a new census");
                Self::rebuild(r, r.renderer.options)?;
            } else {
                // A moving volume met more geometry than its pool holds: grow it, and say so.
                let u = r.renderer.voxels.bricks.settled_usage();
                let grown = u.needed + (u.needed as f64 * crate::voxel::MOVING_POOL_HEADROOM).ceil() as u32;
                println!("note: {e}; the pool grows to {grown} bricks");
                let options = RenderOptions { bricks: Some(grown), ..r.renderer.options };
                Self::rebuild(r, options)?;
                r.renderer.options.bricks = None;
            }
        }
        let timings = timings?;
        if !timings.is_empty() {
            r.last_timings = timings;
        }
        if outcome == FrameOutcome::OutOfDate {
            let s = r.window.inner_size();
            r.swapchain.recreate(s.width.max(1), s.height.max(1))?;
        }
        self.frames += 1;
        r.title_frames += 1;
        let since = (now - r.title_at).as_secs_f32();
        if since >= 0.5 {
            let passes: Vec<String> = r.last_timings.iter().map(|t| format!("{} {:.1}", t.pass, t.ms)).collect();
            r.fps = r.title_frames as f32 / since;
            r.window.set_title(&format!(
                "vct — {:.1} fps — {} {}³ — GPU ms: {}",
                r.fps,
                r.renderer.options.method.label(),
                r.renderer.voxels.grid.voxelized().longest(),
                passes.join(", ")
            ));
            r.title_at = now;
            r.title_frames = 0;
        }
        if let (Some(n), Some((w, h))) = (self.options.frames, self.options.resize_to) {
            if self.frames == (n / 3).max(1) {
                let _ = r.window.request_inner_size(PhysicalSize::new(w, h));
            }
        }
        if self.options.frames.is_some_and(|n| self.frames >= n) {
            self.finish();
            event_loop.exit();
        }
        Ok(())
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.running.is_none() && self.error.is_none() {
            if let Err(e) = self.start(event_loop) {
                self.fail(event_loop, e);
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        let result = match event {
            WindowEvent::CloseRequested => {
                self.finish();
                event_loop.exit();
                Ok(())
            }
            WindowEvent::RedrawRequested => self.redraw(event_loop),
            WindowEvent::KeyboardInput { event, .. } => match event.physical_key {
                PhysicalKey::Code(code) if !event.repeat => {
                    self.on_key(code, event.state == ElementState::Pressed, event_loop)
                }
                _ => Ok(()),
            },
            WindowEvent::MouseInput { state, button, .. } => {
                if let Some(r) = self.running.as_mut() {
                    let look_button = if r.camera.mode == Mode::Fly { MouseButton::Right } else { MouseButton::Left };
                    if button == look_button {
                        r.input.look = (0.0, 0.0);
                        LOOKING.with(|l| l.set(state == ElementState::Pressed));
                    }
                }
                Ok(())
            }
            WindowEvent::MouseWheel { delta, .. } => {
                if let Some(r) = self.running.as_mut() {
                    r.input.zoom += match delta {
                        MouseScrollDelta::LineDelta(_, y) => y,
                        MouseScrollDelta::PixelDelta(p) => p.y as f32 / 40.0,
                    };
                }
                Ok(())
            }
            _ => Ok(()),
        };
        if let Err(e) = result {
            self.fail(event_loop, e);
        }
    }

    fn device_event(&mut self, _event_loop: &ActiveEventLoop, _id: DeviceId, event: DeviceEvent) {
        if let (DeviceEvent::MouseMotion { delta }, Some(r)) = (event, self.running.as_mut()) {
            if LOOKING.with(|l| l.get()) {
                r.input.look.0 += delta.0 as f32;
                r.input.look.1 += delta.1 as f32;
            }
        }
    }

    fn about_to_wait(&mut self, _event_loop: &ActiveEventLoop) {
        if let Some(r) = &self.running {
            r.window.request_redraw();
        }
    }
}

thread_local! {
    /// Whether the look/orbit mouse button is held.
    static LOOKING: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Opens the window and runs until it is closed, Esc is pressed or `frames` have been shown.
pub fn run(options: ViewerOptions) -> Result<ViewerReport> {
    let event_loop = EventLoop::new()
        .map_err(|e| Error::Loader(format!("cannot start the window system (is DISPLAY set?): {e}")))?;
    event_loop.set_control_flow(ControlFlow::Poll);
    let mut app =
        App { options, running: None, error: None, frames: 0, report: None, soak_baseline: None, soak_end: None };
    event_loop.run_app(&mut app).map_err(|e| Error::Loader(format!("event loop: {e}")))?;
    app.finish();
    if let Some(e) = app.error {
        return Err(e);
    }
    app.report.ok_or_else(|| Error::Loader("the viewer never opened its window".into()))
}
