//! Textures as the GPU samples them: texel centres at `(i + 0.5) / size`, nearest or bilinear
//! filtering, clamp-to-edge or repeat addressing, evaluated in f64.

use glam::{DVec2, DVec4};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Filter {
    Nearest,
    Linear,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Wrap {
    ClampToEdge,
    Repeat,
}

/// A texture with the sampler it is read through. Row 0 is at texture coordinate v = 0
/// (for the harness's render targets: the bottom row of the screen).
#[derive(Clone, Debug)]
pub struct Texture {
    pub width: usize,
    pub height: usize,
    pub texels: Vec<DVec4>,
    pub filter: Filter,
    pub wrap: Wrap,
}

impl Texture {
    pub fn new(width: usize, height: usize, texels: Vec<DVec4>, filter: Filter, wrap: Wrap) -> Texture {
        assert_eq!(texels.len(), width * height, "texel count must be width * height");
        Texture { width, height, texels, filter, wrap }
    }

    /// From f32 RGBA texels (a harness readback).
    pub fn from_f32(width: usize, height: usize, texels: &[[f32; 4]], filter: Filter, wrap: Wrap) -> Texture {
        let texels = texels.iter().map(|p| DVec4::from_array(p.map(f64::from))).collect();
        Texture::new(width, height, texels, filter, wrap)
    }

    /// From RGBA8 bytes (a custom texture, the noise texture): UNORM, byte / 255.
    pub fn from_rgba8(width: usize, height: usize, bytes: &[u8], filter: Filter, wrap: Wrap) -> Texture {
        let texels = bytes
            .chunks_exact(4)
            .map(|p| DVec4::new(p[0] as f64, p[1] as f64, p[2] as f64, p[3] as f64) / 255.0)
            .collect();
        Texture::new(width, height, texels, filter, wrap)
    }

    fn texel(&self, x: i64, y: i64) -> DVec4 {
        let ix = self.address(x, self.width);
        let iy = self.address(y, self.height);
        self.texels[iy * self.width + ix]
    }

    fn address(&self, i: i64, size: usize) -> usize {
        match self.wrap {
            Wrap::ClampToEdge => i.clamp(0, size as i64 - 1) as usize,
            Wrap::Repeat => i.rem_euclid(size as i64) as usize,
        }
    }

    /// GLSL `texture(sampler, uv)` without mipmaps.
    pub fn sample(&self, uv: DVec2) -> DVec4 {
        let size = DVec2::new(self.width as f64, self.height as f64);
        match self.filter {
            Filter::Nearest => {
                let p = (uv * size).floor();
                self.texel(p.x as i64, p.y as i64)
            }
            Filter::Linear => {
                let p = uv * size - 0.5;
                let base = p.floor();
                let f = p - base;
                let (x, y) = (base.x as i64, base.y as i64);
                let bottom = self.texel(x, y).lerp(self.texel(x + 1, y), f.x);
                let top = self.texel(x, y + 1).lerp(self.texel(x + 1, y + 1), f.x);
                bottom.lerp(top, f.y)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ramp(filter: Filter, wrap: Wrap) -> Texture {
        let texels = (0..4).map(|i| DVec4::splat(i as f64)).collect();
        Texture::new(4, 1, texels, filter, wrap)
    }

    #[test]
    fn texel_centres_return_the_texel() {
        for (filter, wrap) in [(Filter::Linear, Wrap::Repeat), (Filter::Nearest, Wrap::ClampToEdge), (Filter::Linear, Wrap::ClampToEdge)] {
            let t = ramp(filter, wrap);
            for i in 0..4 {
                assert_eq!(t.sample(DVec2::new((i as f64 + 0.5) / 4.0, 0.5)).x, i as f64);
            }
        }
    }

    #[test]
    fn linear_repeat_wraps_and_clamp_holds_the_edge() {
        // Halfway between the last texel (3) and the first (0) across the seam.
        assert_eq!(ramp(Filter::Linear, Wrap::Repeat).sample(DVec2::new(0.0, 0.5)).x, 1.5);
        assert_eq!(ramp(Filter::Linear, Wrap::ClampToEdge).sample(DVec2::new(0.0, 0.5)).x, 0.0);
        assert_eq!(ramp(Filter::Linear, Wrap::ClampToEdge).sample(DVec2::new(0.25, 0.5)).x, 0.5);
        assert_eq!(ramp(Filter::Nearest, Wrap::ClampToEdge).sample(DVec2::new(1.0, 0.5)).x, 3.0);
    }
}
