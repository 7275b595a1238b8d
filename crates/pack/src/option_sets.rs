//! Validation of every program under the option sets that change its text.
//!
//! Which options matter is discovered, not declared: a program's stages are preprocessed with
//! the default values, the options the preprocessor consulted become relevant, and sets are
//! drawn from the relevant options' values; options found only under some of those sets join
//! and the search repeats until it is closed. Which sets:
//! - all combinations of the relevant options, when there are at most
//!   [`MAX_EXHAUSTIVE_SETS`];
//! - otherwise, every combination of the options the program tests in conditionals
//!   ([`Coverage::Exhaustive`], or [`Coverage::Pairwise`] while that product is at most
//!   [`MAX_PAIRWISE_PRODUCT`]), with options that are only substituted as values varied one
//!   at a time;
//! - under [`Coverage::Pairwise`] with more tested combinations: a covering array in which
//!   every pair of values of any two tested options appears together in some set, plus every
//!   profile.
//!
//! Every set is preprocessed and lowered; identical lowered texts are validated by naga once.

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use rayon::prelude::*;

use tidepack_glsl::Diagnostic;
use tidepack_loader::macros::StandardMacros;
use tidepack_loader::option_lines::{OptionSet, OptionValue};
use tidepack_glsl::preprocess::{self, PreprocessOptions, Preprocessed, resolve_include};
use tidepack_glsl::naga_check::{self, LoweredStage};

use crate::pack_options::PackOptions;
use crate::shipped::{Program, ShippedPack, WithOptions};

/// Largest product of all relevant options validated in full.
pub const MAX_EXHAUSTIVE_SETS: usize = 4096;
/// Largest product of the tested options that [`Coverage::Pairwise`] still validates in full.
pub const MAX_PAIRWISE_PRODUCT: usize = 256;

/// How many option combinations to validate when they are too many for all of them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Coverage {
    /// Every combination of the options each program tests.
    Exhaustive,
    /// Every pair of values of any two tested options, and every profile.
    #[default]
    Pairwise,
}

/// What the validated sets of a program cover, weakest last.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum SetsCovered {
    /// Every combination of every option the program reads.
    AllCombinations,
    /// Every combination of the options it tests; substituted values one at a time.
    TestedCombinations,
    /// Every pair of tested option values, and the profiles.
    Pairs,
}

impl SetsCovered {
    pub fn describe(self) -> &'static str {
        match self {
            SetsCovered::AllCombinations => "every combination of the options each program reads",
            SetsCovered::TestedCombinations => {
                "every combination of the options each program tests, substituted values one at a time"
            }
            SetsCovered::Pairs => "every pair of values of the options each program tests, and every profile",
        }
    }
}

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
    phase: &'static str,
    total: usize,
    done: AtomicUsize,
    last: Mutex<Instant>,
}

impl<'a> Ticker<'a> {
    fn new(report: Option<ProgressFn<'a>>, phase: &'static str, total: usize) -> Self {
        Ticker { report, phase, total, done: AtomicUsize::new(0), last: Mutex::new(Instant::now()) }
    }

    fn tick(&self) {
        let done = self.done.fetch_add(1, Ordering::Relaxed) + 1;
        let Some(report) = self.report else { return };
        let mut last = self.last.lock().expect("no panics while holding the ticker");
        if done == self.total || last.elapsed() >= Duration::from_secs(1) {
            *last = Instant::now();
            report(Progress { phase: self.phase, done, total: self.total });
        }
    }
}

