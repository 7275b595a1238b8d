//! Any OptiFine or Iris pack, read as the loader reads it ([`tidepack_loader`]), for
//! `tidepack render --pack`: the programs of the configuration's dimension, preprocessed with
//! the pack's option values and the loader's standard macros, lowered and validated like our own
//! programs ([`crate::program`]); buffer formats and clears from the sources; blend modes,
//! custom textures and block ids from the properties files.
//!
//! Whatever the pack uses that the harness does not imitate is listed in
//! [`AnyPack::not_modelled`] by name: the frame is drawn without it, never silently.

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::path::Path;

use tidepack_glsl::preprocess::PreprocessOptions;
use tidepack_loader::blocks;
use tidepack_loader::buffers::{BufferClear, BufferFormat, buffer_of_image, colour_buffer_number, shadow_colour_number};
use tidepack_loader::consts;
use tidepack_loader::custom_uniforms;
use tidepack_loader::directives::{self, Blend, BlendFactor, BufferObject, CustomImage, DEFAULT_TRANSLUCENT_BLEND};
use tidepack_loader::input::{Limits, PackFiles, read_pack};
use tidepack_loader::loader::{ENTITY_CHAIN, FULLSCREEN_FAMILIES, Loader, OverlayKind, Phase, SKY_CHAIN, SKY_TEXTURED_CHAIN, TERRAIN_CHAIN, WATER_CHAIN};
use tidepack_loader::option_space::{declared_options, read_properties};
use tidepack_loader::programs::{self, RunBy};
use tidepack_loader::properties::{self, Properties};
use tidepack_loader::shadow::{ShadowSettings, SunPath};
use tidepack_loader::{Configuration, SetProvider};

use crate::HarnessError;
use crate::samplers::{GameTextureBinding, ProgramStage, SamplerNaming, Source, colour_buffers_named, colour_buffers_read};
use tidepack_scene::mesh::{BlockIds, PackVertex, SceneMesh, Sprites};
use crate::program::{
    self, ComputeStage, CustomTexture, LoadedProgram, LoadedStage, PackResources, ProgramFiles, UndeclaredTargets, custom_textures, declared_format_names,
};
use tidepack_scene::scene::Scene;
use crate::uniforms::{self, DrawUniforms, Pass, Value};

/// The game's blending of the sun and the moon onto the sky: added, faded by alpha.
const CELESTIAL_BLEND: Blend = Blend::Factors([BlendFactor::SrcAlpha, BlendFactor::One, BlendFactor::One, BlendFactor::Zero]);

/// The alpha test a loader applies to what a program draws, before shaders.properties's
/// `alphaTest.<program>` overrides it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum LoaderAlphaTest {
    None,
    /// Cutout terrain ([`Loader::cutout_alpha_test`]).
    Cutout,
    /// Water ([`Loader::default_water_alpha_test`]).
    Water,
}

/// Resolving sampler names before the custom textures are read: a custom texture replaces a
/// name OptiFine binds anyway, so it never turns an unbound name into a bound one.
struct NoCustomTextures(Loader);

impl PackResources for NoCustomTextures {
    fn format_of(&self, _: u8) -> BufferFormat {
        BufferFormat::Rgba8
    }

    fn custom_textures(&self) -> &[CustomTexture] {
        &[]
    }

    fn loader(&self) -> Loader {
        self.0
    }
}

#[derive(Debug)]
pub struct AnyPack {
    /// The pack as messages name it (`Pack.zip/shaders/`).
    pub display_root: String,
    pub loader: Loader,
    /// Distant Horizons beside Iris (the configuration's).
    pub distant_horizons: bool,
    /// The folder the programs come from: the dimension's (`world0/`) or the shaders folder
    /// itself (`""`).
    pub world: String,
    /// gbuffers programs the scenes can draw with, by name (fallbacks resolve among these).
    pub gbuffers: BTreeMap<String, LoadedProgram>,
    /// prepare*, deferred*, composite* and final, in the order the loader runs them.
    pub fullscreen: Vec<LoadedProgram>,
    /// shadowcomp*, in the order the loader runs them: full-screen programs drawn after the
    /// shadow pass into the shadow colour buffers, at the shadow map's size.
    pub shadow_composite: Vec<LoadedProgram>,
    /// The compute stages of those programs (and of those that have nothing else), in the
    /// order the loader runs them, each before its program.
    pub compute: Vec<ComputeStage>,
    /// The shadow pass's programs the loader's chains can draw with, by name.
    pub shadow: BTreeMap<String, LoadedProgram>,
    /// Distant Horizons' dh_terrain and dh_water, where the configuration has the mod beside
    /// Iris and the pack has them.
    pub lod: BTreeMap<String, LoadedProgram>,
    /// Whether the frame starts with the shadow pass: some program reads a shadow map (what
    /// makes OptiFine and Iris draw one) and the pack has a program to draw it with.
    pub shadow_pass: bool,
    pub shadow_settings: ShadowSettings,
    /// Whether `shadow` names shadowtex1 ([`PackResources::water_shadow`]).
    pub water_shadow: bool,
    pub formats: BTreeMap<u8, BufferFormat>,
    pub clears: BTreeMap<u8, BufferClear>,
    /// Formats and clears of the shadow colour buffers.
    pub shadow_formats: BTreeMap<u8, BufferFormat>,
    pub shadow_clears: BTreeMap<u8, BufferClear>,
    /// The colour buffers each full-screen program has mipmapped before it runs
    /// (`colortexNMipmapEnabled`), by program.
    pub mipmaps: BTreeMap<String, BTreeSet<u8>>,
    /// `flip.<program>.<buffer>=true|false` of shaders.properties, by program (`composite_pre`
    /// and `deferred_pre` flip before the first program of their family).
    pub flips: BTreeMap<String, BTreeMap<u8, bool>>,
    /// Blend modes per program and colour buffer from shaders.properties.
    pub blends: BTreeMap<String, BTreeMap<u8, Blend>>,
    pub custom_textures: Vec<CustomTexture>,
    pub game_textures: Vec<GameTextureBinding>,
    /// Iris's custom images (`image.<name>`), which OpenGL holds and wgpu does not.
    pub custom_images: Vec<CustomImage>,
    /// Iris's shader storage buffers (`bufferObject.<index>`), which OpenGL holds across the
    /// frame.
    pub buffer_objects: Vec<BufferObject>,
    /// [`PackResources::buffers_shared_across_programs`].
    buffers_shared: bool,
    pub block_ids: HashMap<String, i32>,
    /// entity.properties under the configuration: entity name → `entityId`.
    pub entity_ids: HashMap<String, i32>,
    /// shaders.properties under the configuration, for the custom uniforms of each pass.
    pub properties: Properties,
    /// What the pack uses that the frame does not imitate, one line each.
    pub not_modelled: Vec<String>,
    /// Files the programs name that the pack holds only under a name differing in case, read
    /// from that file as Windows reads a pack folder: the name, and the file's.
    pub read_by_case: BTreeMap<String, String>,
    /// Programs the loader would run that could not be loaded, with the reason.
    pub failed: Vec<(String, String)>,
    /// Programs `program.<name>.enabled` turns off for the chosen options: as if the pack had
    /// none (their fallbacks draw instead).
    pub disabled: Vec<String>,
}

impl PackResources for AnyPack {
    fn format_of(&self, buffer: u8) -> BufferFormat {
        self.formats.get(&buffer).copied().unwrap_or(BufferFormat::Rgba8)
    }

    fn custom_textures(&self) -> &[CustomTexture] {
        &self.custom_textures
    }

    fn game_textures(&self) -> &[GameTextureBinding] {
        &self.game_textures
    }

    fn custom_images(&self) -> &[CustomImage] {
        &self.custom_images
    }

    fn buffers_shared_across_programs(&self) -> bool {
        self.buffers_shared
    }

    fn shadow_settings(&self) -> ShadowSettings {
        self.shadow_settings
    }

    fn water_shadow(&self) -> bool {
        self.water_shadow
    }

    fn loader(&self) -> Loader {
        self.loader
    }
}

impl BlockIds for AnyPack {
    fn id_of(&self, block: &str) -> i32 {
        self.block_ids.get(block).copied().unwrap_or(-1)
    }
}

