//! What shaders.properties directs, key by key, over the entries [`crate::properties`] reads:
//! blend modes, alpha tests, buffer flips, custom textures, and the names custom uniforms,
//! textures and images add to a program's namespace. `program.<name>.enabled` is read by
//! [`crate::custom_uniforms::program_switches`]; profiles by [`crate::option_space`].

use std::collections::{BTreeMap, BTreeSet};

use crate::buffers::colour_buffer_number;
use crate::properties::Properties;

/// A blend mode from shaders.properties: `off` or four factors.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Blend {
    Off,
    Factors([BlendFactor; 4]),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BlendFactor {
    Zero,
    One,
    SrcColor,
    OneMinusSrcColor,
    DstColor,
    OneMinusDstColor,
    SrcAlpha,
    OneMinusSrcAlpha,
    DstAlpha,
    OneMinusDstAlpha,
}

impl BlendFactor {
    fn parse(name: &str) -> Option<BlendFactor> {
        use BlendFactor::*;
        Some(match name {
            "ZERO" => Zero,
            "ONE" => One,
            "SRC_COLOR" => SrcColor,
            "ONE_MINUS_SRC_COLOR" => OneMinusSrcColor,
            "DST_COLOR" => DstColor,
            "ONE_MINUS_DST_COLOR" => OneMinusDstColor,
            "SRC_ALPHA" => SrcAlpha,
            "ONE_MINUS_SRC_ALPHA" => OneMinusSrcAlpha,
            "DST_ALPHA" => DstAlpha,
            "ONE_MINUS_DST_ALPHA" => OneMinusDstAlpha,
            _ => return None,
        })
    }
}

/// OptiFine's default blending of translucent gbuffers programs.
pub const DEFAULT_TRANSLUCENT_BLEND: Blend =
    Blend::Factors([BlendFactor::SrcAlpha, BlendFactor::OneMinusSrcAlpha, BlendFactor::One, BlendFactor::OneMinusSrcAlpha]);

/// The blend mode of each colour buffer `program` writes: `blend.<program>=` for all of them,
/// `blend.<program>.colortexN=` for one, the per-buffer ones only for a loader that reads
/// them (`per_buffer_blend`). An entry that cannot be read is an error naming it.
pub fn blend_modes(properties: &Properties, program: &str, per_buffer_blend: bool) -> Result<BTreeMap<u8, Blend>, String> {
    let mut program_wide = None;
    let mut per_buffer = BTreeMap::new();
    for (rest, entry) in properties.with_prefix("blend.") {
        let Some(buffer) = rest.strip_prefix(program) else { continue };
        if !buffer.is_empty() && !buffer.starts_with('.') {
            continue;
        }
        let value = entry.value.trim();
        let blend = if value == "off" {
            Blend::Off
        } else {
            let factors: Vec<BlendFactor> = value.split_whitespace().filter_map(BlendFactor::parse).collect();
            let factors: [BlendFactor; 4] =
                factors.try_into().map_err(|_| format!("{}={value}: expected off or four blend factors", entry.key))?;
            Blend::Factors(factors)
        };
        if buffer.is_empty() {
            program_wide = Some(blend);
        } else if !per_buffer_blend {
            continue;
        } else if let Some(number) = buffer.strip_prefix(".colortex").and_then(|n| n.parse::<u8>().ok()) {
            per_buffer.insert(number, blend);
        } else {
            return Err(format!("{}: per-buffer blend modes are read as blend.{program}.colortexN", entry.key));
        }
    }
    let mut modes = BTreeMap::new();
    for buffer in 0..16u8 {
        if let Some(b) = per_buffer.get(&buffer).cloned().or_else(|| program_wide.clone()) {
            modes.insert(buffer, b);
        }
    }
    Ok(modes)
}

