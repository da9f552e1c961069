//! Writing rendered frames: tone-mapped PNG and linear-radiance OpenEXR (image crate).

use std::path::Path;

use crate::error::{Error, Result};
use crate::render::FrameImages;

fn create_parent(path: &Path) -> Result<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|source| Error::Io { path: dir.to_path_buf(), source })?;
    }
    Ok(())
}

pub fn write_png(path: &Path, frame: &FrameImages) -> Result<()> {
    create_parent(path)?;
    let rgb: Vec<u8> = frame.ldr.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect();
    image::save_buffer(path, &rgb, frame.width, frame.height, image::ColorType::Rgb8)
        .map_err(|source| Error::Image { path: path.to_path_buf(), source })
}

pub fn write_exr(path: &Path, frame: &FrameImages) -> Result<()> {
    create_parent(path)?;
    let rgb: Vec<f32> = frame.hdr.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect();
    let img = image::Rgb32FImage::from_raw(frame.width, frame.height, rgb).expect("buffer matches the frame size");
    img.save_with_format(path, image::ImageFormat::OpenExr)
        .map_err(|source| Error::Image { path: path.to_path_buf(), source })
}
