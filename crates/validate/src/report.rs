//! What `tidepack validate` found: per program, and every diagnostic once.

use std::collections::BTreeMap;
use std::time::Duration;

use tidepack_glsl::{Code, Diagnostic};

use crate::driver;
use tidepack_loader::input::PackFiles;

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Status {
    Valid,
    Invalid,
    /// Run by another loader (or none): recognised, not validated.
    Skipped(String),
}

#[derive(Clone, Debug)]
pub struct ProgramReport {
    pub id: String,
    pub stages: Vec<String>,
    pub status: Status,
    /// Some error a compiler or linker would also give (not only the loader's directives).
    pub compile_error: bool,
    /// Stage files that were only preprocessed, never compiled (geometry and tessellation
    /// without `--driver`, or stages the driver cannot compile): `Valid` does not cover them.
    pub only_preprocessed: Vec<String>,
    /// Indices into [`Report::diagnostics`] of what was found in this program.
    pub diagnostics: Vec<usize>,
}

#[derive(Debug)]
pub struct Report {
    pub pack: PackFiles,
    pub programs: Vec<ProgramReport>,
    /// Errors and warnings, deduplicated, located in the pack's files (paths relative to
    /// `shaders/`; [`PackFiles::display_root`] says where that is).
    pub diagnostics: Vec<Diagnostic>,
    /// Labels of the option sets validated (`defaults`, `profile LOW`).
    pub option_sets: Vec<String>,
    /// How the (program, option set) pairs were chosen.
    pub plan: crate::PlanSummary,
    /// Distinct lowered stages naga validated.
    pub stages_validated: usize,
    pub elapsed: Duration,
    /// With [`Options::driver`](crate::Options::driver): how the driver's verdicts compare with tidepack's.
    pub driver: Option<driver::DriverSummary>,
    /// Warnings left out by [`Options::levels`](crate::Options::levels): distinct diagnostics
    /// by code, counted as the report counts what it shows.
    pub allowed: BTreeMap<Code, usize>,
}

impl Report {
    pub fn errors(&self) -> usize {
        self.diagnostics.iter().filter(|d| d.is_error()).count()
    }

    pub fn warnings(&self) -> usize {
        self.diagnostics.len() - self.errors()
    }

    /// How many diagnostics of each code the report holds, errors and warnings apart:
    /// `(code, errors, warnings)`, most frequent first.
    pub fn counts_by_code(&self) -> Vec<(Code, usize, usize)> {
        let mut counts: BTreeMap<Code, (usize, usize)> = BTreeMap::new();
        for d in &self.diagnostics {
            let entry = counts.entry(d.code).or_default();
            if d.is_error() { entry.0 += 1 } else { entry.1 += 1 }
        }
        let mut counts: Vec<(Code, usize, usize)> = counts.into_iter().map(|(c, (e, w))| (c, e, w)).collect();
        counts.sort_by_key(|(c, e, w)| (std::cmp::Reverse((*e, *w)), *c));
        counts
    }

    /// Text of a pack file, for snippets.
    pub fn source_of(&self, path: &str) -> Option<String> {
        self.pack.texts.get(path).map(|t| t.to_string())
    }
}
