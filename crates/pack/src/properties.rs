//! Checks the `[properties]` of pack.toml against what OptiFine accepts before they are written
//! to shaders.properties: OptiFine ignores a value it cannot parse (a blend factor typo leaves
//! blending as it was, a missing texture leaves the sampler unbound), so the game would only
//! show a wrong picture.
//!
//! Checked: `blend.<program>[.<buffer>]`, `alphaTest.<program>`, `texture.<stage>.<unit>`,
//! `flip.<program>.<buffer>`, the boolean switches, `clouds` and `iris.features.*`. Keys the pack writes itself
//! (`screen`, `sliders`, `profile.*`) are refused; any other key is written as it is, with a
//! warning that it is unchecked.

use tidepack_glsl::{Code, Diagnostic, Location};

use crate::manifest::line_of;
use crate::shipped::ShippedPack;
use crate::source::PackSource;

/// OpenGL blend factors as OptiFine reads them in `blend.*`.
pub const BLEND_FACTORS: [&str; 11] = [
    "ZERO",
    "ONE",
    "SRC_COLOR",
    "ONE_MINUS_SRC_COLOR",
    "DST_COLOR",
    "ONE_MINUS_DST_COLOR",
    "SRC_ALPHA",
    "ONE_MINUS_SRC_ALPHA",
    "DST_ALPHA",
    "ONE_MINUS_DST_ALPHA",
    "SRC_ALPHA_SATURATE",
];

/// The features `iris.features.required` and `.optional` name.
const IRIS_FEATURES: [&str; 10] = [
    "SEPARATE_HARDWARE_SAMPLERS",
    "HIGHER_SHADOWCOLOR",
    "CUSTOM_IMAGES",
    "PER_BUFFER_BLENDING",
    "COMPUTE_SHADERS",
    "TESSELLATION_SHADERS",
    "ENTITY_TRANSLUCENT",
    "REVERSED_CULLING",
    "BLOCK_EMISSION_ATTRIBUTE",
    "SSBO",
];

/// Comparison functions of `alphaTest.*`.
const ALPHA_FUNCTIONS: [&str; 8] = ["NEVER", "LESS", "EQUAL", "LEQUAL", "GREATER", "NOTEQUAL", "GEQUAL", "ALWAYS"];

/// Stages of `texture.<stage>.<unit>`.
const TEXTURE_STAGES: [&str; 5] = ["gbuffers", "deferred", "composite", "shadowcomp", "prepare"];

/// shaders.properties switches that take `true` or `false`.
const BOOLEAN_KEYS: [&str; 20] = [
    "oldHandLight",
    "dynamicHandLight",
    "oldLighting",
    "shadowTerrain",
    "shadowTranslucent",
    "shadowEntities",
    "shadowBlockEntities",
    "underwaterOverlay",
    "sun",
    "moon",
    "vignette",
    "backFace.solid",
    "backFace.cutout",
    "backFace.cutoutMipped",
    "backFace.translucent",
    "rain.depth",
    "beacon.beam.depth",
    "separateAo",
    "frustum.culling",
    "particles.before.deferred",
];

/// Checks every `[properties]` entry; returns (errors, warnings). `pack` is the shipped pack
/// (any dialect: both have the same files), for program names and texture paths.
pub fn check(source: &PackSource, pack: &ShippedPack) -> (Vec<Diagnostic>, Vec<Diagnostic>) {
    let programs: Vec<String> =
        pack.programs().into_iter().map(|p| p.name.rsplit('/').next().unwrap_or(&p.name).to_string()).collect();
    let mut errors = Vec::new();
    let mut warnings = Vec::new();
    for (key, value) in &source.manifest.properties {
        let at = property_line(&source.manifest_text, key).map(|l| Location::line(source.manifest_path.clone(), l));
        let prefix = format!("[properties] \"{key}\"");
        match check_entry(key, value, &programs, pack) {
            Ok(Checked::Yes) => {}
            Ok(Checked::No) => warnings.push(Diagnostic::warning(
                Code::UncheckedProperty,
                format!("{prefix} is not a key tidepack checks; it goes into shaders.properties as written"),
                at,
            )),
            Err(why) => errors.push(Diagnostic::error(Code::Template, format!("{prefix} = {value:?}: {why}"), at)),
        }
    }
    (errors, warnings)
}

