//! `tidepack validate`: checks any OptiFine shader pack (folder or zip) the way OptiFine loads
//! it, without a game or a GPU.
//!
//! Data flow: [`input::read_pack`] (in memory, hostile input refused entry by entry) →
//! [`programs::find_programs`] (world folders, program names, other loaders' programs) →
//! option sets (defaults, `shaders.properties` profiles) → per program and set, in `stages`:
//! `tidepack_glsl::preprocess` with OptiFine's standard macros → `naga_check::lower_program`
//! and the checks of [`interface`] and [`version_rules`] → in `naga_pool`: naga on each
//! distinct lowered text once, in parallel, panics caught, its messages put in the pack's
//! terms by `messages` → here: diagnostics located in the pack's files, each once, in a
//! [`Report`].

use std::collections::{BTreeMap, BTreeSet, HashSet};
use std::time::Instant;

use tidepack_glsl::{Diagnostic, Location};
use tidepack_loader::directives::custom_names;
use tidepack_loader::input::{self, Limits, PackFiles};
use tidepack_loader::macros::StandardMacros;
use tidepack_loader::option_lines::{OptionKind, OptionSet};
use tidepack_loader::option_space::{self, declared_options, property_macros};
use tidepack_loader::programs::{self, Program, RunBy};
use tidepack_loader::properties::{self, Properties};
use tidepack_loader::{Configuration, Dimension, Loader, SetProvider};

pub mod driver;
pub mod fuzz;
pub mod glslang;
pub mod interface;
mod messages;
mod naga_pool;
pub mod output;
mod report;
mod stages;
pub mod glsl_rules;
pub mod version_rules;

pub use messages::unlower_names;
pub use naga_pool::MAX_NAGA_LINES;
pub use report::{ProgramReport, Report, Status};
pub use stages::other_stage_kind;

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
}

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

/// The option sets to validate under, labelled: the defaults, a profile or every profile
/// (`options.profiles`), each with `options.overrides` over it. Profile warnings join
/// `diagnostics`; an unknown profile, option or value is an error.
fn option_sets(
    props: &Properties,
    declared: &BTreeMap<String, OptionKind>,
    options: &Options,
    diagnostics: &mut Vec<Diagnostic>,
) -> Result<Vec<(String, OptionSet)>, Diagnostic> {
    let mut sets: Vec<(String, OptionSet)> = Vec::new();
    let profile = |name: &str, sets: &mut Vec<(String, OptionSet)>, diagnostics: &mut Vec<Diagnostic>| -> Result<(), Diagnostic> {
        let (set, warnings) = option_space::profile_set(props, name, declared)?;
        diagnostics.extend(warnings);
        sets.push((format!("profile {name}"), set));
        Ok(())
    };
    match &options.profiles {
        Profiles::Defaults => sets.push(("defaults".into(), OptionSet::new())),
        Profiles::Named(name) => profile(name, &mut sets, diagnostics)?,
        Profiles::All => {
            sets.push(("defaults".into(), OptionSet::new()));
            for name in option_space::profiles(props).keys() {
                if let Err(e) = profile(name, &mut sets, diagnostics) {
                    diagnostics.push(e);
                }
            }
        }
    }
    if !options.overrides.is_empty() {
        let configuration = Configuration { options: options.overrides.clone(), ..Configuration::default() };
        let (overrides, _) = configuration.option_set(props, declared).map_err(|e| Diagnostic::error(e, None))?;
        let named: Vec<String> = options.overrides.iter().map(|(n, v)| format!("{n}={v}")).collect();
        for (label, set) in &mut sets {
            set.extend(overrides.clone());
            *label = format!("{label} with {}", named.join(" "));
        }
    }
    Ok(sets)
}

