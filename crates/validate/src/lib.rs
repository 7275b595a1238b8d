//! `tidepack validate`: checks any OptiFine shader pack (folder or zip) the way OptiFine loads
//! it, without a game or a GPU.
//!
//! Data flow: [`input::read_pack`] (in memory, hostile input refused entry by entry) →
//! [`programs::find_programs`] (world folders, program names, other loaders' programs) →
//! option sets (defaults, `shaders.properties` profiles) → per program and set:
//! `tidepack_glsl::preprocess` with OptiFine's standard macros → `validate::lower_program` →
//! naga (each distinct lowered text once, in parallel, panics caught) and the checks of
//! [`interface`] → diagnostics located in the pack's files.

use std::collections::{BTreeMap, BTreeSet, HashMap, HashSet};
use std::panic::AssertUnwindSafe;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use tidepack_glsl::macros::StandardMacros;
use tidepack_glsl::options::{self, OptionKind, OptionSet};
use tidepack_glsl::preprocess::{self, FileProvider, PreprocessOptions, Preprocessed};
use tidepack_glsl::validate::{self, LoweredCompute, LoweredStage};
use tidepack_glsl::{Diagnostic, Location, Stage};

pub mod input;
pub mod interface;
pub mod driver;
pub mod fuzz;
pub mod glslang;
pub mod known;
pub mod output;
pub mod programs;
pub mod properties;
pub mod version_rules;

pub use input::{Limits, PackFiles};
pub use programs::{Loader, Program};

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
            limits: Limits::default(),
            threads: std::thread::available_parallelism().map_or(2, |n| n.get()),
            driver: false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reserved_names_read_as_the_packs() {
        assert_eq!(unlower_names("found Identifier(\"tp_FragData0\")"), "found Identifier(\"gl_FragData[0]\")");
        assert_eq!(unlower_names("tp_sampler_colortex0 and tp_Vertex, tp_TexCoord3; stp_x"), "colortex0 and gl_Vertex, gl_TexCoord[3]; stp_x");
    }

    #[test]
    fn a_stage_without_version_is_glsl_110() {
        let files: HashMap<String, Arc<str>> =
            [("final.fsh".to_string(), Arc::from("uniform sampler2D composite;\nvoid main() {}\n"))].into();
        let mut pre = preprocess::preprocess(&files, "final.fsh", &PreprocessOptions::default()).unwrap();
        assume_glsl_110(&mut pre);
        assert!(pre.text.starts_with("#version 110\nuniform sampler2D composite;\n"), "{}", pre.text);
        assert_eq!(pre.text.lines().count(), pre.lines.len());
        assert_eq!(pre.location(2), Some(Location::line("final.fsh", 1)));
    }

}

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
    /// Distinct lowered stages naga validated.
    pub stages_validated: usize,
    pub elapsed: Duration,
    /// With [`Options::driver`]: how the driver's verdicts compare with tidepack's.
    pub driver: Option<driver::DriverSummary>,
}

impl Report {
    pub fn errors(&self) -> usize {
        self.diagnostics.iter().filter(|d| d.is_error()).count()
    }

    pub fn warnings(&self) -> usize {
        self.diagnostics.len() - self.errors()
    }

    /// Text of a pack file, for snippets.
    pub fn source_of(&self, path: &str) -> Option<String> {
        self.pack.texts.get(path).map(|t| t.to_string())
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

/// A pack's files with one option set applied, as OptiFine rewrites the option lines.
pub struct SetProvider<'a> {
    pack: &'a PackFiles,
    set: &'a OptionSet,
    cache: Mutex<HashMap<String, Arc<str>>>,
}

impl<'a> SetProvider<'a> {
    pub fn new(pack: &'a PackFiles, set: &'a OptionSet) -> Self {
        SetProvider { pack, set, cache: Mutex::new(HashMap::new()) }
    }
}

impl FileProvider for SetProvider<'_> {
    fn read(&self, path: &str) -> Result<Arc<str>, String> {
        if let Some(text) = self.cache.lock().unwrap_or_else(|e| e.into_inner()).get(path) {
            return Ok(text.clone());
        }
        let decoded;
        let text = match (self.pack.texts.get(path), self.pack.files.get(path)) {
            (Some(text), _) => text,
            // OptiFine includes a file of any name (`Common.vert`, `lib.inc`): read it as text.
            (None, Some(bytes)) => match std::str::from_utf8(bytes) {
                Ok(text) => {
                    decoded = Arc::from(text);
                    &decoded
                }
                Err(e) => return Err(format!("not a text file: byte {} is not UTF-8", e.valid_up_to())),
            },
            (None, None) => {
            let lower = path.to_lowercase();
            return Err(match self.pack.files.keys().find(|p| p.to_lowercase() == lower) {
                Some(p) => format!("no such file in the pack; `{p}` differs only in case (Iris and Linux are case-sensitive)"),
                None => "no such file in the pack".into(),
            });
            }
        };
        let text: Arc<str> = match options::apply(text, self.set) {
            std::borrow::Cow::Borrowed(_) => text.clone(),
            std::borrow::Cow::Owned(t) => Arc::from(t),
        };
        self.cache.lock().unwrap_or_else(|e| e.into_inner()).insert(path.to_string(), text.clone());
        Ok(text)
    }
}