/// The alpha test that applies to `program`: `alphaTest.<program>` in shaders.properties
/// (`off`, or `GREATER <ref>`), else the loader's `default`. Other comparison functions are
/// an error naming the entry.
pub fn alpha_test(properties: &Properties, program: &str, default: Option<f32>) -> Result<Option<f32>, String> {
    let key = format!("alphaTest.{program}");
    let Some(entry) = properties.get(&key) else { return Ok(default) };
    match entry.value.as_str() {
        "off" | "false" => Ok(None),
        value => {
            let mut words = value.split_whitespace();
            match (words.next(), words.next().and_then(|r| r.parse::<f32>().ok()), words.next()) {
                (Some("GREATER"), Some(reference), None) => Ok(Some(reference)),
                _ => Err(format!("{key}={value}: only off and GREATER <ref> are imitated")),
            }
        }
    }
}

/// `flip.<program>.<buffer>=true|false`: by program, by buffer number. Entries whose buffer or
/// value cannot be read come back as messages naming them.
pub fn flips(properties: &Properties) -> (BTreeMap<String, BTreeMap<u8, bool>>, Vec<String>) {
    let mut flips: BTreeMap<String, BTreeMap<u8, bool>> = BTreeMap::new();
    let mut unreadable = Vec::new();
    for (rest, entry) in properties.with_prefix("flip.") {
        let parsed = rest.rsplit_once('.').and_then(|(program, buffer)| Some((program, colour_buffer_number(buffer)?, entry.value.parse::<bool>().ok()?)));
        match parsed {
            Some((program, buffer, flip)) => {
                flips.entry(program.to_string()).or_default().insert(buffer, flip);
            }
            None => unreadable.push(format!("shaders.properties:{}: {}={}: expected flip.<program>.<buffer>=true|false", entry.line, entry.key, entry.value)),
        }
    }
    (flips, unreadable)
}

/// A `texture.<stage>.<unit>=<path>` entry.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TextureEntry {
    pub key: String,
    /// `gbuffers`, `composite`, `deferred`, `shadowcomp`, `prepare`, …
    pub stage: String,
    /// The sampler name or unit it replaces (`colortex7`, `noisetex`, `gaux1`).
    pub unit: String,
    /// The path inside `shaders/` (a leading `/` dropped, `a/../b` folded).
    pub path: String,
    /// Words after the path: a raw texture's type, format and size ([`RawLayout::parse`]).
    pub raw: Vec<String>,
    /// A path that names a resource outside the pack (`minecraft:textures/…`).
    pub resource: bool,
}

/// Every `texture.<stage>.<unit>` entry, in file order.
pub fn textures(properties: &Properties) -> Vec<TextureEntry> {
    properties
        .with_prefix("texture.")
        .filter_map(|(rest, entry)| {
            let (stage, unit) = rest.split_once('.')?;
            // `.0` to `.9` after the unit only keep the keys apart.
            let unit = match unit.rsplit_once('.') {
                Some((unit, index)) if index.len() == 1 && index.as_bytes()[0].is_ascii_digit() => unit,
                _ => unit,
            };
            let mut words = entry.value.split_whitespace();
            let written = words.next().unwrap_or("");
            Some(TextureEntry {
                key: entry.key.clone(),
                stage: stage.to_string(),
                unit: unit.to_string(),
                path: normalise_pack_path(written),
                raw: words.map(str::to_string).collect(),
                resource: written.contains(':'),
            })
        })
        .collect()
}

/// The texture target a raw texture is made as (`TEXTURE_3D`); the sampler type that reads it
/// follows (`sampler3D`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TextureTarget {
    D1,
    D2,
    D3,
    Rectangle,
}

/// How a raw texture's texels are stored: the storage of its internal format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TexelStorage {
    Unorm8,
    Snorm8,
    Unorm16,
    Snorm16,
    Half,
    Float,
}

/// How the file's bytes hold a pixel: the pixel type's component.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PixelComponent {
    Byte,
    UnsignedByte,
    Short,
    UnsignedShort,
    Int,
    UnsignedInt,
    Half,
    Float,
}

impl PixelComponent {
    pub fn bytes(self) -> usize {
        match self {
            PixelComponent::Byte | PixelComponent::UnsignedByte => 1,
            PixelComponent::Short | PixelComponent::UnsignedShort | PixelComponent::Half => 2,
            PixelComponent::Int | PixelComponent::UnsignedInt | PixelComponent::Float => 4,
        }
    }
}

