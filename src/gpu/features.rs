//! The device features this renderer uses, by name: which each device offers (for `vct devices`)
//! and which each pass requires. A pass declares its needs as a slice of [`Feature`]s and
//! [`Context::require`](super::Context::require) turns a missing one into an error naming it.

use ash::vk;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Feature {
    DynamicRendering,
    Synchronization2,
    GeometryShader,
    TessellationShader,
    VertexPipelineStoresAndAtomics,
    FragmentStoresAndAtomics,
    SampledImageArrayDynamicIndexing,
    StorageImageExtendedFormats,
    DepthClamp,
    /// Framebuffers without attachments may use 4 samples (MSAA-conservative voxelization).
    NoAttachmentMsaa4,
    /// `VK_EXT_conservative_rasterization` (hardware-conservative voxelization).
    ConservativeRasterization,
}

impl Feature {
    pub const ALL: [Feature; 11] = [
        Feature::DynamicRendering,
        Feature::Synchronization2,
        Feature::GeometryShader,
        Feature::TessellationShader,
        Feature::VertexPipelineStoresAndAtomics,
        Feature::FragmentStoresAndAtomics,
        Feature::SampledImageArrayDynamicIndexing,
        Feature::StorageImageExtendedFormats,
        Feature::DepthClamp,
        Feature::NoAttachmentMsaa4,
        Feature::ConservativeRasterization,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Feature::DynamicRendering => "dynamicRendering",
            Feature::Synchronization2 => "synchronization2",
            Feature::GeometryShader => "geometryShader",
            Feature::TessellationShader => "tessellationShader",
            Feature::VertexPipelineStoresAndAtomics => "vertexPipelineStoresAndAtomics",
            Feature::FragmentStoresAndAtomics => "fragmentStoresAndAtomics",
            Feature::SampledImageArrayDynamicIndexing => "shaderSampledImageArrayDynamicIndexing",
            Feature::StorageImageExtendedFormats => "shaderStorageImageExtendedFormats",
            Feature::DepthClamp => "depthClamp",
            Feature::NoAttachmentMsaa4 => "framebufferNoAttachmentsSampleCounts includes 4",
            Feature::ConservativeRasterization => "VK_EXT_conservative_rasterization",
        }
    }
}

/// What one physical device offers, read once at start-up.
#[derive(Clone, Debug, Default)]
pub struct FeatureSet {
    pub core: vk::PhysicalDeviceFeatures,
    pub dynamic_rendering: bool,
    pub synchronization2: bool,
    pub no_attachment_samples: vk::SampleCountFlags,
    pub conservative_rasterization: bool,
}

impl FeatureSet {
    pub fn has(&self, f: Feature) -> bool {
        let c = &self.core;
        match f {
            Feature::DynamicRendering => self.dynamic_rendering,
            Feature::Synchronization2 => self.synchronization2,
            Feature::GeometryShader => c.geometry_shader == vk::TRUE,
            Feature::TessellationShader => c.tessellation_shader == vk::TRUE,
            Feature::VertexPipelineStoresAndAtomics => c.vertex_pipeline_stores_and_atomics == vk::TRUE,
            Feature::FragmentStoresAndAtomics => c.fragment_stores_and_atomics == vk::TRUE,
            Feature::SampledImageArrayDynamicIndexing => c.shader_sampled_image_array_dynamic_indexing == vk::TRUE,
            Feature::StorageImageExtendedFormats => c.shader_storage_image_extended_formats == vk::TRUE,
            Feature::DepthClamp => c.depth_clamp == vk::TRUE,
            Feature::NoAttachmentMsaa4 => self.no_attachment_samples.contains(vk::SampleCountFlags::TYPE_4),
            Feature::ConservativeRasterization => self.conservative_rasterization,
        }
    }

    /// The core features to enable at device creation: everything in our list that is offered.
    pub fn enabled_core(&self) -> vk::PhysicalDeviceFeatures {
        let c = &self.core;
        vk::PhysicalDeviceFeatures::default()
            .geometry_shader(c.geometry_shader == vk::TRUE)
            .tessellation_shader(c.tessellation_shader == vk::TRUE)
            .vertex_pipeline_stores_and_atomics(c.vertex_pipeline_stores_and_atomics == vk::TRUE)
            .fragment_stores_and_atomics(c.fragment_stores_and_atomics == vk::TRUE)
            .shader_sampled_image_array_dynamic_indexing(c.shader_sampled_image_array_dynamic_indexing == vk::TRUE)
            .shader_storage_image_extended_formats(c.shader_storage_image_extended_formats == vk::TRUE)
            .depth_clamp(c.depth_clamp == vk::TRUE)
            .sampler_anisotropy(c.sampler_anisotropy == vk::TRUE)
    }
}
