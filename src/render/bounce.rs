//! Multiple bounces in voxel space (Wicked Engine's VXGI, Part 4): each occupied voxel gathers
//! the filtered radiance of the bounce before with the diffuse cone set and adds albedo times
//! it to its direct light (`gi/bounce.comp`). The renderer then blends the result into level 0
//! and filters again, once per extra bounce.

use std::sync::Arc;

use ash::vk;

use super::radiance::RadianceVolume;
use crate::error::{Error, Result};
use crate::gpu::{self, scope, shaders, Binding, Context, DescriptorSet, Pipeline, Stage};
use crate::scene::gpu::SceneGpu;
use crate::voxel::occupied::OccupiedVoxels;
use crate::voxel::VoxelVolume;

pub struct BouncePass {
    ctx: Arc<Context>,
    pipeline: Pipeline,
    set: DescriptorSet,
}

impl BouncePass {
    /// `anisotropic`: gather from the six directional chains (specialization constant).
    pub fn new(
        ctx: &Arc<Context>,
        scene: &SceneGpu,
        voxels: &VoxelVolume,
        radiance: &RadianceVolume,
        occupied: &OccupiedVoxels,
        anisotropic: bool,
    ) -> Result<Self> {
        let bounced = radiance.bounced.as_ref().ok_or_else(|| Error::param("bounces", "no bounce target"))?;
        let c = vk::ShaderStageFlags::COMPUTE;
        let storage = |b| Binding::new(b, vk::DescriptorType::STORAGE_IMAGE, c);
        let sampled = |b| Binding::new(b, vk::DescriptorType::COMBINED_IMAGE_SAMPLER, c);
        let mut bindings: Vec<Binding> = (0..5).map(storage).chain((5..9).map(sampled)).collect();
        bindings.push(Binding::new(9, vk::DescriptorType::STORAGE_BUFFER, c));
        bindings.push(Binding::new(10, vk::DescriptorType::STORAGE_BUFFER, c));
        let set = DescriptorSet::new(ctx, "bounce", &bindings)?;
        set.write_storage(0, voxels.albedo.view.raw);
        set.write_storage(1, voxels.normal.view.raw);
        set.write_storage(2, radiance.lit_side.view.raw);
        set.write_storage(3, radiance.injected.view.raw);
        set.write_storage(4, bounced.view.raw);
        radiance.write_to(&set, 5);
        set.write_buffer(9, vk::DescriptorType::STORAGE_BUFFER, &occupied.list);
        set.write_buffer(10, vk::DescriptorType::STORAGE_BUFFER, &voxels.bricks.table);
        let pipeline = Pipeline::compute(
            ctx,
            "bounce",
            Stage::new(c, shaders::GI_BOUNCE_COMP)
                .spec(&voxels.bricks.spec(anisotropic as u32))
                .grid(voxels.grid.spec()),
            &[scene.set.layout, set.layout],
            0,
        )?;
        Ok(BouncePass { ctx: ctx.clone(), pipeline, set })
    }

    /// One bounce into `radiance.bounced` (cleared first: only occupied voxels are written), read
    /// by the blend that follows.
    pub fn record(
        &self,
        cmd: vk::CommandBuffer,
        scene: &SceneGpu,
        radiance: &RadianceVolume,
        occupied: &OccupiedVoxels,
    ) {
        if let Some(b) = &radiance.bounced {
            gpu::clear_to_general(&self.ctx, cmd, b, scope::COMPUTE_RW);
            gpu::memory_barrier(&self.ctx, cmd, scope::CLEAR_WRITE, scope::COMPUTE_RW);
        }
        self.pipeline.bind(cmd, &[scene.set.raw, self.set.raw]);
        occupied.dispatch(cmd);
        // The blend overwrites level 0, which this pass sampled: a write after read.
        gpu::memory_barrier(&self.ctx, cmd, scope::COMPUTE_RW, scope::COMPUTE_RW);
    }
}
