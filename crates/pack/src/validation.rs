//! Validation of every program under every option set that changes its text.
//!
//! Which options matter is discovered, not declared: a program's stages are preprocessed with
//! the default values, the options the preprocessor consulted become relevant, and the sets are
//! the combinations of the relevant options' values; options found only under some of those
//! sets join and the search repeats until it is closed. When the full product grows past
//! [`MAX_EXHAUSTIVE_SETS`], the sets are every combination of the options the program tests in
//! conditionals, with each option that is only substituted as a value varied one at a time.
//! Every set is preprocessed and lowered; identical lowered texts are validated by naga once.

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

use tidepack_glsl::Diagnostic;
use tidepack_glsl::options::{OptionSet, OptionValue};
use tidepack_glsl::preprocess::{self, PreprocessOptions, Preprocessed};
use tidepack_glsl::validate::{self, LoweredStage};

use crate::pack_options::PackOptions;
use crate::shipped::{Program, ShippedPack, WithOptions};

/// Largest number of option sets per program validated as a full product.
pub const MAX_EXHAUSTIVE_SETS: usize = 4096;

#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ValidationReport {
    pub programs: usize,
    /// Option sets over all programs.
    pub option_sets: usize,
    /// Stages naga parsed and validated.
    pub stages_validated: usize,
    /// Stages skipped because an identical lowered text was validated already.
    pub stages_identical: usize,
    /// False when some program's sets were reduced (see the module docs).
    pub exhaustive: bool,
    /// The stages naga validated: shipped path and the first option set that gave its text.
    pub validated: Vec<(String, OptionSet)>,
}

/// OptiFine's standard macros for a typical modern setup, so packs that test them validate.
pub fn standard_macros(glsl_version: u32) -> PreprocessOptions {
    let predefined = [
        ("MC_VERSION", "12104"),
        ("MC_GL_VERSION", "460"),
        ("MC_GLSL_VERSION", &glsl_version.to_string()),
        ("MC_OS_LINUX", "1"),
        ("MC_GL_VENDOR_MESA", "1"),
        ("MC_GL_RENDERER_MESA", "1"),
        ("MC_RENDER_QUALITY", "1.0"),
        ("MC_SHADOW_QUALITY", "1.0"),
        ("MC_HAND_DEPTH", "0.125"),
        ("MC_NORMAL_MAP", "1"),
        ("MC_SPECULAR_MAP", "1"),
    ];
    PreprocessOptions { predefined: predefined.iter().map(|(k, v)| (k.to_string(), v.to_string())).collect() }
}

struct ProgramSets {
    /// Each option set with the preprocessed stages it gives.
    runs: Vec<(OptionSet, Vec<Arc<Preprocessed>>)>,
    exhaustive: bool,
}

/// Validates every program of `pack`; diagnostics point at shipped files.
pub fn validate_pack(pack: &ShippedPack, options: &PackOptions) -> Result<ValidationReport, Vec<Diagnostic>> {
    let glsl_version = match pack.dialect {
        crate::dialect::Dialect::Glsl120 => 120,
        crate::dialect::Dialect::Glsl330 => 330,
    };
    let macros = standard_macros(glsl_version);
    let mut report = ValidationReport { exhaustive: true, ..Default::default() };
    let mut errors: Vec<(Diagnostic, OptionSet)> = Vec::new();
    // Unique lowered stages to validate, each with the first option set that produced it.
    let mut unique: Vec<(LoweredStage, OptionSet)> = Vec::new();
    let mut seen: HashMap<(String, String), ()> = HashMap::new();
    for program in pack.programs() {
        report.programs += 1;
        let sets = match option_sets(pack, &program, options, &macros) {
            Ok(sets) => sets,
            Err((diag, set)) => {
                errors.push((diag, set));
                continue;
            }
        };
        report.exhaustive &= sets.exhaustive;
        report.option_sets += sets.runs.len();
        for (set, stages) in sets.runs {
            let with_stage: Vec<_> = program.stages.iter().map(|(s, _)| *s).zip(stages).collect();
            match validate::lower_program(&with_stage) {
                Ok(lowered) => {
                    for (stage, (_, path)) in lowered.into_iter().zip(&program.stages) {
                        if seen.insert((path.clone(), stage.lowered.text.clone()), ()).is_some() {
                            report.stages_identical += 1;
                        } else {
                            unique.push((stage, set.clone()));
                        }
                    }
                }
                Err(diag) => errors.push((diag, set)),
            }
        }
    }
    report.stages_validated = unique.len();
    report.validated = unique.iter().map(|(stage, set)| (stage.preprocessed.files[0].clone(), set.clone())).collect();
    errors.extend(validate_in_parallel(pack, &unique));
    if errors.is_empty() {
        return Ok(report);
    }
    // One diagnostic per distinct error, noting the options of the first set that shows it.
    let mut distinct: BTreeMap<String, Diagnostic> = BTreeMap::new();
    for (diag, set) in errors {
        let key = diag.to_string();
        distinct.entry(key).or_insert_with(|| diag.with_note(describe_set(&set)));
    }
    Err(distinct.into_values().collect())
}

