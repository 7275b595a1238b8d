//! The report as text for people (codespan snippets), JSON for tools, and GitHub Actions
//! workflow commands (annotations on the pack's files).

use std::fmt::Write as _;

use codespan_reporting::term::termcolor::WriteColor;
use tidepack_glsl::diagnostic;
use tidepack_glsl::{Diagnostic, Severity};

use crate::{Report, Status};

/// The path a diagnostic shows: the pack's `shaders/` folder joined with the location's path.
fn shown_path(report: &Report, path: &str) -> String {
    format!("{}{path}", report.pack.display_root)
}

/// The diagnostics with their paths as the user sees them.
fn displayed(report: &Report) -> Vec<Diagnostic> {
    report
        .diagnostics
        .iter()
        .map(|d| {
            let mut d = d.clone();
            if let Some(loc) = &mut d.location {
                loc.path = shown_path(report, &loc.path);
            }
            d
        })
        .collect()
}

/// Compiler-style diagnostics with snippets (to `diagnostics_out`) and a summary line.
pub fn human(report: &Report, diagnostics_out: &mut dyn WriteColor) -> std::io::Result<String> {
    let shown = displayed(report);
    let root = &report.pack.display_root;
    diagnostic::emit(diagnostics_out, &shown, &|path| report.source_of(path.strip_prefix(root.as_str())?))?;
    let mut summary = String::new();
    let validated = report.programs.iter().filter(|p| p.status != Status::Skipped(String::new()) && !matches!(p.status, Status::Skipped(_))).count();
    let invalid = report.programs.iter().filter(|p| p.status == Status::Invalid).count();
    for p in &report.programs {
        if let Status::Skipped(why) = &p.status {
            writeln!(summary, "  skipped {}: {why}", p.id).unwrap();
        }
    }
    let partial: Vec<&str> = report.programs.iter().flat_map(|p| p.only_preprocessed.iter().map(String::as_str)).collect();
    if !partial.is_empty() {
        let why = if report.driver.is_some() {
            "the OpenGL driver cannot compile them"
        } else {
            "naga has no geometry or tessellation stage; `--driver` compiles them with Mesa"
        };
        writeln!(summary, "  only preprocessed, not compiled ({why}): {}", partial.join(", ")).unwrap();
    }
    if let Some(d) = &report.driver {
        writeln!(
            summary,
            "  driver {}: {} programs both accept, {} both reject, {} only the driver rejects{}, {} only tidepack rejects{}",
            d.driver,
            d.both_accept,
            d.both_reject,
            d.only_driver_rejects.len(),
            list(&d.only_driver_rejects),
            d.only_tidepack_rejects.len(),
            list(&d.only_tidepack_rejects)
        )
        .unwrap();
    }
    writeln!(
        summary,
        "{root}: {validated} programs under {} ({}), {} distinct stages validated in {:.2} s: {invalid} invalid; {} errors, {} warnings",
        if report.option_sets.len() == 1 { "1 option set".to_string() } else { format!("{} option sets", report.option_sets.len()) },
        report.option_sets.join(", "),
        report.stages_validated,
        report.elapsed.as_secs_f64(),
        report.errors(),
        report.warnings()
    )
    .unwrap();
    Ok(summary)
}

fn list(ids: &[String]) -> String {
    if ids.is_empty() { String::new() } else { format!(" ({})", ids.join(", ")) }
}