/// The programs of one world folder loaded as the loader loads them, with what went wrong.
struct ProgramLoading<'a> {
    provider: &'a SetProvider<'a>,
    present: BTreeMap<&'a str, &'a programs::Program>,
    disabled: &'a [String],
    properties: &'a Properties,
    macros: PreprocessOptions,
    loader: Loader,
    not_modelled: Vec<String>,
    failed: Vec<(String, String)>,
    /// The compute stages of the full-screen programs loaded, in the order the loader runs them.
    compute: Vec<ComputeStage>,
}

impl ProgramLoading<'_> {
    /// Loads `name` when the pack has it and it is not turned off; `test` is the alpha test
    /// the loader applies to what it draws.
    fn load(&mut self, name: &str, test: LoaderAlphaTest) -> Option<LoadedProgram> {
        if self.disabled.iter().any(|d| d == name) {
            return None;
        }
        let program = self.present.get(name)?;
        let reading = program::LoaderReading {
            undeclared: if self.loader == Loader::Iris { UndeclaredTargets::FirstOnly } else { UndeclaredTargets::Outputs },
            preprocessed_for_driver: self.loader.preprocesses_for_driver(),
            transform: self.loader.transform(name),
        };
        // Compute stages run before the program's own, in every program but the geometry ones.
        if !program.compute.is_empty() {
            if programs::binds_as_gbuffers(name) {
                self.not_modelled.push(format!("{name}: compute stages ({}), which the loader runs in no program that draws geometry", program.compute.join(", ")));
            } else {
                for path in &program.compute {
                    match program::load_compute_stage(self.provider, name, path, &self.macros, reading) {
                        Ok(stage) => self.compute.push(stage),
                        Err(e) => self.failed.push((name.to_string(), e.to_string())),
                    }
                }
            }
        }
        let stage_file = |stage| program.stages.iter().find(|(s, _)| *s == stage).map(|(_, path)| path.clone());
        let (geometry, tessellation): (Vec<&String>, Vec<&String>) = program.other_stages.iter().partition(|path| path.ends_with(".gsh"));
        let files = ProgramFiles {
            name,
            vertex: stage_file(tidepack_glsl::Stage::Vertex)?,
            geometry: geometry.first().map(|path| path.to_string()),
            fragment: stage_file(tidepack_glsl::Stage::Fragment)?,
        };
        if !tessellation.is_empty() {
            let files: Vec<&str> = tessellation.iter().map(|path| path.as_str()).collect();
            self.not_modelled.push(format!("{name}: tessellation stages ({})", files.join(", ")));
        }
        let (loader, properties) = (self.loader, self.properties);
        let alpha_test = |fragment: &str| {
            // Whether the program writes gl_FragData/gl_FragColor decides OptiFine 1.17+'s test.
            let legacy = ["gl_FragData", "gl_FragColor"].iter().any(|o| fragment.contains(o));
            let default = match test {
                LoaderAlphaTest::None => return None,
                LoaderAlphaTest::Cutout => loader.cutout_alpha_test(legacy),
                LoaderAlphaTest::Water => loader.default_water_alpha_test(legacy),
            };
            // An `alphaTest.<program>` setting the harness cannot imitate leaves no test.
            directives::alpha_test(properties, name, default).unwrap_or(None)
        };
        match program::load_program_files(self.provider, &files, &self.macros, &alpha_test, reading) {
            Ok(p) => {
                if test != LoaderAlphaTest::None
                    && let Err(e) = directives::alpha_test(properties, name, None)
                {
                    self.not_modelled.push(format!("{e} (no alpha test)"));
                }
                Some(p)
            }
            Err(e) => {
                self.failed.push((name.to_string(), e.to_string()));
                None
            }
        }
    }

    /// The gbuffers programs of every chain the scenes draw with, by name. A program on several
    /// chains is loaded for the first: the terrain's alpha test then holds for whatever else it
    /// draws.
    fn gbuffers(&mut self) -> BTreeMap<String, LoadedProgram> {
        let mut wanted: Vec<(&str, LoaderAlphaTest)> = TERRAIN_CHAIN.iter().map(|n| (*n, LoaderAlphaTest::Cutout)).collect();
        wanted.extend(WATER_CHAIN.iter().map(|n| (*n, LoaderAlphaTest::Water)));
        wanted.extend(SKY_CHAIN.iter().chain(&SKY_TEXTURED_CHAIN).chain(&ENTITY_CHAIN).map(|n| (*n, LoaderAlphaTest::None)));
        for kind in OverlayKind::ALL {
            wanted.extend(self.loader.program_chain(kind).iter().map(|n| (*n, LoaderAlphaTest::None)));
        }
        let mut gbuffers = BTreeMap::new();
        for (name, test) in wanted {
            if !gbuffers.contains_key(name)
                && let Some(p) = self.load(name, test)
            {
                gbuffers.insert(name.to_string(), p);
            }
        }
        gbuffers
    }

    /// The shadow programs of the loader's chains, by name.
    fn shadow(&mut self) -> BTreeMap<String, LoadedProgram> {
        let mut shadow = BTreeMap::new();
        for name in [self.loader.shadow_chain(false), self.loader.shadow_chain(true)].concat() {
            if !shadow.contains_key(name)
                && let Some(p) = self.load(name, LoaderAlphaTest::None)
            {
                shadow.insert(name.to_string(), p);
            }
        }
        shadow
    }

    /// Distant Horizons' programs Iris draws the LODs with, by name (dh_water falls back to
    /// dh_terrain: [`AnyPack::resolve_lod`]).
    fn lod(&mut self) -> BTreeMap<String, LoadedProgram> {
        ["dh_terrain", "dh_water"].into_iter().filter_map(|name| Some((name.to_string(), self.load(name, LoaderAlphaTest::None)?))).collect()
    }

    /// shadowcomp*, in the order the loader runs them (their compute stages go to `compute`).
    fn shadow_composite(&mut self) -> Vec<LoadedProgram> {
        (0..100).filter_map(|n| self.load(&if n == 0 { "shadowcomp".to_string() } else { format!("shadowcomp{n}") }, LoaderAlphaTest::None)).collect()
    }

    /// prepare*, deferred*, composite* and final, in the order the loader runs them (their
    /// compute stages, and under Iris those of setup* and begin*, go to `compute`).
    fn fullscreen(&mut self) -> Vec<LoadedProgram> {
        let mut fullscreen = Vec::new();
        // Iris's passes of compute stages alone, run before everything else: setup once, when
        // the pack loads, and begin at the start of every frame.
        if self.loader == Loader::Iris {
            for family in ["setup", "begin"] {
                for n in 0..100 {
                    let name = if n == 0 { family.to_string() } else { format!("{family}{n}") };
                    if self.load(&name, LoaderAlphaTest::None).is_some() {
                        self.not_modelled.push(format!("{name}: its vertex and fragment stages, which Iris does not run in a {family} pass"));
                    }
                }
            }
        }
        for family in FULLSCREEN_FAMILIES {
            for n in 0..100 {
                let name = if n == 0 { family.to_string() } else { format!("{family}{n}") };
                fullscreen.extend(self.load(&name, LoaderAlphaTest::None));
            }
        }
        fullscreen.extend(self.load("final", LoaderAlphaTest::None));
        fullscreen
    }
}

/// The formats, clears and mipmaps the programs' `const` lines declare.
#[derive(Default)]
struct DeclaredBuffers {
    formats: BTreeMap<u8, BufferFormat>,
    clears: BTreeMap<u8, BufferClear>,
    shadow_formats: BTreeMap<u8, BufferFormat>,
    shadow_clears: BTreeMap<u8, BufferClear>,
    mipmaps: BTreeMap<String, BTreeSet<u8>>,
}

