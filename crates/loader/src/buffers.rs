//! The buffers a loader gives a pack, as the pack names and configures them: colour buffers
//! (`colortexN` and the legacy names), shadow colour buffers, their formats and clears.

use crate::texture_formats::{Component, TextureFormat};

/// The colour buffer a name refers to: `colortexN` (N < 16) or one of OptiFine's legacy names
/// for buffers 0-7 (`gcolor`, `gdepth`, `gnormal`, `composite`, `gaux1`-`gaux4`).
pub fn colour_buffer_number(name: &str) -> Option<u8> {
    const LEGACY: [&str; 8] = ["gcolor", "gdepth", "gnormal", "composite", "gaux1", "gaux2", "gaux3", "gaux4"];
    match name.strip_prefix("colortex") {
        Some(n) => n.parse::<u8>().ok().filter(|n| *n < 16),
        None => LEGACY.iter().position(|legacy| *legacy == name).map(|n| n as u8),
    }
}

/// The shadow colour buffer a name refers to: `shadowcolor` (0) or `shadowcolorN` (N < 8).
pub fn shadow_colour_number(name: &str) -> Option<u8> {
    match name.strip_prefix("shadowcolor")? {
        "" => Some(0),
        n => n.parse::<u8>().ok().filter(|n| *n < 8),
    }
}

/// A buffer read and written through an image (OptiFine's shaders.txt, "Image access").
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum ImageOf {
    /// `colorimgN`: colortexN.
    Colour(u8),
    /// `shadowcolorimgN`: shadowcolorN.
    ShadowColour(u8),
}

/// The buffer an image name refers to, if it names one.
pub fn buffer_of_image(name: &str) -> Option<ImageOf> {
    let number = |prefix: &str| name.strip_prefix(prefix)?.parse::<u8>().ok();
    number("colorimg").map(ImageOf::Colour).or_else(|| number("shadowcolorimg").map(ImageOf::ShadowColour))
}

/// The number of mip levels of a full chain for `width` x `height`, as a buffer with
/// `colortexNMipmapEnabled` gets them.
pub fn mip_levels(width: u32, height: u32) -> u32 {
    32 - width.max(height).max(1).leading_zeros()
}

/// A colour buffer format the renderers store a buffer in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BufferFormat {
    Rgba8,
    Rgba16,
    Rgba16F,
    Rgba32F,
    /// Unsigned integers, read through `usampler2D`, never filtered or blended.
    Rgba32Ui,
    /// Signed integers, read through `isampler2D`, never filtered or blended.
    Rgba32I,
}

impl BufferFormat {
    /// Whether the buffer holds integers: it is read unfiltered through an integer sampler.
    pub fn is_integer(self) -> bool {
        matches!(self, BufferFormat::Rgba32Ui | BufferFormat::Rgba32I)
    }