fn json_string(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            c if (c as u32) < 0x20 => write!(out, "\\u{:04x}", c as u32).unwrap(),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// One JSON object: `diagnostics`, `programs` and `summary`.
pub fn json(report: &Report) -> String {
    let mut out = String::from("{\n  \"diagnostics\": [");
    for (i, d) in displayed(report).iter().enumerate() {
        out.push_str(if i == 0 { "\n    {" } else { ",\n    {" });
        let severity = if d.is_error() { "error" } else { "warning" };
        write!(out, "\"severity\": \"{severity}\", \"message\": {}", json_string(&d.message)).unwrap();
        match &d.location {
            Some(loc) => {
                write!(out, ", \"file\": {}, \"line\": {}", json_string(&loc.path), loc.line).unwrap();
                match &loc.columns {
                    Some(c) => write!(out, ", \"column\": {}", c.start + 1).unwrap(),
                    None => out.push_str(", \"column\": null"),
                }
            }
            None => out.push_str(", \"file\": null, \"line\": null, \"column\": null"),
        }
        let notes: Vec<String> = d.notes.iter().map(|n| json_string(n)).collect();
        write!(out, ", \"notes\": [{}]}}", notes.join(", ")).unwrap();
    }
    out.push_str("\n  ],\n  \"programs\": [");
    for (i, p) in report.programs.iter().enumerate() {
        out.push_str(if i == 0 { "\n    {" } else { ",\n    {" });
        let (status, why) = match &p.status {
            Status::Valid => ("valid", None),
            Status::Invalid => ("invalid", None),
            Status::Skipped(why) => ("skipped", Some(why)),
        };
        let stages: Vec<String> = p.stages.iter().map(|s| json_string(s)).collect();
        write!(out, "\"program\": {}, \"status\": \"{status}\", \"stages\": [{}]", json_string(&p.id), stages.join(", ")).unwrap();
        if let Some(why) = why {
            write!(out, ", \"reason\": {}", json_string(why)).unwrap();
        }
        let partial: Vec<String> = p.only_preprocessed.iter().map(|s| json_string(s)).collect();
        write!(out, ", \"only_preprocessed\": [{}]", partial.join(", ")).unwrap();
        out.push('}');
    }
    let sets: Vec<String> = report.option_sets.iter().map(|s| json_string(s)).collect();
    let driver = match &report.driver {
        None => "null".to_string(),
        Some(d) => {
            let ids = |v: &[String]| v.iter().map(|s| json_string(s)).collect::<Vec<_>>().join(", ");
            format!(
                "{{\"driver\": {}, \"both_accept\": {}, \"both_reject\": {}, \"only_driver_rejects\": [{}], \"only_tidepack_rejects\": [{}]}}",
                json_string(&d.driver),
                d.both_accept,
                d.both_reject,
                ids(&d.only_driver_rejects),
                ids(&d.only_tidepack_rejects)
            )
        }
    };
    write!(
        out,
        "\n  ],\n  \"driver\": {driver},\n  \"summary\": {{\"pack\": {}, \"option_sets\": [{}], \"stages_validated\": {}, \"errors\": {}, \"warnings\": {}, \"seconds\": {:.3}}}\n}}\n",
        json_string(&report.pack.display_root),
        sets.join(", "),
        report.stages_validated,
        report.errors(),
        report.warnings(),
        report.elapsed.as_secs_f64()
    )
    .unwrap();
    out
}

/// GitHub Actions escapes for a message and for a property value.
fn github_escape(s: &str, property: bool) -> String {
    let mut out = s.replace('%', "%25").replace('\r', "%0D").replace('\n', "%0A");
    if property {
        out = out.replace(':', "%3A").replace(',', "%2C");
    }
    out
}

/// `::error file=…,line=…::message` lines, one per diagnostic.
pub fn github(report: &Report) -> String {
    let mut out = String::new();
    for d in displayed(report) {
        let command = match d.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        let mut props = vec!["title=tidepack validate".to_string()];
        if let Some(loc) = &d.location {
            props.push(format!("file={}", github_escape(&loc.path, true)));
            props.push(format!("line={}", loc.line));
            if let Some(c) = &loc.columns {
                props.push(format!("col={}", c.start + 1));
            }
        }
        let mut message = d.message.clone();
        for note in &d.notes {
            message.push('\n');
            message.push_str(note);
        }
        writeln!(out, "::{command} {}::{}", props.join(","), github_escape(&message, false)).unwrap();
    }
    out
}
