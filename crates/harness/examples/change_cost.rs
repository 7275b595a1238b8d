//! What a change to the shaders costs: composite time of two copies of the pack's sources,
//! frame by frame in one process (reported, never asserted).
//!
//! `cargo run --release -p tidepack-harness --example change_cost -- --before DIR [--after DIR]
//! [--rounds N] [--profile NAME] [--scene NAME]...`
//!
//! `--after` defaults to shaderpack/; `--before` is typically the sources at a commit
//! (`git archive HEAD shaderpack | tar -x -C /tmp/before`). On a shared CPU renderer one run's
//! composite time moves by 10% or more from run to run, more than most changes save. Here each
//! version draws the scene's whole frame once (640x360, as `pass_times` draws), and its
//! composite is then timed alone over its own G-buffers ([`tidepack_harness::composite_only`]),
//! the two versions taking turns frame by frame for N rounds (default 15) after one warm-up
//! round, each frame followed by the one-tap pass-through. Load changes hit both alike, so the
//! median of the per-round ratios after / before resolves a few percent; the table gives it with
//! its interquartile range, each version's composite / pass-through, and how far the two
//! composite images differ.

use std::path::{Path, PathBuf};

use tidepack_harness::composite_only::{CompositeOnly, GBuffers};
use tidepack_harness::images::{OVER_1_255, count_differing, max_channel_difference};
use tidepack_harness::uniforms::{self, Pass};
use tidepack_harness::{Gpu, PackSelection, Scene, median, program, quartiles, render_wgpu};
use tidepack_pack::Dialect;

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let (mut before, mut after) = (None, root.join("shaderpack"));
    let mut rounds = 15usize;
    let mut profile = Some("HIGH".to_string());
    let mut scenes = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        let mut value = || args.next().unwrap_or_else(|| fail(&format!("{arg} needs a value")));
        match arg.as_str() {
            "--before" => before = Some(PathBuf::from(value())),
            "--after" => after = PathBuf::from(value()),
            "--rounds" => rounds = value().parse().ok().filter(|n| *n > 0).unwrap_or_else(|| fail("--rounds takes a positive number")),
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
    println!("{}, profile {}, {rounds} rounds after 1 warm-up, composite alone at 640x360", gpu.describe(), packs[1].profile);
    println!();
    println!(
        "| scene | before: composite / pass-through | after: composite / pass-through | after / before (median of rounds, IQR) | largest difference (x/255) | pixels over 1/255 |"
    );
    println!("|---|---:|---:|---|---:|---:|");
    for name in &scenes {
        let scene = Scene::load(&root.join("tests/scenes").join(format!("{name}.toml")))
            .unwrap_or_else(|e| fail(&e.to_string()))
            .with_resolution(640, 360);
        let values = uniforms::values(&scene, Pass::Fullscreen);
        let prepared: Vec<(GBuffers, CompositeOnly)> = packs
            .iter()
            .map(|pack| {
                let frame = render_wgpu(&gpu, pack, &scene).unwrap_or_else(|e| fail(&format!("{name}: {e}")));
                let runner = CompositeOnly::new(&gpu, pack, scene.width(), scene.height(), &values).unwrap_or_else(|e| fail(&e.to_string()));
                (GBuffers::from_frame(&frame), runner)
            })
            .collect();
        let mut ratios = [Vec::new(), Vec::new()];
        let mut images = [None, None];
        for round in 0..=rounds {
            // The version that goes first alternates, so neither always follows the other.
            for k in 0..2 {
                let i = (k + round) % 2;
                let (g, runner) = &prepared[i];
                let timed = runner.time(&gpu, &packs[i], g, &values, 1).unwrap_or_else(|e| fail(&e.to_string()));
                if round > 0 {
                    ratios[i].push(timed.composite_ms[0] / timed.passthrough_ms[0]);
                }
                images[i] = Some(timed.image);
            }
        }
        let [Some(before_image), Some(after_image)] = &images else { unreachable!("every round renders both versions") };
        let largest = max_channel_difference(before_image, after_image)[..3].iter().fold(0.0f32, |m, d| m.max(*d)) * 255.0;
        let after_over_before: Vec<f64> = ratios[0].iter().zip(&ratios[1]).map(|(b, a)| a / b).collect();
        let (low, high) = quartiles(&after_over_before);
        println!(
            "| {name} | {:.2} | {:.2} | {:.3} ({:.3}–{:.3}) | {largest:.1} | {} |",
            median(&ratios[0]),
            median(&ratios[1]),
            median(&after_over_before),
            low,
            high,
            count_differing(before_image, after_image, OVER_1_255)
        );
    }
}

fn fail(message: &str) -> ! {
    eprintln!("error: {message}");
    std::process::exit(1)
}
