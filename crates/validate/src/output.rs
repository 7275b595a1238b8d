//! The report as text for people (codespan snippets), JSON for tools, and GitHub Actions
//! workflow commands (annotations on the pack's files).

use std::collections::{BTreeMap, VecDeque};
use std::fmt::Write as _;

use serde::Serialize;

use codespan_reporting::term::termcolor::WriteColor;
use tidepack_glsl::{diagnostic, terminal};
use tidepack_glsl::{Code, Diagnostic, Severity};

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
    let root = &report.pack.display_root;
    diagnostic::emit(diagnostics_out, &displayed(report), &|path| report.source_of(path.strip_prefix(root.as_str())?))?;
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
            "  driver {}: {} both accept, {} both reject, {} only the driver rejects{}, {} only tidepack rejects{}{}",
            d.driver,
            plural(d.both_accept, "program"),
            d.both_reject,
            d.only_driver_rejects.len(),
            list(&d.only_driver_rejects),
            d.only_tidepack_rejects.len(),
            list(&d.only_tidepack_rejects),
            if d.not_compared.is_empty() {
                String::new()
            } else {
                format!(", {} not compared (the driver made no shader object: its context failed){}", d.not_compared.len(), list(&d.not_compared))
            }
        )
        .unwrap();
    }
    let plan = &report.plan;
    if let Some(covered) = plan.covered {
        writeln!(
            summary,
            "  option sets cover {}: {} program texts considered, {} identical to another set's",
            covered.describe(),
            plan.considered,
            plan.identical
        )
        .unwrap();
    }
    if plan.other_shards > 0 {
        writeln!(summary, "  this shard: {} program texts left to the other shards", plan.other_shards).unwrap();
    }
    let by_code = report.counts_by_code();
    if !by_code.is_empty() {
        let counts: Vec<String> = by_code.iter().map(|(code, errors, warnings)| format!("{code} {}", counted(*errors, *warnings))).collect();
        writeln!(summary, "  by code: {}", counts.join(", ")).unwrap();
    }
    if !report.allowed.is_empty() {
        let counts: Vec<String> = report.allowed.iter().map(|(code, n)| format!("{code} {n}")).collect();
        writeln!(summary, "  allowed, not shown: {}", counts.join(", ")).unwrap();
    }
    const LISTED: usize = 4;
    let mut sets = report.option_sets.iter().take(LISTED).cloned().collect::<Vec<_>>().join(", ");
    if report.option_sets.len() > LISTED {
        sets.push_str(&format!(", and {} more", report.option_sets.len() - LISTED));
    }
    writeln!(
        summary,
        "{root}: {} under {} ({sets}), {} validated in {:.2} s: {invalid} invalid; {}",
        plural(validated, "program"),
        plural(report.option_sets.len(), "option set"),
        plural(report.stages_validated, "distinct stage"),
        report.elapsed.as_secs_f64(),
        counted_each(report.errors(), report.warnings())
    )
    .unwrap();
    Ok(terminal::block(&summary))
}

fn plural(n: usize, what: &str) -> String {
    format!("{n} {what}{}", if n == 1 { "" } else { "s" })
}

/// `2 errors, 1 warning`, leaving out a zero count.
fn counted(errors: usize, warnings: usize) -> String {
    match (errors, warnings) {
        (0, w) => plural(w, "warning"),
        (e, 0) => plural(e, "error"),
        (e, w) => counted_each(e, w),
    }
}

/// `0 errors, 1 warning`.
fn counted_each(errors: usize, warnings: usize) -> String {
    format!("{}, {}", plural(errors, "error"), plural(warnings, "warning"))
}

fn list(ids: &[String]) -> String {
    if ids.is_empty() { String::new() } else { format!(" ({})", ids.join(", ")) }
}

#[derive(Serialize)]
struct JsonDiagnostic<'a> {
    severity: &'static str,
    /// Its code (`tidepack codes` lists them), the name `--allow` and `--deny` take.
    code: &'static str,
    message: &'a str,
    file: Option<&'a str>,
    line: Option<u32>,
    /// 1-based.
    column: Option<usize>,
    notes: &'a [String],
    /// The driver families whose compilers refuse it (`mesa`, `amd`, `intel`, `nvidia`,
    /// `macos`); empty for a warning about something no driver refuses.
    refused_by: Vec<&'static str>,
}

#[derive(Serialize)]
struct JsonProgram<'a> {
    program: &'a str,
    status: &'static str,
    stages: &'a [String],
    #[serde(skip_serializing_if = "Option::is_none")]
    reason: Option<&'a str>,
    only_preprocessed: &'a [String],
    /// Indices into `diagnostics`.
    diagnostics: &'a [usize],
}

#[derive(Serialize)]
struct JsonDriver<'a> {
    driver: &'a str,
    both_accept: usize,
    both_reject: usize,
    only_driver_rejects: &'a [String],
    only_tidepack_rejects: &'a [String],
    not_compared: &'a [String],
}

