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
use rayon::prelude::*;

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
/// evaluated stay zero and `evaluated` lists the ones that were.
pub fn render(inputs: &Inputs, settings: &ReferenceSettings, stride: usize) -> Result<ReferenceImage, String> {
    inputs.validate()?;
    let stride = stride.max(1);
    let (w, h) = (inputs.width, inputs.height);
    let mut pixels = vec![DVec3::ZERO; w * h];
    // Rows on every core (rayon); each pixel depends on nothing but its inputs, so the image does
    // not depend on the scheduling.
    let shaded: Vec<(usize, DVec3)> = (0..h)
        .into_par_iter()
        .step_by(stride)
        .flat_map_iter(|y| (0..w).step_by(stride).map(move |x| (y * w + x, shade_pixel(inputs, settings, x, y))))
        .collect();
    for (index, colour) in shaded {
        pixels[index] = colour;
    }
    Ok(ReferenceImage { width: w, height: h, pixels })
}

/// Indices of the pixels `render` evaluates at a stride.
pub fn evaluated(width: usize, height: usize, stride: usize) -> Vec<usize> {
    let stride = stride.max(1);
    (0..height).step_by(stride).flat_map(|y| (0..width).step_by(stride).map(move |x| y * width + x)).collect()
}
