//! The library's error type: every failure names what went wrong and, where there is one, the
//! file or parameter responsible. The binary wraps these with `anyhow` context.

use std::path::PathBuf;

use ash::vk;

pub type Result<T, E = Error> = std::result::Result<T, E>;

#[derive(Debug, thiserror::Error)]
pub enum Error {
    #[error("Vulkan call {call} failed: {result}")]
    Vulkan { call: &'static str, result: vk::Result },
    #[error("cannot load the Vulkan library: {0}")]
    Loader(String),
    #[error("GPU memory allocation for '{name}' failed: {source}")]
    Alloc { name: String, source: gpu_allocator::AllocationError },
    #[error("no Vulkan 1.3 device found{}", .0.as_deref().map(|d| format!(" matching '{d}'")).unwrap_or_default())]
    NoDevice(Option<String>),
    #[error("device '{device}' lacks the feature {feature}, which {needed_by} needs")]
    MissingFeature { device: String, feature: &'static str, needed_by: &'static str },
    #[error("the GPU did not finish '{0}' within {1} s (device hung or lost)")]
    Timeout(String, u64),
    #[error("{path}: {message}")]
    Input { path: PathBuf, message: String },
    #[error("invalid parameter {name}: {message}")]
    Param { name: &'static str, message: String },
    #[error("{path}: {source}")]
    Io { path: PathBuf, source: std::io::Error },
    #[error("{path}: {source}")]
    Image { path: PathBuf, source: image::ImageError },
}

impl Error {
    pub fn input(path: impl Into<PathBuf>, message: impl Into<String>) -> Self {
        Error::Input { path: path.into(), message: message.into() }
    }
    pub fn param(name: &'static str, message: impl Into<String>) -> Self {
        Error::Param { name, message: message.into() }
    }
}

/// Attaches the name of the Vulkan call to a raw `vk::Result` error.
pub trait VkContext<T> {
    fn vk(self, call: &'static str) -> Result<T>;
}

impl<T> VkContext<T> for std::result::Result<T, vk::Result> {
    fn vk(self, call: &'static str) -> Result<T> {
        self.map_err(|result| Error::Vulkan { call, result })
    }
}
