//! tidepack validate against Mesa's OpenGL driver on a folder of extracted packs: per pack, the
//! programs both accept, both reject, only tidepack rejects (false errors) and only Mesa rejects
//! (misses), and the time each takes; glslangValidator's time on the same programs for scale.
//! Every program is checked under the pack's defaults; programs only other loaders run are left
//! out, as `validate` leaves them out.
//!
//! `cargo run --release -p tidepack-validate --example corpus -- [--details FILE] PACK_DIR...`
//! (tools/corpus runs it over every pack of a folder).

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use tidepack_loader::macros::StandardMacros;
use tidepack_loader::option_lines::OptionSet;
use tidepack_loader::SetProvider;
use tidepack_loader::programs::{self, RunBy};
use tidepack_validate::{Options, Status, driver, glslang};

#[derive(Default)]
struct Row {
    pack: String,
    agreed_valid: usize,
    agreed_invalid: usize,
    false_errors: Vec<String>,
    misses: Vec<String>,
    /// Programs whose text could not be expanded for Mesa (an include tidepack refuses), or
    /// whose `#version` this Mesa cannot compile.
    not_compared: Vec<String>,
    tidepack: Duration,
    mesa: Duration,
    glslang: Duration,
    glslang_programs: usize,
}

fn main() {
    let mut args = std::env::args().skip(1);
    let mut details_path: Option<PathBuf> = None;
    let mut dirs: Vec<PathBuf> = Vec::new();
    while let Some(arg) = args.next() {
        if arg == "--details" {
            details_path = args.next().map(PathBuf::from);
        } else {
            dirs.push(PathBuf::from(arg));
        }
    }
    if dirs.is_empty() {
        eprintln!("usage: corpus [--details FILE] PACK_DIR...");
        std::process::exit(2);
    }
    let macros = StandardMacros::default();
    let gl = driver::Driver::new(&macros).unwrap_or_else(|e| {
        eprintln!("{e}");
        std::process::exit(2)
    });
    let defines = macros.define_lines();
    let scratch = std::env::temp_dir().join(format!("tidepack-corpus-{}", std::process::id()));
    std::fs::create_dir_all(&scratch).unwrap();
    let mut rows = Vec::new();
    let mut details = String::new();
    for dir in &dirs {
        let mut row = Row { pack: dir.file_name().map_or_else(|| dir.display().to_string(), |n| n.to_string_lossy().into_owned()), ..Row::default() };
        // One thread, as the driver and glslangValidator below run one program at a time.
        let options = Options { threads: 1, ..Options::default() };
        let started = Instant::now();
        let report = match tidepack_validate::validate_path(dir, &options) {
            Ok(r) => r,
            Err(e) => {
                eprintln!("{}: {e}", dir.display());
                continue;
            }
        };
        row.tidepack = started.elapsed();
        let set = OptionSet::new();
        let provider = SetProvider::new(&report.pack, &set);
        for program in programs::find_programs(report.pack.files.keys()) {
            if program.run_by != RunBy::OptiFine || !program.has_stages() {
                continue;
            }
            let Some(ours) = report.programs.iter().find(|p| p.id == program.id()) else { continue };
            if matches!(ours.status, Status::Skipped(_)) {
                continue;
            }
            let started = Instant::now();
            let mesa = gl.check(&program, &provider);
            row.mesa += started.elapsed();
            if let Ok(Some(verdict)) = glslang::check(&program, &provider, &defines, &scratch) {
                row.glslang += verdict.elapsed;
                row.glslang_programs += 1;
            }
            let id = program.id();
            if matches!(&mesa, Err(diags) if diags.is_empty()) {
                let ours: Vec<String> = ours.diagnostics.iter().map(|&i| report.diagnostics[i].to_string()).collect();
                writeln!(details, "{} {id}: NOT COMPARED (not expanded for Mesa)\n    {}", row.pack, ours.join("\n    ")).unwrap();
                row.not_compared.push(id);
                continue;
            }
            // A `#version` this Mesa does not have (llvmpipe stops at 4.50) says nothing of the
            // shader: the program is not compared, and tidepack's verdict goes to the details.
            if let Err(theirs) = &mesa
                && theirs.iter().any(|d| d.message.contains("is not supported. Supported versions are"))
            {
                let verdict = if ours.compile_error { "invalid" } else { "valid" };
                let ours: Vec<String> = ours.diagnostics.iter().map(|&i| report.diagnostics[i].to_string()).collect();
                writeln!(details, "{} {id}: NOT COMPARED (Mesa lacks its #version; tidepack: {verdict})\n    {}", row.pack, ours.join("\n    ")).unwrap();
                row.not_compared.push(id);
                continue;
            }
            match (ours.compile_error, &mesa) {
                (false, Ok(())) => row.agreed_valid += 1,
                (true, Err(_)) => row.agreed_invalid += 1,
                (true, Ok(())) => {
                    let ours: Vec<String> = ours
                        .diagnostics
                        .iter()
                        .map(|&i| &report.diagnostics[i])
                        .filter(|d| d.is_error())
                        .map(|d| d.to_string())
                        .collect();
                    writeln!(details, "{} {id}: FALSE ERROR\n    {}", row.pack, ours.join("\n    ")).unwrap();
                    row.false_errors.push(id);
                }
                (false, Err(theirs)) => {
                    let theirs: Vec<String> = theirs.iter().filter(|d| d.is_error()).map(|d| d.to_string()).collect();
                    writeln!(details, "{} {id}: MISS (Mesa rejects)\n    {}", row.pack, theirs.join("\n    ")).unwrap();
                    row.misses.push(id);
                }
            }
        }
        eprintln!(
            "{}: {} valid, {} invalid, {} false errors, {} misses, {} not compared",
            row.pack,
            row.agreed_valid,
            row.agreed_invalid,
            row.false_errors.len(),
            row.misses.len(),
            row.not_compared.len()
        );
        rows.push(row);
    }
    std::fs::remove_dir_all(&scratch).ok();
    println!("Mesa: {}\n", gl.describe());
    println!("| pack | agreed valid | agreed invalid | false errors | misses | not compared | tidepack s | Mesa s | glslang s |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    let mut total = Row { pack: "**total**".into(), ..Row::default() };
    for row in &rows {
        print_row(row);
        total.agreed_valid += row.agreed_valid;
        total.agreed_invalid += row.agreed_invalid;
        total.false_errors.extend(row.false_errors.iter().cloned());
        total.misses.extend(row.misses.iter().cloned());
        total.not_compared.extend(row.not_compared.iter().cloned());
        total.tidepack += row.tidepack;
        total.mesa += row.mesa;
        total.glslang += row.glslang;
        total.glslang_programs += row.glslang_programs;
    }
    print_row(&total);
    let seconds = |d: Duration| d.as_secs_f64().max(1e-9);
    println!(
        "\nSpeed, one thread each: tidepack validate {:.2} s, Mesa compiling and linking the same expanded programs {:.2} s \
         ({:.2}x tidepack's time), glslangValidator {:.2} s for {} programs ({:.2}x)",
        seconds(total.tidepack),
        seconds(total.mesa),
        seconds(total.mesa) / seconds(total.tidepack),
        seconds(total.glslang),
        total.glslang_programs,
        seconds(total.glslang) / seconds(total.tidepack),
    );
    if let Some(path) = details_path {
        std::fs::write(&path, details).unwrap_or_else(|e| eprintln!("cannot write {}: {e}", path.display()));
    } else if !details.is_empty() {
        println!("\n{details}");
    }
}

fn print_row(row: &Row) {
    println!(
        "| {} | {} | {} | {} | {} | {} | {:.2} | {:.2} | {:.2} |",
        row.pack,
        row.agreed_valid,
        row.agreed_invalid,
        row.false_errors.len(),
        row.misses.len(),
        row.not_compared.len(),
        row.tidepack.as_secs_f64(),
        row.mesa.as_secs_f64(),
        row.glslang.as_secs_f64()
    );
}
