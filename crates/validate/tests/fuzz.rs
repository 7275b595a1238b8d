//! Bounded fuzzing runs over the corpus packs, the CI smoke run: every execution must end
//! without a panic in tidepack's code and without a broken invariant, through the whole
//! validator and through each cargo-fuzz target's check (`fuzz::targets`). Longer runs:
//! `cargo run --release -p tidepack-validate --example fuzz -- SECONDS [SEED]`, and coverage-
//! guided ones with `tools/fuzz` (docs/fuzzing.md).

use std::path::Path;
use std::time::Duration;

use tidepack_validate::fuzz;

/// The corpus and planted packs, as seeds.
fn corpus_seeds() -> Vec<fuzz::SeedPack> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/validate");
    let mut dirs: Vec<_> = std::fs::read_dir(root.join("corpus")).unwrap().map(|e| e.unwrap().path()).collect();
    dirs.extend(std::fs::read_dir(root.join("planted")).unwrap().map(|e| e.unwrap().path()));
    dirs.sort();
    fuzz::seeds_from(&dirs)
}

/// Each finding with its input, for a failure message.
fn shown(stats: &fuzz::FuzzStats) -> String {
    let findings: Vec<String> =
        stats.findings.iter().map(|(what, input)| format!("{what}\n--- input ---\n{}", String::from_utf8_lossy(input))).collect();
    findings.join("\n\n")
}

#[test]
fn fuzzing_the_corpus_finds_no_crash() {
    let seeds = corpus_seeds();
    assert!(seeds.len() >= 10);
    let stats = fuzz::run(&seeds, 600, Duration::from_secs(45), 0x7469_6465);
    eprintln!("fuzz: {stats:?}");
    assert!(stats.executions >= 100, "{stats:?}");
    assert_eq!(stats.crashes + stats.invariant_failures, 0, "{}", shown(&stats));
}

#[test]
fn the_fuzz_targets_hold_on_mutated_corpus_files() {
    let seeds = corpus_seeds();
    let stats = fuzz::run_targets(&seeds, 20_000, Duration::from_secs(30), 0x6675_7a7a);
    eprintln!("fuzz targets: {stats:?}");
    assert!(stats.executions >= 1_000, "{stats:?}");
    assert_eq!(stats.crashes, 0, "{}", shown(&stats));
}
