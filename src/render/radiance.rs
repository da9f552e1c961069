//! The radiance volume (Freed 2018 §4.3-4.4): an RGBA16F 3D texture with a full mip chain
//! (premultiplied radiance and opacity), plus the level-0 target that injection writes before
//! the temporal blend. Both stay in GENERAL layout: written as storage, sampled by the cones.

use std::sync::Arc;

use ash::vk;

use crate::error::{Error, Result};
use crate::gpu::{self, scope, Context, Image, ImageDesc, Sampler};
use crate::voxel::volume::extent_of;
use crate::voxel::VoxelGrid;

pub const RADIANCE_FORMAT: vk::Format = vk::Format::R16G16B16A16_SFLOAT;

pub struct RadianceVolume {
    pub injected: Image,
    pub radiance: Image,
    /// Directional chains for anisotropic filtering (+X, -X, +Y, -Y, +Z, -Z), stacked along y in
    /// one atlas with an empty block between neighbours (`config::ANISO_BLOCKS`): level l of the
    /// volume is their mip l - 1.
    pub aniso: Image,
    /// Per level-0 voxel, the side its injected light leaves from: the voxel's normal turned
    /// towards the light (packed like the voxel normals, high byte 1), or 0 where the voxel
    /// emits to every side. The directional chains use it so that a lit face is dark when seen
    /// from behind.
    pub lit_side: Image,
    /// A copy of the previous frame's level 0, which the temporal blend reprojects (one texel
    /// when temporal filtering is off).
    pub history: Image,
    /// Each extra bounce's level 0 before it is blended in (only with more than one bounce).
    pub bounced: Option<Image>,
    /// Where each texel's light leaves to: xyz the luminance-weighted sum of lit-side normals,
    /// w the luminance (mip chain as the radiance's; `common/cone.glsl`, CONE_FLAG_FACING).
    pub moment: Image,
    pub sampler: Sampler,
    pub levels: u32,
}

/// The radiance volumes' images over a grid, before allocation (the memory report reads them).
#[derive(Clone, Copy, Debug)]
pub struct RadianceDescs {
    pub injected: ImageDesc,
    pub radiance: ImageDesc,
    pub aniso: ImageDesc,
    pub lit_side: ImageDesc,
    pub history: ImageDesc,
    pub moment: ImageDesc,
    pub bounced: Option<ImageDesc>,
}

impl RadianceDescs {
    /// Over `grid`, the per-voxel targets (injected light, lit side, bounce target) at
    /// `stored`: the grid's extent, or the brick pool's (voxel::bricks); the history at level
    /// 0's extent only with `temporal` filtering (else one texel, bound but never read).
    pub fn new(grid: &VoxelGrid, bounces: bool, stored: vk::Extent3D, temporal: bool) -> Self {
        let levels = grid.mip_levels();
        let extent = extent_of(grid.dims);
        let storage =
            vk::ImageUsageFlags::STORAGE | vk::ImageUsageFlags::TRANSFER_SRC | vk::ImageUsageFlags::TRANSFER_DST;
        let sampled = storage | vk::ImageUsageFlags::SAMPLED;
        let d3 = |usage| ImageDesc::d3_extent(RADIANCE_FORMAT, extent, usage);
        let chain = (grid.dims / 2).max(glam::UVec3::ONE);
        let atlas = vk::Extent3D { width: chain.x, height: chain.y * crate::config::ANISO_BLOCKS, depth: chain.z };
        let pooled = |format, usage| ImageDesc::d3_extent(format, stored, usage);
        RadianceDescs {
            injected: pooled(RADIANCE_FORMAT, storage),
            radiance: d3(sampled).mips(levels),
            aniso: ImageDesc::d3_extent(RADIANCE_FORMAT, atlas, sampled).mips((levels - 1).max(1)),
            lit_side: pooled(crate::voxel::volume::VOXEL_FORMAT, storage),
            history: if temporal {
                d3(sampled)
            } else {
                ImageDesc::d3_extent(RADIANCE_FORMAT, vk::Extent3D { width: 1, height: 1, depth: 1 }, sampled)
            },
            moment: d3(sampled).mips(levels),
            bounced: bounces.then(|| pooled(RADIANCE_FORMAT, storage)),
        }
    }

