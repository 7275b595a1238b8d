//! Raw custom textures (`texture.<stage>.<unit>=<path> TEXTURE_3D RGB8 64 64 64 RGB
//! UNSIGNED_BYTE`): the file's bytes turned into the texels OpenGL stores when the loader
//! uploads them with that internal format, pixel format and pixel type.

use tidepack_loader::directives::{PixelComponent, RawLayout, TexelStorage};

/// Most texels a raw texture may have: 2²⁵ (a 256³ noise volume is 2²⁴).
pub const MAX_RAW_TEXTURE_TEXELS: u64 = 1 << 25;

/// A custom texture's texels, four channels each, the first row of the file first.
#[derive(Clone, Debug, PartialEq)]
pub enum Texels {
    /// 8-bit unsigned normalised channels, exactly as stored.
    Rgba8(Vec<u8>),
    /// Every other storage, as the floats it reads back as.
    Float(Vec<f32>),
}

impl Texels {
    /// The bytes to upload: RGBA8 or RGBA32F.
    pub fn bytes(&self) -> &[u8] {
        match self {
            Texels::Rgba8(bytes) => bytes,
            Texels::Float(floats) => bytemuck::cast_slice(floats),
        }
    }
}

/// The texels of a raw texture whose file holds `bytes`. Each pixel is read as OpenGL reads
/// client data (little-endian; normalised integers to [0, 1] or [-1, 1]); the channels the
/// pixel format lacks, and those the internal format lacks, read 0 (alpha 1); each value is
/// then rounded to the internal format's storage.
pub fn decode(bytes: &[u8], layout: &RawLayout) -> Result<Texels, String> {
    if layout.texels() > MAX_RAW_TEXTURE_TEXELS {
        let [w, h, d] = layout.size;
        return Err(format!("is {w}x{h}x{d} texels, more than the budget of {MAX_RAW_TEXTURE_TEXELS} for a raw texture"));
    }
    if (bytes.len() as u64) < layout.file_bytes() {
        return Err(format!("holds {} bytes, fewer than the {} its size and pixel format need", bytes.len(), layout.file_bytes()));
    }
    let component_bytes = layout.component.bytes();
    let pixel_bytes = layout.pixel_order.len() * component_bytes;
    let texels = layout.texels() as usize;
    let pixel = |i: usize| {
        let mut rgba = [0.0, 0.0, 0.0, 1.0];
        for (k, &channel) in layout.pixel_order.iter().enumerate() {
            let at = i * pixel_bytes + k * component_bytes;
            rgba[channel] = component(&bytes[at..at + component_bytes], layout.component);
        }
        for (channel, value) in rgba.iter_mut().enumerate().skip(layout.channels) {
            *value = if channel == 3 { 1.0 } else { 0.0 };
        }
        rgba
    };
    Ok(match layout.storage {
        TexelStorage::Unorm8 => Texels::Rgba8((0..texels).flat_map(|i| pixel(i).map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)).collect()),
        storage => Texels::Float((0..texels).flat_map(|i| pixel(i).map(|v| stored(v, storage))).collect()),
    })
}

/// One component of a pixel as OpenGL converts it to a float.
fn component(bytes: &[u8], kind: PixelComponent) -> f32 {
    let u16_at = || u16::from_le_bytes([bytes[0], bytes[1]]);
    let u32_at = || u32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]);
    match kind {
        PixelComponent::UnsignedByte => f32::from(bytes[0]) / 255.0,
        PixelComponent::Byte => (f32::from(bytes[0] as i8) / 127.0).max(-1.0),
        PixelComponent::UnsignedShort => f32::from(u16_at()) / 65535.0,
        PixelComponent::Short => (f32::from(u16_at() as i16) / 32767.0).max(-1.0),
        PixelComponent::UnsignedInt => (f64::from(u32_at()) / f64::from(u32::MAX)) as f32,
        PixelComponent::Int => (f64::from(u32_at() as i32) / f64::from(i32::MAX)).max(-1.0) as f32,
        PixelComponent::Half => half::f16::from_bits(u16_at()).to_f32(),
        PixelComponent::Float => f32::from_bits(u32_at()),
    }
}