/// A raw texture's layout from `<type> <internalFormat> <dimensions> <pixelFormat>
/// <pixelType>` (OptiFine's shaders.properties, "Raw textures"; Iris reads the same words).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RawLayout {
    pub target: TextureTarget,
    /// Width, height (1 for TEXTURE_1D) and depth (1 but for TEXTURE_3D).
    pub size: [u32; 3],
    /// The internal format's channels (1 to 4, red first) and storage.
    pub channels: usize,
    pub storage: TexelStorage,
    /// For each component of a pixel in the file, in file order, the RGBA channel it fills
    /// (`BGR` is `[2, 1, 0]`).
    pub pixel_order: Vec<usize>,
    pub component: PixelComponent,
}

impl RawLayout {
    /// Reads the words after a raw texture's path. Integer formats and packed pixel types are
    /// refused with what is not read.
    pub fn parse(words: &[String]) -> Result<RawLayout, String> {
        let words: Vec<&str> = words.iter().map(String::as_str).collect();
        let (target, dimensions) = match words.first() {
            Some(&"TEXTURE_1D") => (TextureTarget::D1, 1),
            Some(&"TEXTURE_2D") => (TextureTarget::D2, 2),
            Some(&"TEXTURE_3D") => (TextureTarget::D3, 3),
            Some(&"TEXTURE_RECTANGLE") => (TextureTarget::Rectangle, 2),
            Some(other) => return Err(format!("`{other}` is not a texture type: TEXTURE_1D, TEXTURE_2D, TEXTURE_3D or TEXTURE_RECTANGLE")),
            None => return Err("a raw texture needs its type, internal format, size, pixel format and pixel type".into()),
        };
        if words.len() != 4 + dimensions {
            return Err(format!("a {} needs {} words after the path (type, internal format, {dimensions} sizes, pixel format, pixel type), not {}", words[0], 4 + dimensions, words.len()));
        }
        let (channels, storage) = internal_format(words[1])?;
        let mut size = [1u32; 3];
        for (k, word) in words[2..2 + dimensions].iter().enumerate() {
            size[k] = word.parse().ok().filter(|&n| n > 0).ok_or_else(|| format!("`{word}` is not a texture size"))?;
        }
        let pixel_order = match words[2 + dimensions] {
            "RED" => vec![0],
            "RG" => vec![0, 1],
            "RGB" => vec![0, 1, 2],
            "BGR" => vec![2, 1, 0],
            "RGBA" => vec![0, 1, 2, 3],
            "BGRA" => vec![2, 1, 0, 3],
            other if other.ends_with("_INTEGER") => return Err(format!("integer pixel format {other} is not read")),
            other => return Err(format!("`{other}` is not a pixel format: RED, RG, RGB, BGR, RGBA or BGRA")),
        };
        let component = match words[3 + dimensions] {
            "BYTE" => PixelComponent::Byte,
            "UNSIGNED_BYTE" => PixelComponent::UnsignedByte,
            "SHORT" => PixelComponent::Short,
            "UNSIGNED_SHORT" => PixelComponent::UnsignedShort,
            "INT" => PixelComponent::Int,
            "UNSIGNED_INT" => PixelComponent::UnsignedInt,
            "HALF_FLOAT" => PixelComponent::Half,
            "FLOAT" => PixelComponent::Float,
            other => return Err(format!("pixel type {other} is not read (packed pixel types are not)")),
        };
        Ok(RawLayout { target, size, channels, storage, pixel_order, component })
    }

    /// Bytes the file must hold: every pixel, rows tightly packed.
    pub fn file_bytes(&self) -> u64 {
        self.texels() * (self.pixel_order.len() * self.component.bytes()) as u64
    }

    pub fn texels(&self) -> u64 {
        self.size.iter().map(|&n| u64::from(n)).product()
    }
}

