//! A program as the harness renders it: the shipped text preprocessed, lowered and validated
//! by naga (the wgpu path), and the same text with its includes expanded (the OpenGL path).
//! Also our own pack ([`LoadedPack`]): one dialect of it generated under a profile and option
//! overrides and read as any pack is ([`crate::any_pack`]).

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::path::PathBuf;
use std::sync::Arc;

use tidepack_glsl::lower::{Interface, ResourceKind};
use tidepack_glsl::naga_check::{self, LoweredStage};
use tidepack_glsl::preprocess::{self, FileProvider};
use tidepack_glsl::token::{Token, TokenKind, function_definitions, tokenize};
use tidepack_glsl::{Diagnostic, Location, Stage};
use tidepack_loader::blocks;
use tidepack_loader::buffers::{BufferFormat, ImageOf, buffer_of_image};
use tidepack_loader::consts;
use tidepack_loader::directives::{self, RawLayout, TextureTarget};
use tidepack_loader::input;
use tidepack_loader::iris;
use tidepack_loader::loader::Loader;
use tidepack_loader::macros::StandardMacros;
use tidepack_loader::option_lines::{OptionKind, OptionSet};
use tidepack_loader::option_space::{Configuration, read_properties};
use tidepack_loader::programs;
use tidepack_scene::mesh::LOD_MATERIAL_INPUT;
use tidepack_loader::properties::Properties;
use tidepack_loader::shadow::ShadowSettings;
use tidepack_pack::dialect::Dialect;
use tidepack_pack::pack_options;
use tidepack_pack::shipped::ShippedPack;
use tidepack_pack::source::PackSource;
use tidepack_pack::specialise::{Specialisation, specialise};
use tidepack_scene::mesh::{self, SceneMesh};
use tidepack_scene::scene::Scene;

use crate::HarnessError;
use crate::raw_texture::{self, Texels};
use crate::samplers::{self, GameTextureBinding};
use crate::any_pack::AnyPack;

/// Which pack text to render.
#[derive(Clone, Debug)]
pub struct PackSelection {
    /// The folder with pack.toml and shaders/ (`shaderpack`).
    pub source_dir: PathBuf,
    pub dialect: Dialect,
    /// Profile whose values are the shipped defaults (default: the manifest's default).
    pub profile: Option<String>,
    /// Option overrides, `NAME` → value as written (`on`/`off` for switches).
    pub options: Vec<(String, String)>,
}

/// One stage ready for both renderers.
#[derive(Clone, Debug)]
pub struct LoadedStage {
    pub stage: Stage,
    /// Path inside `shaders/`.
    pub path: String,
    /// What a GL driver compiles: the shipped text, options applied, includes expanded,
    /// OptiFine's standard macros defined after `#version`, and what only lenient compilers
    /// accept rewritten for a strict one (`gl_rewrites`).
    pub gl_text: String,
    /// The rewrites `tidepack_glsl::compat::for_strict_drivers` made to `gl_text`, each as
    /// `file:line: what` at the pack file and line it was made on.
    pub gl_rewrites: Vec<String>,
    /// The pack file and line of each line of `gl_text` (see [`origins_of_rewritten`]), for
    /// saying a driver's complaint where the author wrote the code.
    pub gl_origins: Vec<Option<Location>>,
    /// The stage with its includes expanded and its comments kept, where the loader reads the
    /// settings a pack writes in comments (`const int colortex0Format = RGBA16F;`); under Iris
    /// `gl_text` has no comments left.
    pub settings_text: String,
    /// The lowered GLSL 450 exactly as the toolchain produces it.
    pub lowered_text: String,
    /// The text naga parsed for wgpu: the lowered text, plus (vertex stage only) a wrapper
    /// `main` on the last line that converts OpenGL clip space to wgpu's (see [`adapt_vertex`]).
    pub harness_text: String,
    pub interface: Interface,
    /// naga's module of `harness_text`, what wgpu draws with; or why naga cannot read or
    /// validate it, in the pack's terms (OpenGL can still draw the program).
    pub naga: Result<naga::Module, String>,
    /// Fragment outputs declared with fewer than four channels, by location: the harness text
    /// writes them as `vec4` and the pipeline masks the channels they lack.
    pub narrow_outputs: BTreeMap<u32, u8>,
}

/// A stage only OpenGL runs, as it compiles it: a geometry stage (naga reads none, so wgpu
/// cannot draw a program that has one) or a compute stage ([`ComputeStage`]).
#[derive(Clone, Debug)]
pub struct OpenGlStage {
    /// Path inside `shaders/`.
    pub path: String,
    /// As [`LoadedStage::gl_text`].
    pub gl_text: String,
    /// As [`LoadedStage::gl_rewrites`].
    pub gl_rewrites: Vec<String>,
    /// As [`LoadedStage::gl_origins`].
    pub gl_origins: Vec<Option<Location>>,
}

impl LoadedStage {
    /// naga's module, or what wgpu cannot draw the stage for.
    pub fn module(&self) -> Result<&naga::Module, HarnessError> {
        self.naga.as_ref().map_err(|e| HarnessError::Unsupported(format!("{}: naga cannot read it for wgpu: {e}", self.path)))
    }
}

impl LoadedProgram {
    /// Why wgpu cannot draw the program as a whole, where a stage of it has no wgpu form.
    pub fn wgpu_cannot_draw(&self) -> Option<HarnessError> {
        let geometry = self.geometry.as_ref()?;
        Some(HarnessError::Unsupported(format!("{}: a geometry stage ({}), which wgpu does not run", self.name, geometry.path)))
    }

    /// The program with every float literal of the text OpenGL compiles moved by `relative` of
    /// itself ([`float_literals_nudged`]), for [`crate::gl_frame::Reference::nudge`].
    pub fn with_float_literals_nudged(&self, relative: f64) -> LoadedProgram {
        let nudge = |text: &str| float_literals_nudged(text, relative);
        let mut program = self.clone();
        program.vertex.gl_text = nudge(&self.vertex.gl_text);
        if let Some(geometry) = &mut program.geometry {
            geometry.gl_text = nudge(&geometry.gl_text);
        }
        program.fragment.gl_text = nudge(&self.fragment.gl_text);
        program
    }

    /// The program with a fragment stage that writes 1 into every output where the stage's
    /// implicit derivatives are undefined and 0 elsewhere ([`crate::derivatives::traced`]), for
    /// [`crate::gl_frame::Reference::trace_derivatives`], lookups in the samplers `level_free`
    /// names left out; None where the stage cannot be traced.
    pub fn with_derivative_trace(&self, level_free: impl Fn(&str) -> bool) -> Option<LoadedProgram> {
        let declarations = interface_declarations(&self.fragment.lowered_text);
        let output_type = |location: u32| {
            let declaration = declarations.iter().find(|d| d.location == location && d.direction() == Some("out"))?;
            let [.., ty, _] = declaration.words.as_slice() else { return None };
            Some(ty.to_string())
        };
        let mut program = self.clone();
        program.fragment.gl_text = crate::derivatives::traced(&self.fragment.gl_text, &self.fragment.interface.outputs, output_type, level_free)?;
        Some(program)
    }

    /// The draw buffers (positions in [`Self::render_targets`]) the fragment stage names and
    /// never writes (`/* DRAWBUFFERS:02 */` beside `gl_FragData[0]` alone). GLSL leaves their
    /// values undefined: wgpu leaves such a buffer as it was, Mesa writes white. `gl_FragColor`
    /// writes every buffer.
    pub fn draw_buffers_never_written(&self) -> Vec<usize> {
        let outputs = &self.fragment.interface.outputs;
        if outputs.values().any(|name| name == "gl_FragColor") {
            return Vec::new();
        }
        (0..self.render_targets.len()).filter(|&i| !outputs.contains_key(&(i as u32))).collect()
    }

    /// Why naga cannot read a stage of the program, if it cannot.
    pub fn naga_refusal(&self) -> Option<&str> {
        [&self.vertex, &self.fragment].into_iter().find_map(|s| s.naga.as_ref().err()).map(String::as_str)
    }
}

#[derive(Clone, Debug)]
pub struct LoadedProgram {
    pub name: String,
    pub vertex: LoadedStage,
    /// The program's geometry stage (`.gsh`), which only OpenGL runs.
    pub geometry: Option<OpenGlStage>,
    pub fragment: LoadedStage,
    /// Buffer numbers the fragment outputs go to, in output order (RENDERTARGETS/DRAWBUFFERS);
    /// `None` where the list says `N`, an output drawn into no buffer.
    pub render_targets: Vec<Option<u8>>,
}

