//! A stage's text as the loader hands it to the driver, which `--driver` and glslangValidator
//! compile: includes expanded by the loader's rules, its standard macros after `#version`, and
//! under Iris its transformer's rewrites.

use tidepack_glsl::preprocess::{self, FileProvider, expand_includes_mapped};
use tidepack_glsl::{Diagnostic, Location};
use tidepack_loader::macros::StandardMacros;

/// The text of the stage at `path` as the loader of `macros` hands it to the driver, with the
/// pack file and line of each of its lines (`None` for the macros'). Under Iris, where its
/// preprocessor reads the stage, the albedo sampler is named `gtexture` in every program,
/// functions nothing calls are removed and `#version` comes first; a stage the preprocessor
/// refuses (an `#extension` after code) goes as written.
pub fn as_loader_hands_it(provider: &dyn FileProvider, path: &str, macros: &StandardMacros) -> Result<(String, Vec<Option<Location>>), Diagnostic> {
    let defines = macros.define_lines();
    let (mut text, mut map) = expand_includes_mapped(provider, path, &defines, macros.include_rules())?;
    if macros.iris_version.is_some()
        && let Ok(seen) = preprocess::preprocess(provider, path, &macros.preprocess_options())
    {
        // Iris's preprocessor puts `#version` first, wherever the pack wrote it (inside an `#if`
        // on the loader's macros, after `#define`s), with its macros defined from the start.
        let (plain, plain_map) = expand_includes_mapped(provider, path, "", macros.include_rules())?;
        if let Some((resolved, _)) = tidepack_loader::iris::version_resolved_on_top(&plain, seen.version.as_ref()) {
            let (version, rest) = resolved.split_once('\n').unwrap_or((&resolved, ""));
            text = format!("{version}\n{defines}{rest}");
            map = std::iter::repeat_n(None, 1 + defines.matches('\n').count()).chain(plain_map).collect();
        }
        text = tidepack_loader::iris::as_transformed(text, &seen.text, true, true).0;
    }
    Ok((text, map))
}
