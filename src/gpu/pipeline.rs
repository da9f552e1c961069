//! Compute and graphics pipelines (with their layouts), built from embedded SPIR-V with
//! specialization constants for variants. Graphics pipelines use dynamic rendering.

use std::ffi::CStr;
use std::sync::Arc;

use ash::vk;

use super::Context;
use crate::error::{Result, VkContext};

/// How the volume's texels lie, as every shader that maps world space to them is specialized:
/// WARPED (constant WARP_CONSTANT_ID, common/warp.glsl: the grid is warped) and CLIPPED
/// (CLIP_CONSTANT_ID, common/frame.glsl: the volume is a clipmap's stack of levels). Off, that
/// layout's code is compiled out.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GridSpec {
    pub warped: bool,
    pub clipped: bool,
}

/// One shader stage: SPIR-V bytes plus specialization constants (constant_id 0, 1, ...), and
/// the grid's layout (`GridSpec`).
#[derive(Clone, Copy)]
pub struct Stage<'a> {
    pub stage: vk::ShaderStageFlags,
    pub spirv: &'a [u8],
    pub spec: &'a [u32],
    pub grid: GridSpec,
}

impl<'a> Stage<'a> {
    pub fn new(stage: vk::ShaderStageFlags, spirv: &'a [u8]) -> Self {
        Stage { stage, spirv, spec: &[], grid: GridSpec::default() }
    }
    pub fn spec(mut self, spec: &'a [u32]) -> Self {
        self.spec = spec;
        self
    }
    /// For a grid laid out as `grid` says (`voxel::VoxelGrid::spec`).
    pub fn grid(mut self, grid: GridSpec) -> Self {
        self.grid = grid;
        self
    }
}

const ENTRY: &CStr = c"main";

struct Module {
    ctx: Arc<Context>,
    raw: vk::ShaderModule,
}

impl Module {
    fn new(ctx: &Arc<Context>, spirv: &[u8]) -> Result<Self> {
        let words = ash::util::read_spv(&mut std::io::Cursor::new(spirv)).map_err(|_| crate::error::Error::Vulkan {
            call: "read_spv",
            result: vk::Result::ERROR_INVALID_SHADER_NV,
        })?;
        let raw = unsafe { ctx.device.create_shader_module(&vk::ShaderModuleCreateInfo::default().code(&words), None) }
            .vk("vkCreateShaderModule")?;
        Ok(Module { ctx: ctx.clone(), raw })
    }
}

impl Drop for Module {
    fn drop(&mut self) {
        unsafe { self.ctx.device.destroy_shader_module(self.raw, None) };
    }
}

/// Specialization data for one stage, kept alive while the pipeline is created.
struct Spec {
    entries: Vec<vk::SpecializationMapEntry>,
    data: Vec<u8>,
}

impl Spec {
    fn new(values: &[u32], grid: GridSpec) -> Self {
        assert!(values.len() as u32 <= crate::config::WARP_CONSTANT_ID, "constant ids collide with WARPED");
        let mut entries: Vec<_> = (0..values.len() as u32)
            .map(|i| vk::SpecializationMapEntry { constant_id: i, offset: i * 4, size: 4 })
            .collect();
        let n = values.len() as u32;
        entries.push(vk::SpecializationMapEntry {
            constant_id: crate::config::WARP_CONSTANT_ID,
            offset: n * 4,
            size: 4,
        });
        let mut data: Vec<u8> = bytemuck::cast_slice(values).to_vec();
        entries.push(vk::SpecializationMapEntry {
            constant_id: crate::config::CLIP_CONSTANT_ID,
            offset: (n + 1) * 4,
            size: 4,
        });
        data.extend_from_slice(&(grid.warped as u32).to_ne_bytes());
        data.extend_from_slice(&(grid.clipped as u32).to_ne_bytes());
        Spec { entries, data }
    }
    fn info(&self) -> vk::SpecializationInfo<'_> {
        vk::SpecializationInfo::default().map_entries(&self.entries).data(&self.data)
    }
}

/// Vertex input: one interleaved binding (per vertex, or per instance when `instanced`).
#[derive(Clone, Copy)]
pub struct VertexLayout<'a> {
    pub stride: u32,
    pub attributes: &'a [vk::VertexInputAttributeDescription],
}

