//! The bench over a chosen list of option sets (profiles, and a profile with one option
//! overridden), for trying profile changes before editing pack.toml:
//!
//!     cargo run --release -p tidepack-bench --example profile_candidates -- [--frames N] [RUN ...]
//!
//! A RUN is `PROFILE` or `PROFILE+OPTION=VALUE`. Without RUNs: the four profiles and the
//! candidates of docs/accuracy.md. Writes target/bench-candidates/ (CSV, JSON, plot, report.md)
//! and prints the table.

use std::path::Path;

use tidepack_bench::{BenchConfig, RunSpec};

fn parse(spec: &str) -> RunSpec {
    match spec.split_once('+') {
        None => RunSpec::profile(spec),
        Some((profile, knob)) => {
            let (k, v) = knob.split_once('=').unwrap_or_else(|| panic!("{spec}: expected PROFILE+OPTION=VALUE"));
            RunSpec::sweep(profile, k, v)
        }
    }
}

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut frames = 15;
    let mut specs = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        if a == "--frames" {
            frames = args.next().and_then(|n| n.parse().ok()).expect("--frames N");
        } else {
            specs.push(a);
        }
    }
    if specs.is_empty() {
        specs = [
            "LOW",
            "MEDIUM",
            "HIGH",
            "ULTRA",
            "MEDIUM+NORMAL_OCTAVES=2",
            "MEDIUM+FRESNEL_EXACT=on",
            "HIGH+WAVE_REFINE_STEPS=0",
            "HIGH+FRESNEL_EXACT=on",
        ]
        .map(String::from)
        .to_vec();
    }
    let config = BenchConfig {
        source_dir: root.join("shaderpack"),
        scenes_dir: root.join("tests/scenes"),
        scene_filter: vec![],
        frames,
        resolution: None,
        reference_stride: 1,
        out_dir: root.join("target/bench-candidates"),
        runs: Some(specs.iter().map(|s| parse(s)).collect()),
        report: None,
        command: std::iter::once("cargo run --release -p tidepack-bench --example profile_candidates --".to_string())
            .chain(std::env::args().skip(1))
            .collect::<Vec<_>>()
            .join(" "),
        progress: false,
        specialise: false,
    };
    let result = tidepack_bench::run(&config).unwrap_or_else(|e| panic!("{e}"));
    print!("{}", tidepack_bench::output::table(&result));
}