impl LoadedProgram {
    /// The buffers the program draws into, in output order.
    pub fn drawn_buffers(&self) -> impl Iterator<Item = u8> + '_ {
        self.render_targets.iter().flatten().copied()
    }
}

/// What binding a program's samplers needs of its pack besides the program itself.
pub trait PackResources {
    /// The format colortex`buffer` is stored in.
    fn format_of(&self, buffer: u8) -> BufferFormat;
    /// Custom textures from shaders.properties.
    fn custom_textures(&self) -> &[CustomTexture];
    /// Game textures shaders.properties binds to units (`minecraft:textures/atlas/blocks.png`).
    fn game_textures(&self) -> &[GameTextureBinding] {
        &[]
    }
    /// Iris's custom images from shaders.properties, which only OpenGL holds.
    fn custom_images(&self) -> &[tidepack_loader::directives::CustomImage] {
        &[]
    }
    /// Whether more than one program (or compute stage) declares a buffer block of Iris's
    /// `bufferObject`s, which OpenGL holds across the frame and wgpu gives each program apart.
    fn buffers_shared_across_programs(&self) -> bool {
        false
    }
    /// The pack's shadow-map constants.
    fn shadow_settings(&self) -> ShadowSettings {
        ShadowSettings::default()
    }
    /// Whether the sampler `shadow` names shadowtex1 (without translucents): OptiFine and Iris
    /// do so when the pack also reads `watershadow`.
    fn water_shadow(&self) -> bool {
        false
    }
    /// The loader binding the samplers: Iris binds names of its own (`shadowtex0HW`).
    fn loader(&self) -> Loader {
        Loader::default()
    }
}

/// Our own pack, generated from its sources and read as the loader reads what ships: its
/// frames are drawn from [`LoadedPack::pack`] like any other pack's.
#[derive(Debug)]
pub struct LoadedPack {
    pub dialect: Dialect,
    pub profile: String,
    /// The option values in force (profile, then overrides).
    pub options: OptionSet,
    /// Uniforms folded into constants ([`load_specialised`]); empty for the general pack.
    pub folded_uniforms: Vec<String>,
    /// The shipped files as the loader reads them under the selected options.
    pub pack: AnyPack,
}

/// A texture the pack binds itself to a sampler unit.
#[derive(Clone, Debug)]
pub struct CustomTexture {
    /// `gbuffers` or `composite` (composite also covers deferred and final in this harness).
    pub stage: String,
    /// The sampler name it replaces (`colortex7`, `noisetex`, …).
    pub unit: String,
    pub path: String,
    /// What it is made as: an image file is TEXTURE_2D, a raw texture says.
    pub target: TextureTarget,
    pub width: u32,
    pub height: u32,
    /// 1 but for TEXTURE_3D.
    pub depth: u32,
    /// First row of the file first (as OptiFine uploads it: row 0 at texture coordinate 0).
    pub texels: Texels,
    /// From `<path>.mcmeta`: linear filtering.
    pub blur: bool,
    /// From `<path>.mcmeta`: clamp instead of repeat.
    pub clamp: bool,
}

impl LoadedPack {
    /// The loader whose frame is drawn.
    pub fn loader(&self) -> Loader {
        self.pack.loader
    }

    pub fn water(&self) -> &LoadedProgram {
        &self.pack.gbuffers["gbuffers_water"]
    }

    pub fn format_of(&self, buffer: u8) -> BufferFormat {
        self.pack.format_of(buffer)
    }

    /// The 2D custom texture bound to a sampler name in the programs of `stage`.
    pub fn custom_texture(&self, name: &str, stage: crate::samplers::ProgramStage) -> Option<&CustomTexture> {
        crate::samplers::custom_texture_of(&self.pack, name, stage, TextureTarget::D2).map(|i| &self.pack.custom_textures[i])
    }

    pub fn composite(&self) -> &LoadedProgram {
        self.pack.fullscreen.iter().find(|p| p.name == "composite").expect("our pack has composite")
    }

    /// The geometry of `scene` as our pack's scenes are drawn: everything but the sky box, the
    /// sun and the moon, so the sky keeps OptiFine's clear colour (the fog colour) that the
    /// water's reference model and golden images assume.
    pub fn mesh(&self, scene: &Scene) -> SceneMesh {
        let mut mesh = mesh::build(scene, &self.pack);
        for sky in [&mut mesh.sky, &mut mesh.sun, &mut mesh.moon] {
            sky.clear();
        }
        mesh
    }
}

fn diag_error(context: &str, diagnostics: &[Diagnostic]) -> HarnessError {
    let list: Vec<String> = diagnostics.iter().map(|d| tidepack_glsl::messages::clarify(d.clone()).to_string()).collect();
    HarnessError::Pack(format!("{context}:\n{}", list.join("\n")))
}

/// Generates the pack in the selected dialect and reads it as the default loader does.
pub fn load(selection: &PackSelection) -> Result<LoadedPack, HarnessError> {
    load_specialised(selection, None)
}

/// [`load`], with the uniforms `specialisation` fixes folded into constants first (as
/// `tidepack build --scene` ships them).
pub fn load_specialised(selection: &PackSelection, specialisation: Option<&Specialisation>) -> Result<LoadedPack, HarnessError> {
    load_for(selection, specialisation, Loader::default())
}

/// [`load_specialised`], for the frame a given loader would draw: the pack is generated with
/// the profile's values as its defaults, and the option overrides are applied to the shipped
/// text as the loader applies a player's choices.
pub fn load_for(selection: &PackSelection, specialisation: Option<&Specialisation>, loader: Loader) -> Result<LoadedPack, HarnessError> {
    load_configured(selection, specialisation, Configuration { options: selection.options.clone(), loader, ..Configuration::default() })
}

/// [`load_for`] Iris with Distant Horizons beside it: `DISTANT_HORIZONS` is defined and the
/// pack's dh_* programs draw the scenes' LODs.
pub fn load_with_distant_horizons(selection: &PackSelection, specialisation: Option<&Specialisation>) -> Result<LoadedPack, HarnessError> {
    let configuration = Configuration { options: selection.options.clone(), loader: Loader::Iris, distant_horizons: true, ..Configuration::default() };
    load_configured(selection, specialisation, configuration)
}

fn load_configured(selection: &PackSelection, specialisation: Option<&Specialisation>, configuration: Configuration) -> Result<LoadedPack, HarnessError> {
    let source = PackSource::load(&selection.source_dir).map_err(|d| diag_error("cannot read the pack", &[d]))?;
    let options = pack_options::collect(&source).map_err(|d| diag_error("the pack's options are invalid", &d))?;
    let profile = selection.profile.clone().unwrap_or_else(|| source.manifest.pack.default_profile.clone());
    let defaults =
        pack_options::profile_set(&source, &options, &profile).map_err(|d| HarnessError::Configuration(d.message))?;
    let mut shipped = ShippedPack::generate(&source, &options, selection.dialect, &defaults)
        .map_err(|d| diag_error("the pack does not generate", &d))?;
    if let Some(spec) = specialisation {
        specialise(&mut shipped, spec);
    }
    let texts = shipped.files.iter().map(|(path, file)| (path.clone(), file.text.as_bytes().to_vec()));
    let binaries = shipped.binaries.iter().map(|(path, bytes)| (path.clone(), bytes.to_vec()));
    let files = input::pack_from_memory("shaders/", texts.chain(binaries));
    let (overrides, _) = configuration.option_set_of(&files).map_err(HarnessError::Configuration)?;
    let pack = AnyPack::from_files(&files, &configuration)?;
    if !pack.failed.is_empty() {
        // Each reason is a harness error's text, which names the program's file already.
        let failed: Vec<&str> = pack.failed.iter().map(|(_, why)| why.strip_prefix("pack: ").unwrap_or(why)).collect();
        return Err(HarnessError::Pack(failed.join("\n")));
    }
    // Our programs must all be drawn by both renderers.
    let unreadable: Vec<&str> = pack.programs().filter_map(LoadedProgram::naga_refusal).collect();
    if !unreadable.is_empty() {
        return Err(HarnessError::Pack(unreadable.join("\n")));
    }
    if !pack.gbuffers.contains_key("gbuffers_water") || !pack.fullscreen.iter().any(|p| p.name == "composite") {
        return Err(HarnessError::Pack("the pack has no gbuffers_water or no composite program".into()));
    }
    let mut in_force = defaults;
    in_force.extend(overrides);
    Ok(LoadedPack { dialect: selection.dialect, profile, options: in_force, folded_uniforms: shipped.folded_uniforms.clone(), pack })
}

