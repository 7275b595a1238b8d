//! shaderpack/shaders/lib/caustics.glsl in f64: the caustic patterns from the height or the noise texture.

use glam::DVec2;

use super::builtins::*;
use super::waves::*;
use crate::sampling::Texture;

/// `causticsFromHeight` (A6): octave k of the pattern is channel k of the water texture (the
/// height at 2^k times its frequency) at both samples.
pub(crate) fn caustics_from_height(water: &Texture, world_xz: DVec2, time: f64, samples: u32) -> f64 {
    let uv = 0.5 + DVec2::new(world_xz.x, -world_xz.y) / WAVE_TILE;
    let a = water.sample(fract2(uv + time * WAVE_DRIFT));
    let b = water.sample(fract2(uv * 1.5 - time * DVec2::new(WAVE_DRIFT.y, WAVE_DRIFT.x)));
    // CAUSTIC_SAMPLES is 1, 2 or 3; the shader takes anything else as 3.
    let octaves = if (1..=3).contains(&samples) { samples } else { 3 };
    let mut sum = 0.0;
    for k in 0..octaves as usize {
        let c = (1.0 - (a[k] + b[k] - 1.0).abs()).clamp(0.0, 1.0);
        let c3 = c * c * c;
        sum += c3 * c3 * c3;
    }
    sum / octaves as f64
}

/// `causticsFromNoise` (D).
pub(crate) fn caustics_from_noise(noise: &Texture, world_xz: DVec2, time: f64, samples: u32) -> f64 {
    let mut sum = 0.0;
    let mut scale = 1.0;
    for _ in 0..samples {
        let uv = scale * world_xz / WAVE_TILE;
        let a = noise.sample(fract2(uv + time * WAVE_DRIFT)).x;
        let b = noise.sample(fract2(uv - time * WAVE_DRIFT)).x;
        sum += (a * 2.0 - 1.0) + (b * 2.0 - 1.0);
        scale *= 2.0;
    }
    sum / samples as f64
}
