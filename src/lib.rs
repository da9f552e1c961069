//! vct: real-time global illumination by voxel cone tracing (Crassin et al. 2011) on Vulkan,
//! rebuilt after S. Freed, *Tessellated Voxelization for Global Illumination using Voxel Cone
//! Tracing* (2018), with its two voxelizers measured against exact references.

pub mod bench;
pub mod error;
pub mod gpu;
pub mod output;
pub mod reference;
pub mod render;
pub mod scene;
pub mod viewer;
pub mod voxel;

/// Constants shared with GLSL (generated from `shaders-glsl/common/config.h`).
pub mod config {
    include!(concat!(env!("OUT_DIR"), "/config.rs"));
}

pub use error::{Error, Result};