/// Validates every program of `pack`; diagnostics point at shipped files.
///
/// The default option set of every program goes first: most mistakes show there, and a
/// failing build then stops before enumerating every set.
/// `profiles` are option sets players can pick, always validated. `progress` hears how far
/// the option-set search, the lowering and naga are.
pub fn validate_pack(
    pack: &ShippedPack,
    options: &PackOptions,
    coverage: Coverage,
    profiles: &[OptionSet],
    progress: Option<ProgressFn>,
) -> Result<ValidationReport, Vec<Diagnostic>> {
    let macros = StandardMacros::default().preprocess_options();
    let programs = pack.programs();
    let defaults: Vec<(&Program, OptionSet)> = programs.iter().map(|p| (p, OptionSet::new())).collect();
    let mut seen = HashMap::new();
    let (unique, mut errors, _) = lower_sets(pack, &defaults, &macros, &mut seen, None);
    errors.extend(validate_in_parallel(pack, &programs, &unique, None));
    if !errors.is_empty() {
        return Err(distinct_errors(pack, &programs, &macros, errors));
    }
    let mut report = ValidationReport { programs: programs.len(), ..Default::default() };
    let mut all_sets = Vec::new();
    let searched = Ticker::new(progress, "programs' option sets found", programs.len());
    for program in &programs {
        match option_sets(pack, program, options, &macros, coverage, profiles) {
            Ok(ProgramSets { sets, covered, read }) => {
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
    let lowered = Ticker::new(progress, "option sets lowered", all_sets.len());
    let (mut unique, lowering_errors, identical) = lower_sets(pack, &all_sets, &macros, &mut HashMap::new(), Some(&lowered));
    errors.extend(lowering_errors);
    report.stages_identical = identical;
    report.stages_validated = unique.len();
    report.validated = unique.iter().map(|(stage, set)| (stage.preprocessed.files[0].clone(), set.clone())).collect();
    let validated = Ticker::new(progress, "stages validated by naga", unique.len());
    errors.extend(validate_in_parallel(pack, &programs, &unique, Some(&validated)));
    unique.clear();
    if errors.is_empty() { Ok(report) } else { Err(distinct_errors(pack, &programs, &macros, errors)) }
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
    program.stages.iter().map(|(_, path)| preprocess::preprocess(&provider, path, macros).map(Arc::new)).collect()
}

/// The option sets of a program, what they cover, and the options its text depends on.
struct ProgramSets {
    sets: Vec<OptionSet>,
    covered: SetsCovered,
    read: BTreeSet<String>,
}

/// An error of the option-set search and the set that showed it, boxed so that the common `Ok`
/// result stays small.
type SetFailure = Box<(Diagnostic, OptionSet)>;

/// The option sets of a program (see the module docs).
fn option_sets(
    pack: &ShippedPack,
    program: &Program,
    options: &PackOptions,
    macros: &PreprocessOptions,
    coverage: Coverage,
    profiles: &[OptionSet],
) -> Result<ProgramSets, SetFailure> {
    let mut relevant: BTreeSet<String> = BTreeSet::new();
    let mut tested: BTreeSet<String> = BTreeSet::new();
    let mut explored: BTreeSet<OptionSet> = BTreeSet::new();
    loop {
        let (sets, covered) = enumerate(&relevant, &tested, options, coverage, profiles);
        let fresh: Vec<&OptionSet> = sets.iter().filter(|s| !explored.contains(*s)).collect();
        let consulted: Vec<_> = fresh.par_iter().map(|set| {
            let stages = run_set(pack, program, set, macros).map_err(|d| Box::new((d, (*set).clone())))?;
            let mut names = (BTreeSet::new(), BTreeSet::new());
            for pre in &stages {
                names.0.extend(pre.consulted_macros.iter().filter(|n| options.contains_key(*n)).cloned());
                names.1.extend(pre.tested_macros.iter().filter(|n| options.contains_key(*n)).cloned());
            }
            Ok::<_, SetFailure>(names)
        }).collect();
        let mut grew = false;
        for result in consulted {
            let (all, in_conditionals) = result?;
            for name in all {
                grew |= relevant.insert(name);
            }
            for name in in_conditionals {
                grew |= tested.insert(name);
            }
        }
        explored.extend(fresh.into_iter().cloned());
        if !grew {
            return Ok(ProgramSets { sets, covered, read: relevant });
        }
    }
}

/// The option sets for the relevant options. Options at their default are left out of a set,
/// so a set means the same whichever options are relevant.
fn enumerate(
    relevant: &BTreeSet<String>,
    tested: &BTreeSet<String>,
    options: &PackOptions,
    coverage: Coverage,
    profiles: &[OptionSet],
) -> (Vec<OptionSet>, SetsCovered) {
    let choices = |name: &String| -> Vec<Option<OptionValue>> {
        let kind = &options[name].kind;
        let default = kind.default_value();
        kind.all_values().into_iter().map(|v| (v != default).then_some(v)).collect()
    };
    let set_of = |names: &[&String], row: &[usize]| -> OptionSet {
        names
            .iter()
            .zip(row)
            .filter_map(|(name, &i)| Some(((*name).clone(), choices(name)[i].clone()?)))
            .collect()
    };
    let all: Vec<&String> = relevant.iter().collect();
    let sizes = |names: &[&String]| names.iter().map(|n| choices(n).len()).collect::<Vec<_>>();
    if sizes(&all).iter().product::<usize>() <= MAX_EXHAUSTIVE_SETS {
        let sets = product(&sizes(&all)).iter().map(|row| set_of(&all, row)).collect();
        return (sets, SetsCovered::AllCombinations);
    }
    let structural: Vec<&String> = relevant.iter().filter(|n| tested.contains(*n)).collect();
    let structural_sizes = sizes(&structural);
    let all_tested = coverage == Coverage::Exhaustive
        || structural_sizes.iter().product::<usize>() <= MAX_PAIRWISE_PRODUCT;
    let (rows, covered) = if all_tested {
        (product(&structural_sizes), SetsCovered::TestedCombinations)
    } else {
        (pairwise(&structural_sizes), SetsCovered::Pairs)
    };
    let mut sets: Vec<OptionSet> = rows.iter().map(|row| set_of(&structural, row)).collect();
    for name in relevant.iter().filter(|n| !tested.contains(*n)) {
        for value in choices(name).into_iter().flatten() {
            sets.push([(name.clone(), value)].into());
        }
    }
    if covered == SetsCovered::Pairs {
        for profile in profiles {
            let set: OptionSet = profile
                .iter()
                .filter(|(name, value)| relevant.contains(*name) && options[*name].kind.default_value() != **value)
                .map(|(k, v)| (k.clone(), v.clone()))
                .collect();
            sets.push(set);
        }
    }
    sets.sort();
    sets.dedup();
    (sets, covered)
}

/// Every combination of indices below `sizes`.
fn product(sizes: &[usize]) -> Vec<Vec<usize>> {
    let mut rows = vec![Vec::new()];
    for &size in sizes {
        rows = rows.into_iter().flat_map(|row| (0..size).map(move |v| [row.clone(), vec![v]].concat())).collect();
    }
    rows
}

/// A covering array of strength 2: rows of indices below `sizes` such that every pair of
/// values of any two positions appears in some row. Greedy and deterministic: each row starts
/// from an uncovered pair and fills the other positions with the value covering most pairs.
fn pairwise(sizes: &[usize]) -> Vec<Vec<usize>> {
    let n = sizes.len();
    let mut uncovered: BTreeSet<(usize, usize, usize, usize)> = BTreeSet::new();
    for a in 0..n {
        for b in a + 1..n {
            for va in 0..sizes[a] {
                for vb in 0..sizes[b] {
                    uncovered.insert((a, va, b, vb));
                }
            }
        }
    }
    // The all-defaults row first: index 0 is each option's default.
    let mut rows = vec![vec![0; n]];
    remove_covered(&mut uncovered, &rows[0]);
    while let Some(&(a, va, b, vb)) = uncovered.iter().next() {
        let mut row: Vec<Option<usize>> = vec![None; n];
        row[a] = Some(va);
        row[b] = Some(vb);
        for position in 0..n {
            if row[position].is_some() {
                continue;
            }
            let gain = |value: usize| {
                row.iter()
                    .enumerate()
                    .filter_map(|(other, v)| Some((other, (*v)?)))
                    .filter(|&(other, v)| {
                        let key = if other < position { (other, v, position, value) } else { (position, value, other, v) };
                        uncovered.contains(&key)
                    })
                    .count()
            };
            let best = (0..sizes[position]).max_by_key(|&v| (gain(v), std::cmp::Reverse(v))).unwrap_or(0);
            row[position] = Some(best);
        }
        let row: Vec<usize> = row.into_iter().map(|v| v.unwrap_or(0)).collect();
        remove_covered(&mut uncovered, &row);
        rows.push(row);
    }
    rows
}

fn remove_covered(uncovered: &mut BTreeSet<(usize, usize, usize, usize)>, row: &[usize]) {
    for a in 0..row.len() {
        for b in a + 1..row.len() {
            uncovered.remove(&(a, row[a], b, row[b]));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pairwise_covers_every_pair_with_few_rows() {
        let sizes = [2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 3, 2];
        let rows = pairwise(&sizes);
        for a in 0..sizes.len() {
            for b in a + 1..sizes.len() {
                for va in 0..sizes[a] {
                    for vb in 0..sizes[b] {
                        assert!(rows.iter().any(|r| r[a] == va && r[b] == vb), "pair ({a}={va}, {b}={vb}) uncovered");
                    }
                }
            }
        }
        assert_eq!(rows[0], vec![0; sizes.len()]);
        assert!(rows.len() <= 16, "{} rows", rows.len());
    }

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
        for phase in ["programs' option sets found", "option sets lowered", "stages validated by naga"] {
            let last = seen.iter().rfind(|(p, _, _)| p == phase).unwrap_or_else(|| panic!("no {phase}: {seen:?}"));
            assert_eq!(last.1, last.2, "{phase} ends at its total: {seen:?}");
        }
        assert!(seen.iter().any(|(p, done, _)| p == "stages validated by naga" && *done == report.stages_validated));
        assert!(report.options_read.contains("CAUSTICS") && report.options_read.contains("SSR_STEPS"), "{:?}", report.options_read);
    }

    #[test]
    fn product_lists_every_combination() {
        assert_eq!(product(&[2, 3]).len(), 6);
        assert_eq!(product(&[]), vec![Vec::<usize>::new()]);
    }
}