impl DeclaredBuffers {
    fn read(stages: &[&LoadedStage], fullscreen: &[LoadedProgram], not_modelled: &mut Vec<String>) -> DeclaredBuffers {
        let mut declared = DeclaredBuffers::default();
        for stage in stages {
            read_formats(&stage.settings_text, "shadowcolor", shadow_colour_number, &mut declared.shadow_formats, not_modelled);
            read_formats(&stage.settings_text, "colortex", colour_buffer_number, &mut declared.formats, not_modelled);
            declared.shadow_clears.extend(declared_clears(&stage.settings_text, shadow_colour_number));
            declared.clears.extend(declared_clears(&stage.settings_text, colour_buffer_number));
            let shadow_mipmaps = ["shadowcolor", "shadowtex", "generateShadowMipmap", "generateShadowColorMipmap"];
            if declared_switches(&stage.settings_text).any(|name| name.contains("Mipmap") && shadow_mipmaps.iter().any(|s| name.starts_with(s))) {
                not_modelled.push("mipmaps of the shadow maps are not generated".to_string());
            }
        }
        // `colortexNMipmapEnabled` in a full-screen program: the loader makes buffer N's mipmaps
        // just before that program runs, and the program reads them.
        for p in fullscreen {
            let buffers: BTreeSet<u8> = [&p.vertex, &p.fragment]
                .iter()
                .flat_map(|stage| declared_switches(&stage.settings_text).filter_map(|name| name.strip_suffix("MipmapEnabled").and_then(colour_buffer_number)).collect::<Vec<_>>())
                .collect();
            if !buffers.is_empty() {
                declared.mipmaps.insert(p.name.clone(), buffers);
            }
        }
        declared
    }
}

/// The declared formats of one kind of buffer (`colortex`, `shadowcolor`), stand-ins named.
fn read_formats(text: &str, kind: &str, number: fn(&str) -> Option<u8>, formats: &mut BTreeMap<u8, BufferFormat>, not_modelled: &mut Vec<String>) {
    for (buffer, name) in declared_format_names(text, number) {
        match BufferFormat::stand_in(&name) {
            Some((format, exact)) => {
                if !exact {
                    not_modelled.push(format!("{kind}{buffer}Format = {name}: stored as {format:?}"));
                }
                formats.insert(buffer, format);
            }
            None => not_modelled.push(format!("{kind}{buffer}Format = {name}: not a format the loaders know; stored as Rgba8")),
        }
    }
}

/// Which shadow maps the frame needs: whether any program reads one (what makes the loaders
/// draw the shadow pass) and whether `shadow` names shadowtex1 (a program reads `watershadow`).
fn shadow_map_reads(
    gbuffers: &BTreeMap<String, LoadedProgram>,
    fullscreen: &[LoadedProgram],
    shadow: &BTreeMap<String, LoadedProgram>,
    loader: Loader,
    custom_images: &[CustomImage],
    not_modelled: &mut Vec<String>,
) -> (bool, bool) {
    // colorimgN is colortexN and shadowcolorimgN shadowcolorN; custom images are made as the
    // loader makes them.
    let holds_image = |name: &str| buffer_of_image(name).is_some() || custom_images.iter().any(|i| i.name == name);
    let holds_image_sampler = |name: &str| custom_images.iter().any(|i| i.sampler.as_deref() == Some(name));
    let mut reads_shadow_maps = false;
    let mut water_shadow = false;
    let all_programs = gbuffers.values().chain(fullscreen).map(|p| (p, SamplerNaming::Frame)).chain(shadow.values().map(|p| (p, SamplerNaming::ShadowPass)));
    for (program, naming) in all_programs {
        let program_stage = ProgramStage::of(&program.name);
        for stage in [&program.vertex, &program.fragment] {
            for name in program::image_uniforms(&stage.gl_text).into_iter().filter(|name| !holds_image(name)) {
                not_modelled.push(format!(
                    "image {name} in {}: bound empty (neither a colour buffer's nor a custom image the loader makes): it reads zero and what the program stores in it is not kept; OpenGL draws the program",
                    program.name
                ));
            }
            for (name, _) in program::texture_resources(&stage.interface) {
                water_shadow |= name == "watershadow";
                match naming.resolve(&NoCustomTextures(loader), &name, program_stage) {
                    Ok(Source::Unbound) if !holds_image_sampler(&name) => {
                        not_modelled.push(format!("sampler {name} in {}: nothing the harness makes is bound to it; it reads zero", program.name))
                    }
                    Ok(Source::ShadowDepth(_) | Source::ShadowColour(_)) => reads_shadow_maps |= naming == SamplerNaming::Frame,
                    _ => {}
                }
            }
        }
    }
    (reads_shadow_maps, water_shadow)
}

/// The keys of shaders.properties the frame does not imitate, grouped by prefix.
fn unimitated_keys(properties: &Properties) -> Vec<String> {
    let mut notes = Vec::new();
    for key in ["size.buffer.", "scale.", "alphaTest."] {
        // The alpha tests of the terrain's and the water's chains are imitated.
        let imitated = |k: &str| k.strip_prefix("alphaTest.").is_some_and(|p| TERRAIN_CHAIN.contains(&p) || WATER_CHAIN.contains(&p));
        let used: Vec<&str> = properties.with_prefix(key).map(|(_, e)| e.key.as_str()).filter(|k| !imitated(k)).collect();
        if !used.is_empty() {
            let shown: Vec<&str> = used.iter().take(6).copied().collect();
            let more = if used.len() > shown.len() { format!(" and {} more", used.len() - shown.len()) } else { String::new() };
            notes.push(format!("shaders.properties {key}*: {}{more}", shown.join(", ")));
        }
    }
    notes
}

impl AnyPack {
    /// Reads the pack at `path` (folder or zip) and loads every program a scene can use under
    /// `configuration`.
    pub fn load(path: &Path, configuration: &Configuration) -> Result<AnyPack, HarnessError> {
        let files = read_pack(path, &Limits::default()).map_err(|d| HarnessError::Io(d.message))?;
        AnyPack::from_files(&files, configuration)
    }

