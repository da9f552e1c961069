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
    /// `sparseBinding` and `sparseResidencyImage3D`: 3D images whose memory is bound block by
    /// block (resident voxel storage).
    SparseResidencyImage3D,
    /// Reads of unbound blocks return zero and writes to them are discarded
    /// (`residencyNonResidentStrict`), so a resident volume reads as its dense twin.
    ResidencyNonResidentStrict,
    /// Sparse blocks may share memory (`sparseResidencyAliased`): where reads of unbound blocks
    /// are not defined, every block without a brick is bound to one shared block of zeros.
    SparseResidencyAliased,
    /// Sparse 3D images use the standard 64 KiB block shapes (`residencyStandard3DBlockShape`),
    /// so the memory report can tell what a resident texture binds before it is made.
    ResidencyStandard3DBlockShape,
    /// The queue vct submits to also binds sparse memory.
    SparseBindingQueue,
}

impl Feature {
    pub const ALL: [Feature; 16] = [
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
        Feature::SparseResidencyImage3D,
        Feature::ResidencyNonResidentStrict,
        Feature::SparseResidencyAliased,
        Feature::ResidencyStandard3DBlockShape,
        Feature::SparseBindingQueue,
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
            Feature::SparseResidencyImage3D => "sparseBinding + sparseResidencyImage3D",
            Feature::ResidencyNonResidentStrict => "residencyNonResidentStrict",
            Feature::SparseResidencyAliased => "sparseResidencyAliased",
            Feature::ResidencyStandard3DBlockShape => "residencyStandard3DBlockShape",
            Feature::SparseBindingQueue => "a graphics queue with VK_QUEUE_SPARSE_BINDING_BIT",
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
    pub sparse: vk::PhysicalDeviceSparseProperties,
    /// The graphics+compute queue family vct would use also binds sparse memory.
    pub sparse_queue: bool,
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
            Feature::SparseResidencyImage3D => c.sparse_binding == vk::TRUE && c.sparse_residency_image3_d == vk::TRUE,
            Feature::ResidencyNonResidentStrict => self.sparse.residency_non_resident_strict == vk::TRUE,
            Feature::SparseResidencyAliased => c.sparse_residency_aliased == vk::TRUE,
            Feature::ResidencyStandard3DBlockShape => self.sparse.residency_standard3_d_block_shape == vk::TRUE,
            Feature::SparseBindingQueue => self.sparse_queue,
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
            .sparse_binding(c.sparse_binding == vk::TRUE)
            .sparse_residency_image3_d(c.sparse_residency_image3_d == vk::TRUE)
            .sparse_residency_aliased(c.sparse_residency_aliased == vk::TRUE)
    }
}
