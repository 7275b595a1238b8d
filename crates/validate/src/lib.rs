//! `tidepack validate`: checks any OptiFine shader pack (folder or zip) the way OptiFine loads
//! it, without a game or a GPU.
//!
//! Data flow: [`input::read_pack`] (in memory, hostile input refused entry by entry) →
//! [`PackFiles::programs`](tidepack_loader::input::PackFiles::programs) (world folders, program names, other loaders' programs) →
//! option sets (defaults, `shaders.properties` profiles) → per program and set, in `stages`:
//! `tidepack_glsl::preprocess` with OptiFine's standard macros → `naga_check::lower_program`
//! and the checks of [`interface`] and [`version_rules`] → in `naga_pool`: naga on each
//! distinct lowered text once, in parallel, panics caught, its messages put in the pack's
//! terms by `messages` → here: diagnostics located in the pack's files, each once, in a
//! [`Report`].

use std::collections::{BTreeMap, BTreeSet, HashMap, HashSet};
use std::time::Instant;
use std::sync::Arc;

use rayon::prelude::*;
use sha2::{Digest, Sha256};

use tidepack_glsl::{Code, Diagnostic, Drivers, Location};
use tidepack_glsl::known_valid::KnownValid;
use tidepack_glsl::preprocess::{PreprocessOptions, TokenCache};
use tidepack_loader::directives::{CustomNames, custom_names};
use tidepack_loader::input::{self, Limits, PackFiles};
use tidepack_loader::macros::StandardMacros;
use tidepack_loader::option_lines::{OptionKind, OptionSet};
use tidepack_loader::option_space::{self, declared_options, read_properties};
use tidepack_loader::programs::{self, Program, RunBy};
use tidepack_loader::properties::{self, Properties};
use tidepack_loader::{Configuration, Dimension, Loader, SetProvider};

mod cache;
mod configurations;
pub mod driver;
pub mod fuzz;
pub mod glslang;
pub mod interface;
pub mod levels;
pub mod loader_text;
mod naga_pool;
pub mod output;
mod report;
mod stages;
pub mod glsl_rules;
pub mod version_rules;

pub use naga_pool::MAX_NAGA_LINES;
pub use levels::Levels;
pub use report::{ProgramReport, Report, Status};
pub use configurations::{PlanSummary, Shard};
pub use stages::other_stage_kind;
pub use tidepack_loader::coverage::{Coverage, SetsCovered};

use cache::Cache;
use configurations::{Pair, Reader, SetTable};
use naga_pool::{Job, JobStage};
use stages::{check_compute, check_program, preprocess_other_stages};

/// Which option values to validate under.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum Profiles {
    /// The defaults written in the pack's sources.
    #[default]
    Defaults,
    /// One profile of `shaders.properties`.
    Named(String),
    /// The defaults and every profile.
    All,
    /// The defaults, every profile, and each program under the covering sets of the options
    /// its text depends on ([`tidepack_loader::coverage`]).
    Covering(Coverage),
}

#[derive(Clone, Debug)]
pub struct Options {
    pub macros: StandardMacros,
    pub profiles: Profiles,
    /// Option values (`NAME` → value as written) set over every profile validated.
    pub overrides: Vec<(String, String)>,
    /// Only the programs this dimension runs (its world folder's, or the shaders folder's);
    /// `None`: every world folder.
    pub dimension: Option<Dimension>,
    /// The loader whose choice of world folder `dimension` follows.
    pub loader: Loader,
    pub limits: Limits,
    /// Worker threads for naga (at least 1).
    pub threads: usize,
    /// Also compile every program with the real OpenGL driver (see [`driver`]).
    pub driver: bool,
    /// Keep each pair's findings in this folder across runs (see [`cache`]).
    pub cache: Option<std::path::PathBuf>,
    /// Validate only this share of the distinct program texts.
    pub shard: Option<Shard>,
    /// The drivers whose refusals are errors; an error only others refuse becomes a warning,
    /// and one only macOS refuses is left out unless macOS is a target.
    pub target: Drivers,
    /// Warnings silenced or made errors, by code.
    pub levels: Levels,
}