    pub fn from_files(files: &PackFiles, configuration: &Configuration) -> Result<AnyPack, HarnessError> {
        let loader = configuration.loader;
        let (options, _) = configuration.option_set_of(files).map_err(HarnessError::Configuration)?;
        let standard = configuration.standard_macros();
        let declared = declared_options(files);
        let properties_text = files.texts.get(properties::PATH).map_or("", |t| &**t);
        let properties = read_properties(properties_text, &standard, &declared, &options);
        let standard = standard.with_optional_features(&properties);
        let provider = SetProvider::new(files, &options).ignoring_case();
        let all = files.programs(loader);
        let world = files.world_folder(&configuration.dimension, loader);
        let present: BTreeMap<&str, &programs::Program> =
            all.iter().filter(|p| p.world == world && (p.stages.len() == 2 || !p.compute.is_empty())).map(|p| (p.name.as_str(), p)).collect();
        let mut not_modelled: Vec<String> = properties.problems.iter().map(|(line, e)| format!("shaders.properties:{line}: {e}")).collect();
        let (disabled, problems) = programs::disabled_programs(&properties, &world, &declared, &options);
        not_modelled.extend(problems);
        let mut loading = ProgramLoading {
            provider: &provider,
            present: present.clone(),
            disabled: &disabled,
            properties: &properties,
            macros: standard.preprocess_options(),
            loader,
            not_modelled,
            failed: Vec::new(),
            compute: Vec::new(),
        };
        let gbuffers = loading.gbuffers();
        let shadow = loading.shadow();
        let shadow_composite = loading.shadow_composite();
        let fullscreen = loading.fullscreen();
        let lod = if configuration.distant_horizons { loading.lod() } else { BTreeMap::new() };
        let ProgramLoading { mut not_modelled, failed, compute, .. } = loading;

        for name in present.keys() {
            let loaded = gbuffers.contains_key(*name)
                || shadow.contains_key(*name)
                || fullscreen.iter().chain(&shadow_composite).any(|p| p.name == *name)
                || compute.iter().any(|c| c.program == *name);
            let skipped = failed.iter().any(|(f, _)| f == name) || disabled.iter().any(|d| d == name);
            if loaded || skipped || programs::run_by(name) != RunBy::OptiFine {
                continue;
            }
            let why = match *name {
                n if n.starts_with("shadow_") => "the loader draws the shadow pass with another program",
                _ => "the scenes hold no geometry this program draws",
            };
            not_modelled.push(format!("{name}: {why}"));
        }

        // OptiFine reads no `image.` and `bufferObject.` lines.
        let buffer_objects = if loader == Loader::Iris {
            let (buffers, problems) = directives::buffer_objects(&properties);
            not_modelled.extend(problems);
            buffers
        } else {
            Vec::new()
        };
        let custom_images = if loader == Loader::Iris {
            let (images, problems) = directives::custom_images(&properties);
            not_modelled.extend(problems);
            for image in images.iter().filter(|i| crate::gl::image_internal_format(&i.internal_format).is_none()) {
                not_modelled.push(format!("image {}: internal format {} is not one the harness makes; it is bound empty", image.name, image.internal_format));
            }
            images
        } else {
            Vec::new()
        };
        let (reads_shadow_maps, water_shadow) = shadow_map_reads(&gbuffers, &fullscreen, &shadow, loader, &custom_images, &mut not_modelled);
        if !SKY_TEXTURED_CHAIN.iter().any(|name| gbuffers.contains_key(*name)) {
            not_modelled.push("the sun and the moon: without a program of gbuffers_skytextured's chain the game's own are not drawn".into());
        }
        let shadow_program = loader.shadow_chain(false).iter().find(|name| shadow.contains_key(**name));
        let shadow_pass = reads_shadow_maps && shadow_program.is_some();
        if reads_shadow_maps && shadow_program.is_none() {
            not_modelled.push(
                "the shadow pass without a shadow program (the game's own shading) is not drawn: shadowtex* read depth 1, shadowcolor* white".into(),
            );
        }
        if !reads_shadow_maps && let Some(name) = shadow_program {
            not_modelled.push(format!("{name}: no program reads a shadow map, so the loader draws none"));
        }
        let shadow_composite_names = shadow_composite.iter().map(|p| p.name.as_str()).chain(compute.iter().map(|c| c.program.as_str()).filter(|n| n.starts_with("shadowcomp")));
        for name in shadow_composite_names.collect::<BTreeSet<_>>().into_iter().filter(|_| !shadow_pass) {
            not_modelled.push(format!("{name}: not run: the loader runs shadowcomp after the shadow pass, which this frame does not draw"));
        }
        let mut blends = BTreeMap::new();
        for name in gbuffers.keys().chain(shadow.keys()).chain(lod.keys()).chain(fullscreen.iter().chain(&shadow_composite).map(|p| &p.name)) {
            match directives::blend_modes(&properties, name, loader.per_buffer_blend()) {
                Ok(modes) => {
                    blends.insert(name.clone(), modes);
                }
                Err(e) => not_modelled.push(format!("{name}: {e}")),
            }
        }
        let read_bytes = |path: &str| files.files.get(path).map(|b| b.to_vec()).ok_or_else(|| format!("{path} is not in the pack"));
        let textures = custom_textures(&read_bytes, &provider, &properties)?;
        not_modelled.extend(textures.unsupported);
        let (custom_textures, game_textures) = (textures.custom, textures.game);
        let (flips, unreadable_flips) = directives::flips(&properties);
        not_modelled.extend(unreadable_flips);
        not_modelled.extend(unimitated_keys(&properties));

        let stages: Vec<&LoadedStage> =
            gbuffers.values().chain(shadow.values()).chain(lod.values()).chain(fullscreen.iter()).chain(&shadow_composite).flat_map(|p| [&p.vertex, &p.fragment]).collect();
        let shadow_settings = ShadowSettings::from_texts(stages.iter().map(|s| s.settings_text.as_str()));
        let buffers = DeclaredBuffers::read(&stages, &fullscreen, &mut not_modelled);
        if shadow_pass {
            let (drawn, multiplier) = shadow_settings.drawn_resolution();
            if multiplier < 1.0 {
                not_modelled.push(format!(
                    "shadowMapResolution = {}: drawn at {drawn} (OptiFine's Shadow Quality {multiplier}x)",
                    shadow_settings.declared_resolution
                ));
            }
        }
        let block_ids = program::mapped_ids(&provider, blocks::BLOCK_PROPERTIES, "block", &standard, &declared, &options);
        let entity_ids = program::mapped_ids(&provider, blocks::ENTITY_PROPERTIES, "entity", &standard, &declared, &options);
        // Programs and compute stages that declare a buffer block, which wgpu gives each its own.
        let buffer_block_users = gbuffers.values().chain(shadow.values()).chain(lod.values()).chain(&fullscreen).chain(&shadow_composite)
            .filter(|p| [&p.vertex.gl_text, &p.fragment.gl_text].iter().any(|t| program::declares_buffer_block(t)))
            .count()
            + compute.iter().filter(|c| program::declares_buffer_block(&c.stage.gl_text)).count();
        not_modelled.sort();
        not_modelled.dedup();
        Ok(AnyPack {
            display_root: files.display_root.clone(),
            loader,
            distant_horizons: configuration.distant_horizons,
            world,
            gbuffers,
            fullscreen,
            shadow_composite,
            compute,
            shadow,
            lod,
            shadow_pass,
            shadow_settings,
            water_shadow,
            formats: buffers.formats,
            clears: buffers.clears,
            shadow_formats: buffers.shadow_formats,
            shadow_clears: buffers.shadow_clears,
            mipmaps: buffers.mipmaps,
            flips,
            blends,
            custom_textures,
            game_textures,
            custom_images,
            buffers_shared: !buffer_objects.is_empty() && buffer_block_users > 1,
            buffer_objects,
            block_ids,
            entity_ids,
            properties,
            disabled,
            not_modelled,
            read_by_case: provider.read_by_case(),
            failed,
        })
    }

    /// Sets aside, as programs that do not load, those naga cannot read for wgpu, as loading
    /// did before OpenGL could draw them: for a frame neither renderer can draw whole, wgpu then
    /// draws what the loader would run without them. Whether there were any.
    pub fn set_aside_unreadable(&mut self) -> bool {
        let before = self.failed.len();
        let failed = &mut self.failed;
        let mut keep = |p: &LoadedProgram| match p.naga_refusal() {
            Some(why) => {
                failed.push((p.name.clone(), HarnessError::Pack(why.to_string()).to_string()));
                false
            }
            None => true,
        };
        self.gbuffers.retain(|_, p| keep(p));
        self.shadow.retain(|_, p| keep(p));
        self.lod.retain(|_, p| keep(p));
        self.fullscreen.retain(|p| keep(p));
        self.shadow_composite.retain(|p| keep(p));
        for compute in self.compute.drain(..) {
            let why = compute.only_opengl();
            self.failed.push((compute.program, why));
        }
        self.failed.len() > before
    }

    /// Every program loaded: gbuffers, shadow, Distant Horizons', shadow composite and full-screen
    /// ones.
    pub fn programs(&self) -> impl Iterator<Item = &LoadedProgram> {
        self.gbuffers.values().chain(self.shadow.values()).chain(self.lod.values()).chain(&self.shadow_composite).chain(&self.fullscreen)
    }

    /// What the OpenGL text of each program had rewritten for a strict driver, as
    /// `program: file:line: what`, in program order, after the files read by a name differing
    /// in case.
    pub fn gl_rewrites(&self) -> Vec<String> {
        let by_case = self.read_by_case.iter().map(|(name, file)| {
            format!("`{name}` read from `{file}`, whose name differs only in case, as Windows' file system gives a pack folder")
        });
        let programs = self.programs().flat_map(|p| {
            let geometry = p.geometry.iter().flat_map(|g| &g.gl_rewrites);
            p.vertex.gl_rewrites.iter().chain(geometry).chain(&p.fragment.gl_rewrites).map(move |r| format!("{}: {r}", p.name))
        });
        by_case.chain(programs).collect()
    }

    /// The first program of `chain` the pack has: what the loader draws with.
    pub fn resolve(&self, chain: &[&str]) -> Option<&LoadedProgram> {
        chain.iter().find_map(|name| self.gbuffers.get(*name))
    }

    /// The program drawing Distant Horizons' opaque LODs, or with `translucent` its water.
    pub fn resolve_lod(&self, translucent: bool) -> Option<&LoadedProgram> {
        let own = if translucent { self.lod.get("dh_water") } else { None };
        own.or_else(|| self.lod.get("dh_terrain"))
    }

    /// The shadow program drawing the opaque terrain, or with `translucent` the water.
    pub fn resolve_shadow(&self, translucent: bool) -> Option<&LoadedProgram> {
        self.loader.shadow_chain(translucent).iter().find_map(|name| self.shadow.get(*name))
    }

    /// The format of shadowcolor`buffer`.
    pub fn shadow_format_of(&self, buffer: u8) -> BufferFormat {
        self.shadow_formats.get(&buffer).copied().unwrap_or(BufferFormat::Rgba8)
    }