/// Validates a pack already in memory.
pub fn validate_pack(pack: PackFiles, options: &Options) -> Result<Report, Diagnostic> {
    let started = Instant::now();
    let declared = declared_options(&pack);
    let properties_text = pack.texts.get(properties::PATH).map_or("", |t| &**t);
    // Profiles are read under the defaults; each set's own reading decides its custom names.
    let props = Properties::parse(properties_text, &property_macros(&options.macros, &declared, &OptionSet::new()));
    let mut diagnostics: Vec<Diagnostic> = pack.warnings.clone();
    // OptiFine takes a conditional line it cannot evaluate as false and says so in its log.
    diagnostics.extend(props.problems.iter().map(|(line, problem)| Diagnostic::warning(problem.clone(), Some(Location::line(properties::PATH, *line)))));
    let sets = option_sets(&props, &declared, options, &mut diagnostics)?;
    let mut programs = programs::find_programs(pack.files.keys());
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
    let macros = options.macros.preprocess_options();
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
                _ if programs::runs(&p.name, options.loader) => Status::Valid,
                RunBy::Other(who) => Status::Skipped(format!("run by {who}; not validated under {}", options.loader)),
                _ => Status::Skipped("no loader runs a program of this name; not validated".into()),
            },
            compile_error: false,
            only_preprocessed: if programs::runs(&p.name, options.loader) && !options.driver { p.other_stages.clone() } else { Vec::new() },
            diagnostics: Vec::new(),
        })
        .collect();
    let mut found: Vec<Finding> = Vec::new();
    let mut jobs: Vec<Job> = Vec::new();
    let mut seen: HashSet<(String, String)> = HashSet::new();
    // (program, option set) pairs under which `program.<name>.enabled` turns the program off.
    let mut off_under: HashSet<(usize, usize)> = HashSet::new();
    for (set_index, (_, set)) in sets.iter().enumerate() {
        let provider = SetProvider::new(&pack, set);
        let set_properties = Properties::parse(properties_text, &property_macros(&options.macros, &declared, set));
        let names = custom_names(&set_properties);
        // `program.<name>.enabled` entries turn programs off under this set, per world folder.
        let mut disabled: BTreeMap<&str, Vec<String>> = BTreeMap::new();
        for (index, program) in programs.iter().enumerate() {
            if !programs::runs(&program.name, options.loader) || !program.has_stages() {
                continue;
            }
            let off = disabled.entry(program.world.as_str()).or_insert_with(|| {
                let (off, problems) = programs::disabled_programs(&set_properties, &program.world, &declared, set);
                for problem in problems.into_iter().map(|p| Diagnostic::warning(p, None)) {
                    if !diagnostics.contains(&problem) {
                        diagnostics.push(problem);
                    }
                }
                off
            });
            if off.contains(&program.name) {
                off_under.insert((index, set_index));
                continue;
            }
            let diags = preprocess_other_stages(program, &provider, &macros, options.driver);
            found.extend(diags.into_iter().map(|diagnostic| Finding { program: index, set: set_index, diagnostic }));
            let position_optional = !program.other_stages.is_empty();
            let mut push = |stage: JobStage, jobs: &mut Vec<Job>| {
                let path = stage.preprocessed().files[0].clone();
                if seen.insert((path, stage.text().to_string())) {
                    jobs.push(Job { stage, set: set_index, program: index, position_optional });
                }
            };
            if !program.stages.is_empty() {
                match check_program(program, &provider, &macros, &names, options.loader) {
                    Ok((lowered, diags)) => {
                        found.extend(diags.into_iter().map(|diagnostic| Finding { program: index, set: set_index, diagnostic }));
                        for stage in lowered {
                            push(JobStage::Graphics(stage), &mut jobs);
                        }
                    }
                    Err(diags) => found.extend(diags.into_iter().map(|diagnostic| Finding { program: index, set: set_index, diagnostic })),
                }
            }
            for path in &program.compute {
                let (lowered, diags) = check_compute(path, &program.name, &provider, &macros, &names, options.loader);
                found.extend(diags.into_iter().map(|diagnostic| Finding { program: index, set: set_index, diagnostic }));
                if let Some(stage) = lowered {
                    push(JobStage::Compute(stage), &mut jobs);
                }
            }
        }
    }
    for (index, report) in reports.iter_mut().enumerate() {
        let off = off_under.iter().filter(|(program, _)| *program == index).count();
        if off == sets.len() && report.status == Status::Valid {
            let key = format!("program.{}.enabled", report.id);
            report.status = Status::Skipped(format!("turned off by {key} in shaders.properties under every option set validated"));
        }
    }
    let stages_validated = jobs.len();
    if let Some(message) = dimension_without_programs {
        // A pack may shade some dimensions only: nothing to check is the answer here.
        diagnostics.push(Diagnostic::warning(message, None));
    } else if !reports.iter().any(|r| r.status == Status::Valid) && !found.iter().any(|f| f.diagnostic.is_error()) {
        // A CI check that checked nothing must not pass.
        let skipped: Vec<String> = reports.iter().map(|r| r.id.clone()).collect();
        let mut diag = Diagnostic::error(format!("no program that {} runs was found, so nothing was validated", options.loader), None);
        if !skipped.is_empty() {
            diag = diag.with_note(format!("found only programs other loaders run: {}", skipped.join(", ")));
        }
        diagnostics.push(diag);
    }
    // naga's error at a line where a GLSL rule already named the mistake says the same in
    // naga's words: the rule's message stands alone.
    let explained: HashSet<(String, u32)> = found
        .iter()
        .filter(|f| f.diagnostic.is_error())
        .filter_map(|f| f.diagnostic.location.as_ref().map(|l| (l.path.clone(), l.line)))
        .collect();
    let naga_findings = naga_pool::run_naga(&jobs, &pack, &sets, options.threads);
    found.extend(naga_findings.into_iter().filter(|f| {
        let at = f.diagnostic.location.as_ref().map(|l| (l.path.clone(), l.line));
        !(f.diagnostic.is_error() && at.is_some_and(|at| explained.contains(&at)))
    }));
    let driver_summary = if options.driver {
        let mut unsupported = Vec::new();
        let summary = run_driver(&programs, &pack, &sets, &off_under, options, &mut found, &mut unsupported)?;
        for (program, path) in unsupported {
            if !reports[program].only_preprocessed.contains(&path) {
                reports[program].only_preprocessed.push(path);
            }
        }
        Some(summary)
    } else {
        None
    };
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
    for (diag, in_programs, in_sets) in distinct.into_values() {
        let ids: Vec<String> = in_programs.iter().map(|&p| programs[p].id()).collect();
        let mut context = match ids.as_slice() {
            [one] => format!("in program {one}"),
            _ => format!("in programs {}", ids.join(", ")),
        };
        if sets.len() > 1 || sets.iter().any(|(_, set)| !set.is_empty()) {
            let labels: Vec<&str> = in_sets.iter().map(|&s| sets[s].0.as_str()).collect();
            context.push_str(&format!(" with {}", labels.join(", ")));
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
        stages_validated,
        elapsed: started.elapsed(),
        driver: driver_summary,
    })
}

