//! The radiance volume (Freed 2018 §4.3-4.4): RGBA16F premultiplied radiance and opacity. Its
//! level 0 (and the injected light that the temporal blend reads) is stored as the per-voxel
//! textures are, in the brick pool with sparse storage (voxel::bricks; the cones filter it
//! through the page table, common/level0.glsl); the levels above it are dense mip chains, the
//! isotropic one and the six directional ones. All stay in GENERAL layout: written as storage,
//! sampled by the cones.

use std::sync::Arc;

use ash::vk;

use crate::error::{Error, Result};
use crate::gpu::{self, scope, Context, Image, ImageDesc, Sampler};
use crate::voxel::volume::extent_of;
use crate::voxel::VoxelGrid;

pub const RADIANCE_FORMAT: vk::Format = vk::Format::R16G16B16A16_SFLOAT;

pub struct RadianceVolume {
    pub injected: Image,
    /// Level 0 after the temporal blend and the bounces (none where it is the injected light:
    /// see [`RadianceVolume::level0`]).
    pub radiance: Option<Image>,
    /// The isotropic chain above level 0 (its mip m is level m + 1; one texel unless
    /// `chains.isotropic`).
    pub chain: Image,
    /// Directional chains for anisotropic filtering (+X, -X, +Y, -Y, +Z, -Z), stacked in one
    /// atlas with empty separators between neighbours (`atlas`): level l of the volume is their
    /// mip l - 1.
    pub aniso: Image,
    pub atlas: AtlasLayout,
    /// Which chains above level 0 exist.
    pub chains: Chains,
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
    /// w the luminance (`common/cone.glsl`, CONE_FLAG_FACING): the radiance's chain from level
    /// 1, its mip m level m + 1 (gi/moment.comp).
    pub moment: Image,
    pub sampler: Sampler,
    /// The grid's mip levels (the isotropic chain has them all only with `chains.isotropic`).
    pub levels: u32,
}

/// Which of the sampled chains above level 0 a renderer allocates: those something reads. The
/// directional model's cones read the isotropic volume's level 0 only, and the isotropic model's
/// cones no directional chain; unread, they would hold 4.6 and 38.9 MiB on Sponza's 256 grid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Chains {
    /// The isotropic chain's levels above 0: the isotropic model's cones and the radiance view
    /// read them.
    pub isotropic: bool,
    /// The six directional chains: the directional model's cones.
    pub directional: bool,
}

impl Chains {
    pub const ALL: Chains = Chains { isotropic: true, directional: true };

    /// The chains that `filter`'s cones read, and the isotropic one too for a radiance view.
    pub fn read_by(filter: crate::scene::file::Filter, radiance_view: bool) -> Self {
        let directional = filter == crate::scene::file::Filter::Aniso;
        Chains { isotropic: !directional || radiance_view, directional }
    }
}

/// The radiance volumes' images over a grid, before allocation (the memory report reads them).
#[derive(Clone, Copy, Debug)]
pub struct RadianceDescs {
    pub injected: ImageDesc,
    /// Level 0 after the temporal blend and the bounces, stored as the per-voxel targets; none
    /// where it would equal the injected light (one bounce, no temporal filter).
    pub radiance: Option<ImageDesc>,
    /// The isotropic chain above level 0: its mip m is level m + 1.
    pub chain: ImageDesc,
    pub aniso: ImageDesc,
    pub lit_side: ImageDesc,
    pub history: ImageDesc,
    pub moment: ImageDesc,
    pub bounced: Option<ImageDesc>,
}

impl RadianceDescs {
    /// Over `grid`, the per-voxel targets (injected light, level 0, lit side, bounce target,
    /// history) at `stored`: the grid's extent, or the brick pool's (voxel::bricks); the
    /// history only with `temporal` filtering, and of the sampled chains above level 0 only
    /// `chains` (else one texel: bound but never read).
    pub fn new(grid: &VoxelGrid, bounces: bool, stored: vk::Extent3D, temporal: bool, chains: Chains) -> Self {
        let levels = grid.mip_levels();
        let storage =
            vk::ImageUsageFlags::STORAGE | vk::ImageUsageFlags::TRANSFER_SRC | vk::ImageUsageFlags::TRANSFER_DST;
        let sampled = storage | vk::ImageUsageFlags::SAMPLED;
        let atlas = AtlasLayout::new(grid).extent();
        let chain = (grid.dims / 2).max(glam::UVec3::ONE);
        let texel = vk::Extent3D { width: 1, height: 1, depth: 1 };
        let pooled = |format, usage| ImageDesc::d3_extent(format, stored, usage);
        RadianceDescs {
            injected: pooled(RADIANCE_FORMAT, sampled),
            radiance: (temporal || bounces).then(|| pooled(RADIANCE_FORMAT, sampled)),
            chain: if chains.isotropic {
                ImageDesc::d3_extent(RADIANCE_FORMAT, extent_of(chain), sampled).mips((levels - 1).max(1))
            } else {
                ImageDesc::d3_extent(RADIANCE_FORMAT, texel, sampled)
            },
            aniso: if chains.directional {
                ImageDesc::d3_extent(RADIANCE_FORMAT, atlas, sampled).mips((levels - 1).max(1))
            } else {
                ImageDesc::d3_extent(RADIANCE_FORMAT, texel, sampled)
            },
            lit_side: pooled(crate::voxel::volume::VOXEL_FORMAT, storage),
            history: if temporal {
                pooled(RADIANCE_FORMAT, sampled)
            } else {
                ImageDesc::d3_extent(RADIANCE_FORMAT, texel, sampled)
            },
            moment: ImageDesc::d3_extent(RADIANCE_FORMAT, extent_of(chain), sampled).mips((levels - 1).max(1)),
            bounced: bounces.then(|| pooled(RADIANCE_FORMAT, storage)),
        }
    }

