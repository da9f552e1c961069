//! Depth prepass (Freed 2018 §4.7.1): camera depth first, so the expensive shading runs once
//! per visible pixel (shading tests depth EQUAL with the same vertex shader).

use std::sync::Arc;

use ash::vk;

use super::Targets;
use crate::error::Result;
use crate::gpu::{self, scope, shaders, Attachments, Context, GraphicsDesc, Pipeline, Stage};
use crate::scene::gpu::{vertex_layout, SceneGpu};

pub struct DepthPrepass {
    ctx: Arc<Context>,
    pipeline: Pipeline,
}

impl DepthPrepass {
    pub fn new(ctx: &Arc<Context>, scene: &SceneGpu) -> Result<Self> {
        let mut desc = GraphicsDesc::new(
            "depth prepass",
            vec![Stage::new(vk::ShaderStageFlags::VERTEX, shaders::SCENE_SCENE_VERT).spec(&[0])],
        );
        desc.set_layouts = vec![scene.set.layout];
        desc.push_constant_size = 4;
        desc.vertex = Some(vertex_layout());
        desc.depth_format = Targets::DEPTH_FORMAT;
        desc.depth_test = true;
        desc.depth_write = true;
        let pipeline = Pipeline::graphics(ctx, &desc)?;
        Ok(DepthPrepass { ctx: ctx.clone(), pipeline })
    }

    pub fn record(&self, cmd: vk::CommandBuffer, scene: &SceneGpu, targets: &Targets) {
        let ctx = &self.ctx;
        gpu::discard_to_depth(ctx, cmd, &targets.depth, scope::DEPTH_RW);
        let att = Attachments {
            color: None,
            depth: Some((&targets.depth, vk::AttachmentLoadOp::CLEAR)),
            width: targets.width,
            height: targets.height,
        };
        gpu::render(ctx, cmd, att, || {
            self.pipeline.bind(cmd, &[scene.set.raw]);
            scene.draw(cmd, self.pipeline.layout, false);
        });
    }
}
