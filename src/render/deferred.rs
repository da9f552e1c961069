//! Deferred variant of the final shading, kept to measure where cone tracing should run
//! (`--tracing deferred`): a G-buffer pass (depth; albedo with textures applied + material
//! index; shading normal + camera distance), then one compute thread per pixel running the same
//! `shade_surface` (common/shading.glsl) as the forward path. With a GI scale s > 1 the diffuse
//! cones are traced first at one pixel in s² and upsampled edge-aware in the shading pass (the
//! reduced-resolution indirect light engines that ship cone tracing use; shade/deferred.comp).

use std::sync::Arc;

use ash::vk;

use super::radiance::RadianceVolume;
use super::shadow::ShadowPass;
use super::Targets;
use crate::error::Result;
use crate::gpu::{
    self, scope, shaders, Binding, Context, DescriptorSet, GraphicsDesc, Image, ImageDesc, Pipeline, Sampler, Stage,
};
use crate::scene::gpu::{vertex_layout, SceneGpu};

const ALBEDO_FORMAT: vk::Format = vk::Format::R16G16B16A16_SFLOAT;
/// Normal and camera distance: 32-bit, so the rebuilt position is as exact as the forward one.
const NORMAL_FORMAT: vk::Format = vk::Format::R32G32B32A32_SFLOAT;

pub struct DeferredShadePass {
    ctx: Arc<Context>,
    gbuffer_pipeline: Pipeline,
    shade_pipeline: Pipeline,
    /// The diffuse cones at one pixel in `gi_scale`² (none at scale 1).
    trace_pipeline: Option<Pipeline>,
    /// Their gather (a 1×1 stand-in at scale 1).
    diffuse_low: Image,
    set: DescriptorSet,
    albedo: Image,
    normal: Image,
    _shadow_sampler: Sampler,
}

impl DeferredShadePass {
    /// `anisotropic`: cones sample the six directional chains (specialization constant);
    /// `gi_scale`: the diffuse cones run at one pixel in `gi_scale`² (1, 2 or 4).
    #[allow(clippy::too_many_arguments)] // the passes it reads, and two switches
    pub fn new(
        ctx: &Arc<Context>,
        scene: &SceneGpu,
        shadow: &ShadowPass,
        radiance: &RadianceVolume,
        bricks: &crate::voxel::bricks::Bricks,
        targets: &Targets,
        anisotropic: bool,
        gi_scale: u32,
    ) -> Result<Self> {
        if !matches!(gi_scale, 1 | 2 | 4) {
            return Err(crate::Error::param("gi-scale", format!("must be 1, 2 or 4, got {gi_scale}")));
        }
        let usage = vk::ImageUsageFlags::COLOR_ATTACHMENT | vk::ImageUsageFlags::STORAGE;
        let albedo =
            Image::new(ctx, "gbuffer albedo", ImageDesc::d2(ALBEDO_FORMAT, targets.width, targets.height, usage))?;
        let normal =
            Image::new(ctx, "gbuffer normal", ImageDesc::d2(NORMAL_FORMAT, targets.width, targets.height, usage))?;
        let mut desc = GraphicsDesc::new(
            "gbuffer",
            vec![
                Stage::new(vk::ShaderStageFlags::VERTEX, shaders::SCENE_SCENE_VERT).spec(&[0]),
                Stage::new(vk::ShaderStageFlags::FRAGMENT, shaders::SHADE_GBUFFER_FRAG),
            ],
        );
        desc.set_layouts = vec![scene.set.layout, scene.material_sets.layout];
        desc.push_constant_size = 4;
        desc.vertex = Some(vertex_layout());
        desc.depth_format = Targets::DEPTH_FORMAT;
        desc.depth_test = true;
        desc.depth_write = true;
        desc.color_formats = vec![ALBEDO_FORMAT, NORMAL_FORMAT];
        let gbuffer_pipeline = Pipeline::graphics(ctx, &desc)?;

        let c = vk::ShaderStageFlags::COMPUTE;
        let sampled = vk::DescriptorType::COMBINED_IMAGE_SAMPLER;
        let storage = vk::DescriptorType::STORAGE_IMAGE;
        let set = DescriptorSet::new(
            ctx,
            "deferred shade",
            &[
                Binding::new(0, sampled, c),
                Binding::new(1, sampled, c),
                Binding::new(2, storage, c),
                Binding::new(3, storage, c),
                Binding::new(4, storage, c),
                Binding::new(5, sampled, c),
                Binding::new(6, sampled, c),
                Binding::new(7, sampled, c),
                Binding::new(8, vk::DescriptorType::STORAGE_BUFFER, c),
                Binding::new(9, storage, c),
            ],
        )?;
        let (lw, lh) =
            if gi_scale > 1 { (targets.width.div_ceil(gi_scale), targets.height.div_ceil(gi_scale)) } else { (1, 1) };
        let diffuse_low = Image::new(
            ctx,
            "diffuse gather (reduced)",
            ImageDesc::d2(vk::Format::R16G16B16A16_SFLOAT, lw, lh, vk::ImageUsageFlags::STORAGE),
        )?;
        set.write_storage(9, diffuse_low.view.raw);
        let shadow_sampler = Sampler::shadow(ctx, "deferred shadow sampler")?;
        set.write_sampled(0, shadow.map.view.raw, shadow_sampler.raw);
        set.write_images(1, sampled, &[radiance.sampled_info()]);
        set.write_images(5, sampled, &[radiance.aniso_info()]);
        set.write_images(6, sampled, &[radiance.moment_info()]);
        set.write_images(7, sampled, &[radiance.chain_info()]);
        set.write_buffer(8, vk::DescriptorType::STORAGE_BUFFER, &bricks.table);
        set.write_storage(2, albedo.view.raw);
        set.write_storage(3, normal.view.raw);
        set.write_storage(4, targets.hdr.view.raw);
        let [aniso, sparse, resident] = bricks.spec(anisotropic as u32);
        let layouts = [scene.set.layout, scene.material_sets.layout, set.layout];
        let pipeline = |name: &str, pass: u32| {
            let spec = [aniso, sparse, resident, gi_scale, pass];
            Pipeline::compute(ctx, name, Stage::new(c, shaders::SHADE_DEFERRED_COMP).spec(&spec), &layouts, 0)
        };
        let shade_pipeline = pipeline("deferred shade", 0)?;
        let trace_pipeline = (gi_scale > 1).then(|| pipeline("diffuse cones (reduced)", 1)).transpose()?;
        Ok(DeferredShadePass {
            ctx: ctx.clone(),
            gbuffer_pipeline,
            shade_pipeline,
            trace_pipeline,
            diffuse_low,
            set,
            albedo,
            normal,
            _shadow_sampler: shadow_sampler,
        })
    }

