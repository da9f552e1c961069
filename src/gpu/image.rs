//! Images with their default view, extra per-mip views, and samplers; each owns its handles
//! and memory and carries a debug name.

use std::sync::Arc;

use ash::vk;
use gpu_allocator::vulkan::{Allocation, AllocationCreateDesc, AllocationScheme};
use gpu_allocator::MemoryLocation;

use super::Context;
use crate::error::{Error, Result, VkContext};

#[derive(Clone, Copy, Debug)]
pub struct ImageDesc {
    pub ty: vk::ImageType,
    pub format: vk::Format,
    pub extent: vk::Extent3D,
    pub mip_levels: u32,
    pub usage: vk::ImageUsageFlags,
    /// Array layers (2D images).
    pub layers: u32,
    /// Viewed as an array (a 2D array view even of one layer).
    pub array: bool,
}

impl ImageDesc {
    pub fn d2(format: vk::Format, width: u32, height: u32, usage: vk::ImageUsageFlags) -> Self {
        ImageDesc {
            ty: vk::ImageType::TYPE_2D,
            format,
            extent: vk::Extent3D { width, height, depth: 1 },
            mip_levels: 1,
            usage,
            layers: 1,
            array: false,
        }
    }
    /// A 2D array of `layers` layers, viewed as an array.
    pub fn d2_array(format: vk::Format, width: u32, height: u32, layers: u32, usage: vk::ImageUsageFlags) -> Self {
        ImageDesc { layers, array: true, ..Self::d2(format, width, height, usage) }
    }
    pub fn d3(format: vk::Format, n: u32, usage: vk::ImageUsageFlags) -> Self {
        ImageDesc {
            ty: vk::ImageType::TYPE_3D,
            format,
            extent: vk::Extent3D { width: n, height: n, depth: n },
            mip_levels: 1,
            usage,
            layers: 1,
            array: false,
        }
    }
    /// A 3D image of `extent` texels.
    pub fn d3_extent(format: vk::Format, extent: vk::Extent3D, usage: vk::ImageUsageFlags) -> Self {
        ImageDesc { extent, ..Self::d3(format, 1, usage) }
    }
    pub fn mips(mut self, levels: u32) -> Self {
        self.mip_levels = levels;
        self
    }

    /// Level 0's texels along x, y, z.
    pub fn size(&self) -> [u32; 3] {
        [self.extent.width, self.extent.height, self.extent.depth]
    }

    /// Bytes of texel data over every mip level (what the image holds, before the driver's
    /// alignment and tiling).
    pub fn texel_bytes(&self) -> u64 {
        let e = self.extent;
        (0..self.mip_levels)
            .map(|l| {
                let d = |v: u32| (v >> l).max(1) as u64;
                d(e.width) * d(e.height) * d(e.depth)
            })
            .sum::<u64>()
            * texel_size(self.format) as u64
    }
}

pub fn is_depth(format: vk::Format) -> bool {
    matches!(format, vk::Format::D32_SFLOAT | vk::Format::D16_UNORM | vk::Format::D24_UNORM_S8_UINT)
}

pub fn aspect_of(format: vk::Format) -> vk::ImageAspectFlags {
    if is_depth(format) {
        vk::ImageAspectFlags::DEPTH
    } else {
        vk::ImageAspectFlags::COLOR
    }
}

/// Bytes per texel of the formats this renderer reads back.
pub fn texel_size(format: vk::Format) -> usize {
    match format {
        vk::Format::R32G32B32A32_SFLOAT => 16,
        vk::Format::R16G16B16A16_SFLOAT => 8,
        _ => 4,
    }
}

pub struct ImageView {
    ctx: Arc<Context>,
    pub raw: vk::ImageView,
}

impl ImageView {
    pub(super) fn new(
        ctx: &Arc<Context>,
        image: vk::Image,
        desc: &ImageDesc,
        base_mip: u32,
        mips: u32,
        name: &str,
    ) -> Result<Self> {
        Self::layers(ctx, image, desc, base_mip, mips, 0..desc.layers, name)
    }

