//! `tidepack`: the command line. Parses arguments, calls the library crates, prints results.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};
use codespan_reporting::term::termcolor::{ColorChoice, StandardStream};
use tidepack_glsl::diagnostic;
use tidepack_pack::{BuildOptions, Dialect};

#[derive(Parser)]
#[command(name = "tidepack", version, about = "Build and check OptiFine shader packs for Minecraft water")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Generate the pack from shaderpack/, validate every program under every option set
    /// through naga, and write one zip per GLSL dialect.
    ///
    /// Nothing is written when any program fails to validate; errors name the template file
    /// and line, and the options that trigger them.
    Build {
        /// Folder with pack.toml and the shader templates.
        #[arg(long, default_value = "shaderpack")]
        source: PathBuf,
        /// Folder the zips are written to.
        #[arg(long, default_value = "dist")]
        out: PathBuf,
        /// GLSL dialect(s) to build.
        #[arg(long, value_enum, default_value_t = DialectArg::All)]
        dialect: DialectArg,
        /// Profile whose option values become the pack's defaults (default: the manifest's
        /// default_profile).
        #[arg(long)]
        profile: Option<String>,
    },
}

#[derive(Clone, Copy, ValueEnum)]
enum DialectArg {
    /// `#version 120`
    #[value(name = "120")]
    V120,
    /// `#version 330 compatibility`
    #[value(name = "330")]
    V330,
    /// Both dialects.
    All,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Build { source, out, dialect, profile } => {
            let dialects = match dialect {
                DialectArg::V120 => vec![Dialect::Glsl120],
                DialectArg::V330 => vec![Dialect::Glsl330],
                DialectArg::All => Dialect::ALL.to_vec(),
            };
            run_build(&BuildOptions { source_dir: source, out_dir: out, dialects, profile })
        }
    }
}

fn run_build(opts: &BuildOptions) -> ExitCode {
    match tidepack_pack::build(opts) {
        Ok(report) => {
            println!(
                "Built {} {} (profile {}, {} options) in {:.2} s",
                report.pack_name,
                report.version,
                report.profile,
                report.options,
                report.elapsed.as_secs_f64()
            );
            for o in &report.outcomes {
                let v = &o.validation;
                let coverage = if v.exhaustive {
                    "every combination of the options each program reads"
                } else {
                    "every combination of the options each program tests, values one at a time"
                };
                println!(
                    "  {:<22} {} programs, {} option sets ({coverage}); naga validated {} stages, {} skipped as identical",
                    o.dialect.to_string(),
                    v.programs,
                    v.option_sets,
                    v.stages_validated,
                    v.stages_identical
                );
                println!("  {:<22} {} ({:.1} KiB)", "", o.zip.display(), o.zip_bytes as f64 / 1024.0);
            }
            ExitCode::SUCCESS
        }
        Err(failure) => {
            let color = if std::io::stderr().is_terminal() { ColorChoice::Auto } else { ColorChoice::Never };
            let mut stderr = StandardStream::stderr(color);
            let _ = diagnostic::emit(&mut stderr, &failure.diagnostics, &|path| failure.source_of(path));
            let errors = failure.diagnostics.iter().filter(|d| d.is_error()).count();
            eprintln!("build failed with {errors} error{}; no zip was written", if errors == 1 { "" } else { "s" });
            ExitCode::FAILURE
        }
    }
}
