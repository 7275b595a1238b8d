//! Error of a GPU composite image against the reference: max abs, RMSE and PSNR on linear
//! colour clamped to 0..1 (what reaches the RGBA8 framebuffer), and mean FLIP on the 8-bit images.

use glam::DVec3;
use tidepack_harness::FloatImage;
use tidepack_harness::images::{self, to_unorm8};
use tidepack_reference::ReferenceImage;

/// How far an image is from the reference, by four measures (a measurement, not a failure).
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct ErrorMetrics {
    pub max_abs: f64,
    pub rmse: f64,
    /// 10 log10(1 / MSE), peak 1.0; infinite when the images are equal.
    pub psnr: f64,
    /// Mean of NVIDIA FLIP's (LDR) error map, 0..1.
    pub mean_flip: f64,
}

/// The error of `gpu` against `reference`, rgb channels, every pixel. Returns the FLIP error map too.
pub fn error(gpu: &FloatImage, reference: &ReferenceImage) -> (ErrorMetrics, nv_flip::FlipImageFloat) {
    let every = vec![true; reference.pixels.len()];
    error_where(gpu, reference, &every).expect("a frame has pixels")
}

/// The error of `gpu` against `reference` over the pixels `compared` keeps (bottom row first,
/// as both images), with the FLIP map, whose pixels outside `compared` are 0. None when
/// `compared` keeps no pixel.
pub fn error_where(gpu: &FloatImage, reference: &ReferenceImage, compared: &[bool]) -> Option<(ErrorMetrics, nv_flip::FlipImageFloat)> {
    assert_eq!((gpu.width as usize, gpu.height as usize), (reference.width, reference.height));
    assert_eq!(compared.len(), reference.pixels.len());
    let count = compared.iter().filter(|&&c| c).count();
    if count == 0 {
        return None;
    }
    let (mut max_abs, mut squares) = (0.0f64, 0.0f64);
    for ((g, r), _) in gpu.pixels.iter().zip(&reference.pixels).zip(compared).filter(|(_, c)| **c) {
        let g = DVec3::new(g[0] as f64, g[1] as f64, g[2] as f64);
        let g = if g.is_finite() { g.clamp(DVec3::ZERO, DVec3::ONE) } else { DVec3::ONE };
        let d = (g - r.clamp(DVec3::ZERO, DVec3::ONE)).abs();
        max_abs = max_abs.max(d.max_element());
        squares += d.length_squared();
    }
    let mse = squares / (3 * count) as f64;
    let mut flip_map = images::flip_map(&gpu.to_rgb8_top_first(), &reference_rgb8_top_first(reference), gpu.width, gpu.height);
    if count < compared.len() {
        // The map is top row first; the mask bottom row first.
        let (w, h) = (reference.width, reference.height);
        let values: Vec<f32> = flip_map
            .to_vec()
            .into_iter()
            .enumerate()
            .map(|(i, v)| if compared[(h - 1 - i / w) * w + i % w] { v } else { 0.0 })
            .collect();
        flip_map = nv_flip::FlipImageFloat::with_data(gpu.width, gpu.height, &values);
    }
    let mean_flip = if count == compared.len() {
        images::mean_flip(&flip_map)
    } else {
        flip_map.to_vec().iter().map(|&v| v as f64).sum::<f64>() / count as f64
    };
    Some((ErrorMetrics { max_abs, rmse: mse.sqrt(), psnr: psnr_of_mse(mse), mean_flip }, flip_map))
}

/// PSNR in dB of a mean squared error over 0..1 values; infinite (identical) when the error is
/// below f32's resolution, where it is the f64 reference's rounding, not a difference.
pub fn psnr_of_mse(mse: f64) -> f64 {
    let resolution = f64::from(f32::EPSILON);
    if mse > resolution * resolution { 10.0 * (1.0 / mse).log10() } else { f64::INFINITY }
}

/// The reference as RGB8, top row first, rounded as the framebuffer would hold it.
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

/// The FLIP map through the magma colour map with its legend, as a PNG.
pub fn write_heatmap(map: &nv_flip::FlipImageFloat, path: &std::path::Path) -> Result<(), String> {
    heatmap_image(map)?.save(path).map_err(|e| format!("cannot write {}: {e}", path.display()))
}

