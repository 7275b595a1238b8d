//! Which warnings a pack's check silences and which fail it, by diagnostic code: `--allow` and
//! `--deny` on the command line over the `[validate]` table of a `tidepack.toml` in the pack's
//! repository. Errors cannot be allowed: an error is what a target driver refuses, and
//! `--target` is what narrows the drivers.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use serde::Deserialize;
use tidepack_glsl::{Code, Diagnostic, Location, Severity};

/// The configuration file a pack repository keeps beside its `shaders/` (or at its root).
pub const CONFIG_FILE: &str = "tidepack.toml";

#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Levels {
    /// Warnings of these codes are left out of the report (and counted).
    pub allow: BTreeSet<Code>,
    /// Warnings of these codes are errors.
    pub deny: BTreeSet<Code>,
}

/// The warnings the levels left out, each distinct diagnostic once however many programs and
/// option sets it was seen in, so that "allowed" counts what the report would have shown.
#[derive(Debug, Default)]
pub struct Silenced(BTreeMap<Code, BTreeSet<String>>);

impl Silenced {
    /// How many distinct diagnostics of each code were left out.
    pub fn counts(&self) -> BTreeMap<Code, usize> {
        self.0.iter().map(|(code, seen)| (*code, seen.len())).collect()
    }
}

impl Levels {
    /// Adds the command line's `--allow` and `--deny` codes over these (read from a file): a
    /// code the command line names leaves the other list. A code named in both is an error.
    pub fn with_command_line(mut self, allow: &[Code], deny: &[Code]) -> Result<Levels, String> {
        if let Some(both) = allow.iter().find(|c| deny.contains(c)) {
            return Err(format!("--allow {both} and --deny {both} contradict each other"));
        }
        for code in allow {
            self.deny.remove(code);
            self.allow.insert(*code);
        }
        for code in deny {
            self.allow.remove(code);
            self.deny.insert(*code);
        }
        Ok(self)
    }

    /// The diagnostic as the levels leave it: a denied warning becomes an error saying why; an
    /// allowed one is recorded in `silenced` and dropped. Errors pass unchanged.
    pub fn apply(&self, mut diag: Diagnostic, silenced: &mut Silenced) -> Option<Diagnostic> {
        if diag.severity != Severity::Warning {
            return Some(diag);
        }
        if self.allow.contains(&diag.code) {
            silenced.0.entry(diag.code).or_default().insert(diag.to_string());
            return None;
        }
        if self.deny.contains(&diag.code) {
            diag.severity = Severity::Error;
            diag.notes.push(format!("a warning that fails the check: `{}` is denied", diag.code));
        }
        Some(diag)
    }

    /// The `[validate]` table of a `tidepack.toml`: `allow` and `deny`, lists of codes. Every
    /// mistake in it is an error naming the file and line.
    pub fn parse(path: &str, text: &str) -> Result<Levels, Diagnostic> {
        #[derive(Deserialize)]
        #[serde(deny_unknown_fields)]
        struct File {
            #[serde(default)]
            validate: Table,
        }
        #[derive(Deserialize, Default)]
        #[serde(deny_unknown_fields)]
        struct Table {
            #[serde(default)]
            allow: Vec<toml::Spanned<String>>,
            #[serde(default)]
            deny: Vec<toml::Spanned<String>>,
        }
        let line_of = |offset: usize| 1 + text[..offset.min(text.len())].bytes().filter(|b| *b == b'\n').count() as u32;
        let at = |offset: usize| Some(Location::line(path, line_of(offset)));
        let file: File = toml::from_str(text).map_err(|e| {
            let line = e.span().map_or(1, |s| line_of(s.start));
            Diagnostic::error(Code::Usage, e.message().trim().to_string(), Some(Location::line(path, line)))
        })?;
        let read = |names: &[toml::Spanned<String>]| -> Result<BTreeSet<Code>, Diagnostic> {
            names.iter().map(|n| Code::parse(n.get_ref()).map_err(|m| Diagnostic::error(Code::Usage, m, at(n.span().start)))).collect()
        };
        let levels = Levels { allow: read(&file.validate.allow)?, deny: read(&file.validate.deny)? };
        if let Some(both) = levels.allow.intersection(&levels.deny).next() {
            let span = file.validate.deny.iter().find(|n| n.get_ref() == both.name()).map_or(0, |n| n.span().start);
            return Err(Diagnostic::error(Code::Usage, format!("`{both}` is both allowed and denied"), at(span)));
        }
        Ok(levels)
    }

    /// The levels a check of the pack at `pack` runs with: those of `config`, or else of a
    /// tidepack.toml beside the pack (in its folder) or in the current folder, with the command
    /// line's `allow` and `deny` over them.
    pub fn for_pack(pack: &Path, config: Option<&Path>, allow: &[Code], deny: &[Code]) -> Result<Levels, Diagnostic> {
        let from_file = match config {
            Some(path) => Levels::read(path)?,
            None => {
                let beside = if pack.is_dir() { Some(pack) } else { pack.parent() };
                let folders: Vec<&Path> = beside.into_iter().chain([Path::new(".")]).collect();
                Levels::find(&folders)?.0
            }
        };
        from_file.with_command_line(allow, deny).map_err(|m| Diagnostic::error(Code::Usage, m, None))
    }

    /// The levels of the first `tidepack.toml` among `folders`, with its path; none (and no
    /// path) when no folder has one.
    pub fn find(folders: &[&Path]) -> Result<(Levels, Option<std::path::PathBuf>), Diagnostic> {
        for folder in folders {
            let path = folder.join(CONFIG_FILE);
            if path.is_file() {
                return Ok((Levels::read(&path)?, Some(path)));
            }
        }
        Ok((Levels::default(), None))
    }