    /// The format a pack's format name ([`TextureFormat`]) is stored in, and whether exactly:
    /// formats the renderers lack (fewer channels, packed, signed) are stored in the RGBA format
    /// that holds every value they can (`R11F_G11F_B10F` in RGBA16F, `R32F` in RGBA32F,
    /// `RGB10_A2` in RGBA16, `R32UI` in RGBA32UI). A three-channel format is stored exactly in
    /// its four-channel one, alpha aside.
    pub fn stand_in(name: &str) -> Option<(BufferFormat, bool)> {
        use Component::*;
        Some(match TextureFormat::parse(name)? {
            TextureFormat::Uniform { channels: 3 | 4, bits: 8, component: Unorm } => (BufferFormat::Rgba8, true),
            TextureFormat::Uniform { channels: 3 | 4, bits: 16, component: Unorm } => (BufferFormat::Rgba16, true),
            TextureFormat::Uniform { channels: 3 | 4, bits: 16, component: Float } => (BufferFormat::Rgba16F, true),
            TextureFormat::Uniform { channels: 3 | 4, bits: 32, component: Float } => (BufferFormat::Rgba32F, true),
            TextureFormat::Uniform { channels: 4, bits: 32, component: Uint } => (BufferFormat::Rgba32Ui, true),
            TextureFormat::Uniform { channels: 4, bits: 32, component: Int } => (BufferFormat::Rgba32I, true),
            TextureFormat::Uniform { component: Uint, .. } => (BufferFormat::Rgba32Ui, false),
            TextureFormat::Uniform { component: Int, .. } => (BufferFormat::Rgba32I, false),
            // Signed normalised formats keep their negative values in a float buffer.
            TextureFormat::Uniform { component: Snorm, .. } | TextureFormat::Uniform { bits: 32, component: Float, .. } => (BufferFormat::Rgba32F, false),
            TextureFormat::Uniform { component: Float, .. } | TextureFormat::R11fG11fB10f | TextureFormat::Rgb9E5 => (BufferFormat::Rgba16F, false),
            TextureFormat::Uniform { component: Unorm, .. } | TextureFormat::R3G3B2 | TextureFormat::Rgb5A1 | TextureFormat::Rgb10A2 => (BufferFormat::Rgba16, false),
        })
    }
}

/// What a colour buffer is cleared to at the start of a frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BufferClear {
    /// colortex0: the fog colour; colortex1: white; the rest: transparent black.
    Default,
    /// `const vec4 colortexNClearColor = vec4(...)`.
    Color([f64; 4]),
    /// `const bool colortexNClear = false`: the previous frame's contents stay.
    Keep,
}

impl BufferClear {
    /// The RGBA colour shadowcolorN holds after the shadow pass's clear: white unless declared.
    pub fn shadow_colour(self) -> [f64; 4] {
        match self {
            BufferClear::Color(c) => c,
            BufferClear::Keep => [0.0; 4],
            BufferClear::Default => [1.0; 4],
        }
    }

    /// The RGBA colour colortex`buffer` holds after the clear under `fog_color` (a kept buffer
    /// starts transparent black in a single frame).
    pub fn colour(self, buffer: u8, fog_color: [f64; 3]) -> [f64; 4] {
        match (self, buffer) {
            (BufferClear::Color(c), _) => c,
            (BufferClear::Keep, _) => [0.0; 4],
            (BufferClear::Default, 0) => {
                let [r, g, b] = fog_color;
                [r, g, b, 1.0]
            }
            (BufferClear::Default, 1) => [1.0; 4],
            (BufferClear::Default, _) => [0.0; 4],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn buffer_names_and_formats() {
        assert_eq!(colour_buffer_number("colortex15"), Some(15));
        assert_eq!(colour_buffer_number("colortex16"), None);
        assert_eq!(colour_buffer_number("gaux2"), Some(5));
        assert_eq!(shadow_colour_number("shadowcolor"), Some(0));
        assert_eq!(shadow_colour_number("shadowcolor1"), Some(1));
        assert_eq!(buffer_of_image("colorimg3"), Some(ImageOf::Colour(3)));
        assert_eq!(buffer_of_image("shadowcolorimg1"), Some(ImageOf::ShadowColour(1)));
        assert_eq!(buffer_of_image("colorimg"), None);
        assert_eq!(buffer_of_image("voxels"), None);
        assert_eq!(BufferFormat::stand_in("R11F_G11F_B10F"), Some((BufferFormat::Rgba16F, false)));
        assert_eq!(BufferFormat::stand_in("RGBA16F"), Some((BufferFormat::Rgba16F, true)));
        assert_eq!(BufferFormat::stand_in("R32UI"), Some((BufferFormat::Rgba32Ui, false)));
        assert_eq!(BufferFormat::stand_in("RGBA32UI"), Some((BufferFormat::Rgba32Ui, true)));
        assert_eq!(BufferFormat::stand_in("RG16I"), Some((BufferFormat::Rgba32I, false)));
        assert_eq!(BufferFormat::stand_in("RGBA64UI"), None);
    }
}