/// The default `--target`: every family that runs OpenGL 4.6. macOS (4.1 at most) is a target
/// only when asked for, since most packs need more.
pub const DEFAULT_TARGET: Drivers = Drivers::ALL.without(Drivers::MACOS);

impl Default for Options {
    fn default() -> Self {
        Options {
            macros: StandardMacros::default(),
            profiles: Profiles::Defaults,
            overrides: Vec::new(),
            dimension: None,
            loader: Loader::default(),
            limits: Limits::default(),
            threads: std::thread::available_parallelism().map_or(2, |n| n.get()),
            driver: false,
            cache: None,
            shard: None,
            target: DEFAULT_TARGET,
            levels: Levels::default(),
        }
    }
}

/// Reads and validates a pack folder or zip. `Err` means the input could not be read, or the
/// options name a profile the pack lacks.
pub fn validate_path(path: &std::path::Path, options: &Options) -> Result<Report, Diagnostic> {
    let started = Instant::now();
    let pack = input::read_pack(path, &options.limits)?;
    let mut report = validate_pack(pack, options)?;
    report.elapsed = started.elapsed();
    Ok(report)
}

/// A diagnostic with the program (index into the found programs) and option set (index into
/// the validated sets) it was found in.
struct Finding {
    program: usize,
    set: usize,
    diagnostic: Diagnostic,
}

/// Most profiles `--all-profiles` validates; a player picks among a handful, and each is
/// validated as a set of its own.
pub const MAX_PROFILES_VALIDATED: usize = 1000;

/// The option sets to validate every program under, labelled: the defaults, a profile or every
/// profile (`options.profiles`), each with `options.overrides` over it, and the overrides'
/// own set. Profile warnings join
/// `diagnostics`; an unknown profile, option or value is an error.
fn option_sets(
    props: &Properties,
    declared: &BTreeMap<String, OptionKind>,
    options: &Options,
    diagnostics: &mut Vec<Diagnostic>,
) -> Result<(Vec<(String, OptionSet)>, OptionSet), Diagnostic> {
    let mut sets: Vec<(String, OptionSet)> = Vec::new();
    let mut resolver = option_space::ProfileResolver::new(props, declared);
    match &options.profiles {
        Profiles::Defaults => sets.push(("defaults".into(), OptionSet::new())),
        Profiles::Named(name) => {
            let (set, warnings) = resolver.resolve(name)?;
            diagnostics.extend(warnings);
            sets.push((format!("profile {name}"), set));
        }
        Profiles::All | Profiles::Covering(_) => {
            sets.push(("defaults".into(), OptionSet::new()));
            let names: Vec<String> = option_space::profiles(props).into_keys().collect();
            if names.len() > MAX_PROFILES_VALIDATED {
                diagnostics.push(Diagnostic::error(
                    Code::Budget,
                    format!(
                        "shaders.properties defines {} profiles, more than the {MAX_PROFILES_VALIDATED} validated (the budget for profiles); none is validated",
                        names.len()
                    ),
                    None,
                ));
            } else {
                for name in names {
                    match resolver.resolve(&name) {
                        Ok((set, warnings)) => {
                            diagnostics.extend(warnings);
                            sets.push((format!("profile {name}"), set));
                        }
                        // Profiles that name a broken one share its error: say it once.
                        Err(e) if diagnostics.contains(&e) => {}
                        Err(e) => diagnostics.push(e),
                    }
                }
            }
        }
    }
    let mut overrides = OptionSet::new();
    if !options.overrides.is_empty() {
        let configuration = Configuration { options: options.overrides.clone(), ..Configuration::default() };
        (overrides, _) = configuration.option_set(props, declared).map_err(|e| Diagnostic::error(Code::Usage, e, None))?;
        let named: Vec<String> = options.overrides.iter().map(|(n, v)| format!("{n}={v}")).collect();
        for (label, set) in &mut sets {
            set.extend(overrides.clone());
            *label = format!("{label} with {}", named.join(" "));
        }
    }
    Ok((sets, overrides))
}

