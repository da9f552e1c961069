//! Descriptor sets that own their layout and pool: a `DescriptorSet` holds one or more sets of
//! one layout (made from a list of [`Binding`]s), written with typed helpers.

use std::sync::Arc;

use ash::vk;

use super::{Buffer, Context};
use crate::error::{Result, VkContext};

#[derive(Clone, Copy, Debug)]
pub struct Binding {
    pub binding: u32,
    pub ty: vk::DescriptorType,
    pub count: u32,
    pub stages: vk::ShaderStageFlags,
}

impl Binding {
    pub fn new(binding: u32, ty: vk::DescriptorType, stages: vk::ShaderStageFlags) -> Self {
        Binding { binding, ty, count: 1, stages }
    }
    pub fn array(mut self, count: u32) -> Self {
        self.count = count;
        self
    }
}

pub struct DescriptorSet {
    ctx: Arc<Context>,
    pub layout: vk::DescriptorSetLayout,
    pool: vk::DescriptorPool,
    /// The first set (most passes have one).
    pub raw: vk::DescriptorSet,
    /// All sets of this layout.
    pub sets: Vec<vk::DescriptorSet>,
}

impl DescriptorSet {
    pub fn new(ctx: &Arc<Context>, name: &str, bindings: &[Binding]) -> Result<Self> {
        Self::new_many(ctx, name, bindings, 1)
    }

    /// `count` sets of one layout from one pool.
    pub fn new_many(ctx: &Arc<Context>, name: &str, bindings: &[Binding], count: u32) -> Result<Self> {
        let count = count.max(1);
        let d = &ctx.device;
        let vk_bindings: Vec<_> = bindings
            .iter()
            .map(|b| {
                vk::DescriptorSetLayoutBinding::default()
                    .binding(b.binding)
                    .descriptor_type(b.ty)
                    .descriptor_count(b.count)
                    .stage_flags(b.stages)
            })
            .collect();
        let layout = unsafe {
            d.create_descriptor_set_layout(&vk::DescriptorSetLayoutCreateInfo::default().bindings(&vk_bindings), None)
        }
        .vk("vkCreateDescriptorSetLayout")?;
        let sizes: Vec<_> =
            bindings.iter().map(|b| vk::DescriptorPoolSize { ty: b.ty, descriptor_count: b.count * count }).collect();
        let pool = unsafe {
            d.create_descriptor_pool(&vk::DescriptorPoolCreateInfo::default().max_sets(count).pool_sizes(&sizes), None)
        }
        .vk("vkCreateDescriptorPool")?;
        let layouts = vec![layout; count as usize];
        let sets = unsafe {
            d.allocate_descriptor_sets(
                &vk::DescriptorSetAllocateInfo::default().descriptor_pool(pool).set_layouts(&layouts),
            )
        }
        .vk("vkAllocateDescriptorSets")?;
        ctx.set_name(layout, name);
        for s in &sets {
            ctx.set_name(*s, name);
        }
        Ok(DescriptorSet { ctx: ctx.clone(), layout, pool, raw: sets[0], sets })
    }

    pub fn write_buffer(&self, binding: u32, ty: vk::DescriptorType, buffer: &Buffer) {
        self.write_buffer_at(0, binding, ty, buffer);
    }

    /// Writes `buffer` (whole) at `binding` of set `set` (of a [`Self::new_many`] set).
    pub fn write_buffer_at(&self, set: usize, binding: u32, ty: vk::DescriptorType, buffer: &Buffer) {
        let info = [vk::DescriptorBufferInfo { buffer: buffer.raw, offset: 0, range: vk::WHOLE_SIZE }];
        let write = vk::WriteDescriptorSet::default()
            .dst_set(self.sets[set])
            .dst_binding(binding)
            .descriptor_type(ty)
            .buffer_info(&info);
        unsafe { self.ctx.device.update_descriptor_sets(&[write], &[]) };
    }

    pub fn write_images(&self, binding: u32, ty: vk::DescriptorType, infos: &[vk::DescriptorImageInfo]) {
        self.write_images_at(0, binding, ty, infos);
    }

    pub fn write_images_at(&self, set: usize, binding: u32, ty: vk::DescriptorType, infos: &[vk::DescriptorImageInfo]) {
        let write = vk::WriteDescriptorSet::default()
            .dst_set(self.sets[set])
            .dst_binding(binding)
            .descriptor_type(ty)
            .image_info(infos);
        unsafe { self.ctx.device.update_descriptor_sets(&[write], &[]) };
    }

    /// A sampled image (combined with `sampler`) in `SHADER_READ_ONLY_OPTIMAL`.
    pub fn write_sampled(&self, binding: u32, view: vk::ImageView, sampler: vk::Sampler) {
        self.write_sampled_at(0, binding, view, sampler);
    }

    pub fn write_sampled_at(&self, set: usize, binding: u32, view: vk::ImageView, sampler: vk::Sampler) {
        self.write_images_at(
            set,
            binding,
            vk::DescriptorType::COMBINED_IMAGE_SAMPLER,
            &[vk::DescriptorImageInfo {
                sampler,
                image_view: view,
                image_layout: vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL,
            }],
        );
    }

    /// A storage image in `GENERAL`.
    pub fn write_storage(&self, binding: u32, view: vk::ImageView) {
        self.write_storage_at(0, binding, view);
    }

    pub fn write_storage_at(&self, set: usize, binding: u32, view: vk::ImageView) {
        self.write_images_at(
            set,
            binding,
            vk::DescriptorType::STORAGE_IMAGE,
            &[vk::DescriptorImageInfo {
                sampler: vk::Sampler::null(),
                image_view: view,
                image_layout: vk::ImageLayout::GENERAL,
            }],
        );
    }
}

impl Drop for DescriptorSet {
    fn drop(&mut self) {
        unsafe {
            self.ctx.device.destroy_descriptor_pool(self.pool, None);
            self.ctx.device.destroy_descriptor_set_layout(self.layout, None);
        }
    }
}