    pub fn shadow_clear_of(&self, buffer: u8) -> BufferClear {
        self.shadow_clears.get(&buffer).copied().unwrap_or(BufferClear::Default)
    }

    /// Where the scene's sun puts the sun's path, named when the pack declares another tilt
    /// (the scene's sun direction is kept: the pack's sky and shadows follow it).
    pub fn sun_path_note(&self, scene: &Scene) -> Option<String> {
        let declared = self.shadow_settings.sun_path_rotation?;
        let scene_tilt = SunPath::of_sun_direction(scene.sun_direction()).rotation;
        ((declared - scene_tilt).abs() > 0.5)
            .then(|| format!("sunPathRotation = {declared}: the scene's sun direction fixes the sun path's tilt at {scene_tilt:.1}"))
    }

    /// How `program` blends into `buffer`: its own mode from shaders.properties, else
    /// `default`.
    pub fn blend_of(&self, program: Option<&LoadedProgram>, buffer: u8, default: &Blend) -> Blend {
        program.and_then(|p| self.blends.get(&p.name)).and_then(|m| m.get(&buffer)).cloned().unwrap_or_else(|| default.clone())
    }

    /// The uniform values of `pass` in `scene`: the harness's standard ones and the pack's
    /// custom uniforms (shaders.properties), with the problems of those that fail.
    pub fn uniform_values(&self, scene: &Scene, pass: Pass) -> (BTreeMap<String, Value>, Vec<custom_uniforms::Problem>) {
        let mut values = uniforms::values_with_shadow(scene, pass, &self.shadow_settings);
        let custom = custom_uniforms::evaluate(&self.properties, &values);
        values.extend(custom.uniforms);
        (values, custom.problems)
    }

    pub fn clear_of(&self, buffer: u8) -> BufferClear {
        self.clears.get(&buffer).copied().unwrap_or(BufferClear::Default)
    }
}

/// The uniform values of each kind of pass of a frame: the standard ones and the pack's
/// custom uniforms, computed once for both renderers.
pub struct PassValues {
    pub gbuffers: BTreeMap<String, Value>,
    pub fullscreen: BTreeMap<String, Value>,
    pub shadow: BTreeMap<String, Value>,
    pub celestial: BTreeMap<String, Value>,
    pub distant_horizons: BTreeMap<String, Value>,
}

impl PassValues {
    /// The values of every pass in `scene`, with the problems of the custom uniforms that fail.
    pub fn of(pack: &AnyPack, scene: &Scene) -> (PassValues, Vec<custom_uniforms::Problem>) {
        let (gbuffers, problems) = pack.uniform_values(scene, Pass::Gbuffers);
        let values = PassValues {
            gbuffers,
            fullscreen: pack.uniform_values(scene, Pass::Fullscreen).0,
            shadow: pack.uniform_values(scene, Pass::Shadow).0,
            celestial: pack.uniform_values(scene, Pass::Celestial).0,
            distant_horizons: pack.uniform_values(scene, Pass::DistantHorizons).0,
        };
        (values, problems)
    }

    /// Every value [`Value::nudged`] by `relative`.
    pub fn nudged(&self, relative: f64) -> PassValues {
        let all = |values: &BTreeMap<String, Value>| values.iter().map(|(name, v)| (name.clone(), v.nudged(relative))).collect();
        PassValues {
            gbuffers: all(&self.gbuffers),
            fullscreen: all(&self.fullscreen),
            shadow: all(&self.shadow),
            celestial: all(&self.celestial),
            distant_horizons: all(&self.distant_horizons),
        }
    }

    pub fn of_pass(&self, pass: Pass) -> &BTreeMap<String, Value> {
        match pass {
            Pass::Gbuffers => &self.gbuffers,
            Pass::Fullscreen => &self.fullscreen,
            Pass::Shadow => &self.shadow,
            Pass::Celestial => &self.celestial,
            Pass::DistantHorizons => &self.distant_horizons,
        }
    }
}

/// What one step of a frame does, in terms of the pack's programs and the frame's buffers.
/// Every colour buffer has two textures; `current` says which of each a step reads (and, for
/// geometry, draws into).
#[derive(Debug)]
pub enum PlannedWork<'a> {
    /// Geometry drawn by a gbuffers program, or by the loader's own colour where the chain has
    /// none (into the buffers [`tidepack_loader::loader::MissingProgramDraws`] says).
    Geometry {
        program: Option<&'a LoadedProgram>,
        vertices: &'a [PackVertex],
        /// Blend of buffers the program sets none for.
        default_blend: Blend,
        depth_write: bool,
        current: BTreeMap<u8, usize>,
        /// Colour buffers the program samples: copied just before the draw and read from the
        /// copy (GL leaves reading a buffer being drawn into undefined).
        snapshots: BTreeSet<u8>,
        /// What `gtexture` holds.
        sprites: Sprites,
        /// Whose uniform values: gbuffers, the sun and moon's, or Distant Horizons' (which also
        /// draws into Distant Horizons' own depth buffer).
        pass: Pass,
        /// `renderStage` and `entityId` for the draw.
        draw: DrawUniforms,
    },
    /// depthtex0 to depthtex1.
    DepthCopy,
    /// Distant Horizons' depth before its water to dhDepthTex1.
    LodDepthCopy,
    /// Geometry drawn into the shadow map by a shadow program, under the shadow camera: its
    /// render targets are shadow colour buffers, its depth buffer shadowtex0; no blending.
    ShadowGeometry { program: &'a LoadedProgram, vertices: &'a [PackVertex], draw: DrawUniforms },
    /// shadowtex0 to shadowtex1: the shadow map without translucents.
    ShadowDepthCopy,
    /// A compute stage, dispatched over the frame before its program's own stages: it reads the
    /// current textures and reads and writes the current texture of each buffer it names as an
    /// image, in place (nothing flips).
    Compute { stage: &'a ComputeStage, current: BTreeMap<u8, usize> },
    /// A full-screen program: reads the current textures, draws into the other texture of each
    /// of its render targets (which then becomes current); with `into_screen`, colortex0's
    /// output goes to the screen instead (final, or [`ScreenOutput::Unrounded`]), and colortex0
    /// does not flip. `mipmaps`: buffers whose current texture gets its mipmaps just before,
    /// read with them.
    Fullscreen { program: &'a LoadedProgram, current: BTreeMap<u8, usize>, into_screen: bool, mipmaps: BTreeSet<u8> },
    /// colortex0's current texture to the screen, for a pack without final.
    ScreenCopy { current: usize },
    /// A shadowcomp program: the full-screen quad at the shadow map's size into the shadow
    /// colour buffers it writes, reading each shadow colour buffer as it was before the draw
    /// (the loaders flip the ones it writes) and the colour buffers' current textures.
    ShadowComposite { program: &'a LoadedProgram, current: BTreeMap<u8, usize> },
}

#[derive(Debug)]
pub struct PlannedStep<'a> {
    /// `terrain (gbuffers_terrain)`, `composite1`, `depth copy`, …
    pub label: String,
    pub work: PlannedWork<'a>,
}

/// What the screen shows when the pack has no final.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ScreenOutput {
    /// colortex0 copied to the screen, as the loader does: the screen holds what colortex0's
    /// format can.
    #[default]
    AsLoader,
    /// The last full-screen program writing colortex0 draws that output straight into the
    /// RGBA32F screen, so its values, NaN and Inf reach the readback unrounded: what the
    /// measurements of our own pack (reference error, stress) read. colortex0 keeps what the
    /// geometry drew.
    Unrounded,
}