/// The channels and storage of an internal format name of a raw texture.
fn internal_format(name: &str) -> Result<(usize, TexelStorage), String> {
    use crate::texture_formats::{Component, TextureFormat};
    let format = TextureFormat::parse(name).ok_or_else(|| format!("`{name}` is not a texture format"))?;
    let storage = match format {
        TextureFormat::Uniform { bits: 8, component: Component::Unorm, .. } => TexelStorage::Unorm8,
        TextureFormat::Uniform { bits: 8, component: Component::Snorm, .. } => TexelStorage::Snorm8,
        TextureFormat::Uniform { bits: 16, component: Component::Unorm, .. } => TexelStorage::Unorm16,
        TextureFormat::Uniform { bits: 16, component: Component::Snorm, .. } => TexelStorage::Snorm16,
        TextureFormat::Uniform { bits: 16, component: Component::Float, .. } => TexelStorage::Half,
        TextureFormat::Uniform { bits: 32, component: Component::Float, .. } => TexelStorage::Float,
        _ if format.is_integer() => return Err(format!("integer texture format {name} is not read")),
        _ => return Err(format!("texture format {name} is not read")),
    };
    Ok((usize::from(format.channels()), storage))
}

/// A texture path of shaders.properties as a path inside `shaders/`: a leading `/` dropped,
/// `a/../b` folded (`../shaders/x` and `/../shaders/x` climb out of `shaders/` and back in).
fn normalise_pack_path(path: &str) -> String {
    let mut parts: Vec<&str> = Vec::new();
    let mut climbed_out = false;
    for part in path.trim_start_matches('/').split('/') {
        match part {
            "" | "." => {}
            ".." => {
                climbed_out |= parts.pop().is_none();
            }
            "shaders" if parts.is_empty() && climbed_out => climbed_out = false,
            other => parts.push(other),
        }
    }
    parts.join("/")
}

/// The names shaders.properties adds to what a program may declare.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct CustomNames {
    /// `uniform.<type>.<name>` and `variable.<type>.<name>`: name → type.
    pub uniforms: BTreeMap<String, String>,
    /// Sampler names of `customTexture.<name>` (Iris) and of `image.<name>` (Iris custom images).
    pub samplers: BTreeSet<String>,
    /// Image names of `image.<name> = <sampler> <format> …` (Iris).
    pub images: BTreeSet<String>,
}

pub fn custom_names(properties: &Properties) -> CustomNames {
    let mut names = CustomNames::default();
    for entry in properties.entries() {
        let key = entry.key.as_str();
        if let Some(rest) = key.strip_prefix("uniform.").or_else(|| key.strip_prefix("variable.")) {
            if let Some((ty, name)) = rest.split_once('.') {
                names.uniforms.insert(name.to_string(), ty.to_string());
            }
        } else if let Some(name) = key.strip_prefix("customTexture.") {
            names.samplers.insert(name.to_string());
        } else if let Some(name) = key.strip_prefix("image.") {
            names.images.insert(name.to_string());
            if let Some(sampler) = entry.value.split_whitespace().next() {
                names.samplers.insert(sampler.to_string());
            }
        }
    }
    names
}

