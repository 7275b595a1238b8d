//! `tidepack validate PATH`: checks any OptiFine pack (folder or zip) as OptiFine would load it.
//! Exit code 0: no errors (warnings allowed unless `--deny-warnings`); 1: shader errors; 2: the
//! input cannot be read.

use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use super::{CANNOT_RUN, FINDINGS};

use clap::{Args, ValueEnum};
use tidepack_glsl::{Code, Drivers};
use codespan_reporting::term::termcolor::{ColorChoice, StandardStream};
use tidepack_loader::macros::{Os, Vendor, parse_gl_version, parse_mc_version, platform_gl_versions};
use tidepack_validate::{Coverage, Levels, Options, Profiles, Shard, output};

use super::configuration::ConfigurationArgs;
use super::print_diagnostics;

#[derive(Args)]
pub struct ValidateArgs {
    /// Pack folder or zip (`shaders/` at its root or inside one wrapper folder), or a `shaders`
    /// folder itself.
    pub path: PathBuf,
    /// How to print the diagnostics.
    #[arg(long, value_enum, default_value_t = Format::Human)]
    pub format: Format,
    /// Profile, option values, dimension (only its programs are validated; without it, every
    /// world folder's) and loader (its standard macros and world folders).
    #[command(flatten)]
    pub configuration: ConfigurationArgs,
    /// Validate under the defaults and every profile (with `--set` values over each).
    #[arg(long, conflicts_with = "profile")]
    pub all_profiles: bool,
    /// Validate what players can pick: the defaults, every profile, and each program under a
    /// covering set of the options its text depends on (every pair of values of the options
    /// it tests; every combination where they are few). `--set` values stay fixed.
    #[arg(long, conflicts_with = "profile")]
    pub covering: bool,
    /// With `--covering`: every combination of the options each program tests, however many.
    #[arg(long, requires = "covering")]
    pub exhaustive: bool,
    /// Keep what each program gave under each option set in this folder, and reuse it on the
    /// next run where the program's text is the same (for CI caches).
    #[arg(long, value_name = "DIR")]
    pub cache: Option<PathBuf>,
    /// Validate only part K of N of the distinct program texts (a CI matrix job each).
    #[arg(long, value_name = "K/N", value_parser = Shard::parse)]
    pub shard: Option<Shard>,
    /// Minecraft version for MC_VERSION (default: the loader's).
    #[arg(long)]
    pub mc_version: Option<String>,
    /// MC_GL_VERSION: 4.6 or 460 (default: what the OS gives that Minecraft version: 2.1 on
    /// macOS before 1.17, 4.1 on later macOS, else 4.6).
    #[arg(long, value_parser = parse_gl_version)]
    pub gl_version: Option<u32>,
    /// MC_GLSL_VERSION, the driver's highest GLSL version: 4.6 or 460 (default: as for
    /// --gl-version; 1.20 on macOS before 1.17). A stage whose #version is higher is an error.
    #[arg(long, value_parser = parse_gl_version)]
    pub glsl_version: Option<u32>,
    /// Operating system for MC_OS_*.
    #[arg(long, value_enum, default_value_t = OsArg::Linux)]
    pub os: OsArg,
    /// GPU vendor for MC_GL_VENDOR_* and MC_GL_RENDERER_*.
    #[arg(long, value_enum, default_value_t = VendorArg::Mesa)]
    pub vendor: VendorArg,
    /// Also compile and link every program with the real OpenGL driver (Mesa through EGL,
    /// headless) and report where it disagrees with tidepack.
    #[arg(long)]
    pub driver: bool,
    /// The drivers whose refusals are errors, comma-separated: mesa, amd, intel, nvidia, macos
    /// or all. An error only other drivers refuse is a warning saying who does; macOS's
    /// refusals (OpenGL 4.1: no `#version` above 410, compute, storage blocks or images) are
    /// checked only when it is named.
    #[arg(long, value_name = "DRIVERS", value_parser = Drivers::parse, default_value = "mesa,amd,intel,nvidia")]
    pub target: Drivers,
    /// Exit 1 on warnings too (unknown uniforms, unlisted outputs, …), not only on errors.
    #[arg(long)]
    pub deny_warnings: bool,
    /// Leave out the warnings of these codes (`tidepack codes` lists them), comma-separated or
    /// repeated. Errors cannot be allowed: `--target` chooses whose refusals are errors.
    #[arg(long, value_name = "CODE", value_delimiter = ',', value_parser = Code::parse)]
    pub allow: Vec<Code>,
    /// Make the warnings of these codes errors (exit 1), comma-separated or repeated.
    #[arg(long, value_name = "CODE", value_delimiter = ',', value_parser = Code::parse)]
    pub deny: Vec<Code>,
    /// The configuration file whose `[validate]` table lists codes to `allow` and `deny`
    /// (default: tidepack.toml in PATH's folder, or else in the current folder). The command
    /// line's --allow and --deny go over it.
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// Also append the report as Markdown to FILE: the verdict, a table of codes and every
    /// diagnostic grouped by code (for CI job summaries: `--summary "$GITHUB_STEP_SUMMARY"`).
    #[arg(long, value_name = "FILE")]
    pub summary: Option<PathBuf>,
}

#[derive(Clone, Copy, ValueEnum)]
pub enum Format {
    /// Compiler-style diagnostics with snippets.
    Human,
    /// One JSON object on stdout.
    Json,
    /// GitHub Actions annotations on stdout.
    Github,
}

