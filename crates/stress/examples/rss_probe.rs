//! RSS probe for the stress sweep's memory growth (docs/stress.md, "Memory"): renders one case
//! `N` times through one part of the per-case work and prints VmRSS every 100 iterations.
//!
//!     cargo run --release -p tidepack-stress --example rss_probe -- gpu|ref|both [N]
//!
//! `gpu`: `CompositeOnly::render` alone; `ref`: the f64 reference alone; `both`: one after the
//! other, as `tidepack stress` does.

use std::path::Path;

use tidepack_harness::composite_only::{CompositeOnly, GBuffers, UniformBinding};
use tidepack_harness::uniforms::{self, Pass};
use tidepack_harness::{Gpu, PackSelection, Scene, program, render_wgpu};
use tidepack_pack::Dialect;
use tidepack_reference::harness::{self as reference, Precision, Textures};

fn main() {
    let mut args = std::env::args().skip(1);
    let mode = args.next().unwrap_or_else(|| "both".into());
    let n: usize = args.next().map_or(1000, |s| s.parse().expect("N"));
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let pack = program::load(&PackSelection {
        source_dir: root.join("shaderpack"),
        dialect: Dialect::Glsl330,
        profile: None,
        options: vec![],
    })
    .expect("pack");
    let gpu = Gpu::new().expect("gpu");
    let scene = Scene::load(&root.join("tests/scenes/case4_above_near.toml")).expect("scene").with_resolution(32, 18);
    let frame = render_wgpu(&gpu, &pack, &scene).expect("frame");
    let g = GBuffers::from_frame(&frame);
    let values = uniforms::values(&scene, Pass::Fullscreen);
    // TP_UNIFORM_BINDING=uniform: the blocks as declared, the binding whose per-draw
    // recompilation the probe measures (docs/stress.md, "Memory").
    let binding = match std::env::var("TP_UNIFORM_BINDING").as_deref() {
        Ok("uniform") => UniformBinding::Uniform,
        _ => UniformBinding::ReadOnlyStorage,
    };
    let runner = CompositeOnly::with_binding(&gpu, &pack, 32, 18, &values, binding).expect("runner");
    let settings = tidepack_reference::ReferenceSettings::converged();
    let textures = Textures::of(&pack).expect("textures");
    let rss = || tidepack_harness::resident_mib().unwrap_or(0.0);
    println!("mode {mode}, start RSS {:.1} MiB", rss());
    if mode == "frames" {
        // Whole harness frames as the bench renders them: pipelines made per call, 8 frames.
        let big = Scene::load(&root.join("tests/scenes/case4_above_near.toml")).expect("scene").with_resolution(640, 360);
        for i in 1..=n {
            tidepack_harness::render_wgpu_repeated(&gpu, &pack, &big, 8).expect("frames");
            println!("{i} calls of 8 frames, RSS {:.1} MiB", rss());
        }
        return;
    }
    if mode == "compare" {
        // The same case through both bindings: how far apart are the outputs?
        let other = CompositeOnly::with_binding(&gpu, &pack, 32, 18, &values, UniformBinding::Uniform).expect("runner");
        let a = runner.render(&gpu, &pack, &g, &values).expect("render");
        let b = other.render(&gpu, &pack, &g, &values).expect("render");
        let max = a.pixels.iter().zip(&b.pixels).flat_map(|(p, q)| (0..4).map(move |c| (p[c] - q[c]).abs())).fold(0.0f32, f32::max);
        println!("storage vs uniform binding: max |difference| {max:e}");
        return;
    }
    if mode == "recreate" {
        for i in 1..=n {
            let gpu = Gpu::new().expect("gpu");
            let runner = CompositeOnly::with_binding(&gpu, &pack, 32, 18, &values, binding).expect("runner");
            for _ in 0..50 {
                runner.render(&gpu, &pack, &g, &values).expect("render");
            }
            drop(runner);
            drop(gpu);
            println!("{i} devices of 50 renders, RSS {:.1} MiB", rss());
        }
        return;
    }
    for i in 1..=n {
        if mode == "gpu" || mode == "both" {
            let image = runner.render(&gpu, &pack, &g, &values).expect("render");
            assert_eq!(image.pixels.len(), 32 * 18);
        }
        if mode == "ref" || mode == "both" {
            // The reference's inputs for the case, built as `tidepack stress` builds them.
            let uniforms = reference::uniforms_of(&values, Precision::Exact).expect("uniforms");
            let inputs = reference::from_gbuffers(&pack, &g.colors, &g.depth0, &g.depth1, Some(false), &textures, uniforms).expect("inputs");
            let image = tidepack_reference::render(&inputs, &settings, 1).expect("reference");
            assert_eq!(image.pixels.len(), 32 * 18);
        }
        if i % 100 == 0 {
            println!("{i} iterations, RSS {:.1} MiB", rss());
        }
    }
}
