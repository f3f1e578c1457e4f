//! PNG: the scene's SVG rasterised by resvg (tiny-skia), a well-kept renderer, rather than
//! a rasteriser of our own.

use super::{RenderError, MAX_PNG_PIXELS};
use alloc::string::ToString;
use alloc::vec::Vec;
use resvg::{tiny_skia, usvg};

/// The PNG bytes of `svg` drawn at `width` x `height` pixels.
pub(super) fn rasterise(svg: &str, width: u32, height: u32) -> Result<Vec<u8>, RenderError> {
    if u64::from(width) * u64::from(height) > MAX_PNG_PIXELS {
        return Err(RenderError::PngSize { width, height });
    }
    let tree = usvg::Tree::from_str(svg, &usvg::Options::default())
        .map_err(|e| RenderError::Png(e.to_string()))?;
    let mut pixmap = tiny_skia::Pixmap::new(width, height)
        .ok_or_else(|| RenderError::Png("no pixmap of that size".to_string()))?;
    let size = tree.size();
    let scale = tiny_skia::Transform::from_scale(
        width as f32 / size.width(),
        height as f32 / size.height(),
    );
    resvg::render(&tree, scale, &mut pixmap.as_mut());
    pixmap
        .encode_png()
        .map_err(|e| RenderError::Png(e.to_string()))
}
