//! Float images in OpenGL orientation (row 0 is the bottom of the screen), PNG output (flipped
//! back to top-first), and the comparisons the tests, the GL check and the bench use (PSNR,
//! differences, NVIDIA's FLIP through the `nv-flip` crate).

use std::path::Path;

use crate::HarnessError;

#[derive(Clone, Debug, PartialEq)]
pub struct FloatImage {
    pub width: u32,
    pub height: u32,
    /// Bottom row first.
    pub pixels: Vec<[f32; 4]>,
}

impl FloatImage {
    pub fn new(width: u32, height: u32) -> FloatImage {
        FloatImage { width, height, pixels: vec![[0.0; 4]; (width * height) as usize] }
    }

    /// The pixel at column x of row y counted from the bottom.
    pub fn at(&self, x: u32, y: u32) -> [f32; 4] {
        self.pixels[(y * self.width + x) as usize]
    }

    /// Pixels that are NaN or infinite in any channel.
    pub fn non_finite(&self) -> usize {
        self.pixels.iter().filter(|p| p.iter().any(|c| !c.is_finite())).count()
    }

    /// 8-bit RGBA, top row first, each channel clamped and rounded as a UNORM8 target would.
    pub fn to_rgba8_top_first(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(self.pixels.len() * 4);
        for y in (0..self.height).rev() {
            for x in 0..self.width {
                out.extend(self.at(x, y).map(to_unorm8));
            }
        }
        out
    }

    /// 8-bit RGB, top row first: [`Self::to_rgba8_top_first`] without alpha, the layout FLIP takes.
    pub fn to_rgb8_top_first(&self) -> Vec<u8> {
        rgba8_to_rgb8(&self.to_rgba8_top_first())
    }

    /// Writes a PNG (opaque: alpha is forced to 255 unless `keep_alpha`).
    pub fn write_png(&self, path: &Path, keep_alpha: bool) -> Result<(), HarnessError> {
        let mut bytes = self.to_rgba8_top_first();
        if !keep_alpha {
            bytes.chunks_exact_mut(4).for_each(|p| p[3] = 255);
        }
        write_rgba8_png(path, self.width, self.height, &bytes)
    }

    /// A depth image as grey levels stretched over the non-sky range (for viewing only).
    pub fn depth_for_viewing(&self) -> FloatImage {
        let (lo, hi) = self
            .pixels
            .iter()
            .map(|p| p[0])
            .filter(|d| *d < 1.0)
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), d| (lo.min(d), hi.max(d)));
        let range = if hi > lo { hi - lo } else { 1.0 };
        FloatImage {
            width: self.width,
            height: self.height,
            pixels: self
                .pixels
                .iter()
                .map(|p| {
                    let v = if p[0] >= 1.0 { 1.0 } else { (p[0] - lo) / range * 0.9 };
                    [v, v, v, 1.0]
                })
                .collect(),
        }
    }
}

pub fn to_unorm8(c: f32) -> u8 {
    if c.is_nan() { 0 } else { (c.clamp(0.0, 1.0) * 255.0).round() as u8 }
}

pub fn write_rgba8_png(path: &Path, width: u32, height: u32, rgba_top_first: &[u8]) -> Result<(), HarnessError> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| HarnessError::Io(format!("cannot create {}: {e}", dir.display())))?;
    }
    image::save_buffer(path, rgba_top_first, width, height, image::ColorType::Rgba8)
        .map_err(|e| HarnessError::Io(format!("cannot write {}: {e}", path.display())))
}

/// Reads a PNG as 8-bit RGBA, top row first.
pub fn read_rgba8_png(path: &Path) -> Result<(u32, u32, Vec<u8>), HarnessError> {
    let img = image::open(path).map_err(|e| HarnessError::Io(format!("cannot read {}: {e}", path.display())))?;
    let rgba = img.to_rgba8();
    Ok((rgba.width(), rgba.height(), rgba.into_raw()))
}

/// Largest absolute difference per channel (RGBA) of two float images, after clamping both to
/// 0..1 as the displayed 8-bit image does; NaN anywhere counts as a difference of 1.
pub fn max_channel_difference(a: &FloatImage, b: &FloatImage) -> [f32; 4] {
    assert_eq!((a.width, a.height), (b.width, b.height), "images of different sizes");
    let mut max = [0.0f32; 4];
    for (p, q) in a.pixels.iter().zip(&b.pixels) {
        for c in 0..4 {
            let d = if p[c].is_nan() || q[c].is_nan() { 1.0 } else { (p[c].clamp(0.0, 1.0) - q[c].clamp(0.0, 1.0)).abs() };
            max[c] = max[c].max(d);
        }
    }
    max
}