    /// Every image with its name, in the report's order.
    pub fn named(&self) -> Vec<(&'static str, ImageDesc)> {
        let mut v = vec![
            ("injected radiance", self.injected),
            ("radiance volume", self.radiance),
            ("radiance directional chains", self.aniso),
            ("lit side", self.lit_side),
            ("radiance history", self.history),
            ("radiance moment", self.moment),
        ];
        v.extend(self.bounced.map(|b| ("bounced radiance", b)));
        v
    }
}

impl RadianceVolume {
    /// Volumes over `grid`'s dims, the per-voxel targets in `voxels`' layout; `bounces`: also
    /// the target of the voxel-space bounce pass; `temporal`: a full-size history.
    pub fn new(ctx: &Arc<Context>, voxels: &crate::voxel::VoxelVolume, bounces: bool, temporal: bool) -> Result<Self> {
        let grid = &voxels.grid;
        let props = unsafe { ctx.instance.get_physical_device_format_properties(ctx.physical, RADIANCE_FORMAT) };
        let need = vk::FormatFeatureFlags::STORAGE_IMAGE | vk::FormatFeatureFlags::SAMPLED_IMAGE_FILTER_LINEAR;
        if !props.optimal_tiling_features.contains(need) {
            return Err(Error::MissingFeature {
                device: ctx.info.name.clone(),
                feature: "R16G16B16A16_SFLOAT storage images with linear filtering",
                needed_by: "the radiance volume",
            });
        }
        let d = RadianceDescs::new(grid, bounces, voxels.bricks.extent(grid), temporal);
        let levels = d.radiance.mip_levels;
        let mut images = d
            .named()
            .into_iter()
            .map(|(name, desc)| Image::new(ctx, name, desc))
            .collect::<Result<Vec<_>>>()?
            .into_iter();
        let mut next = || images.next().expect("one image per description");
        let (injected, radiance, aniso, lit_side, history, moment) = (next(), next(), next(), next(), next(), next());
        let bounced = bounces.then(next);
        // Start all in GENERAL and zero, so the first temporal blend reads defined history.
        ctx.submit_and_wait("clear radiance", |cmd| {
            for img in [&injected, &radiance, &lit_side, &history, &moment, &aniso].into_iter().chain(&bounced) {
                gpu::clear_to_general(ctx, cmd, img, scope::NONE);
            }
        })?;
        Ok(RadianceVolume {
            injected,
            radiance,
            aniso,
            lit_side,
            history,
            bounced,
            moment,
            sampler: Sampler::linear_border(ctx, "radiance sampler")?,
            levels,
        })
    }

    /// The volumes, in [`RadianceDescs::named`]'s order.
    pub fn images(&self) -> Vec<&Image> {
        let mut v = vec![&self.injected, &self.radiance, &self.aniso, &self.lit_side, &self.history, &self.moment];
        v.extend(&self.bounced);
        v
    }

    /// Whether the history holds level 0 (temporal filtering can run).
    pub fn has_history(&self) -> bool {
        self.history.desc.extent == self.radiance.desc.extent
    }

    /// Descriptor info for sampling the whole mip chain (GENERAL layout).
    pub fn sampled_info(&self) -> vk::DescriptorImageInfo {
        vk::DescriptorImageInfo {
            sampler: self.sampler.raw,
            image_view: self.radiance.view.raw,
            image_layout: vk::ImageLayout::GENERAL,
        }
    }

    /// Descriptor info for sampling the directional chains' atlas.
    pub fn aniso_info(&self) -> vk::DescriptorImageInfo {
        vk::DescriptorImageInfo { image_view: self.aniso.view.raw, ..self.sampled_info() }
    }

    /// Descriptor info for sampling the moment's mip chain.
    pub fn moment_info(&self) -> vk::DescriptorImageInfo {
        vk::DescriptorImageInfo { image_view: self.moment.view.raw, ..self.sampled_info() }
    }

    /// Writes the isotropic volume at `binding`, the directional chains' atlas after it and then
    /// the moment.
    pub fn write_to(&self, set: &crate::gpu::DescriptorSet, binding: u32) {
        let sampled = vk::DescriptorType::COMBINED_IMAGE_SAMPLER;
        set.write_images(binding, sampled, &[self.sampled_info()]);
        set.write_images(binding + 1, sampled, &[self.aniso_info()]);
        set.write_images(binding + 2, sampled, &[self.moment_info()]);
    }

    /// Where directional chain `d` starts in the atlas at chain mip `mip` (texels along y).
    pub fn chain_offset(&self, d: u32, mip: u32) -> u32 {
        2 * d * self.aniso.extent_at(mip).height / crate::config::ANISO_BLOCKS
    }
}