enum Checked {
    Yes,
    No,
}

/// The line of `key` in the `[properties]` table, quoted or bare.
fn property_line(text: &str, key: &str) -> Option<u32> {
    line_of(text, "[properties]", &format!("\"{key}\"")).or_else(|| line_of(text, "[properties]", &format!("{key} =")))
}

fn check_entry(key: &str, value: &str, programs: &[String], pack: &ShippedPack) -> Result<Checked, String> {
    if key.is_empty() || key.contains(|c: char| c.is_whitespace() || c.is_control() || c == '=' || c == ':') {
        return Err("a key cannot be empty or hold white space, `=` or `:`".into());
    }
    if value.contains(|c: char| c.is_control()) {
        return Err("the value holds a line break or control character, which would end the line in shaders.properties".into());
    }
    if key == "screen" || key == "sliders" || key.starts_with("screen.") || key.starts_with("profile.") {
        return Err("tidepack writes this key from [screen] and the [[profile]] tables; set it there".into());
    }
    let parts: Vec<&str> = key.split('.').collect();
    let known_program = |name: &str| -> Result<(), String> {
        if programs.iter().any(|p| p == name) {
            Ok(())
        } else {
            Err(format!("the pack has no program {name}; its programs are {}", programs.join(", ")))
        }
    };
    match parts.as_slice() {
        ["blend", program] | ["blend", program, _] => {
            known_program(program)?;
            if let [_, _, buffer] = parts.as_slice() {
                check_buffer(buffer)?;
            }
            check_blend(value)?;
        }
        ["alphaTest", program] => {
            known_program(program)?;
            check_alpha_test(value)?;
        }
        ["flip", program, buffer] => {
            known_program(program)?;
            check_buffer(buffer)?;
            check_boolean(value)?;
        }
        ["texture", stage, unit] => {
            if !TEXTURE_STAGES.contains(stage) {
                return Err(format!("{stage} is not a texture stage; OptiFine's are {}", TEXTURE_STAGES.join(", ")));
            }
            if unit.is_empty() {
                return Err("the key names no sampler".into());
            }
            check_texture_path(value, pack)?;
        }
        _ if key == "iris.features.required" || key == "iris.features.optional" => {
            // Iris refuses a pack that requires a feature it does not know, so a typo would
            // refuse the pack everywhere.
            if let Some(unknown) = value.split_whitespace().find(|f| !IRIS_FEATURES.contains(f)) {
                return Err(format!("{unknown} is not an Iris feature; Iris knows {}", IRIS_FEATURES.join(", ")));
            }
        }
        _ if key == "clouds" => {
            if !matches!(value, "fast" | "fancy" | "off") {
                return Err("clouds takes fast, fancy or off".into());
            }
        }
        _ if BOOLEAN_KEYS.contains(&key) => check_boolean(value)?,
        _ if key == "shadow.culling" => {
            if !matches!(value, "true" | "false" | "reversed") {
                return Err("shadow.culling takes true, false or reversed".into());
            }
        }
        _ => return Ok(Checked::No),
    }
    Ok(Checked::Yes)
}

fn check_buffer(buffer: &str) -> Result<(), String> {
    let numbered = buffer.strip_prefix("colortex").and_then(|n| n.parse::<u8>().ok()).is_some_and(|n| n <= 15);
    let named = matches!(buffer, "gcolor" | "gdepth" | "gnormal" | "composite" | "gaux1" | "gaux2" | "gaux3" | "gaux4");
    if numbered || named {
        Ok(())
    } else {
        Err(format!("{buffer} is not a colour buffer (colortex0 to colortex15, gcolor, gdepth, gnormal, composite, gaux1 to gaux4)"))
    }
}

