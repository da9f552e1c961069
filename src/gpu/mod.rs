//! The thin layer over `ash`: the only code that creates or destroys Vulkan objects. Every
//! wrapper owns its handles, frees them in `Drop`, and carries a debug name.

pub mod buffer;
pub mod commands;
pub mod context;
pub mod descriptor;
pub mod features;
pub mod frames;
pub mod image;
pub mod pipeline;
pub mod scope;
pub mod sparse;
pub mod swapchain;
pub mod timer;

pub use buffer::{Buffer, FrameBuffer, FrameSlot, FRAMES_IN_FLIGHT};
pub use commands::{
    blit_to_present, clear_mips, clear_to_general, copy_buffer, copy_buffer_at, copy_level, discard_to_depth, dispatch,
    dispatch_indirect, fill_buffer, fill_buffer_at, image_barrier, image_barrier_mips, memory_barrier, read_buffer,
    read_image, render, render_depth_layer, render_multi, update_buffer, upload_levels, Attachments,
};
pub use context::{Context, ContextOptions, DeviceInfo};
pub use descriptor::{Binding, DescriptorSet};
pub use features::{Feature, FeatureSet};
pub use frames::FrameRing;
pub use image::{Image, ImageDesc, Sampler};
pub use pipeline::{GraphicsDesc, GridSpec, Pipeline, Stage, VertexLayout};
pub use swapchain::{FrameOutcome, Swapchain};
pub use timer::{GpuTimer, Timing};

/// SPIR-V of every shader in `shaders-glsl/`, compiled by build.rs.
pub mod shaders {
    include!(concat!(env!("OUT_DIR"), "/shaders.rs"));
}