    /// The levels of the configuration file at `path`.
    pub fn read(path: &Path) -> Result<Levels, Diagnostic> {
        let shown = path.display().to_string();
        let unreadable = |why: String| Diagnostic::error(Code::Usage, format!("cannot read the configuration {shown}: {why}"), None);
        let meta = std::fs::metadata(path).map_err(|e| unreadable(e.to_string()))?;
        if !meta.is_file() {
            return Err(unreadable("not a file".into()));
        }
        if meta.len() > 1 << 20 {
            return Err(unreadable("over 1 MiB, so not a configuration file".into()));
        }
        let bytes = std::fs::read(path).map_err(|e| unreadable(e.to_string()))?;
        let text = String::from_utf8(bytes).map_err(|e| {
            let line = line_at(e.as_bytes(), e.utf8_error().valid_up_to());
            Diagnostic::error(Code::Usage, "not valid UTF-8", Some(Location::line(shown.clone(), line)))
        })?;
        Levels::parse(&shown, &text)
    }
}

fn line_at(bytes: &[u8], offset: usize) -> u32 {
    1 + bytes[..offset].iter().filter(|b| **b == b'\n').count() as u32
}

#[cfg(test)]
mod tests {
    use super::*;

    fn warning(code: Code) -> Diagnostic {
        Diagnostic::warning(code, "w", None)
    }

    #[test]
    fn allowed_warnings_are_counted_once_each_and_denied_ones_become_errors() {
        let levels = Levels::default().with_command_line(&[Code::UnknownUniform], &[Code::UndefinedInIf]).unwrap();
        let mut silenced = Silenced::default();
        let other = Diagnostic::warning(Code::UnknownUniform, "another", None);
        let found = [warning(Code::UnknownUniform), warning(Code::UnknownUniform), other, warning(Code::UndefinedInIf), warning(Code::Properties)];
        let kept: Vec<Diagnostic> = found.into_iter().filter_map(|d| levels.apply(d, &mut silenced)).collect();
        // The same warning seen twice (in two programs, say) is one diagnostic of the report.
        assert_eq!(silenced.counts(), BTreeMap::from([(Code::UnknownUniform, 2)]));
        assert_eq!(kept.iter().map(|d| (d.code, d.severity)).collect::<Vec<_>>(), [
            (Code::UndefinedInIf, Severity::Error),
            (Code::Properties, Severity::Warning)
        ]);
        assert!(kept[0].notes.iter().any(|n| n.contains("`undefined-in-if` is denied")));
    }

    #[test]
    fn errors_are_never_allowed() {
        let levels = Levels::default().with_command_line(&[Code::Glsl], &[]).unwrap();
        let kept = levels.apply(Diagnostic::error(Code::Glsl, "e", None), &mut Silenced::default());
        assert!(kept.is_some_and(|d| d.is_error()));
    }

    #[test]
    fn the_command_line_wins_over_the_file_and_contradicts_only_itself() {
        let file = Levels::parse("tidepack.toml", "[validate]\ndeny = [\"unknown-uniform\"]\n").unwrap();
        let levels = file.with_command_line(&[Code::UnknownUniform], &[]).unwrap();
        assert!(levels.allow.contains(&Code::UnknownUniform) && levels.deny.is_empty());
        let err = Levels::default().with_command_line(&[Code::Link], &[Code::Link]).unwrap_err();
        assert!(err.contains("--allow link and --deny link"), "{err}");
    }

    #[test]
    fn mistakes_in_the_file_name_its_line() {
        let err = Levels::parse("tidepack.toml", "[validate]\nallow = [\n  \"unknown-uniform\",\n  \"unknown-uniforms\",\n]\n").unwrap_err();
        assert_eq!(err.location, Some(Location::line("tidepack.toml", 4)));
        assert!(err.message.contains("did you mean unknown-uniform"), "{}", err.message);
        let err = Levels::parse("tidepack.toml", "[validate]\nallow = []\nsilence = [\"x\"]\n").unwrap_err();
        assert_eq!(err.location, Some(Location::line("tidepack.toml", 3)));
        assert!(err.message.contains("silence"), "{}", err.message);
        let err = Levels::parse("tidepack.toml", "[validate]\nallow = [\"link\"]\ndeny = [\"link\"]\n").unwrap_err();
        assert_eq!(err.location, Some(Location::line("tidepack.toml", 3)));
        let err = Levels::parse("tidepack.toml", "[validate\n").unwrap_err();
        assert_eq!(err.location.map(|l| l.line), Some(1));
    }

    #[test]
    fn the_first_folder_with_a_file_gives_the_levels() {
        let dir = tempfile::tempdir().unwrap();
        let (none, path) = Levels::find(&[dir.path()]).unwrap();
        assert!(none == Levels::default() && path.is_none());
        std::fs::write(dir.path().join(CONFIG_FILE), "[validate]\nallow = [\"properties\"]\n").unwrap();
        let (levels, path) = Levels::find(&[Path::new("/nonexistent"), dir.path()]).unwrap();
        assert!(levels.allow.contains(&Code::Properties) && path.is_some());
        std::fs::write(dir.path().join(CONFIG_FILE), b"[validate]\nallow = [\"\xff\"]\n").unwrap();
        let err = Levels::find(&[dir.path()]).unwrap_err();
        assert!(err.message.contains("UTF-8") && err.location.map(|l| l.line) == Some(2));
    }
}