fn check_blend(value: &str) -> Result<(), String> {
    if value == "off" {
        return Ok(());
    }
    let factors: Vec<&str> = value.split_whitespace().collect();
    let unknown: Vec<&&str> = factors.iter().filter(|f| !BLEND_FACTORS.contains(f)).collect();
    if factors.len() != 4 || !unknown.is_empty() {
        let what = match unknown.first() {
            Some(word) => format!("{word} is not a blend factor"),
            None => format!("{} factors given", factors.len()),
        };
        return Err(format!(
            "{what}; a blend is `off` or four factors (source colour, destination colour, source alpha, destination \
             alpha) out of {}",
            BLEND_FACTORS.join(" ")
        ));
    }
    Ok(())
}

fn check_alpha_test(value: &str) -> Result<(), String> {
    if value == "off" {
        return Ok(());
    }
    let words: Vec<&str> = value.split_whitespace().collect();
    match words.as_slice() {
        [function, reference] if ALPHA_FUNCTIONS.contains(function) && reference.parse::<f32>().is_ok_and(f32::is_finite) => {
            Ok(())
        }
        _ => Err(format!(
            "an alpha test is `off` or a function and a reference value (`GREATER 0.1`); functions: {}",
            ALPHA_FUNCTIONS.join(" ")
        )),
    }
}

fn check_boolean(value: &str) -> Result<(), String> {
    if matches!(value, "true" | "false") { Ok(()) } else { Err("takes true or false".into()) }
}

/// A texture path is relative to `shaders/` and must be a file the pack ships.
fn check_texture_path(value: &str, pack: &ShippedPack) -> Result<(), String> {
    if value.split_whitespace().count() != 1 {
        return Err("tidepack binds texture files only: write one path relative to shaders/".into());
    }
    let path = value.strip_prefix('/').unwrap_or(value);
    if pack.files.contains_key(path) || pack.binaries.contains_key(path) {
        return Ok(());
    }
    let mut images: Vec<&str> = pack
        .binaries
        .keys()
        .chain(pack.files.keys())
        .map(String::as_str)
        .filter(|p| p.ends_with(".png"))
        .collect();
    images.sort();
    let known = if images.is_empty() { "it has no images".to_string() } else { format!("its images: {}", images.join(", ")) };
    Err(format!("the pack has no file shaders/{path} ({known})"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blend_values_are_off_or_four_known_factors() {
        assert!(check_blend("off").is_ok());
        assert!(check_blend("SRC_ALPHA ONE_MINUS_SRC_ALPHA ZERO ZERO").is_ok());
        let typo = check_blend("of").unwrap_err();
        assert!(typo.contains("of is not a blend factor") && typo.contains("SRC_ALPHA_SATURATE"), "{typo}");
        assert!(check_blend("ONE ZERO").unwrap_err().contains("2 factors given"));
        assert!(check_blend("ONE ZERO ONE ONE_MINUS_SRC").unwrap_err().contains("ONE_MINUS_SRC is not"));
    }

    #[test]
    fn alpha_tests_booleans_and_buffers() {
        assert!(check_alpha_test("GREATER 0.1").is_ok());
        assert!(check_alpha_test("off").is_ok());
        assert!(check_alpha_test("GREATER").is_err());
        assert!(check_alpha_test("BIGGER 0.1").is_err());
        assert!(check_alpha_test("GREATER nan").is_err());
        assert!(check_boolean("true").is_ok());
        assert!(check_boolean("yes").is_err());
        assert!(check_buffer("colortex15").is_ok());
        assert!(check_buffer("gaux4").is_ok());
        assert!(check_buffer("colortex16").is_err());
        assert!(check_buffer("colortex").is_err());
    }
}