/// A stage's text as the loader gives it to the driver: under OptiFine, with its includes
/// expanded by the loader's rules (`macros`) and `defines` after `#version`; where the loader's
/// own preprocessor resolves the stage first ([`LoaderReading::preprocessed_for_driver`]),
/// its output `seen`, unrewritten, with the chosen `#version` on top
/// ([`iris::as_preprocessor_leaves_it`]). `preprocessed` is the stage as the render path read it.
fn expanded_as_loader_gives_it(
    provider: &dyn FileProvider,
    path: &str,
    macros: &preprocess::PreprocessOptions,
    defines: &str,
    preprocessed: &preprocess::Preprocessed,
    seen: &str,
    reading: LoaderReading,
) -> Result<ExpandedStage, HarnessError> {
    let (expanded, expanded_map) = preprocess::expand_includes_mapped(provider, path, defines, macros.include_rules)
        .map_err(|d| diag_error(&format!("{path} includes"), &[d]))?;
    if reading.preprocessed_for_driver {
        let (text, line_map, moved_first) = iris::as_preprocessor_leaves_it(seen, preprocessed);
        return Ok(ExpandedStage { text, line_map, moved_first, settings_text: expanded });
    }
    Ok(ExpandedStage { text: expanded.clone(), line_map: expanded_map, moved_first: None, settings_text: expanded })
}

/// The lines (1-based) of an expanded text, whose pack locations are `line_map`, that come from
/// the pack line `at`.
fn lines_from(line_map: &[Option<Location>], at: &Location) -> Vec<u32> {
    line_map.iter().enumerate().filter(|(_, l)| l.as_ref() == Some(at)).map(|(i, _)| i as u32 + 1).collect()
}

/// The macros the lenient preprocessor saw redefined in `preprocessed`, at the lines of its
/// expanded text.
fn redefined_lines(preprocessed: &preprocess::Preprocessed, line_map: &[Option<Location>]) -> Vec<(u32, String)> {
    preprocessed.redefinitions.iter().flat_map(|(at, name)| lines_from(line_map, at).into_iter().map(move |line| (line, name.clone()))).collect()
}

/// `what` was done at `line` of an expanded text of `path`: said at the pack line it came from.
fn located_rewrite(line_map: &[Option<Location>], path: &str, line: u32, what: &str) -> String {
    match line_map.get(line as usize - 1).cloned().flatten() {
        Some(at) => format!("{at}: {what}"),
        None => format!("{path}: {what}"),
    }
}

/// A stage's text as the loader hands it to the driver, before the rewrites for strict drivers.
struct ExpandedStage {
    text: String,
    /// The pack location of each line of `text`.
    line_map: Vec<Option<Location>>,
    /// What was done where the loader put a `#version` chosen in an `#if` first, or moved
    /// `#extension` lines after code up to follow it.
    moved_first: Option<String>,
    /// [`LoadedStage::settings_text`].
    settings_text: String,
}

/// Lines a rewrite may move from where they were in the text it rewrote: the `#undef` lines it
/// inserts, an `#extension` moved up, a `main` wrapped.
const REWRITE_REACH: usize = 64;

/// The pack location of each line of `text`, a rewrite of `expanded` whose lines come from
/// `origins`: a line found unchanged in `expanded` near where the rewrites left it has that
/// line's origin; a line they changed (the line after it is the next one unchanged) has the
/// origin of the line it replaced; a line they added has the origin of the line before it.
pub(crate) fn origins_of_rewritten(text: &str, expanded: &str, origins: &[Option<Location>]) -> Vec<Option<Location>> {
    let before: Vec<&str> = expanded.lines().collect();
    let after: Vec<&str> = text.lines().collect();
    let find = |line: &str, from: usize| (from..before.len().min(from + REWRITE_REACH)).find(|&k| before[k] == line && (!line.trim().is_empty() || k == from));
    let mut next = 0usize;
    let mut last: Option<Location> = None;
    let mut found_origins = Vec::with_capacity(after.len());
    for (i, line) in after.iter().enumerate() {
        let replaced = || after.get(i + 1).is_some_and(|following| before.get(next + 1) == Some(following)).then_some(next);
        if let Some(k) = find(line, next).or_else(replaced) {
            next = k + 1;
            last = origins.get(k).cloned().flatten().or(last);
        }
        found_origins.push(last.clone());
    }
    found_origins
}

/// The two stage files of one program, as paths inside `shaders/`.
pub(crate) struct ProgramFiles<'a> {
    pub name: &'a str,
    pub vertex: String,
    pub geometry: Option<String>,
    pub fragment: String,
}

/// How the loader reads a stage's text before the driver sees it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct LoaderReading {
    pub undeclared: UndeclaredTargets,
    /// [`Loader::preprocesses_for_driver`].
    pub preprocessed_for_driver: bool,
    /// What of Iris's transformer applies to this program ([`Loader::renames_albedo_sampler`],
    /// [`Loader::removes_unused_functions`], [`Loader::raises_version_to_330`]).
    pub transform: iris::Transform,
}

/// Where a fragment stage without RENDERTARGETS or DRAWBUFFERS writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum UndeclaredTargets {
    /// Every buffer it has an output for, output N to colortexN (OptiFine: all used buffers;
    /// outputs not written are undefined there, untouched here).
    Outputs,
    /// colortex0 only (Iris).
    FirstOnly,
}

