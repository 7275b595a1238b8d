//! A stage's text as the loader hands it to the driver, which `--driver` and glslangValidator
//! compile: under OptiFine, includes expanded and its standard macros after `#version`; under
//! Iris, its preprocessor's output with its transformer's rewrites.

use tidepack_glsl::preprocess::{self, FileProvider, expand_includes_mapped};
use tidepack_glsl::{Diagnostic, Location};
use tidepack_loader::macros::StandardMacros;

/// The text of the stage at `path` as the loader of `macros` hands it to the driver, with the
/// pack file and line of each of its lines (`None` for lines the loader adds). OptiFine splices
/// the includes in and adds its macros after `#version`; the driver reads every other
/// directive. Iris's preprocessor reads every directive itself, so the driver gets its output:
/// `#version` first and raised to 3.30, the albedo sampler named `gtexture` in every program
/// and functions nothing calls removed. A stage the preprocessor refuses (an `#extension` after code) goes as OptiFine
/// hands it.
pub fn as_loader_hands_it(provider: &dyn FileProvider, path: &str, macros: &StandardMacros) -> Result<(String, Vec<Option<Location>>), Diagnostic> {
    if macros.iris_version.is_some()
        && let Ok(seen) = preprocess::preprocess(provider, path, &macros.preprocess_options())
    {
        let (text, map, _) = tidepack_loader::iris::as_preprocessor_leaves_it(&seen.text, &seen);
        return Ok((tidepack_loader::iris::as_transformed(text, &seen.text, tidepack_loader::iris::Transform::ALL, tidepack_glsl::Stage::from_path(path)).0, map));
    }
    expand_includes_mapped(provider, path, &macros.define_lines(), macros.include_rules())
}
