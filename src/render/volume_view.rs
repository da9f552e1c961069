//! Debug views of the voxel volumes (`--view voxels`, `--view radiance:LEVEL`): a compute pass
//! that marches each pixel's camera ray through the grid and writes the first voxel it meets
//! into the HDR target, in place of the depth prepass and shading.

use std::sync::Arc;

use ash::vk;

use super::radiance::RadianceVolume;
use super::Targets;
use crate::error::Result;
use crate::gpu::{self, scope, shaders, Binding, Context, DescriptorSet, Pipeline, Stage};
use crate::scene::gpu::SceneGpu;
use crate::voxel::VoxelVolume;

pub struct VolumeViewPass {
    ctx: Arc<Context>,
    pipeline: Pipeline,
    set: DescriptorSet,
}

impl VolumeViewPass {
    pub fn new(
        ctx: &Arc<Context>,
        scene: &SceneGpu,
        voxels: &VoxelVolume,
        radiance: &RadianceVolume,
        targets: &Targets,
    ) -> Result<Self> {
        let c = vk::ShaderStageFlags::COMPUTE;
        let set = DescriptorSet::new(
            ctx,
            "volume view",
            &[
                Binding::new(0, vk::DescriptorType::STORAGE_IMAGE, c),
                Binding::new(1, vk::DescriptorType::COMBINED_IMAGE_SAMPLER, c),
                Binding::new(2, vk::DescriptorType::STORAGE_IMAGE, c),
                Binding::new(3, vk::DescriptorType::STORAGE_BUFFER, c),
                Binding::new(4, vk::DescriptorType::COMBINED_IMAGE_SAMPLER, c),
            ],
        )?;
        set.write_storage(0, voxels.albedo.view.raw);
        set.write_images(1, vk::DescriptorType::COMBINED_IMAGE_SAMPLER, &[radiance.sampled_info()]);
        set.write_storage(2, targets.hdr.view.raw);
        set.write_buffer(3, vk::DescriptorType::STORAGE_BUFFER, &voxels.bricks.table);
        set.write_images(4, vk::DescriptorType::COMBINED_IMAGE_SAMPLER, &[radiance.chain_info()]);
        let pipeline = Pipeline::compute(
            ctx,
            "volume view",
            Stage::new(c, shaders::GI_VOLUME_VIEW_COMP).spec(&voxels.bricks.spec(0)).grid(voxels.grid.spec()),
            &[scene.set.layout, set.layout],
            0,
        )?;
        Ok(VolumeViewPass { ctx: ctx.clone(), pipeline, set })
    }

    pub fn record(&self, cmd: vk::CommandBuffer, scene: &SceneGpu, targets: &Targets) {
        let ctx = &self.ctx;
        targets.hdr_for_compute(ctx, cmd);
        self.pipeline.bind(cmd, &[scene.set.raw, self.set.raw]);
        targets.dispatch_per_pixel(ctx, cmd);
        gpu::memory_barrier(ctx, cmd, scope::COMPUTE_RW, scope::COMPUTE_RW);
    }
}
