//! `tidepack build`: prints the build summary or the diagnostics.

use std::process::ExitCode;

use tidepack_pack::BuildOptions;

use super::print_diagnostics;

pub fn run(opts: &BuildOptions) -> ExitCode {
    match tidepack_pack::build(opts) {
        Ok(report) => {
            println!(
                "Built {} {} (profile {}, {} options) in {:.2} s",
                report.pack_name,
                report.version,
                report.profile,
                report.options,
                report.elapsed.as_secs_f64()
            );
            for o in &report.outcomes {
                let v = &o.validation;
                let coverage = v.covered.map_or("no option sets", |c| c.describe());
                println!(
                    "  {:<22} {} programs, {} option sets ({coverage}); naga validated {} stages, {} skipped as identical",
                    o.dialect.to_string(),
                    v.programs,
                    v.option_sets,
                    v.stages_validated,
                    v.stages_identical
                );
                println!("  {:<22} {} ({:.1} KiB)", "", o.zip.display(), o.zip_bytes as f64 / 1024.0);
            }
            ExitCode::SUCCESS
        }
        Err(failure) => {
            print_diagnostics(&failure.diagnostics, &|path| failure.source_of(path));
            let errors = failure.diagnostics.iter().filter(|d| d.is_error()).count();
            eprintln!("build failed with {errors} error{}; no zip was written", if errors == 1 { "" } else { "s" });
            ExitCode::FAILURE
        }
    }
}
