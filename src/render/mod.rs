//! The frame: each pass is one module with one struct (`new` + `record`), and
//! [`Renderer::record`] lists the frame's passes in order, top to bottom.

pub mod frame;
pub mod prepass;
pub mod scene_gpu;
pub mod shade;
pub mod shadow;
pub mod tonemap;
pub mod voxel_view;

use std::sync::Arc;

use ash::vk;

use crate::error::Result;
use crate::gpu::{self, Context, GpuTimer, Image, ImageDesc, Timing};
use crate::scene::Scene;
use frame::FrameUniforms;
use prepass::DepthPrepass;
use scene_gpu::SceneGpu;
use shade::ShadePass;
use shadow::ShadowPass;
use tonemap::TonemapPass;

/// The images a frame renders into.
pub struct Targets {
    pub width: u32,
    pub height: u32,
    pub depth: Image,
    /// Linear radiance.
    pub hdr: Image,
    /// Tone-mapped, gamma-encoded output.
    pub ldr: Image,
}

impl Targets {
    pub const DEPTH_FORMAT: vk::Format = vk::Format::D32_SFLOAT;
    pub const HDR_FORMAT: vk::Format = vk::Format::R32G32B32A32_SFLOAT;
    pub const LDR_FORMAT: vk::Format = vk::Format::R8G8B8A8_UNORM;

    pub fn new(ctx: &Arc<Context>, width: u32, height: u32) -> Result<Self> {
        let u = vk::ImageUsageFlags::TRANSFER_SRC;
        Ok(Targets {
            width,
            height,
            depth: Image::new(ctx, "depth", ImageDesc::d2(Self::DEPTH_FORMAT, width, height, vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT | u))?,
            hdr: Image::new(
                ctx,
                "hdr radiance",
                ImageDesc::d2(Self::HDR_FORMAT, width, height, vk::ImageUsageFlags::COLOR_ATTACHMENT | vk::ImageUsageFlags::STORAGE | u),
            )?,
            ldr: Image::new(ctx, "ldr output", ImageDesc::d2(Self::LDR_FORMAT, width, height, vk::ImageUsageFlags::STORAGE | u))?,
        })
    }
}

/// A rendered frame read back to the host.
pub struct FrameImages {
    pub width: u32,
    pub height: u32,
    /// Linear radiance, RGBA32F, row-major from the top.
    pub hdr: Vec<f32>,
    /// Tone-mapped sRGB-ish (gamma 2.2) RGBA8.
    pub ldr: Vec<u8>,
}

pub struct Renderer {
    pub ctx: Arc<Context>,
    pub scene: Scene,
    pub scene_gpu: SceneGpu,
    shadow: ShadowPass,
    prepass: DepthPrepass,
    shade: ShadePass,
    tonemap: TonemapPass,
    pub targets: Targets,
    timer: GpuTimer,
}

impl Renderer {
    pub fn new(ctx: &Arc<Context>, scene: Scene) -> Result<Self> {
        let scene_gpu = SceneGpu::new(ctx, &scene)?;
        let targets = Targets::new(ctx, scene.camera.width, scene.camera.height)?;
        let shadow = ShadowPass::new(ctx, &scene_gpu, scene.settings.shadow_resolution)?;
        let prepass = DepthPrepass::new(ctx, &scene_gpu)?;
        let shade = ShadePass::new(ctx, &scene_gpu, &shadow)?;
        let tonemap = TonemapPass::new(ctx, &targets)?;
        let timer = GpuTimer::new(ctx, 16)?;
        Ok(Renderer { ctx: ctx.clone(), scene, scene_gpu, shadow, prepass, shade, tonemap, targets, timer })
    }

    /// Uploads this frame's uniforms from the scene's camera and light.
    pub fn update_uniforms(&self) {
        let s = &self.scene;
        let u = FrameUniforms::new(&s.camera, &s.light, &s.mesh.bounds, s.settings.shadow_resolution);
        self.scene_gpu.uniforms.write_pod(&u);
    }

    /// Records one whole frame. The passes, in order:
    pub fn record(&self, cmd: vk::CommandBuffer) {
        let t = &self.timer;
        t.reset(cmd);
        t.span(cmd, "total", || {
            t.span(cmd, "shadow map", || self.shadow.record(cmd, &self.scene_gpu));
            t.span(cmd, "depth prepass", || self.prepass.record(cmd, &self.scene_gpu, &self.targets));
            t.span(cmd, "shade", || self.shade.record(cmd, &self.scene_gpu, &self.targets));
            t.span(cmd, "tonemap", || self.tonemap.record(cmd, &self.targets));
        });
    }

    /// Renders one frame and waits for it; returns the GPU time of each pass.
    pub fn render(&self) -> Result<Vec<Timing>> {
        self.update_uniforms();
        self.ctx.submit_and_wait("frame", |cmd| self.record(cmd))?;
        self.timer.read()
    }

    /// Reads the last frame's HDR and LDR images back to the host.
    pub fn read_frame(&self) -> Result<FrameImages> {
        let hdr = gpu::read_image(&self.ctx, &self.targets.hdr, vk::ImageLayout::GENERAL, 0)?;
        let ldr = gpu::read_image(&self.ctx, &self.targets.ldr, vk::ImageLayout::GENERAL, 0)?;
        Ok(FrameImages {
            width: self.targets.width,
            height: self.targets.height,
            hdr: bytemuck::cast_slice(&hdr).to_vec(),
            ldr,
        })
    }
}