    /// A view of `layers` (an array view when the image is viewed as an array and more than one
    /// layer, or every layer, is asked for).
    pub(super) fn layers(
        ctx: &Arc<Context>,
        image: vk::Image,
        desc: &ImageDesc,
        base_mip: u32,
        mips: u32,
        layers: std::ops::Range<u32>,
        name: &str,
    ) -> Result<Self> {
        let whole = layers.start == 0 && layers.end == desc.layers;
        let view_type = match desc.ty {
            vk::ImageType::TYPE_3D => vk::ImageViewType::TYPE_3D,
            _ if desc.array && whole => vk::ImageViewType::TYPE_2D_ARRAY,
            _ => vk::ImageViewType::TYPE_2D,
        };
        let info =
            vk::ImageViewCreateInfo::default().image(image).view_type(view_type).format(desc.format).subresource_range(
                vk::ImageSubresourceRange {
                    aspect_mask: aspect_of(desc.format),
                    base_mip_level: base_mip,
                    level_count: mips,
                    base_array_layer: layers.start,
                    layer_count: layers.end - layers.start,
                },
            );
        let raw = unsafe { ctx.device.create_image_view(&info, None) }.vk("vkCreateImageView")?;
        ctx.set_name(raw, name);
        Ok(ImageView { ctx: ctx.clone(), raw })
    }
}

impl Drop for ImageView {
    fn drop(&mut self) {
        unsafe { self.ctx.device.destroy_image_view(self.raw, None) };
    }
}

pub struct Image {
    pub(super) ctx: Arc<Context>,
    pub raw: vk::Image,
    pub(super) allocation: Option<Allocation>,
    pub desc: ImageDesc,
    /// View of every mip level.
    pub view: ImageView,
    /// One view per mip level (for storage writes and per-level sampling).
    pub mip_views: Vec<ImageView>,
    /// One view per array layer of an array image (attachments render one layer each).
    pub layer_views: Vec<ImageView>,
    pub name: String,
    /// Bytes of device memory bound to the image (the driver's requirement).
    pub bytes: u64,
}

/// Creates the image `desc` describes (one sample, optimal tiling), with `flags`.
pub(super) fn create_raw(ctx: &Context, desc: &ImageDesc, flags: vk::ImageCreateFlags) -> Result<vk::Image> {
    let info = vk::ImageCreateInfo::default()
        .flags(flags)
        .image_type(desc.ty)
        .format(desc.format)
        .extent(desc.extent)
        .mip_levels(desc.mip_levels)
        .array_layers(desc.layers)
        .samples(vk::SampleCountFlags::TYPE_1)
        .tiling(vk::ImageTiling::OPTIMAL)
        .usage(desc.usage)
        .sharing_mode(vk::SharingMode::EXCLUSIVE)
        .initial_layout(vk::ImageLayout::UNDEFINED);
    unsafe { ctx.device.create_image(&info, None) }.vk("vkCreateImage")
}

impl Image {
    pub fn new(ctx: &Arc<Context>, name: &str, desc: ImageDesc) -> Result<Self> {
        let raw = create_raw(ctx, &desc, vk::ImageCreateFlags::empty())?;
        let requirements = unsafe { ctx.device.get_image_memory_requirements(raw) };
        let allocation = ctx
            .allocate(&AllocationCreateDesc {
                name,
                requirements,
                location: MemoryLocation::GpuOnly,
                linear: false,
                allocation_scheme: AllocationScheme::GpuAllocatorManaged,
            })
            .map_err(|source| {
                unsafe { ctx.device.destroy_image(raw, None) };
                Error::Alloc { name: name.to_string(), source }
            })?;
        unsafe { ctx.device.bind_image_memory(raw, allocation.memory(), allocation.offset()) }
            .vk("vkBindImageMemory")?;
        ctx.set_name(raw, name);
        let view = ImageView::new(ctx, raw, &desc, 0, desc.mip_levels, name)?;
        let mip_views = if desc.mip_levels > 1 {
            (0..desc.mip_levels)
                .map(|m| ImageView::new(ctx, raw, &desc, m, 1, &format!("{name} mip {m}")))
                .collect::<Result<_>>()?
        } else {
            Vec::new()
        };
        let layer_views = if desc.array {
            (0..desc.layers)
                .map(|l| ImageView::layers(ctx, raw, &desc, 0, desc.mip_levels, l..l + 1, &format!("{name} layer {l}")))
                .collect::<Result<_>>()?
        } else {
            Vec::new()
        };
        Ok(Image {
            ctx: ctx.clone(),
            raw,
            allocation: Some(allocation),
            desc,
            view,
            mip_views,
            layer_views,
            name: name.to_string(),
            bytes: requirements.size,
        })
    }