/// The threshold the renderers' images are compared at: more than 1/255 in some channel (a hair
/// over, so that values one 8-bit step apart after float rounding are not counted).
pub const OVER_1_255: f32 = 1.0 / 255.0 + 1e-6;

/// Whether two pixels' RGB differ by more than `threshold` in some channel, clamped to 0..1
/// as the displayed image is (NaN on one side alone differs).
fn pixels_differ(p: &[f32; 4], q: &[f32; 4], threshold: f32) -> bool {
    (0..3).any(|c| (p[c].clamp(0.0, 1.0) - q[c].clamp(0.0, 1.0)).abs() > threshold || p[c].is_nan() != q[c].is_nan())
}

/// Pixels whose RGB differ by more than `threshold` in some channel.
pub fn count_differing(a: &FloatImage, b: &FloatImage, threshold: f32) -> usize {
    a.pixels.iter().zip(&b.pixels).filter(|(p, q)| pixels_differ(p, q, threshold)).count()
}

/// Per pixel, how far apart the mean RGB of the `side` x `side` block it lies in is between the
/// two images (blocks from the first pixel on; the last row and column of blocks may be
/// smaller): the largest channel's difference, with both clamped to 0..1 as the displayed image
/// is.
pub fn block_mean_differences(a: &FloatImage, b: &FloatImage, side: u32) -> Vec<f32> {
    assert_eq!((a.width, a.height), (b.width, b.height), "images of different sizes");
    let (w, h, side) = (a.width as usize, a.height as usize, side.max(1) as usize);
    let mut apart = vec![0.0; w * h];
    for by in (0..h).step_by(side) {
        for bx in (0..w).step_by(side) {
            let pixels: Vec<usize> = (by..(by + side).min(h)).flat_map(|y| (bx..(bx + side).min(w)).map(move |x| y * w + x)).collect();
            let mean = |image: &FloatImage, c: usize| pixels.iter().map(|&i| image.pixels[i][c].clamp(0.0, 1.0)).sum::<f32>() / pixels.len() as f32;
            let difference = (0..3).map(|c| (mean(a, c) - mean(b, c)).abs()).fold(0.0, f32::max);
            for i in pixels {
                apart[i] = difference;
            }
        }
    }
    apart
}

/// Per pixel of a `width`x`height` image, whether its `side`-pixel block holds a pixel `mask`
/// marks.
pub fn blocks_holding(mask: &[bool], width: u32, height: u32, side: u32) -> Vec<bool> {
    let (w, h, side) = (width as usize, height as usize, side.max(1) as usize);
    let blocks_across = w.div_ceil(side);
    let mut held = vec![false; blocks_across * h.div_ceil(side)];
    for (i, _) in mask.iter().enumerate().filter(|(_, m)| **m) {
        held[(i / w) / side * blocks_across + (i % w) / side] = true;
    }
    (0..w * h).map(|i| held[(i / w) / side * blocks_across + (i % w) / side]).collect()
}

/// Per pixel, whether its RGB differ by more than `threshold` in some channel.
pub fn differing_pixels(a: &FloatImage, b: &FloatImage, threshold: f32) -> Vec<bool> {
    a.pixels.iter().zip(&b.pixels).map(|(p, q)| pixels_differ(p, q, threshold)).collect()
}

/// PSNR in dB over the RGB channels of two 8-bit RGBA images (infinite when identical).
pub fn psnr_rgb8(a: &[u8], b: &[u8]) -> f64 {
    assert_eq!(a.len(), b.len(), "images of different sizes");
    let (mut sum, mut n) = (0.0f64, 0usize);
    for (p, q) in a.chunks_exact(4).zip(b.chunks_exact(4)) {
        for c in 0..3 {
            let d = p[c] as f64 - q[c] as f64;
            sum += d * d;
            n += 1;
        }
    }
    if sum == 0.0 {
        return f64::INFINITY;
    }
    let mse = sum / n as f64;
    10.0 * (255.0 * 255.0 / mse).log10()
}

/// A difference image of two 8-bit RGBA images: |a - b| per channel, amplified 8×, opaque.
pub fn difference_rgb8(a: &[u8], b: &[u8]) -> Vec<u8> {
    a.chunks_exact(4)
        .zip(b.chunks_exact(4))
        .flat_map(|(p, q)| {
            let d = |c: usize| ((p[c] as i32 - q[c] as i32).unsigned_abs() * 8).min(255) as u8;
            [d(0), d(1), d(2), 255]
        })
        .collect()
}

