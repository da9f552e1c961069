//! Rasterized voxelizer (Freed 2018 §4.1.1): the geometry shader projects each triangle along
//! its dominant axis onto an attachment-less N×N framebuffer (N the grid's longest axis); coverage is made conservative by
//! 4× MSAA (the thesis' method), by hardware conservative rasterization where offered, by
//! growing the triangle in the geometry shader (conservative without the extension), or not at
//! all; the fragment shader writes the voxels the triangle really touches, with atomic averaging.

use std::sync::Arc;

use ash::vk;

use super::{flag, params_for, voxel_set, Coverage, ParamsUbo, VoxelVolume};
use crate::config;
use crate::error::Result;
use crate::gpu::{self, shaders, Attachments, Context, DescriptorSet, GraphicsDesc, Pipeline, Stage};
use crate::scene::gpu::{vertex_layout_untangented, SceneGpu};

pub struct RasterVoxelizer {
    ctx: Arc<Context>,
    pipeline: Pipeline,
    pub(crate) set: DescriptorSet,
    pub(crate) params: ParamsUbo,
    size: u32,
}

impl RasterVoxelizer {
    pub fn new(
        ctx: &Arc<Context>,
        scene_gpu: &SceneGpu,
        volume: &VoxelVolume,
        coverage: Coverage,
        viewport_scale: f32,
        depth_span: bool,
    ) -> Result<Self> {
        let viewport_scale = viewport_scale.clamp(0.125, 8.0);
        let size = ((volume.grid.voxelized().longest() as f32 * viewport_scale).round() as u32).max(1);
        let max = ctx.info.limits.max_framebuffer_width.min(ctx.info.limits.max_framebuffer_height);
        if size > max {
            return Err(crate::Error::param(
                "viewport-scale",
                format!("{size} pixels exceed the device's framebuffer limit {max}"),
            ));
        }
        let conservative = coverage == Coverage::Conservative;
        if conservative && !depth_span {
            // The grown triangle's extra fragments are only dropped by the exact voxel test.
            return Err(crate::Error::param("no-depth-span", "conservative coverage needs the exact depth span"));
        }
        let flags =
            flag(depth_span, config::VOXEL_FLAG_DEPTH_SPAN) | flag(conservative, config::VOXEL_FLAG_CONSERVATIVE);
        let params = params_for(&volume.grid, flags, viewport_scale, 1.0, 1.0);
        let (set, params_buffer) = voxel_set(ctx, volume, &params)?;
        let spec = volume.bricks.spec(0);
        let mut desc = GraphicsDesc::new(
            "raster voxelizer",
            vec![
                Stage::new(vk::ShaderStageFlags::VERTEX, shaders::VOXELIZE_WORLD_VERT),
                // A perspective warp's triangles are mapped among the texels here.
                Stage::new(vk::ShaderStageFlags::GEOMETRY, shaders::VOXELIZE_RASTER_GEOM).grid(volume.grid.spec()),
                Stage::new(vk::ShaderStageFlags::FRAGMENT, shaders::VOXELIZE_RASTER_FRAG)
                    .spec(&spec)
                    .grid(volume.grid.spec()),
            ],
        );
        desc.set_layouts = vec![scene_gpu.set.layout, scene_gpu.material_sets.layout, set.layout];
        desc.push_constant_size = 4;
        desc.vertex = Some(vertex_layout_untangented());
        desc.samples =
            if coverage == Coverage::Msaa { vk::SampleCountFlags::TYPE_4 } else { vk::SampleCountFlags::TYPE_1 };
        desc.conservative = coverage == Coverage::Hardware;
        let pipeline = Pipeline::graphics(ctx, &desc)?;
        Ok(RasterVoxelizer { ctx: ctx.clone(), pipeline, set, params: params_buffer, size })
    }

    /// Voxelizes the scene, or only its triangles near `within` (a clipmap level's box).
    pub fn record(&self, cmd: vk::CommandBuffer, scene_gpu: &SceneGpu, within: Option<&crate::scene::Aabb>) {
        let att = Attachments { color: None, depth: None, width: self.size, height: self.size };
        gpu::render(&self.ctx, cmd, att, || {
            self.pipeline.bind(cmd, &[scene_gpu.set.raw]);
            self.pipeline.bind_set(cmd, 2, self.set.raw);
            scene_gpu.draw_within(cmd, self.pipeline.layout, true, within);
        });
    }
}
