//! Radiance injection (Freed 2018 §4.3, Algorithm 2) in three compute dispatches: resolve
//! (one thread per voxel: opacity of every occupied voxel plus emission), inject (one thread
//! per shadow-map texel: the direct light each lit voxel reflects), and the temporal blend into
//! level 0 of the radiance volume (§4.7.2).

use std::sync::Arc;

use ash::vk;

use super::radiance::RadianceVolume;
use super::scene_gpu::SceneGpu;
use super::shadow::ShadowPass;
use crate::config::{WORKGROUP_2D, WORKGROUP_3D};
use crate::error::Result;
use crate::gpu::{self, scope, shaders, Binding, Context, DescriptorSet, Pipeline, Sampler, Stage};
use crate::voxel::VoxelVolume;

pub struct InjectPass {
    ctx: Arc<Context>,
    resolve: Pipeline,
    resolve_set: DescriptorSet,
    inject: Pipeline,
    inject_set: DescriptorSet,
    blend: Pipeline,
    blend_set: DescriptorSet,
    anisotropic: bool,
    _depth_sampler: Sampler,
    resolution: u32,
    shadow_resolution: u32,
}

impl InjectPass {
    pub fn new(
        ctx: &Arc<Context>,
        scene: &SceneGpu,
        shadow: &ShadowPass,
        voxels: &VoxelVolume,
        radiance: &RadianceVolume,
        anisotropic: bool,
    ) -> Result<Self> {
        let c = vk::ShaderStageFlags::COMPUTE;
        let storage = |b| Binding::new(b, vk::DescriptorType::STORAGE_IMAGE, c);
        let resolve_set = DescriptorSet::new(ctx, "resolve", &[storage(0), storage(1), storage(2)])?;
        resolve_set.write_storage(0, voxels.albedo.view.raw);
        resolve_set.write_storage(1, voxels.emission.view.raw);
        resolve_set.write_storage(2, radiance.injected.view.raw);
        let resolve =
            Pipeline::compute(ctx, "resolve", Stage::new(c, shaders::GI_RESOLVE_COMP), &[resolve_set.layout], 0)?;

        let depth_sampler = Sampler::new(
            ctx,
            "shadow depth (nearest)",
            &vk::SamplerCreateInfo::default()
                .mag_filter(vk::Filter::NEAREST)
                .min_filter(vk::Filter::NEAREST)
                .address_mode_u(vk::SamplerAddressMode::CLAMP_TO_EDGE)
                .address_mode_v(vk::SamplerAddressMode::CLAMP_TO_EDGE),
        )?;
        let inject_set = DescriptorSet::new(
            ctx,
            "inject",
            &[
                Binding::new(0, vk::DescriptorType::COMBINED_IMAGE_SAMPLER, c),
                storage(1),
                storage(2),
                storage(3),
                storage(4),
                storage(5),
            ],
        )?;
        inject_set.write_sampled(0, shadow.map.view.raw, depth_sampler.raw);
        inject_set.write_storage(1, voxels.albedo.view.raw);
        inject_set.write_storage(2, voxels.normal.view.raw);
        inject_set.write_storage(3, voxels.emission.view.raw);
        inject_set.write_storage(4, radiance.injected.view.raw);
        inject_set.write_storage(5, radiance.lit_side.view.raw);
        let inject = Pipeline::compute(
            ctx,
            "inject",
            Stage::new(c, shaders::GI_INJECT_COMP).spec(&[anisotropic as u32]),
            &[scene.set.layout, inject_set.layout],
            0,
        )?;

        let blend_set = DescriptorSet::new(
            ctx,
            "temporal blend",
            &[storage(0), storage(1), Binding::new(2, vk::DescriptorType::COMBINED_IMAGE_SAMPLER, c)],
        )?;
        blend_set.write_storage(0, radiance.injected.view.raw);
        blend_set.write_storage(1, radiance.radiance.mip_view(0));
        blend_set.write_images(
            2,
            vk::DescriptorType::COMBINED_IMAGE_SAMPLER,
            &[vk::DescriptorImageInfo {
                sampler: radiance.sampler.raw,
                image_view: radiance.history.view.raw,
                image_layout: vk::ImageLayout::GENERAL,
            }],
        );
        let blend = Pipeline::compute(
            ctx,
            "temporal blend",
            Stage::new(c, shaders::GI_BLEND_COMP),
            &[scene.set.layout, blend_set.layout],
            0,
        )?;

        Ok(InjectPass {
            ctx: ctx.clone(),
            resolve,
            resolve_set,
            inject,
            inject_set,
            blend,
            blend_set,
            anisotropic,
            _depth_sampler: depth_sampler,
            resolution: voxels.grid.resolution,
            shadow_resolution: shadow.map.desc.extent.width,
        })
    }

    /// With `temporal` (a blend factor below 1) the previous level 0 is first copied aside for
    /// the blend to reproject. With anisotropic filtering the lit side of each lit voxel is
    /// recorded too.
    pub fn record(&self, cmd: vk::CommandBuffer, scene: &SceneGpu, radiance: &RadianceVolume, temporal: bool) {
        let ctx = &self.ctx;
        let n = self.resolution;
        let cube = [WORKGROUP_3D; 3];
        let (w, r) = (scope::COMPUTE_WRITE, scope::COMPUTE_RW);
        self.resolve.bind(cmd, &[self.resolve_set.raw]);
        gpu::dispatch(ctx, cmd, [n, n, n], cube);
        gpu::memory_barrier(ctx, cmd, w, r);
        if self.anisotropic {
            gpu::clear_to_general(ctx, cmd, &radiance.lit_side, scope::ANY);
            gpu::memory_barrier(ctx, cmd, scope::CLEAR_WRITE, w);
        }
        self.inject.bind(cmd, &[scene.set.raw, self.inject_set.raw]);
        gpu::dispatch(ctx, cmd, [self.shadow_resolution, self.shadow_resolution, 1], [WORKGROUP_2D, WORKGROUP_2D, 1]);
        gpu::memory_barrier(ctx, cmd, w, r);
        if temporal {
            gpu::copy_level(ctx, cmd, &radiance.radiance, 0, &radiance.history);
        }
        self.blend.bind(cmd, &[scene.set.raw, self.blend_set.raw]);
        gpu::dispatch(ctx, cmd, [n, n, n], cube);
        gpu::memory_barrier(ctx, cmd, w, r);
    }
}
