//! The standard macros: what a loader defines right after each stage's `#version` line (and
//! for the conditionals of its properties files), for a configurable machine (Minecraft
//! version, GL versions, OS, GPU vendor, settings) and loader ([`StandardMacros::for_loader`]:
//! OptiFine's set, or Iris's, which adds its own names and fixes the quality settings at 1).
//! This is the one set every part of the toolchain defines.

use tidepack_glsl::preprocess::{IncludeRules, PreprocessOptions};

use crate::loader::Loader;
use crate::properties::Properties;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Os {
    Windows,
    Mac,
    Linux,
    Other,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Vendor {
    Amd,
    Intel,
    Mesa,
    Nvidia,
    Other,
}

/// The machine and settings the macros describe; [`Default`] is a current Linux/Mesa setup.
#[derive(Clone, Debug, PartialEq)]
pub struct StandardMacros {
    /// `1.21.4` → 12104.
    pub mc_version: u32,
    /// `4.6` → 460.
    pub gl_version: u32,
    /// Highest GLSL version of the driver (not the shader's `#version`).
    pub glsl_version: u32,
    pub os: Os,
    pub vendor: Vendor,
    pub render_quality: f32,
    pub shadow_quality: f32,
    pub hand_depth: f32,
    /// `MC_NORMAL_MAP`, `MC_SPECULAR_MAP` (the resource pack has them).
    pub normal_and_specular_maps: bool,
    /// `MC_GL_<extension>` for each extension the driver has (OptiFine defines only those a
    /// shader mentions; defining all is equivalent for the preprocessor).
    pub extensions: Vec<String>,
    /// Iris's version (`1.8.1` → 10801) when Iris loads the pack: it adds `IS_IRIS`,
    /// `IRIS_VERSION` and its other names. `None`: OptiFine.
    pub iris_version: Option<u32>,
    /// Distant Horizons is installed beside Iris: `DISTANT_HORIZONS` is defined in every
    /// program, and Iris runs the `dh_*` programs.
    pub distant_horizons: bool,
    /// The feature flags the pack's `iris.features.optional` names that Iris and this machine
    /// support, as written: Iris defines `IRIS_FEATURE_<flag>` for each in every program
    /// ([`StandardMacros::with_optional_features`]).
    pub iris_optional_features: Vec<String>,
}

/// The Iris version whose macros `for_loader(Loader::Iris)` defines.
pub const IRIS_VERSION: u32 = 10801;

/// Iris's feature flags (`iris.features.required`/`optional`), each with whether macOS's
/// OpenGL 4.1 has what it needs (image load/store, compute shaders and SSBOs came with 4.2
/// and 4.3); every one is usable on a current Linux or Windows driver.
pub const IRIS_FEATURE_FLAGS: [(&str, bool); 10] = [
    ("SEPARATE_HARDWARE_SAMPLERS", true),
    ("HIGHER_SHADOWCOLOR", true),
    ("CUSTOM_IMAGES", false),
    ("PER_BUFFER_BLENDING", true),
    ("COMPUTE_SHADERS", false),
    ("TESSELLATION_SHADERS", true),
    ("ENTITY_TRANSLUCENT", true),
    ("REVERSED_CULLING", true),
    ("BLOCK_EMISSION_ATTRIBUTE", true),
    ("SSBO", false),
];

/// Distant Horizons' material ids Iris defines as `DH_BLOCK_*`, in value order.
pub const DH_BLOCKS: [&str; 16] = [
    "UNKNOWN", "LEAVES", "STONE", "WOOD", "METAL", "DIRT", "LAVA", "DEEPSLATE", "SNOW", "SAND", "TERRACOTTA", "NETHER_STONE", "WATER",
    "GRASS", "AIR", "ILLUMINATED",
];

impl Default for StandardMacros {
    fn default() -> Self {
        StandardMacros {
            mc_version: 12104,
            gl_version: 460,
            glsl_version: 460,
            os: Os::Linux,
            vendor: Vendor::Mesa,
            render_quality: 1.0,
            shadow_quality: 1.0,
            hand_depth: 0.125,
            normal_and_specular_maps: true,
            extensions: COMMON_EXTENSIONS.iter().map(|e| e.to_string()).collect(),
            iris_version: None,
            distant_horizons: false,
            iris_optional_features: Vec::new(),
        }
    }
}

/// Extensions a current desktop driver (Mesa 22 and later, NVIDIA, AMD) exposes that packs test.
pub const COMMON_EXTENSIONS: [&str; 14] = [
    "GL_ARB_shader_texture_lod",
    "GL_EXT_gpu_shader4",
    "GL_ARB_gpu_shader5",
    "GL_ARB_texture_gather",
    "GL_ARB_texture_query_lod",
    "GL_ARB_shading_language_packing",
    "GL_ARB_shader_bit_encoding",
    "GL_ARB_shader_image_load_store",
    "GL_ARB_shader_storage_buffer_object",
    "GL_ARB_compute_shader",
    "GL_ARB_derivative_control",
    "GL_ARB_conservative_depth",
    "GL_ARB_explicit_attrib_location",
    "GL_EXT_texture_array",
];

/// `MC_RENDER_STAGE_*` constants, in value order (0 = NONE).
pub const RENDER_STAGES: [&str; 24] = [
    "NONE",
    "SKY",
    "SUNSET",
    "CUSTOM_SKY",
    "SUN",
    "MOON",
    "STARS",
    "VOID",
    "TERRAIN_SOLID",
    "TERRAIN_CUTOUT_MIPPED",
    "TERRAIN_CUTOUT",
    "ENTITIES",
    "BLOCK_ENTITIES",
    "DESTROY",
    "OUTLINE",
    "DEBUG",
    "HAND_SOLID",
    "TERRAIN_TRANSLUCENT",
    "TRIPWIRE",
    "PARTICLES",
    "CLOUDS",
    "RAIN_SNOW",
    "WORLD_BORDER",
    "HAND_TRANSLUCENT",
];

impl StandardMacros {
    /// The macros `loader` defines on the default machine: its Minecraft version, and for Iris
    /// its own names with the quality settings fixed at 1.0 as Iris fixes them.
    pub fn for_loader(loader: Loader) -> StandardMacros {
        let mc_version = match loader {
            Loader::OptiFine1_21 | Loader::Iris => 12104,
            Loader::OptiFine1_16_5 => 11605,
            Loader::OptiFine1_12_2 => 11202,
            Loader::OptiFine1_8_9 => 10809,
        };
        let iris_version = (loader == Loader::Iris).then_some(IRIS_VERSION);
        StandardMacros { mc_version, iris_version, ..StandardMacros::default() }
    }

    /// Whether Iris on this machine can use the feature flag `name` (any case), as Iris's
    /// `FeatureFlags.isUsable` decides: an unknown name cannot be used.
    pub fn iris_feature_usable(&self, name: &str) -> bool {
        IRIS_FEATURE_FLAGS.iter().any(|(flag, on_macos)| flag.eq_ignore_ascii_case(name) && (*on_macos || self.os != Os::Mac))
    }

    /// These macros for a pack with shaders.properties `props`: under Iris, each flag of its
    /// `iris.features.optional` list that this machine can use is defined as
    /// `IRIS_FEATURE_<flag>`, spelled as the pack spells it, as Iris's `ShaderPack` defines
    /// them. OptiFine defines none.
    pub fn with_optional_features(mut self, props: &Properties) -> StandardMacros {
        self.iris_optional_features = match (self.iris_version, props.get("iris.features.optional")) {
            (Some(_), Some(entry)) => entry.value.split_whitespace().filter(|flag| self.iris_feature_usable(flag)).map(str::to_string).collect(),
            _ => Vec::new(),
        };
        self
    }

    /// The macros a properties file's conditionals see beside [`StandardMacros::definitions`]:
    /// under Iris, `IRIS_FEATURE_<FLAG>` for every flag this machine can use, whatever the pack
    /// asks for.
    pub fn property_definitions(&self) -> Vec<(String, String)> {
        let mut out = self.definitions();
        if self.iris_version.is_some() {
            let usable = IRIS_FEATURE_FLAGS.iter().filter(|(flag, _)| self.iris_feature_usable(flag));
            out.extend(usable.map(|(flag, _)| (format!("IRIS_FEATURE_{flag}"), String::new())));
        }
        out
    }

    /// The macros in the order the loader defines them.
    pub fn definitions(&self) -> Vec<(String, String)> {
        let mut out: Vec<(String, String)> = vec![
            ("MC_VERSION".into(), self.mc_version.to_string()),
            ("MC_GL_VERSION".into(), self.gl_version.to_string()),
            ("MC_GLSL_VERSION".into(), self.glsl_version.to_string()),
        ];
        let os = match self.os {
            Os::Windows => "MC_OS_WINDOWS",
            Os::Mac => "MC_OS_MAC",
            Os::Linux => "MC_OS_LINUX",
            Os::Other => "MC_OS_OTHER",
        };
        let (vendor, renderer) = match self.vendor {
            Vendor::Amd => ("MC_GL_VENDOR_AMD", "MC_GL_RENDERER_RADEON"),
            Vendor::Intel => ("MC_GL_VENDOR_INTEL", "MC_GL_RENDERER_INTEL"),
            Vendor::Mesa => ("MC_GL_VENDOR_MESA", "MC_GL_RENDERER_MESA"),
            Vendor::Nvidia => ("MC_GL_VENDOR_NVIDIA", "MC_GL_RENDERER_GEFORCE"),
            Vendor::Other => ("MC_GL_VENDOR_OTHER", "MC_GL_RENDERER_OTHER"),
        };
        for name in [os, vendor, renderer] {
            out.push((name.into(), String::new()));
        }
        for ext in &self.extensions {
            out.push((format!("MC_{ext}"), String::new()));
        }
        out.push(("MC_FXAA_LEVEL".into(), "0".into()));
        if self.normal_and_specular_maps {
            out.push(("MC_NORMAL_MAP".into(), String::new()));
            out.push(("MC_SPECULAR_MAP".into(), String::new()));
        }
        out.push(("MC_RENDER_QUALITY".into(), float(self.render_quality)));
        out.push(("MC_SHADOW_QUALITY".into(), float(self.shadow_quality)));
        out.push(("MC_HAND_DEPTH".into(), float(self.hand_depth)));
        for (value, stage) in RENDER_STAGES.iter().enumerate() {
            out.push((format!("MC_RENDER_STAGE_{stage}"), value.to_string()));
        }
        if let Some(version) = self.iris_version {
            for (name, value) in [
                ("IRIS_VERSION", version.to_string()),
                ("IS_IRIS", String::new()),
                ("MAX_COLOR_BUFFERS", "16".to_string()),
                ("IRIS_HAS_TRANSLUCENCY_SORTING", String::new()),
                ("IRIS_TAG_SUPPORT", "2".to_string()),
            ] {
                out.push((name.to_string(), value));
            }
            out.extend(BIOMES.iter().enumerate().map(|(value, name)| (format!("BIOME_{name}"), value.to_string())));
            for names in [&BIOME_CATEGORIES[..], &PRECIPITATIONS[..]] {
                out.extend(names.iter().enumerate().map(|(value, name)| (name.to_string(), value.to_string())));
            }
            for (value, block) in DH_BLOCKS.iter().enumerate() {
                out.push((format!("DH_BLOCK_{block}"), value.to_string()));
            }
            if self.distant_horizons {
                out.push(("DISTANT_HORIZONS".into(), String::new()));
            }
            out.extend(self.iris_optional_features.iter().map(|flag| (format!("IRIS_FEATURE_{flag}"), String::new())));
        }
        out
    }

    pub fn preprocess_options(&self) -> PreprocessOptions {
        PreprocessOptions { predefined: self.definitions(), include_rules: self.include_rules(), lenient: false, token_cache: None }
    }

    /// How the loader these macros stand for reads `#include` paths: Iris also without quotes.
    pub fn include_rules(&self) -> IncludeRules {
        if self.iris_version.is_some() { IncludeRules::Iris } else { IncludeRules::OptiFine }
    }

    /// The macros as `#define` lines, for text handed to a GL driver or glslangValidator.
    pub fn define_lines(&self) -> String {
        self.definitions().iter().map(|(k, v)| format!("#define {k} {v}\n")).collect()
    }
}

/// Biome categories by value: OptiFine documents the first 17 (`CAT_NONE` 0 to `CAT_NETHER` 16)
/// for custom uniforms; Iris adds `CAT_MOUNTAIN` and `CAT_UNDERGROUND`, and also defines every
/// one as a macro in the shaders.
pub const BIOME_CATEGORIES: [&str; 19] = [
    "CAT_NONE",
    "CAT_TAIGA",
    "CAT_EXTREME_HILLS",
    "CAT_JUNGLE",
    "CAT_MESA",
    "CAT_PLAINS",
    "CAT_SAVANNA",
    "CAT_ICY",
    "CAT_THE_END",
    "CAT_BEACH",
    "CAT_FOREST",
    "CAT_OCEAN",
    "CAT_DESERT",
    "CAT_RIVER",
    "CAT_SWAMP",
    "CAT_MUSHROOM",
    "CAT_NETHER",
    "CAT_MOUNTAIN",
    "CAT_UNDERGROUND",
];

/// The game's biomes in the order it registers them (1.21.4 on; `Biomes`), which is the order
/// Iris numbers them in: each is defined as `BIOME_<NAME>` with its number (0 for `THE_VOID`).
pub const BIOMES: [&str; 65] = [
    "THE_VOID", "PLAINS", "SUNFLOWER_PLAINS", "SNOWY_PLAINS", "ICE_SPIKES", "DESERT", "SWAMP",
    "MANGROVE_SWAMP", "FOREST", "FLOWER_FOREST", "BIRCH_FOREST", "DARK_FOREST", "PALE_GARDEN",
    "OLD_GROWTH_BIRCH_FOREST", "OLD_GROWTH_PINE_TAIGA", "OLD_GROWTH_SPRUCE_TAIGA", "TAIGA",
    "SNOWY_TAIGA", "SAVANNA", "SAVANNA_PLATEAU", "WINDSWEPT_HILLS", "WINDSWEPT_GRAVELLY_HILLS",
    "WINDSWEPT_FOREST", "WINDSWEPT_SAVANNA", "JUNGLE", "SPARSE_JUNGLE", "BAMBOO_JUNGLE", "BADLANDS",
    "ERODED_BADLANDS", "WOODED_BADLANDS", "MEADOW", "CHERRY_GROVE", "GROVE", "SNOWY_SLOPES",
    "FROZEN_PEAKS", "JAGGED_PEAKS", "STONY_PEAKS", "RIVER", "FROZEN_RIVER", "BEACH", "SNOWY_BEACH",
    "STONY_SHORE", "WARM_OCEAN", "LUKEWARM_OCEAN", "DEEP_LUKEWARM_OCEAN", "OCEAN", "DEEP_OCEAN",
    "COLD_OCEAN", "DEEP_COLD_OCEAN", "FROZEN_OCEAN", "DEEP_FROZEN_OCEAN", "MUSHROOM_FIELDS",
    "DRIPSTONE_CAVES", "LUSH_CAVES", "DEEP_DARK", "NETHER_WASTES", "WARPED_FOREST",
    "CRIMSON_FOREST", "SOUL_SAND_VALLEY", "BASALT_DELTAS", "THE_END", "END_HIGHLANDS",
    "END_MIDLANDS", "SMALL_END_ISLANDS", "END_BARRENS",
];

/// Precipitation kinds by value, as `biome_precipitation` holds them (and Iris's macros).
pub const PRECIPITATIONS: [&str; 3] = ["PPT_NONE", "PPT_RAIN", "PPT_SNOW"];

/// A float literal that always has a decimal point (`1` → `1.0`).
fn float(value: f32) -> String {
    let text = value.to_string();
    if text.contains(['.', 'e', 'E']) { text } else { format!("{text}.0") }
}

/// Parses `1.21.4` (or `1.8.9`, `1.21`) into OptiFine's number (12104, 10809, 12100).
/// The OpenGL and GLSL versions (as the macros hold them) a player's machine gives the game:
/// macOS gives Minecraft before 1.17 a legacy OpenGL 2.1 context (GLSL 1.20) and later
/// versions its 4.1 core one; elsewhere drivers give 4.6.
pub fn platform_gl_versions(os: Os, mc_version: u32) -> (u32, u32) {
    match os {
        Os::Mac if mc_version < 11700 => (210, 120),
        Os::Mac => (410, 410),
        _ => (460, 460),
    }
}

/// An OpenGL or GLSL version as a person writes it (`4.6`) or as the macros hold it (`460`).
pub fn parse_gl_version(text: &str) -> Result<u32, String> {
    let bad = || format!("`{}` is not a version such as 4.6 or 460", tidepack_glsl::terminal::line(text));
    match text.split_once('.') {
        Some((major, minor)) => {
            let (major, minor): (u32, u32) = (major.parse().map_err(|_| bad())?, minor.parse().map_err(|_| bad())?);
            if minor > 9 { Err(bad()) } else { Ok(major * 100 + minor * 10) }
        }
        None => text.parse().map_err(|_| bad()),
    }
}

pub fn parse_mc_version(text: &str) -> Option<u32> {
    let mut parts = text.trim().split('.').map(|p| p.parse::<u32>().ok());
    let major = parts.next()??;
    let minor = parts.next()??;
    let patch = parts.next().unwrap_or(Some(0))?;
    if parts.next().is_some() || minor > 99 || patch > 99 {
        return None;
    }
    Some(major * 10000 + minor * 100 + patch)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn macos_before_1_17_gives_glsl_1_20() {
        assert_eq!(platform_gl_versions(Os::Mac, 11605), (210, 120));
        assert_eq!(platform_gl_versions(Os::Mac, 12104), (410, 410));
        assert_eq!(platform_gl_versions(Os::Windows, 11605), (460, 460));
    }

    #[test]
    fn gl_versions_read_as_written_or_as_numbers() {
        assert_eq!(parse_gl_version("4.6"), Ok(460));
        assert_eq!(parse_gl_version("3.3"), Ok(330));
        assert_eq!(parse_gl_version("120"), Ok(120));
        assert!(parse_gl_version("4.x").unwrap_err().contains("such as 4.6 or 460"));
        assert!(parse_gl_version("4.10").is_err());
    }

    /// Iris defines `IRIS_FEATURE_<flag>` in the shaders for each optional flag the pack names
    /// and the machine has, spelled as written, and for every usable flag in the properties'
    /// conditionals; OptiFine defines none.
    #[test]
    fn iris_defines_the_optional_features_the_machine_has() {
        let props = Properties::parse_plain("iris.features.optional = CUSTOM_IMAGES ssbo NO_SUCH_FLAG\n");
        let iris = StandardMacros::for_loader(Loader::Iris).with_optional_features(&props);
        let defined = |macros: &StandardMacros| -> Vec<String> {
            macros.definitions().into_iter().map(|(name, _)| name).filter(|name| name.starts_with("IRIS_FEATURE_")).collect()
        };
        assert_eq!(defined(&iris), ["IRIS_FEATURE_CUSTOM_IMAGES", "IRIS_FEATURE_ssbo"]);
        let mac = StandardMacros { os: Os::Mac, ..StandardMacros::for_loader(Loader::Iris) }.with_optional_features(&props);
        assert!(defined(&mac).is_empty());
        let in_properties = iris.property_definitions();
        assert!(in_properties.iter().any(|(name, _)| name == "IRIS_FEATURE_COMPUTE_SHADERS"));
        let optifine = StandardMacros::for_loader(Loader::OptiFine1_21).with_optional_features(&props);
        assert!(defined(&optifine).is_empty() && optifine.property_definitions().iter().all(|(name, _)| !name.starts_with("IRIS_FEATURE_")));
    }

    #[test]
    fn defaults_define_one_os_vendor_and_renderer() {
        let defs = StandardMacros::default().definitions();
        let has = |name: &str| defs.iter().any(|(k, _)| k == name);
        assert!(has("MC_OS_LINUX") && !has("MC_OS_WINDOWS"));
        assert!(has("MC_GL_VENDOR_MESA") && has("MC_GL_RENDERER_MESA"));
        assert!(has("MC_GL_EXT_gpu_shader4"));
        let value = |name: &str| defs.iter().find(|(k, _)| k == name).map(|(_, v)| v.as_str());
        assert_eq!(value("MC_VERSION"), Some("12104"));
        assert_eq!(value("MC_RENDER_QUALITY"), Some("1.0"));
        assert_eq!(value("MC_RENDER_STAGE_HAND_TRANSLUCENT"), Some("23"));
    }

    #[test]
    fn each_loader_defines_its_own_names() {
        let names = |loader| StandardMacros::for_loader(loader).definitions();
        let value = |defs: &[(String, String)], name: &str| defs.iter().find(|(k, _)| k == name).map(|(_, v)| v.clone());
        let iris = names(Loader::Iris);
        assert_eq!(value(&iris, "IRIS_VERSION"), Some("10801".into()));
        assert_eq!(value(&iris, "DH_BLOCK_WATER"), Some("12".into()));
        assert!(value(&iris, "IS_IRIS").is_some());
        assert_eq!(value(&iris, "CAT_NETHER"), Some("16".into()));
        assert_eq!(value(&iris, "CAT_UNDERGROUND"), Some("18".into()));
        assert_eq!(value(&iris, "PPT_SNOW"), Some("2".into()));
        // The biome the scenes are set in is the `biome` uniform's 1.
        assert_eq!(value(&iris, "BIOME_PLAINS"), Some("1".into()));
        assert_eq!(value(&iris, "BIOME_OCEAN"), Some("45".into()));
        assert_eq!(value(&iris, "BIOME_THE_END"), Some("60".into()));
        let optifine = names(Loader::OptiFine1_12_2);
        assert_eq!(value(&optifine, "MC_VERSION"), Some("11202".into()));
        assert_eq!(value(&optifine, "IS_IRIS"), None);
        assert_eq!(value(&optifine, "CAT_NETHER"), None);
        assert_eq!(value(&optifine, "BIOME_PLAINS"), None);
    }

    #[test]
    fn minecraft_versions_parse_like_optifine() {
        assert_eq!(parse_mc_version("1.21.4"), Some(12104));
        assert_eq!(parse_mc_version("1.8.9"), Some(10809));
        assert_eq!(parse_mc_version("1.21"), Some(12100));
        assert_eq!(parse_mc_version("1.x"), None);
    }
}
