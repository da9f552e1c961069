//! Radiance injection (Freed 2018 §4.3, Algorithm 2) in two compute dispatches: inject (one
//! thread per shadow-map texel: marks the voxel it finds lit by its light) and resolve (one
//! thread per voxel: opacity of every occupied voxel plus emission, and the direct light it
//! reflects from the lights that marked it, with its lit side). The temporal blend into the
//! radiance volume follows (`temporal.rs`).
//!
//! The shadow map is sized for direct shadows, not for the grid: a 2048² map over a 64³ grid
//! puts some 30 texels across each voxel, and every one of them finds the same voxel (whose
//! light is computed at its centre, once). So injection reads every `stride`-th texel, the stride chosen
//! to keep `texels_per_voxel` texels across a voxel at the farthest lit point: its cost then
//! follows the grid's voxel size over the lit extent. How many it needs is set by the surfaces
//! the light grazes, whose voxels few texels hit (config.h, INJECT_TEXELS_PER_VOXEL). Each layer
//! of a map has its own stride (a cube's faces see the scene at their own depths), and a layer
//! that sees nothing its light lights is not read (`frame::layer_texel_sizes`).

use std::sync::Arc;

use ash::vk;

use super::radiance::RadianceVolume;
use super::shadow::ShadowPass;
use crate::config::WORKGROUP_2D;
use crate::error::Result;
use crate::gpu::{self, scope, shaders, Binding, Context, DescriptorSet, Pipeline, Sampler, Stage};
use crate::scene::file::Injection;
use crate::scene::gpu::SceneGpu;
use crate::voxel::occupied::OccupiedVoxels;
use crate::voxel::VoxelVolume;

pub struct InjectPass {
    ctx: Arc<Context>,
    resolve: Pipeline,
    resolve_set: DescriptorSet,
    inject: Pipeline,
    inject_set: DescriptorSet,
    _depth_sampler: Sampler,
    /// The grid's voxels along each axis.
    dims: [u32; 3],
    shadow_resolution: u32,
    /// Injection reads every `stride`-th texel of a layer along each axis: one a layer of each
    /// light's (None: the layer is not read).
    strides: Vec<Vec<Option<u32>>>,
    /// The resolve runs over the occupied voxels (the target cleared first).
    listed: bool,
    /// Injection from the voxels (`Injection::Voxels`): no texel pass; the resolve looks each
    /// voxel up in the shadow maps.
    from_voxels: bool,
    _shadow_sampler: Sampler,
}

/// The stride that leaves `texels_per_voxel` texels of `texel` world size across a `voxel`
/// (1, every texel, where the map is no finer than that; 0 `texels_per_voxel`: every texel).
pub fn injection_stride(texel: f32, voxel: f32, texels_per_voxel: f32) -> u32 {
    if !(texels_per_voxel > 0.0 && texel > 0.0) {
        return 1;
    }
    ((voxel / (texel * texels_per_voxel)).floor() as u32).max(1)
}

/// Whether injection runs from the voxels: as `choice` says, but never on a warped grid. Its
/// texels, up to four grid voxels deep, do not say where in them their surface lies, and a
/// lookup at one point of the lit side sees the light where the floor before the short box lies
/// in its shadow (its front face then gathers 1.6-1.9x the reference's indirect light).
pub fn from_voxels(choice: Injection, warped: bool) -> bool {
    choice == Injection::Voxels && !warped
}

