//! `tidepack compare`: our pack beside released packs on the same scenes (tidepack_bench::compare).
//! Prints the water cost per pack and scene; writes the pictures, compare.json and report.md
//! under --out, and the page with --report. Exit 0: every pack drew every scene; 1: some did
//! not (each named with why); 2: no Vulkan driver or unreadable input.

use std::path::PathBuf;
use std::process::ExitCode;

use super::{CANNOT_RUN, FINDINGS};

use clap::Args;
use tidepack_bench::compare::{CompareConfig, DEFAULT_SCENES};

#[derive(Args)]
pub struct CompareArgs {
    /// A released pack (folder or zip) to draw beside ours; repeatable.
    #[arg(long = "pack", value_name = "PATH")]
    pub packs: Vec<PathBuf>,
    /// A scene file to draw instead of the default five (shore, under water, rain, stained
    /// glass, night); repeatable.
    #[arg(long = "scene", value_name = "FILE")]
    pub scenes: Vec<PathBuf>,
    /// Folder the default scenes are read from.
    #[arg(long, default_value = "tests/scenes")]
    pub scenes_dir: PathBuf,
    /// Frames per rendering; the first is left out of the median.
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u64).range(2..=1000))]
    pub frames: u64,
    /// Renderings of each scene with and without its water, alternating.
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u64).range(1..=100))]
    pub rounds: u64,
    /// Output folder.
    #[arg(long, default_value = "target/compare")]
    pub out: PathBuf,
    /// Also write the Markdown page here, its pictures in a folder of the page's name beside it
    /// (docs/compare.md is made this way).
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Folder with pack.toml and the shader templates of our pack.
    #[arg(long, default_value = "shaderpack")]
    pub source: PathBuf,
}

pub fn run(args: &CompareArgs) -> ExitCode {
    let scenes = if args.scenes.is_empty() {
        DEFAULT_SCENES.iter().map(|(file, label)| (args.scenes_dir.join(file), label.to_string())).collect()
    } else {
        args.scenes.iter().map(|p| (p.clone(), p.file_stem().map_or_else(String::new, |s| s.to_string_lossy().into_owned()))).collect()
    };
    let config = CompareConfig {
        source_dir: args.source.clone(),
        packs: args.packs.clone(),
        scenes,
        frames: args.frames as usize,
        rounds: args.rounds as usize,
        out_dir: args.out.clone(),
        report: args.report.clone(),
        command: std::iter::once("cargo run --release --".to_string()).chain(std::env::args().skip(1)).collect::<Vec<_>>().join(" "),
    };
    match tidepack_bench::compare::run(&config) {
        Ok(result) => {
            say!("{} packs on {} scenes ({})", result.packs.len(), result.scenes.len(), result.adapter);
            for m in &result.measurements {
                say!(
                    "  {:<44} {:<24} water {:>6.1}x  frame {:>6.1}x the pass-through",
                    m.pack,
                    m.scene,
                    m.water_cost,
                    m.frame_cost
                );
            }
            for f in &result.failures {
                tell!("error: {} did not draw {}: {}", f.pack, f.scene, f.error);
            }
            for (pack, program, why) in &result.failed_programs {
                tell!("warning: {pack}: {program} did not load: {why}");
            }
            say!("  wrote {}", args.out.join("report.md").display());
            if let Some(r) = &args.report {
                say!("  wrote {}", r.display());
            }
            if result.failures.is_empty() { ExitCode::SUCCESS } else { ExitCode::from(FINDINGS) }
        }
        Err(e) => {
            tell!("error: {e}");
            ExitCode::from(if e.cannot_run { CANNOT_RUN } else { FINDINGS })
        }
    }
}
