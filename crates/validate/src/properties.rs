//! What the validator reads from `shaders.properties`: profiles (option values to validate
//! under), custom uniforms and custom texture names (so their uses are not "unknown").

use std::collections::{BTreeMap, BTreeSet};

use tidepack_glsl::options::{OptionKind, OptionSet, OptionValue};
use tidepack_glsl::{Diagnostic, Location};

pub const PATH: &str = "shaders.properties";

#[derive(Clone, Debug, Default)]
pub struct Properties {
    /// `profile.NAME=` values with the line they start on.
    pub profiles: BTreeMap<String, (String, u32)>,
    /// `uniform.<type>.<name>` and `variable.<type>.<name>`: name → type.
    pub custom_uniforms: BTreeMap<String, String>,
    /// Sampler names made available by `customTexture.<name>` (Iris) and by the sampler
    /// names of `image.<name>` (Iris custom images).
    pub custom_samplers: BTreeSet<String>,
    /// Image names made available by `image.<name> = <sampler> <format> …` (Iris).
    pub custom_images: BTreeSet<String>,
}

/// Reads the keys the validator needs. Directive lines (`#ifdef …`) are skipped: profiles are
/// read without option macros, and a custom uniform defined under any branch is accepted.
pub fn parse(text: &str) -> Properties {
    let mut props = Properties::default();
    let mut pending: Option<(String, u32)> = None;
    for (index, raw) in text.lines().enumerate() {
        let line_no = index as u32 + 1;
        let (mut logical, start) = match pending.take() {
            Some((head, start)) => (head + raw.trim_start(), start),
            None => (raw.trim_start().to_string(), line_no),
        };
        if logical.ends_with('\\') && !logical.ends_with("\\\\") {
            logical.pop();
            pending = Some((logical, start));
            continue;
        }
        if logical.starts_with('#') || logical.starts_with('!') {
            continue;
        }
        let Some((key, value)) = logical.split_once(['=', ':']) else { continue };
        let (key, value) = (key.trim(), value.trim());
        if let Some(name) = key.strip_prefix("profile.") {
            props.profiles.insert(name.to_string(), (value.to_string(), start));
        } else if let Some(rest) = key.strip_prefix("uniform.").or_else(|| key.strip_prefix("variable.")) {
            if let Some((ty, name)) = rest.split_once('.') {
                props.custom_uniforms.insert(name.to_string(), ty.to_string());
            }
        } else if let Some(name) = key.strip_prefix("customTexture.") {
            props.custom_samplers.insert(name.to_string());
        } else if let Some(name) = key.strip_prefix("image.") {
            props.custom_images.insert(name.to_string());
            if let Some(sampler) = value.split_whitespace().next() {
                props.custom_samplers.insert(sampler.to_string());
            }
        }
    }
    props
}

/// The option set of profile `name`: its own entries, and those of the profiles it names.
/// `options` are the pack's declared options; entries naming other things are reported.
pub fn profile_set(
    props: &Properties,
    name: &str,
    options: &BTreeMap<String, OptionKind>,
) -> Result<(OptionSet, Vec<Diagnostic>), Diagnostic> {
    let mut set = OptionSet::new();
    let mut warnings = Vec::new();
    let mut visiting = Vec::new();
    apply_profile(props, name, options, &mut set, &mut warnings, &mut visiting)?;
    Ok((set, warnings))
}

