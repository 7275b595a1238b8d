//! Measures tidepack validate against the references on the packs in tests/validate (or the
//! pack folders given as arguments): per program, tidepack's verdict (compile-level errors),
//! glslangValidator's (each stage of the text OptiFine would hand the driver: includes expanded,
//! standard macros, the case's profile) and Mesa's (`--driver`); then validation speed.
//!
//! `cargo run --release -p tidepack-validate --example compare [PACK_DIR...]`

use std::path::{Path, PathBuf};
use std::time::Instant;

use tidepack_loader::option_lines::OptionSet;
use tidepack_loader::programs;
use tidepack_loader::{Configuration, SetProvider};
use tidepack_validate::{Options, Profiles, Status, glslang};

fn profile_of(dir: &Path) -> Profiles {
    let args = std::fs::read_to_string(dir.join("args.txt")).unwrap_or_default();
    match args.split_whitespace().collect::<Vec<_>>().as_slice() {
        ["--profile", name] => Profiles::Named(name.to_string()),
        _ => Profiles::Defaults,
    }
}

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/validate");
    let mut dirs: Vec<PathBuf> = std::env::args().skip(1).map(PathBuf::from).collect();
    if dirs.is_empty() {
        for sub in ["corpus", "planted"] {
            dirs.extend(std::fs::read_dir(root.join(sub)).unwrap().map(|e| e.unwrap().path()));
        }
        dirs.sort();
    }
    let tmp = std::env::temp_dir().join(format!("tidepack-compare-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    let macros = tidepack_loader::macros::StandardMacros::default();
    let (mut programs_total, mut glslang_seconds, mut glslang_programs) = (0usize, 0.0f64, 0usize);
    let mut agree_glslang = [[0usize; 2]; 2]; // [tidepack rejects][glslang rejects]
    let mut agree_mesa = [[0usize; 2]; 2];
    let mut disagreements = Vec::new();
    for dir in &dirs {
        let options = Options { profiles: profile_of(dir), driver: true, threads: 1, ..Options::default() };
        let report = match tidepack_validate::validate_path(dir, &options) {
            Ok(r) => r,
            Err(e) => {
                eprintln!("{}: {e}", dir.display());
                continue;
            }
        };
        let pack = &report.pack;
        let set: OptionSet = match &options.profiles {
            Profiles::Named(name) => Configuration { profile: Some(name.clone()), ..Configuration::default() }.option_set_of(pack).unwrap().0,
            _ => OptionSet::new(),
        };
        let driver = report.driver.as_ref().unwrap();
        for program in programs::find_programs(pack.files.keys()) {
            let Some(ours) = report.programs.iter().find(|p| p.id == program.id()) else { continue };
            if matches!(ours.status, Status::Skipped(_)) {
                continue;
            }
            programs_total += 1;
            let name = format!("{}: {}", dir.file_name().unwrap().to_string_lossy(), program.id());
            let tidepack_rejects = ours.compile_error;
            // Mesa: disagreements are listed; otherwise it agrees with tidepack.
            let mesa_rejects = if driver.only_driver_rejects.contains(&program.id()) {
                true
            } else if driver.only_tidepack_rejects.contains(&program.id()) {
                false
            } else {
                tidepack_rejects
            };
            agree_mesa[tidepack_rejects as usize][mesa_rejects as usize] += 1;
            let provider = SetProvider::new(pack, &set);
            match glslang::check(&program, &provider, &macros, &tmp).unwrap_or_else(|e| panic!("{e}")) {
                Some(v) => {
                    let rejects = v.rejects;
                    glslang_seconds += v.elapsed.as_secs_f64();
                    glslang_programs += 1;
                    agree_glslang[tidepack_rejects as usize][rejects as usize] += 1;
                    if rejects != tidepack_rejects {
                        let why = v.errors.first().cloned().unwrap_or_default();
                        disagreements.push(format!("glslang {} but tidepack {}: {name} {why}", verdict(rejects), verdict(tidepack_rejects)));
                    }
                }
                None => disagreements.push(format!("glslang not run (includes cannot be expanded): {name}")),
            }
            if mesa_rejects != tidepack_rejects {
                disagreements.push(format!("Mesa {} but tidepack {}: {name}", verdict(mesa_rejects), verdict(tidepack_rejects)));
            }
        }
    }
    std::fs::remove_dir_all(&tmp).ok();
    let table = |name: &str, m: [[usize; 2]; 2]| {
        let total: usize = m.iter().flatten().sum();
        println!(
            "{name}: {total} programs; both accept {}, both reject {}, only {name} rejects {}, only tidepack rejects {} -> agreement {:.1}%",
            m[0][0],
            m[1][1],
            m[0][1],
            m[1][0],
            100.0 * (m[0][0] + m[1][1]) as f64 / total.max(1) as f64
        );
    };
    println!("{} packs, {programs_total} programs validated", dirs.len());
    table("glslangValidator", agree_glslang);
    table("Mesa", agree_mesa);
    for d in &disagreements {
        println!("  {d}");
    }

    // Speed on the corpus: tidepack (one thread and all threads, no driver) against glslangValidator.
    let corpus: Vec<&PathBuf> = dirs.iter().filter(|d| d.to_string_lossy().contains("corpus")).collect();
    for threads in [1, std::thread::available_parallelism().map_or(2, |n| n.get())] {
        let mut programs = 0;
        let started = Instant::now();
        let rounds = 10;
        for _ in 0..rounds {
            for dir in &corpus {
                let options = Options { threads, ..Options::default() };
                let report = tidepack_validate::validate_path(dir, &options).unwrap();
                programs += report.programs.iter().filter(|p| !matches!(p.status, Status::Skipped(_))).count();
            }
        }
        let seconds = started.elapsed().as_secs_f64();
        println!("tidepack validate ({threads} thread(s)): {programs} programs in {seconds:.2} s = {:.0} programs/s", programs as f64 / seconds);
    }
    println!(
        "glslangValidator (one process per stage, as measured above): {glslang_programs} programs in {glslang_seconds:.2} s = {:.0} programs/s",
        glslang_programs as f64 / glslang_seconds.max(1e-9)
    );
}

fn verdict(rejects: bool) -> &'static str {
    if rejects { "rejects" } else { "accepts" }
}
