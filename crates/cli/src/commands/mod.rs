//! One module per subcommand; each turns a library result into output and an exit code.

use std::io::IsTerminal;

use codespan_reporting::term::termcolor::{ColorChoice, StandardStream};
use tidepack_glsl::{Diagnostic, diagnostic};

#[cfg(feature = "bench")]
pub mod bench;
pub mod build;
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
