//! Compiler-style diagnostics that point at a file and line of the pack's sources.

use std::fmt;
use std::ops::Range;

use codespan_reporting::diagnostic::{Diagnostic as CsDiagnostic, Label};
use codespan_reporting::files::SimpleFiles;
use codespan_reporting::term::{self, termcolor::WriteColor};

use crate::terminal;
use crate::code::Code;

#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Severity {
    Warning,
    Error,
}

/// A place in a source file: a pack-relative path and a 1-based line, optionally narrowed to
/// a byte range within that line.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Location {
    pub path: String,
    pub line: u32,
    pub columns: Option<Range<usize>>,
}

impl Location {
    pub fn line(path: impl Into<String>, line: u32) -> Self {
        Location { path: path.into(), line, columns: None }
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.columns {
            Some(cols) => write!(f, "{}:{}:{}", self.path, self.line, cols.start + 1),
            None => write!(f, "{}:{}", self.path, self.line),
        }
    }
}

/// Families of OpenGL drivers, told apart by what their GLSL compilers accept: Mesa (Linux's
/// open drivers), AMD's (as strict as glslang's front end), Intel's, NVIDIA's (which accepts
/// much that the specification forbids) and macOS's (OpenGL 4.1 core at most).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Drivers(u8);

impl Drivers {
    pub const NONE: Drivers = Drivers(0);
    pub const MESA: Drivers = Drivers(1);
    pub const AMD: Drivers = Drivers(2);
    pub const INTEL: Drivers = Drivers(4);
    pub const NVIDIA: Drivers = Drivers(8);
    pub const MACOS: Drivers = Drivers(16);
    pub const ALL: Drivers = Drivers(31);
    /// Every family but NVIDIA's: what the specification forbids and NVIDIA's compiler lets by.
    pub const ALL_BUT_NVIDIA: Drivers = Drivers(31 & !8);
    const NAMES: [(Drivers, &'static str); 5] =
        [(Drivers::MESA, "mesa"), (Drivers::AMD, "amd"), (Drivers::INTEL, "intel"), (Drivers::NVIDIA, "nvidia"), (Drivers::MACOS, "macos")];

    pub const fn union(self, other: Drivers) -> Drivers {
        Drivers(self.0 | other.0)
    }

    pub const fn intersection(self, other: Drivers) -> Drivers {
        Drivers(self.0 & other.0)
    }

    pub const fn without(self, other: Drivers) -> Drivers {
        Drivers(self.0 & !other.0)
    }

    pub const fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// The lower-case names (`mesa`, `amd`, `intel`, `nvidia`, `macos`), in that order.
    pub fn names(self) -> Vec<&'static str> {
        Drivers::NAMES.iter().filter(|(d, _)| self.intersection(*d) == *d).map(|(_, n)| *n).collect()
    }

    /// Reads a comma-separated list of names, or `all`.
    pub fn parse(text: &str) -> Result<Drivers, String> {
        let mut found = Drivers::NONE;
        for word in text.split(',').map(str::trim).filter(|w| !w.is_empty()) {
            if word == "all" {
                found = Drivers::ALL;
                continue;
            }
            let Some((d, _)) = Drivers::NAMES.iter().find(|(_, n)| *n == word) else {
                return Err(format!("unknown driver `{}`: mesa, amd, intel, nvidia, macos or all", word.escape_debug()));
            };
            found = found.union(*d);
        }
        if found.is_empty() {
            return Err("name at least one driver: mesa, amd, intel, nvidia, macos or all".into());
        }
        Ok(found)
    }
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
    pub severity: Severity,
    /// What it is about: the name `--allow` and `--deny` take.
    pub code: Code,
    pub message: String,
    pub location: Option<Location>,
    /// Further context, each printed as a `= note:` line.
    pub notes: Vec<String>,
    /// The drivers whose compilers refuse what this says: every family for an error unless a
    /// rule knows better, none for a warning.
    pub refused_by: Drivers,
}

/// Longest message or note a diagnostic keeps: one quoting a pack's text (a token of a
/// minified line, a value) is cut there, so no output (terminal, JSON, annotations) repeats
/// megabytes of it.
pub const MAX_MESSAGE_BYTES: usize = 1000;

/// The largest character boundary of `text` at or below `index` (which is at most its length).
fn floor_char_boundary(text: &str, mut index: usize) -> usize {
    while !text.is_char_boundary(index) {
        index -= 1;
    }
    index
}

/// `text` cut to [`MAX_MESSAGE_BYTES`] at a character boundary, saying how much was left out.
fn clipped(text: String) -> String {
    if text.len() <= MAX_MESSAGE_BYTES {
        return text;
    }
    let end = floor_char_boundary(&text, MAX_MESSAGE_BYTES);
    format!("{}… ({} more bytes)", &text[..end], text.len() - end)
}

impl Diagnostic {
    pub fn error(code: Code, message: impl Into<String>, location: Option<Location>) -> Self {
        Diagnostic { severity: Severity::Error, code, message: clipped(message.into()), location, notes: Vec::new(), refused_by: Drivers::ALL }
    }