impl InjectPass {
    #[allow(clippy::too_many_arguments)] // the passes it reads, the strides, and two switches
    pub fn new(
        ctx: &Arc<Context>,
        scene: &SceneGpu,
        shadow: &ShadowPass,
        voxels: &VoxelVolume,
        radiance: &RadianceVolume,
        strides: Vec<Vec<Option<u32>>>,
        listed: bool,
        from_voxels: bool,
    ) -> Result<Self> {
        let c = vk::ShaderStageFlags::COMPUTE;
        let storage = |b| Binding::new(b, vk::DescriptorType::STORAGE_IMAGE, c);
        let buffer = |b| Binding::new(b, vk::DescriptorType::STORAGE_BUFFER, c);
        let bricks = &voxels.bricks;
        let resolve_set = DescriptorSet::new(
            ctx,
            "resolve",
            &[
                storage(0),
                storage(1),
                storage(2),
                buffer(3),
                buffer(4),
                storage(5),
                storage(6),
                Binding::new(7, vk::DescriptorType::COMBINED_IMAGE_SAMPLER, c),
            ],
        )?;
        let shadow_sampler = Sampler::shadow(ctx, "injection shadow")?;
        resolve_set.write_sampled(7, shadow.map.view.raw, shadow_sampler.raw);
        resolve_set.write_storage(0, voxels.albedo.view.raw);
        resolve_set.write_storage(1, voxels.emission.view.raw);
        resolve_set.write_storage(2, radiance.injected.view.raw);
        resolve_set.write_buffer(3, vk::DescriptorType::STORAGE_BUFFER, &voxels.occupied.list);
        resolve_set.write_buffer(4, vk::DescriptorType::STORAGE_BUFFER, &bricks.table);
        resolve_set.write_storage(5, voxels.normal.view.raw);
        resolve_set.write_storage(6, radiance.lit_side.view.raw);
        let resolve = Pipeline::compute(
            ctx,
            "resolve",
            // Constant 3: whether any light is an area light (else its code is compiled out).
            Stage::new(c, shaders::GI_RESOLVE_COMP)
                .spec(
                    &[bricks.spec(listed as u32).as_slice(), &[scene.area_lights as u32, from_voxels as u32]].concat(),
                )
                .grid(voxels.grid.spec()),
            &[scene.set.layout, resolve_set.layout],
            0,
        )?;

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
            &[Binding::new(0, vk::DescriptorType::COMBINED_IMAGE_SAMPLER, c), storage(1), storage(2), buffer(3)],
        )?;
        inject_set.write_sampled(0, shadow.map.view.raw, depth_sampler.raw);
        inject_set.write_storage(1, voxels.albedo.view.raw);
        inject_set.write_storage(2, radiance.lit_side.view.raw);
        inject_set.write_buffer(3, vk::DescriptorType::STORAGE_BUFFER, &bricks.table);
        let inject = Pipeline::compute(
            ctx,
            "inject",
            Stage::new(c, shaders::GI_INJECT_COMP).spec(&bricks.spec(0)).grid(voxels.grid.spec()),
            &[scene.set.layout, inject_set.layout],
            12,
        )?;
        Ok(InjectPass {
            ctx: ctx.clone(),
            resolve,
            resolve_set,
            inject,
            inject_set,
            _depth_sampler: depth_sampler,
            dims: voxels.grid.dims.into(),
            shadow_resolution: shadow.map.desc.extent.width,
            strides,
            listed,
            from_voxels,
            _shadow_sampler: shadow_sampler,
        })
    }

    /// Fills `radiance.injected` (emission and opacity, plus the shadowed lights' reflection
    /// when `light`) and `radiance.lit_side`, over `occupied` (the voxelizers' list) when listed.
    pub fn record(
        &self,
        cmd: vk::CommandBuffer,
        scene: &SceneGpu,
        radiance: &RadianceVolume,
        occupied: &OccupiedVoxels,
        light: bool,
    ) {
        let ctx = &self.ctx;
        let (w, r) = (scope::COMPUTE_WRITE, scope::COMPUTE_RW);
        gpu::clear_to_general(ctx, cmd, &radiance.lit_side, scope::ANY);
        if self.listed {
            gpu::clear_to_general(ctx, cmd, &radiance.injected, scope::ANY);
        }
        gpu::memory_barrier(ctx, cmd, scope::CLEAR_WRITE, r);
        if light && !self.from_voxels {
            // One dispatch per layer of each light's shadow map (a point or area light's six
            // cube faces), each marking the voxels its texels find with its light's bit.
            self.inject.bind(cmd, &[scene.set.raw, self.inject_set.raw]);
            for (light, layers) in self.strides.iter().enumerate() {
                for (layer, stride) in layers.iter().enumerate() {
                    let Some(stride) = *stride else { continue };
                    let s = self.shadow_resolution.div_ceil(stride);
                    self.inject.push(cmd, &[stride, light as u32, layer as u32]);
                    gpu::dispatch(ctx, cmd, [s, s, 1], [WORKGROUP_2D, WORKGROUP_2D, 1]);
                }
            }
            gpu::memory_barrier(ctx, cmd, r, r);
        }
        // Every occupied voxel once: its emission, opacity and the light of the lights that
        // marked it (a voxel's value is then the sum of what each light alone gives it).
        self.resolve.bind(cmd, &[scene.set.raw, self.resolve_set.raw]);
        occupied.dispatch_or_dense(cmd, self.listed, self.dims);
        gpu::memory_barrier(ctx, cmd, w, r);
    }
}