#[derive(Clone, Copy, ValueEnum)]
pub enum OsArg {
    Windows,
    Mac,
    Linux,
    Other,
}

#[derive(Clone, Copy, ValueEnum)]
pub enum VendorArg {
    Amd,
    Intel,
    Mesa,
    Nvidia,
    Other,
}

pub fn run(args: &ValidateArgs) -> ExitCode {
    let configuration = match args.configuration.configuration() {
        Ok(c) => c,
        Err(e) => {
            tell!("error: {e}");
            return ExitCode::from(CANNOT_RUN);
        }
    };
    let mut macros = configuration.standard_macros();
    if let Some(text) = &args.mc_version {
        let Some(mc_version) = parse_mc_version(text) else {
            tell!("error: --mc-version `{}` is not a version like 1.21.4", text.escape_debug());
            return ExitCode::from(CANNOT_RUN);
        };
        macros.mc_version = mc_version;
    }
    macros.os = match args.os {
        OsArg::Windows => Os::Windows,
        OsArg::Mac => Os::Mac,
        OsArg::Linux => Os::Linux,
        OsArg::Other => Os::Other,
    };
    let (gl_version, glsl_version) = platform_gl_versions(macros.os, macros.mc_version);
    macros.gl_version = args.gl_version.unwrap_or(gl_version);
    macros.glsl_version = args.glsl_version.unwrap_or(glsl_version);
    macros.vendor = match args.vendor {
        VendorArg::Amd => Vendor::Amd,
        VendorArg::Intel => Vendor::Intel,
        VendorArg::Mesa => Vendor::Mesa,
        VendorArg::Nvidia => Vendor::Nvidia,
        VendorArg::Other => Vendor::Other,
    };
    let profiles = match (&configuration.profile, args.covering, args.all_profiles) {
        (Some(name), _, _) => Profiles::Named(name.clone()),
        (None, true, _) => Profiles::Covering(if args.exhaustive { Coverage::Exhaustive } else { Coverage::Pairwise }),
        (None, false, true) => Profiles::All,
        (None, false, false) => Profiles::Defaults,
    };
    if args.path.join("pack.toml").is_file() && args.path.join("shaders").is_dir() {
        // tidepack's own template source: the build writes lib/generated.glsl,
        // shaders.properties and the GLSL 120 dialect, and validates every option set itself.
        tell!(
            "error: {} is tidepack's template source (pack.toml beside shaders/), not a pack: `tidepack build` \
             generates the rest of the pack and validates it; to check the result as a player gets it, validate \
             a zip it writes (tidepack validate dist/<name>-glsl330.zip)",
            args.path.display()
        );
        return ExitCode::from(CANNOT_RUN);
    }
    let levels = match Levels::for_pack(&args.path, args.config.as_deref(), &args.allow, &args.deny) {
        Ok(levels) => levels,
        Err(diag) => {
            print_diagnostics(&[diag], &|_| None);
            return ExitCode::from(CANNOT_RUN);
        }
    };
    let options = Options {
        macros,
        profiles,
        overrides: configuration.options,
        dimension: args.configuration.dimension.clone(),
        loader: configuration.loader,
        driver: args.driver,
        cache: args.cache.clone(),
        shard: args.shard,
        target: args.target,
        levels,
        ..Options::default()
    };
    let report = match tidepack_validate::validate_path(&args.path, &options) {
        Ok(report) => report,
        Err(diag) => {
            match args.format {
                Format::Human => print_diagnostics(&[diag], &|_| None),
                Format::Json => print!("{}", output::input_error_json(&diag)),
                Format::Github => print!("{}", output::input_error_github(&diag)),
            }
            return ExitCode::from(CANNOT_RUN);
        }
    };
    let mut stdout = std::io::stdout().lock();
    let written = match args.format {
        Format::Human => {
            let color = if std::io::stderr().is_terminal() { ColorChoice::Auto } else { ColorChoice::Never };
            let mut stderr = StandardStream::stderr(color);
            output::human(&report, &mut stderr).and_then(|summary| stdout.write_all(summary.as_bytes()))
        }
        Format::Json => stdout.write_all(output::json(&report).as_bytes()),
        Format::Github => stdout.write_all(output::github(&report).as_bytes()),
    };
    if written.is_err() {
        return ExitCode::from(CANNOT_RUN);
    }
    if let Some(path) = &args.summary {
        let appended = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(path)
            .and_then(|mut file| file.write_all(output::markdown(&report).as_bytes()));
        if let Err(e) = appended {
            tell!("error: --summary {}: {e}", path.display());
            return ExitCode::from(CANNOT_RUN);
        }
    }
    if report.errors() > 0 {
        return ExitCode::from(FINDINGS);
    }
    if args.deny_warnings && report.warnings() > 0 {
        let plural = if report.warnings() == 1 { "" } else { "s" };
        tell!("error: --deny-warnings: {} warning{plural} (listed above), so the check fails", report.warnings());
        return ExitCode::from(FINDINGS);
    }
    ExitCode::SUCCESS
}

/// `tidepack codes`: every diagnostic code with its summary, or the docs page.
pub fn list_codes(markdown: bool) -> ExitCode {
    if markdown {
        print!("{}", tidepack_glsl::code::reference_page());
    } else {
        let width = Code::ALL.iter().map(|c| c.name().len()).max().unwrap_or(0);
        for code in Code::ALL {
            say!("{:width$}  {}", code.name(), code.summary());
        }
    }
    ExitCode::SUCCESS
}
