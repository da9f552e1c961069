//! Sparse residency (Vulkan spec, "Sparse Resources"; the hardware path of the GRAPP 2020
//! sparse-texture paper): a single-level 3D image whose memory is bound block by block, only
//! in the blocks the caller names. With `residencyNonResidentStrict` the rest reads as zero
//! and drops writes, so shaders address the image exactly as its dense twin. Without it (Mesa
//! 25's lavapipe), reads of unbound blocks are undefined, so every other block is bound to one
//! shared block (`sparseResidencyAliased`), which the caller keeps zero by clearing the image
//! and writing only inside its own blocks.

use std::sync::Arc;

use ash::vk;
use gpu_allocator::vulkan::{AllocationCreateDesc, AllocationScheme};
use gpu_allocator::MemoryLocation;

use super::image::{aspect_of, Image, ImageDesc, ImageView};
use super::Context;
use crate::error::{Error, Result};

fn flags(shared: bool) -> vk::ImageCreateFlags {
    let f = vk::ImageCreateFlags::SPARSE_BINDING | vk::ImageCreateFlags::SPARSE_RESIDENCY;
    if shared {
        f | vk::ImageCreateFlags::SPARSE_ALIASED
    } else {
        f
    }
}

/// Whether unbound blocks read as zero on this device; if not, resident images bind them to a
/// shared block instead (see the module's note).
pub fn unbound_reads_zero(ctx: &Context) -> bool {
    ctx.info.features.has(super::Feature::ResidencyNonResidentStrict)
}

/// The texels of one sparse block of an image like `desc` (`imageGranularity`), or an error
/// naming the format when the device has no sparse residency for it.
pub fn block_shape(ctx: &Context, desc: &ImageDesc) -> Result<[u32; 3]> {
    let props = unsafe {
        ctx.instance.get_physical_device_sparse_image_format_properties(
            ctx.physical,
            desc.format,
            desc.ty,
            vk::SampleCountFlags::TYPE_1,
            desc.usage,
            vk::ImageTiling::OPTIMAL,
        )
    };
    match props.iter().find(|p| p.aspect_mask.contains(aspect_of(desc.format))) {
        Some(p) => {
            let g = p.image_granularity;
            Ok([g.width, g.height, g.depth])
        }
        None => Err(Error::MissingFeature {
            device: ctx.info.name.clone(),
            feature: match desc.format {
                vk::Format::R32_UINT => "sparse residency for R32_UINT 3D images",
                vk::Format::R16G16B16A16_SFLOAT => "sparse residency for R16G16B16A16_SFLOAT 3D images",
                _ => "sparse residency for this 3D image format",
            },
            needed_by: "resident voxel storage (--storage resident)",
        }),
    }
}