/// On the pixels [`count_differing`] counts, white, or grey where `set_aside` (per pixel, bottom
/// row first as the images are) marks them; black elsewhere: 8-bit RGBA, top row first, to find
/// the few pixels where two renderers part.
pub fn differing_mask_rgba8(a: &FloatImage, b: &FloatImage, threshold: f32, set_aside: &[bool]) -> Vec<u8> {
    let mut mask = Vec::with_capacity(a.pixels.len() * 4);
    for y in (0..a.height).rev() {
        for x in 0..a.width {
            let grey = set_aside.get((y * a.width + x) as usize).copied().unwrap_or(false);
            let v = match (pixels_differ(&a.at(x, y), &b.at(x, y), threshold), grey) {
                (false, _) => 0,
                (true, true) => 96,
                (true, false) => 255,
            };
            mask.extend_from_slice(&[v, v, v, 255]);
        }
    }
    mask
}

/// Drops the alpha of 8-bit RGBA pixels.
pub fn rgba8_to_rgb8(rgba: &[u8]) -> Vec<u8> {
    rgba.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect()
}

/// NVIDIA FLIP's LDR error map (0..1 per pixel) of `test` against `reference`, both 8-bit RGB,
/// top row first, at FLIP's default viewing conditions (67 pixels per degree). The composite
/// writes display values straight to an 8-bit framebuffer, so these bytes are already the
/// sRGB-encoded image LDR FLIP expects.
pub fn flip_map(test_rgb8: &[u8], reference_rgb8: &[u8], width: u32, height: u32) -> nv_flip::FlipImageFloat {
    let reference = nv_flip::FlipImageRgb8::with_data(width, height, reference_rgb8);
    let test = nv_flip::FlipImageRgb8::with_data(width, height, test_rgb8);
    nv_flip::flip(reference, test, nv_flip::DEFAULT_PIXELS_PER_DEGREE)
}

/// The mean of a FLIP error map, the single number FLIP's tools report.
pub fn mean_flip(map: &nv_flip::FlipImageFloat) -> f64 {
    nv_flip::FlipPool::from_image(map).mean() as f64
}

/// A FLIP error map through FLIP's magma colour map (0 black, 1 near white), as opaque 8-bit
/// RGBA top row first.
pub fn flip_heatmap_rgba8(map: &nv_flip::FlipImageFloat) -> Vec<u8> {
    map.apply_color_lut(&nv_flip::magma_lut()).to_vec().chunks_exact(3).flat_map(|p| [p[0], p[1], p[2], 255]).collect()
}

/// Median of pass times (NaN for none): what every timing report of the harness quotes.
pub fn median(samples: &[f64]) -> f64 {
    let mut sorted = samples.to_vec();
    sorted.sort_by(f64::total_cmp);
    let n = sorted.len();
    match n {
        0 => f64::NAN,
        _ if n % 2 == 1 => sorted[n / 2],
        _ => (sorted[n / 2 - 1] + sorted[n / 2]) / 2.0,
    }
}

/// The first and third quartiles of `samples` (nearest rank; NaN for none): the spread the
/// timing reports quote beside a median.
pub fn quartiles(samples: &[f64]) -> (f64, f64) {
    let mut sorted = samples.to_vec();
    sorted.sort_by(f64::total_cmp);
    let at = |q: f64| if sorted.is_empty() { f64::NAN } else { sorted[((sorted.len() - 1) as f64 * q).round() as usize] };
    (at(0.25), at(0.75))
}

/// The median of a run's per-frame times without the first frame, which pays for llvmpipe's
/// lazy shader compilation (all of them when there is one).
pub fn settled_median(samples: &[f64]) -> f64 {
    median(if samples.len() > 1 { &samples[1..] } else { samples })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flip_is_zero_for_equal_images_and_grows_with_the_difference() {
        let (w, h) = (32u32, 16u32);
        let base: Vec<u8> = (0..w * h).flat_map(|i| [(i % w * 8) as u8, (i / w * 16) as u8, 128]).collect();
        assert_eq!(mean_flip(&flip_map(&base, &base, w, h)), 0.0);
        let shifted = |d: u8| base.iter().map(|c| c.saturating_add(d)).collect::<Vec<u8>>();
        let (small, large) = (mean_flip(&flip_map(&shifted(4), &base, w, h)), mean_flip(&flip_map(&shifted(64), &base, w, h)));
        assert!(0.0 < small && small < large && large <= 1.0, "{small} {large}");
        let heat = flip_heatmap_rgba8(&flip_map(&shifted(64), &base, w, h));
        assert_eq!(heat.len(), (w * h * 4) as usize);
        assert!(heat.chunks_exact(4).all(|p| p[3] == 255));
    }
}
