//! Pass times of every scene (reported, never asserted).
//!
//! `cargo run --release -p tidepack-harness --example pass_times -- [--frames N] [--size WxH]
//! [--dialect 120|330] [--profile NAME] [--option NAME=VALUE]... [--scene NAME]`
//!
//! Renders every tests/scenes/*.toml at 640x360 (default) on the first Vulkan adapter
//! (lavapipe without a GPU), pipelines made once per scene: one warm-up frame (llvmpipe
//! compiles shader variants at the first draw), then N frames (default 9). Prints, per scene,
//! the median time of terrain, gbuffers_water, composite and the one-tap pass-through composite
//! measured in the same frames, and composite / pass-through: the median of the frames' own
//! ratios with their interquartile range, so that a change of load between frames moves both
//! times of a ratio alike. GPU timestamps when the adapter has them, else wall time (the table
//! says which).
//!
//! Leave Mesa's shader cache on: llvmpipe compiles fragment shader variants lazily inside the
//! timed passes, and with MESA_SHADER_CACHE_DISABLE=true that compilation lands in every
//! frame's composite time (measured: 6-9 s instead of about 0.5 s per frame at 640x360).

use std::path::{Path, PathBuf};

use tidepack_harness::{Gpu, PackSelection, Scene, median, program, quartiles, render_wgpu_repeated};
use tidepack_pack::Dialect;

/// The steps timed, by the start of their label in the frame plan.
const PASSES: [&str; 3] = ["terrain", "water", "composite"];

fn main() {
    let mut frames = 9usize;
    let (mut width, mut height) = (640u32, 360u32);
    let mut dialect = Dialect::Glsl330;
    let mut profile = None;
    let mut options = Vec::new();
    let mut only_scene = None;
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        let mut value = || args.next().unwrap_or_else(|| fail(&format!("{arg} needs a value")));
        match arg.as_str() {
            "--frames" => frames = value().parse().ok().filter(|n| *n > 0).unwrap_or_else(|| fail("--frames takes a positive number")),
            "--size" => {
                let v = value();
                let parsed = v.split_once('x').and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)));
                (width, height) = parsed.unwrap_or_else(|| fail("--size takes WxH"));
            }
            "--dialect" => {
                dialect = match value().as_str() {
                    "120" => Dialect::Glsl120,
                    "330" => Dialect::Glsl330,
                    _ => fail("--dialect takes 120 or 330"),
                }
            }
            "--profile" => profile = Some(value()),
            "--option" => {
                let v = value();
                let (name, setting) = v.split_once('=').unwrap_or_else(|| fail("--option takes NAME=VALUE"));
                options.push((name.to_string(), setting.to_string()));
            }
            "--scene" => only_scene = Some(value()),
            _ => fail(&format!("unknown argument {arg}")),
        }
    }

    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let pack = program::load(&PackSelection { source_dir: root.join("shaderpack"), dialect, profile, options })
        .unwrap_or_else(|e| fail(&e.to_string()));
    let gpu = Gpu::new().unwrap_or_else(|e| fail(&e.to_string()));
    let mut scenes: Vec<PathBuf> = std::fs::read_dir(root.join("tests/scenes"))
        .unwrap_or_else(|e| fail(&format!("tests/scenes: {e}")))
        .filter_map(|e| Some(e.ok()?.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .filter(|p| only_scene.as_ref().is_none_or(|name| p.file_stem().is_some_and(|s| s == name.as_str())))
        .collect();
    scenes.sort();

    let clock = if gpu.timestamps { "GPU timestamps" } else { "wall time (no timestamp queries)" };
    println!(
        "{} at {width}x{height}, {dialect}, profile {}, median of {frames} frames after 1 warm-up, {clock}, ms",
        gpu.describe(),
        pack.profile
    );
    println!();
    println!("| scene | terrain | gbuffers_water | composite | pass-through | composite / pass-through (IQR) |");
    println!("|---|---:|---:|---:|---:|---:|");
    for path in scenes {
        let scene = Scene::load(&path).unwrap_or_else(|e| fail(&e.to_string())).with_resolution(width, height);
        // Pipelines are made once; frame 0 (with llvmpipe's lazy shader compilation) is the warm-up.
        let frame = render_wgpu_repeated(&gpu, &pack, &scene, frames + 1).unwrap_or_else(|e| fail(&format!("{}: {e}", scene.name)));
        let mut samples: Vec<Vec<f64>> = PASSES
            .iter()
            .map(|pass| {
                let step = frame.passes.iter().find(|p| p.pass.starts_with(pass)).unwrap_or_else(|| fail(&format!("no {pass} step")));
                step.samples_ms[1..].to_vec()
            })
            .collect();
        samples.push(frame.timing.passthrough_samples_ms[1..].to_vec());
        let m: Vec<f64> = samples.iter().map(|s| median(s)).collect();
        let ratios: Vec<f64> = samples[2].iter().zip(&samples[3]).map(|(composite, passthrough)| composite / passthrough).collect();
        let (low, high) = quartiles(&ratios);
        println!(
            "| {} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} ({low:.2}–{high:.2}) |",
            scene.name,
            m[0],
            m[1],
            m[2],
            m[3],
            median(&ratios)
        );
    }
}

fn fail(message: &str) -> ! {
    eprintln!("error: {message}");
    std::process::exit(1)
}