    pub fn warning(code: Code, message: impl Into<String>, location: Option<Location>) -> Self {
        Diagnostic { severity: Severity::Warning, code, message: clipped(message.into()), location, notes: Vec::new(), refused_by: Drivers::NONE }
    }

    /// The same diagnostic, said to be refused by `drivers` only.
    pub fn refused_by(mut self, drivers: Drivers) -> Self {
        self.refused_by = drivers;
        self
    }

    pub fn with_note(mut self, note: impl Into<String>) -> Self {
        self.notes.push(clipped(note.into()));
        self
    }

    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let kind = match self.severity {
            Severity::Warning => "warning",
            Severity::Error => "error",
        };
        if let Some(loc) = &self.location {
            write!(f, "{loc}: ")?;
        }
        write!(f, "{kind}[{}]: {}", self.code, self.message)?;
        for note in &self.notes {
            write!(f, "\n  = note: {note}")?;
        }
        Ok(())
    }
}

impl std::error::Error for Diagnostic {}

/// Prints diagnostics the way rustc and naga do, with a snippet of the source line.
/// `source_of` returns the text of a path named by a location (`None` prints no snippet).
pub fn emit(
    writer: &mut dyn WriteColor,
    diagnostics: &[Diagnostic],
    source_of: &dyn Fn(&str) -> Option<String>,
) -> std::io::Result<()> {
    let mut files = SimpleFiles::new();
    let mut ids = std::collections::HashMap::new();
    let config = term::Config::default();
    for diag in diagnostics {
        let severity = match diag.severity {
            Severity::Warning => codespan_reporting::diagnostic::Severity::Warning,
            Severity::Error => codespan_reporting::diagnostic::Severity::Error,
        };
        let mut out = CsDiagnostic::new(severity)
            .with_code(diag.code.name())
            .with_message(terminal::block(&diag.message))
            .with_notes(diag.notes.iter().map(|n| terminal::block(n)).collect());
        if let Some(loc) = &diag.location {
            let shown_path = terminal::line(&loc.path);
            let id = *ids
                .entry(loc.path.clone())
                .or_insert_with(|| source_of(&loc.path).map(|text| files.add(shown_path.clone(), terminal::source(&text))));
            match id.and_then(|id| Some((id, span_of(files.get(id).ok()?.source(), loc)?))) {
                Some((id, span)) => {
                    let source = files.get(id).map_or("", |f| f.source().as_str());
                    match long_line_window(source, loc.line, span.clone()) {
                        Some((window, span, note)) => {
                            let id = files.add(shown_path, window);
                            out = out.with_labels(vec![Label::primary(id, span)]);
                            out.notes.push(note);
                        }
                        None => out = out.with_labels(vec![Label::primary(id, span)]),
                    }
                }
                None => out.message = format!("{}: {}", Location { path: shown_path, ..loc.clone() }, out.message),
            }
        }
        term::emit_to_write_style(writer, &config, &files, &out).map_err(std::io::Error::other)?;
    }
    Ok(())
}

/// Longest line a snippet shows whole; a longer one is cut to a window around the span.
const MAX_SNIPPET_LINE_BYTES: usize = 200;

/// For a span on a line longer than [`MAX_SNIPPET_LINE_BYTES`] (a minified include, a line of
/// bad bytes): a stand-in source holding only a window of that line at the same line number,
/// the span within it, and a note saying which bytes are shown.
fn long_line_window(text: &str, line: u32, span: Range<usize>) -> Option<(String, Range<usize>, String)> {
    let start = line_start(text, line)?;
    let end = text[start..].find('\n').map_or(text.len(), |i| start + i);
    if end - start <= MAX_SNIPPET_LINE_BYTES {
        return None;
    }
    let from = floor_char_boundary(text, span.start.saturating_sub(MAX_SNIPPET_LINE_BYTES / 4).max(start));
    let to = floor_char_boundary(text, (from + MAX_SNIPPET_LINE_BYTES).min(end));
    let mut window = "\n".repeat(line as usize - 1);
    let offset = window.len();
    window.push_str(&text[from..to]);
    let span = offset + span.start.clamp(from, to) - from..offset + span.end.clamp(from, to) - from;
    let note = format!("line {line} is {} bytes long: the snippet shows bytes {}..{} of it", end - start, from - start, to - start);
    Some((window, span, note))
}

