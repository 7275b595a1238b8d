//! Each program's stages preprocessed and lowered for naga, with the checks that need no naga.

use std::sync::Arc;

use tidepack_glsl::naga_check::{self, LoweredCompute, LoweredStage};
use tidepack_glsl::preprocess::{self, FileProvider, PreprocessOptions, Preprocessed, assume_glsl_110};
use tidepack_glsl::{Code, Diagnostic, Drivers, Location, Stage};
use tidepack_glsl::token::{Token, tokenize};

use tidepack_loader::directives::CustomNames;
use tidepack_loader::loader::Loader;
use tidepack_loader::programs::{Program, with_loader_declarations};

use crate::{glsl_rules, interface, version_rules};

/// Preprocesses and lowers a program's stages and runs the checks that need no naga.
pub(crate) fn check_program(
    program: &Program,
    provider: &dyn FileProvider,
    macros: &PreprocessOptions,
    names: &CustomNames,
    loader: Loader,
) -> Result<(Vec<LoweredStage>, Vec<Diagnostic>), Vec<Diagnostic>> {
    let mut diags = Vec::new();
    let mut preprocessed = Vec::new();
    for (stage, path) in &program.stages {
        match preprocess::preprocess(provider, path, macros) {
            Ok(mut pre) => {
                assume_glsl_110(&mut pre);
                if let std::borrow::Cow::Owned(declared) = with_loader_declarations(&program.name, *stage == Stage::Vertex, &pre.text) {
                    pre.text = declared;
                }
                // What the loader's transformer does before the driver gets the stage; Iris's
                // driver compiles it at 3.30 at least.
                let transform = loader.transform(&program.name);
                if transform != tidepack_loader::iris::Transform::default() {
                    let seen = pre.text.clone();
                    (pre.text, _) = tidepack_loader::iris::as_transformed(std::mem::take(&mut pre.text), &seen, transform, Some(*stage));
                }
                if let (true, Some(raised)) = (transform.raises_version, pre.version.as_ref().and_then(tidepack_loader::iris::raised_to_330)) {
                    pre.version = Some(raised);
                }
                diags.extend(pre.warnings.iter().cloned());
                diags.extend(no_buffer_under_iris(&pre, loader));
                // One reading of the text for every rule; text that does not tokenize gives none
                // of them anything (the lowering reports it).
                let tokens = tokenize(&pre.text).unwrap_or_default();
                diags.extend(version_rules::check(&pre, &tokens, *stage, loader).into_iter().map(lenient_on_nvidia));
                diags.extend(version_rules::unknown_extensions(&pre, &tokens));
                diags.extend(version_rules::extensions_some_drivers_lack(&pre, &tokens));
                diags.extend(glsl_rules::check(&pre, &tokens, *stage));
                diags.extend(macos_refusals(&pre, &tokens, false));
                drop(tokens);
                diags.extend(above_configured_glsl(&pre, macros));
                preprocessed.push((*stage, Arc::new(pre)));
            }
            Err(e) => {
                diags.push(e);
                return Err(diags);
            }
        }
    }
    // With a geometry or tessellation stage between them, vertex and fragment do not talk
    // directly.
    let linked = program.other_stages.is_empty();
    let groups: Vec<Vec<(Stage, Arc<Preprocessed>)>> =
        if linked { vec![preprocessed.clone()] } else { preprocessed.iter().map(|s| vec![s.clone()]).collect() };
    let mut lowered = Vec::new();
    for group in groups {
        match naga_check::lower_program(&group) {
            Ok(stages) => lowered.extend(stages),
            Err(e) => {
                diags.push(e);
                return Err(diags);
            }
        }
    }
    let vertex = preprocessed.iter().find(|(s, _)| *s == Stage::Vertex);
    let fragment = preprocessed.iter().find(|(s, _)| *s == Stage::Fragment);
    if let (Some((_, vs)), Some((_, fs)), true) = (vertex, fragment, linked) {
        let (found, never_written) = interface::check_varyings(vs, fs);
        diags.extend(found);
        if !never_written.is_empty() {
            diags.extend(judge_never_written(never_written, &lowered, provider));
        }
    }
    for stage in &lowered {
        if stage.stage == Stage::Fragment {
            diags.extend(interface::check_render_targets(&stage.preprocessed, stage));
        }
        diags.extend(interface::check_resources(&stage.preprocessed, &stage.lowered, &program.name, names, loader));
    }
    Ok((lowered, diags))
}