/// A frame of any pack on one scene as OptiFine 1.16.5 and later draw it:
///
/// 0. when the pack has one ([`AnyPack::shadow_pass`]), the shadow pass: the terrain, shadowtex0
///    to shadowtex1, the water;
/// 1. prepare*;
/// 2. the sky (gbuffers_skybasic's chain, no depth written), the loader's overlays before the
///    terrain, Distant Horizons' opaque LODs (dh_terrain, into dhDepthTex0, where the pack has
///    it and the scene has LODs), the terrain (gbuffers_terrain's chain), the overlays before
///    the water;
/// 3. depthtex0 to depthtex1;
/// 4. deferred*;
/// 5. dhDepthTex0 to dhDepthTex1 and Distant Horizons' water (dh_water's chain) where there are
///    LODs, the water and glass (gbuffers_water's chain), the overlays after the water;
/// 6. composite*;
/// 7. final into the screen, or colortex0 copied there ([`ScreenOutput`]).
#[derive(Debug)]
pub struct FramePlan<'a> {
    /// Every colour buffer a program writes or reads, and colortex0.
    pub buffers: BTreeSet<u8>,
    /// Every shadow colour buffer the shadow pass writes or a program reads, and shadowcolor0;
    /// empty without a shadow pass.
    pub shadow_buffers: BTreeSet<u8>,
    /// Colour buffers some program reads with mipmaps: their textures have mip chains.
    pub mipmapped: BTreeSet<u8>,
    pub steps: Vec<PlannedStep<'a>>,
    /// Which texture of each buffer is current at the end.
    pub current: BTreeMap<u8, usize>,
}

/// The depth buffers a renderer drawing a step from another's frame takes from it
/// ([`FramePlan::depth_seed`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DepthSeed {
    /// Both as the frame ended: the step comes after the last geometry.
    AsEnded,
    /// The opaque depth for both: the step comes after the depth copy and before the next
    /// geometry, when depthtex0 held what depthtex1 holds at the end.
    OpaqueOnly,
}

impl<'a> FramePlan<'a> {
    /// Whether a shadowcomp program draws in the frame.
    pub fn has_shadow_composite(&self) -> bool {
        self.steps.iter().any(|s| matches!(s.work, PlannedWork::ShadowComposite { .. }))
    }

    /// For a full-screen step `index`, which depth buffers of the reference's final ones hold
    /// what the step reads; None for other steps, or where neither does.
    pub fn depth_seed(&self, index: usize) -> Option<DepthSeed> {
        if !matches!(self.steps[index].work, PlannedWork::Fullscreen { .. }) {
            return None;
        }
        let is_geometry = |step: &PlannedStep| matches!(step.work, PlannedWork::Geometry { .. });
        let depth_copy = self.steps.iter().position(|s| matches!(s.work, PlannedWork::DepthCopy));
        if self.steps.iter().rposition(is_geometry).is_none_or(|g| g < index) {
            Some(DepthSeed::AsEnded)
        } else if depth_copy.is_some_and(|c| c < index && !self.steps[c..index].iter().any(is_geometry)) {
            Some(DepthSeed::OpaqueOnly)
        } else {
            None
        }
    }