/// Options declared in the pack's shader sources (first declaration wins).
pub fn declared_options(pack: &PackFiles) -> BTreeMap<String, OptionKind> {
    let mut found = BTreeMap::new();
    for (path, text) in &pack.texts {
        if path.ends_with(".properties") || path.ends_with(".lang") || path.ends_with(".txt") {
            continue;
        }
        for decl in options::scan(text) {
            found.entry(decl.name).or_insert(decl.kind);
        }
    }
    found
}

/// One distinct lowered stage for naga, with the program and option set that produced it.
struct Job {
    stage: JobStage,
    set: usize,
    program: usize,
    /// A vertex stage followed by a geometry or tessellation stage need not write
    /// `gl_Position`, which naga requires of every vertex stage.
    position_optional: bool,
}

/// naga's complaint about a vertex stage that does not write `gl_Position`.
const POSITION_REQUIRED: &str = "must return a `@builtin(position)` output";

enum JobStage {
    Graphics(LoweredStage),
    Compute(LoweredCompute),
}

impl JobStage {
    fn preprocessed(&self) -> &Preprocessed {
        match self {
            JobStage::Graphics(s) => &s.preprocessed,
            JobStage::Compute(s) => &s.preprocessed,
        }
    }

    fn text(&self) -> &str {
        match self {
            JobStage::Graphics(s) => &s.lowered.text,
            JobStage::Compute(s) => &s.lowered.text,
        }
    }
}