/// Gap between the panels of [`panels`], pixels.
pub const PANEL_GAP: u32 = 6;

/// `images` left to right, [`PANEL_GAP`] apart, on white as tall as the tallest.
pub fn panels(images: &[image::RgbImage]) -> image::RgbImage {
    let width = images.iter().map(|i| i.width()).sum::<u32>() + PANEL_GAP * (images.len().max(1) as u32 - 1);
    let height = images.iter().map(|i| i.height()).max().unwrap_or(1);
    let mut canvas = image::RgbImage::from_pixel(width.max(1), height, image::Rgb([255, 255, 255]));
    let mut x = 0;
    for image in images {
        image::imageops::replace(&mut canvas, image, i64::from(x), 0);
        x += image.width() + PANEL_GAP;
    }
    canvas
}

/// `image` at half its size (at least one pixel), filtered.
pub fn half_size(image: &image::RgbImage) -> image::RgbImage {
    image::imageops::resize(image, (image.width() / 2).max(1), (image.height() / 2).max(1), image::imageops::FilterType::Triangle)
}

/// Where the model differs from the truth, at half size: the truth, the pack's frame, and the
/// FLIP map between them with its legend, left to right.
pub fn side_by_side(truth: &image::RgbImage, frame: &FloatImage, map: &nv_flip::FlipImageFloat) -> Result<image::RgbImage, String> {
    let (w, h) = (frame.width, frame.height);
    let (hw, hh) = ((w / 2).max(1), (h / 2).max(1));
    let pack = image::RgbImage::from_raw(w, h, frame.to_rgb8_top_first()).expect("three bytes a pixel");
    // The map's values averaged over each 2x2 block, so that the colours keep FLIP's scale.
    let values = map.to_vec();
    let half: Vec<f32> = (0..hh)
        .flat_map(|y| (0..hw).map(move |x| (x, y)))
        .map(|(x, y)| {
            let block = [(0, 0), (1, 0), (0, 1), (1, 1)].map(|(dx, dy)| values[((2 * y + dy).min(h - 1) * w + (2 * x + dx).min(w - 1)) as usize]);
            block.iter().sum::<f32>() / 4.0
        })
        .collect();
    let heat = heatmap_image(&nv_flip::FlipImageFloat::with_data(hw, hh, &half))?;
    Ok(panels(&[half_size(truth), half_size(&pack), heat]))
}

/// Height of the legend strip under a heat map, pixels.
pub const LEGEND_HEIGHT: u32 = 62;
/// The legend's bar: horizontal inset, and rows below the map.
pub const LEGEND_INSET: u32 = 14;
pub const LEGEND_BAR_ROWS: std::ops::Range<u32> = 6..20;

/// The values the legend labels, at the bar's ends and middle: FLIP's colour map spans 0..1
/// whatever the map holds, so that heat maps of different runs compare by colour.
pub const LEGEND_TICKS: [f64; 3] = [0.0, 0.5, 1.0];

