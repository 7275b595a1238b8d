//! The f64 reference of the composite water model: the pack's composite pass ported function
//! by function to the CPU, evaluated in double precision with converged iteration counts (by
//! default), fed the same G-buffers, uniforms and textures as the GPU.
//! It is the ground truth the pack's quality knobs are measured against. See docs/reference.md.

#[cfg(feature = "harness")]
pub mod harness;
pub mod inputs;
pub mod model;
pub mod sampling;
pub mod settings;

use glam::DVec3;

pub use inputs::{Inputs, Uniforms};
pub use model::shade_pixel;
pub use sampling::{Filter, Texture, Wrap};
pub use settings::{Absorption, CausticsMode, NormalMode, ReferenceSettings};

/// A composite image in linear colour, row 0 at the bottom (the harness's orientation).
#[derive(Clone, Debug, PartialEq)]
pub struct ReferenceImage {
    pub width: usize,
    pub height: usize,
    pub pixels: Vec<DVec3>,
}

/// Evaluates every pixel `stride`-th pixel in x and y (stride 1: the full frame); pixels not
/// evaluated stay zero and `evaluated` lists the ones that were. Rows are split over the
/// available cores.
pub fn render(inputs: &Inputs, settings: &ReferenceSettings, stride: usize) -> Result<ReferenceImage, String> {
    inputs.validate()?;
    let stride = stride.max(1);
    let (w, h) = (inputs.width, inputs.height);
    let mut pixels = vec![DVec3::ZERO; w * h];
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get()).min(8);
    let rows: Vec<usize> = (0..h).step_by(stride).collect();
    let chunk = rows.len().div_ceil(threads).max(1);
    let shaded: Vec<Vec<(usize, DVec3)>> = std::thread::scope(|scope| {
        let workers: Vec<_> = rows
            .chunks(chunk)
            .map(|band| {
                scope.spawn(move || {
                    let mut out = Vec::new();
                    for &y in band {
                        for x in (0..w).step_by(stride) {
                            out.push((y * w + x, shade_pixel(inputs, settings, x, y)));
                        }
                    }
                    out
                })
            })
            .collect();
        workers.into_iter().map(|t| t.join().expect("a reference worker panicked")).collect()
    });
    for (index, colour) in shaded.into_iter().flatten() {
        pixels[index] = colour;
    }
    Ok(ReferenceImage { width: w, height: h, pixels })
}

/// Indices of the pixels `render` evaluates at a stride.
pub fn evaluated(width: usize, height: usize, stride: usize) -> Vec<usize> {
    let stride = stride.max(1);
    (0..height).step_by(stride).flat_map(|y| (0..width).step_by(stride).map(move |x| y * width + x)).collect()
}
