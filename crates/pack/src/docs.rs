//! The parts of docs/*.md that the pack's sources and its build decide, written from them so
//! they cannot go stale: each sits between a `<!-- generated: NAME ... -->` line and a
//! `<!-- end generated -->` line, and `tidepack docs` rewrites it (`--check` fails where a
//! doc differs; a test runs that).

use std::fmt::Write as _;
use std::path::Path;

use tidepack_loader::option_lines::{OptionKind, OptionValue};

use crate::build::{BuildOptions, BuildReport};
use crate::option_sets::Coverage;
use crate::pack_options::{self, PackOptions};
use crate::source::PackSource;

/// One generated section: the doc it lives in (relative to docs/), its name and its text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Section {
    pub doc: &'static str,
    pub name: &'static str,
    pub text: String,
}

/// The sections the sources decide, and those the default build's figures decide.
pub fn sections(source: &PackSource, options: &PackOptions, build: &BuildReport) -> Result<Vec<Section>, String> {
    Ok(vec![
        Section { doc: "water-model.md", name: "options-and-profiles", text: options_table(source, options)? },
        Section { doc: "skipping.md", name: "identical-stages", text: identical_stages(build) },
    ])
}

/// Every option in the order settings.glsl declares it, with its range and each profile's value.
fn options_table(source: &PackSource, options: &PackOptions) -> Result<String, String> {
    let profiles = &source.manifest.profiles;
    let sets = profiles
        .iter()
        .map(|p| pack_options::profile_set(source, options, &p.name).map_err(|d| d.message))
        .collect::<Result<Vec<_>, _>>()?;
    let mut ordered: Vec<_> = options.values().collect();
    ordered.sort_by(|a, b| (&a.declared_at.path, a.declared_at.line).cmp(&(&b.declared_at.path, b.declared_at.line)));
    let mut out = String::from("| option | range |");
    for p in profiles {
        write!(out, " {} |", p.name).unwrap();
    }
    out.push_str("\n|---|---|");
    out.push_str(&"---|".repeat(profiles.len()));
    out.push('\n');
    for option in ordered {
        let range = match &option.kind {
            OptionKind::Switch { .. } => "switch".to_string(),
            OptionKind::Value { values, .. } => values.join(" "),
        };
        write!(out, "| `{}` | {range} |", option.name).unwrap();
        for set in &sets {
            let value = match set.get(&option.name) {
                Some(OptionValue::Switch(true)) => "on".to_string(),
                Some(OptionValue::Switch(false)) => "off".to_string(),
                Some(OptionValue::Value(v)) => v.clone(),
                None => return Err(format!("a profile leaves {} unset", option.name)),
            };
            write!(out, " {value} |").unwrap();
        }
        out.push('\n');
    }
    Ok(out)
}

fn identical_stages(build: &BuildReport) -> String {
    let per_dialect: Vec<String> = build
        .outcomes
        .iter()
        .map(|o| format!("{}: {} stages validated, {} skipped as identical", o.dialect, o.validation.stages_validated, o.validation.stages_identical))
        .collect();
    format!("For the default build ({} option sets per dialect): {}.\n", build.outcomes.first().map_or(0, |o| o.validation.option_sets), per_dialect.join("; "))
}

/// Writes every generated part of the docs in `docs_dir` from the pack sources in
/// `source_dir` (building the pack into a temporary folder for its figures), or with `check`
/// only compares. Returns the docs that differed (and, without `check`, were rewritten).
pub fn update(source_dir: &Path, docs_dir: &Path, check: bool) -> Result<Vec<String>, String> {
    let source = PackSource::load(source_dir).map_err(|d| d.to_string())?;
    let options = pack_options::collect(&source).map_err(|e| e.iter().map(ToString::to_string).collect::<Vec<_>>().join("\n"))?;
    let out_dir = std::env::temp_dir().join(format!("tidepack-docs-{}", std::process::id()));
    let build = crate::build::build(
        &BuildOptions {
            source_dir: source_dir.to_path_buf(),
            out_dir: out_dir.clone(),
            dialects: crate::Dialect::ALL.to_vec(),
            profile: None,
            coverage: Coverage::Pairwise,
            specialisation: None,
        },
        None,
    );
    let _ = std::fs::remove_dir_all(&out_dir);
    let build = build.map_err(|f| f.diagnostics.iter().map(ToString::to_string).collect::<Vec<_>>().join("\n"))?;
    let mut docs: std::collections::BTreeMap<&str, (String, String)> = std::collections::BTreeMap::new();
    let mut read = |name: &'static str| -> Result<(), String> {
        if !docs.contains_key(name) {
            let text = std::fs::read_to_string(docs_dir.join(name)).map_err(|e| format!("cannot read docs/{name}: {e}"))?;
            docs.insert(name, (text.clone(), text));
        }
        Ok(())
    };
    let sections = sections(&source, &options, &build)?;
    for section in &sections {
        read(section.doc)?;
    }
    for section in &sections {
        let (_, new) = docs.get_mut(section.doc).expect("read above");
        *new = splice(new, section)?;
    }
    let diagnostics = std::fs::read_to_string(docs_dir.join("diagnostics.md")).unwrap_or_default();
    docs.insert("diagnostics.md", (diagnostics, tidepack_glsl::code::reference_page()));
    let mut differed = Vec::new();
    for (name, (old, new)) in &docs {
        if old != new {
            differed.push(format!("docs/{name}"));
            if !check {
                std::fs::write(docs_dir.join(name), new).map_err(|e| format!("cannot write docs/{name}: {e}"))?;
            }
        }
    }
    Ok(differed)
}

/// `doc` with the section's text in its place; an error when the doc has no such section.
pub fn splice(doc: &str, section: &Section) -> Result<String, String> {
    let start_marker = format!("<!-- generated: {} ", section.name);
    let start = doc.find(&start_marker).ok_or_else(|| format!("docs/{} has no `{start_marker}…-->` line", section.doc))?;
    let body_start = start + doc[start..].find('\n').ok_or_else(|| format!("docs/{}: the marker line does not end", section.doc))? + 1;
    let end_marker = "<!-- end generated -->";
    let end = body_start
        + doc[body_start..].find(end_marker).ok_or_else(|| format!("docs/{}: section {} has no `{end_marker}`", section.doc, section.name))?;
    Ok(format!("{}{}{}", &doc[..body_start], section.text, &doc[end..]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_section_replaces_what_is_between_its_markers_only() {
        let section = Section { doc: "x.md", name: "table", text: "new\n".into() };
        let doc = "intro\n<!-- generated: table (by `tidepack docs`) -->\nold\nrows\n<!-- end generated -->\nafter\n";
        assert_eq!(splice(doc, &section).unwrap(), "intro\n<!-- generated: table (by `tidepack docs`) -->\nnew\n<!-- end generated -->\nafter\n");
        let err = splice("no markers\n", &section).unwrap_err();
        assert!(err.contains("docs/x.md") && err.contains("generated: table"), "{err}");
    }
}
