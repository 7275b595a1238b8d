//! The water texture, generated procedurally so the pack ships no hand-made binary.
//!
//! One RGBA8 texture, tiling exactly: every channel is a sum of sinusoids with whole numbers
//! of cycles across the texture.
//! - R: wave height in [0, 1];
//! - G, B: the same height at twice and four times the frequency (the same sinusoids, each with
//!   its cycles doubled or quadrupled, so each tiles too), so one lookup gives a caustic sample
//!   of each of the three octaves;
//! - A: foam pattern in [0, 1].
//!
//! Beside it, the height cross textures, one per octave of `waveNormal`'s height samples: what
//! four bilinear lookups of the height, k texels either side of a point along u and v, reduce
//! to. Bilinear filtering is linear, so a difference (or sum) of lookups k texels apart is one
//! lookup of the per-texel difference (or sum), with the same weights. Per texel, for height
//! bytes h: R = h[u+k] - h[u-k] + 128, G = h[v+k] - h[v-k] + 128, B = h, A = the four
//! neighbours' sum - 4h + 128; every value fits a byte exactly, so nothing is rounded.

use std::f64::consts::TAU;
use std::io::Cursor;

use rand_core::{Rng, SeedableRng};
use rand_xoshiro::SplitMix64;

/// Path inside `shaders/`, as named by `texture.composite.colortex7`.
pub const WATER_TEXTURE: &str = "textures/water.png";
pub const SIZE: u32 = 256;
/// The height cross textures (path inside `shaders/`, sampler composite reads it through,
/// texels apart): k = 1 and 2 are where waveNormal's ±0.25 blocks fall at the first and the
/// second octave's scale (WAVE_TILE / SIZE = 0.25 blocks per texel at scale 1).
pub const HEIGHT_CROSS_TEXTURES: [(&str, &str, usize); 2] =
    [("textures/height_cross1.png", "colortex1", 1), ("textures/height_cross2.png", "colortex2", 2)];

pub struct WaterTexture {
    pub png: Vec<u8>,
    /// The height cross textures of `HEIGHT_CROSS_TEXTURES`, in its order.
    pub height_cross: Vec<Vec<u8>>,
}

/// A wave component: whole cycles along u and v, amplitude, phase.
struct Wave {
    fu: f64,
    fv: f64,
    amplitude: f64,
    phase: f64,
}