/// Everything that varies between this renderer's graphics pipelines.
#[derive(Clone)]
pub struct GraphicsDesc<'a> {
    pub name: &'a str,
    pub stages: Vec<Stage<'a>>,
    pub set_layouts: Vec<vk::DescriptorSetLayout>,
    pub push_constant_size: u32,
    pub vertex: Option<VertexLayout<'a>>,
    pub topology: vk::PrimitiveTopology,
    pub patch_control_points: u32,
    pub cull: vk::CullModeFlags,
    pub depth_format: vk::Format,
    pub depth_test: bool,
    pub depth_write: bool,
    pub depth_compare: vk::CompareOp,
    pub depth_bias: Option<(f32, f32)>,
    pub color_formats: Vec<vk::Format>,
    pub samples: vk::SampleCountFlags,
    pub conservative: bool,
    /// No rasterization at all (the tessellation voxelizer writes from the TES).
    pub rasterizer_discard: bool,
    /// The vertex binding advances per instance.
    pub instanced: bool,
}

impl<'a> GraphicsDesc<'a> {
    pub fn new(name: &'a str, stages: Vec<Stage<'a>>) -> Self {
        GraphicsDesc {
            name,
            stages,
            set_layouts: Vec::new(),
            push_constant_size: 0,
            vertex: None,
            topology: vk::PrimitiveTopology::TRIANGLE_LIST,
            patch_control_points: 0,
            cull: vk::CullModeFlags::NONE,
            depth_format: vk::Format::UNDEFINED,
            depth_test: false,
            depth_write: false,
            depth_compare: vk::CompareOp::LESS,
            depth_bias: None,
            color_formats: Vec::new(),
            samples: vk::SampleCountFlags::TYPE_1,
            conservative: false,
            rasterizer_discard: false,
            instanced: false,
        }
    }
}

pub struct Pipeline {
    ctx: Arc<Context>,
    pub raw: vk::Pipeline,
    pub layout: vk::PipelineLayout,
    pub bind_point: vk::PipelineBindPoint,
}

fn create_layout(ctx: &Context, set_layouts: &[vk::DescriptorSetLayout], push: u32) -> Result<vk::PipelineLayout> {
    let ranges = [vk::PushConstantRange { stage_flags: vk::ShaderStageFlags::ALL, offset: 0, size: push }];
    let info = vk::PipelineLayoutCreateInfo::default().set_layouts(set_layouts).push_constant_ranges(if push > 0 {
        &ranges[..]
    } else {
        &[]
    });
    unsafe { ctx.device.create_pipeline_layout(&info, None) }.vk("vkCreatePipelineLayout")
}

impl Pipeline {
    pub fn compute(
        ctx: &Arc<Context>,
        name: &str,
        stage: Stage,
        set_layouts: &[vk::DescriptorSetLayout],
        push_constant_size: u32,
    ) -> Result<Self> {
        let module = Module::new(ctx, stage.spirv)?;
        let spec = Spec::new(stage.spec, stage.grid);
        let spec_info = spec.info();
        let layout = create_layout(ctx, set_layouts, push_constant_size)?;
        let info = vk::ComputePipelineCreateInfo::default()
            .stage(
                vk::PipelineShaderStageCreateInfo::default()
                    .stage(vk::ShaderStageFlags::COMPUTE)
                    .module(module.raw)
                    .name(ENTRY)
                    .specialization_info(&spec_info),
            )
            .layout(layout);
        let raw = unsafe { ctx.device.create_compute_pipelines(vk::PipelineCache::null(), &[info], None) }
            .map_err(|(_, r)| r)
            .vk("vkCreateComputePipelines")?[0];
        ctx.set_name(raw, name);
        Ok(Pipeline { ctx: ctx.clone(), raw, layout, bind_point: vk::PipelineBindPoint::COMPUTE })
    }