/// Loads one program from its stage files with `macros` predefined. `alpha_test` gives the
/// loader's alpha test for the fragment stage's shipped text (includes expanded): fragments
/// whose output 0 has an alpha not above it are discarded.
pub(crate) fn load_program_files(
    provider: &dyn FileProvider,
    files: &ProgramFiles,
    macros: &preprocess::PreprocessOptions,
    alpha_test: &dyn Fn(&str) -> Option<f32>,
    reading: LoaderReading,
) -> Result<LoadedProgram, HarnessError> {
    let name = files.name;
    let defines: String = macros.predefined.iter().map(|(k, v)| format!("#define {k} {v}\n")).collect();
    let mut pre = Vec::new();
    // Each stage as the loader's preprocessor leaves it, before Iris's transformer: what that
    // transformer decides its rewrites on, for the text OpenGL gets too.
    let mut as_preprocessed = BTreeMap::new();
    let mut met_by_driver = BTreeMap::new();
    for (stage, path) in [(Stage::Vertex, &files.vertex), (Stage::Fragment, &files.fragment)] {
        provider.read(path).map_err(|_| HarnessError::Pack(format!("the pack has no {path}")))?;
        // The renderer draws what lenient drivers run (`PreprocessOptions::lenient`).
        let lenient = preprocess::PreprocessOptions { lenient: true, ..macros.clone() };
        let mut p = preprocess::preprocess(provider, path, &lenient).map_err(|d| diag_error(path, &[d]))?;
        preprocess::assume_glsl_110(&mut p);
        as_preprocessed.insert(stage, p.text.clone());
        // The render path lowers the stage at the version it declares.
        (p.text, _) = iris::as_transformed(p.text.clone(), &as_preprocessed[&stage], iris::Transform { raises_version: false, ..reading.transform }, Some(stage));
        if stage == Stage::Vertex {
            p.text = with_lod_material_attribute(name, &p.text)?;
        }
        // What the driver meets, for `compat::for_strict_drivers`, which rewrites the text for
        // OpenGL and lists the rewrites; naga gets what NVIDIA makes of it.
        met_by_driver.insert(stage, p.text.clone());
        if let Some((text, _)) = tidepack_glsl::compat::lenient_expressions(&p.text) {
            p.text = text;
        }
        if let Some((text, _)) = tidepack_glsl::compat::constants_made_variables(&p.text) {
            p.text = text;
        }
        pre.push((stage, Arc::new(p)));
    }
    // Varyings the stages declare at other float sizes, which NVIDIA links: the fragment stage
    // reads them at the vertex stage's, for naga here and for OpenGL below.
    let resized = tidepack_glsl::compat::varyings_resized(&pre[0].1.text, &pre[1].1.text);
    if let Some((text, _)) = tidepack_glsl::compat::inputs_resized(&pre[1].1.text, &resized)
        && let Some(fragment) = Arc::get_mut(&mut pre[1].1)
    {
        fragment.text = text;
    }
    let declared_targets = pre[1].1.render_targets.as_ref().map(|rt| rt.buffers.clone());
    let lowered = naga_check::lower_program(&pre).map_err(|d| diag_error(&format!("{name} does not lower"), &[d]))?;
    let fragment_lowered = lowered.iter().find(|s| s.stage == Stage::Fragment).map(|s| s.lowered.text.clone()).unwrap_or_default();
    let mut frontend = naga_check::Frontend::default();
    let mut stages = Vec::new();
    for stage in lowered {
        let path = stage.preprocessed.files[0].clone();
        let lowered_text = stage.lowered.text.clone();
        let mut narrow_outputs = BTreeMap::new();
        let mut interface = stage.lowered.interface.clone();
        let ExpandedStage { text: expanded, line_map, moved_first, settings_text } =
            expanded_as_loader_gives_it(provider, &path, macros, &defines, &stage.preprocessed, &as_preprocessed[&stage.stage], reading)?;
        let lines_from = |at: &Location| lines_from(&line_map, at);
        let redefined = redefined_lines(&stage.preprocessed, &line_map);
        let located = |line: u32, what: &str| located_rewrite(&line_map, &path, line, what);
        // What only lenient compilers accept, rewritten for OpenGL and located in the pack.
        let for_opengl = |expanded: &str| {
            let (text, rewrites) = tidepack_glsl::compat::for_strict_drivers(expanded, &met_by_driver[&stage.stage], stage.stage, &redefined);
            (text, rewrites.iter().map(|r| located(r.line, &r.what)).collect::<Vec<_>>())
        };
        let (mut expanded, transformed) = iris::as_transformed(expanded, &as_preprocessed[&stage.stage], reading.transform, Some(stage.stage));
        let mut loader_rewrites: Vec<String> = moved_first.into_iter().chain(transformed).map(|what| format!("{path}: {what}")).collect();
        if stage.stage == Stage::Fragment
            && let Some((text, what)) = tidepack_glsl::compat::inputs_resized(&expanded, &resized)
        {
            expanded = text;
            loader_rewrites.push(format!("{path}: {what}"));
        }
        if stage.stage == Stage::Vertex
            && files.geometry.is_none()
            && let Some((text, what)) = tidepack_glsl::compat::vertex_outputs_completed(&expanded, &met_by_driver[&Stage::Fragment])
        {
            expanded = text;
            loader_rewrites.push(format!("{path}: {what}"));
        }
        let (mut gl_text, mut gl_rewrites) = for_opengl(&expanded);
        gl_rewrites.extend(loader_rewrites.iter().cloned());
        // A fragment stage that writes no output 0 (one that only discards) leaves the test
        // nothing to read: it draws untested.
        let writes_output_0 = lowered_output(&lowered_text, 0).is_some();
        let alpha_test = if stage.stage == Stage::Fragment && writes_output_0 { alpha_test(&gl_text) } else { None };
        let harness_text = match stage.stage {
            Stage::Vertex => adapt_vertex(&complete_vertex_outputs(&lowered_text, &fragment_lowered))?,
            Stage::Fragment => {
                let (writing, kept) = without_outputs_writing_no_buffer(&lowered_text);
                // Outputs named `gl_FragData[i]` are not declarations of the shipped text.
                interface.outputs.retain(|location, name| name.starts_with("gl_") || kept.contains(location));
                let (text, mut epilogue, widened) = widen_fragment_outputs(&writing);
                narrow_outputs = widened;
                if let (Some(reference), Some(output)) = (alpha_test, lowered_output(&lowered_text, 0)) {
                    epilogue.push_str(&alpha_test_statement(&output, reference));
                }
                if epilogue.is_empty() { text } else { wrap_main(&text, &epilogue)? }
            }
        };
        let adapted = LoweredStage {
            stage: stage.stage,
            preprocessed: stage.preprocessed.clone(),
            lowered: tidepack_glsl::lower::Lowered { text: harness_text.clone(), interface: interface.clone() },
        };
        let validated = naga_check::validate_stage(&mut frontend, &adapted, provider);
        // What naga's checks repaired as NVIDIA takes it is repaired for OpenGL too, at the same
        // lines of the pack, before the other rewrites.
        if let Some(repairs) = validated.as_ref().ok().map(|v| &v.lenient_repairs).filter(|r| !r.is_empty()) {
            use tidepack_glsl::naga_check::Leniency;
            let mut repaired = expanded.clone();
            let mut made = Vec::new();
            for repair in repairs {
                for line in repair.location.as_ref().map(lines_from).unwrap_or_default() {
                    let (text, what) = match &repair.leniency {
                        Leniency::Converted { constructor, value, beside } => {
                            let Some((text, value)) = tidepack_glsl::compat::convert_on_line(&repaired, line, constructor, value, beside.as_deref()) else { continue };
                            (text, format!("`{value}` converted with {constructor}() as NVIDIA converts it implicitly"))
                        }
                        Leniency::Replaced { written, with } => {
                            let Some(text) = tidepack_glsl::compat::replace_on_line(&repaired, line, written, with) else { continue };
                            (text, format!("`{written}`, which NVIDIA takes component by component, written `{with}`"))
                        }
                        Leniency::OffsetAsCoordinate { dimensions, vertex } => {
                            let Some((text, n)) = tidepack_glsl::compat::offsets_as_coordinates_on_line(&repaired, line, *dimensions, *vertex) else { continue };
                            let lookups = if n == 1 { "a lookup" } else { "lookups" };
                            (text, format!("{lookups} with an offset that is not a constant (NVIDIA takes it) made at the moved coordinate ({n})"))
                        }
                    };
                    repaired = text;
                    made.push(located(line, &what));
                }
            }
            (gl_text, gl_rewrites) = for_opengl(&repaired);
            gl_rewrites.extend(loader_rewrites.iter().cloned());
            gl_rewrites.extend(made);
        }
        if stage.stage == Stage::Vertex {
            gl_text = with_lod_material_attribute(name, &gl_text)?;
        }
        let naga = validated.map(|valid| valid.module).map_err(|d| match diag_error(&format!("{path} does not validate"), &d) {
            // naga names functions as the harness text has them: the shipped main is renamed for
            // the harness's own (see `adapt_vertex`).
            HarnessError::Pack(message) => message.replace("'tp_shipped_main'", "'main'"),
            other => other.to_string(),
        });
        if let Some(reference) = alpha_test {
            let output = stage.lowered.interface.outputs.get(&0).cloned().unwrap_or_else(|| "gl_FragData[0]".into());
            gl_text = with_alpha_test(&gl_text, &output, reference)?;
        }
        let gl_origins = origins_of_rewritten(&gl_text, &expanded, &line_map);
        stages.push(LoadedStage {
            stage: stage.stage,
            path,
            gl_text,
            gl_rewrites,
            gl_origins,
            settings_text,
            lowered_text,
            harness_text,
            interface,
            naga,
            narrow_outputs,
        });
    }
    let fragment = stages.pop().expect("two stages");
    let vertex = stages.pop().expect("two stages");
    let geometry = match &files.geometry {
        Some(path) => Some(load_opengl_stage(provider, path, macros, &defines, reading)?),
        None => None,
    };
    let render_targets = match (declared_targets, reading.undeclared) {
        (Some(buffers), _) => buffers,
        (None, UndeclaredTargets::Outputs) => (0..fragment.interface.outputs.keys().max().map_or(1, |m| m + 1) as u8).map(Some).collect(),
        (None, UndeclaredTargets::FirstOnly) => vec![Some(0)],
    };
    Ok(LoadedProgram { name: name.to_string(), vertex, geometry, fragment, render_targets })
}