fn describe_set(set: &OptionSet) -> String {
    if set.is_empty() {
        "with the default options".into()
    } else {
        let parts: Vec<String> = set.iter().map(|(k, v)| format!("{k}={v}")).collect();
        format!("with options {}", parts.join(" "))
    }
}

fn validate_in_parallel(pack: &ShippedPack, unique: &[(LoweredStage, OptionSet)]) -> Vec<(Diagnostic, OptionSet)> {
    let next = AtomicUsize::new(0);
    let workers = std::thread::available_parallelism().map_or(2, |n| n.get()).min(unique.len().max(1));
    std::thread::scope(|scope| {
        let handles: Vec<_> = (0..workers)
            .map(|_| {
                scope.spawn(|| {
                    let mut frontend = validate::Frontend::default();
                    let mut found = Vec::new();
                    loop {
                        let i = next.fetch_add(1, Ordering::Relaxed);
                        let Some((stage, set)) = unique.get(i) else { break };
                        let provider = WithOptions::new(pack, set);
                        if let Err(diags) = validate::validate_stage(&mut frontend, stage, &provider) {
                            found.extend(diags.into_iter().map(|d| (d, set.clone())));
                        }
                    }
                    found
                })
            })
            .collect();
        handles.into_iter().flat_map(|h| h.join().expect("validation worker panicked")).collect()
    })
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

fn option_sets(
    pack: &ShippedPack,
    program: &Program,
    options: &PackOptions,
    macros: &PreprocessOptions,
) -> Result<ProgramSets, (Diagnostic, OptionSet)> {
    let mut relevant: BTreeSet<String> = BTreeSet::new();
    let mut tested: BTreeSet<String> = BTreeSet::new();
    let mut cache: BTreeMap<OptionSet, Vec<Arc<Preprocessed>>> = BTreeMap::new();
    loop {
        let (sets, exhaustive) = enumerate(&relevant, &tested, options);
        let mut grew = false;
        for set in &sets {
            if !cache.contains_key(set) {
                let stages = run_set(pack, program, set, macros).map_err(|d| (d, set.clone()))?;
                cache.insert(set.clone(), stages);
            }
            for pre in &cache[set] {
                for name in pre.consulted_macros.iter().filter(|n| options.contains_key(*n)) {
                    grew |= relevant.insert(name.clone());
                }
                for name in pre.tested_macros.iter().filter(|n| options.contains_key(*n)) {
                    grew |= tested.insert(name.clone());
                }
            }
        }
        if !grew {
            let runs = sets.into_iter().map(|set| {
                let stages = cache[&set].clone();
                (set, stages)
            });
            return Ok(ProgramSets { runs: runs.collect(), exhaustive });
        }
    }
}

/// The option sets for the relevant options. Options at their default are left out of a set,
/// so a set means the same whichever options are relevant.
fn enumerate(relevant: &BTreeSet<String>, tested: &BTreeSet<String>, options: &PackOptions) -> (Vec<OptionSet>, bool) {
    let choices = |name: &String| -> Vec<Option<OptionValue>> {
        let kind = &options[name].kind;
        let default = kind.default_value();
        kind.all_values().into_iter().map(|v| (v != default).then_some(v)).collect()
    };
    let full: usize = relevant.iter().map(|n| choices(n).len()).product();
    let product_over = |names: &[&String]| {
        let mut sets = vec![OptionSet::new()];
        for name in names {
            let mut next = Vec::with_capacity(sets.len() * 2);
            for set in &sets {
                for value in choices(name) {
                    let mut s = set.clone();
                    if let Some(v) = value {
                        s.insert((*name).clone(), v);
                    }
                    next.push(s);
                }
            }
            sets = next;
        }
        sets
    };
    if full <= MAX_EXHAUSTIVE_SETS {
        let names: Vec<&String> = relevant.iter().collect();
        return (product_over(&names), true);
    }
    let structural: Vec<&String> = relevant.iter().filter(|n| tested.contains(*n)).collect();
    let mut sets = product_over(&structural);
    for name in relevant.iter().filter(|n| !tested.contains(*n)) {
        for value in choices(name).into_iter().flatten() {
            sets.push([(name.clone(), value)].into());
        }
    }
    (sets, false)
}
