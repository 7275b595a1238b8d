//! Each program's stages preprocessed and lowered for naga, with the checks that need no naga.

use std::sync::Arc;

use tidepack_glsl::naga_check::{self, LoweredCompute, LoweredStage};
use tidepack_glsl::preprocess::{self, FileProvider, PreprocessOptions, Preprocessed, assume_glsl_110};
use tidepack_glsl::{Diagnostic, Location, Stage};

use tidepack_loader::directives::CustomNames;
use tidepack_loader::loader::Loader;
use tidepack_loader::programs::Program;

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
                diags.extend(pre.warnings.iter().cloned());
                diags.extend(version_rules::check(&pre, *stage, loader));
                diags.extend(glsl_rules::check(&pre, *stage));
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
        diags.extend(interface::check_varyings(vs, fs));
    }
    for stage in &lowered {
        if stage.stage == Stage::Fragment {
            diags.extend(interface::check_render_targets(&stage.preprocessed, stage));
        }
        diags.extend(interface::check_resources(&stage.preprocessed, &stage.lowered, &program.name, names, loader));
    }
    Ok((lowered, diags))
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
                if !driver {
                    diags.push(Diagnostic::warning(
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
    diags.extend(version_rules::check_compute(&pre));
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
