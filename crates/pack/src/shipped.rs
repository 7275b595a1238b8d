//! The pack as it ships in one dialect: every file under `shaders/`, in memory, each knowing
//! where it came from so that a diagnostic about a shipped line can name the template line.

use std::collections::{BTreeMap, HashMap};
use std::sync::Arc;

use tidepack_loader::option_lines::{self, OptionSet};
use tidepack_glsl::preprocess::FileProvider;
use tidepack_glsl::{Code, Diagnostic, Location, Stage};

use crate::dialect::{self, Dialect};
use crate::pack_options::{PackOptions, is_glsl};
use crate::source::PackSource;
use crate::{textures, writers};

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Origin {
    /// Generated from a template; `header_line` is the one line the generator added.
    Template { display_path: String, header_line: u32 },
    /// Written from the manifest.
    Manifest,
}

#[derive(Clone, Debug)]
pub struct ShippedFile {
    pub text: Arc<str>,
    pub origin: Origin,
}

/// A program: a vertex and a fragment stage with a common name.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct Program {
    /// `gbuffers_water`, `world-1/composite`.
    pub name: String,
    pub stages: Vec<(Stage, String)>,
}

#[derive(Clone, Debug)]
pub struct ShippedPack {
    pub dialect: Dialect,
    /// Text files by path inside `shaders/`.
    pub files: BTreeMap<String, ShippedFile>,
    /// Binary files (generated textures) by path inside `shaders/`.
    pub binaries: BTreeMap<String, Arc<[u8]>>,
    /// Uniforms folded into constants by [`crate::specialise`]; empty for the general pack.
    pub folded_uniforms: Vec<String>,
}

/// The GLSL file generated from the manifest and the texture generator.
pub const GENERATED_GLSL: &str = "lib/generated.glsl";

impl ShippedPack {
    /// Generates the pack in `dialect`; `defaults` rewrites option defaults (a profile).
    pub fn generate(
        source: &PackSource,
        options: &PackOptions,
        dialect: Dialect,
        defaults: &OptionSet,
    ) -> Result<ShippedPack, Vec<Diagnostic>> {
        let samplers = dialect::sampler_types(source.templates.iter().filter(|t| is_glsl(&t.path)).map(|t| t.text.as_str()));
        let mut files = BTreeMap::new();
        let mut errors = Vec::new();
        let manifest_name = "shaderpack/pack.toml";
        for template in &source.templates {
            if !is_glsl(&template.path) {
                // Textures and other assets ship as they are.
                files.insert(
                    template.path.clone(),
                    ShippedFile { text: Arc::from(template.text.as_str()), origin: Origin::Manifest },
                );
                continue;
            }
            let header = writers::generated_header(
                "//",
                &format!("{dialect}"),
                &format!("shaderpack/shaders/{}", template.path),
            )
            .replace(" Edit that file, not this one.", " Edit the template, not this file.");
            let text = option_lines::apply(&template.text, defaults);
            match dialect::generate(&template.display_path, &template.path, &text, dialect, &samplers, &header) {
                Ok(text) => {
                    files.insert(
                        template.path.clone(),
                        ShippedFile {
                            text: Arc::from(text),
                            origin: Origin::Template {
                                display_path: template.display_path.clone(),
                                header_line: dialect::header_line(&template.text),
                            },
                        },
                    );
                }
                Err(e) => errors.push(e),
            }
        }
        if !errors.is_empty() {
            return Err(errors);
        }
        let m = &source.manifest;
        let water = textures::water_texture();
        let mut binaries: BTreeMap<String, Arc<[u8]>> = [(textures::WATER_TEXTURE.to_string(), Arc::from(water.png))].into();
        for (&(path, _, _), png) in textures::HEIGHT_CROSS_TEXTURES.iter().zip(water.height_cross) {
            binaries.insert(path.to_string(), Arc::from(png));
        }
        let texture_metas = binaries.keys().map(|path| (format!("{path}.mcmeta"), textures::WATER_TEXTURE_META.to_string()));
        let generated = [
            (GENERATED_GLSL.to_string(), writers::generated_glsl(m, manifest_name)),
            ("shaders.properties".to_string(), writers::shaders_properties(m, options, manifest_name)),
            ("block.properties".to_string(), writers::block_properties(m, manifest_name)),
            ("lang/en_us.lang".to_string(), writers::lang(m, manifest_name)),
        ];
        for (path, text) in texture_metas.collect::<Vec<_>>().into_iter().chain(generated) {
            if files.contains_key(&path) {
                return Err(vec![Diagnostic::error(
                    Code::Template,
                    format!("shaderpack/shaders/{path} is generated from the manifest; remove the hand-written copy"),
                    None,
                )]);
            }
            files.insert(path, ShippedFile { text: Arc::from(text), origin: Origin::Manifest });
        }
        Ok(ShippedPack { dialect, files, binaries, folded_uniforms: Vec::new() })
    }