/// Reads of inputs the vertex stage never writes, judged on the fragment stage's IR: an error
/// where the value reaches the stage's results, nothing where Mesa's optimiser drops the read
/// (it links then), the old warning where naga does not read the stage.
fn judge_never_written(never_written: Vec<interface::NeverWritten>, lowered: &[LoweredStage], provider: &dyn FileProvider) -> Vec<Diagnostic> {
    let live = lowered
        .iter()
        .find(|s| s.stage == Stage::Fragment)
        .and_then(|fragment| naga_check::validate_stage(&mut naga_check::Frontend::default(), fragment, provider).ok())
        .map(|valid| tidepack_glsl::liveness::live_global_names(&valid.module));
    never_written
        .into_iter()
        .filter_map(|read| match &live {
            Some(live) if live.contains(&read.input) => Some(read.refused),
            Some(_) => None,
            None => Some(read.unknown),
        })
        .collect()
}

/// What the specification forbids and NVIDIA's compiler lets by: the version rules name
/// constructs of a later GLSL version, which NVIDIA's driver compiles at any version
/// (reported on pack trackers as "works on NVIDIA only").
/// An `N` in a draw-buffer list, which OptiFine takes as an output drawn into no buffer and
/// Iris cannot read: it parses each entry as a number (`Integer.parseInt`, `Character.digit`)
/// and fails to load the pack.
fn no_buffer_under_iris(pre: &Preprocessed, loader: Loader) -> Option<Diagnostic> {
    let targets = pre.render_targets.as_ref().filter(|t| loader == Loader::Iris && t.buffers.contains(&None))?;
    let name = if targets.modern { "RENDERTARGETS" } else { "DRAWBUFFERS" };
    let at = Location::line(pre.files[targets.line.file as usize].clone(), targets.line.line);
    Some(Diagnostic::error(
        Code::DrawBuffers,
        format!("`N` in {name} (an output drawn into no buffer) is OptiFine's: Iris reads every entry as a buffer number and does not load the pack"),
        Some(at),
    ))
}

fn lenient_on_nvidia(diag: Diagnostic) -> Diagnostic {
    if diag.is_error() {
        let refused = diag.refused_by.intersection(Drivers::ALL_BUT_NVIDIA);
        diag.refused_by(refused)
    } else {
        diag
    }
}

/// Highest GLSL version macOS compiles: its OpenGL stops at 4.1 core.
const MACOS_GLSL: u32 = 410;

/// What macOS's OpenGL 4.1 refuses in a stage: a `#version` above 410, compute shaders (4.3),
/// shader storage blocks and images (4.3 and 4.2). Errors for macOS only.
/// A stage whose `#version` is above the highest GLSL version of the configuration's driver
/// (`MC_GLSL_VERSION`: `--glsl-version`, or what `--os` and `--mc-version` imply, such as GLSL
/// 1.20 on macOS before Minecraft 1.17): that driver refuses it.
fn above_configured_glsl(pre: &Preprocessed, macros: &PreprocessOptions) -> Option<Diagnostic> {
    let highest: u32 = macros.predefined.iter().find(|(name, _)| name == "MC_GLSL_VERSION")?.1.parse().ok()?;
    let version = pre.version.as_ref().filter(|v| v.number > highest && v.profile.as_deref() != Some("es"))?;
    // Above macOS's own 4.1, `macos_refusals` says it.
    let mac = macros.predefined.iter().any(|(name, _)| name == "MC_OS_MAC");
    if mac && version.number > MACOS_GLSL {
        return None;
    }
    Some(Diagnostic::error(
        Code::Version,
        format!(
            "`#version {}` is above GLSL {highest}, the highest this configuration's driver compiles (MC_GLSL_VERSION {highest}, from \
             --glsl-version or what --os and --mc-version give): the program does not load there",
            version.number
        ),
        pre.location(version_line(pre)),
    ))
}

