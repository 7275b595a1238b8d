//! tidepack validate against Mesa's OpenGL driver on a folder of extracted packs: per pack, the
//! programs both accept, both reject, only tidepack rejects (false errors) and only Mesa rejects
//! (misses), and the time each takes; glslangValidator's time on the same programs for scale.
//! Every program is checked under the pack's defaults; programs only other loaders run are left
//! out, as `validate` leaves them out.
//!
//! With `--covering`, each pack is also validated under every configuration `--covering` chooses
//! (the defaults, every profile, the covering sets of each program's options): once alone, timed,
//! and once with `--driver`, where Mesa compiles and links every (program, set) pair validated;
//! a second table gives those pairs both accept, both reject, only Mesa rejects (misses) and
//! only tidepack rejects (false errors).
//!
//! With `--iris-dh`, the packs are read as Iris with Distant Horizons reads them (`--loader iris
//! --distant-horizons`): Iris's programs and the `dh_*` programs are compared too.
//!
//! `cargo run --release -p tidepack-validate --example corpus -- [--details FILE] [--covering]
//! [--threads N] [--iris-dh] PACK_DIR...` (tools/corpus runs it over every pack of a folder).

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use tidepack_loader::macros::StandardMacros;
use tidepack_loader::option_lines::OptionSet;
use tidepack_loader::{Loader, SetProvider};
use tidepack_loader::programs::RunBy;
use tidepack_validate::{Coverage, Options, Profiles, Status, driver, glslang};

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
    covering: Option<CoveringRow>,
}

/// `--covering`: every configuration validated, against Mesa.
#[derive(Default)]
struct CoveringRow {
    programs: usize,
    option_sets: usize,
    considered: usize,
    identical: usize,
    errors_defaults: usize,
    errors_covering: usize,
    both_accept: usize,
    both_reject: usize,
    misses: Vec<String>,
    false_errors: Vec<String>,
    /// `--covering` alone.
    tidepack: Duration,
    /// `--covering --driver`.
    with_driver: Duration,
}