/// Compiles every validated program with the OpenGL driver, adds its errors to `found` and
/// compares verdicts.
#[allow(clippy::too_many_arguments)]
fn run_driver(
    programs: &[Program],
    pack: &PackFiles,
    sets: &[(String, OptionSet)],
    off_under: &HashSet<(usize, usize)>,
    options: &Options,
    found: &mut Vec<Finding>,
    unsupported: &mut Vec<(usize, String)>,
) -> Result<driver::DriverSummary, Diagnostic> {
    let gl = driver::Driver::new(&options.macros)?;
    let mut summary = driver::DriverSummary { driver: gl.describe(), ..Default::default() };
    for (set_index, (label, set)) in sets.iter().enumerate() {
        let provider = SetProvider::new(pack, set);
        for (index, program) in programs.iter().enumerate() {
            if !programs::runs(&program.name, options.loader) || !program.has_stages() || off_under.contains(&(index, set_index)) {
                continue;
            }
            let ours = found
                .iter()
                .any(|f| f.program == index && f.set == set_index && f.diagnostic.is_error() && !driver::is_loader_level(&f.diagnostic));
            let name = if sets.len() > 1 { format!("{} ({label})", program.id()) } else { program.id() };
            for diag in gl.unsupported(program) {
                if let Some(at) = &diag.location {
                    unsupported.push((index, at.path.clone()));
                }
                found.push(Finding { program: index, set: set_index, diagnostic: diag });
            }
            match gl.check(program, &provider) {
                Ok(()) if ours => {
                    let entry = program.entry().map(|s| Location::line(s.to_string(), 1));
                    let diag = Diagnostic::warning(
                        format!("the OpenGL driver ({}) compiles and links {}: tidepack's errors in it may be false", summary.driver, program.id()),
                        entry,
                    );
                    found.push(Finding { program: index, set: set_index, diagnostic: diag });
                    summary.only_tidepack_rejects.push(name);
                }
                Ok(()) => summary.both_accept += 1,
                Err(diags) if diags.is_empty() => {}
                Err(_) if ours => summary.both_reject += 1,
                Err(diags) => {
                    summary.only_driver_rejects.push(name);
                    found.extend(diags.into_iter().map(|diagnostic| Finding { program: index, set: set_index, diagnostic }));
                }
            }
        }
    }
    Ok(summary)
}
