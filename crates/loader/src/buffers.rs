//! The buffers a loader gives a pack, as the pack names and configures them: colour buffers
//! (`colortexN` and the legacy names), shadow colour buffers, their formats and clears.

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

    /// The format a pack's format name is stored in, and whether exactly: formats the renderers
    /// lack (fewer channels, packed, signed) are stored in the RGBA format that holds every
    /// value they can (`R11F_G11F_B10F` in RGBA16F, `R32F` in RGBA32F, `RGB10_A2` in RGBA16,
    /// `R32UI` in RGBA32UI).
    pub fn stand_in(name: &str) -> Option<(BufferFormat, bool)> {
        if let Some(exact) = BufferFormat::parse(name) {
            return Some((exact, true));
        }
        let stand_in = match name {
            "R8" | "RG8" | "RGB5_A1" | "RGBA2" | "RGBA4" | "R3_G3_B2" | "R16" | "RG16" | "RGB10_A2" | "RGB12" | "RGBA12" => {
                BufferFormat::Rgba16
            }
            "R16F" | "RG16F" | "R11F_G11F_B10F" | "RGB9_E5" => BufferFormat::Rgba16F,
            // Signed normalised formats keep their negative values in a float buffer.
            "R8_SNORM" | "RG8_SNORM" | "RGB8_SNORM" | "RGBA8_SNORM" | "R16_SNORM" | "RG16_SNORM" | "RGB16_SNORM" | "RGBA16_SNORM" => {
                BufferFormat::Rgba32F
            }
            "R32F" | "RG32F" => BufferFormat::Rgba32F,
            "R8UI" | "RG8UI" | "RGB8UI" | "RGBA8UI" | "R16UI" | "RG16UI" | "RGB16UI" | "RGBA16UI" | "R32UI" | "RG32UI" | "RGB32UI" | "RGB10_A2UI" => {
                BufferFormat::Rgba32Ui
            }
            "R8I" | "RG8I" | "RGB8I" | "RGBA8I" | "R16I" | "RG16I" | "RGB16I" | "RGBA16I" | "R32I" | "RG32I" | "RGB32I" => BufferFormat::Rgba32I,
            _ => return None,
        };
        Some((stand_in, false))
    }

    /// The formats stored exactly.
    pub fn parse(name: &str) -> Option<BufferFormat> {
        Some(match name {
            "RGBA" | "RGBA8" | "RGB8" | "RGB" => BufferFormat::Rgba8,
            "RGBA16" | "RGB16" => BufferFormat::Rgba16,
            "RGBA16F" | "RGB16F" => BufferFormat::Rgba16F,
            "RGBA32F" | "RGB32F" => BufferFormat::Rgba32F,
            "RGBA32UI" => BufferFormat::Rgba32Ui,
            "RGBA32I" => BufferFormat::Rgba32I,
            _ => return None,
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
        assert_eq!(BufferFormat::stand_in("R11F_G11F_B10F"), Some((BufferFormat::Rgba16F, false)));
        assert_eq!(BufferFormat::stand_in("RGBA16F"), Some((BufferFormat::Rgba16F, true)));
        assert_eq!(BufferFormat::stand_in("R32UI"), Some((BufferFormat::Rgba32Ui, false)));
        assert_eq!(BufferFormat::stand_in("RGBA32UI"), Some((BufferFormat::Rgba32Ui, true)));
        assert_eq!(BufferFormat::stand_in("RG16I"), Some((BufferFormat::Rgba32I, false)));
        assert_eq!(BufferFormat::stand_in("RGBA64UI"), None);
    }
}
