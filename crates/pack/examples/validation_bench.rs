//! Benchmark: validating the pack with naga (in process) against glslangValidator on the same
//! stage texts (one process per file, as a CI script would run it).
//!
//! `cargo run --release -p tidepack-pack --example validation_bench [runs] [--exhaustive]`
//! Prints medians over `runs` (default 7) and the ratio, measured in the same process.
use std::time::Instant;

use tidepack_glsl::preprocess::expand_includes;
use tidepack_glsl::Stage;
use tidepack_pack::build::generate_validated;
use tidepack_loader::macros::StandardMacros;
use tidepack_pack::dialect::Dialect;
use tidepack_pack::shipped::WithOptions;
use tidepack_pack::source::PackSource;
use tidepack_pack::option_sets::Coverage;
use tidepack_pack::pack_options;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let runs: usize = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(7);
    let coverage = if std::env::args().any(|a| a == "--exhaustive") { Coverage::Exhaustive } else { Coverage::Pairwise };
    let source = PackSource::load("shaderpack".as_ref()).expect("run from the repository root");
    let options = pack_options::collect(&source).unwrap();
    let mut naga_times = Vec::new();
    let mut packs = Vec::new();
    for _ in 0..runs {
        let started = Instant::now();
        packs = generate_validated(&source, &options, &Dialect::ALL, &Default::default(), coverage, None, None).map_err(|f| f.diagnostics).unwrap().0;
        naga_times.push(started.elapsed().as_secs_f64());
    }
    let work = std::env::temp_dir().join(format!("tidepack-bench-{}", std::process::id()));
    std::fs::create_dir_all(&work).unwrap();
    let mut files = Vec::new();
    for (pack, report) in &packs {
        let macros = StandardMacros::default().define_lines();
        for (i, (path, set)) in report.validated.iter().enumerate() {
            let provider = WithOptions::new(pack, set);
            let text = expand_includes(&provider, path, &macros).unwrap();
            let file = work.join(format!("{}-{i}-{}", pack.dialect.slug(), path.replace('/', "_")));
            std::fs::write(&file, text).unwrap();
            files.push((file, Stage::from_path(path).unwrap()));
        }
    }
    let mut glslang_times = Vec::new();
    for _ in 0..runs {
        let started = Instant::now();
        for (file, stage) in &files {
            let kind = if *stage == Stage::Vertex { "vert" } else { "frag" };
            let ok = std::process::Command::new("glslangValidator").args(["-S", kind]).arg(file).output().expect("glslangValidator").status.success();
            assert!(ok, "glslangValidator rejects {}", file.display());
        }
        glslang_times.push(started.elapsed().as_secs_f64());
    }
    std::fs::remove_dir_all(&work).unwrap();
    let sets: usize = packs.iter().map(|(_, r)| r.option_sets).sum();
    let stages: usize = packs.iter().map(|(_, r)| r.stages_validated).sum();
    let skipped: usize = packs.iter().map(|(_, r)| r.stages_identical).sum();
    let (naga, glslang) = (median(naga_times), median(glslang_times));
    println!("both dialects: {sets} option sets, {stages} distinct stages validated, {skipped} skipped as identical");
    println!("tidepack (generate + preprocess + lower + naga): median {:.1} ms over {runs} runs", naga * 1e3);
    println!("glslangValidator on the same {} stage texts:  median {:.1} ms over {runs} runs", files.len(), glslang * 1e3);
    println!("ratio glslangValidator / tidepack: {:.1}x", glslang / naga);
}