#[derive(Serialize)]
struct JsonSummary<'a> {
    pack: &'a str,
    option_sets: &'a [String],
    /// With `--covering`: what the sets cover.
    #[serde(skip_serializing_if = "Option::is_none")]
    covered: Option<&'static str>,
    /// (program, option set) pairs considered, and those skipped as identical to another.
    program_texts_considered: usize,
    program_texts_identical: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    program_texts_in_other_shards: Option<usize>,
    stages_validated: usize,
    errors: usize,
    warnings: usize,
    /// Warnings left out by `--allow` or the configuration file, by code.
    allowed: BTreeMap<&'static str, usize>,
}

#[derive(Serialize)]
struct JsonReport<'a> {
    diagnostics: Vec<JsonDiagnostic<'a>>,
    programs: Vec<JsonProgram<'a>>,
    driver: Option<JsonDriver<'a>>,
    summary: JsonSummary<'a>,
}

/// One JSON object: `diagnostics`, `programs` (each with the indices of its diagnostics),
/// `driver` and `summary`. Nothing in it depends on timing, so repeated runs are identical.
pub fn json(report: &Report) -> String {
    let shown = displayed(report);
    let diagnostics = shown
        .iter()
        .map(|d| JsonDiagnostic {
            severity: if d.is_error() { "error" } else { "warning" },
            code: d.code.name(),
            message: &d.message,
            file: d.location.as_ref().map(|l| l.path.as_str()),
            line: d.location.as_ref().map(|l| l.line),
            column: d.location.as_ref().and_then(|l| l.columns.as_ref()).map(|c| c.start + 1),
            notes: &d.notes,
            refused_by: d.refused_by.names(),
        })
        .collect();
    let programs = report
        .programs
        .iter()
        .map(|p| {
            let (status, reason) = match &p.status {
                Status::Valid => ("valid", None),
                Status::Invalid => ("invalid", None),
                Status::Skipped(why) => ("skipped", Some(why.as_str())),
            };
            JsonProgram {
                program: &p.id,
                status,
                stages: &p.stages,
                reason,
                only_preprocessed: &p.only_preprocessed,
                diagnostics: &p.diagnostics,
            }
        })
        .collect();
    let driver = report.driver.as_ref().map(|d| JsonDriver {
        driver: &d.driver,
        both_accept: d.both_accept,
        both_reject: d.both_reject,
        only_driver_rejects: &d.only_driver_rejects,
        only_tidepack_rejects: &d.only_tidepack_rejects,
        not_compared: &d.not_compared,
    });
    let summary = JsonSummary {
        pack: &report.pack.display_root,
        option_sets: &report.option_sets,
        covered: report.plan.covered.map(|c| c.describe()),
        program_texts_considered: report.plan.considered,
        program_texts_identical: report.plan.identical,
        program_texts_in_other_shards: (report.plan.other_shards > 0).then_some(report.plan.other_shards),
        stages_validated: report.stages_validated,
        errors: report.errors(),
        warnings: report.warnings(),
        allowed: report.allowed.iter().map(|(code, n)| (code.name(), *n)).collect(),
    };
    let mut out = serde_json::to_string_pretty(&JsonReport { diagnostics, programs, driver, summary })
        .expect("the report serialises: it holds only strings and numbers");
    out.push('\n');
    out
}

/// An input that cannot be read at all, as the chosen format says it.
pub fn input_error_json(diag: &Diagnostic) -> String {
    serde_json::json!({ "input_error": diag.message }).to_string() + "\n"
}

/// [`input_error_json`] as a GitHub Actions annotation.
pub fn input_error_github(diag: &Diagnostic) -> String {
    format!("::error title=tidepack validate::{}\n", github_escape(&diag.message, false))
}

/// GitHub Actions escapes for a message and for a property value.
fn github_escape(s: &str, property: bool) -> String {
    let mut out = s.replace('%', "%25").replace('\r', "%0D").replace('\n', "%0A");
    if property {
        out = out.replace(':', "%3A").replace(',', "%2C");
    }
    out
}

/// GitHub shows at most ten warning annotations of a step (and ten errors); more are dropped
/// unseen.
pub const MAX_WARNING_ANNOTATIONS: usize = 10;

