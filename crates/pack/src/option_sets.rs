//! Validation of every program under the option sets that change its text: the covering sets
//! of [`tidepack_loader::coverage`], each preprocessed and lowered; identical lowered texts are
//! validated by naga once.

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use rayon::prelude::*;

use tidepack_glsl::{Diagnostic, Stage};
use tidepack_loader::coverage::{self, Consulted, CoveringSets, Representatives};
pub use tidepack_loader::coverage::{Coverage, SetsCovered};
use tidepack_loader::loader::Loader;
use tidepack_loader::macros::StandardMacros;
use tidepack_loader::programs;
use tidepack_loader::option_lines::{OptionKind, OptionSet};
use tidepack_glsl::preprocess::{self, PreprocessOptions, Preprocessed, resolve_include};
use tidepack_glsl::naga_check::{self, LoweredStage};

use crate::pack_options::PackOptions;
use crate::shipped::{Program, ShippedPack, WithOptions};

#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ValidationReport {
    pub programs: usize,
    /// Option sets over all programs.
    pub option_sets: usize,
    /// Stages naga parsed and validated.
    pub stages_validated: usize,
    /// Stages skipped because an identical lowered text was validated already.
    pub stages_identical: usize,
    /// The weakest coverage over the programs (see the module docs).
    pub covered: Option<SetsCovered>,
    /// The stages naga validated: shipped path and the first option set that gave its text.
    pub validated: Vec<(String, OptionSet)>,
    /// Options some program's text depends on (the rest change nothing when a player sets them).
    pub options_read: BTreeSet<String>,
}

/// Where validation is, for a progress display: `done` of `total` items of `phase`.
#[derive(Clone, Copy, Debug)]
pub struct Progress<'a> {
    pub phase: &'a str,
    pub done: usize,
    pub total: usize,
}

/// Receives [`Progress`] at most once a second per phase, and at each phase's end.
pub type ProgressFn<'a> = &'a (dyn Fn(Progress) + Sync);

/// Counts finished items of a phase across worker threads and reports them, rate limited.
struct Ticker<'a> {
    report: Option<ProgressFn<'a>>,
    phase: String,
    total: usize,
    done: AtomicUsize,
    last: Mutex<Instant>,
}

impl<'a> Ticker<'a> {
    fn new(report: Option<ProgressFn<'a>>, phase: String, total: usize) -> Self {
        Ticker { report, phase, total, done: AtomicUsize::new(0), last: Mutex::new(Instant::now()) }
    }

    fn tick(&self) {
        let done = self.done.fetch_add(1, Ordering::Relaxed) + 1;
        let Some(report) = self.report else { return };
        let mut last = self.last.lock().expect("no panics while holding the ticker");
        if done == self.total || last.elapsed() >= Duration::from_secs(1) {
            *last = Instant::now();
            report(Progress { phase: &self.phase, done, total: self.total });
        }
    }
}