/// A geometry or compute stage's text for OpenGL, read as the vertex and fragment stages are,
/// with the rewrites for strict drivers that apply to any stage but the vertex stage.
fn load_opengl_stage(
    provider: &dyn FileProvider,
    path: &str,
    macros: &preprocess::PreprocessOptions,
    defines: &str,
    reading: LoaderReading,
) -> Result<OpenGlStage, HarnessError> {
    let lenient = preprocess::PreprocessOptions { lenient: true, ..macros.clone() };
    let mut preprocessed = preprocess::preprocess(provider, path, &lenient).map_err(|d| diag_error(path, &[d]))?;
    preprocess::assume_glsl_110(&mut preprocessed);
    let ExpandedStage { text: expanded, line_map, moved_first, .. } = expanded_as_loader_gives_it(provider, path, macros, defines, &preprocessed, &preprocessed.text, reading)?;
    let (expanded, raised) = iris::as_transformed(expanded, &preprocessed.text, iris::Transform { raises_version: reading.transform.raises_version, ..Default::default() }, None);
    let redefined = redefined_lines(&preprocessed, &line_map);
    let (gl_text, rewrites) = tidepack_glsl::compat::for_strict_drivers(&expanded, &preprocessed.text, Stage::Fragment, &redefined);
    let mut gl_rewrites: Vec<String> = moved_first.into_iter().chain(raised).map(|what| format!("{path}: {what}")).collect();
    gl_rewrites.extend(rewrites.iter().map(|r| located_rewrite(&line_map, path, r.line, &r.what)));
    let gl_origins = origins_of_rewritten(&gl_text, &expanded, &line_map);
    Ok(OpenGlStage { path: path.to_string(), gl_text, gl_rewrites, gl_origins })
}

/// A compute stage of a program (`composite1.csh`, `composite1_a.csh`): the loader runs it
/// before the program's own stages, over the frame (OptiFine's shaders.txt, "Compute Shaders";
/// Iris alike). Only OpenGL dispatches it.
#[derive(Clone, Debug)]
pub struct ComputeStage {
    /// The program it belongs to (`composite1`), which may have no other stage.
    pub program: String,
    pub stage: OpenGlStage,
    pub work_groups: WorkGroups,
    /// `layout(local_size_x = …, local_size_y = …, local_size_z = …) in;`, 1 where unsaid.
    pub local_size: [u32; 3],
    /// The colour buffers it names as images (`colorimg3`: colortex3), which it reads and
    /// writes in place.
    pub images: Vec<u8>,
    /// The shadow colour buffers it names as images (`shadowcolorimg1`: shadowcolor1), read and
    /// written in place likewise.
    pub shadow_images: Vec<u8>,
}

impl ComputeStage {
    /// Why wgpu does not draw this stage's step.
    pub fn only_opengl(&self) -> String {
        format!("{}: a compute stage, which only OpenGL dispatches here", self.stage.path)
    }
}

/// How many work groups a compute stage is dispatched with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum WorkGroups {
    /// `const ivec3 workGroups = ivec3(x, y, z);`
    Fixed([u32; 3]),
    /// `const vec2 workGroupsRender = vec2(x, y);`: enough groups of the stage's local size to
    /// cover that share of the frame, one invocation per pixel at `vec2(1.0)`, the default.
    Render([f32; 2]),
}

impl WorkGroups {
    /// What `text` (the stage, preprocessed) declares, read as the loader reads its `const`
    /// settings; the default where it declares neither.
    pub fn declared(text: &str) -> WorkGroups {
        let value = |name: &str, constructor: &str, components: usize| {
            tidepack_loader::consts::declarations(text).find(|d| d.name == name).and_then(|d| d.vector(constructor, components))
        };
        if let Some(n) = value("workGroups", "ivec3", 3) {
            return WorkGroups::Fixed([n[0], n[1], n[2]].map(|v| v.max(0.0) as u32));
        }
        match value("workGroupsRender", "vec2", 2) {
            Some(n) => WorkGroups::Render([n[0] as f32, n[1] as f32]),
            None => WorkGroups::Render([1.0, 1.0]),
        }
    }

    /// The groups to dispatch for a frame of `width` x `height` and a local size of `local`.
    pub fn count(self, width: u32, height: u32, local: [u32; 3]) -> [u32; 3] {
        match self {
            WorkGroups::Fixed(groups) => groups,
            WorkGroups::Render([x, y]) => {
                let cover = |pixels: u32, share: f32, local: u32| ((pixels as f32 * share).ceil().max(0.0) as u32).div_ceil(local.max(1));
                [cover(width, x, local[0]), cover(height, y, local[1]), 1]
            }
        }
    }
}

/// Loads the compute stage at `path` of `program` as OpenGL compiles it, with `macros`
/// predefined.
pub(crate) fn load_compute_stage(
    provider: &dyn FileProvider,
    program: &str,
    path: &str,
    macros: &preprocess::PreprocessOptions,
    reading: LoaderReading,
) -> Result<ComputeStage, HarnessError> {
    let defines: String = macros.predefined.iter().map(|(k, v)| format!("#define {k} {v}\n")).collect();
    let lenient = preprocess::PreprocessOptions { lenient: true, ..macros.clone() };
    let preprocessed = preprocess::preprocess(provider, path, &lenient).map_err(|d| diag_error(path, &[d]))?;
    let work_groups = WorkGroups::declared(&preprocessed.text);
    let tokens = tokenize(&preprocessed.text).unwrap_or_default();
    let named: BTreeSet<ImageOf> = tokens.iter().filter(|t| t.kind == TokenKind::Ident).filter_map(|t| buffer_of_image(t.text)).collect();
    let images = named.iter().filter_map(|image| if let ImageOf::Colour(n) = image { Some(*n) } else { None }).collect();
    let shadow_images = named.iter().filter_map(|image| if let ImageOf::ShadowColour(n) = image { Some(*n) } else { None }).collect();
    let local_size = tidepack_glsl::lower::local_size(&tokens).unwrap_or([1; 3]);
    let stage = load_opengl_stage(provider, path, macros, &defines, reading)?;
    Ok(ComputeStage { program: program.to_string(), stage, work_groups, local_size, images, shadow_images })
}

/// `text`, a vertex stage of `program`, with `dhMaterialId` read as Iris gives it where a
/// Distant Horizons program uses it undeclared: each use reads [`LOD_MATERIAL_INPUT`], declared
/// before the first line of code. Line numbers are kept.
fn with_lod_material_attribute(program: &str, text: &str) -> Result<String, HarnessError> {
    if !programs::DISTANT_HORIZONS_PROGRAMS.contains(&program) || !programs::uses_undeclared_dh_material_id(text) {
        return Ok(text.to_string());
    }
    let tokens = tokenize(text).map_err(|e| HarnessError::Pack(format!("shader text: {}", e.message)))?;
    let read = format!("int({LOD_MATERIAL_INPUT}.x + 0.5)");
    let replaced: String = tokens.iter().map(|t| if t.text == "dhMaterialId" { read.as_str() } else { t.text }).collect();
    Ok(programs::declare_before_code(&replaced, &format!("attribute vec4 {LOD_MATERIAL_INPUT};")).into_owned())
}

/// The one change the harness makes to a lowered vertex shader: the shipped `main` becomes
/// `tp_shipped_main`, and a new `main` on the last line calls it and then maps OpenGL's clip
/// space to wgpu's: y flipped (buffers are stored bottom row first, as in OpenGL) and z from
/// -w..w to 0..w (the depth buffer then holds OpenGL's window depth). No line is added, so
/// naga's line numbers still map to the pack's files.
pub fn adapt_vertex(lowered: &str) -> Result<String, HarnessError> {
    wrap_main(lowered, "gl_Position.y = -gl_Position.y; gl_Position.z = 0.5 * (gl_Position.z + gl_Position.w);")
}

/// A fragment stage with a loader's alpha test after its `main`: the fragment is discarded
/// unless `output`'s alpha is above `reference` (OpenGL's `GREATER`).
///
/// `text` is shipped text as the driver compiles it, preprocessor branches and all (a pack may
/// define `main` once per stage under `#ifdef`s, and end on `#endif`): a `#define` after the
/// `#version` line renames whichever `main` is compiled, and the new `main` follows the last
/// line. Lines after `#version` are numbered one further on.
pub fn with_alpha_test(text: &str, output: &str, reference: f32) -> Result<String, HarnessError> {
    let mut lines: Vec<&str> = text.lines().collect();
    let after_version = lines.iter().position(|l| l.trim_start().starts_with("#version")).map_or(0, |i| i + 1);
    lines.insert(after_version, "#define main tp_shipped_main");
    let statement = alpha_test_statement(output, reference);
    Ok(format!("{}\n#undef main\nvoid main() {{ tp_shipped_main(); {statement} }}\n", lines.join("\n")))
}