/// An Iris custom image (`image.<name> = <sampler> <format> <internalFormat> <pixelType>
/// <clear> <relative> <width> <height> [<depth>]`, IrisShaders/Iris `ShaderProperties`): a
/// texture programs store into through the image uniform `name` and read through the sampler
/// `sampler`.
#[derive(Clone, Debug, PartialEq)]
pub struct CustomImage {
    pub name: String,
    /// `none` gives none.
    pub sampler: Option<String>,
    /// The internal format as written (`RGBA16F`, `R32UI`).
    pub internal_format: String,
    /// Whether the loader clears it every frame.
    pub clear: bool,
    pub size: ImageSize,
    /// The line of shaders.properties.
    pub line: u32,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ImageSize {
    /// A share of the frame's width and height.
    Relative([f32; 2]),
    /// Texels: a 1D image has no height, a 2D one no depth (0 there).
    Absolute { width: u32, height: u32, depth: u32 },
}

/// Iris's limit on custom images.
pub const MAX_CUSTOM_IMAGES: usize = 16;

/// Every `image.` entry of shaders.properties, in the order written, and why each one that
/// cannot be read is not (Iris logs those and skips them).
pub fn custom_images(properties: &Properties) -> (Vec<CustomImage>, Vec<String>) {
    let (mut images, mut problems) = (Vec::new(), Vec::new());
    for entry in properties.entries() {
        let Some(name) = entry.key.strip_prefix("image.") else { continue };
        let parts: Vec<&str> = entry.value.split_whitespace().collect();
        let number = |i: usize| parts.get(i).and_then(|p| p.parse::<f32>().ok());
        let relative = parts.get(5).is_some_and(|p| p.eq_ignore_ascii_case("true"));
        let size = match (relative, parts.len()) {
            (true, 8..) => number(6).zip(number(7)).map(|(w, h)| ImageSize::Relative([w, h])),
            (false, 7..=9) => {
                let texels = |i: usize| if i < parts.len() { number(i).map(|n| n.max(0.0) as u32) } else { Some(0) };
                match (texels(6), texels(7), texels(8)) {
                    (Some(width), Some(height), Some(depth)) => Some(ImageSize::Absolute { width, height, depth }),
                    _ => None,
                }
            }
            _ => None,
        };
        let Some(size) = size else {
            problems.push(format!("shaders.properties:{}: image.{name}: `{}` gives no size Iris reads; the image is not made", entry.line, entry.value));
            continue;
        };
        if images.len() == MAX_CUSTOM_IMAGES {
            problems.push(format!("shaders.properties:{}: image.{name}: past Iris's {MAX_CUSTOM_IMAGES} custom images; Iris skips it", entry.line));
            continue;
        }
        images.push(CustomImage {
            name: name.to_string(),
            sampler: parts.first().filter(|s| **s != "none").map(|s| s.to_string()),
            internal_format: parts.get(2).unwrap_or(&"").to_string(),
            clear: parts.get(4).is_some_and(|p| p.eq_ignore_ascii_case("true")),
            size,
            line: entry.line,
        });
    }
    (images, problems)
}

/// An Iris shader storage buffer (`bufferObject.<index> = <bytes>`, or `= <bytes per pixel>
/// <relative> <scale x> <scale y>`, IrisShaders/Iris `ShaderProperties`): zero-filled, bound at
/// binding `index` for every program, kept across the frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BufferObject {
    pub index: u32,
    pub size: BufferObjectSize,
    /// Its line in shaders.properties.
    pub line: u32,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BufferObjectSize {
    Bytes(u64),
    /// Bytes per pixel of a frame scaled by these.
    PerPixel { bytes: u64, scale: [f32; 2] },
}

impl BufferObject {
    /// Its size in bytes for a frame of `width` x `height`, as Iris computes it.
    pub fn bytes(&self, width: u32, height: u32) -> u64 {
        match self.size {
            BufferObjectSize::Bytes(bytes) => bytes,
            BufferObjectSize::PerPixel { bytes, scale: [x, y] } => (width as f32 * x) as u64 * (height as f32 * y) as u64 * bytes,
        }
    }
}

/// Iris's highest buffer object index.
pub const MAX_BUFFER_OBJECT_INDEX: u32 = 8;

/// Every `bufferObject.` entry of shaders.properties Iris makes, and why each other one is not
/// (Iris logs those and skips them; a size below 1 turns the buffer off).
pub fn buffer_objects(properties: &Properties) -> (Vec<BufferObject>, Vec<String>) {
    let (mut buffers, mut problems) = (Vec::new(), Vec::new());
    for entry in properties.entries() {
        let Some(index) = entry.key.strip_prefix("bufferObject.") else { continue };
        let parts: Vec<&str> = entry.value.split_whitespace().collect();
        let bytes = parts.first().and_then(|b| b.parse::<i64>().ok());
        let scale = |i: usize| parts.get(i).and_then(|p| p.parse::<f32>().ok());
        let size = match (bytes, parts.len()) {
            (Some(b), 1..=2) => Some((b, BufferObjectSize::Bytes(b.max(0) as u64))),
            (Some(b), _) if parts[1].eq_ignore_ascii_case("true") => {
                scale(2).zip(scale(3)).map(|(x, y)| (b, BufferObjectSize::PerPixel { bytes: b.max(0) as u64, scale: [x, y] }))
            }
            (Some(b), _) => Some((b, BufferObjectSize::Bytes(b.max(0) as u64))),
            _ => None,
        };
        match (index.parse::<u32>().ok().filter(|i| *i <= MAX_BUFFER_OBJECT_INDEX), size) {
            (Some(_), Some((bytes, _))) if bytes < 1 => {}
            (Some(index), Some((_, size))) => buffers.push(BufferObject { index, size, line: entry.line }),
            _ => problems.push(format!(
                "shaders.properties:{}: bufferObject.{index} = {}: not an index up to {MAX_BUFFER_OBJECT_INDEX} and a size Iris reads; Iris makes no buffer",
                entry.line, entry.value
            )),
        }
    }
    (buffers, problems)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn buffer_objects_fixed_relative_off_and_unreadable() {
        let p = Properties::parse_plain("bufferObject.0=16384\nbufferObject.1=4 true 1.0 0.5\nbufferObject.2=0\nbufferObject.9=64\n");
        let (buffers, problems) = buffer_objects(&p);
        assert_eq!(buffers.len(), 2);
        assert_eq!(buffers[0].bytes(640, 360), 16384);
        assert_eq!((buffers[1].index, buffers[1].bytes(640, 360)), (1, 4 * 640 * 180));
        assert_eq!(problems.len(), 1);
        assert!(problems[0].starts_with("shaders.properties:4: bufferObject.9"), "{problems:?}");
    }

    #[test]
    fn custom_images_relative_and_absolute_and_one_without_a_size() {
        let p = Properties::parse_plain(
            "image.imgDepth = texDepth RED R16F HALF_FLOAT false true 0.5 0.5\nimage.voxels = none RGBA RGBA8 UNSIGNED_BYTE true false 64 32 16\nimage.broken = s RGBA RGBA8 UNSIGNED_BYTE true false\n",
        );
        let (images, problems) = custom_images(&p);
        assert_eq!(images.len(), 2);
        assert_eq!(images[0].sampler.as_deref(), Some("texDepth"));
        assert_eq!((images[0].internal_format.as_str(), images[0].clear, images[0].size), ("R16F", false, ImageSize::Relative([0.5, 0.5])));
        assert_eq!((images[1].sampler.clone(), images[1].size), (None, ImageSize::Absolute { width: 64, height: 32, depth: 16 }));
        assert_eq!(problems.len(), 1);
        assert!(problems[0].starts_with("shaders.properties:3: image.broken"), "{problems:?}");
    }

    #[test]
    fn raw_texture_layouts_and_an_index_after_the_unit() {
        let p = Properties::parse_plain(
            "texture.deferred.colortex10.1 = image/curl.dat TEXTURE_3D RGB8 32 16 8 BGR UNSIGNED_BYTE\ntexture.composite.gaux1=lut.dat TEXTURE_1D RGBA32F 256 RGBA FLOAT\n",
        );
        let entries = textures(&p);
        assert_eq!((entries[0].unit.as_str(), entries[0].path.as_str()), ("colortex10", "image/curl.dat"));
        let curl = RawLayout::parse(&entries[0].raw).unwrap();
        assert_eq!((curl.target, curl.size, curl.channels, curl.storage), (TextureTarget::D3, [32, 16, 8], 3, TexelStorage::Unorm8));
        assert_eq!((curl.pixel_order.clone(), curl.file_bytes()), (vec![2, 1, 0], 32 * 16 * 8 * 3));
        for written in ["/../shaders/lib/a.bin", "../shaders/lib/a.bin", "lib/x/../a.bin", "/lib/./a.bin"] {
            assert_eq!(normalise_pack_path(written), "lib/a.bin", "{written}");
        }
        let lut = RawLayout::parse(&entries[1].raw).unwrap();
        assert_eq!((lut.target, lut.size, lut.storage, lut.file_bytes()), (TextureTarget::D1, [256, 1, 1], TexelStorage::Float, 256 * 16));
        let words = |text: &str| text.split_whitespace().map(str::to_string).collect::<Vec<_>>();
        assert!(RawLayout::parse(&words("TEXTURE_2D R32UI 4 4 RED_INTEGER UNSIGNED_INT")).unwrap_err().contains("integer"));
        assert!(RawLayout::parse(&words("TEXTURE_3D RGBA8 4 4 RGBA UNSIGNED_BYTE")).unwrap_err().contains("needs 7 words"));
        assert!(RawLayout::parse(&words("TEXTURE_2D RGBA8 0 4 RGBA UNSIGNED_BYTE")).unwrap_err().contains("not a texture size"));
    }

    #[test]
    fn blend_modes_per_program_and_buffer() {
        let p = Properties::parse_plain("blend.gbuffers_water=SRC_ALPHA ONE_MINUS_SRC_ALPHA ONE ZERO\nblend.gbuffers_water.colortex4=off\nblend.gbuffers_water_x=off\n");
        let modes = blend_modes(&p, "gbuffers_water", true).unwrap();
        assert_eq!(modes[&4], Blend::Off);
        assert!(matches!(modes[&0], Blend::Factors([BlendFactor::SrcAlpha, ..])));
        assert!(matches!(blend_modes(&p, "gbuffers_water", false).unwrap()[&4], Blend::Factors(_)));
        let bad = Properties::parse_plain("blend.composite=ONE\n");
        assert!(blend_modes(&bad, "composite", true).unwrap_err().contains("four blend factors"));
    }

    #[test]
    fn alpha_tests_flips_and_textures() {
        let p = Properties::parse_plain(
            "alphaTest.gbuffers_water=GREATER 0.5\nalphaTest.gbuffers_terrain=off\nalphaTest.gbuffers_hand=LESS 0.1\n\
             flip.composite.colortex0=false\nflip.composite1.gaux2 = true\nflip.composite2.colortex1=maybe\n\
             texture.composite.colortex7=/textures/water.png\ntexture.noise=x.png\ntexture.gbuffers.gaux1=minecraft:textures/x.png\n",
        );
        assert_eq!(alpha_test(&p, "gbuffers_water", None), Ok(Some(0.5)));
        assert_eq!(alpha_test(&p, "gbuffers_terrain", Some(0.1)), Ok(None));
        assert_eq!(alpha_test(&p, "gbuffers_basic", Some(0.1)), Ok(Some(0.1)));
        assert!(alpha_test(&p, "gbuffers_hand", None).is_err());
        let (flips, unreadable) = flips(&p);
        assert_eq!(flips["composite"][&0], false);
        assert_eq!(flips["composite1"][&5], true);
        assert_eq!(unreadable.len(), 1);
        assert!(unreadable[0].starts_with("shaders.properties:6:"), "{unreadable:?}");
        let textures = textures(&p);
        assert_eq!(textures.len(), 2);
        assert_eq!((textures[0].stage.as_str(), textures[0].unit.as_str(), textures[0].path.as_str()), ("composite", "colortex7", "textures/water.png"));
        assert!(textures[1].resource);
    }

    #[test]
    fn custom_names_of_uniforms_textures_and_images() {
        let p = Properties::parse_plain("uniform.float.fadeIn = 1\nvariable.vec2.v = vec2(1, 2)\ncustomTexture.noiseTex = n.png\nimage.imgDepth = texDepth RED R16F HALF_FLOAT false true 0.5 0.5\n");
        let names = custom_names(&p);
        assert_eq!(names.uniforms.get("fadeIn").map(String::as_str), Some("float"));
        assert!(names.samplers.contains("noiseTex") && names.samplers.contains("texDepth"));
        assert!(names.images.contains("imgDepth"));
    }
}
