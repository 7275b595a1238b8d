//! `tidepack stress`: adversarial and random uniform sets and G-buffers through the real
//! composite on the harness, against the f64 reference (tidepack-stress, docs/stress.md).
//! Exit code 0: no NaN/Inf pixel; 1: some; 2: the sweep could not run (no driver, bad pack).

use std::path::PathBuf;
use std::process::ExitCode;

use super::{CANNOT_RUN, FINDINGS};

use clap::Args;
use tidepack_pack::Dialect;
use tidepack_stress::StressOptions;

use super::render::RenderDialect;

#[derive(Args)]
pub struct StressArgs {
    /// Number of cases, run exactly: spread over the 14 categories as evenly as possible (with
    /// fewer than 13, only the first categories run).
    #[arg(long, default_value_t = 10_000, value_parser = clap::value_parser!(u64).range(1..))]
    pub cases: u64,
    /// Folder for summary.json, categories.csv, distance.csv and cases.csv. Without it the
    /// tables are printed to stdout and no file is written.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// GLSL dialect of the shipped text to run.
    #[arg(long, value_enum, default_value_t = RenderDialect::V330)]
    pub dialect: RenderDialect,
    /// Profile whose values are the option defaults (default: the manifest's default_profile).
    #[arg(long)]
    pub profile: Option<String>,
    /// Frame size of each case.
    #[arg(long, default_value_t = 32)]
    pub width: u32,
    #[arg(long, default_value_t = 18)]
    pub height: u32,
    /// Seed of the random cases.
    #[arg(long, default_value_t = 0x5EED_0005)]
    pub seed: u64,
    /// Folder with pack.toml and the shader templates.
    #[arg(long, default_value = "shaderpack")]
    pub source: PathBuf,
    /// Folder with the base scenes.
    #[arg(long, default_value = "tests/scenes")]
    pub scenes: PathBuf,
}

pub fn run(args: &StressArgs) -> ExitCode {
    let mut opts = StressOptions::new(std::path::Path::new("."));
    opts.source_dir = args.source.clone();
    opts.scenes_dir = args.scenes.clone();
    opts.dialect = match args.dialect {
        RenderDialect::V120 => Dialect::Glsl120,
        RenderDialect::V330 => Dialect::Glsl330,
    };
    opts.profile = args.profile.clone();
    opts.cases = args.cases as usize;
    opts.width = args.width;
    opts.height = args.height;
    opts.seed = args.seed;
    opts.out_dir = args.out.clone();
    let report = match tidepack_stress::run(&opts, &mut |m| tell!("{m}")) {
        Ok(r) => r,
        Err(e) => {
            tell!("error: {e}");
            return ExitCode::from(CANNOT_RUN);
        }
    };
    print!("{}", tidepack_glsl::terminal::block(&tidepack_stress::tables(&report)));
    if let Some(dir) = &args.out {
        say!("\nwritten: {}/{{summary.json,categories.csv,distance.csv,cases.csv}}", dir.display());
    }
    if report.non_finite_pixels > 0 { ExitCode::from(FINDINGS) } else { ExitCode::SUCCESS }
}