    /// Every image with its name and whether it is a per-voxel target (stored as the voxel
    /// textures are), in the report's order.
    pub fn named(&self) -> Vec<(&'static str, ImageDesc, bool)> {
        let mut v = vec![("injected radiance", self.injected, true)];
        v.extend(self.radiance.map(|r| ("radiance level 0", r, true)));
        v.extend([
            ("radiance chain", self.chain, false),
            ("radiance directional chains", self.aniso, false),
            ("lit side", self.lit_side, true),
            // One texel, never read, without temporal filtering.
            ("radiance history", self.history, self.history.extent == self.injected.extent),
            ("radiance moment", self.moment, false),
        ]);
        v.extend(self.bounced.map(|b| ("bounced radiance", b, true)));
        v
    }
}

impl RadianceVolume {
    /// Volumes over `grid`'s dims, the per-voxel targets in `voxels`' layout; `bounces`: also
    /// the target of the voxel-space bounce pass; `temporal`: a full-size history.
    pub fn new(
        ctx: &Arc<Context>,
        voxels: &crate::voxel::VoxelVolume,
        bounces: bool,
        temporal: bool,
        chains: Chains,
    ) -> Result<Self> {
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
        let d = RadianceDescs::new(grid, bounces, voxels.bricks.extent(grid), temporal, chains);
        let levels = grid.mip_levels();
        let mut images = d
            .named()
            .into_iter()
            .map(
                |(name, desc, per_voxel)| {
                    if per_voxel {
                        voxels.bricks.image(name, desc)
                    } else {
                        Image::new(ctx, name, desc)
                    }
                },
            )
            .collect::<Result<Vec<_>>>()?
            .into_iter();
        let mut next = || images.next().expect("one image per description");
        let injected = next();
        let radiance = d.radiance.map(|_| next());
        let (chain, aniso, lit_side, history, moment) = (next(), next(), next(), next(), next());
        let bounced = bounces.then(next);
        let volume = RadianceVolume {
            injected,
            radiance,
            chain,
            aniso,
            atlas: AtlasLayout::new(grid),
            chains,
            lit_side,
            history,
            bounced,
            moment,
            sampler: Sampler::linear_border(ctx, "radiance sampler")?,
            levels,
        };
        // Start all in GENERAL and zero, so the first temporal blend reads defined history.
        ctx.submit_and_wait("clear radiance", |cmd| {
            for img in volume.images() {
                gpu::clear_to_general(ctx, cmd, img, scope::NONE);
            }
        })?;
        Ok(volume)
    }

    /// The volumes, in [`RadianceDescs::named`]'s order.
    pub fn images(&self) -> Vec<&Image> {
        let mut v = vec![&self.injected];
        v.extend(&self.radiance);
        v.extend([&self.chain, &self.aniso, &self.lit_side, &self.history, &self.moment]);
        v.extend(&self.bounced);
        v
    }

    /// Level 0 as the cones read it: after the blend and the bounces, or the injected light
    /// itself where nothing is blended in.
    pub fn level0(&self) -> &Image {
        self.radiance.as_ref().unwrap_or(&self.injected)
    }

    /// Whether the history holds level 0 (temporal filtering can run).
    pub fn has_history(&self) -> bool {
        self.radiance.is_some() && self.history.desc.extent == self.injected.desc.extent
    }

    /// Descriptor info for sampling level 0 (GENERAL layout; stored as the per-voxel targets).
    pub fn sampled_info(&self) -> vk::DescriptorImageInfo {
        vk::DescriptorImageInfo {
            sampler: self.sampler.raw,
            image_view: self.level0().view.raw,
            image_layout: vk::ImageLayout::GENERAL,
        }
    }

    /// Descriptor info for sampling the isotropic chain above level 0.
    pub fn chain_info(&self) -> vk::DescriptorImageInfo {
        vk::DescriptorImageInfo { image_view: self.chain.view.raw, ..self.sampled_info() }
    }

    /// Descriptor info for sampling the directional chains' atlas.
    pub fn aniso_info(&self) -> vk::DescriptorImageInfo {
        vk::DescriptorImageInfo { image_view: self.aniso.view.raw, ..self.sampled_info() }
    }

    /// Descriptor info for sampling the moment's mip chain.
    pub fn moment_info(&self) -> vk::DescriptorImageInfo {
        vk::DescriptorImageInfo { image_view: self.moment.view.raw, ..self.sampled_info() }
    }