fn alpha_test_statement(output: &str, reference: f32) -> String {
    format!("if (!({output}.a > {reference:?})) {{ discard; }}")
}

/// The location-`location` output a lowered fragment stage declares
/// (`layout(location = 0) out vec4 outColor0;`).
fn lowered_output(lowered: &str, location: u32) -> Option<String> {
    let declaration = format!("layout(location = {location}) out vec4 ");
    let at = lowered.find(&declaration)? + declaration.len();
    let name: String = lowered[at..].chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
    (!name.is_empty()).then_some(name)
}

/// A `layout(location = N) [qualifiers] in|out TYPE NAME;` declaration of a lowered stage.
pub(crate) struct InterfaceDeclaration<'a> {
    location: u32,
    /// The statement's bytes in the text, `;` included.
    statement: std::ops::Range<usize>,
    /// Everything after the location: qualifiers, direction, type and name (with any array size).
    pub(crate) words: Vec<&'a str>,
}

impl InterfaceDeclaration<'_> {
    pub(crate) fn direction(&self) -> Option<&str> {
        self.words.iter().copied().find(|w| matches!(*w, "in" | "out"))
    }
}

/// The single-variable interface declarations of a lowered stage (blocks are left out).
pub(crate) fn interface_declarations(text: &str) -> Vec<InterfaceDeclaration<'_>> {
    const HEAD: &str = "layout(location = ";
    let mut found = Vec::new();
    let mut from = 0;
    while let Some(at) = text[from..].find(HEAD).map(|i| from + i) {
        let Some(end) = text[at..].find(';').map(|i| at + i + 1) else { break };
        from = at + HEAD.len();
        let rest = &text[from..end - 1];
        let Some((number, tail)) = rest.split_once(')') else { continue };
        let (Ok(location), false) = (number.trim().parse::<u32>(), tail.contains(['{', '}', '('])) else { continue };
        found.push(InterfaceDeclaration { location, statement: at..end, words: tail.split_whitespace().collect() });
    }
    found
}

/// The lowered vertex stage with an output declared for every input of the fragment stage it
/// lacks. OpenGL links such a program (before GLSL 4.20) and the input's value is undefined;
/// wgpu refuses the pipeline. The declarations go at the end of the line after `#version`, so
/// no line moves.
fn complete_vertex_outputs(vertex: &str, fragment: &str) -> String {
    let vertex_outputs: Vec<InterfaceDeclaration> = interface_declarations(vertex).into_iter().filter(|d| d.direction() == Some("out")).collect();
    let declared = |input: &InterfaceDeclaration| vertex_outputs.iter().any(|o| o.location == input.location || o.words.last() == input.words.last());
    let mut added = String::new();
    for input in interface_declarations(fragment).iter().filter(|d| d.direction() == Some("in") && !declared(d)) {
        let words: Vec<&str> = input.words.iter().map(|w| if *w == "in" { "out" } else { w }).collect();
        added.push_str(&format!(" layout(location = {}) {};", input.location, words.join(" ")));
    }
    insert_after_version_line(vertex, &added)
}

/// `text` with every float literal moved by `relative` of itself (`0.5` becomes `5.000002e-1`),
/// its suffix kept; integers, hexadecimal ones included, unchanged.
fn float_literals_nudged(text: &str, relative: f64) -> String {
    let Ok(tokens) = tokenize(text) else { return text.to_string() };
    tokens
        .iter()
        .map(|t| {
            let hex = t.text.starts_with("0x") || t.text.starts_with("0X");
            let digits = t.text.trim_end_matches(['f', 'F', 'l', 'L']);
            match digits.parse::<f64>() {
                Ok(value) if t.kind == TokenKind::Number && !hex && t.text.contains(['.', 'e', 'E']) => {
                    format!("{:e}{}", value * (1.0 + relative), &t.text[digits.len()..])
                }
                _ => t.text.to_string(),
            }
        })
        .collect()
}

/// `text` with `addition` at the end of its second line (the one after `#version`).
fn insert_after_version_line(text: &str, addition: &str) -> String {
    if addition.is_empty() {
        return text.to_string();
    }
    let second_line_end = text.match_indices('\n').nth(1).map_or(text.len(), |(i, _)| i);
    format!("{}{addition}{}", &text[..second_line_end], &text[second_line_end..])
}

/// The lowered fragment stage with every `float`, `vec2` or `vec3` output widened to `vec4`
/// (wgpu wants an output for each channel of its buffer; OpenGL leaves the missing channels
/// undefined): the declaration becomes a plain global, and a `vec4` output at its location
/// takes its value at the end of `main` (`epilogue`). Returns the text, the epilogue, and
/// each widened location with its original channel count.
fn widen_fragment_outputs(fragment: &str) -> (String, String, BTreeMap<u32, u8>) {
    let mut text = fragment.to_string();
    let mut epilogue = String::new();
    let mut widened = BTreeMap::new();
    // From the end, so earlier byte ranges stay valid.
    for declaration in interface_declarations(fragment).iter().rev() {
        let [.., direction, ty, name] = declaration.words.as_slice() else { continue };
        // A vec4 fills its buffer already.
        let Some(channels) = tidepack_glsl::lower::float_components(ty).filter(|&n| n < 4) else { continue };
        if *direction != "out" || name.contains('[') {
            continue;
        }
        let location = declaration.location;
        text.replace_range(declaration.statement.clone(), &format!("{ty} {name}; layout(location = {location}) out vec4 tp_widened{location};"));
        let zeros = ", 0.0".repeat(4 - channels);
        epilogue.push_str(&format!("tp_widened{location} = vec4({name}{zeros}); "));
        widened.insert(location, channels as u8);
    }
    (text, epilogue, widened)
}

/// Fragment outputs that write no draw buffer, made plain variables:
/// - those at a location no draw buffer has (8 on): the loaders bind no buffer there and drop
///   what they hold, and wgpu refuses a pipeline with such an output (`layout(location = 0..9)
///   out vec4 FD0..FD9;` declared in one header for every program);
/// - those the stage never names but in their declaration: their buffers get undefined values
///   in OpenGL, and both renderers leave them as they were
///   ([`LoadedProgram::draw_buffers_never_written`]).
///
/// Returns the text and the locations of the outputs that remain.
fn without_outputs_writing_no_buffer(fragment: &str) -> (String, BTreeSet<u32>) {
    let mut text = fragment.to_string();
    let mut kept = BTreeSet::new();
    let tokens = tokenize(fragment).unwrap_or_default();
    let named_once = |name: &str| tokens.iter().filter(|t| t.text == name).count() == 1;
    for declaration in interface_declarations(fragment).iter().rev() {
        if let [.., "out", ty, name] = declaration.words.as_slice() {
            if declaration.location as usize >= preprocess::MAX_DRAW_BUFFERS || named_once(name) {
                text.replace_range(declaration.statement.clone(), &format!("{ty} {name};"));
            } else {
                kept.insert(declaration.location);
            }
        }
    }
    (text, kept)
}

/// Renames the definition of `main` to `tp_shipped_main` and appends, on the last line, a new
/// `main` that calls it and then runs `epilogue`.
fn wrap_main(text: &str, epilogue: &str) -> Result<String, HarnessError> {
    let tokens = tokenize(text).map_err(|e| HarnessError::Pack(format!("shader text: {}", e.message)))?;
    // The definition, not a prototype.
    let main_at = function_definitions(&tokens).into_iter().map(|f| f.name).rfind(|&name| {
        tokens[name].text == "main" && tokens[..name].iter().rev().find(|t| !t.is_trivia()).is_some_and(|t| t.text == "void")
    });
    let main_at = main_at.ok_or_else(|| HarnessError::Pack("the shader has no `void main() { ... }`".into()))?;
    let mut out = String::with_capacity(text.len() + 160);
    for (i, t) in tokens.iter().enumerate() {
        out.push_str(if i == main_at { "tp_shipped_main" } else { t.text });
    }
    if out.ends_with('\n') {
        out.pop();
    }
    out.push_str(&format!(" void main() {{ tp_shipped_main(); {epilogue} }}\n"));
    Ok(out)
}

