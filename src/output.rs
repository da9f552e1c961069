//! Writing rendered frames: tone-mapped PNG and linear-radiance OpenEXR (image crate).

use std::path::Path;

use glam::Vec3;

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

impl FrameImages {
    /// A frame from linear radiance computed on the CPU (tone-mapped like the GPU's output).
    pub fn from_linear(width: u32, height: u32, radiance: &[Vec3]) -> FrameImages {
        let ldr = crate::reference::metrics::tonemap(radiance)
            .chunks_exact(3)
            .flat_map(|p| [p[0], p[1], p[2], 255])
            .collect();
        let hdr = radiance.iter().flat_map(|c| [c.x, c.y, c.z, 1.0]).collect();
        FrameImages { width, height, hdr, ldr }
    }

    /// Linear radiance per pixel.
    pub fn linear(&self) -> Vec<Vec3> {
        self.hdr.chunks_exact(4).map(|p| Vec3::new(p[0], p[1], p[2])).collect()
    }

    /// Tone-mapped RGB8 per pixel.
    pub fn rgb8(&self) -> Vec<u8> {
        self.ldr.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect()
    }
}

/// Reads a PNG (tone-mapped; no linear data) or an OpenEXR (linear; tone-mapped here) image.
pub fn read_frame(path: &Path) -> Result<FrameImages> {
    let img = image::open(path).map_err(|source| Error::Image { path: path.to_path_buf(), source })?;
    let exr = path.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("exr"));
    let (w, h) = (img.width(), img.height());
    if exr {
        let rgb = img.to_rgb32f();
        let lin: Vec<Vec3> = rgb.pixels().map(|p| Vec3::new(p[0], p[1], p[2])).collect();
        Ok(FrameImages::from_linear(w, h, &lin))
    } else {
        let ldr = img.to_rgba8().into_raw();
        Ok(FrameImages { width: w, height: h, hdr: Vec::new(), ldr })
    }
}