/// `::error file=…,line=…::message` lines: every error, then up to
/// [`MAX_WARNING_ANNOTATIONS`] warnings, each taken a code at a time (so the ten GitHub shows
/// cover as many codes as they can), then a notice counting the warnings left to the job summary
/// ([`markdown`]). GitHub attaches an annotation to a file of the repository by its path from
/// the repository root, where workflows run: a pack folder's files are named from the working
/// directory. Files inside a zip are in no repository, so their annotations name the zip and
/// the entry in the message.
pub fn github(report: &Report) -> String {
    let cwd = std::env::current_dir().ok();
    let mut out = String::new();
    let errors = a_code_at_a_time(report.diagnostics.iter().filter(|d| d.is_error()));
    let mut warnings = a_code_at_a_time(report.diagnostics.iter().filter(|d| !d.is_error()));
    warnings.truncate(MAX_WARNING_ANNOTATIONS);
    for d in errors.iter().chain(&warnings) {
        let command = match d.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        let mut props = vec![format!("title=tidepack validate [{}]", d.code)];
        let mut message = String::new();
        if let Some(loc) = &d.location {
            let shown = shown_path(report, &loc.path);
            if report.pack.archive {
                message = format!("{shown}:{}: ", loc.line);
            } else {
                let path = std::path::Path::new(&shown);
                let canonical = std::fs::canonicalize(path).ok();
                let relative = match (cwd.as_deref(), canonical.as_deref()) {
                    (Some(cwd), Some(canonical)) => canonical.strip_prefix(cwd).unwrap_or(path),
                    _ => path,
                };
                let relative = relative.to_string_lossy();
                let relative = relative.strip_prefix("./").unwrap_or(&relative);
                props.push(format!("file={}", github_escape(relative, true)));
                props.push(format!("line={}", loc.line));
                if let Some(c) = &loc.columns {
                    props.push(format!("col={}", c.start + 1));
                }
            }
        }
        message.push_str(&d.message);
        for note in &d.notes {
            message.push('\n');
            message.push_str(note);
        }
        writeln!(out, "::{command} {}::{}", props.join(","), github_escape(&message, false)).unwrap();
    }
    let left = report.warnings() - warnings.len();
    if left > 0 {
        let notice = format!("{left} more warnings are not annotated; the job summary (--summary) lists every diagnostic, grouped by code");
        writeln!(out, "::notice title=tidepack validate::{}", github_escape(&notice, false)).unwrap();
    }
    out
}

/// `diagnostics` reordered to take one of each code in turn, so that the first few of them
/// (all that GitHub shows) cover as many codes as they can.
fn a_code_at_a_time<'a>(diagnostics: impl Iterator<Item = &'a Diagnostic>) -> Vec<&'a Diagnostic> {
    let mut by_code: BTreeMap<Code, VecDeque<&Diagnostic>> = BTreeMap::new();
    for d in diagnostics {
        by_code.entry(d.code).or_default().push_back(d);
    }
    let mut ordered = Vec::new();
    while by_code.values().any(|q| !q.is_empty()) {
        ordered.extend(by_code.values_mut().filter_map(VecDeque::pop_front));
    }
    ordered
}

/// The report as Markdown for a CI job summary (GitHub's `$GITHUB_STEP_SUMMARY`): the verdict
/// and totals, a table of the codes found, and every diagnostic under its code. Text from the
/// pack goes in code spans, so nothing in it is read as Markdown or HTML.
pub fn markdown(report: &Report) -> String {
    let mut out = String::new();
    let verdict = if report.errors() > 0 { "fails" } else { "passes" };
    writeln!(out, "### tidepack validate {}: {verdict}\n", code_span(&report.pack.display_root)).unwrap();
    let allowed = if report.allowed.is_empty() {
        String::new()
    } else {
        let counts: Vec<String> = report.allowed.iter().map(|(code, n)| format!("`{code}` {n}")).collect();
        format!("; allowed, not shown: {}", counts.join(", "))
    };
    writeln!(
        out,
        "{}, {} distinct stages validated: **{}**{allowed}\n",
        plural(report.option_sets.len(), "option set"),
        report.stages_validated,
        counted_each(report.errors(), report.warnings()),
    )
    .unwrap();
    let by_code = report.counts_by_code();
    if by_code.is_empty() {
        return out;
    }
    out.push_str("| code | errors | warnings | what it is |\n|---|--:|--:|---|\n");
    for (code, errors, warnings) in &by_code {
        writeln!(out, "| `{code}` | {errors} | {warnings} | {} |", code.summary().replace('|', "\\|")).unwrap();
    }
    for (code, errors, warnings) in &by_code {
        writeln!(out, "\n<details><summary><code>{code}</code>: {}</summary>\n", counted(*errors, *warnings)).unwrap();
        for d in report.diagnostics.iter().filter(|d| d.code == *code) {
            let kind = if d.is_error() { "error" } else { "warning" };
            let place = d.location.as_ref().map_or(String::new(), |l| format!(" {}", code_span(&format!("{}:{}", shown_path(report, &l.path), l.line))));
            writeln!(out, "- {kind}{place}: {}", code_span(&d.message)).unwrap();
            for note in &d.notes {
                writeln!(out, "  - {}", code_span(note)).unwrap();
            }
        }
        out.push_str("\n</details>\n");
    }
    out
}

/// `text` as a Markdown code span on one line: control characters escaped, and a fence of
/// more backticks than any run in it.
fn code_span(text: &str) -> String {
    let line = terminal::line(text);
    let longest = line.split(|c| c != '`').map(str::len).max().unwrap_or(0);
    let fence = "`".repeat(longest + 1);
    format!("{fence} {line} {fence}")
}