/// The buffer and format name of each `const int <buffer>Format = <FORMAT>;` line, buffers
/// numbered by `number` ([`colour_buffer_number`] or
/// [`tidepack_loader::buffers::shadow_colour_number`]).
pub(crate) fn declared_format_names(text: &str, number: fn(&str) -> Option<u8>) -> Vec<(u8, String)> {
    consts::declarations(text)
        .filter(|d| d.ty == "int")
        .filter_map(|d| Some((number(d.name.strip_suffix("Format")?)?, d.value.to_string())))
        .collect()
}

/// The `texture.<stage>.<unit>` entries' textures: the image `read_bytes` gives for the path,
/// or its raw texels as the words after the path lay them out, with the filter and wrap of its
/// `.mcmeta`; and the game textures entries bind. Entries the harness cannot honour come back
/// as messages naming the key, for the caller to refuse or report.
pub(crate) fn custom_textures(
    read_bytes: &dyn Fn(&str) -> Result<Vec<u8>, String>,
    provider: &dyn FileProvider,
    properties: &Properties,
) -> Result<PackTextures, HarnessError> {
    let mut found = Vec::new();
    let mut game = Vec::new();
    let mut unsupported = Vec::new();
    for entry in directives::textures(properties) {
        let (key, path) = (&entry.key, &entry.path);
        if !matches!(entry.stage.as_str(), "gbuffers" | "prepare" | "deferred" | "composite") {
            unsupported.push(format!("{key}: the harness binds custom textures in gbuffers, prepare, deferred and composite programs only"));
            continue;
        }
        if entry.resource {
            match samplers::game_texture(path) {
                Some(source) => game.push(GameTextureBinding { stage: entry.stage.clone(), unit: entry.unit.clone(), source }),
                None => unsupported.push(format!("{key}={path}: the harness holds no textures of the game's assets")),
            }
            continue;
        }
        let raw = match (entry.raw.is_empty(), RawLayout::parse(&entry.raw)) {
            (true, _) => None,
            (false, Ok(layout)) if layout.target != TextureTarget::Rectangle => Some(layout),
            (false, Ok(_)) => {
                unsupported.push(format!("{key}={path}: TEXTURE_RECTANGLE raw textures are not made"));
                continue;
            }
            (false, Err(e)) => {
                unsupported.push(format!("{key}={path}: {e}"));
                continue;
            }
        };
        let side = raw.as_ref().map_or(0, |layout| layout.size.into_iter().max().unwrap_or(0));
        if let Some(layout) = raw.as_ref().filter(|layout| side > largest_side(layout.target)) {
            let [w, h, d] = layout.size;
            unsupported.push(format!("{key}={path}: {w}x{h}x{d} texels, more along a side than the {} the harness's renderers take", largest_side(layout.target)));
            continue;
        }
        let bytes = match read_bytes(path) {
            Ok(bytes) => bytes,
            Err(e) => {
                unsupported.push(format!("{key}: {e}"));
                continue;
            }
        };
        let (target, [width, height, depth], texels) = match raw {
            Some(layout) => (layout.target, layout.size, raw_texture::decode(&bytes, &layout).map_err(|e| HarnessError::Pack(format!("{key}: {path} {e}")))?),
            None => {
                let decoded = decode_within_budget(&bytes, path).map_err(|e| HarnessError::Pack(format!("{key}: {path} {e}")))?;
                if decoded.width().max(decoded.height()) > largest_side(TextureTarget::D2) {
                    let (w, h) = decoded.dimensions();
                    unsupported.push(format!("{key}={path}: {w}x{h} pixels, more along a side than the {} the harness's renderers take", largest_side(TextureTarget::D2)));
                    continue;
                }
                (TextureTarget::D2, [decoded.width(), decoded.height(), 1], Texels::Rgba8(decoded.into_raw()))
            }
        };
        let meta = provider.read(&format!("{path}.mcmeta")).map(|t| t.to_string()).unwrap_or_default();
        let flag = |name: &str| {
            meta.split(&format!("\"{name}\"")).nth(1).is_some_and(|rest| rest.trim_start_matches([' ', ':']).starts_with("true"))
        };
        found.push(CustomTexture {
            stage: entry.stage.clone(),
            unit: entry.unit.clone(),
            path: path.clone(),
            target,
            width,
            height,
            depth,
            blur: flag("blur"),
            clamp: flag("clamp"),
            texels,
        });
    }
    Ok(PackTextures { custom: found, game, unsupported })
}

/// What the `texture.<stage>.<unit>` entries of a pack bind ([`custom_textures`]).
pub(crate) struct PackTextures {
    pub custom: Vec<CustomTexture>,
    pub game: Vec<GameTextureBinding>,
    /// A message per entry the harness cannot honour, naming its key.
    pub unsupported: Vec<String>,
}

/// The longest side of a custom texture of `target` that every wgpu device takes (WebGPU's
/// defaults: 8192 for 1D and 2D, 2048 for 3D); OpenGL drivers take at least as much.
fn largest_side(target: TextureTarget) -> u32 {
    match target {
        TextureTarget::D3 => 2048,
        TextureTarget::D1 | TextureTarget::D2 | TextureTarget::Rectangle => 8192,
    }
}

/// Most pixels a custom texture may have: 4096², 64 MiB decoded as RGBA8.
pub const MAX_CUSTOM_TEXTURE_PIXELS: u64 = 4096 * 4096;

/// Decodes an image whose header's size is within [`MAX_CUSTOM_TEXTURE_PIXELS`], read before
/// anything is decoded; the decoder's own allocations are held to the same budget. The format
/// is the one the bytes show, or for a format without a signature (TGA) the one `path`'s
/// extension names.
fn decode_within_budget(bytes: &[u8], path: &str) -> Result<image::RgbaImage, String> {
    let reader = || {
        let mut reader = image::ImageReader::new(std::io::Cursor::new(bytes)).with_guessed_format().map_err(|e| format!("is not a readable image: {e}"))?;
        if reader.format().is_none()
            && let Ok(format) = image::ImageFormat::from_path(path)
        {
            reader.set_format(format);
        }
        Ok::<_, String>(reader)
    };
    let (width, height) = reader()?.into_dimensions().map_err(|e| format!("is not a readable image: {e}"))?;
    if u64::from(width) * u64::from(height) > MAX_CUSTOM_TEXTURE_PIXELS {
        return Err(format!("is {width}x{height} pixels, more than the budget of {MAX_CUSTOM_TEXTURE_PIXELS} (4096x4096) for a custom texture"));
    }
    let mut reader = reader()?;
    let mut limits = image::Limits::default();
    limits.max_alloc = Some(4 * MAX_CUSTOM_TEXTURE_PIXELS * 2);
    reader.limits(limits);
    Ok(reader.decode().map_err(|e| format!("is not a readable image: {e}"))?.to_rgba8())
}

/// A pack's `file` (block.properties or entity.properties) read under `set` as the loader of
/// `standard` reads it: name → id of its `<prefix>.<id>` entries.
pub(crate) fn mapped_ids(
    provider: &dyn FileProvider,
    file: &str,
    prefix: &str,
    standard: &StandardMacros,
    declared: &BTreeMap<String, OptionKind>,
    set: &OptionSet,
) -> HashMap<String, i32> {
    let text = provider.read(file).map(|t| t.to_string()).unwrap_or_default();
    blocks::ids(&read_properties(&text, standard, declared, set), prefix)
}

/// Whether `text` declares a buffer block (`layout(std430, binding = 0) buffer Data { … }`).
pub fn declares_buffer_block(text: &str) -> bool {
    let Ok(tokens) = tokenize(text) else { return false };
    let sig: Vec<&Token> = tokens.iter().filter(|t| !t.is_trivia()).collect();
    sig.windows(3).any(|w| w[0].is_ident("buffer") && w[1].kind == TokenKind::Ident && w[2].is_punct("{"))
}

/// The image uniforms (`uniform image3D voxels;`, any layout and memory qualifiers before the
/// type) a stage's text declares at file scope, by name.
pub fn image_uniforms(text: &str) -> Vec<String> {
    uniforms_of_type(text, tidepack_glsl::lower::is_image_type)
}

/// The sampler uniforms (`uniform sampler2D colortex3;`, `usampler2D`, …) a stage's text
/// declares at file scope, by name: what a compute stage reads, which naga's interface does not
/// give for the stages only OpenGL runs.
pub fn sampler_uniforms(text: &str) -> Vec<String> {
    uniforms_of_type(text, |ty| ["sampler", "isampler", "usampler"].iter().any(|prefix| ty.starts_with(prefix)))
}