/// The 1-based line of the preprocessed text that holds `#version` (1 when none does).
fn version_line(pre: &Preprocessed) -> u32 {
    pre.version_line().unwrap_or(1)
}

fn macos_refusals(pre: &Preprocessed, tokens: &[Token], compute: bool) -> Vec<Diagnostic> {
    let mut found = Vec::new();
    let entry = || pre.location(version_line(pre)).or_else(|| Some(Location::line(pre.files[0].clone(), 1)));
    let macos = |message: String, at: Option<Location>| Diagnostic::error(Code::Macos, message, at).refused_by(Drivers::MACOS);
    if compute {
        found.push(macos("compute shaders need OpenGL 4.3; macOS stops at 4.1, so this pass does not run there".into(), entry()));
    }
    if let Some(version) = pre.version.as_ref().filter(|v| v.number > MACOS_GLSL) {
        found.push(macos(
            format!("`#version {}` is above {MACOS_GLSL}, the highest macOS compiles (OpenGL 4.1 core): the program does not load there", version.number),
            entry(),
        ));
        return found;
    }
    let significant: Vec<_> = tokens.iter().filter(|t| !t.is_trivia()).collect();
    for (k, t) in significant.iter().enumerate() {
        let storage_block = t.is_ident("buffer") && significant.get(k + 1).is_some_and(|n| n.kind == tidepack_glsl::token::TokenKind::Ident);
        let image = t.kind == tidepack_glsl::token::TokenKind::Ident && tidepack_glsl::lower::is_image_type(t.text);
        if storage_block || image {
            let what = if storage_block { "shader storage blocks (`buffer`) need OpenGL 4.3" } else { "images need OpenGL 4.2" };
            found.push(macos(format!("{what}; macOS stops at 4.1, so the program does not load there"), pre.location(t.line)));
            break;
        }
    }
    found
}

/// The kind of stage of a geometry or tessellation file, for messages.
pub fn other_stage_kind(path: &str) -> &'static str {
    if path.ends_with(".gsh") {
        "geometry"
    } else if path.ends_with(".tcs") {
        "tessellation control"
    } else {
        "tessellation evaluation"
    }
}

/// Preprocesses a program's geometry and tessellation stages, which naga cannot read: include
/// errors, `#error` and macro errors are reported; without `driver`, a warning per file says it
/// was only preprocessed.
pub(crate) fn preprocess_other_stages(
    program: &Program,
    provider: &dyn FileProvider,
    macros: &PreprocessOptions,
    driver: bool,
) -> Vec<Diagnostic> {
    let mut diags = Vec::new();
    for path in &program.other_stages {
        match preprocess::preprocess(provider, path, macros) {
            Ok(pre) => {
                diags.extend(pre.warnings.iter().cloned());
                diags.extend(built_ins_of_other_stages(&pre, other_stage_kind(path)));
                if !driver {
                    diags.push(Diagnostic::warning(
                        Code::NotCompiled,
                        format!(
                            "{path} was only preprocessed, not compiled: naga has no {} stage; `--driver` compiles it with Mesa",
                            other_stage_kind(path)
                        ),
                        Some(Location::line(path.clone(), 1)),
                    ));
                }
            }
            Err(e) => diags.push(e),
        }
    }
    diags
}