/// The FLIP map through the magma colour map, with a strip below it: a bar of the colour map
/// labelled at [`LEGEND_TICKS`], and the map's mean and max. The image is at least wide enough
/// for the labels to be legible on small maps.
pub fn heatmap_image(map: &nv_flip::FlipImageFloat) -> Result<image::RgbImage, String> {
    use plotters::prelude::*;
    let lut = nv_flip::magma_lut();
    let (w, h) = (map.width(), map.height());
    let (width, height) = (w.max(320), h + LEGEND_HEIGHT);
    let mut canvas = image::RgbImage::from_pixel(width, height, image::Rgb([255, 255, 255]));
    let heat = map.apply_color_lut(&lut).to_vec();
    for (i, p) in heat.chunks_exact(3).enumerate() {
        canvas.put_pixel(i as u32 % w, i as u32 / w, image::Rgb([p[0], p[1], p[2]]));
    }
    // The bar through the same lookup as the map, so its colours are the map's exactly.
    let bar_width = width - 2 * LEGEND_INSET;
    let ramp: Vec<f32> = (0..bar_width).map(|x| x as f32 / (bar_width - 1) as f32).collect();
    let bar = nv_flip::FlipImageFloat::with_data(bar_width, 1, &ramp).apply_color_lut(&lut).to_vec();
    for (x, p) in bar.chunks_exact(3).enumerate() {
        for y in LEGEND_BAR_ROWS {
            canvas.put_pixel(LEGEND_INSET + x as u32, h + y, image::Rgb([p[0], p[1], p[2]]));
        }
    }
    let values = map.to_vec();
    let (mean, max) = (values.iter().map(|&v| v as f64).sum::<f64>() / values.len().max(1) as f64, values.iter().fold(0.0f32, |m, &v| m.max(v)));
    crate::register_font();
    let e = |e: &dyn std::fmt::Display| format!("heat-map legend: {e}");
    {
        let root = BitMapBackend::with_buffer(canvas.as_mut(), (width, height)).into_drawing_area();
        let font: TextStyle = ("sans-serif", 14).into();
        let bar_bottom = (h + LEGEND_BAR_ROWS.end) as i32;
        for t in LEGEND_TICKS {
            let x = LEGEND_INSET as i32 + (t * (bar_width - 1) as f64).round() as i32;
            root.draw(&PathElement::new(vec![(x, bar_bottom), (x, bar_bottom + 4)], BLACK)).map_err(|x| e(&x))?;
            let label = format!("{t}");
            let (tw, _) = root.estimate_text_size(&label, &font).map_err(|x| e(&x))?;
            // Centred on its tick, but inside the image at the ends.
            let left = (x - tw as i32 / 2).clamp(2, width as i32 - tw as i32 - 2);
            root.draw(&Text::new(label, (left, bar_bottom + 6), font.clone())).map_err(|x| e(&x))?;
        }
        let caption = format!("FLIP error: mean {mean:.4}, max {max:.3}");
        root.draw(&Text::new(caption, (LEGEND_INSET as i32, bar_bottom + 24), font.clone())).map_err(|x| e(&x))?;
        root.present().map_err(|x| e(&x))?;
    }
    Ok(canvas)
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

    #[test]
    fn heat_maps_carry_a_labelled_colour_bar() {
        // A small map (the bench's --quick maps are 160x90, the tests' 96x54).
        let (w, h) = (96u32, 54u32);
        let values: Vec<f32> = (0..w * h).map(|i| (i % w) as f32 / w as f32 * 0.4).collect();
        let map = nv_flip::FlipImageFloat::with_data(w, h, &values);
        let image = heatmap_image(&map).unwrap();
        assert_eq!(image.height(), h + LEGEND_HEIGHT);
        assert!(image.width() >= 320);
        // The map is unchanged at the top left.
        let heat = map.apply_color_lut(&nv_flip::magma_lut()).to_vec();
        assert_eq!(image.get_pixel(5, 7).0, [heat[(7 * w as usize + 5) * 3], heat[(7 * w as usize + 5) * 3 + 1], heat[(7 * w as usize + 5) * 3 + 2]]);
        // The bar runs from the colour map's 0 (near black) to its 1 (near white).
        let row = h + (LEGEND_BAR_ROWS.start + LEGEND_BAR_ROWS.end) / 2;
        let lut = nv_flip::magma_lut().to_vec();
        assert_eq!(image.get_pixel(LEGEND_INSET, row).0, [lut[0], lut[1], lut[2]]);
        assert_eq!(image.get_pixel(image.width() - LEGEND_INSET - 1, row).0, [lut[765], lut[766], lut[767]]);
        // Text under the bar at both ends and in the middle: dark pixels in each third.
        let label_rows = h + LEGEND_BAR_ROWS.end + 6..h + LEGEND_BAR_ROWS.end + 20;
        let third = image.width() / 3;
        for (i, xs) in [0..third, third..2 * third, 2 * third..image.width()].into_iter().enumerate() {
            let dark = xs.clone().flat_map(|x| label_rows.clone().map(move |y| (x, y))).filter(|&(x, y)| image.get_pixel(x, y).0[0] < 128).count();
            assert!(dark > 5, "no label in third {i}");
        }
        assert_eq!(LEGEND_TICKS, [0.0, 0.5, 1.0]);
    }
}