/// `value` as the storage keeps it.
fn stored(value: f32, storage: TexelStorage) -> f32 {
    match storage {
        TexelStorage::Unorm8 => (value.clamp(0.0, 1.0) * 255.0).round() / 255.0,
        TexelStorage::Snorm8 => (value.clamp(-1.0, 1.0) * 127.0).round() / 127.0,
        TexelStorage::Unorm16 => (value.clamp(0.0, 1.0) * 65535.0).round() / 65535.0,
        TexelStorage::Snorm16 => (value.clamp(-1.0, 1.0) * 32767.0).round() / 32767.0,
        TexelStorage::Half => half::f16::from_f32(value).to_f32(),
        TexelStorage::Float => value,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn layout(words: &str) -> RawLayout {
        RawLayout::parse(&words.split_whitespace().map(str::to_string).collect::<Vec<_>>()).unwrap()
    }

    #[test]
    fn bgr_bytes_fill_red_green_blue_and_alpha_reads_one() {
        let texels = decode(&[10, 20, 30, 40, 50, 60], &layout("TEXTURE_1D RGBA8 2 BGR UNSIGNED_BYTE")).unwrap();
        assert_eq!(texels, Texels::Rgba8(vec![30, 20, 10, 255, 60, 50, 40, 255]));
    }

    #[test]
    fn channels_the_internal_format_lacks_read_zero_and_one() {
        // RG8 from RGBA bytes keeps red and green; RGB8 drops alpha.
        assert_eq!(decode(&[1, 2, 3, 4], &layout("TEXTURE_2D RG8 1 1 RGBA UNSIGNED_BYTE")).unwrap(), Texels::Rgba8(vec![1, 2, 0, 255]));
        assert_eq!(decode(&[1, 2, 3, 4], &layout("TEXTURE_2D RGB8 1 1 RGBA UNSIGNED_BYTE")).unwrap(), Texels::Rgba8(vec![1, 2, 3, 255]));
    }

    #[test]
    fn floats_are_rounded_to_the_storage() {
        let bytes: Vec<u8> = [0.1f32, -2.0, 3.0].iter().flat_map(|v| v.to_le_bytes()).collect();
        let Texels::Float(half) = decode(&bytes, &layout("TEXTURE_3D RGB16F 1 1 1 RGB FLOAT")).unwrap() else { panic!("half storage reads as floats") };
        assert_eq!(half, vec![half::f16::from_f32(0.1).to_f32(), -2.0, 3.0, 1.0]);
        let Texels::Float(unorm) = decode(&bytes, &layout("TEXTURE_3D RGB16 1 1 1 RGB FLOAT")).unwrap() else { panic!("16-bit storage reads as floats") };
        assert_eq!(unorm, vec![(0.1f32 * 65535.0).round() / 65535.0, 0.0, 1.0, 1.0]);
        let shorts: Vec<u8> = [65535u16, 0].iter().flat_map(|v| v.to_le_bytes()).collect();
        assert_eq!(decode(&shorts, &layout("TEXTURE_2D R16 2 1 RED UNSIGNED_SHORT")).unwrap(), Texels::Float(vec![1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]));
    }

    #[test]
    fn a_short_file_and_an_absurd_size_are_refused() {
        assert!(decode(&[0; 7], &layout("TEXTURE_2D RGBA8 2 1 RGBA UNSIGNED_BYTE")).unwrap_err().contains("fewer than the 8"));
        assert!(decode(&[], &layout("TEXTURE_3D R8 4096 4096 4096 RED UNSIGNED_BYTE")).unwrap_err().contains("budget"));
    }
}