fn main() {
    let mut args = std::env::args().skip(1);
    let mut details_path: Option<PathBuf> = None;
    let mut covering = false;
    let mut iris_dh = false;
    let mut threads = std::thread::available_parallelism().map_or(2, |n| n.get());
    let mut dirs: Vec<PathBuf> = Vec::new();
    while let Some(arg) = args.next() {
        if arg == "--details" {
            details_path = args.next().map(PathBuf::from);
        } else if arg == "--covering" {
            covering = true;
        } else if arg == "--iris-dh" {
            iris_dh = true;
        } else if arg == "--threads" {
            threads = args.next().and_then(|n| n.parse().ok()).unwrap_or(threads).max(1);
        } else {
            dirs.push(PathBuf::from(arg));
        }
    }
    if dirs.is_empty() {
        eprintln!("usage: corpus [--details FILE] [--covering] [--threads N] PACK_DIR...");
        std::process::exit(2);
    }
    let (loader, macros) = if iris_dh {
        (Loader::Iris, StandardMacros { distant_horizons: true, ..StandardMacros::for_loader(Loader::Iris) })
    } else {
        (Loader::default(), StandardMacros::default())
    };
    // Compared with Mesa: what only other drivers refuse is a warning here (`--target mesa`).
    let base = Options { macros: macros.clone(), loader, target: tidepack_glsl::Drivers::MESA, ..Options::default() };
    let gl = driver::Driver::new(&macros).unwrap_or_else(|e| {
        eprintln!("{e}");
        std::process::exit(2)
    });
    let scratch = std::env::temp_dir().join(format!("tidepack-corpus-{}", std::process::id()));
    std::fs::create_dir_all(&scratch).unwrap();
    let mut rows = Vec::new();
    let mut details = String::new();
    for dir in &dirs {
        let mut row = Row { pack: dir.file_name().map_or_else(|| dir.display().to_string(), |n| n.to_string_lossy().into_owned()), ..Row::default() };
        // One thread, as the driver and glslangValidator below run one program at a time.
        let options = Options { threads: 1, ..base.clone() };
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
        for program in report.pack.programs(loader) {
            if (program.run_by != RunBy::OptiFine && !iris_dh) || !program.has_stages() {
                continue;
            }
            let Some(ours) = report.programs.iter().find(|p| p.id == program.id()) else { continue };
            if matches!(ours.status, Status::Skipped(_)) {
                continue;
            }
            let started = Instant::now();
            let mesa = match gl.check(&program, &provider) {
                Ok(verdict) => verdict,
                Err(why) => {
                    writeln!(details, "{} {}: NOT COMPARED (Mesa gave no verdict: {why})", row.pack, program.id()).unwrap();
                    row.not_compared.push(program.id());
                    continue;
                }
            };
            row.mesa += started.elapsed();
            if let Ok(Some(verdict)) = glslang::check(&program, &provider, &macros, &scratch) {
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
        if covering {
            let errors_defaults = report.errors();
            let programs = report.programs.iter().filter(|p| !matches!(p.status, Status::Skipped(_))).count();
            match covering_row(dir, &Options { threads, ..base.clone() }, errors_defaults, programs, &row.pack, &mut details) {
                Ok(c) => row.covering = Some(c),
                Err(e) => eprintln!("{}: --covering: {e}", dir.display()),
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
    if covering {
        let read_as = if iris_dh { ", read as Iris with Distant Horizons" } else { "" };
        println!(
            "\nEvery configuration (`--covering`, {threads} threads{read_as}), Mesa compiling and linking every (program, set) pair validated:\n"
        );
        println!(
            "| pack | programs | option sets | program texts | distinct | errors (defaults) | errors (covering) | Mesa: both accept | both reject | misses | false errors | not given to Mesa | tidepack --covering s | with --driver s | Mesa defaults once s |"
        );
        println!("|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|");
        for row in &rows {
            let Some(c) = &row.covering else { continue };
            let compared = c.both_accept + c.both_reject + c.misses.len() + c.false_errors.len();
            println!(
                "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {:.1} | {:.1} | {:.2} |",
                row.pack,
                c.programs,
                c.option_sets,
                c.considered,
                c.considered - c.identical,
                c.errors_defaults,
                c.errors_covering,
                c.both_accept,
                c.both_reject,
                c.misses.len(),
                c.false_errors.len(),
                (c.considered - c.identical).saturating_sub(compared),
                c.tidepack.as_secs_f64(),
                c.with_driver.as_secs_f64(),
                row.mesa.as_secs_f64()
            );
        }
    }
    if let Some(path) = details_path {
        std::fs::write(&path, details).unwrap_or_else(|e| eprintln!("cannot write {}: {e}", path.display()));
    } else if !details.is_empty() {
        println!("\n{details}");
    }
}

/// `--covering` alone (timed), then with `--driver`: Mesa's verdict on every pair validated.
fn covering_row(
    dir: &std::path::Path,
    base: &Options,
    errors_defaults: usize,
    programs: usize,
    pack: &str,
    details: &mut String,
) -> Result<CoveringRow, String> {
    let options = Options { profiles: Profiles::Covering(Coverage::Pairwise), ..base.clone() };
    let started = Instant::now();
    let alone = tidepack_validate::validate_path(dir, &options).map_err(|e| e.to_string())?;
    let tidepack = started.elapsed();
    let started = Instant::now();
    let checked = tidepack_validate::validate_path(dir, &Options { driver: true, ..options }).map_err(|e| e.to_string())?;
    let with_driver = started.elapsed();
    let summary = checked.driver.ok_or("no driver summary")?;
    for id in &summary.only_driver_rejects {
        writeln!(details, "{pack} {id}: MISS under --covering (Mesa rejects)").unwrap();
    }
    for id in &summary.only_tidepack_rejects {
        writeln!(details, "{pack} {id}: FALSE ERROR under --covering").unwrap();
    }
    // Mesa's messages for the pairs only it rejects, and tidepack's errors, are in the report.
    for d in checked.diagnostics.iter().filter(|d| {
        !summary.only_driver_rejects.is_empty() && d.is_error() || d.code == tidepack_glsl::Code::DriverAccepts
    }) {
        writeln!(details, "    {}", d.to_string().replace('\n', "\n    ")).unwrap();
    }
    Ok(CoveringRow {
        programs,
        option_sets: alone.option_sets.len(),
        considered: alone.plan.considered,
        identical: alone.plan.identical,
        errors_defaults,
        errors_covering: alone.errors(),
        both_accept: summary.both_accept,
        both_reject: summary.both_reject,
        misses: summary.only_driver_rejects,
        false_errors: summary.only_tidepack_rejects,
        tidepack,
        with_driver,
    })
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
