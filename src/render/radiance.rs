//! The radiance volume (Freed 2018 §4.3-4.4): an RGBA16F 3D texture with a full mip chain
//! (premultiplied radiance and opacity), plus the level-0 target that injection writes before
//! the temporal blend. Both stay in GENERAL layout: written as storage, sampled by the cones.

use std::sync::Arc;

use ash::vk;

use crate::error::{Error, Result};
use crate::gpu::{self, scope, Context, Image, ImageDesc, Sampler};

pub const RADIANCE_FORMAT: vk::Format = vk::Format::R16G16B16A16_SFLOAT;

pub struct RadianceVolume {
    pub injected: Image,
    pub radiance: Image,
    /// Directional chains for anisotropic filtering (+X, -X, +Y, -Y, +Z, -Z): level l of the
    /// volume is their mip l - 1.
    pub aniso: Vec<Image>,
    /// Per level-0 voxel, the side its injected light leaves from: the voxel's normal turned
    /// towards the light (packed like the voxel normals, high byte 1), or 0 where the voxel
    /// emits to every side. The directional chains use it so that a lit face is dark when seen
    /// from behind.
    pub lit_side: Image,
    /// A copy of the previous frame's level 0, which the temporal blend reprojects (only when
    /// temporal filtering is on).
    pub history: Image,
    pub sampler: Sampler,
    pub levels: u32,
}

impl RadianceVolume {
    pub fn new(ctx: &Arc<Context>, resolution: u32) -> Result<Self> {
        let props = unsafe { ctx.instance.get_physical_device_format_properties(ctx.physical, RADIANCE_FORMAT) };
        let need = vk::FormatFeatureFlags::STORAGE_IMAGE | vk::FormatFeatureFlags::SAMPLED_IMAGE_FILTER_LINEAR;
        if !props.optimal_tiling_features.contains(need) {
            return Err(Error::MissingFeature {
                device: ctx.info.name.clone(),
                feature: "R16G16B16A16_SFLOAT storage images with linear filtering",
                needed_by: "the radiance volume",
            });
        }
        let levels = 32 - resolution.leading_zeros();
        let storage =
            vk::ImageUsageFlags::STORAGE | vk::ImageUsageFlags::TRANSFER_SRC | vk::ImageUsageFlags::TRANSFER_DST;
        let injected = Image::new(ctx, "injected radiance", ImageDesc::d3(RADIANCE_FORMAT, resolution, storage))?;
        let radiance = Image::new(
            ctx,
            "radiance volume",
            ImageDesc::d3(RADIANCE_FORMAT, resolution, storage | vk::ImageUsageFlags::SAMPLED).mips(levels),
        )?;
        let aniso = ["+x", "-x", "+y", "-y", "+z", "-z"]
            .iter()
            .map(|d| {
                let desc =
                    ImageDesc::d3(RADIANCE_FORMAT, (resolution / 2).max(1), storage | vk::ImageUsageFlags::SAMPLED);
                Image::new(ctx, &format!("radiance {d}"), desc.mips((levels - 1).max(1)))
            })
            .collect::<Result<Vec<_>>>()?;
        let lit_side =
            Image::new(ctx, "lit side", ImageDesc::d3(crate::voxel::volume::VOXEL_FORMAT, resolution, storage))?;
        let history = Image::new(
            ctx,
            "radiance history",
            ImageDesc::d3(RADIANCE_FORMAT, resolution, storage | vk::ImageUsageFlags::SAMPLED),
        )?;
        // Start all in GENERAL and zero, so the first temporal blend reads defined history.
        ctx.submit_and_wait("clear radiance", |cmd| {
            for img in [&injected, &radiance, &lit_side, &history].into_iter().chain(&aniso) {
                gpu::clear_to_general(ctx, cmd, img, scope::NONE);
            }
        })?;
        Ok(RadianceVolume {
            injected,
            radiance,
            aniso,
            lit_side,
            history,
            sampler: Sampler::linear_border(ctx, "radiance sampler")?,
            levels,
        })
    }

    /// Descriptor info for sampling the whole mip chain (GENERAL layout).
    pub fn sampled_info(&self) -> vk::DescriptorImageInfo {
        vk::DescriptorImageInfo {
            sampler: self.sampler.raw,
            image_view: self.radiance.view.raw,
            image_layout: vk::ImageLayout::GENERAL,
        }
    }

    /// Descriptor infos for the six directional chains.
    pub fn aniso_infos(&self) -> Vec<vk::DescriptorImageInfo> {
        self.aniso
            .iter()
            .map(|a| vk::DescriptorImageInfo {
                sampler: self.sampler.raw,
                image_view: a.view.raw,
                image_layout: vk::ImageLayout::GENERAL,
            })
            .collect()
    }

    /// Writes the isotropic volume at `binding` and the six directional ones after it.
    pub fn write_to(&self, set: &crate::gpu::DescriptorSet, binding: u32) {
        let sampled = vk::DescriptorType::COMBINED_IMAGE_SAMPLER;
        set.write_images(binding, sampled, &[self.sampled_info()]);
        for (i, info) in self.aniso_infos().into_iter().enumerate() {
            set.write_images(binding + 1 + i as u32, sampled, &[info]);
        }
    }
}
