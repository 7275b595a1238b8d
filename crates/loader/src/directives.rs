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
    /// Words after the path: a raw texture's type, format and size.
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

/// A texture path of shaders.properties as a path inside `shaders/`: a leading `/` dropped,
/// `a/../b` folded (`../shaders/x` climbs out of `shaders/` and back in).
fn normalise_pack_path(path: &str) -> String {
    let mut parts: Vec<&str> = Vec::new();
    for part in path.trim_start_matches('/').split('/') {
        match part {
            "" | "." => {}
            ".." => {
                parts.pop();
            }
            "shaders" if parts.is_empty() && path.starts_with("../") => {}
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
            (Some(index), Some((_, size))) => buffers.push(BufferObject { index, size }),
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