/// Uniform in [0, 1) from the top 53 bits. splitmix64 is value-stable for a seed (see the
/// workspace manifest), so the texture is the same on every build.
fn unit(rng: &mut SplitMix64) -> f64 {
    (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64
}

/// A whole number of cycles in min..=max, either sign.
fn frequency(rng: &mut SplitMix64, min: i64, max: i64) -> f64 {
    let span = (max - min + 1) as f64;
    let magnitude = (min as f64 + (unit(rng) * span).floor()).min(max as f64);
    if unit(rng) < 0.5 { -magnitude } else { magnitude }
}

fn waves(rng: &mut SplitMix64, count: usize, min: i64, max: i64) -> Vec<Wave> {
    (0..count)
        .map(|_| {
            let fu = frequency(rng, min, max);
            let fv = frequency(rng, min, max);
            let amplitude = 1.0 / (fu * fu + fv * fv).sqrt().max(1.0);
            Wave { fu, fv, amplitude, phase: unit(rng) * TAU }
        })
        .collect()
}

/// Value of a sum of waves at (u, v).
fn evaluate(waves: &[Wave], u: f64, v: f64) -> f64 {
    waves.iter().map(|w| w.amplitude * (TAU * (w.fu * u + w.fv * v) + w.phase).sin()).sum()
}

pub fn water_texture() -> WaterTexture {
    let mut rng = SplitMix64::seed_from_u64(0x7469_6465_7061_636B); // "tidepack"
    let height_waves = waves(&mut rng, 24, 1, 9);
    let foam_waves = waves(&mut rng, 16, 10, 28);
    let n = SIZE as usize;
    let texel = |i: usize| (i as f64 + 0.5) / SIZE as f64;
    let heights: Vec<f64> = (0..n * n).map(|k| evaluate(&height_waves, texel(k % n), texel(k / n))).collect();
    let foams: Vec<f64> = (0..n * n).map(|k| evaluate(&foam_waves, texel(k % n), texel(k / n))).collect();
    let (lo, hi) = heights.iter().fold((f64::MAX, f64::MIN), |(lo, hi), &h| (lo.min(h), hi.max(h)));
    let scale = 1.0 / (hi - lo);
    let (foam_lo, foam_hi) = foams.iter().fold((f64::MAX, f64::MIN), |(lo, hi), &f| (lo.min(f), hi.max(f)));
    let to_byte = |x: f64| (x.clamp(0.0, 1.0) * 255.0).round() as u8;
    let mut rgba = Vec::with_capacity(n * n * 4);
    // The height at `frequency` times its own at texel k, on the same scale as R.
    let octave = |k: usize, frequency: f64| to_byte((evaluate(&height_waves, frequency * texel(k % n), frequency * texel(k / n)) - lo) * scale);
    for (k, (h, f)) in heights.iter().zip(&foams).enumerate() {
        let foam = (f - foam_lo) / (foam_hi - foam_lo);
        // Foam is patchy: only the upper part of the pattern shows.
        let foam = ((foam - 0.45) / 0.3).clamp(0.0, 1.0);
        rgba.extend_from_slice(&[to_byte((h - lo) * scale), octave(k, 2.0), octave(k, 4.0), to_byte(foam * foam * (3.0 - 2.0 * foam))]);
    }
    let heights: Vec<u8> = rgba.chunks_exact(4).map(|texel| texel[0]).collect();
    let height_cross = HEIGHT_CROSS_TEXTURES.iter().map(|&(_, _, k)| encode_png(height_cross(&heights, k))).collect();
    WaterTexture { png: encode_png(rgba), height_cross }
}

fn encode_png(rgba: Vec<u8>) -> Vec<u8> {
    let image = image::RgbaImage::from_raw(SIZE, SIZE, rgba).expect("buffer matches the size");
    let mut png = Vec::new();
    image.write_to(&mut Cursor::new(&mut png), image::ImageFormat::Png).expect("PNG encoding to memory");
    png
}

/// The height cross texture `k` texels wide (see the module doc) of a SIZE x SIZE height map,
/// rows along v, wrapping as the texture repeats.
fn height_cross(heights: &[u8], k: usize) -> Vec<u8> {
    let n = SIZE as usize;
    let h = |u: usize, v: usize| i32::from(heights[(v % n) * n + u % n]);
    let biased = |x: i32| u8::try_from(x + 128).expect("the generated heights change by less than 128 over a height cross");
    let mut rgba = Vec::with_capacity(n * n * 4);
    for v in 0..n {
        for u in 0..n {
            let (left, right, down, up) = (h(u + n - k, v), h(u + k, v), h(u, v + n - k), h(u, v + k));
            rgba.extend_from_slice(&[
                biased(right - left),
                biased(up - down),
                heights[v * n + u],
                biased(left + right + down + up - 4 * h(u, v)),
            ]);
        }
    }
    rgba
}

/// Linear filtering and repeat, for OptiFine's custom-texture loader (every generated texture).
pub const WATER_TEXTURE_META: &str = "{\"texture\": {\"blur\": true, \"clamp\": false}}\n";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn texture_is_deterministic_and_tiles() {
        let a = water_texture();
        assert_eq!(a.png, water_texture().png);
        let image = image::load_from_memory(&a.png).unwrap().to_rgba8();
        assert_eq!(image.dimensions(), (SIZE, SIZE));
        // Whole cycles across the texture: the first column continues the last one smoothly.
        let last = SIZE - 1;
        for y in (0..SIZE).step_by(17) {
            let (left, right) = (image.get_pixel(0, y)[0] as i32, image.get_pixel(last, y)[0] as i32);
            assert!((left - right).abs() < 24, "row {y}: {left} vs {right}");
        }
        // Heights span the whole range.
        let reds: Vec<u8> = image.pixels().map(|p| p[0]).collect();
        assert_eq!((reds.iter().min(), reds.iter().max()), (Some(&0), Some(&255)));
    }

    /// G and B are the height at twice and four times its frequency: G at a texel is close to
    /// the mean of R's 2x2 texels around twice its coordinates (texel centres (i + 0.5) / SIZE go
    /// to (2i + 1) / SIZE, between texels 2i and 2i + 1), and B to G's likewise.
    #[test]
    fn green_and_blue_are_the_heights_octaves() {
        let t = water_texture();
        let image = image::load_from_memory(&t.png).unwrap().to_rgba8();
        let channel = |c: usize, x: u32, y: u32| image.get_pixel(x % SIZE, y % SIZE)[c] as f64;
        for c in [1, 2] {
            let mut worst = 0.0f64;
            for k in 0..400u32 {
                let (x, y) = ((k * 37) % SIZE, (k * 91) % SIZE);
                let below = |u, v| channel(c - 1, u, v);
                let mean = (below(2 * x, 2 * y) + below(2 * x + 1, 2 * y) + below(2 * x, 2 * y + 1) + below(2 * x + 1, 2 * y + 1)) / 4.0;
                worst = worst.max((channel(c, x, y) - mean).abs());
            }
            assert!(worst < 12.0, "channel {c} differs from the octave below at twice the coordinates by {worst}");
        }
    }
}