/// The loaders the pack is validated for: OptiFine's macros, and Iris's with Distant Horizons
/// beside it, whose `DISTANT_HORIZONS` and `DH_BLOCK_*` open the pack's code for the LODs and
/// which alone runs the `dh_*` programs. Each loader's programs are those it runs.
pub fn loaders() -> [(&'static str, StandardMacros, Loader, bool); 2] {
    let iris = StandardMacros { distant_horizons: true, ..StandardMacros::for_loader(Loader::Iris) };
    [("OptiFine", StandardMacros::default(), Loader::OptiFine1_21, false), ("Iris with Distant Horizons", iris, Loader::Iris, true)]
}

/// Validates every program of `pack` under every loader of [`loaders`]; diagnostics point at
/// shipped files. A stage whose text two loaders share is validated once.
///
/// The default option set of every program goes first: most mistakes show there, and a
/// failing build then stops before enumerating every set.
/// `profiles` are option sets players can pick, always validated. `progress` hears how far
/// the option-set search, the lowering and naga are, for each loader in turn.
pub fn validate_pack(
    pack: &ShippedPack,
    options: &PackOptions,
    coverage: Coverage,
    profiles: &[OptionSet],
    progress: Option<ProgressFn>,
) -> Result<ValidationReport, Vec<Diagnostic>> {
    let mut report = ValidationReport::default();
    let mut names = BTreeSet::new();
    let mut seen = HashMap::new();
    for (label, macros, loader, distant_horizons) in loaders() {
        let programs: Vec<Program> = pack
            .programs()
            .into_iter()
            .filter(|p| programs::runs_with(p.name.rsplit('/').next().unwrap_or(&p.name), loader, distant_horizons))
            .collect();
        names.extend(programs.iter().map(|p| p.name.clone()));
        let macros = macros.preprocess_options();
        let one = validate_for_loader(pack, options, coverage, profiles, progress.map(|p| (p, label)), &macros, &programs, &mut seen)?;
        report.option_sets += one.option_sets;
        report.stages_validated += one.stages_validated;
        report.stages_identical += one.stages_identical;
        report.covered = report.covered.max(one.covered);
        report.validated.extend(one.validated);
        report.options_read.extend(one.options_read);
    }
    report.programs = names.len();
    Ok(report)
}

/// [`validate_pack`] for one loader's `programs` under its `macros`, progress reported with the
/// loader's name; `seen` holds the stages validated already, by shipped path and lowered text.
#[allow(clippy::too_many_arguments)]
fn validate_for_loader(
    pack: &ShippedPack,
    options: &PackOptions,
    coverage: Coverage,
    profiles: &[OptionSet],
    progress: Option<(ProgressFn, &str)>,
    macros: &PreprocessOptions,
    programs: &[Program],
    seen: &mut HashMap<(String, String), ()>,
) -> Result<ValidationReport, Vec<Diagnostic>> {
    let defaults: Vec<(&Program, OptionSet)> = programs.iter().map(|p| (p, OptionSet::new())).collect();
    let (unique, mut errors, _) = lower_sets(pack, &defaults, macros, seen, None);
    errors.extend(validate_in_parallel(pack, programs, &unique, None));
    if !errors.is_empty() {
        return Err(distinct_errors(pack, programs, macros, errors));
    }
    let mut report = ValidationReport { programs: programs.len(), ..Default::default() };
    let mut all_sets = Vec::new();
    let kinds: BTreeMap<String, OptionKind> = options.iter().map(|(name, option)| (name.clone(), option.kind.clone())).collect();
    let (progress, label) = progress.map_or((None, ""), |(p, label)| (Some(p), label));
    let phase = |name: &str| format!("{name} for {label}");
    let searched = Ticker::new(progress, phase("programs' option sets found"), programs.len());
    for program in programs {
        match option_sets(pack, program, &kinds, macros, coverage, profiles) {
            Ok(CoveringSets { sets, covered, read }) => {
                report.covered = report.covered.max(Some(covered));
                report.option_sets += sets.len();
                report.options_read.extend(read);
                all_sets.extend(sets.into_iter().map(|set| (program, set)));
            }
            Err(failed) => {
                let (diag, set) = *failed;
                errors.push((diag, set, program.name.clone()));
            }
        }
        searched.tick();
    }
    let lowered = Ticker::new(progress, phase("option sets lowered"), all_sets.len());
    let (mut unique, lowering_errors, identical) = lower_sets(pack, &all_sets, macros, seen, Some(&lowered));
    errors.extend(lowering_errors);
    report.stages_identical = identical;
    report.stages_validated = unique.len();
    report.validated = unique.iter().map(|(stage, set)| (stage.preprocessed.files[0].clone(), set.clone())).collect();
    let validated = Ticker::new(progress, phase("stages validated by naga"), unique.len());
    errors.extend(validate_in_parallel(pack, programs, &unique, Some(&validated)));
    unique.clear();
    if errors.is_empty() { Ok(report) } else { Err(distinct_errors(pack, programs, macros, errors)) }
}

/// An error, the option set that showed it and the program it was found in.
type Failure = (Diagnostic, OptionSet, String);

/// Preprocesses and lowers each (program, option set); returns the stages whose lowered text
/// is new (with the set that gave it), the errors, and how many stages were identical.
fn lower_sets(
    pack: &ShippedPack,
    sets: &[(&Program, OptionSet)],
    macros: &PreprocessOptions,
    seen: &mut HashMap<(String, String), ()>,
    ticker: Option<&Ticker>,
) -> (Vec<(LoweredStage, OptionSet)>, Vec<Failure>, usize) {
    // Collected in the order of `sets` (rayon keeps an indexed iterator's order), so the
    // diagnostics and the first set that gave a lowered text do not depend on the scheduling.
    let lowered: Vec<_> = sets.par_iter().map(|(program, set)| {
        let stages = run_set(pack, program, set, macros)?;
        let with_stage: Vec<_> = program.stages.iter().map(|(s, _)| *s).zip(stages).collect();
        let result = naga_check::lower_program(&with_stage);
        if let Some(ticker) = ticker {
            ticker.tick();
        }
        result
    }).collect();
    let mut unique = Vec::new();
    let mut errors = Vec::new();
    let mut identical = 0;
    for ((program, set), result) in sets.iter().zip(lowered) {
        match result {
            Ok(stages) => {
                for (stage, (_, path)) in stages.into_iter().zip(&program.stages) {
                    if seen.insert((path.clone(), stage.lowered.text.clone()), ()).is_some() {
                        identical += 1;
                    } else {
                        unique.push((stage, set.clone()));
                    }
                }
            }
            Err(diag) => errors.push((diag, set.clone(), program.name.clone())),
        }
    }
    (unique, errors, identical)
}

/// One diagnostic per distinct error. Notes name the option values the error needs (the
/// failing set reduced to the options whose removal makes the error go away) and, for an
/// error inside an included file, the programs that include it and through which files.
fn distinct_errors(pack: &ShippedPack, programs: &[Program], macros: &PreprocessOptions, errors: Vec<Failure>) -> Vec<Diagnostic> {
    let mut distinct: BTreeMap<String, (Diagnostic, OptionSet, BTreeSet<String>)> = BTreeMap::new();
    for (diag, set, program) in errors {
        let entry = distinct.entry(diag.to_string()).or_insert_with(|| (diag, set, BTreeSet::new()));
        entry.2.insert(program);
    }
    distinct
        .into_iter()
        .map(|(key, (diag, set, in_programs))| {
            let first = programs.iter().find(|p| in_programs.contains(&p.name));
            let needed = match first {
                Some(program) => minimal_set(pack, program, macros, &set, &key),
                None => set,
            };
            let mut diag = diag.with_note(describe_set(&needed));
            let Some(path) = diag.location.as_ref().map(|l| l.path.clone()) else { return diag };
            for program in programs.iter().filter(|p| in_programs.contains(&p.name)) {
                if program.stages.iter().any(|(_, stage)| *stage == path) {
                    continue;
                }
                if let Some(chain) = program.stages.iter().find_map(|(_, stage)| include_chain(pack, stage, &path)) {
                    diag = diag.with_note(format!("included by program {}: {}", program.name, chain.join(" includes ")));
                }
            }
            diag
        })
        .collect()
}

/// `set` without every option that the error `key` does not need: options are dropped one at
/// a time, keeping a drop when `program` still shows the same error without it.
fn minimal_set(pack: &ShippedPack, program: &Program, macros: &PreprocessOptions, set: &OptionSet, key: &str) -> OptionSet {
    let mut needed = set.clone();
    let mut frontend = naga_check::Frontend::default();
    for name in set.keys() {
        let mut trial = needed.clone();
        trial.remove(name);
        if shows_error(pack, program, macros, &trial, key, &mut frontend) {
            needed = trial;
        }
    }
    needed
}

/// Whether `program` under `set` gives the error `key` (preprocessing, lowering or naga).
fn shows_error(
    pack: &ShippedPack,
    program: &Program,
    macros: &PreprocessOptions,
    set: &OptionSet,
    key: &str,
    frontend: &mut naga_check::Frontend,
) -> bool {
    let stages = match run_set(pack, program, set, macros) {
        Ok(stages) => stages,
        Err(diag) => return diag.to_string() == key,
    };
    let with_stage: Vec<_> = program.stages.iter().map(|(s, _)| *s).zip(stages).collect();
    let lowered = match naga_check::lower_program(&with_stage) {
        Ok(lowered) => lowered,
        Err(diag) => return diag.to_string() == key,
    };
    let provider = WithOptions::new(pack, set);
    lowered.iter().any(|stage| {
        naga_check::validate_stage(frontend, stage, &provider).is_err_and(|diags| diags.iter().any(|d| d.to_string() == key))
    })
}

/// The files from `from` to `target` along `#include` lines (`["composite.fsh",
/// "lib/water.glsl", "lib/caustics.glsl"]`), if `from` includes `target` at all.
fn include_chain(pack: &ShippedPack, from: &str, target: &str) -> Option<Vec<String>> {
    fn walk(pack: &ShippedPack, path: &str, target: &str, chain: &mut Vec<String>) -> bool {
        if chain.iter().any(|p| p == path) {
            return false;
        }
        chain.push(path.to_string());
        if path == target {
            return true;
        }
        let text = pack.files.get(path).map(|f| f.text.clone()).unwrap_or_default();
        for line in text.lines() {
            let Some(rest) = line.trim_start().strip_prefix("#include") else { continue };
            let Some(included) = rest.trim().strip_prefix('"').and_then(|r| r.split('"').next()) else { continue };
            if let Ok(resolved) = resolve_include(path, included)
                && walk(pack, &resolved, target, chain)
            {
                return true;
            }
        }
        chain.pop();
        false
    }
    let mut chain = Vec::new();
    walk(pack, from, target, &mut chain).then_some(chain)
}

fn describe_set(set: &OptionSet) -> String {
    if set.is_empty() {
        "with the default options".into()
    } else {
        let parts: Vec<String> = set.iter().map(|(k, v)| format!("{k}={v}")).collect();
        format!("with options {}", parts.join(" "))
    }
}

fn validate_in_parallel(
    pack: &ShippedPack,
    programs: &[Program],
    unique: &[(LoweredStage, OptionSet)],
    ticker: Option<&Ticker>,
) -> Vec<Failure> {
    // One naga front-end per rayon job, reused for the stages it takes; results in input order.
    let results: Vec<_> = unique.par_iter().map_init(naga_check::Frontend::default, |frontend, (stage, set)| {
        let provider = WithOptions::new(pack, set);
        let result = naga_check::validate_stage(frontend, stage, &provider).err();
        if let Some(ticker) = ticker {
            ticker.tick();
        }
        let path = &stage.preprocessed.files[0];
        let program = programs.iter().find(|p| p.stages.iter().any(|(_, s)| s == path)).map_or_else(|| path.clone(), |p| p.name.clone());
        result.map(|diags| (diags, set.clone(), program))
    }).collect();
    results
        .into_iter()
        .flatten()
        .flat_map(|(diags, set, program)| diags.into_iter().map(move |d| (d, set.clone(), program.clone())))
        .collect()
}

/// Preprocesses a program's stages under one option set; returns the stages and the options
/// they consulted (all, and those tested in conditionals).
fn run_set(
    pack: &ShippedPack,
    program: &Program,
    set: &OptionSet,
    macros: &PreprocessOptions,
) -> Result<Vec<Arc<Preprocessed>>, Diagnostic> {
    let provider = WithOptions::new(pack, set);
    let name = program.name.rsplit('/').next().unwrap_or(&program.name);
    program
        .stages
        .iter()
        .map(|(stage, path)| {
            let mut pre = preprocess::preprocess(&provider, path, macros)?;
            if let std::borrow::Cow::Owned(declared) = programs::with_loader_declarations(name, *stage == Stage::Vertex, &pre.text) {
                pre.text = declared;
            }
            Ok(Arc::new(pre))
        })
        .collect()
}

/// An error of the option-set search and the set that showed it, boxed so that the common `Ok`
/// result stays small.
type SetFailure = Box<(Diagnostic, OptionSet)>;

/// The covering sets of a program, each candidate set preprocessed in parallel.
fn option_sets(
    pack: &ShippedPack,
    program: &Program,
    kinds: &BTreeMap<String, OptionKind>,
    macros: &PreprocessOptions,
    coverage: Coverage,
    profiles: &[OptionSet],
) -> Result<CoveringSets, SetFailure> {
    // Our own pack's options are few: every value pairs.
    coverage::covering_sets(kinds, &Representatives::new(), coverage, profiles, |sets| {
        sets.par_iter()
            .map(|set| {
                let stages = run_set(pack, program, set, macros).map_err(|d| Box::new((d, (*set).clone())))?;
                let mut names = Consulted::default();
                for pre in &stages {
                    names.read.extend(pre.consulted_macros.iter().cloned());
                    names.tested.extend(pre.tested_macros.iter().cloned());
                }
                Ok(names)
            })
            .collect()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn progress_reports_every_phase_to_its_end() {
        use crate::dialect::Dialect;
        use crate::source::PackSource;
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shaderpack");
        let source = PackSource::load(&root).unwrap();
        let options = crate::pack_options::collect(&source).unwrap();
        let pack = ShippedPack::generate(&source, &options, Dialect::Glsl330, &OptionSet::new()).unwrap();
        let seen = Mutex::new(Vec::new());
        let record = |step: Progress| seen.lock().unwrap().push((step.phase.to_string(), step.done, step.total));
        let report = validate_pack(&pack, &options, Coverage::Pairwise, &[], Some(&record)).unwrap();
        let seen = seen.into_inner().unwrap();
        let mut validated = 0;
        for loader in ["OptiFine", "Iris with Distant Horizons"] {
            for phase in ["programs' option sets found", "option sets lowered", "stages validated by naga"] {
                let phase = format!("{phase} for {loader}");
                let last = seen.iter().rfind(|(p, _, _)| *p == phase).unwrap_or_else(|| panic!("no {phase}: {seen:?}"));
                assert_eq!(last.1, last.2, "{phase} ends at its total: {seen:?}");
                if phase.starts_with("stages validated") {
                    validated += last.1;
                }
            }
        }
        assert_eq!(validated, report.stages_validated);
        assert!(report.options_read.contains("CAUSTICS") && report.options_read.contains("SSR_STEPS"), "{:?}", report.options_read);
    }
}