/// Byte range in `text` of a location: its columns, or the line without leading indentation.
fn span_of(text: &str, loc: &Location) -> Option<Range<usize>> {
    let start = line_start(text, loc.line)?;
    let line = text[start..].split('\n').next().unwrap_or("").trim_end_matches('\r');
    match &loc.columns {
        Some(cols) if cols.end <= line.len() => Some(start + cols.start..start + cols.end),
        _ => {
            let indent = line.len() - line.trim_start().len();
            Some(start + indent..start + line.len())
        }
    }
}

/// Byte offset where 1-based `line` starts, if the text has that many lines.
pub fn line_start(text: &str, line: u32) -> Option<usize> {
    if line == 0 {
        return None;
    }
    if line == 1 {
        return Some(0);
    }
    text.match_indices('\n').nth(line as usize - 2).map(|(i, _)| i + 1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use codespan_reporting::term::termcolor::NoColor;

    #[test]
    fn renders_snippet_with_file_and_line() {
        let diag = Diagnostic::error(Code::Glsl, "unknown identifier `foo`", Some(Location::line("lib/water.glsl", 2)));
        let mut out = NoColor::new(Vec::new());
        emit(&mut out, &[diag], &|_| Some("a;\n  foo = 1;\n".into())).unwrap();
        let text = String::from_utf8(out.into_inner()).unwrap();
        assert!(text.contains("lib/water.glsl:2:3"), "{text}");
        assert!(text.contains("foo = 1;"), "{text}");
    }

    #[test]
    fn a_long_line_is_shown_as_a_window_around_the_span() {
        let line = format!("{}oops{}", "a+".repeat(500_000), "+b".repeat(500_000));
        let text = format!("first\n{line}\n");
        let at = 6 + 1_000_000;
        let diag = Diagnostic::error(Code::Glsl, "unknown identifier `oops`", Some(Location { path: "lib/min.glsl".into(), line: 2, columns: Some(at - 6..at - 2) }));
        let mut out = NoColor::new(Vec::new());
        emit(&mut out, &[diag], &|_| Some(text.clone())).unwrap();
        let shown = String::from_utf8(out.into_inner()).unwrap();
        assert!(shown.len() < 2_000, "{} bytes", shown.len());
        assert!(shown.contains("lib/min.glsl:2:") && shown.contains("oops") && shown.contains("^^^^"), "{shown}");
        assert!(shown.contains("line 2 is 2000004 bytes long"), "{shown}");
    }

    #[test]
    fn nothing_from_a_pack_reaches_the_terminal_raw() {
        // An `#error` text, a file name and a source line, each with escapes and line breaks.
        let diag = Diagnostic::error(Code::Preprocessor, "#error \x1b[2Jgone\r\nerror: forged", Some(Location::line("lib/\x1b]0;title\x07a.glsl", 1)))
            .with_note("note \x1b[31mred");
        let mut out = NoColor::new(Vec::new());
        emit(&mut out, &[diag], &|_| Some("float x = 1.0; // \x1b[1m\u{202E}\n".into())).unwrap();
        let text = String::from_utf8(out.into_inner()).unwrap();
        assert!(!text.contains('\x1b') && !text.contains('\r') && !text.contains('\x07') && !text.contains('\u{202E}'), "{text:?}");
        assert!(text.contains("^[[2Jgone^M") && text.contains("lib/^[]0;title^Ga.glsl"), "{text}");
    }

    #[test]
    fn a_message_quoting_megabytes_is_cut() {
        let diag = Diagnostic::error(Code::Glsl, format!("unexpected `{}`", "é".repeat(1 << 20)), None).with_note("x".repeat(5000));
        assert!(diag.message.len() < MAX_MESSAGE_BYTES + 40 && diag.message.ends_with("more bytes)"), "{}", diag.message.len());
        assert!(diag.notes[0].len() < MAX_MESSAGE_BYTES + 40);
    }

    #[test]
    fn line_start_finds_each_line() {
        let text = "a\nbc\n\nd";
        assert_eq!([1, 2, 3, 4].map(|l| line_start(text, l)), [Some(0), Some(2), Some(5), Some(6)]);
        assert_eq!(line_start(text, 5), None);
    }
}
