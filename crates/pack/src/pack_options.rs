//! The pack's options as OptiFine sees them, checked against the manifest: every option has a
//! label, a comment and a place on a screen, every profile sets every option to a value the
//! option offers, and the GLSL defaults are the default profile.

use std::collections::BTreeMap;

use tidepack_loader::option_lines::{self, OptionKind, OptionSet, OptionValue};
use tidepack_glsl::{Code, Diagnostic, Location};

use crate::manifest::line_of;
use crate::source::PackSource;

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PackOption {
    pub name: String,
    pub kind: OptionKind,
    pub tooltip: String,
    /// Where it is declared: template display path and line.
    pub declared_at: Location,
}

pub type PackOptions = BTreeMap<String, PackOption>;

/// Options declared by the GLSL templates (the same in both dialects).
pub fn collect(source: &PackSource) -> Result<PackOptions, Vec<Diagnostic>> {
    let mut found: PackOptions = BTreeMap::new();
    let mut errors = Vec::new();
    for template in source.templates.iter().filter(|t| is_glsl(&t.path)) {
        for decl in option_lines::scan(&template.text) {
            let at = Location::line(template.display_path.clone(), decl.line);
            if let Some(previous) = found.get(&decl.name) {
                if previous.kind != decl.kind {
                    errors.push(
                        Diagnostic::error(Code::Template, format!("option {} is declared twice with different defaults or values", decl.name), Some(at))
                            .with_note(format!("first declared at {}; OptiFine disables such an option", previous.declared_at)),
                    );
                }
                continue;
            }
            found.insert(
                decl.name.clone(),
                PackOption { name: decl.name, kind: decl.kind, tooltip: decl.tooltip, declared_at: at },
            );
        }
    }
    if errors.is_empty() { Ok(found) } else { Err(errors) }
}

pub fn is_glsl(path: &str) -> bool {
    path.ends_with(".vsh") || path.ends_with(".fsh") || path.ends_with(".glsl")
}

/// The options with `defaults` as their default values (a pack built with a profile).
pub fn with_defaults(options: &PackOptions, defaults: &OptionSet) -> PackOptions {
    let mut shipped = options.clone();
    for (name, value) in defaults {
        let Some(option) = shipped.get_mut(name) else { continue };
        option.kind = match (&option.kind, value) {
            (OptionKind::Switch { .. }, OptionValue::Switch(on)) => OptionKind::Switch { default: *on },
            (OptionKind::Value { values, .. }, OptionValue::Value(v)) => {
                OptionKind::Value { default: v.clone(), values: values.clone() }
            }
            (kind, _) => kind.clone(),
        };
    }
    shipped
}

/// Parses a profile's setting for `option`.
fn profile_value(option: &PackOption, value: &toml::Value) -> Result<OptionValue, String> {
    match (&option.kind, value) {
        (OptionKind::Switch { .. }, toml::Value::Boolean(on)) => Ok(OptionValue::Switch(*on)),
        (OptionKind::Switch { .. }, _) => Err(format!("{} is a switch: set it to true or false", option.name)),
        (OptionKind::Value { values, .. }, toml::Value::String(v)) if values.contains(v) => {
            Ok(OptionValue::Value(v.clone()))
        }
        (OptionKind::Value { values, .. }, _) => Err(format!(
            "{} takes one of its values, written as in the GLSL and quoted: {}",
            option.name,
            values.iter().map(|v| format!("\"{v}\"")).collect::<Vec<_>>().join(", ")
        )),
    }
}

/// How a profile in pack.toml writes `value`: switches as booleans, values quoted.
fn toml_value_of(value: &OptionValue) -> String {
    match value {
        OptionValue::Switch(on) => on.to_string(),
        OptionValue::Value(v) => format!("\"{v}\""),
    }
}

/// The option values of a profile.
pub fn profile_set(source: &PackSource, options: &PackOptions, profile: &str) -> Result<OptionSet, Diagnostic> {
    let Some(p) = source.manifest.profiles.iter().find(|p| p.name == profile) else {
        let names: Vec<&str> = source.manifest.profiles.iter().map(|p| p.name.as_str()).collect();
        return Err(Diagnostic::error(Code::Template, format!("no profile named {}; the pack has {}", tidepack_glsl::terminal::line(profile), names.join(", ")), None));
    };
    p.settings
        .iter()
        .filter_map(|(name, value)| Some((name, options.get(name)?, value)))
        .map(|(name, option, value)| {
            let value = profile_value(option, value).map_err(|m| Diagnostic::error(Code::Template, m, None))?;
            Ok((name.clone(), value))
        })
        .collect()
}

