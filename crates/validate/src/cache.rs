//! `--cache DIR`: what a (program, option set) pair gave, kept across runs under a key of
//! everything the verdict depends on, so that CI validates only what changed.
//!
//! The key digests tidepack's build (version, and its executable's size and time), the loader, `--driver`, the program's
//! [`Fingerprint`](crate::configurations::Fingerprint) (its expanded text, so the standard
//! macros too) and the option set; one JSON file per key. A file that cannot be read or parsed is a miss, and
//! writes go through a temporary file renamed into place, so that parallel CI jobs sharing the
//! folder never see half a file.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

use tidepack_glsl::{Code, Diagnostic, Drivers, Location, Severity};
use tidepack_loader::Loader;
use tidepack_loader::option_lines::OptionSet;

use crate::configurations::Fingerprint;

/// Cache entries are named by this digest in hex.
pub(crate) type Key = [u8; 32];

/// Which build of tidepack runs: its version, and the size and time of its executable, so that
/// a rebuilt tidepack does not read what another build found.
fn build_identity() -> String {
    let executable = std::env::current_exe().and_then(std::fs::metadata).ok();
    let stamp = executable.map(|m| {
        let modified = m.modified().ok().and_then(|t| t.duration_since(std::time::UNIX_EPOCH).ok()).map_or(0, |d| d.as_nanos());
        format!("{} {modified}", m.len())
    });
    format!("tidepack-validate {} {}", env!("CARGO_PKG_VERSION"), stamp.unwrap_or_default())
}

/// The key of a pair's findings under `loader`, with or without `--driver` (which changes
/// what is said of stages naga cannot read).
pub(crate) fn key(loader: Loader, driver: bool, fingerprint: &Fingerprint, set: &OptionSet) -> Key {
    static BUILD: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    let mut hasher = Sha256::new();
    hasher.update(BUILD.get_or_init(build_identity).as_bytes());
    hasher.update([0]);
    hasher.update(format!("{loader}\0{driver}").as_bytes());
    hasher.update(fingerprint);
    for (name, value) in set {
        hasher.update(format!("\0{name}={value}").as_bytes());
    }
    hasher.finalize().into()
}

#[derive(Serialize, Deserialize)]
struct Entry {
    diagnostics: Vec<StoredDiagnostic>,
}

#[derive(Serialize, Deserialize)]
struct StoredDiagnostic {
    error: bool,
    /// Its [`Code`] by name; an entry whose code this version does not know is not reused.
    code: String,
    message: String,
    path: Option<String>,
    line: u32,
    columns: Option<(usize, usize)>,
    notes: Vec<String>,
    refused_by: Vec<String>,
}

impl From<&Diagnostic> for StoredDiagnostic {
    fn from(d: &Diagnostic) -> Self {
        StoredDiagnostic {
            error: d.is_error(),
            code: d.code.name().to_string(),
            message: d.message.clone(),
            path: d.location.as_ref().map(|l| l.path.clone()),
            line: d.location.as_ref().map_or(0, |l| l.line),
            columns: d.location.as_ref().and_then(|l| l.columns.as_ref().map(|c| (c.start, c.end))),
            notes: d.notes.clone(),
            refused_by: d.refused_by.names().into_iter().map(String::from).collect(),
        }
    }
}

impl TryFrom<StoredDiagnostic> for Diagnostic {
    type Error = String;

    fn try_from(d: StoredDiagnostic) -> Result<Self, String> {
        Ok(Diagnostic {
            severity: if d.error { Severity::Error } else { Severity::Warning },
            code: Code::parse(&d.code)?,
            message: d.message,
            location: d.path.map(|path| Location { path, line: d.line, columns: d.columns.map(|(start, end)| start..end) }),
            notes: d.notes,
            refused_by: Drivers::parse(&d.refused_by.join(",")).unwrap_or(Drivers::NONE),
        })
    }
}

/// A folder of cache entries.
pub(crate) struct Cache {
    dir: PathBuf,
}

impl Cache {
    /// Opens (creating if need be) the folder; an error names it.
    pub fn open(dir: &Path) -> Result<Cache, Diagnostic> {
        std::fs::create_dir_all(dir)
            .map_err(|e| Diagnostic::error(Code::Usage, format!("--cache {}: cannot create the folder: {e}", dir.display()), None))?;
        Ok(Cache { dir: dir.to_path_buf() })
    }

    fn path(&self, key: &Key) -> PathBuf {
        let hex: String = key.iter().map(|b| format!("{b:02x}")).collect();
        self.dir.join(format!("{hex}.json"))
    }

    /// The diagnostics stored under `key`, if any.
    pub fn get(&self, key: &Key) -> Option<Vec<Diagnostic>> {
        let text = std::fs::read_to_string(self.path(key)).ok()?;
        let entry: Entry = serde_json::from_str(&text).ok()?;
        entry.diagnostics.into_iter().map(Diagnostic::try_from).collect::<Result<_, _>>().ok()
    }

    /// Stores `diagnostics` under `key`. A failure to write only loses the entry.
    pub fn put(&self, key: &Key, diagnostics: &[Diagnostic]) {
        let entry = Entry { diagnostics: diagnostics.iter().map(StoredDiagnostic::from).collect() };
        let Ok(text) = serde_json::to_string(&entry) else { return };
        let path = self.path(key);
        let temporary = path.with_extension(format!("{}.tmp", std::process::id()));
        if std::fs::write(&temporary, text).is_ok() && std::fs::rename(&temporary, &path).is_err() {
            let _ = std::fs::remove_file(&temporary);
        }
    }
}
