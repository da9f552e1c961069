//! Tessellation voxelizer (Freed 2018 §4.1.2): 3-control-point patches; the control shader
//! sets levels from edge lengths and the largest altitude against the voxel size, the
//! evaluation shader (point mode) writes one voxel per generated vertex. Triangles whose
//! levels would pass the device limit, or the patch-balance bound below it, are subdivided when
//! the scene loads.

use std::sync::Arc;

use ash::vk;

use super::subdivide::subdivide_for_tessellation;
use super::{flag, params_for, voxel_set, ParamsUbo, VoxelVolume};
use crate::config;
use crate::error::Result;
use crate::gpu::{self, shaders, Attachments, Context, DescriptorSet, GraphicsDesc, Pipeline, Stage};
use crate::scene::gpu::{vertex_layout_untangented, MeshBuffers, SceneGpu};
use crate::scene::Scene;

/// Triangles are split at load until no tessellation level passes this bound, so that no patch
/// is huge: a per-patch CPU tessellator (lavapipe) runs patches in parallel, and a few huge ones
/// serialize. Measured on the Cornell box (docs/design/voxelizers.md): at 128³ the
/// device limit (64) gives 2187 ms, 16 gives 872, 8 gives 625, 4 gives 798 (too many patches),
/// with recall unchanged (0.994).
pub const PATCH_LEVEL_BOUND: f32 = 8.0;

pub struct TessVoxelizer {
    ctx: Arc<Context>,
    pipeline: Pipeline,
    pub(crate) set: DescriptorSet,
    pub(crate) params: ParamsUbo,
    /// The scene mesh with over-large triangles split (or as loaded, without subdivision).
    mesh: MeshBuffers,
    split: usize,
    subdivide: bool,
    max_level: f32,
}

impl TessVoxelizer {
    /// The method's four switches come as `VoxelizeMethod::Tess` holds them.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        ctx: &Arc<Context>,
        scene: &Scene,
        scene_gpu: &SceneGpu,
        volume: &VoxelVolume,
        level_scale: f32,
        subdivide: bool,
        min_level: bool,
        neighbours: bool,
    ) -> Result<Self> {
        let max_level = ctx.info.limits.max_tessellation_generation_level as f32;
        let (mesh, split) = if subdivide {
            let bound = max_level.min(PATCH_LEVEL_BOUND);
            let (m, split) = subdivide_for_tessellation(&scene.mesh, &volume.grid, level_scale, bound);
            (MeshBuffers::new(ctx, "tess voxelizer mesh", &m)?, split)
        } else {
            (MeshBuffers::new(ctx, "tess voxelizer mesh", &scene.mesh)?, 0)
        };
        let flags = flag(min_level, config::VOXEL_FLAG_MIN_LEVEL) | flag(neighbours, config::VOXEL_FLAG_NEIGHBOURS);
        let params = params_for(&volume.grid, flags, 1.0, level_scale, max_level);
        let (set, params_buffer) = voxel_set(ctx, volume, &params)?;
        let spec = volume.bricks.spec(0);
        let mut desc = GraphicsDesc::new(
            "tess voxelizer",
            vec![
                Stage::new(vk::ShaderStageFlags::VERTEX, shaders::VOXELIZE_WORLD_VERT),
                Stage::new(vk::ShaderStageFlags::TESSELLATION_CONTROL, shaders::VOXELIZE_TESS_TESC)
                    .grid(volume.grid.spec()),
                Stage::new(vk::ShaderStageFlags::TESSELLATION_EVALUATION, shaders::VOXELIZE_TESS_TESE)
                    .spec(&spec)
                    .grid(volume.grid.spec()),
            ],
        );
        desc.set_layouts = vec![scene_gpu.set.layout, scene_gpu.material_sets.layout, set.layout];
        desc.push_constant_size = 4;
        desc.vertex = Some(vertex_layout_untangented());
        desc.topology = vk::PrimitiveTopology::PATCH_LIST;
        desc.patch_control_points = 3;
        desc.rasterizer_discard = true;
        let pipeline = Pipeline::graphics(ctx, &desc)?;
        Ok(TessVoxelizer { ctx: ctx.clone(), pipeline, set, params: params_buffer, mesh, split, subdivide, max_level })
    }

    /// Voxelizes the scene, or only its triangles near `within` (a clipmap level's box).
    pub fn record(&self, cmd: vk::CommandBuffer, scene_gpu: &SceneGpu, within: Option<&crate::scene::Aabb>) {
        let att = Attachments { color: None, depth: None, width: 1, height: 1 };
        gpu::render(&self.ctx, cmd, att, || {
            self.pipeline.bind(cmd, &[scene_gpu.set.raw]);
            self.pipeline.bind_set(cmd, 2, self.set.raw);
            self.mesh.draw_within(cmd, self.pipeline.layout, Some(&scene_gpu.material_sets), within);
        });
    }

    pub fn notes(&self) -> Vec<String> {
        if self.subdivide {
            vec![format!(
                "tessellation: split {} triangle(s) whose levels passed {PATCH_LEVEL_BOUND} (patch balance; device limit {})",
                self.split, self.max_level
            )]
        } else {
            vec!["tessellation: subdivision off; triangles past the level limit leave holes".into()]
        }
    }
}