/// Cross-checks the GLSL options and the manifest; returns every problem found.
pub fn check_manifest(source: &PackSource, options: &PackOptions) -> Vec<Diagnostic> {
    let m = &source.manifest;
    let text = &source.manifest_text;
    let at = |section: &str, needle: &str| {
        line_of(text, section, needle).map(|line| Location::line(source.manifest_path.clone(), line))
    };
    let mut errors = Vec::new();
    for option in options.values() {
        if !m.options.contains_key(&option.name) {
            errors.push(
                Diagnostic::error(
                    Code::Template,
                    format!("option {} has no label: add [options.{}] with label and comment to the manifest", option.name, option.name),
                    Some(option.declared_at.clone()),
                )
                .with_note(format!("the lang file needs option.{0} and option.{0}.comment", option.name)),
            );
        }
    }
    for (name, text_entry) in &m.options {
        let here = at(&format!("[options.{name}]"), &format!("[options.{name}]"));
        match options.get(name) {
            None => errors.push(Diagnostic::error(Code::Template, format!("[options.{name}] names no option declared in the GLSL"), here)),
            Some(option) => {
                if text_entry.label.trim().is_empty() || text_entry.comment.trim().is_empty() {
                    errors.push(Diagnostic::error(Code::Template, format!("option {name} needs a non-empty label and comment"), here.clone()));
                }
                if let OptionKind::Value { values, .. } = &option.kind {
                    for value in text_entry.values.keys().filter(|v| !values.contains(v)) {
                        errors.push(Diagnostic::error(Code::Template, format!("option {name} has no value {value} to label"), here.clone()));
                    }
                }
            }
        }
    }
    // Screens: every item exists, every option is placed exactly once.
    let mut placed: BTreeMap<&str, usize> = BTreeMap::new();
    let screens = std::iter::once(("main", &m.screen.main)).chain(m.screen.subs.iter().map(|(n, s)| (n.as_str(), &s.items)));
    for (screen, items) in screens {
        for item in items {
            let here = at("[screen", &format!("\"{item}\""));
            if let Some(sub) = item.strip_prefix('[').and_then(|s| s.strip_suffix(']')) {
                if !m.screen.subs.contains_key(sub) {
                    errors.push(Diagnostic::error(Code::Template, format!("screen {screen} links to [{sub}], which is not defined"), here));
                }
            } else if !matches!(item.as_str(), "<profile>" | "<empty>" | "*") {
                if options.contains_key(item) {
                    *placed.entry(item).or_default() += 1;
                } else {
                    errors.push(Diagnostic::error(Code::Template, format!("screen {screen} lists {item}, which is not an option"), here));
                }
            }
        }
    }
    for option in options.values() {
        match placed.get(option.name.as_str()) {
            None => errors.push(Diagnostic::error(
                Code::Template,
                format!("option {} is on no screen; players could not change it", option.name),
                Some(option.declared_at.clone()),
            )),
            Some(n) if *n > 1 => errors.push(Diagnostic::error(
                Code::Template,
                format!("option {} is on {n} screens; place it once", option.name),
                Some(option.declared_at.clone()),
            )),
            _ => {}
        }
    }
    for slider in &m.screen.sliders {
        if !matches!(options.get(slider).map(|o| &o.kind), Some(OptionKind::Value { .. })) {
            errors.push(Diagnostic::error(Code::Template, format!("slider {slider} is not a value option"), at("sliders", slider)));
        }
    }
    // Profiles: complete, valid, and the defaults are the default profile.
    if !m.profiles.iter().any(|p| p.name == m.pack.default_profile) {
        errors.push(Diagnostic::error(
            Code::Template,
            format!("default_profile {} is not one of the profiles", m.pack.default_profile),
            at("[pack]", "default_profile"),
        ));
    }
    for profile in &m.profiles {
        let section = format!("name = \"{}\"", profile.name);
        for option in options.values() {
            match profile.settings.get(&option.name) {
                None => errors.push(Diagnostic::error(
                    Code::Template,
                    format!("profile {} does not set {}; every profile sets every option", profile.name, option.name),
                    at(&section, &section),
                )),
                Some(value) => {
                    let glsl_default = option.kind.default_value();
                    match profile_value(option, value) {
                        Err(message) => errors.push(Diagnostic::error(Code::Template, message, at(&section, &format!("{} =", option.name)))),
                        Ok(set) if profile.name == m.pack.default_profile && set != glsl_default => {
                            let setting_at = at(&section, &format!("{} =", option.name))
                                .map_or_else(|| source.manifest_path.clone(), |l| l.to_string());
                            errors.push(
                                Diagnostic::error(
                                    Code::Template,
                                    format!(
                                        "{} defaults to {glsl_default} in the GLSL but the default profile {} sets {set}",
                                        option.name, profile.name,
                                    ),
                                    Some(option.declared_at.clone()),
                                )
                                .with_note(format!(
                                    "the GLSL defaults must equal the default profile (default_profile = \"{}\" in [pack]): \
                                     to make {glsl_default} the default, set {} = {} in [profile.settings] of the profile named \
                                     {} at {setting_at}; to keep {set}, write it back on the #define line at {}",
                                    profile.name,
                                    option.name,
                                    toml_value_of(&glsl_default),
                                    profile.name,
                                    option.declared_at,
                                ))
                                .with_note("OptiFine would show the defaults as a custom profile"),
                            );
                        }
                        Ok(_) => {}
                    }
                }
            }
        }
        for name in profile.settings.keys().filter(|n| !options.contains_key(*n)) {
            errors.push(Diagnostic::error(
                Code::Template,
                format!("profile {} sets {name}, which is not an option", profile.name),
                at(&section, &format!("{name} =")),
            ));
        }
    }
    errors
}