fn apply_profile(
    props: &Properties,
    name: &str,
    options: &BTreeMap<String, OptionKind>,
    set: &mut OptionSet,
    warnings: &mut Vec<Diagnostic>,
    visiting: &mut Vec<String>,
) -> Result<(), Diagnostic> {
    let Some((value, line)) = props.profiles.get(name) else {
        let known: Vec<&str> = props.profiles.keys().map(String::as_str).collect();
        return Err(Diagnostic::error(
            format!("no profile `{name}` in shaders.properties (profiles: {})", if known.is_empty() { "none".into() } else { known.join(", ") }),
            None,
        ));
    };
    if visiting.iter().any(|v| v == name) {
        return Err(Diagnostic::error(
            format!("profile cycle: {} -> {name}", visiting.join(" -> ")),
            Some(Location::line(PATH, *line)),
        ));
    }
    visiting.push(name.to_string());
    let at = || Some(Location::line(PATH, *line));
    for entry in value.split_whitespace() {
        if let Some(other) = entry.strip_prefix("profile.") {
            apply_profile(props, other, options, set, warnings, visiting)?;
            continue;
        }
        if entry.starts_with("!program.") || entry.starts_with("program.") {
            continue;
        }
        let (option, value) = match entry.split_once([':', '=']) {
            Some((o, v)) => (o, Some(v)),
            None => (entry.trim_start_matches('!'), None),
        };
        match (options.get(option), value) {
            (Some(OptionKind::Switch { .. }), None) => {
                set.insert(option.to_string(), OptionValue::Switch(!entry.starts_with('!')));
            }
            (Some(OptionKind::Value { values, .. }), Some(v)) => {
                if !values.iter().any(|x| x == v) {
                    warnings.push(Diagnostic::warning(
                        format!("profile `{name}` sets {option} to `{v}`, which is not among its values [{}]", values.join(" ")),
                        at(),
                    ));
                }
                set.insert(option.to_string(), OptionValue::Value(v.to_string()));
            }
            (Some(_), _) => warnings.push(Diagnostic::warning(
                format!("profile `{name}`: `{entry}` does not match how {option} is declared (switch or value)"),
                at(),
            )),
            (None, _) => warnings.push(Diagnostic::warning(
                format!("profile `{name}` sets `{option}`, which no shader file declares as an option"),
                at(),
            )),
        }
    }
    visiting.pop();
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_profiles_uniforms_and_continuations() {
        let props = parse(
            "#ifdef X\nuniform.float.fadeIn = smooth(1, 2, 3)\n#endif\nprofile.LOW=!SHADOWS QUALITY:1 \\\n  profile.BASE\nprofile.BASE=WAVES\n",
        );
        assert_eq!(props.custom_uniforms.get("fadeIn").map(String::as_str), Some("float"));
        let images = parse("image.imgDepthQ = texDepthQ RED R16F HALF_FLOAT false true 0.25 0.25\n");
        assert!(images.custom_images.contains("imgDepthQ") && images.custom_samplers.contains("texDepthQ"));
        assert_eq!(props.profiles["LOW"], ("!SHADOWS QUALITY:1 profile.BASE".to_string(), 4));
        let options: BTreeMap<String, OptionKind> = [
            ("SHADOWS".to_string(), OptionKind::Switch { default: true }),
            ("WAVES".to_string(), OptionKind::Switch { default: false }),
            ("QUALITY".to_string(), OptionKind::Value { default: "2".into(), values: vec!["1".into(), "2".into()] }),
        ]
        .into();
        let (set, warnings) = profile_set(&props, "LOW", &options).unwrap();
        assert!(warnings.is_empty(), "{warnings:?}");
        assert_eq!(set["SHADOWS"], OptionValue::Switch(false));
        assert_eq!(set["WAVES"], OptionValue::Switch(true));
        assert_eq!(set["QUALITY"], OptionValue::Value("1".into()));
        assert!(profile_set(&props, "NONE", &options).is_err());
    }

    #[test]
    fn profile_cycles_and_unknown_options_are_reported() {
        let props = parse("profile.A=profile.B\nprofile.B=profile.A TYPO\n");
        let err = profile_set(&props, "A", &BTreeMap::new()).unwrap_err();
        assert!(err.message.contains("cycle"), "{err}");
        let props = parse("profile.A=TYPO\n");
        let (_, warnings) = profile_set(&props, "A", &BTreeMap::new()).unwrap();
        assert_eq!(warnings[0].location.as_ref().unwrap().line, 1);
    }
}