    pub fn new(pack: &'a AnyPack, scene: &Scene, mesh: &'a SceneMesh, screen: ScreenOutput) -> FramePlan<'a> {
        let is_final = |p: &LoadedProgram| p.name == "final";
        let mut buffers: BTreeSet<u8> = BTreeSet::from([0]);
        for program in pack.gbuffers.values() {
            buffers.extend(program.drawn_buffers());
            buffers.extend(colour_buffers_read(pack, program, SamplerNaming::Frame));
        }
        for compute in &pack.compute {
            buffers.extend(compute.images.iter().copied());
            let names = program::sampler_uniforms(&compute.stage.gl_text);
            buffers.extend(colour_buffers_named(pack, names, ProgramStage::of(&compute.program), SamplerNaming::Frame));
        }
        for program in &pack.fullscreen {
            if !is_final(program) {
                buffers.extend(program.drawn_buffers());
            }
            buffers.extend(colour_buffers_read(pack, program, SamplerNaming::Frame));
        }
        // shadowcomp draws into the shadow colour buffers, but may read colour buffers too.
        for program in &pack.shadow_composite {
            buffers.extend(colour_buffers_read(pack, program, SamplerNaming::Frame));
        }
        let mut shadow_buffers = BTreeSet::new();
        if pack.shadow_pass {
            shadow_buffers.insert(0);
            shadow_buffers.extend(pack.shadow.values().chain(&pack.shadow_composite).flat_map(|p| p.drawn_buffers()));
            shadow_buffers.extend(pack.compute.iter().flat_map(|c| c.shadow_images.iter().copied()));
            for program in pack.gbuffers.values().chain(&pack.fullscreen).chain(&pack.shadow_composite) {
                for stage in [&program.vertex, &program.fragment] {
                    for (name, _) in program::texture_resources(&stage.interface) {
                        if let Ok(Source::ShadowColour(n)) = SamplerNaming::Frame.resolve(pack, &name, ProgramStage::of(&program.name)) {
                            shadow_buffers.insert(n);
                        }
                    }
                }
            }
        }
        let mipmapped = pack.mipmaps.values().flatten().copied().filter(|b| buffers.contains(b)).collect();
        let mut plan =
            FramePlan { current: buffers.iter().map(|b| (*b, 0)).collect(), buffers, shadow_buffers, mipmapped, steps: Vec::new() };
        // The frame drawn is the first: Iris's setup passes have just run, then its begin passes.
        for family in ["setup", "begin"] {
            plan.family(pack, family, None);
        }
        if pack.shadow_pass {
            plan.shadow_geometry(pack, false, &mesh.terrain, "shadow terrain");
            plan.steps.push(PlannedStep { label: "shadowtex0 to shadowtex1".into(), work: PlannedWork::ShadowDepthCopy });
            plan.shadow_geometry(pack, true, &mesh.translucent, "shadow water");
            plan.shadow_composite(pack);
        }
        let family = |prefix: &'a str| pack.fullscreen.iter().filter(move |p| p.name.starts_with(prefix));
        plan.family(pack, "prepare", None);
        // The sky: the game's own colour where the pack has no skybasic program.
        plan.geometry(pack, pack.resolve(&SKY_CHAIN), &mesh.sky, Blend::Off, false, "sky", Sprites::Blocks, DrawUniforms::stage("SKY"));
        if let Some(program) = pack.resolve(&SKY_TEXTURED_CHAIN) {
            plan.geometry(pack, Some(program), &mesh.sun, CELESTIAL_BLEND, false, "sun", Sprites::Sun, DrawUniforms::stage("SUN"));
            plan.geometry(pack, Some(program), &mesh.moon, CELESTIAL_BLEND, false, "moon", Sprites::Moon, DrawUniforms::stage("MOON"));
        }
        plan.overlays(pack, scene, mesh, Phase::BeforeTerrain);
        // Iris draws Distant Horizons' LODs only with the pack's own programs.
        let lod = scene.distant_horizons.is_some() && pack.resolve_lod(false).is_some();
        if lod {
            plan.lod_geometry(pack, false, &mesh.lod_terrain, "LOD terrain", "TERRAIN_SOLID");
        }
        plan.geometry(pack, pack.resolve(&TERRAIN_CHAIN), &mesh.terrain, Blend::Off, true, "terrain", Sprites::Blocks, DrawUniforms::stage("TERRAIN_SOLID"));
        plan.entities(pack, mesh);
        plan.overlays(pack, scene, mesh, Phase::BeforeWater);
        plan.steps.push(PlannedStep { label: "depth copy".into(), work: PlannedWork::DepthCopy });
        plan.forced_flips(pack, "deferred_pre");
        plan.family(pack, "deferred", None);
        if lod {
            plan.steps.push(PlannedStep { label: "dhDepthTex0 to dhDepthTex1".into(), work: PlannedWork::LodDepthCopy });
            plan.lod_geometry(pack, true, &mesh.lod_translucent, "LOD water", "TERRAIN_TRANSLUCENT");
        }
        plan.geometry(pack, pack.resolve(&WATER_CHAIN), &mesh.translucent, DEFAULT_TRANSLUCENT_BLEND, true, "water", Sprites::Blocks, DrawUniforms::stage("TERRAIN_TRANSLUCENT"));
        plan.overlays(pack, scene, mesh, Phase::AfterWater);
        plan.forced_flips(pack, "composite_pre");
        let composites: Vec<&LoadedProgram> = family("composite").collect();
        let final_program = pack.fullscreen.iter().find(|p| is_final(p));
        // Without final, the last composite writing colortex0 may draw it into the screen.
        let last_into_screen = match (final_program, screen) {
            (None, ScreenOutput::Unrounded) => composites.iter().rposition(|p| p.render_targets.contains(&Some(0))),
            _ => None,
        };
        plan.family(pack, "composite", last_into_screen.map(|i| composites[i].name.as_str()));
        plan.compute(pack, "final");
        match final_program {
            Some(program) => plan.fullscreen(pack, program, true),
            None if last_into_screen.is_some() => {}
            None => {
                let current = plan.current[&0];
                plan.steps.push(PlannedStep { label: "colortex0 to the screen (no final)".into(), work: PlannedWork::ScreenCopy { current } });
            }
        }
        plan
    }

    #[allow(clippy::too_many_arguments)]
    fn geometry(
        &mut self,
        pack: &'a AnyPack,
        program: Option<&'a LoadedProgram>,
        vertices: &'a [PackVertex],
        default_blend: Blend,
        depth_write: bool,
        what: &str,
        sprites: Sprites,
        draw: DrawUniforms,
    ) {
        let snapshots = program.map(|p| colour_buffers_read(pack, p, SamplerNaming::Frame)).unwrap_or_default();
        let pass = if sprites == Sprites::Blocks { Pass::Gbuffers } else { Pass::Celestial };
        let current = self.current.clone();
        self.steps.push(PlannedStep {
            label: format!("{what} ({})", program.map_or("the loader's own", |p| p.name.as_str())),
            work: PlannedWork::Geometry { program, vertices, default_blend, depth_write, current, snapshots, sprites, pass, draw },
        });
    }

    /// Distant Horizons' LODs drawn by dh_terrain, or with `translucent` its water by dh_water's
    /// chain: under [`Pass::DistantHorizons`], into Distant Horizons' own depth buffer.
    fn lod_geometry(&mut self, pack: &'a AnyPack, translucent: bool, vertices: &'a [PackVertex], what: &str, render_stage: &'static str) {
        let draw = DrawUniforms::stage(render_stage);
        let Some(program) = pack.resolve_lod(translucent) else { return };
        let default_blend = if translucent { DEFAULT_TRANSLUCENT_BLEND } else { Blend::Off };
        let snapshots = colour_buffers_read(pack, program, SamplerNaming::Frame);
        let current = self.current.clone();
        self.steps.push(PlannedStep {
            label: format!("{what} ({})", program.name),
            work: PlannedWork::Geometry {
                program: Some(program),
                vertices,
                default_blend,
                depth_write: true,
                current,
                snapshots,
                sprites: Sprites::Blocks,
                pass: Pass::DistantHorizons,
                draw,
            },
        });
    }

    /// The flips `flip.<virtual>.<buffer>=true` asks for before a family of programs.
    fn forced_flips(&mut self, pack: &AnyPack, virtual_program: &str) {
        for (b, flip) in pack.flips.get(virtual_program).into_iter().flatten() {
            if *flip && let Some(current) = self.current.get_mut(b) {
                *current = 1 - *current;
            }
        }
    }

    fn shadow_geometry(&mut self, pack: &'a AnyPack, translucent: bool, vertices: &'a [PackVertex], what: &str) {
        if let Some(program) = pack.resolve_shadow(translucent) {
            let draw = DrawUniforms::stage(if translucent { "TERRAIN_TRANSLUCENT" } else { "TERRAIN_SOLID" });
            let work = PlannedWork::ShadowGeometry { program, vertices, draw };
            self.steps.push(PlannedStep { label: format!("{what} ({})", program.name), work });
        }
    }

    /// Each entity of the scene, after the opaque terrain as the game draws them, by
    /// gbuffers_entities' chain with `entityId` from the pack's entity.properties (-1 for an
    /// entity it does not list).
    fn entities(&mut self, pack: &'a AnyPack, mesh: &'a SceneMesh) {
        let program = pack.resolve(&ENTITY_CHAIN);
        for (name, vertices) in &mesh.entities {
            let entity_id = pack.entity_ids.get(&blocks::namespaced(name)).copied().unwrap_or(-1);
            let draw = DrawUniforms { render_stage: "ENTITIES", entity_id };
            self.geometry(pack, program, vertices, DEFAULT_TRANSLUCENT_BLEND, true, &format!("entity {name}"), Sprites::Blocks, draw);
        }
    }

    fn overlays(&mut self, pack: &'a AnyPack, scene: &Scene, mesh: &'a SceneMesh, phase: Phase) {
        for (kind, vertices) in &mesh.overlay {
            if scene.overlay_phase(pack.loader, *kind) == phase {
                let program = pack.resolve(pack.loader.program_chain(*kind));
                let depth_write = tidepack_loader::loader::writes_depth(*kind);
                let stage = match kind {
                    OverlayKind::Rain => "RAIN_SNOW",
                    OverlayKind::Clouds => "CLOUDS",
                    OverlayKind::Particles => "PARTICLES",
                    OverlayKind::Hand => "HAND_TRANSLUCENT",
                };
                self.geometry(pack, program, vertices, DEFAULT_TRANSLUCENT_BLEND, depth_write, &format!("{kind:?}"), Sprites::Blocks, DrawUniforms::stage(stage));
            }
        }
    }

    /// The compute stages of the program `name`, each a step.
    fn compute(&mut self, pack: &'a AnyPack, name: &str) {
        for stage in pack.compute.iter().filter(|c| c.program == name) {
            let label = format!("{name} ({})", stage.stage.path);
            self.steps.push(PlannedStep { label, work: PlannedWork::Compute { stage, current: self.current.clone() } });
        }
    }

    /// shadowcomp* ([`family_slots`]), each its compute stages and then its program drawn into
    /// the shadow colour buffers.
    fn shadow_composite(&mut self, pack: &'a AnyPack) {
        for (name, program) in family_slots(&pack.shadow_composite, &pack.compute, "shadowcomp") {
            self.compute(pack, name);
            if let Some(program) = program {
                self.steps.push(PlannedStep { label: program.name.clone(), work: PlannedWork::ShadowComposite { program, current: self.current.clone() } });
            }
        }
    }

    /// The programs of `family` ([`family_slots`]), each its compute stages and then its
    /// full-screen program; `into_screen` names the one drawing colortex0 into the screen.
    fn family(&mut self, pack: &'a AnyPack, family: &str, into_screen: Option<&str>) {
        for (name, program) in family_slots(&pack.fullscreen, &pack.compute, family) {
            self.compute(pack, name);
            if let Some(program) = program {
                self.fullscreen(pack, program, into_screen == Some(name));
            }
        }
    }

    fn fullscreen(&mut self, pack: &AnyPack, program: &'a LoadedProgram, into_screen: bool) {
        let current = self.current.clone();
        // Each render target flips, unless shaders.properties says otherwise for the program; a
        // buffer it does not write flips only when told to. Final flips nothing, and a program
        // drawing colortex0 into the screen leaves colortex0 as it was.
        let overrides = pack.flips.get(&program.name);
        for b in self.buffers.iter().filter(|_| program.name != "final") {
            let default = program.render_targets.contains(&Some(*b));
            if !(into_screen && *b == 0) && overrides.and_then(|o| o.get(b)).copied().unwrap_or(default) {
                self.current.insert(*b, 1 - current[b]);
            }
        }
        let mipmaps = pack.mipmaps.get(&program.name).map(|m| m.intersection(&self.buffers).copied().collect()).unwrap_or_default();
        self.steps.push(PlannedStep { label: program.name.clone(), work: PlannedWork::Fullscreen { program, current, into_screen, mipmaps } });
    }
}

/// The programs of a family (`deferred`: deferred, deferred1, …) the loader runs, in its order,
/// each with its program among `programs` where it has one (a program may be compute stages
/// alone, among `compute`).
fn family_slots<'p>(programs: &'p [LoadedProgram], compute: &'p [ComputeStage], family: &str) -> Vec<(&'p str, Option<&'p LoadedProgram>)> {
    let number = |name: &str| match name.strip_prefix(family)? {
        "" => Some(0),
        rest => rest.parse::<u32>().ok(),
    };
    let names = programs.iter().map(|p| p.name.as_str()).chain(compute.iter().map(|c| c.program.as_str()));
    let mut slots: Vec<(u32, &str)> = names.filter_map(|name| Some((number(name)?, name))).collect();
    slots.sort();
    slots.dedup();
    slots.into_iter().map(|(_, name)| (name, programs.iter().find(|p| p.name == name))).collect()
}

/// The names of `const bool <name> = true;` declarations.
fn declared_switches(text: &str) -> impl Iterator<Item = &str> {
    consts::declarations(text).filter(|d| d.switch() == Some(true)).map(|d| d.name)
}