    /// Writes level 0 at `binding`, the directional chains' atlas after it, then the moment and
    /// the isotropic chain above level 0 (common/level0.glsl reads level 0 through the page
    /// table, which the includer binds).
    pub fn write_to(&self, set: &crate::gpu::DescriptorSet, binding: u32) {
        let sampled = vk::DescriptorType::COMBINED_IMAGE_SAMPLER;
        set.write_images(binding, sampled, &[self.sampled_info()]);
        set.write_images(binding + 1, sampled, &[self.aniso_info()]);
        set.write_images(binding + 2, sampled, &[self.moment_info()]);
        set.write_images(binding + 3, sampled, &[self.chain_info()]);
    }
}

/// Where the six directional chains lie in their atlas. They are stacked along the chains'
/// longest axis, each followed by an empty separator, so that trilinear filtering at every mip
/// meets zeros at a chain's edge, as at the volume's border. A separator one texel thick at the
/// coarsest mip suffices, since a sample's filter reaches at most one texel past its chain (the
/// cones stop half a texel outside the volume): 2^(mips - 1) texels at mip 0. Stacking along the
/// longest axis keeps those separators short against the chains: Sponza's 256 × 128 × 128 grid
/// has chains of 128 × 64 × 64 and seven mips, so stacked along x its separators are half a
/// chain long; along y they would be a whole chain.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AtlasLayout {
    /// The axis the chains are stacked along (0 x, 1 y, 2 z).
    pub axis: usize,
    /// One chain's extent at mip 0.
    pub chain: glam::UVec3,
    /// From one chain's start to the next's along `axis` at mip 0 (texels): the chain and its
    /// separator.
    pub pitch: u32,
}

impl AtlasLayout {
    pub fn new(grid: &VoxelGrid) -> Self {
        let chain = (grid.dims / 2).max(glam::UVec3::ONE);
        let axis = (0..3).max_by_key(|&a| (chain[a], std::cmp::Reverse(a))).expect("three axes");
        let mips = (grid.mip_levels() - 1).max(1);
        let separator = (1u32 << (mips - 1)).min(chain[axis]);
        AtlasLayout { axis, chain, pitch: chain[axis] + separator }
    }

    /// The atlas' extent at mip 0: six chains and the five separators between them.
    pub fn extent(&self) -> vk::Extent3D {
        let mut e = self.chain;
        e[self.axis] = self.extent_along();
        extent_of(e)
    }

    /// Where chain `d` starts along the stacking axis at chain mip `mip` (texels).
    pub fn offset(&self, d: u32, mip: u32) -> u32 {
        (d * self.pitch) >> mip
    }

    /// The chain's extent at chain mip `mip`.
    pub fn chain_at(&self, mip: u32) -> glam::UVec3 {
        (self.chain >> mip).max(glam::UVec3::ONE)
    }

    /// For the shaders (`FrameUniforms::aniso_atlas`, common/cone.glsl): the stacking axis, the
    /// pitch and the atlas' length along it, the last two over one chain's length.
    pub fn uniform(&self) -> glam::Vec4 {
        let n = self.chain[self.axis] as f32;
        glam::Vec4::new(self.axis as f32, self.pitch as f32 / n, self.extent_along() as f32 / n, 0.0)
    }

    fn extent_along(&self) -> u32 {
        5 * self.pitch + self.chain[self.axis]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Aabb;
    use glam::{UVec3, Vec3};

    #[test]
    fn atlas_chains_stack_along_the_longest_axis_with_separators_aligned_at_every_mip() {
        for dims in [UVec3::new(256, 128, 128), UVec3::splat(64), UVec3::new(32, 128, 16), UVec3::new(16, 16, 512)] {
            let bounds = Aabb { min: Vec3::ZERO, max: dims.as_vec3() };
            let grid = VoxelGrid::fit_dims(&bounds, dims).unwrap();
            let a = AtlasLayout::new(&grid);
            let mips = grid.mip_levels() - 1;
            assert_eq!(a.chain[a.axis], a.chain.max_element(), "{dims}");
            let separator = a.pitch - a.chain[a.axis];
            // One texel at the coarsest mip, and every chain's start on a texel at every mip.
            assert_eq!(separator, 1 << (mips - 1), "{dims}");
            for m in 0..mips {
                for d in 0..6 {
                    assert_eq!(a.offset(d, m) << m, d * a.pitch, "{dims}: chain {d} at mip {m}");
                }
            }
            let e = a.extent();
            assert_eq!(
                e.width * e.height * e.depth,
                a.chain.element_product() / a.chain[a.axis] * (5 * a.pitch + a.chain[a.axis])
            );
        }
        // Sponza's grid: separators half a chain long (a whole one stacked along y).
        let bounds = Aabb { min: Vec3::ZERO, max: Vec3::new(2.0, 1.0, 1.0) };
        let a = AtlasLayout::new(&VoxelGrid::fit_dims(&bounds, UVec3::new(256, 128, 128)).unwrap());
        assert_eq!((a.axis, a.pitch, a.extent().width), (0, 192, 1088));
    }
}
