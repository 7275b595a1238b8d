//! What a change to the shaders costs: composite time of two copies of the pack's sources,
//! rendered in alternating rounds in one process (reported, never asserted).
//!
//! `cargo run --release -p tidepack-harness --example change_cost -- --before DIR [--after DIR]
//! [--rounds N] [--frames N] [--profile NAME] [--scene NAME]...`
//!
//! `--after` defaults to shaderpack/; `--before` is typically the sources at a commit
//! (`git archive HEAD shaderpack | tar -x -C /tmp/before`). On a shared CPU renderer one run's
//! composite time moves by 10% or more from run to run, more than most changes save; rounds
//! that alternate the two packs in one process see the same load, so the median of the
//! per-round ratios after / before resolves a few percent. Each round renders each pack's
//! scene once: one warm-up frame, then `--frames` (default 5) frames whose median is the round's.

use std::path::{Path, PathBuf};

use tidepack_harness::{Gpu, LoadedPack, PackSelection, Scene, median, program, render_wgpu_repeated};
use tidepack_pack::Dialect;

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let (mut before, mut after) = (None, root.join("shaderpack"));
    let (mut rounds, mut frames) = (7usize, 5usize);
    let mut profile = Some("HIGH".to_string());
    let mut scenes = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        let mut value = || args.next().unwrap_or_else(|| fail(&format!("{arg} needs a value")));
        let positive = |v: String, name: &str| v.parse().ok().filter(|n| *n > 0).unwrap_or_else(|| fail(&format!("{name} takes a positive number")));
        match arg.as_str() {
            "--before" => before = Some(PathBuf::from(value())),
            "--after" => after = PathBuf::from(value()),
            "--rounds" => rounds = positive(value(), "--rounds"),
            "--frames" => frames = positive(value(), "--frames"),
            "--profile" => profile = Some(value()),
            "--scene" => scenes.push(value()),
            _ => fail(&format!("unknown argument {arg}")),
        }
    }
    let before = before.unwrap_or_else(|| fail("--before DIR is required"));
    if scenes.is_empty() {
        scenes = ["case4_above_near", "rain_over_lake", "case5_above_far"].map(String::from).to_vec();
    }
    let load = |source_dir: PathBuf| {
        program::load(&PackSelection { source_dir, dialect: Dialect::Glsl330, profile: profile.clone(), options: Vec::new() })
            .unwrap_or_else(|e| fail(&e.to_string()))
    };
    let packs = [load(before), load(after)];
    let gpu = Gpu::new().unwrap_or_else(|e| fail(&e.to_string()));
    println!("{}, profile {}, {rounds} rounds of {frames} frames after 1 warm-up, composite ms", gpu.describe(), packs[1].profile);
    println!();
    println!("| scene | before | after | after / before (median of rounds) | range of rounds |");
    println!("|---|---:|---:|---:|---|");
    for name in &scenes {
        let scene = Scene::load(&root.join("tests/scenes").join(format!("{name}.toml"))).unwrap_or_else(|e| fail(&e.to_string()));
        let composite = |pack: &LoadedPack| {
            let frame = render_wgpu_repeated(&gpu, pack, &scene, frames + 1).unwrap_or_else(|e| fail(&format!("{name}: {e}")));
            let step = frame.passes.iter().find(|p| p.pass.starts_with("composite")).unwrap_or_else(|| fail("no composite step"));
            median(&step.samples_ms[1..])
        };
        let times: Vec<[f64; 2]> = (0..rounds).map(|_| [composite(&packs[0]), composite(&packs[1])]).collect();
        let mut ratios: Vec<f64> = times.iter().map(|[b, a]| a / b).collect();
        ratios.sort_by(f64::total_cmp);
        let side = |i: usize| median(&times.iter().map(|t| t[i]).collect::<Vec<_>>());
        println!("| {name} | {:.2} | {:.2} | {:.3} | {:.3}–{:.3} |", side(0), side(1), median(&ratios), ratios[0], ratios[rounds - 1]);
    }
}

fn fail(message: &str) -> ! {
    eprintln!("error: {message}");
    std::process::exit(1)
}
