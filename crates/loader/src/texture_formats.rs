//! The texture formats a pack names: a colour buffer's `colortexNFormat`, a raw custom texture's
//! internal format and an Iris custom image's. One table for all three: OptiFine's shaders.txt
//! ("Texture Formats"), and Iris's `InternalTextureFormat`, which adds `RGBA` and reads a name
//! in any case.

/// What each component of a format holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Component {
    /// Unsigned normalised: 0..1.
    Unorm,
    /// Signed normalised: -1..1.
    Snorm,
    Float,
    Int,
    Uint,
}

/// A format of the table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TextureFormat {
    /// `channels` components of `bits` bits each, all of one kind (`RG16F`: 2 of 16, floats).
    Uniform { channels: u8, bits: u8, component: Component },
    /// The mixed formats, unsigned normalised but for the two float ones.
    R3G3B2,
    Rgb5A1,
    Rgb10A2,
    R11fG11fB10f,
    Rgb9E5,
}

impl TextureFormat {
    /// The format named `name` (`RGBA16F`, `r32ui`), if the loaders know it.
    pub fn parse(name: &str) -> Option<TextureFormat> {
        use Component::*;
        let name = name.to_ascii_uppercase();
        Some(match name.as_str() {
            "RGBA" => TextureFormat::Uniform { channels: 4, bits: 8, component: Unorm },
            "R3_G3_B2" => TextureFormat::R3G3B2,
            "RGB5_A1" => TextureFormat::Rgb5A1,
            "RGB10_A2" => TextureFormat::Rgb10A2,
            "R11F_G11F_B10F" => TextureFormat::R11fG11fB10f,
            "RGB9_E5" => TextureFormat::Rgb9E5,
            _ => {
                let (channels, rest) = ["RGBA", "RGB", "RG", "R"].iter().find_map(|prefix| Some((prefix.len() as u8, name.strip_prefix(prefix)?)))?;
                let (bits, component) = match rest {
                    "8" => (8, Unorm),
                    "8_SNORM" => (8, Snorm),
                    "8I" => (8, Int),
                    "8UI" => (8, Uint),
                    "16" => (16, Unorm),
                    "16_SNORM" => (16, Snorm),
                    "16F" => (16, Float),
                    "16I" => (16, Int),
                    "16UI" => (16, Uint),
                    "32F" => (32, Float),
                    "32I" => (32, Int),
                    "32UI" => (32, Uint),
                    _ => return None,
                };
                TextureFormat::Uniform { channels, bits, component }
            }
        })
    }

    pub fn channels(self) -> u8 {
        match self {
            TextureFormat::Uniform { channels, .. } => channels,
            TextureFormat::Rgb5A1 | TextureFormat::Rgb10A2 => 4,
            TextureFormat::R3G3B2 | TextureFormat::R11fG11fB10f | TextureFormat::Rgb9E5 => 3,
        }
    }

    /// Whether it holds integers, read through integer samplers and never filtered.
    pub fn is_integer(self) -> bool {
        matches!(self, TextureFormat::Uniform { component: Component::Int | Component::Uint, .. })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_tables_names_in_any_case_and_nothing_else() {
        use Component::*;
        assert_eq!(TextureFormat::parse("RGBA16F"), Some(TextureFormat::Uniform { channels: 4, bits: 16, component: Float }));
        assert_eq!(TextureFormat::parse("rg8_snorm"), Some(TextureFormat::Uniform { channels: 2, bits: 8, component: Snorm }));
        assert_eq!(TextureFormat::parse("RGB32UI"), Some(TextureFormat::Uniform { channels: 3, bits: 32, component: Uint }));
        assert_eq!(TextureFormat::parse("RGBA"), Some(TextureFormat::Uniform { channels: 4, bits: 8, component: Unorm }));
        assert_eq!(TextureFormat::parse("RGB9_E5").map(TextureFormat::channels), Some(3));
        for unknown in ["RGB", "RGBA64UI", "RGB12", "R32", "R8F", "DEPTH24"] {
            assert_eq!(TextureFormat::parse(unknown), None, "{unknown}");
        }
        assert!(TextureFormat::parse("R16I").is_some_and(TextureFormat::is_integer));
        assert!(!TextureFormat::parse("RGB10_A2").is_some_and(TextureFormat::is_integer));
    }
}
