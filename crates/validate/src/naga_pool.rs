//! naga on the distinct lowered stages, on worker threads with stacks deep enough for naga's
//! recursion; a panic inside naga becomes a warning that the stage was not checked.

use std::panic::AssertUnwindSafe;

use rayon::prelude::*;

use tidepack_loader::option_lines::OptionSet;
use tidepack_glsl::preprocess::Preprocessed;
use tidepack_glsl::known_valid::KnownValid;
use tidepack_glsl::naga_check::{self, LoweredCompute, LoweredStage};
use tidepack_glsl::{Code, Diagnostic, Location};

use tidepack_glsl::messages::clarify;
use tidepack_loader::{PackFiles, SetProvider};

/// One distinct lowered stage for naga, with the option set that produced it.
pub(crate) struct Job {
    pub stage: JobStage,
    pub set: usize,
    /// A vertex stage followed by a geometry or tessellation stage need not write
    /// `gl_Position`, which naga requires of every vertex stage.
    pub position_optional: bool,
}

/// naga's complaint about a vertex stage that does not write `gl_Position`.
const POSITION_REQUIRED: &str = "must return a `@builtin(position)` output";

/// A vertex stage that never writes `gl_Position`, in GLSL's terms: before GLSL 1.40 drivers
/// refuse it (Mesa's link: "vertex shader does not write to `gl_Position'"), from 1.40 on they
/// accept it and the program draws nothing, as a pack's program that only discards may want.
fn position_not_written(pre: &Preprocessed) -> Diagnostic {
    let version = pre.version.as_ref().map_or(110, |v| v.number);
    let main_line = pre.text.lines().position(|l| l.contains("void main")).map_or(1, |i| i as u32 + 1);
    let at = pre.location(main_line);
    if version < 140 {
        Diagnostic::error(
            Code::NoGlPosition,
            format!(
                "this vertex shader never writes gl_Position, which GLSL {version} requires: the program fails to link (Mesa: \
                 \"vertex shader does not write to `gl_Position'\"); write it, or declare GLSL 1.40 or later"
            ),
            at,
        )
    } else {
        Diagnostic::warning(
            Code::NoGlPosition,
            format!("this vertex shader never writes gl_Position, so the program draws nothing (drivers accept it in GLSL {version})"),
            at,
        )
    }
}

pub(crate) enum JobStage {
    Graphics(LoweredStage),
    Compute(LoweredCompute),
}

impl JobStage {
    pub fn preprocessed(&self) -> &Preprocessed {
        match self {
            JobStage::Graphics(s) => &s.preprocessed,
            JobStage::Compute(s) => &s.preprocessed,
        }
    }

    pub fn text(&self) -> &str {
        match self {
            JobStage::Graphics(s) => &s.lowered.text,
            JobStage::Compute(s) => &s.lowered.text,
        }
    }
}

/// Longest stage (in lines, after preprocessing) naga is given: its parse time grows
/// quadratically with the number of declarations (200 000 take minutes), and no real pack
/// comes near (the largest known stages have a few thousand lines).
pub const MAX_NAGA_LINES: usize = 40_000;

/// Most function definitions times global declarations a stage naga is given may have:
/// naga's GLSL front-end gives every function its own copy of every global, so its memory
/// grows with the product (2,500 of each take 760 MiB). Released packs stay far below.
pub const MAX_NAGA_FUNCTIONS_TIMES_GLOBALS: usize = 2_000_000;

/// Which budget of naga's a lowered stage exceeds, said in full; checked in the order of their
/// cost (lines are counted without tokenizing).
fn over_naga_budget(text: &str) -> Option<String> {
    let lines = text.lines().count();
    if lines > MAX_NAGA_LINES {
        return Some(format!("{lines} lines after preprocessing, more than the {MAX_NAGA_LINES} naga is given"));
    }
    // Function definitions, and global declarations (top-level `;`).
    let tokens = tidepack_glsl::token::tokenize(text).ok()?;
    let functions = tidepack_glsl::token::function_definitions(&tokens).len();
    let depths = tidepack_glsl::token::brace_depths(&tokens);
    let globals = tokens.iter().zip(&depths).filter(|(t, depth)| **depth == 0 && t.is_punct(";")).count();
    (functions.saturating_mul(globals) > MAX_NAGA_FUNCTIONS_TIMES_GLOBALS).then(|| {
        format!(
            "{functions} functions times {globals} global declarations after preprocessing, more than the \
             {MAX_NAGA_FUNCTIONS_TIMES_GLOBALS} naga is given (its memory grows with the product)"
        )
    })
}

/// Stack of each naga worker: naga's parser and validator recurse once per nesting level.
const WORKER_STACK_BYTES: usize = 64 << 20;

/// The worker threads of a validation: `threads` of them (at least 1), with stacks deep enough
/// for naga and the preprocessor.
pub(crate) fn worker_pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads.max(1))
        .stack_size(WORKER_STACK_BYTES)
        .build()
        .expect("start the validation's worker threads")
}

/// Validates the jobs with naga on `pool`; each job's diagnostics, in the order of `jobs`.
/// `known` holds the functions naga accepted so far in this run (see [`KnownValid`]).
pub(crate) fn run_naga(pool: &rayon::ThreadPool, jobs: &[Job], pack: &PackFiles, sets: &[(String, OptionSet)], known: &KnownValid) -> Vec<Vec<Diagnostic>> {
    // One naga front-end per rayon job, reused for the stages it takes.
    pool.install(|| jobs.par_iter().map_init(naga_check::Frontend::default, |frontend, job| check_one(frontend, job, pack, &sets[job.set].1, known)).collect())
}

/// One job through naga under `set`; a panic inside naga becomes a warning that the stage was
/// not checked.
pub(crate) fn check_one(frontend: &mut naga_check::Frontend, job: &Job, pack: &PackFiles, set: &OptionSet, known: &KnownValid) -> Vec<Diagnostic> {
    let provider = SetProvider::new(pack, set);
    let entry = &job.stage.preprocessed().files[0];
    if let Some(over) = over_naga_budget(job.stage.text()) {
        return vec![Diagnostic::warning(Code::Budget, format!("not validated: {over}"), Some(Location::line(entry.clone(), 1)))];
    }
    let result = std::panic::catch_unwind(AssertUnwindSafe(|| match &job.stage {
        JobStage::Graphics(stage) => naga_check::validate_stage_reusing(frontend, stage, &provider, known),
        JobStage::Compute(stage) => naga_check::validate_compute_reusing(frontend, stage, &provider, known),
    }));
    match result {
        Ok(Ok(())) => Vec::new(),
        Ok(Err(diags)) => diags
            .into_iter()
            .filter(|d| !(job.position_optional && d.message.contains(POSITION_REQUIRED)))
            .map(|d| if d.message.contains(POSITION_REQUIRED) { position_not_written(job.stage.preprocessed()) } else { d })
            .map(clarify)
            .collect(),
        Err(panic) => {
            // The front-end may be left half-way through a parse.
            *frontend = naga_check::Frontend::default();
            let what = panic
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            // A bug in naga, not a verdict on the shader: the stage stays unchecked, as the
            // warning says.
            let diag = Diagnostic::warning(
                Code::NotChecked,
                format!(
                    "{entry} is not checked: naga crashed on it ({what}), a bug in naga rather than in the \
                     shader; `--driver` compiles it with Mesa"
                ),
                Some(Location::line(entry.clone(), 1)),
            );
            vec![diag]
        }
    }
}
