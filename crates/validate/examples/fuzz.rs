//! Fuzzes the tokenizer, preprocessor, lowering and validator with mutations of the corpus
//! packs for SECONDS (default 60) and prints executions, crashes and naga panics.
//! `cargo run --release -p tidepack-validate --example fuzz -- 600 42`; crashing inputs are
//! written to target/fuzz-findings/.

use std::path::Path;
use std::time::Duration;

fn main() {
    let mut args = std::env::args().skip(1);
    let seconds: u64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(60);
    let seed: u64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(1);
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/validate");
    let mut dirs = Vec::new();
    for sub in ["corpus", "planted"] {
        dirs.extend(std::fs::read_dir(root.join(sub)).expect("tests/validate").map(|e| e.unwrap().path()));
    }
    dirs.sort();
    let seeds = tidepack_validate::fuzz::seeds_from(&dirs);
    let started = std::time::Instant::now();
    let stats = tidepack_validate::fuzz::run(&seeds, u64::MAX, Duration::from_secs(seconds), seed);
    let elapsed = started.elapsed().as_secs_f64();
    println!(
        "{} executions in {elapsed:.0} s ({:.0}/s): {} crashes, {} invariant failures, {} naga panics (caught)",
        stats.executions,
        stats.executions as f64 / elapsed,
        stats.crashes,
        stats.invariant_failures,
        stats.naga_panics
    );
    let out = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../target/fuzz-findings");
    for (i, (what, input)) in stats.findings.iter().enumerate() {
        std::fs::create_dir_all(&out).unwrap();
        std::fs::write(out.join(format!("finding-{i}.txt")), input).unwrap();
        println!("finding-{i}: {what}");
    }
    if stats.crashes + stats.invariant_failures > 0 {
        std::process::exit(1);
    }
}
