//! `tidepack bench`: composite time against error for every scene, profile and single-knob
//! sweep (tidepack_bench). Prints the table over all scenes; writes bench.csv, bench.json,
//! pareto.png, report.md and heatmaps/ under --out. Exit 0: done; 1: a run failed; 2: no
//! Vulkan driver (the message names the Debian package) or unreadable input.

use std::path::PathBuf;
use std::process::ExitCode;

use super::{CANNOT_RUN, FINDINGS};

use clap::Args;
use tidepack_bench::BenchConfig;

#[derive(Args)]
pub struct BenchArgs {
    /// Folder of scene files.
    #[arg(long, default_value = "tests/scenes")]
    pub scenes: PathBuf,
    /// Frames per option set and scene (at least 1); the median GPU time is reported, and the
    /// frames' spread decides which Pareto verdicts are ties within timing noise.
    #[arg(long, default_value_t = 7, value_parser = clap::value_parser!(u64).range(1..))]
    pub frames: u64,
    /// Output folder.
    #[arg(long, default_value = "target/bench")]
    pub out: PathBuf,
    /// Quick look: every scene at 160x90 and 3 frames.
    #[arg(long)]
    pub quick: bool,
    /// Only these scenes (file stems; repeatable).
    #[arg(long = "scene")]
    pub scene: Vec<String>,
    /// Also write the Markdown report to this file, the plot beside it as <stem>-pareto.png
    /// (docs/accuracy.md is made this way).
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Time each option set specialised for each scene, as `build --scene` ships it (the
    /// uniforms the scene fixes folded into constants), instead of the general pack.
    #[arg(long)]
    pub specialise: bool,
    /// Folder with pack.toml and the shader templates.
    #[arg(long, default_value = "shaderpack")]
    pub source: PathBuf,
}

pub fn run(args: &BenchArgs) -> ExitCode {
    let config = BenchConfig {
        source_dir: args.source.clone(),
        scenes_dir: args.scenes.clone(),
        scene_filter: args.scene.clone(),
        frames: if args.quick { args.frames.min(3) as usize } else { args.frames as usize },
        resolution: args.quick.then_some([160, 90]),
        reference_stride: 1,
        out_dir: args.out.clone(),
        runs: None,
        report: args.report.clone(),
        command: std::iter::once("cargo run --release --".to_string()).chain(std::env::args().skip(1)).collect::<Vec<_>>().join(" "),
        progress: true,
        specialise: args.specialise,
    };
    match tidepack_bench::run(&config) {
        Ok(result) => {
            let scenes = result.scenes.len();
            say!("{scenes} scene{} on {} ({} timing)", if scenes == 1 { "" } else { "s" }, result.adapter, result.timing_source);
            print!("{}", tidepack_glsl::terminal::block(&tidepack_bench::output::table(&result)));
            for f in ["bench.csv", "bench.json", "pareto.png", "report.md", "heatmaps/", "truth/"] {
                say!("  wrote {}", args.out.join(f).display());
            }
            if let Some(r) = &args.report {
                say!("  wrote {}", r.display());
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            tell!("error: {e}");
            if e.contains("mesa-vulkan-drivers") || e.contains("cannot read") { ExitCode::from(CANNOT_RUN) } else { ExitCode::from(FINDINGS) }
        }
    }
}