/// Validates a pack already in memory.
pub fn validate_pack(pack: PackFiles, options: &Options) -> Result<Report, Diagnostic> {
    let started = Instant::now();
    let props = pack.texts.get(properties::PATH).map(|t| properties::parse(t)).unwrap_or_default();
    let declared = declared_options(&pack);
    let mut diagnostics: Vec<Diagnostic> = pack.warnings.clone();
    let mut sets: Vec<(String, OptionSet)> = Vec::new();
    let profile = |name: &str, sets: &mut Vec<(String, OptionSet)>, diagnostics: &mut Vec<Diagnostic>| -> Result<(), Diagnostic> {
        let (set, warnings) = properties::profile_set(&props, name, &declared)?;
        diagnostics.extend(warnings);
        sets.push((format!("profile {name}"), set));
        Ok(())
    };
    match &options.profiles {
        Profiles::Defaults => sets.push(("defaults".into(), OptionSet::new())),
        Profiles::Named(name) => profile(name, &mut sets, &mut diagnostics)?,
        Profiles::All => {
            sets.push(("defaults".into(), OptionSet::new()));
            for name in props.profiles.keys() {
                if let Err(e) = profile(name, &mut sets, &mut diagnostics) {
                    diagnostics.push(e);
                }
            }
        }
    }
    let programs = programs::find_programs(pack.files.keys());
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
            status: match &p.loader {
                Loader::OptiFine => Status::Valid,
                Loader::Other(who) => Status::Skipped(format!("run by {who}; not validated")),
                Loader::Unknown => Status::Skipped("no loader runs a program of this name; not validated".into()),
            },
            compile_error: false,
            only_preprocessed: if p.loader == Loader::OptiFine && !options.driver { p.other_stages.clone() } else { Vec::new() },
            diagnostics: Vec::new(),
        })
        .collect();
    // (program index, diagnostic) for everything found before naga.
    let mut found: Vec<(usize, usize, Diagnostic)> = Vec::new();
    let mut jobs: Vec<Job> = Vec::new();
    let mut seen: HashSet<(String, String)> = HashSet::new();
    for (set_index, (_, set)) in sets.iter().enumerate() {
        let provider = SetProvider::new(&pack, set);
        for (index, program) in programs.iter().enumerate() {
            if program.loader != Loader::OptiFine || !program.has_stages() {
                continue;
            }
            let diags = preprocess_other_stages(program, &provider, &macros, options.driver);
            found.extend(diags.into_iter().map(|d| (index, set_index, d)));
            let position_optional = !program.other_stages.is_empty();
            let mut push = |stage: JobStage, jobs: &mut Vec<Job>| {
                let path = stage.preprocessed().files[0].clone();
                if seen.insert((path, stage.text().to_string())) {
                    jobs.push(Job { stage, set: set_index, program: index, position_optional });
                }
            };
            if !program.stages.is_empty() {
                match check_program(program, &provider, &macros, &props) {
                    Ok((lowered, diags)) => {
                        found.extend(diags.into_iter().map(|d| (index, set_index, d)));
                        for stage in lowered {
                            push(JobStage::Graphics(stage), &mut jobs);
                        }
                    }
                    Err(diags) => found.extend(diags.into_iter().map(|d| (index, set_index, d))),
                }
            }
            for path in &program.compute {
                let (lowered, diags) = check_compute(path, &program.name, &provider, &macros, &props);
                found.extend(diags.into_iter().map(|d| (index, set_index, d)));
                if let Some(stage) = lowered {
                    push(JobStage::Compute(stage), &mut jobs);
                }
            }
        }
    }
    let stages_validated = jobs.len();
    if !reports.iter().any(|r| r.status == Status::Valid) && !found.iter().any(|(_, _, d)| d.is_error()) {
        // A CI check that checked nothing must not pass.
        let skipped: Vec<String> = reports.iter().map(|r| r.id.clone()).collect();
        let mut diag = Diagnostic::error("no program that OptiFine runs was found, so nothing was validated", None);
        if !skipped.is_empty() {
            diag = diag.with_note(format!("found only programs other loaders run: {}", skipped.join(", ")));
        }
        diagnostics.push(diag);
    }
    for (program, set, diag) in run_naga(&jobs, &pack, &sets, options.threads) {
        found.push((program, set, diag));
    }
    let driver_summary = if options.driver {
        let mut unsupported = Vec::new();
        let summary = run_driver(&programs, &pack, &sets, options, &mut found, &mut unsupported)?;
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
    // was seen in. naga's results arrive in thread order: everything here is keyed and sorted
    // so that the report does not depend on it.
    let pack_level: BTreeSet<String> = diagnostics.iter().map(|d| d.to_string()).collect();
    let mut distinct: BTreeMap<String, (Diagnostic, BTreeSet<usize>, BTreeSet<usize>)> = BTreeMap::new();
    for (program, set, diag) in found {
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
fn run_driver(
    programs: &[Program],
    pack: &PackFiles,
    sets: &[(String, OptionSet)],
    options: &Options,
    found: &mut Vec<(usize, usize, Diagnostic)>,
    unsupported: &mut Vec<(usize, String)>,
) -> Result<driver::DriverSummary, Diagnostic> {
    let gl = driver::Driver::new(&options.macros)?;
    let mut summary = driver::DriverSummary { driver: gl.describe(), ..Default::default() };
    for (set_index, (label, set)) in sets.iter().enumerate() {
        let provider = SetProvider::new(pack, set);
        for (index, program) in programs.iter().enumerate() {
            if program.loader != Loader::OptiFine || !program.has_stages() {
                continue;
            }
            let ours = found
                .iter()
                .any(|(p, s, d)| *p == index && *s == set_index && d.is_error() && !driver::is_loader_level(d));
            let name = if sets.len() > 1 { format!("{} ({label})", program.id()) } else { program.id() };
            for diag in gl.unsupported(program) {
                if let Some(at) = &diag.location {
                    unsupported.push((index, at.path.clone()));
                }
                found.push((index, set_index, diag));
            }
            match gl.check(program, &provider) {
                Ok(()) if ours => {
                    let entry = program.entry().map(|s| Location::line(s.to_string(), 1));
                    let diag = Diagnostic::warning(
                        format!("the OpenGL driver ({}) compiles and links {}: tidepack's errors in it may be false", summary.driver, program.id()),
                        entry,
                    );
                    found.push((index, set_index, diag));
                    summary.only_tidepack_rejects.push(name);
                }
                Ok(()) => summary.both_accept += 1,
                Err(diags) if diags.is_empty() => {}
                Err(_) if ours => summary.both_reject += 1,
                Err(diags) => {
                    summary.only_driver_rejects.push(name);
                    found.extend(diags.into_iter().map(|d| (index, set_index, d)));
                }
            }
        }
    }
    Ok(summary)
}

/// Preprocesses and lowers a program's stages and runs the checks that need no naga.
fn check_program(
    program: &Program,
    provider: &dyn FileProvider,
    macros: &PreprocessOptions,
    props: &properties::Properties,
) -> Result<(Vec<LoweredStage>, Vec<Diagnostic>), Vec<Diagnostic>> {
    let mut diags = Vec::new();
    let mut preprocessed = Vec::new();
    for (stage, path) in &program.stages {
        match preprocess::preprocess(provider, path, macros) {
            Ok(mut pre) => {
                assume_glsl_110(&mut pre);
                diags.extend(pre.warnings.iter().cloned());
                diags.extend(version_rules::check(&pre, *stage));
                preprocessed.push((*stage, Arc::new(pre)));
            }
            Err(e) => {
                diags.push(e);
                return Err(diags);
            }
        }
    }
    // With a geometry or tessellation stage between them, vertex and fragment do not talk
    // directly.
    let linked = program.other_stages.is_empty();
    let groups: Vec<Vec<(Stage, Arc<Preprocessed>)>> =
        if linked { vec![preprocessed.clone()] } else { preprocessed.iter().map(|s| vec![s.clone()]).collect() };
    let mut lowered = Vec::new();
    for group in groups {
        match validate::lower_program(&group) {
            Ok(stages) => lowered.extend(stages),
            Err(e) => {
                diags.push(e);
                return Err(diags);
            }
        }
    }
    let vertex = preprocessed.iter().find(|(s, _)| *s == Stage::Vertex);
    let fragment = preprocessed.iter().find(|(s, _)| *s == Stage::Fragment);
    if let (Some((_, vs)), Some((_, fs)), true) = (vertex, fragment, linked) {
        diags.extend(interface::check_varyings(vs, fs));
    }
    for stage in &lowered {
        if stage.stage == Stage::Fragment {
            diags.extend(interface::check_render_targets(&stage.preprocessed, stage));
        }
        diags.extend(interface::check_resources(&stage.preprocessed, &stage.lowered, &program.name, props));
    }
    Ok((lowered, diags))
}

/// The kind of stage of a geometry or tessellation file, for messages.
pub fn other_stage_kind(path: &str) -> &'static str {
    if path.ends_with(".gsh") {
        "geometry"
    } else if path.ends_with(".tcs") {
        "tessellation control"
    } else {
        "tessellation evaluation"
    }
}

/// Preprocesses a program's geometry and tessellation stages, which naga cannot read: include
/// errors, `#error` and macro errors are reported; without `driver`, a warning per file says it
/// was only preprocessed.
fn preprocess_other_stages(
    program: &Program,
    provider: &dyn FileProvider,
    macros: &PreprocessOptions,
    driver: bool,
) -> Vec<Diagnostic> {
    let mut diags = Vec::new();
    for path in &program.other_stages {
        match preprocess::preprocess(provider, path, macros) {
            Ok(pre) => {
                diags.extend(pre.warnings.iter().cloned());
                if !driver {
                    diags.push(Diagnostic::warning(
                        format!(
                            "{path} was only preprocessed, not compiled: naga has no {} stage; `--driver` compiles it with Mesa",
                            other_stage_kind(path)
                        ),
                        Some(Location::line(path.clone(), 1)),
                    ));
                }
            }
            Err(e) => diags.push(e),
        }
    }
    diags
}

/// Preprocesses and lowers one compute stage and runs the checks that need no naga.
fn check_compute(
    path: &str,
    program: &str,
    provider: &dyn FileProvider,
    macros: &PreprocessOptions,
    props: &properties::Properties,
) -> (Option<LoweredCompute>, Vec<Diagnostic>) {
    let mut pre = match preprocess::preprocess(provider, path, macros) {
        Ok(pre) => pre,
        Err(e) => return (None, vec![e]),
    };
    assume_glsl_110(&mut pre);
    let mut diags: Vec<Diagnostic> = pre.warnings.clone();
    diags.extend(version_rules::check_compute(&pre));
    match validate::lower_compute(Arc::new(pre)) {
        Ok(stage) => {
            diags.extend(interface::check_resources(&stage.preprocessed, &stage.lowered, program, props));
            (Some(stage), diags)
        }
        Err(e) => {
            diags.push(e);
            (None, diags)
        }
    }
}

/// Speaks of the pack's names instead of the lowering's reserved ones in naga's messages, and
/// explains the messages that the lowering makes obscure.
fn clarify(mut diag: Diagnostic) -> Diagnostic {
    diag.message = unlower_names(&diag.message);
    let sampling = ["texture", "textureLod", "textureProj", "textureGrad", "texelFetch", "textureSize", "textureOffset"];
    let unknown = diag.message.strip_prefix("Unknown function '").and_then(|r| r.strip_suffix('\'')).map(str::to_string);
    let unknown_variable = diag.message.strip_prefix("Unknown variable: ").map(str::to_string);
    if let Some(name) = unknown.as_deref().or(unknown_variable.as_deref())
        && NAGA_LACKS.iter().any(|prefix| name.starts_with(prefix))
    {
        // Valid GLSL naga's front-end does not implement: not the pack's mistake.
        let call = if unknown.is_some() { "()" } else { "" };
        diag.severity = tidepack_glsl::Severity::Warning;
        diag.message = format!("{name}{call} is not checked: naga's GLSL front-end does not implement it (`--driver` compiles it with Mesa)");
        return diag;
    }
    if diag.message.contains("Unable to operate on image class Sampled { kind: Uint")
        || diag.message.contains("Unable to operate on image class Sampled { kind: Sint")
    {
        // GLSL samples integer textures (nearest texel); naga only loads from them.
        diag.severity = tidepack_glsl::Severity::Warning;
        diag.message = "sampling an integer texture (isampler*/usampler*) is not checked: naga refuses it, drivers \
                        accept it (`--driver` compiles it with Mesa)"
            .into();
        return diag;
    }
    if let Some(name) = unknown.as_deref()
        && sampling.contains(&name)
    {
        diag = diag.with_note(format!(
            "no form of {name}() (texture2D, shadow2D, … in old GLSL) takes these arguments: check the sampler's type \
             (sampler2D, sampler2DShadow, sampler3D, …) against the coordinates"
        ));
    } else if let Some(name) = unknown.as_deref()
        && matches!(name, "imageLoad" | "imageStore" | "imageSize")
    {
        diag = diag.with_note(format!(
            "no form of {name}() takes these arguments: check the image's type (image2D, uimage2D, image3D, …) against \
             the coordinates (ivec2 for image2D) and the value (vec4 for image*, uvec4 for uimage*, ivec4 for iimage*)"
        ));
    } else if let Some(name) = unknown.as_deref()
        && name.starts_with("atomic")
    {
        diag = diag.with_note(format!("no form of {name}() takes these arguments: atomics take an int or uint variable (shared or in a buffer) and an int or uint value"));
    }
    diag
}

/// Built-in functions and variables (by prefix) naga's GLSL front-end lacks and the lowering has
/// no stand-in for: image atomics (images cannot be function parameters in naga), atomic
/// counters, the subgroup built-ins of `GL_KHR_shader_subgroup_*`, and the `textureGather*` and
/// `textureQueryLod` forms the lowering has no stand-in for (other sampler types).
const NAGA_LACKS: [&str; 6] = ["imageAtomic", "atomicCounter", "subgroup", "gl_Subgroup", "textureGather", "textureQueryLod"];

/// `tp_FragData1` → `gl_FragData[1]`, `tp_sampler_x` → `x`, `tp_Vertex` → `gl_Vertex`, …
pub fn unlower_names(message: &str) -> String {
    let prefix = tidepack_glsl::lower::RESERVED_PREFIX;
    let mut out = String::with_capacity(message.len());
    let mut rest = message;
    while let Some(at) = rest.find(prefix) {
        let word_start = at == 0 || !rest.as_bytes()[at - 1].is_ascii_alphanumeric() && rest.as_bytes()[at - 1] != b'_';
        out.push_str(&rest[..at]);
        let tail = &rest[at + prefix.len()..];
        let len = tail.find(|c: char| !c.is_ascii_alphanumeric() && c != '_').unwrap_or(tail.len());
        let name = &tail[..len];
        if !word_start {
            out.push_str(prefix);
            out.push_str(name);
        } else if let Some(n) = name.strip_prefix("FragData") {
            out.push_str(&format!("gl_FragData[{n}]"));
        } else if let Some(n) = name.strip_prefix("TexCoord").filter(|n| !n.is_empty()) {
            out.push_str(&format!("gl_TexCoord[{n}]"));
        } else if let Some(x) =
            ["sampler_", "bool_", "kw_", "init_", "scalar_"].iter().find_map(|p| name.strip_prefix(p))
        {
            out.push_str(x);
        } else if name == "main" {
            out.push_str("main");
        } else {
            out.push_str("gl_");
            out.push_str(name);
        }
        rest = &tail[len..];
    }
    out.push_str(rest);
    out
}

/// A stage without `#version` is GLSL 1.10 to the driver: say so on an added first line, which
/// the line map attributes to the entry's first line.
pub fn assume_glsl_110(pre: &mut Preprocessed) {
    if pre.version.is_none() && !pre.lines.is_empty() {
        pre.text.insert_str(0, "#version 110\n");
        pre.lines.insert(0, pre.lines[0]);
        pre.version = Some(tidepack_glsl::preprocess::VersionDirective { number: 110, profile: None });
    }
}

/// Longest stage (in lines, after preprocessing) naga is given: its parse time grows
/// quadratically with the number of declarations (200 000 take minutes), and no real pack
/// comes near (the largest known stages have a few thousand lines).
pub const MAX_NAGA_LINES: usize = 40_000;

/// Validates the jobs with naga on `threads` workers; a panic inside naga becomes a warning
/// that the stage was not checked.
fn run_naga(jobs: &[Job], pack: &PackFiles, sets: &[(String, OptionSet)], threads: usize) -> Vec<(usize, usize, Diagnostic)> {
    let next = AtomicUsize::new(0);
    let workers = threads.max(1).min(jobs.len().max(1));
    std::thread::scope(|scope| {
        let handles: Vec<_> = (0..workers)
            .map(|_| {
                std::thread::Builder::new()
                    .stack_size(64 << 20)
                    .spawn_scoped(scope, || {
                        let mut frontend = validate::Frontend::default();
                        let mut found = Vec::new();
                        loop {
                            let i = next.fetch_add(1, Ordering::Relaxed);
                            let Some(job) = jobs.get(i) else { break };
                            let provider = SetProvider::new(pack, &sets[job.set].1);
                            let entry = &job.stage.preprocessed().files[0];
                            let lines = job.stage.text().lines().count();
                            if lines > MAX_NAGA_LINES {
                                let diag = Diagnostic::warning(
                                    format!("not validated: {lines} lines after preprocessing, more than the {MAX_NAGA_LINES} naga is given"),
                                    Some(Location::line(entry.clone(), 1)),
                                );
                                found.push((job.program, job.set, diag));
                                continue;
                            }
                            let result = std::panic::catch_unwind(AssertUnwindSafe(|| {
                                match &job.stage {
                                    JobStage::Graphics(stage) => validate::validate_stage(&mut frontend, stage, &provider).map(|_| ()),
                                    JobStage::Compute(stage) => validate::validate_compute(&mut frontend, stage, &provider).map(|_| ()),
                                }
                            }));
                            match result {
                                Ok(Ok(_)) => {}
                                Ok(Err(diags)) => found.extend(
                                    diags
                                        .into_iter()
                                        .filter(|d| !(job.position_optional && d.message.contains(POSITION_REQUIRED)))
                                        .map(|d| (job.program, job.set, clarify(d))),
                                ),
                                Err(panic) => {
                                    frontend = validate::Frontend::default();
                                    let what = panic
                                        .downcast_ref::<String>()
                                        .cloned()
                                        .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                                        .unwrap_or_default();
                                    // A bug in naga, not a verdict on the shader: the stage
                                    // stays unchecked, as the warning says.
                                    let diag = Diagnostic::warning(
                                        format!(
                                            "{entry} is not checked: naga crashed on it ({what}), a bug in naga rather than in the \
                                             shader; `--driver` compiles it with Mesa"
                                        ),
                                        Some(Location::line(entry.clone(), 1)),
                                    );
                                    found.push((job.program, job.set, diag));
                                }
                            }
                        }
                        found
                    })
                    .expect("spawn a validation thread")
            })
            .collect();
        handles.into_iter().flat_map(|h| h.join().unwrap_or_default()).collect()
    })
}
