//! Error of a GPU composite image against the reference: max abs, RMSE and PSNR on linear
//! colour clamped to 0..1 (what reaches the RGBA8 framebuffer), and mean FLIP on the 8-bit images.

use glam::DVec3;
use tidepack_harness::FloatImage;
use tidepack_harness::images::to_unorm8;
use tidepack_reference::ReferenceImage;

#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct Error {
    pub max_abs: f64,
    pub rmse: f64,
    /// 10 log10(1 / MSE), peak 1.0; infinite when the images are equal.
    pub psnr: f64,
    /// Mean of NVIDIA FLIP's (LDR) error map, 0..1.
    pub mean_flip: f64,
}

/// The error of `gpu` against `reference`, rgb channels, every pixel. Returns the FLIP error map too.
pub fn error(gpu: &FloatImage, reference: &ReferenceImage) -> (Error, nv_flip::FlipImageFloat) {
    assert_eq!((gpu.width as usize, gpu.height as usize), (reference.width, reference.height));
    let (mut max_abs, mut squares) = (0.0f64, 0.0f64);
    for (g, r) in gpu.pixels.iter().zip(&reference.pixels) {
        let g = DVec3::new(g[0] as f64, g[1] as f64, g[2] as f64);
        let g = if g.is_finite() { g.clamp(DVec3::ZERO, DVec3::ONE) } else { DVec3::ONE };
        let d = (g - r.clamp(DVec3::ZERO, DVec3::ONE)).abs();
        max_abs = max_abs.max(d.max_element());
        squares += d.length_squared();
    }
    let mse = squares / (3 * gpu.pixels.len()) as f64;
    let flip_map = flip(&rgb8_top_first(gpu), &reference_rgb8_top_first(reference), gpu.width, gpu.height);
    let mean_flip = nv_flip::FlipPool::from_image(&flip_map).mean() as f64;
    (Error { max_abs, rmse: mse.sqrt(), psnr: psnr_of_mse(mse), mean_flip }, flip_map)
}

/// PSNR in dB of a mean squared error over 0..1 values; infinite (identical) when the error is
/// below f32's resolution, where it is the f64 reference's rounding, not a difference.
pub fn psnr_of_mse(mse: f64) -> f64 {
    let resolution = f64::from(f32::EPSILON);
    if mse > resolution * resolution { 10.0 * (1.0 / mse).log10() } else { f64::INFINITY }
}

/// FLIP's error map of `test` against `reference` (8-bit RGB, top row first). The composite
/// writes display values straight to an 8-bit framebuffer, so these bytes are already the
/// sRGB-encoded image FLIP expects.
pub fn flip(test: &[u8], reference: &[u8], width: u32, height: u32) -> nv_flip::FlipImageFloat {
    let r = nv_flip::FlipImageRgb8::with_data(width, height, reference);
    let t = nv_flip::FlipImageRgb8::with_data(width, height, test);
    nv_flip::flip(r, t, nv_flip::DEFAULT_PIXELS_PER_DEGREE)
}

/// RGB8, top row first, as the framebuffer would hold it.
pub fn rgb8_top_first(image: &FloatImage) -> Vec<u8> {
    let (w, h) = (image.width as usize, image.height as usize);
    let mut out = Vec::with_capacity(w * h * 3);
    for y in (0..h).rev() {
        for p in &image.pixels[y * w..(y + 1) * w] {
            out.extend([to_unorm8(p[0]), to_unorm8(p[1]), to_unorm8(p[2])]);
        }
    }
    out
}

pub fn reference_rgb8_top_first(image: &ReferenceImage) -> Vec<u8> {
    let (w, h) = (image.width, image.height);
    let mut out = Vec::with_capacity(w * h * 3);
    for y in (0..h).rev() {
        for p in &image.pixels[y * w..(y + 1) * w] {
            out.extend([to_unorm8(p.x as f32), to_unorm8(p.y as f32), to_unorm8(p.z as f32)]);
        }
    }
    out
}

/// The FLIP map through the magma colour map, as a PNG.
pub fn write_heatmap(map: &nv_flip::FlipImageFloat, path: &std::path::Path) -> Result<(), String> {
    let rgb = map.apply_color_lut(&nv_flip::magma_lut());
    let image = image::RgbImage::from_raw(rgb.width(), rgb.height(), rgb.to_vec()).ok_or("heat-map size")?;
    image.save(path).map_err(|e| format!("cannot write {}: {e}", path.display()))
}


#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn f32_rounding_is_identical_and_real_errors_are_not() {
        // 1.6e-15 is the f32-vs-f64 rounding that printed as PSNR 147.9 dB.
        assert_eq!(psnr_of_mse(1.6e-15), f64::INFINITY);
        assert_eq!(psnr_of_mse(0.0), f64::INFINITY);
        assert!((psnr_of_mse(1e-6) - 60.0).abs() < 1e-9);
    }
}