    /// Depth and G-buffer in one geometry pass (it replaces the depth prepass).
    pub fn record_gbuffer(&self, cmd: vk::CommandBuffer, scene: &SceneGpu, targets: &Targets) {
        let ctx = &self.ctx;
        gpu::discard_to_depth(ctx, cmd, &targets.depth, scope::COMPUTE_READ);
        for img in [&self.albedo, &self.normal] {
            gpu::image_barrier(
                ctx,
                cmd,
                img,
                vk::ImageLayout::UNDEFINED,
                vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
                scope::COMPUTE_READ,
                scope::COLOR_WRITE,
            );
        }
        let color: Vec<_> = [&self.albedo, &self.normal]
            .iter()
            .map(|img| {
                vk::RenderingAttachmentInfo::default()
                    .image_view(img.view.raw)
                    .image_layout(vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL)
                    .load_op(vk::AttachmentLoadOp::CLEAR)
                    .store_op(vk::AttachmentStoreOp::STORE)
            })
            .collect();
        gpu::render_multi(
            ctx,
            cmd,
            &color,
            Some((&targets.depth, vk::AttachmentLoadOp::CLEAR)),
            targets.width,
            targets.height,
            || {
                self.gbuffer_pipeline.bind(cmd, &[scene.set.raw]);
                scene.draw(cmd, self.gbuffer_pipeline.layout, true);
            },
        );
        for img in [&self.albedo, &self.normal] {
            gpu::image_barrier(
                ctx,
                cmd,
                img,
                vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
                vk::ImageLayout::GENERAL,
                scope::COLOR_WRITE,
                scope::COMPUTE_READ,
            );
        }
    }

    /// One compute thread per pixel shades into `targets.hdr` (left in GENERAL).
    pub fn record_shade(&self, cmd: vk::CommandBuffer, scene: &SceneGpu, targets: &Targets) {
        let ctx = &self.ctx;
        targets.hdr_for_compute(ctx, cmd);
        let rw = scope::COMPUTE_RW;
        gpu::image_barrier(ctx, cmd, &self.diffuse_low, vk::ImageLayout::UNDEFINED, vk::ImageLayout::GENERAL, rw, rw);
        if let Some(trace) = &self.trace_pipeline {
            trace.bind(cmd, &[scene.set.raw]);
            trace.bind_set(cmd, 2, self.set.raw);
            let (w, h) = (self.diffuse_low.desc.extent.width, self.diffuse_low.desc.extent.height);
            let local = crate::config::WORKGROUP_2D;
            gpu::dispatch(ctx, cmd, [w, h, 1], [local, local, 1]);
            gpu::memory_barrier(ctx, cmd, rw, rw);
        }
        self.shade_pipeline.bind(cmd, &[scene.set.raw]);
        self.shade_pipeline.bind_set(cmd, 2, self.set.raw);
        targets.dispatch_per_pixel(ctx, cmd);
        gpu::memory_barrier(ctx, cmd, scope::COMPUTE_RW, scope::COMPUTE_RW);
    }
}