/// Validates a pack already in memory.
pub fn validate_pack(pack: PackFiles, options: &Options) -> Result<Report, Diagnostic> {
    let started = Instant::now();
    let declared = declared_options(&pack);
    let properties_text = pack.texts.get(properties::PATH).map_or("", |t| &**t);
    // Profiles are read under the defaults; each set's own reading decides its custom names.
    let props = read_properties(properties_text, &options.macros, &declared, &OptionSet::new());
    let with_features = Options { macros: options.macros.clone().with_optional_features(&props), ..options.clone() };
    let options = &with_features;
    let mut diagnostics: Vec<Diagnostic> = pack.warnings.clone();
    // OptiFine takes a conditional line it cannot evaluate as false and says so in its log.
    diagnostics.extend(props.problems.iter().map(|(line, problem)| Diagnostic::warning(Code::Properties, problem.clone(), Some(Location::line(properties::PATH, *line)))));
    if options.loader == Loader::Iris && !options.target.intersection(Drivers::MACOS).is_empty() {
        diagnostics.extend(stages::iris_features_on_macos(&props));
    }
    let (sets, overrides) = option_sets(&props, &declared, options, &mut diagnostics)?;
    let mut programs = pack.programs(options.loader);
    let mut dimension_without_programs = None;
    if let Some(dimension) = &options.dimension {
        let world = pack.world_folder(dimension, options.loader);
        let elsewhere = !programs.is_empty();
        programs.retain(|p| p.world == world);
        if programs.is_empty() && elsewhere {
            let folder = if world.is_empty() { "shaders/".to_string() } else { format!("shaders/{world}/") };
            dimension_without_programs = Some(format!(
                "in the {dimension} the loader runs the programs of {folder}, and the pack has none there: that dimension is drawn without shaders"
            ));
        }
    }
    // Every program under every set reads the same files: each is tokenized once.
    let macros = PreprocessOptions { token_cache: Some(std::sync::Arc::new(TokenCache::default())), ..options.macros.preprocess_options() };
    let runs = |name: &str| programs::runs_with(name, options.loader, options.macros.distant_horizons);
    let mut reports: Vec<ProgramReport> = programs
        .iter()
        .map(|p| ProgramReport {
            id: p.id(),
            stages: p
                .stages
                .iter()
                .map(|(_, s)| s.clone())
                .chain(p.other_stages.iter().cloned())
                .chain(p.compute.iter().cloned())
                .collect(),
            status: match &p.run_by {
                _ if runs(&p.name) => Status::Valid,
                RunBy::Other(who) if programs::DISTANT_HORIZONS_PROGRAMS.contains(&p.name.as_str()) => {
                    Status::Skipped(format!("run by {who}; validated with --loader iris --distant-horizons"))
                }
                RunBy::Other(who) => Status::Skipped(format!("run by {who}; not validated under {}", options.loader)),
                _ => Status::Skipped("no loader runs a program of this name; not validated".into()),
            },
            compile_error: false,
            only_preprocessed: if runs(&p.name) && !options.driver { p.other_stages.clone() } else { Vec::new() },
            diagnostics: Vec::new(),
        })
        .collect();
    let runnable: Vec<usize> =
        (0..programs.len()).filter(|&i| runs(&programs[i].name) && programs[i].has_stages()).collect();
    let cache = options.cache.as_deref().map(Cache::open).transpose()?;
    let covering = match options.profiles {
        Profiles::Covering(coverage) => Some(coverage),
        _ => None,
    };
    let dedup = covering.is_some() || cache.is_some() || options.shard.is_some();
    let pool = naga_pool::worker_pool(options.threads);
    let reader = Reader::new(&pack, properties_text, &declared, &options.macros, &macros);
    let mut table = SetTable::new(sets);
    let (pairs, plan) =
        pool.install(|| configurations::plan(&reader, &programs, &runnable, &mut table, covering, &overrides, dedup, options.shard));
    let sets = table.sets;
    // Per set: the names shaders.properties declares and the programs it turns off per world
    // folder (`program.<name>.enabled`).
    let worlds: BTreeSet<&str> = runnable.iter().map(|&i| programs[i].world.as_str()).collect();
    // shaders.properties reads only the options it names: sets that agree on those share one
    // reading of it.
    let keys: Vec<OptionSet> = sets.iter().map(|(_, set)| reader.properties_key(set)).collect();
    let distinct: Vec<&OptionSet> = keys.iter().collect::<BTreeSet<_>>().into_iter().collect();
    let read: BTreeMap<&OptionSet, Arc<SetContext>> = pool.install(|| {
        distinct
            .par_iter()
            .map(|&key| {
                let properties = read_properties(properties_text, &options.macros, &declared, key);
                let mut problems = Vec::new();
                let disabled = worlds
                    .iter()
                    .map(|world| {
                        let (off, found) = programs::disabled_programs(&properties, world, &declared, key);
                        problems.extend(found);
                        (world.to_string(), off)
                    })
                    .collect();
                (key, Arc::new(SetContext { names: custom_names(&properties), disabled, problems }))
            })
            .collect()
    });
    let contexts: Vec<Arc<SetContext>> = keys.iter().map(|key| read[key].clone()).collect();
    for problem in contexts.iter().flat_map(|c| &c.problems).map(|p| Diagnostic::warning(Code::Properties, p.clone(), None)) {
        if !diagnostics.contains(&problem) {
            diagnostics.push(problem);
        }
    }
    let mut found: Vec<Finding> = Vec::new();
    // (program, option set) pairs under which `program.<name>.enabled` turns the program off.
    let mut off_under: HashSet<(usize, usize)> = HashSet::new();
    // Distinct lowered stages by digest of path and text, as indices into `stage_findings`.
    let mut seen_stages: HashMap<[u8; 32], usize> = HashMap::new();
    // The functions naga accepted, which later stages give it as prototypes.
    let known = KnownValid::new();
    let mut stage_findings: Vec<Vec<Diagnostic>> = Vec::new();
    let mut stages_validated = 0;
    let chunk_size = 16 * options.threads.max(1);
    for chunk in pairs.chunks(chunk_size) {
        let checked: Vec<Checked> = pool.install(|| {
            chunk
                .par_iter()
                .map(|pair| {
                    let program = &programs[pair.program];
                    let (_, set) = &sets[pair.set];
                    let context = &contexts[pair.set];
                    if context.disabled.get(&program.world).is_some_and(|off| off.contains(&program.name)) {
                        return Checked::Off;
                    }
                    let key = cache.as_ref().zip(pair.fingerprint).map(|(_, f)| cache::key(options.loader, options.driver, &f, set));
                    if let Some(diagnostics) = cache.as_ref().zip(key).and_then(|(cache, key)| cache.get(&key)) {
                        return Checked::Cached(diagnostics);
                    }
                    let provider = SetProvider::new(&pack, set);
                    let (diagnostics, stages) = check_pair(program, &provider, &macros, &context.names, options);
                    Checked::Fresh { key, diagnostics, stages }
                })
                .collect()
        });
        let mut jobs: Vec<Job> = Vec::new();
        // Fresh pairs: the pair, its cache key, what it gave before naga, its stages' ids.
        let mut fresh: Vec<(Pair, Option<cache::Key>, Vec<Diagnostic>, Vec<usize>)> = Vec::new();
        for (pair, result) in chunk.iter().zip(checked) {
            let finding = |diagnostic| Finding { program: pair.program, set: pair.set, diagnostic };
            match result {
                Checked::Off => {
                    off_under.insert((pair.program, pair.set));
                }
                Checked::Cached(diagnostics) => found.extend(diagnostics.into_iter().map(finding)),
                Checked::Fresh { key, diagnostics, stages } => {
                    let mut stage_ids = Vec::new();
                    for stage in stages {
                        let digest: [u8; 32] = Sha256::new()
                            .chain_update(stage.preprocessed().files[0].as_bytes())
                            .chain_update([0])
                            .chain_update(stage.text().as_bytes())
                            .finalize()
                            .into();
                        let next = stage_findings.len() + jobs.len();
                        let id = *seen_stages.entry(digest).or_insert(next);
                        if id == next {
                            let position_optional = !programs[pair.program].other_stages.is_empty();
                            jobs.push(Job { stage, set: pair.set, position_optional });
                        }
                        stage_ids.push(id);
                    }
                    fresh.push((*pair, key, diagnostics, stage_ids));
                }
            }
        }
        stages_validated += jobs.len();
        stage_findings.extend(naga_pool::run_naga(&pool, &jobs, &pack, &sets, &known));
        // naga's findings of a stage belong to every pair that has the stage, whichever pair
        // gave it first. naga's error at a line where one of the pair's own GLSL rules already
        // named the mistake says the same in naga's words: the rule's message stands alone.
        for (pair, key, mut diagnostics, stage_ids) in fresh {
            let explained: HashSet<(&str, u32)> =
                diagnostics.iter().filter(|d| d.is_error()).filter_map(|d| d.location.as_ref().map(|l| (l.path.as_str(), l.line))).collect();
            let naga_findings: Vec<Diagnostic> = stage_ids
                .iter()
                .flat_map(|&id| stage_findings[id].iter())
                .filter(|d| !(d.is_error() && d.location.as_ref().is_some_and(|l| explained.contains(&(l.path.as_str(), l.line)))))
                .cloned()
                .collect();
            diagnostics.extend(naga_findings);
            if let Some((cache, key)) = cache.as_ref().zip(key) {
                cache.put(&key, &diagnostics);
            }
            found.extend(diagnostics.into_iter().map(|diagnostic| Finding { program: pair.program, set: pair.set, diagnostic }));
        }
    }
    for (index, report) in reports.iter_mut().enumerate() {
        let planned = pairs.iter().filter(|p| p.program == index).count();
        let off = off_under.iter().filter(|(program, _)| *program == index).count();
        if planned > 0 && off == planned && report.status == Status::Valid {
            let key = format!("program.{}.enabled", report.id);
            report.status = Status::Skipped(format!("turned off by {key} in shaders.properties under every option set validated"));
        }
    }
    if let Some(message) = dimension_without_programs {
        // A pack may shade some dimensions only: nothing to check is the answer here.
        diagnostics.push(Diagnostic::warning(Code::NothingValidated, message, None));
    } else if !reports.iter().any(|r| r.status == Status::Valid) && !found.iter().any(|f| f.diagnostic.is_error()) {
        // A CI check that checked nothing must not pass.
        let skipped: Vec<String> = reports.iter().map(|r| r.id.clone()).collect();
        let mut diag = Diagnostic::error(Code::NothingValidated, format!("no program that {} runs was found, so nothing was validated", options.loader), None);
        if !skipped.is_empty() {
            diag = diag.with_note(format!("found only programs other loaders run: {}", skipped.join(", ")));
        }
        diagnostics.push(diag);
    }
    let driver_summary = if options.driver {
        let mut unsupported = Vec::new();
        let summary = run_driver(&programs, &pack, &sets, &pairs, &off_under, options, &mut found, &mut unsupported)?;
        for (program, path) in unsupported {
            if !reports[program].only_preprocessed.contains(&path) {
                reports[program].only_preprocessed.push(path);
            }
        }
        Some(summary)
    } else {
        None
    };
    let mut reproductions =
        if covering.is_some() { pool.install(|| reproductions(&found, &programs, &pack, &sets, &contexts, &macros, options, &known)) } else { BTreeMap::new() };
    found = in_target(found, options.target, &mut reproductions);
    let mut silenced = levels::Silenced::default();
    diagnostics = std::mem::take(&mut diagnostics).into_iter().filter_map(|d| options.levels.apply(d, &mut silenced)).collect();
    found = found.into_iter().filter_map(|f| Some(Finding { diagnostic: options.levels.apply(f.diagnostic, &mut silenced)?, ..f })).collect();
    // One diagnostic per distinct message and place, noting every program and option set it
    // was seen in, keyed by message and sorted by place so that the report reads file by file.
    let pack_level: BTreeSet<String> = diagnostics.iter().map(|d| d.to_string()).collect();
    let mut distinct: BTreeMap<String, (Diagnostic, BTreeSet<usize>, BTreeSet<usize>)> = BTreeMap::new();
    for Finding { program, set, diagnostic: diag } in found {
        if diag.is_error() {
            reports[program].status = Status::Invalid;
            reports[program].compile_error |= !driver::is_loader_level(&diag);
        }
        let key = diag.to_string();
        if pack_level.contains(&key) {
            continue;
        }
        let entry = distinct.entry(key).or_insert_with(|| (diag, BTreeSet::new(), BTreeSet::new()));
        entry.1.insert(program);
        entry.2.insert(set);
    }
    let mut seen_in: Vec<(Diagnostic, BTreeSet<usize>)> = diagnostics.drain(..).map(|d| (d, BTreeSet::new())).collect();
    for (key, (mut diag, in_programs, in_sets)) in distinct {
        if let Some(set) = reproductions.get(&key) {
            diag = diag.with_note(format!("shown with: {}", configurations::label_of(set)));
        }
        let ids: Vec<String> = in_programs.iter().map(|&p| programs[p].id()).collect();
        let mut context = match ids.as_slice() {
            [one] => format!("in program {one}"),
            _ => format!("in programs {}", ids.join(", ")),
        };
        if sets.len() > 1 || sets.iter().any(|(_, set)| !set.is_empty()) {
            context.push_str(&format!(" with {}", sets_named(&sets, &in_sets)));
        }
        seen_in.push((diag.with_note(context), in_programs));
    }
    seen_in.sort_by(|(a, _), (b, _)| {
        let key = |d: &Diagnostic| {
            (
                d.location.as_ref().map(|l| (l.path.clone(), l.line, l.columns.as_ref().map(|c| (c.start, c.end)))),
                std::cmp::Reverse(d.severity),
                d.message.clone(),
                d.notes.clone(),
            )
        };
        key(a).cmp(&key(b))
    });
    for (index, (diag, in_programs)) in seen_in.into_iter().enumerate() {
        for program in in_programs {
            reports[program].diagnostics.push(index);
        }
        diagnostics.push(diag);
    }
    Ok(Report {
        pack,
        programs: reports,
        diagnostics,
        option_sets: sets.into_iter().map(|(label, _)| label).collect(),
        plan,
        stages_validated,
        elapsed: started.elapsed(),
        driver: driver_summary,
        allowed: silenced.counts(),
    })
}

