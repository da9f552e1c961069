//! Shadow map pass (Freed 2018 §4.2): the scene's depth from the light into a D32 texture,
//! with a small slope-scaled depth bias (shading adds a normal offset; a large slope bias let
//! light under thin walls); read by shading (PCF) and later by radiance injection. Every light
//! has its own layers of one layered map: a point light six (a cube of 90° faces), the others
//! one; each layer is rendered by its own pipeline (the layer a specialization constant of the
//! scene vertex shader, which reads that layer's matrix from the frame uniforms).

use std::sync::Arc;

use ash::vk;

use crate::error::Result;
use crate::gpu::{self, scope, shaders, Context, GraphicsDesc, Image, ImageDesc, Pipeline, Stage};
use crate::scene::gpu::{vertex_layout, SceneGpu};
use crate::scene::Light;

pub const SHADOW_FORMAT: vk::Format = vk::Format::D32_SFLOAT;

pub struct ShadowPass {
    ctx: Arc<Context>,
    /// One per layer of the map.
    pipelines: Vec<Pipeline>,
    pub map: Image,
}

impl ShadowPass {
    /// `lights`: the scene's shadowed lights (a scene without one keeps one unused layer).
    pub fn new(ctx: &Arc<Context>, scene: &SceneGpu, resolution: u32, lights: &[Light]) -> Result<Self> {
        let usage = vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT | vk::ImageUsageFlags::SAMPLED;
        let layers = lights.iter().map(super::frame::shadow_layers).sum::<u32>().max(1);
        let map =
            Image::new(ctx, "shadow map", ImageDesc::d2_array(SHADOW_FORMAT, resolution, resolution, layers, usage))?;
        let pipeline = |layer: u32| {
            // Scene vertex shader: VIEW 1 (a light's shadow map), layer FACE.
            let spec = [1, layer];
            let mut desc = GraphicsDesc::new(
                "shadow map",
                vec![Stage::new(vk::ShaderStageFlags::VERTEX, shaders::SCENE_SCENE_VERT).spec(&spec)],
            );
            desc.set_layouts = vec![scene.set.layout];
            desc.push_constant_size = 4;
            desc.vertex = Some(vertex_layout());
            desc.depth_format = SHADOW_FORMAT;
            desc.depth_test = true;
            desc.depth_write = true;
            desc.depth_bias = Some((2.0, 1.0));
            Pipeline::graphics(ctx, &desc)
        };
        let pipelines = (0..layers).map(pipeline).collect::<Result<Vec<_>>>()?;
        // Ready for sampling from the start: a scene without a shadowed light never renders it,
        // but the shading passes still bind it.
        ctx.submit_and_wait("shadow map layout", |cmd| {
            gpu::image_barrier(
                ctx,
                cmd,
                &map,
                vk::ImageLayout::UNDEFINED,
                vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL,
                scope::NONE,
                scope::NONE,
            )
        })?;
        Ok(ShadowPass { ctx: ctx.clone(), pipelines, map })
    }

    /// Renders the shadow map and leaves it ready for sampling in fragment and compute shaders.
    pub fn record(&self, cmd: vk::CommandBuffer, scene: &SceneGpu) {
        let ctx = &self.ctx;
        let sampled = (
            vk::PipelineStageFlags2::FRAGMENT_SHADER | vk::PipelineStageFlags2::COMPUTE_SHADER,
            vk::AccessFlags2::SHADER_SAMPLED_READ,
        );
        gpu::discard_to_depth(ctx, cmd, &self.map, sampled);
        for (layer, pipeline) in self.pipelines.iter().enumerate() {
            gpu::render_depth_layer(ctx, cmd, &self.map, layer as u32, || {
                pipeline.bind(cmd, &[scene.set.raw]);
                scene.draw(cmd, pipeline.layout, false);
            });
        }
        gpu::image_barrier(
            ctx,
            cmd,
            &self.map,
            vk::ImageLayout::DEPTH_ATTACHMENT_OPTIMAL,
            vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL,
            scope::DEPTH_RW,
            sampled,
        );
    }
}
