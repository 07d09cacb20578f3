//! 8-bit RGBA images: PNG output and side-by-side composition.

use crate::RenderError;
use std::io::Write;
use std::path::Path;

/// A row-major 8-bit RGBA image (sRGB colour, straight alpha).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RgbaImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `4 * width * height` bytes, top row first.
    pub data: Vec<u8>,
}

impl RgbaImage {
    /// An image filled with one colour.
    pub fn filled(width: u32, height: u32, rgba: [u8; 4]) -> RgbaImage {
        let mut data = Vec::with_capacity(4 * width as usize * height as usize);
        for _ in 0..width as usize * height as usize {
            data.extend_from_slice(&rgba);
        }
        RgbaImage {
            width,
            height,
            data,
        }
    }

    /// The pixel at column `x`, row `y` (row 0 at the top).
    pub fn pixel(&self, x: u32, y: u32) -> [u8; 4] {
        let i = 4 * (y as usize * self.width as usize + x as usize);
        [
            self.data[i],
            self.data[i + 1],
            self.data[i + 2],
            self.data[i + 3],
        ]
    }

    /// Copies `src` into this image with its top-left corner at `(x, y)`, clipped.
    pub fn blit(&mut self, src: &RgbaImage, x: u32, y: u32) {
        let w = src.width.min(self.width.saturating_sub(x)) as usize;
        for row in 0..src.height.min(self.height.saturating_sub(y)) as usize {
            let s = 4 * row * src.width as usize;
            let d = 4 * ((y as usize + row) * self.width as usize + x as usize);
            self.data[d..d + 4 * w].copy_from_slice(&src.data[s..s + 4 * w]);
        }
    }

    /// Images placed left to right with `gap` pixels between them, on `background`.
    pub fn hstack(images: &[RgbaImage], gap: u32, background: [u8; 4]) -> RgbaImage {
        let width = images.iter().map(|i| i.width).sum::<u32>()
            + gap * (images.len().saturating_sub(1) as u32);
        let height = images.iter().map(|i| i.height).max().unwrap_or(0);
        let mut out = RgbaImage::filled(width, height, background);
        let mut x = 0;
        for im in images {
            out.blit(im, x, (height - im.height) / 2);
            x += im.width + gap;
        }
        out
    }

    /// Encodes the image as PNG (8-bit RGBA) into `w`.
    pub fn write_png<W: Write>(&self, w: W) -> Result<(), RenderError> {
        let mut enc = png::Encoder::new(w, self.width, self.height);
        enc.set_color(png::ColorType::Rgba);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_compression(png::Compression::High);
        enc.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
        let mut writer = enc
            .write_header()
            .map_err(|e| RenderError::Png(e.to_string()))?;
        writer
            .write_image_data(&self.data)
            .map_err(|e| RenderError::Png(e.to_string()))?;
        writer.finish().map_err(|e| RenderError::Png(e.to_string()))
    }

    /// Writes the image to a PNG file.
    pub fn save_png(&self, path: impl AsRef<Path>) -> Result<(), RenderError> {
        let file = std::fs::File::create(path.as_ref())?;
        let mut w = std::io::BufWriter::new(file);
        self.write_png(&mut w)?;
        w.flush()?;
        Ok(())
    }
}