    /// Programs: `.vsh`/`.fsh` files at the top level or in a world folder.
    pub fn programs(&self) -> Vec<Program> {
        let mut programs: BTreeMap<String, Vec<(Stage, String)>> = BTreeMap::new();
        for path in self.files.keys() {
            let in_program_folder = !path.contains('/') || (path.starts_with("world") && path.matches('/').count() == 1);
            if let Some(stage) = Stage::from_path(path).filter(|_| in_program_folder) {
                let name = &path[..path.len() - 4];
                programs.entry(name.to_string()).or_default().push((stage, path.clone()));
            }
        }
        programs.into_iter().map(|(name, mut stages)| {
            stages.sort();
            Program { name, stages }
        }).collect()
    }

    /// The template location of a location in a shipped file (unchanged for generated files).
    /// Columns are re-found on the template line, since dialect rewrites move them.
    pub fn to_template(&self, loc: &Location, source: &PackSource) -> Location {
        let Some(file) = self.files.get(&loc.path) else { return loc.clone() };
        match &file.origin {
            Origin::Template { display_path, header_line } => {
                let Some(line) = dialect::template_line(loc.line, *header_line) else {
                    return Location::line(display_path.clone(), loc.line);
                };
                let template = source.templates.iter().find(|t| &t.display_path == display_path);
                let columns = loc.columns.clone().and_then(|cols| {
                    let shipped_line = file.text.lines().nth(loc.line as usize - 1)?;
                    let token = shipped_line.get(cols)?;
                    let template_line = template?.text.lines().nth(line as usize - 1)?;
                    let mut hits = template_line.match_indices(token);
                    let (start, _) = hits.next()?;
                    hits.next().is_none().then_some(start..start + token.len())
                });
                Location { path: display_path.clone(), line, columns }
            }
            Origin::Manifest => Location { path: format!("shaders/{}", loc.path), ..loc.clone() },
        }
    }

    /// Text of a path as diagnostics name it: a template's display path or `shaders/<generated>`.
    pub fn diagnostic_source(&self, path: &str, source: &PackSource) -> Option<String> {
        if let Some(t) = source.templates.iter().find(|t| t.display_path == path) {
            return Some(t.text.clone());
        }
        if path == source.manifest_path {
            return Some(source.manifest_text.clone());
        }
        self.files.get(path.strip_prefix("shaders/")?).map(|f| f.text.to_string())
    }
}

/// Reads shipped files with a set of option values applied, as OptiFine does when a player
/// changes options.
pub struct WithOptions<'a> {
    pub pack: &'a ShippedPack,
    pub set: &'a OptionSet,
    cache: std::sync::Mutex<HashMap<String, Arc<str>>>,
}

impl<'a> WithOptions<'a> {
    pub fn new(pack: &'a ShippedPack, set: &'a OptionSet) -> Self {
        WithOptions { pack, set, cache: Default::default() }
    }
}

impl FileProvider for WithOptions<'_> {
    fn read(&self, path: &str) -> Result<Arc<str>, String> {
        let mut cache = self.cache.lock().expect("no panics while holding the cache");
        if let Some(text) = cache.get(path) {
            return Ok(text.clone());
        }
        let file = self.pack.files.get(path).ok_or_else(|| "no such file in the pack".to_string())?;
        let text: Arc<str> = match option_lines::apply(&file.text, self.set) {
            std::borrow::Cow::Borrowed(_) => file.text.clone(),
            std::borrow::Cow::Owned(s) => Arc::from(s),
        };
        cache.insert(path.to_string(), text.clone());
        Ok(text)
    }
}