impl Image {
    /// A single-level 3D image with memory of its own only in the blocks `blocks` lists (block
    /// coordinates: texel origin over [`block_shape`], sorted, each once), and in its mip tail
    /// and metadata where the device has them. Elsewhere it reads zero: unbound where the device
    /// is strict, else bound to one shared block that the caller keeps zero. `bytes` is the
    /// memory it holds.
    pub fn resident(ctx: &Arc<Context>, name: &str, desc: ImageDesc, blocks: &[[u32; 3]]) -> Result<Self> {
        assert_eq!(desc.mip_levels, 1, "resident images have one level");
        let shared = !unbound_reads_zero(ctx);
        let raw = super::image::create_raw(ctx, &desc, flags(shared))?;
        let mut image = Image {
            ctx: ctx.clone(),
            raw,
            allocation: None,
            desc,
            view: ImageView::new(ctx, raw, &desc, 0, 1, name)?,
            mip_views: Vec::new(),
            layer_views: Vec::new(),
            name: name.to_string(),
            bytes: 0,
        };
        ctx.set_name(raw, name);
        let requirements = unsafe { ctx.device.get_image_memory_requirements(raw) };
        let sparse = unsafe { ctx.device.get_image_sparse_memory_requirements(raw) };
        let aspect = aspect_of(desc.format);
        let color = sparse.iter().find(|r| r.format_properties.aspect_mask.contains(aspect)).ok_or_else(|| {
            Error::MissingFeature {
                device: ctx.info.name.clone(),
                feature: "sparse memory requirements for the image's colour aspect",
                needed_by: "resident voxel storage (--storage resident)",
            }
        })?;
        let block = requirements.alignment;
        let g = color.format_properties.image_granularity;
        // Level 0 in blocks unless it lies in the mip tail (an image smaller than a block).
        let in_tail = color.image_mip_tail_first_lod == 0;
        let tails: Vec<(u64, u64, vk::SparseMemoryBindFlags)> = sparse
            .iter()
            .filter_map(|r| {
                let metadata = r.format_properties.aspect_mask.contains(vk::ImageAspectFlags::METADATA);
                (metadata || (in_tail && std::ptr::eq(r, color))).then(|| {
                    let flag = if metadata { vk::SparseMemoryBindFlags::METADATA } else { Default::default() };
                    (r.image_mip_tail_offset, r.image_mip_tail_size, flag)
                })
            })
            .collect();
        let blocks = if in_tail { &[][..] } else { blocks };
        let e = desc.extent;
        let grid = [e.width.div_ceil(g.width), e.height.div_ceil(g.height), e.depth.div_ceil(g.depth)];
        // Every block: its own memory (listed), the shared block, or none.
        let all: Vec<([u32; 3], Option<usize>)> = if shared && !in_tail {
            let mut own = blocks.iter().enumerate().peekable();
            let mut v = Vec::new();
            for z in 0..grid[2] {
                for y in 0..grid[1] {
                    for x in 0..grid[0] {
                        let b = [x, y, z];
                        let i = own.next_if(|(_, o)| **o == b).map(|(i, _)| i);
                        v.push((b, i));
                    }
                }
            }
            assert!(own.next().is_none(), "resident blocks are sorted z, y, x and inside the image");
            v
        } else {
            blocks.iter().enumerate().map(|(i, &b)| (b, Some(i))).collect()
        };
        let zero_block = blocks.len() as u64;
        let own_blocks = blocks.len() as u64 + all.iter().any(|b| b.1.is_none()) as u64;
        let tail_bytes: u64 = tails.iter().map(|t| t.1.next_multiple_of(block)).sum();
        let size = own_blocks * block + tail_bytes;
        if size == 0 {
            return Ok(image);
        }
        let allocation = ctx
            .allocate(&AllocationCreateDesc {
                name,
                requirements: vk::MemoryRequirements { size, ..requirements },
                location: MemoryLocation::GpuOnly,
                linear: false,
                allocation_scheme: AllocationScheme::GpuAllocatorManaged,
            })
            .map_err(|source| Error::Alloc { name: name.to_string(), source })?;
        let (memory, base) = (unsafe { allocation.memory() }, allocation.offset());
        image.allocation = Some(allocation);
        let image_binds: Vec<vk::SparseImageMemoryBind> = all
            .iter()
            .map(|&(b, i)| {
                let offset = vk::Offset3D {
                    x: (b[0] * g.width) as i32,
                    y: (b[1] * g.height) as i32,
                    z: (b[2] * g.depth) as i32,
                };
                // A block at the image's edge is bound up to the edge.
                let extent = vk::Extent3D {
                    width: g.width.min(e.width - offset.x as u32),
                    height: g.height.min(e.height - offset.y as u32),
                    depth: g.depth.min(e.depth - offset.z as u32),
                };
                vk::SparseImageMemoryBind::default()
                    .subresource(vk::ImageSubresource { aspect_mask: aspect, mip_level: 0, array_layer: 0 })
                    .offset(offset)
                    .extent(extent)
                    .memory(memory)
                    .memory_offset(base + i.map_or(zero_block, |i| i as u64) * block)
            })
            .collect();
        let mut at = base + own_blocks * block;
        let opaque_binds: Vec<vk::SparseMemoryBind> = tails
            .iter()
            .map(|&(offset, bytes, flags)| {
                let bind = vk::SparseMemoryBind::default()
                    .resource_offset(offset)
                    .size(bytes)
                    .memory(memory)
                    .memory_offset(at)
                    .flags(flags);
                at += bytes.next_multiple_of(block);
                bind
            })
            .collect();
        let image_info = [vk::SparseImageMemoryBindInfo::default().image(raw).binds(&image_binds)];
        let opaque_info = [vk::SparseImageOpaqueMemoryBindInfo::default().image(raw).binds(&opaque_binds)];
        let mut bind = vk::BindSparseInfo::default();
        if !image_binds.is_empty() {
            bind = bind.image_binds(&image_info);
        }
        if !opaque_binds.is_empty() {
            bind = bind.image_opaque_binds(&opaque_info);
        }
        ctx.bind_sparse_and_wait(name, &bind)?;
        image.bytes = size;
        Ok(image)
    }
}
