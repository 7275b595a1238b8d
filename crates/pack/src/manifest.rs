//! `shaderpack/pack.toml`: what the pack is, beyond its GLSL.
//!
//! The GLSL templates declare the options (OptiFine reads them from the `#define` lines); the
//! manifest says how players meet them: labels and comments for the lang file, the menu screens,
//! sliders, profiles, the block ids shared between block.properties and the shaders, and the
//! pipeline settings of shaders.properties.

use std::collections::BTreeMap;

use serde::Deserialize;
use tidepack_glsl::{Code, Diagnostic, Location};

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    pub pack: PackInfo,
    /// Block ids: each becomes a `block.<id>=` line and a `#define` in lib/generated.glsl.
    #[serde(default, rename = "block")]
    pub blocks: Vec<BlockId>,
    /// Pipeline settings written as they are to shaders.properties (`blend.gbuffers_water.colortex4`).
    #[serde(default)]
    pub properties: BTreeMap<String, String>,
    pub screen: Screen,
    /// Option labels and comments for the lang file, by option name.
    #[serde(default)]
    pub options: BTreeMap<String, OptionText>,
    /// Profiles in menu order, low to high.
    #[serde(default, rename = "profile")]
    pub profiles: Vec<Profile>,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PackInfo {
    pub name: String,
    pub version: String,
    /// The profile whose values are the defaults written in the GLSL.
    pub default_profile: String,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BlockId {
    pub id: i16,
    /// Macro name in lib/generated.glsl.
    #[serde(rename = "macro")]
    pub macro_name: String,
    pub names: Vec<String>,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Screen {
    /// Items of the main screen: option names, `[SUB]` links, `<profile>`, `<empty>`.
    pub main: Vec<String>,
    #[serde(default = "default_columns")]
    pub columns: u32,
    #[serde(default)]
    pub sliders: Vec<String>,
    #[serde(default, rename = "sub")]
    pub subs: BTreeMap<String, SubScreen>,
}

fn default_columns() -> u32 {
    2
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SubScreen {
    pub label: String,
    pub comment: String,
    pub items: Vec<String>,
    #[serde(default)]
    pub columns: Option<u32>,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OptionText {
    pub label: String,
    pub comment: String,
    /// Labels for individual values, keyed by the value exactly as written in the GLSL.
    #[serde(default)]
    pub values: BTreeMap<String, String>,
    /// Text shown after the value (`suffix.NAME`), e.g. a unit.
    #[serde(default)]
    pub suffix: Option<String>,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Profile {
    pub name: String,
    pub label: String,
    pub comment: String,
    /// Every option's value in this profile: `true`/`false` for switches, the value as written
    /// in the GLSL (a string) for value options.
    pub settings: BTreeMap<String, toml::Value>,
}

impl Manifest {
    /// Parses the manifest; errors name `path` and the line.
    pub fn parse(path: &str, text: &str) -> Result<Manifest, Diagnostic> {
        let manifest: Manifest = toml::from_str(text).map_err(|e| {
            let line = e.span().map(|s| text[..s.start].matches('\n').count() as u32 + 1);
            let message = e.message().to_string();
            Diagnostic::error(Code::Template, format!("invalid pack manifest: {message}"), line.map(|l| Location::line(path, l)))
        })?;
        for (field, value) in [("name", &manifest.pack.name), ("version", &manifest.pack.version)] {
            if let Err(why) = check_file_name_part(value) {
                let at = line_of(text, "[pack]", &format!("{field} =")).map(|l| Location::line(path, l));
                return Err(Diagnostic::error(Code::Template, format!("[pack] {field} {value:?} {why}"), at).with_note(
                    "the zips are named <name>-<version>-<dialect>.zip inside the output folder, so name and version \
                     must be plain file-name text",
                ));
            }
        }
        for menu in manifest.menu_texts() {
            if let Some((index, c)) = menu.char_indices().find(|(_, c)| *c == '\\' || c.is_control()) {
                // The text before the bad character appears in the TOML as written.
                let at = line_of(text, "", &menu[..index]).map(|l| Location::line(path, l));
                return Err(Diagnostic::error(Code::Template, format!("menu text {menu:?} contains {c:?}"), at).with_note(
                    "lang files are read differently by OptiFine (text as written) and Iris (Java properties: \
                     `\\` escapes, line continuations); write the text without backslashes or line breaks",
                ));
            }
        }
        Ok(manifest)
    }

    /// Every text that goes into the lang file.
    fn menu_texts(&self) -> impl Iterator<Item = &str> {
        let profiles = self.profiles.iter().flat_map(|p| [p.label.as_str(), p.comment.as_str()]);
        let screens = self.screen.subs.values().flat_map(|s| [s.label.as_str(), s.comment.as_str()]);
        let options = self.options.values().flat_map(|o| {
            [o.label.as_str(), o.comment.as_str()].into_iter().chain(o.values.values().map(String::as_str)).chain(o.suffix.as_deref())
        });
        profiles.chain(screens).chain(options)
    }
}

/// Why `part` cannot be part of a zip's file name: a separator or `..` would put the zip
/// outside the output folder; control and Windows-reserved characters make names that some
/// systems cannot create.
fn check_file_name_part(part: &str) -> Result<(), String> {
    if part.trim().is_empty() {
        return Err("is empty".into());
    }
    if part == "." || part == ".." || part.contains("..") {
        return Err("contains `..`".into());
    }
    if let Some(c) = part.chars().find(|c| c.is_control() || matches!(c, '/' | '\\' | ':' | '*' | '?' | '"' | '<' | '>' | '|')) {
        return Err(format!("contains {c:?}, which cannot be in a file name"));
    }
    if part.trim() != part {
        return Err("starts or ends with white space".into());
    }
    Ok(())
}

/// The line of the first occurrence of `needle` in `text` (for pointing errors at the manifest),
/// searched after `after` when that is found.
pub fn line_of(text: &str, after: &str, needle: &str) -> Option<u32> {
    let start = text.find(after).unwrap_or(0);
    let at = start + text[start..].find(needle)?;
    Some(text[..at].matches('\n').count() as u32 + 1)
}