/// The uniforms of a type `is_type` takes, by name.
fn uniforms_of_type(text: &str, is_type: fn(&str) -> bool) -> Vec<String> {
    use tidepack_glsl::lower::is_memory_qualifier;
    let Ok(tokens) = tokenize(text) else { return Vec::new() };
    let sig: Vec<_> = tokens.iter().filter(|t| !t.is_trivia()).collect();
    let mut names = Vec::new();
    for (k, t) in sig.iter().enumerate() {
        if !t.is_ident("uniform") {
            continue;
        }
        // Memory and precision qualifiers may stand between `uniform` and the type.
        let qualifier = |m: &usize| sig[*m].kind == TokenKind::Ident && (is_memory_qualifier(sig[*m].text) || matches!(sig[*m].text, "highp" | "mediump" | "lowp"));
        let Some(type_at) = (k + 1..sig.len()).find(|m| !qualifier(m)) else { continue };
        if is_type(sig[type_at].text) && let Some(name) = sig.get(type_at + 1).filter(|n| n.kind == TokenKind::Ident) {
            names.push(name.text.to_string());
        }
    }
    names
}

/// The shipped name of a lowered resource: the interface maps shipped names to resource kinds;
/// textures lowered from the atlas name `texture` are called `gtexture`.
pub fn texture_resources(interface: &Interface) -> Vec<(String, u32)> {
    interface
        .resources
        .iter()
        .filter_map(|(name, kind)| match kind {
            ResourceKind::Texture { binding, .. } => Some((name.clone(), *binding)),
            ResourceKind::Uniform { .. } => None,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    /// A driver's line names the pack line it came from through the compat rewrites: an inserted
    /// line takes its predecessor's origin, a changed one too, and the lines after follow.
    #[test]
    fn rewritten_lines_keep_their_pack_origins() {
        use super::{Location, origins_of_rewritten};
        let expanded = "#version 120\nvarying vec4 c;\n#define A 1\n#define A 2\nvoid main() {\n    float f = 1;\n    gl_FragColor = c;\n}\n";
        let origins: Vec<Option<Location>> = (1..=8).map(|l| Some(Location::line(if l == 7 { "lib/out.glsl" } else { "a.fsh" }, l))).collect();
        let rewritten = "#version 120\nvarying vec4 c;\n#define A 1\n#undef A\n#define A 2\nvoid main() {\n    float f = float(1);\n    gl_FragColor = c;\n}\n";
        let found: Vec<String> = origins_of_rewritten(rewritten, expanded, &origins).iter().map(|o| o.as_ref().unwrap().to_string()).collect();
        assert_eq!(found, ["a.fsh:1", "a.fsh:2", "a.fsh:3", "a.fsh:3", "a.fsh:4", "a.fsh:5", "a.fsh:6", "lib/out.glsl:7", "a.fsh:8"]);
    }

    use super::*;

    #[test]
    fn float_literals_are_nudged_and_integers_kept() {
        let text = "float x = 0.5 * 43758.5453 + 2.0f + 1e3; int i = 3; uint u = 0x1Fu; float z = 0.0;";
        let nudged = float_literals_nudged(text, 0.5);
        assert_eq!(nudged, "float x = 7.5e-1 * 6.563781795e4 + 3e0f + 1.5e3; int i = 3; uint u = 0x1Fu; float z = 0e0;");
    }

    #[test]
    fn a_custom_texture_over_the_budget_is_refused_before_it_is_decoded() {
        let encode = |side: u32| {
            let mut png = Vec::new();
            image::GrayImage::new(side, side).write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png).unwrap();
            png
        };
        assert_eq!(decode_within_budget(&encode(64), "a.png").unwrap().dimensions(), (64, 64));
        let error = decode_within_budget(&encode(4097), "a.png").unwrap_err();
        assert!(error.contains("4097x4097") && error.contains("budget"), "{error}");
        assert!(decode_within_budget(b"\x89PNG\r\n\x1a\n truncated", "a.png").unwrap_err().contains("not a readable image"));
    }

    #[test]
    fn raw_texture_entries_too_large_or_unread_are_named_not_made() {
        let properties = Properties::parse_plain(
            "texture.composite.colortex5=a.dat TEXTURE_1D RG16F 2 RG HALF_FLOAT\n\
             texture.composite.colortex6=b.dat TEXTURE_3D R8 4096 1 1 RED UNSIGNED_BYTE\n\
             texture.composite.colortex7=c.dat TEXTURE_2D R32UI 1 1 RED_INTEGER UNSIGNED_INT\n\
             texture.composite.colortex8=minecraft:textures/atlas/blocks_n.png\n",
        );
        let read_bytes = |path: &str| if path == "a.dat" { Ok(vec![0u8; 8]) } else { Err(format!("{path} is not in the pack")) };
        let files: HashMap<String, Arc<str>> = HashMap::new();
        let textures = custom_textures(&read_bytes, &files, &properties).unwrap();
        assert_eq!(textures.custom.len(), 1);
        assert_eq!((textures.custom[0].target, textures.custom[0].width), (TextureTarget::D1, 2));
        assert_eq!(textures.game.len(), 1);
        assert_eq!(textures.unsupported.len(), 2, "{:?}", textures.unsupported);
        assert!(textures.unsupported[0].contains("4096x1x1 texels, more along a side than the 2048"), "{:?}", textures.unsupported);
        assert!(textures.unsupported[1].contains("integer"), "{:?}", textures.unsupported);
    }

    #[test]
    fn custom_textures_decode_in_every_format_a_loader_reads() {
        let picture = image::RgbImage::from_fn(8, 4, |x, y| image::Rgb([x as u8 * 30, y as u8 * 60, 200]));
        for format in [image::ImageFormat::Jpeg, image::ImageFormat::Bmp, image::ImageFormat::Gif, image::ImageFormat::Tga] {
            let mut bytes = Vec::new();
            image::DynamicImage::ImageRgb8(picture.clone()).write_to(&mut std::io::Cursor::new(&mut bytes), format).unwrap();
            let path = format!("textures/sky.{}", format.extensions_str()[0]);
            let decoded = decode_within_budget(&bytes, &path).unwrap_or_else(|e| panic!("{format:?}: {e}"));
            assert_eq!(decoded.dimensions(), (8, 4), "{format:?}");
        }
    }

    #[test]
    fn adapt_vertex_keeps_every_line() {
        let text = "#version 450\nvoid helper() {}\nvoid main() {\n    gl_Position = vec4(1.0);\n}\n";
        let adapted = adapt_vertex(text).unwrap();
        assert_eq!(adapted.lines().count(), text.lines().count());
        assert!(adapted.contains("void tp_shipped_main() {"));
        assert!(adapted.lines().last().unwrap().starts_with("} void main() { tp_shipped_main();"));
        assert!(adapt_vertex("#version 450\nvoid main();\n").is_err());
    }

    #[test]
    fn the_alpha_test_wraps_the_main_the_driver_compiles() {
        // Two mains under #ifdef and an #endif on the last line, as packs sharing one file
        // between stages write it.
        let text = "#version 330\nout vec4 outColor0;\n#ifdef FSH\nvoid main() {\n    outColor0 = vec4(0.0);\n}\n#else\nvoid main() {}\n#endif\n";
        let tested = with_alpha_test(text, "outColor0", 0.1).unwrap();
        assert!(tested.starts_with("#version 330\n#define main tp_shipped_main\nout vec4 outColor0;\n"), "{tested}");
        assert!(tested.ends_with("#endif\n#undef main\nvoid main() { tp_shipped_main(); if (!(outColor0.a > 0.1)) { discard; } }\n"), "{tested}");
        assert_eq!(lowered_output("layout(location = 0) out vec4 tp_FragData0; layout(location = 1) out vec4 x;", 0).as_deref(), Some("tp_FragData0"));
    }

    #[test]
    fn declared_formats_are_read_inside_comments_too() {
        let text = "/*\nconst int colortex4Format = RGBA16;\nconst int gaux2Format = RGBA32F;\n*/";
        let formats = declared_format_names(text, tidepack_loader::buffers::colour_buffer_number);
        assert_eq!(formats, vec![(4, "RGBA16".to_string()), (5, "RGBA32F".to_string())]);
    }
}