/// Built-in variables only the fragment or the compute stage declares.
const FRAGMENT_AND_COMPUTE_BUILT_INS: [(&str, &str); 17] = [
    ("gl_FragCoord", "fragment"),
    ("gl_FrontFacing", "fragment"),
    ("gl_PointCoord", "fragment"),
    ("gl_FragDepth", "fragment"),
    ("gl_FragColor", "fragment"),
    ("gl_FragData", "fragment"),
    ("gl_SampleID", "fragment"),
    ("gl_SamplePosition", "fragment"),
    ("gl_SampleMaskIn", "fragment"),
    ("gl_SampleMask", "fragment"),
    ("gl_HelperInvocation", "fragment"),
    ("gl_NumWorkGroups", "compute"),
    ("gl_WorkGroupID", "compute"),
    ("gl_LocalInvocationID", "compute"),
    ("gl_GlobalInvocationID", "compute"),
    ("gl_LocalInvocationIndex", "compute"),
    ("gl_WorkGroupSize", "compute"),
];

/// A geometry or tessellation stage (`kind`), which naga cannot read, naming a built-in only
/// the fragment or the compute stage declares: every driver refuses it as undeclared. The
/// first use of each, at its line.
fn built_ins_of_other_stages(pre: &Preprocessed, kind: &str) -> Vec<Diagnostic> {
    let tokens = tokenize(&pre.text).unwrap_or_default();
    FRAGMENT_AND_COMPUTE_BUILT_INS
        .iter()
        .filter_map(|(name, owner)| {
            let first = tokens.iter().find(|t| t.is_ident(name))?;
            let message = naga_check::built_in_of_another_stage_message(name, owner, kind);
            Some(Diagnostic::error(Code::Glsl, message, pre.location(first.line)))
        })
        .collect()
}

/// Preprocesses and lowers one compute stage and runs the checks that need no naga.
pub(crate) fn check_compute(
    path: &str,
    program: &str,
    provider: &dyn FileProvider,
    macros: &PreprocessOptions,
    names: &CustomNames,
    loader: Loader,
) -> (Option<LoweredCompute>, Vec<Diagnostic>) {
    let mut pre = match preprocess::preprocess(provider, path, macros) {
        Ok(pre) => pre,
        Err(e) => return (None, vec![e]),
    };
    assume_glsl_110(&mut pre);
    let mut diags: Vec<Diagnostic> = pre.warnings.clone();
    let tokens = tokenize(&pre.text).unwrap_or_default();
    diags.extend(version_rules::check_compute(&pre, &tokens).map(lenient_on_nvidia));
    diags.extend(version_rules::unknown_extensions(&pre, &tokens));
    diags.extend(version_rules::extensions_some_drivers_lack(&pre, &tokens));
    diags.extend(macos_refusals(&pre, &tokens, true));
    drop(tokens);
    diags.extend(above_configured_glsl(&pre, macros));
    match naga_check::lower_compute(Arc::new(pre)) {
        Ok(stage) => {
            diags.extend(interface::check_resources(&stage.preprocessed, &stage.lowered, program, names, loader));
            (Some(stage), diags)
        }
        Err(e) => {
            diags.push(e);
            (None, diags)
        }
    }
}

/// Iris features that need more than macOS's OpenGL 4.1, with what each needs.
const IRIS_FEATURES_ABOVE_MACOS: [(&str, &str); 3] =
    [("CUSTOM_IMAGES", "image load/store, OpenGL 4.2"), ("COMPUTE_SHADERS", "compute shaders, OpenGL 4.3"), ("SSBO", "shader storage buffers, OpenGL 4.3")];

/// `iris.features.required` naming a feature macOS's OpenGL lacks: Iris refuses to load the
/// pack there, whatever its programs hold.
pub(crate) fn iris_features_on_macos(props: &tidepack_loader::properties::Properties) -> Vec<Diagnostic> {
    let Some(entry) = props.get("iris.features.required") else { return Vec::new() };
    entry
        .value
        .split_whitespace()
        .filter_map(|feature| IRIS_FEATURES_ABOVE_MACOS.iter().find(|(name, _)| *name == feature))
        .map(|(feature, needs)| {
            Diagnostic::error(
                Code::Macos,
                format!("iris.features.required names {feature} ({needs}); macOS stops at OpenGL 4.1, so Iris refuses to load the pack there"),
                Some(Location::line(tidepack_loader::properties::PATH, entry.line)),
            )
            .refused_by(Drivers::MACOS)
        })
        .collect()
}
