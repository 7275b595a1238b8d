//! `tidepack`: the command line. Parses arguments, calls the library crates, prints results.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};
use tidepack_pack::option_sets::Coverage;
use tidepack_pack::{BuildOptions, Dialect};

mod commands;

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
        /// Validate every combination of the options each program tests, however many (and of
        /// every value of each option read, up to 4096). By default, past 16 such combinations
        /// per program, every pair of option values and every profile are validated.
        #[arg(long)]
        exhaustive: bool,
        /// Specialise the pack for one scene (tests/scenes/*.toml): the uniforms the scene
        /// fixes become constants before validation, the zip is named after the scene, and the
        /// composite's speedup against the general pack is measured on the harness.
        #[arg(long, value_name = "FILE")]
        scene: Option<PathBuf>,
    },
    /// Check any OptiFine shader pack (folder or zip) the way OptiFine loads it, headless: every
    /// program of every world folder through OptiFine's preprocessor and naga, plus the links
    /// between stages, render targets, uniforms and samplers. Exit 0: clean; 1: shader
    /// errors; 2: unreadable input.
    Validate(commands::validate::ValidateArgs),
    /// Write the parts of docs/*.md that the pack's sources and its build decide (tables of
    /// options and profiles, build figures, the diagnostic codes). Run from the checkout root.
    Docs {
        /// Only compare: exit 1 naming the docs that differ from what would be written.
        #[arg(long)]
        check: bool,
        /// Folder with pack.toml and the shader templates.
        #[arg(long, default_value = "shaderpack")]
        source: PathBuf,
        /// The docs folder.
        #[arg(long, default_value = "docs")]
        docs: PathBuf,
    },
    /// List the diagnostic codes `--allow` and `--deny` take, with what each is about.
    Codes {
        /// Print docs/diagnostics.md instead: the codes as a Markdown page.
        #[arg(long)]
        markdown: bool,
    },
    /// Render one scene (tests/scenes/*.toml) headless through the harness: writes
    /// OUT/<scene>.png and OUT/<scene>.json (pass times, adapter, resolution, dialect, options).
    #[cfg(feature = "render")]
    Render(commands::render::RenderArgs),
    /// Sweep adversarial and random uniform sets and G-buffers through the composite on the
    /// harness against the f64 reference: NaN/Inf counts, error per category and against
    /// |cameraPosition| (docs/stress.md). Prints the tables; writes files only with --out.
    #[cfg(feature = "render")]
    Stress(commands::stress::StressArgs),
    /// Composite time against error for every scene, profile and single-knob sweep, the error
    /// both against the converged model and against the physically based truth: table, CSV,
    /// JSON, Pareto plot, FLIP heat-maps, the truth beside the pack (docs/accuracy.md).
    #[cfg(feature = "bench")]
    Bench(commands::bench::BenchArgs),
    /// Our pack beside released packs on the same scenes: each pack's water cost (frame with
    /// water minus without, in one-tap pass-through units) and the pictures side by side
    /// (docs/compare.md).
    #[cfg(feature = "bench")]
    Compare(commands::compare::CompareArgs),
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
    // Output piped into `head` or a pager that closes early ends the process quietly, as other
    // command-line tools do, instead of panicking on the failed write.
    #[cfg(unix)]
    // SAFETY: setting a signal's disposition to its default, before any thread starts.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    // A panic inside naga becomes a diagnostic; its panic message would only repeat it raw.
    let report_panic = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        if std::thread::current().name() != Some(tidepack_glsl::naga_check::NAGA_THREAD) {
            report_panic(info);
        }
    }));
    let cli = Cli::parse();
    match cli.command {
        Command::Build { source, out, dialect, profile, exhaustive, scene } => {
            let dialects = match dialect {
                DialectArg::V120 => vec![Dialect::Glsl120],
                DialectArg::V330 => vec![Dialect::Glsl330],
                DialectArg::All => Dialect::ALL.to_vec(),
            };
            let coverage = if exhaustive { Coverage::Exhaustive } else { Coverage::Pairwise };
            let opts = BuildOptions { source_dir: source, out_dir: out, dialects, profile, coverage, specialisation: None };
            commands::build::run(opts, scene.as_deref())
        }
        Command::Validate(args) => commands::validate::run(&args),
        Command::Codes { markdown } => commands::validate::list_codes(markdown),
        Command::Docs { check, source, docs } => commands::build::docs(&source, &docs, check),
        #[cfg(feature = "render")]
        Command::Render(args) => commands::render::run(&args),
        #[cfg(feature = "render")]
        Command::Stress(args) => commands::stress::run(&args),
        #[cfg(feature = "bench")]
        Command::Bench(args) => commands::bench::run(&args),
        #[cfg(feature = "bench")]
        Command::Compare(args) => commands::compare::run(&args),
    }
}