    pub fn graphics(ctx: &Arc<Context>, desc: &GraphicsDesc) -> Result<Self> {
        let modules: Vec<Module> = desc.stages.iter().map(|s| Module::new(ctx, s.spirv)).collect::<Result<_>>()?;
        let specs: Vec<Spec> = desc.stages.iter().map(|s| Spec::new(s.spec, s.grid)).collect();
        let spec_infos: Vec<_> = specs.iter().map(|s| s.info()).collect();
        let stages: Vec<_> = desc
            .stages
            .iter()
            .zip(&modules)
            .zip(&spec_infos)
            .map(|((s, m), si)| {
                vk::PipelineShaderStageCreateInfo::default()
                    .stage(s.stage)
                    .module(m.raw)
                    .name(ENTRY)
                    .specialization_info(si)
            })
            .collect();

        let bindings;
        let vertex_input = match &desc.vertex {
            Some(v) => {
                bindings = [vk::VertexInputBindingDescription {
                    binding: 0,
                    stride: v.stride,
                    input_rate: if desc.instanced {
                        vk::VertexInputRate::INSTANCE
                    } else {
                        vk::VertexInputRate::VERTEX
                    },
                }];
                vk::PipelineVertexInputStateCreateInfo::default()
                    .vertex_binding_descriptions(&bindings)
                    .vertex_attribute_descriptions(v.attributes)
            }
            None => vk::PipelineVertexInputStateCreateInfo::default(),
        };
        let input_assembly = vk::PipelineInputAssemblyStateCreateInfo::default().topology(desc.topology);
        let tessellation =
            vk::PipelineTessellationStateCreateInfo::default().patch_control_points(desc.patch_control_points);
        let viewport = vk::PipelineViewportStateCreateInfo::default().viewport_count(1).scissor_count(1);
        let mut conservative = vk::PipelineRasterizationConservativeStateCreateInfoEXT::default()
            .conservative_rasterization_mode(vk::ConservativeRasterizationModeEXT::OVERESTIMATE);
        let mut raster = vk::PipelineRasterizationStateCreateInfo::default()
            .polygon_mode(vk::PolygonMode::FILL)
            .cull_mode(desc.cull)
            .front_face(vk::FrontFace::COUNTER_CLOCKWISE)
            .rasterizer_discard_enable(desc.rasterizer_discard)
            .line_width(1.0);
        if let Some((constant, slope)) = desc.depth_bias {
            raster = raster.depth_bias_enable(true).depth_bias_constant_factor(constant).depth_bias_slope_factor(slope);
        }
        if desc.conservative {
            raster = raster.push_next(&mut conservative);
        }
        let multisample = vk::PipelineMultisampleStateCreateInfo::default().rasterization_samples(desc.samples);
        let depth = vk::PipelineDepthStencilStateCreateInfo::default()
            .depth_test_enable(desc.depth_test)
            .depth_write_enable(desc.depth_write)
            .depth_compare_op(desc.depth_compare);
        let blend_attachments: Vec<_> = desc
            .color_formats
            .iter()
            .map(|_| vk::PipelineColorBlendAttachmentState::default().color_write_mask(vk::ColorComponentFlags::RGBA))
            .collect();
        let blend = vk::PipelineColorBlendStateCreateInfo::default().attachments(&blend_attachments);
        let dynamic_states = [vk::DynamicState::VIEWPORT, vk::DynamicState::SCISSOR];
        let dynamic = vk::PipelineDynamicStateCreateInfo::default().dynamic_states(&dynamic_states);
        let mut rendering = vk::PipelineRenderingCreateInfo::default()
            .color_attachment_formats(&desc.color_formats)
            .depth_attachment_format(desc.depth_format);

        let layout = create_layout(ctx, &desc.set_layouts, desc.push_constant_size)?;
        let mut info = vk::GraphicsPipelineCreateInfo::default()
            .stages(&stages)
            .vertex_input_state(&vertex_input)
            .input_assembly_state(&input_assembly)
            .viewport_state(&viewport)
            .rasterization_state(&raster)
            .multisample_state(&multisample)
            .depth_stencil_state(&depth)
            .color_blend_state(&blend)
            .dynamic_state(&dynamic)
            .layout(layout)
            .push_next(&mut rendering);
        if desc.patch_control_points > 0 {
            info = info.tessellation_state(&tessellation);
        }
        let raw = unsafe { ctx.device.create_graphics_pipelines(vk::PipelineCache::null(), &[info], None) }
            .map_err(|(_, r)| r)
            .vk("vkCreateGraphicsPipelines")?[0];
        ctx.set_name(raw, desc.name);
        Ok(Pipeline { ctx: ctx.clone(), raw, layout, bind_point: vk::PipelineBindPoint::GRAPHICS })
    }

    /// Binds the pipeline and its descriptor sets (set 0, 1, ...).
    pub fn bind(&self, cmd: vk::CommandBuffer, sets: &[vk::DescriptorSet]) {
        unsafe {
            self.ctx.device.cmd_bind_pipeline(cmd, self.bind_point, self.raw);
            if !sets.is_empty() {
                self.ctx.device.cmd_bind_descriptor_sets(cmd, self.bind_point, self.layout, 0, sets, &[]);
            }
        }
    }

    /// Binds one descriptor set at index `index`.
    pub fn bind_set(&self, cmd: vk::CommandBuffer, index: u32, set: vk::DescriptorSet) {
        unsafe { self.ctx.device.cmd_bind_descriptor_sets(cmd, self.bind_point, self.layout, index, &[set], &[]) };
    }

    pub fn push<T: bytemuck::Pod>(&self, cmd: vk::CommandBuffer, value: &T) {
        unsafe {
            self.ctx.device.cmd_push_constants(
                cmd,
                self.layout,
                vk::ShaderStageFlags::ALL,
                0,
                bytemuck::bytes_of(value),
            )
        };
    }
}

impl Drop for Pipeline {
    fn drop(&mut self) {
        unsafe {
            self.ctx.device.destroy_pipeline(self.raw, None);
            self.ctx.device.destroy_pipeline_layout(self.layout, None);
        }
    }
}