/// `const bool colortexNClear = false;` and `const vec4 colortexNClearColor = vec4(...);`, buffers
/// numbered by `number` (colour or shadow colour buffers).
fn declared_clears(text: &str, number: fn(&str) -> Option<u8>) -> Vec<(u8, BufferClear)> {
    consts::declarations(text)
        .filter_map(|d| {
            if let Some(buffer) = d.name.strip_suffix("ClearColor").and_then(number) {
                Some((buffer, BufferClear::Color(d.vec4()?)))
            } else {
                let buffer = d.name.strip_suffix("Clear").and_then(number)?;
                (d.switch() == Some(false)).then_some((buffer, BufferClear::Keep))
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn program_enabled_entries_turn_programs_off_for_the_chosen_options() {
        let vertex = b"#version 120\nvoid main() { gl_Position = ftransform(); }\n".to_vec();
        let fragment = b"#version 120\n//#define BLOOM\n#define TAA\n#ifdef BLOOM\n#endif\n#ifdef TAA\n#endif\nvoid main() { gl_FragData[0] = vec4(1.0); }\n".to_vec();
        let properties = b"program.composite1.enabled=BLOOM || !TAA\nprogram.world0/composite.enabled=false\nprogram.composite2.enabled=NOPE\n".to_vec();
        let mut files = vec![("shaders.properties".to_string(), properties)];
        for name in ["composite", "composite1", "composite2"] {
            files.push((format!("{name}.vsh"), vertex.clone()));
            files.push((format!("{name}.fsh"), fragment.clone()));
        }
        let files = tidepack_loader::input::pack_from_memory("test/shaders/", files);
        let names = |configuration: &Configuration| {
            let pack = AnyPack::from_files(&files, configuration).unwrap();
            (pack.fullscreen.iter().map(|p| p.name.clone()).collect::<Vec<_>>(), pack.not_modelled)
        };
        // BLOOM is off and TAA on by default: composite1 is off; the world0/ entry is for
        // another folder; NOPE is no option, so composite2 runs and the entry is named.
        let (running, not_modelled) = names(&Configuration::default());
        assert_eq!(running, ["composite", "composite2"]);
        assert!(not_modelled.iter().any(|l| l.contains("shaders.properties:3: program.composite2.enabled") && l.contains("NOPE")), "{not_modelled:?}");
        let bloom = Configuration { options: vec![("BLOOM".into(), "on".into())], ..Configuration::default() };
        assert_eq!(names(&bloom).0, ["composite", "composite1", "composite2"]);
    }

    #[test]
    fn cutout_terrain_gets_the_loaders_alpha_test() {
        let vertex = b"#version 120\nvoid main() { gl_Position = ftransform(); }\n".to_vec();
        let legacy = b"#version 120\nvoid main() { gl_FragData[0] = vec4(0.5); }\n".to_vec();
        let declared = b"#version 330 compatibility\nlayout(location = 0) out vec4 color;\nvoid main() { color = vec4(0.5); }\n".to_vec();
        let tested = |fragment: &[u8], properties: &str, loader: Loader| {
            let files = tidepack_loader::input::pack_from_memory(
                "test/shaders/",
                [
                    ("gbuffers_terrain.vsh".to_string(), vertex.clone()),
                    ("gbuffers_terrain.fsh".to_string(), fragment.to_vec()),
                    ("shaders.properties".to_string(), properties.as_bytes().to_vec()),
                ],
            );
            let pack = AnyPack::from_files(&files, &Configuration { loader, ..Configuration::default() }).unwrap();
            pack.gbuffers["gbuffers_terrain"].fragment.gl_text.contains("discard")
        };
        assert!(tested(&legacy, "", Loader::OptiFine1_21));
        assert!(!tested(&declared, "", Loader::OptiFine1_21), "OptiFine 1.17+ leaves declared outputs alone");
        assert!(tested(&declared, "", Loader::OptiFine1_16_5));
        // Iris's transformer tests writes of gl_FragData[0] alone.
        assert!(tested(&legacy, "", Loader::Iris) && !tested(&declared, "", Loader::Iris));
        assert!(!tested(&legacy, "alphaTest.gbuffers_terrain=off\n", Loader::OptiFine1_21));
    }

    #[test]
    fn flip_entries_keep_or_force_the_ping_pong() {
        let vertex = b"#version 120\nvoid main() { gl_Position = ftransform(); }\n".to_vec();
        let writes = b"#version 120\nuniform sampler2D colortex0;\nuniform sampler2D colortex5;\nvoid main() {\n/* DRAWBUFFERS:0 */\n gl_FragData[0] = texture2D(colortex0, vec2(0.5)) + texture2D(colortex5, vec2(0.5)); }\n".to_vec();
        let properties = b"flip.composite.colortex0=false\nflip.composite_pre.colortex5=true\nflip.composite1.gaux2 = true\n".to_vec();
        let mut files = vec![("shaders.properties".to_string(), properties)];
        for name in ["composite", "composite1", "composite2"] {
            files.push((format!("{name}.vsh"), vertex.clone()));
            files.push((format!("{name}.fsh"), writes.clone()));
        }
        let files = tidepack_loader::input::pack_from_memory("test/shaders/", files);
        let pack = AnyPack::from_files(&files, &Configuration::default()).unwrap();
        let scene = Scene::load(&std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/scenes/case4_above_near.toml")).unwrap();
        let mesh = tidepack_scene::mesh::build(&scene, &pack);
        let plan = FramePlan::new(&pack, &scene, &mesh, ScreenOutput::AsLoader);
        let reads: Vec<(&str, usize, usize)> = plan
            .steps
            .iter()
            .filter_map(|s| match &s.work {
                PlannedWork::Fullscreen { program, current, .. } => Some((program.name.as_str(), current[&0], current[&5])),
                _ => None,
            })
            .collect();
        // composite_pre flips colortex5 before composite; composite writes colortex0 without a
        // flip, so composite1 reads what composite read; composite1 flips colortex0 as it
        // writes it, and colortex5 (gaux2) although it does not write it.
        assert_eq!(reads, [("composite", 0, 1), ("composite1", 0, 1), ("composite2", 1, 0)]);
    }

    #[test]
    fn each_draw_of_the_world_has_its_render_stage() {
        let shaders = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/packs/shadow_map");
        let pack = AnyPack::load(&shaders, &Configuration::default()).unwrap();
        let scene = Scene::load(&std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/scenes/rain_over_lake.toml")).unwrap();
        let mesh = tidepack_scene::mesh::build(&scene, &pack);
        let plan = FramePlan::new(&pack, &scene, &mesh, ScreenOutput::AsLoader);
        let stages: Vec<(&str, &str)> = plan
            .steps
            .iter()
            .filter_map(|s| match &s.work {
                PlannedWork::Geometry { draw, .. } | PlannedWork::ShadowGeometry { draw, .. } => Some((s.label.as_str(), draw.render_stage)),
                _ => None,
            })
            .collect();
        assert_eq!(
            stages,
            [
                ("shadow terrain (shadow)", "TERRAIN_SOLID"),
                ("shadow water (shadow)", "TERRAIN_TRANSLUCENT"),
                ("sky (the loader's own)", "SKY"),
                ("terrain (gbuffers_terrain)", "TERRAIN_SOLID"),
                ("water (gbuffers_water)", "TERRAIN_TRANSLUCENT"),
                ("Rain (the loader's own)", "RAIN_SNOW"),
            ]
        );
        let values = DrawUniforms::stage("TERRAIN_TRANSLUCENT").applied(&uniforms::values(&scene, Pass::Gbuffers));
        assert_eq!(values["renderStage"], Value::int(17));
    }

    #[test]
    fn reads_clear_directives() {
        let text = "const bool colortex2Clear = false;\nconst vec4 colortex3ClearColor = vec4(1.0, 0.5, 0.0, 1.0);\nconst vec4 gaux1ClearColor = vec4(0.25);\n";
        assert_eq!(
            declared_clears(text, colour_buffer_number),
            [(2, BufferClear::Keep), (3, BufferClear::Color([1.0, 0.5, 0.0, 1.0])), (4, BufferClear::Color([0.25; 4]))]
        );
    }
}
