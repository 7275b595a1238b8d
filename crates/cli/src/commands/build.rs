//! `tidepack build`: prints the build summary or the diagnostics; with `--scene`, specialises
//! the pack for the scene and measures the speedup on the harness.

use std::io::IsTerminal;
use std::path::Path;
use std::process::ExitCode;

use super::{CANNOT_RUN, FINDINGS};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use tidepack_pack::option_sets::Progress;
use tidepack_pack::{BuildOptions, Dialect};

use super::print_diagnostics;

pub fn run(mut opts: BuildOptions, scene_path: Option<&Path>) -> ExitCode {
    let mut scene = None;
    if let Some(path) = scene_path {
        match load_scene(path) {
            Ok((loaded, spec)) => {
                opts.specialisation = Some(spec);
                scene = Some((path, loaded));
            }
            Err(message) => {
                tell!("error: {message}");
                return ExitCode::from(CANNOT_RUN);
            }
        }
    }
    let progress = ProgressLine::new();
    let result = tidepack_pack::build(&opts, Some(&|dialect, step| progress.show(dialect, step)));
    progress.finish();
    match result {
        Ok(report) => {
            print_diagnostics(&report.warnings, &|path| std::fs::read_to_string(path).ok());
            say!(
                "Built {} {} (profile {}, {} options) in {:.2} s",
                report.pack_name,
                report.version,
                report.profile,
                report.options,
                report.elapsed.as_secs_f64()
            );
            for o in &report.outcomes {
                let v = &o.validation;
                let coverage = v.covered.map_or("no option sets", |c| c.describe());
                say!(
                    "  {:<22} {} programs, {} option sets ({coverage}); naga validated {} stages, {} skipped as identical",
                    o.dialect.to_string(),
                    v.programs,
                    v.option_sets,
                    v.stages_validated,
                    v.stages_identical
                );
                say!("  {:<22} {} ({:.1} KiB)", "", o.zip.display(), o.zip_bytes as f64 / 1024.0);
            }
            if let (Some((path, scene)), Some(first)) = (&scene, report.outcomes.first()) {
                say!("  specialised for {} ({} uniforms folded into constants)", path.display(), report.folded.len());
                report_speedup(&opts, first.dialect, path, scene);
            }
            ExitCode::SUCCESS
        }
        Err(failure) => {
            print_diagnostics(&failure.diagnostics, &|path| failure.source_of(path));
            let errors = failure.diagnostics.iter().filter(|d| d.is_error()).count();
            let plural = if errors == 1 { "" } else { "s" };
            if failure.written.is_empty() {
                tell!("build failed with {errors} error{plural}; no zip was written");
            } else {
                let written: Vec<String> = failure.written.iter().map(|p| p.display().to_string()).collect();
                tell!("build failed with {errors} error{plural}; only these zips were written: {}", written.join(", "));
            }
            if failure.usage { ExitCode::from(CANNOT_RUN) } else { ExitCode::from(FINDINGS) }
        }
    }
}

/// Validation progress on stderr: one line rewritten in place on a terminal, otherwise a line
/// every ten seconds, so a long `--exhaustive` build shows it is moving either way.
struct ProgressLine {
    terminal: bool,
    /// When the last line was printed (or the build started), and whether a terminal line is open.
    state: Mutex<(Instant, bool)>,
}

impl ProgressLine {
    fn new() -> Self {
        // Off a terminal the first line waits ten seconds too: quick builds print none.
        ProgressLine { terminal: std::io::stderr().is_terminal(), state: Mutex::new((Instant::now(), false)) }
    }

    fn show(&self, dialect: Dialect, step: Progress) {
        let mut state = self.state.lock().expect("no panics while printing");
        let text = format!("{dialect}: {}/{} {}", step.done, step.total, step.phase);
        if self.terminal {
            eprint!("\r\x1b[2K{}", tidepack_glsl::terminal::line(&text));
            state.1 = true;
        } else if state.0.elapsed() >= Duration::from_secs(10) {
            tell!("{text}");
            state.0 = Instant::now();
        }
    }

    /// Ends an open terminal line, so what follows starts on its own line.
    fn finish(&self) {
        let state = self.state.lock().expect("no panics while printing");
        if state.1 {
            eprint!("\r\x1b[2K");
        }
    }
}

#[cfg(feature = "render")]
use tidepack_harness::Scene;

/// Without the render feature no scene can be read.
#[cfg(not(feature = "render"))]
enum Scene {}

/// The scene file and the specialisation it implies, read once for both the build and the timing.
#[cfg(feature = "render")]
fn load_scene(path: &Path) -> Result<(Scene, tidepack_pack::specialise::Specialisation), String> {
    let scene = Scene::load(path).map_err(|e| e.to_string())?;
    let spec = tidepack_harness::uniforms::scene_specialisation(&scene, &path.display().to_string());
    Ok((scene, spec))
}

#[cfg(not(feature = "render"))]
fn load_scene(_: &Path) -> Result<(Scene, tidepack_pack::specialise::Specialisation), String> {
    Err("build --scene reads scenes through the harness: this tidepack was built without the render feature".into())
}

/// The pack is built either way; a missing renderer only means no speedup figure.
#[cfg(feature = "render")]
fn report_speedup(opts: &BuildOptions, dialect: tidepack_pack::Dialect, path: &Path, scene: &Scene) {
    use tidepack_harness::{Gpu, PackSelection, job, program};
    let selection = PackSelection {
        source_dir: opts.source_dir.clone(),
        dialect,
        profile: opts.profile.clone(),
        options: Vec::new(),
    };
    let measured = Gpu::new().and_then(|gpu| {
        let general = program::load(&selection)?;
        job::specialisation_speedup(&gpu, &selection, &general, scene, &path.display().to_string(), 9)
    });
    match measured {
        Ok(report) => super::print_specialisation(&report),
        Err(e) => tell!("warning: speedup not measured: {e}"),
    }
}

#[cfg(not(feature = "render"))]
fn report_speedup(_: &BuildOptions, _: tidepack_pack::Dialect, _: &Path, scene: &Scene) {
    match *scene {}
}

/// `tidepack docs`: the generated parts of the docs written, or with `check` compared.
pub fn docs(source: &Path, docs: &Path, check: bool) -> ExitCode {
    match tidepack_pack::docs::update(source, docs, check) {
        Ok(differed) if differed.is_empty() => {
            say!("{} is up to date", docs.display());
            ExitCode::SUCCESS
        }
        Ok(differed) if check => {
            tell!("error: out of date (run `tidepack docs` from the checkout root): {}", differed.join(", "));
            ExitCode::from(FINDINGS)
        }
        Ok(differed) => {
            say!("wrote {}", differed.join(", "));
            ExitCode::SUCCESS
        }
        Err(e) => {
            tell!("error: {e}");
            ExitCode::from(CANNOT_RUN)
        }
    }
}