    /// The view of one mip level (the default view when there is only one).
    pub fn mip_view(&self, level: u32) -> vk::ImageView {
        if self.mip_views.is_empty() {
            self.view.raw
        } else {
            self.mip_views[level as usize].raw
        }
    }

    pub fn extent_at(&self, level: u32) -> vk::Extent3D {
        let e = self.desc.extent;
        vk::Extent3D {
            width: (e.width >> level).max(1),
            height: (e.height >> level).max(1),
            depth: (e.depth >> level).max(1),
        }
    }

    pub fn range(&self) -> vk::ImageSubresourceRange {
        vk::ImageSubresourceRange {
            aspect_mask: aspect_of(self.desc.format),
            base_mip_level: 0,
            level_count: self.desc.mip_levels,
            base_array_layer: 0,
            layer_count: self.desc.layers,
        }
    }
}

impl Drop for Image {
    fn drop(&mut self) {
        self.mip_views.clear();
        self.layer_views.clear();
        // The image first: a resident image's memory stays bound until it is destroyed.
        unsafe { self.ctx.device.destroy_image(self.raw, None) };
        if let Some(a) = self.allocation.take() {
            self.ctx.free(a);
        }
    }
}

pub struct Sampler {
    ctx: Arc<Context>,
    pub raw: vk::Sampler,
}

impl Sampler {
    pub fn new(ctx: &Arc<Context>, name: &str, info: &vk::SamplerCreateInfo) -> Result<Self> {
        let raw = unsafe { ctx.device.create_sampler(info, None) }.vk("vkCreateSampler")?;
        ctx.set_name(raw, name);
        Ok(Sampler { ctx: ctx.clone(), raw })
    }

    /// Trilinear, repeating (material textures).
    pub fn linear_repeat(ctx: &Arc<Context>, name: &str) -> Result<Self> {
        let info = vk::SamplerCreateInfo::default()
            .mag_filter(vk::Filter::LINEAR)
            .min_filter(vk::Filter::LINEAR)
            .mipmap_mode(vk::SamplerMipmapMode::LINEAR)
            .address_mode_u(vk::SamplerAddressMode::REPEAT)
            .address_mode_v(vk::SamplerAddressMode::REPEAT)
            .address_mode_w(vk::SamplerAddressMode::REPEAT)
            .max_lod(vk::LOD_CLAMP_NONE);
        Self::new(ctx, name, &info)
    }

    /// Trilinear, clamped to a transparent border (voxel volumes).
    pub fn linear_border(ctx: &Arc<Context>, name: &str) -> Result<Self> {
        let info = vk::SamplerCreateInfo::default()
            .mag_filter(vk::Filter::LINEAR)
            .min_filter(vk::Filter::LINEAR)
            .mipmap_mode(vk::SamplerMipmapMode::LINEAR)
            .address_mode_u(vk::SamplerAddressMode::CLAMP_TO_BORDER)
            .address_mode_v(vk::SamplerAddressMode::CLAMP_TO_BORDER)
            .address_mode_w(vk::SamplerAddressMode::CLAMP_TO_BORDER)
            .border_color(vk::BorderColor::FLOAT_TRANSPARENT_BLACK)
            .max_lod(vk::LOD_CLAMP_NONE);
        Self::new(ctx, name, &info)
    }

    /// Depth comparison with bilinear PCF, clamped to "lit" outside the map.
    pub fn shadow(ctx: &Arc<Context>, name: &str) -> Result<Self> {
        let info = vk::SamplerCreateInfo::default()
            .mag_filter(vk::Filter::LINEAR)
            .min_filter(vk::Filter::LINEAR)
            .address_mode_u(vk::SamplerAddressMode::CLAMP_TO_BORDER)
            .address_mode_v(vk::SamplerAddressMode::CLAMP_TO_BORDER)
            .address_mode_w(vk::SamplerAddressMode::CLAMP_TO_BORDER)
            .border_color(vk::BorderColor::FLOAT_OPAQUE_WHITE)
            .compare_enable(true)
            .compare_op(vk::CompareOp::LESS_OR_EQUAL);
        Self::new(ctx, name, &info)
    }
}

impl Drop for Sampler {
    fn drop(&mut self) {
        unsafe { self.ctx.device.destroy_sampler(self.raw, None) };
    }
}