/// The findings as `target` sees them: an error no target driver refuses becomes a warning
/// naming who does, except one only macOS refuses, which is left out when macOS is not a
/// target; an error some drivers accept says which.
fn in_target(found: Vec<Finding>, target: Drivers, reproductions: &mut BTreeMap<String, OptionSet>) -> Vec<Finding> {
    let named = |drivers: Drivers| {
        drivers
            .names()
            .iter()
            .map(|n| match *n {
                "mesa" => "Mesa",
                "amd" => "AMD",
                "intel" => "Intel",
                "nvidia" => "NVIDIA",
                _ => "macOS",
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    found
        .into_iter()
        .filter_map(|mut f| {
            let before = f.diagnostic.to_string();
            if !in_target_one(&mut f, target, &named) {
                return None;
            }
            if let Some(set) = reproductions.get(&before).cloned() {
                reproductions.insert(f.diagnostic.to_string(), set);
            }
            Some(f)
        })
        .collect()
}

/// [`in_target`] for one finding: `false` if it is left out.
fn in_target_one(f: &mut Finding, target: Drivers, named: &dyn Fn(Drivers) -> String) -> bool {
    let refused = f.diagnostic.refused_by;
    if !f.diagnostic.is_error() || refused == Drivers::ALL {
        return true;
    }
    if refused.intersection(target).is_empty() {
        if refused == Drivers::MACOS {
            return false;
        }
        f.diagnostic.severity = tidepack_glsl::Severity::Warning;
        f.diagnostic.notes.push(format!("only {} refuse this, and --target leaves them out", named(refused)));
        return true;
    }
    let accept = Drivers::ALL.without(refused);
    let verb = if accept.names().len() == 1 { "accepts" } else { "accept" };
    f.diagnostic.notes.push(format!("refused by {}; {} {verb} it", named(refused), named(accept)));
    true
}

/// Most errors a covering run reduces to the options they need.
const MAX_REDUCED_ERRORS: usize = 64;

/// For each distinct error (by its text) the defaults do not show, the fewest `--set` options
/// found to show it: its smallest set, reduced by dropping options in halves, then quarters, …
/// while the program still gives the same error (at the same place).
#[allow(clippy::too_many_arguments)]
fn reproductions(
    found: &[Finding],
    programs: &[Program],
    pack: &PackFiles,
    sets: &[(String, OptionSet)],
    contexts: &[Arc<SetContext>],
    macros: &PreprocessOptions,
    options: &Options,
    known: &KnownValid,
) -> BTreeMap<String, OptionSet> {
    let under_defaults: HashSet<String> =
        found.iter().filter(|f| sets[f.set].1.is_empty()).map(|f| f.diagnostic.to_string()).collect();
    // Per distinct error: the finding with the smallest set.
    let mut smallest: BTreeMap<String, usize> = BTreeMap::new();
    for (index, f) in found.iter().enumerate() {
        let key = f.diagnostic.to_string();
        if !f.diagnostic.is_error() || under_defaults.contains(&key) {
            continue;
        }
        let entry = smallest.entry(key).or_insert(index);
        if sets[f.set].1.len() < sets[found[*entry].set].1.len() {
            *entry = index;
        }
    }
    let chosen: Vec<usize> = smallest.into_values().take(MAX_REDUCED_ERRORS).collect();
    let reduced: Vec<(usize, OptionSet)> = chosen
        .par_iter()
        .map(|&index| {
            let f = &found[index];
            let program = &programs[f.program];
            let shows = |set: &OptionSet| {
                let provider = SetProvider::new(pack, set);
                let (diagnostics, stages) = check_pair(program, &provider, macros, &contexts[f.set].names, options);
                // The whole diagnostic: naga's errors without a line differ only in the note
                // that names their file.
                let same = |d: &Diagnostic| *d == f.diagnostic;
                diagnostics.iter().any(same) || {
                    let jobs: Vec<Job> = stages.into_iter().map(|stage| Job { stage, set: 0, position_optional: !program.other_stages.is_empty() }).collect();
                    let mut frontend = tidepack_glsl::naga_check::Frontend::default();
                    jobs.iter().any(|job| naga_pool::check_one(&mut frontend, job, pack, set, known).iter().any(same))
                }
            };
            let mut needed: Vec<(String, tidepack_loader::option_lines::OptionValue)> =
                sets[f.set].1.iter().map(|(k, v)| (k.clone(), v.clone())).collect();
            let mut chunk = needed.len().div_ceil(2);
            while chunk >= 1 && !needed.is_empty() {
                let mut start = 0;
                while start < needed.len() {
                    let end = (start + chunk).min(needed.len());
                    let trial: OptionSet = needed[..start].iter().chain(&needed[end..]).cloned().collect();
                    if shows(&trial) {
                        needed.drain(start..end);
                    } else {
                        start = end;
                    }
                }
                chunk /= 2;
            }
            (index, needed.into_iter().collect())
        })
        .collect();
    reduced.into_iter().map(|(index, set)| (found[index].diagnostic.to_string(), set)).collect()
}

/// The option sets a diagnostic was seen under, for its note: the few with the fewest options
/// first (the shortest command line that shows it), then how many more.
fn sets_named(sets: &[(String, OptionSet)], in_sets: &BTreeSet<usize>) -> String {
    const SHOWN: usize = 3;
    let mut named: Vec<usize> = in_sets.iter().copied().collect();
    named.sort_by_key(|&s| (sets[s].1.len(), s));
    let mut text = named.iter().take(SHOWN).map(|&s| sets[s].0.as_str()).collect::<Vec<_>>().join(", ");
    if named.len() > SHOWN {
        text.push_str(&format!(" and {} other option sets", named.len() - SHOWN));
    }
    text
}

/// Where a pair's checks stand before naga.
enum Checked {
    /// `program.<name>.enabled` turns the program off under the set.
    Off,
    /// Found in the cache: everything the pair gave.
    Cached(Vec<Diagnostic>),
    /// Checked now: the diagnostics so far and the lowered stages for naga, with the pair's
    /// cache key when there is a cache.
    Fresh { key: Option<cache::Key>, diagnostics: Vec<Diagnostic>, stages: Vec<JobStage> },
}

/// What shaders.properties says under one option set.
struct SetContext {
    names: CustomNames,
    /// Program names turned off, per world folder.
    disabled: BTreeMap<String, Vec<String>>,
    problems: Vec<String>,
}

/// Preprocesses, lowers and checks every stage of a program under one set (naga aside).
fn check_pair(
    program: &Program,
    provider: &SetProvider,
    macros: &PreprocessOptions,
    names: &CustomNames,
    options: &Options,
) -> (Vec<Diagnostic>, Vec<JobStage>) {
    let mut diagnostics = preprocess_other_stages(program, provider, macros, options.driver);
    let mut stages = Vec::new();
    if !program.stages.is_empty() {
        match check_program(program, provider, macros, names, options.loader) {
            Ok((lowered, diags)) => {
                diagnostics.extend(diags);
                stages.extend(lowered.into_iter().map(JobStage::Graphics));
            }
            Err(diags) => diagnostics.extend(diags),
        }
    }
    for path in &program.compute {
        let (lowered, diags) = check_compute(path, &program.name, provider, macros, names, options.loader);
        diagnostics.extend(diags);
        stages.extend(lowered.map(JobStage::Compute));
    }
    (diagnostics, stages)
}

/// Compiles every validated program with the OpenGL driver, adds its errors to `found` and
/// compares verdicts.
#[allow(clippy::too_many_arguments)]
fn run_driver(
    programs: &[Program],
    pack: &PackFiles,
    sets: &[(String, OptionSet)],
    pairs: &[Pair],
    off_under: &HashSet<(usize, usize)>,
    options: &Options,
    found: &mut Vec<Finding>,
    unsupported: &mut Vec<(usize, String)>,
) -> Result<driver::DriverSummary, Diagnostic> {
    let gl = driver::Driver::new(&options.macros)?;
    let mut summary = driver::DriverSummary { driver: gl.describe(), ..Default::default() };
    for &Pair { program: index, set: set_index, .. } in pairs {
        let (label, set) = &sets[set_index];
        let program = &programs[index];
        let provider = SetProvider::new(pack, set);
        {
            if off_under.contains(&(index, set_index)) {
                continue;
            }
            let ours = found
                .iter()
                .any(|f| {
                    f.program == index
                        && f.set == set_index
                        && f.diagnostic.is_error()
                        && !f.diagnostic.refused_by.intersection(Drivers::MESA).is_empty()
                        && !driver::is_loader_level(&f.diagnostic)
                });
            let name = if sets.len() > 1 { format!("{} ({label})", program.id()) } else { program.id() };
            for diag in gl.unsupported(program) {
                if let Some(at) = &diag.location {
                    unsupported.push((index, at.path.clone()));
                }
                found.push(Finding { program: index, set: set_index, diagnostic: diag });
            }
            match gl.check(program, &provider) {
                Err(why) => summary.not_compared.push(format!("{name} ({why})")),
                Ok(Ok(())) if ours => {
                    let entry = program.entry().map(|s| Location::line(s.to_string(), 1));
                    let diag = Diagnostic::warning(
                        Code::DriverAccepts,
                        format!("the OpenGL driver ({}) compiles and links {}: tidepack's errors in it may be false", summary.driver, program.id()),
                        entry,
                    );
                    found.push(Finding { program: index, set: set_index, diagnostic: diag });
                    summary.only_tidepack_rejects.push(name);
                }
                Ok(Ok(())) => summary.both_accept += 1,
                Ok(Err(diags)) if diags.is_empty() => {}
                Ok(Err(_)) if ours => summary.both_reject += 1,
                Ok(Err(diags)) => {
                    summary.only_driver_rejects.push(name);
                    found.extend(diags.into_iter().map(|diagnostic| Finding { program: index, set: set_index, diagnostic }));
                }
            }
        }
    }
    Ok(summary)
}
