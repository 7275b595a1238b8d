//! One module per subcommand; each turns a library result into output and an exit code.

use std::io::IsTerminal;

use codespan_reporting::term::termcolor::{ColorChoice, StandardStream};
use tidepack_glsl::{Diagnostic, diagnostic};

/// `println!` through [`tidepack_glsl::terminal::block`]: whatever a pack, a scene or the command
/// line put in the text is shown, never acted on by the terminal. Every line the CLI prints goes
/// through this, [`tell!`] or [`print_diagnostics`].
macro_rules! say {
    ($($arg:tt)*) => { println!("{}", tidepack_glsl::terminal::block(&format!($($arg)*))) };
}

/// `eprintln!` through [`tidepack_glsl::terminal::block`], as [`say!`].
macro_rules! tell {
    ($($arg:tt)*) => { eprintln!("{}", tidepack_glsl::terminal::block(&format!($($arg)*))) };
}

/// The exit-code rule of every command (README, "Exit codes"): 0 when the check is clean,
/// [`FINDINGS`] when it found errors in what it checked (a pack, a template, a render),
/// [`CANNOT_RUN`] when it could not check at all: a bad argument (as clap's own usage errors),
/// unreadable input, a missing driver.
pub const FINDINGS: u8 = 1;
pub const CANNOT_RUN: u8 = 2;

#[cfg(feature = "bench")]
pub mod bench;
#[cfg(feature = "bench")]
pub mod compare;
pub mod build;
pub mod configuration;
#[cfg(feature = "render")]
pub mod render;
#[cfg(feature = "render")]
pub mod stress;
pub mod validate;

/// Prints diagnostics to stderr like a compiler, coloured on a terminal.
pub fn print_diagnostics(diagnostics: &[Diagnostic], source_of: &dyn Fn(&str) -> Option<String>) {
    let color = if std::io::stderr().is_terminal() { ColorChoice::Auto } else { ColorChoice::Never };
    let mut stderr = StandardStream::stderr(color);
    let _ = diagnostic::emit(&mut stderr, diagnostics, source_of);
}

/// The `--specialise` / `--scene` summary: composite time of the general and the specialised
/// pack, and whether the picture changed.
#[cfg(feature = "render")]
pub fn print_specialisation(report: &tidepack_harness::job::SpecialisationReport) {
    let d = report.max_difference.map(|c| c * 255.0);
    say!(
        "  specialised composite {:.2} ms vs general {:.2} ms (pass-through {:.2} ms): {}, median of {} frames each",
        report.specialised_ms,
        report.general_ms,
        report.passthrough_ms,
        if report.speedup >= 1.0 { format!("{:.2}x faster", report.speedup) } else { format!("{:.2}x slower", 1.0 / report.speedup) },
        report.frames
    );
    say!(
        "  images differ by at most R {:.2} G {:.2} B {:.2} A {:.2} (x/255); folded {}",
        d[0], d[1], d[2], d[3], report.folded.join(", ")
    );
}
