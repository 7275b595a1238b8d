//! tidepack validate against the two references on the packs of tests/validate: Mesa's OpenGL
//! driver (through `--driver`) and glslangValidator. Both must be installed (tools/test installs
//! glslang-tools and libegl1 libegl-mesa0 libgl1-mesa-dri); without them these tests fail, they
//! never skip.

mod common;

use std::path::{Path, PathBuf};

use tidepack_loader::option_lines::OptionSet;
use tidepack_loader::programs;
use tidepack_loader::{Configuration, SetProvider};
use tidepack_validate::{Options, Profiles, Status, glslang, validate_path};

fn packs() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/validate");
    let mut dirs = Vec::new();
    for sub in ["corpus", "accepted", "planted"] {
        dirs.extend(std::fs::read_dir(root.join(sub)).unwrap().map(|e| e.unwrap().path()));
    }
    dirs.sort();
    dirs
}

#[test]
fn mesa_agrees_with_tidepack_on_every_program() {
    let mut compared = 0;
    for dir in packs() {
        let options = Options { driver: true, ..common::case_options(&dir) };
        let report = validate_path(&dir, &options).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
        let driver = report.driver.as_ref().expect("a driver summary");
        assert!(
            driver.only_driver_rejects.is_empty() && driver.only_tidepack_rejects.is_empty(),
            "{}: {driver:?}",
            dir.display()
        );
        compared += driver.both_accept + driver.both_reject;
    }
    assert!(compared >= 35, "{compared} programs compared");
}

#[test]
fn glslang_disagrees_only_where_it_is_stricter_or_does_not_link() {
    let scratch = tempfile::tempdir().unwrap();
    let (mut agree, mut total) = (0, 0);
    let mut unexplained = Vec::new();
    for dir in packs() {
        let options = common::case_options(&dir);
        let report = validate_path(&dir, &options).unwrap();
        let set = match options.profiles {
            Profiles::Named(name) => Configuration { profile: Some(name), ..Configuration::default() }.option_set_of(&report.pack).unwrap().0,
            _ => OptionSet::new(),
        };
        let provider = SetProvider::new(&report.pack, &set);
        for program in programs::find_programs(report.pack.files.keys()) {
            let Some(ours) = report.programs.iter().find(|p| p.id == program.id() && !matches!(p.status, Status::Skipped(_))) else {
                continue;
            };
            let Some(verdict) = glslang::check(&program, &provider, &options.macros, scratch.path()).unwrap_or_else(|e| panic!("{e}")) else {
                continue;
            };
            total += 1;
            if verdict.rejects == ours.compile_error {
                agree += 1;
                continue;
            }
            // glslang enforces GLSL 4.20 for line continuations and 4.60 for empty declarations
            // (drivers accept both; tidepack warns of the second), wants GL_ARB_shader_texture_lod
            // for `texture2DLod` in a fragment shader where GL_EXT_gpu_shader4 (which it lacks)
            // brings it too, and compiles stages alone, so
            // it cannot see a vertex/fragment mismatch; it accepts `#extension` after code and
            // converts return values before GLSL 4.20, both of which Mesa refuses, it lets a
            // fragment shader write gl_FragData beside its own `out` variables, which Mesa
            // refuses, it asks for `flat` on integer fragment inputs but not on the members
            // of an input block, it gives textureQueryLod to GLSL 3.30, which Mesa does not, and
            // it has extensions some drivers lack (the subgroup ones).
            let stricter = verdict.rejects
                && verdict.errors.iter().all(|e| e.contains("line continuation")
                        || e.contains("missing #endif")
                        || e.contains("extraneous semicolon")
                        || e.contains("required extension not requested: GL_ARB_shader_texture_lod")
                        || e.contains("compilation terminated"));
            let link_only = !verdict.rejects && report.diagnostics.iter().any(|d| d.message.contains("fails to link"));
            let lenient = !verdict.rejects
                && report.diagnostics.iter().any(|d| d.message.contains("#extension after code")
                    || d.message.contains("converts return values only")
                    || d.message.contains("and its own output")
                    || d.message.contains("textureQueryLod() needs GLSL 4.00")
                    || d.message.contains("needs an extension that")
                    || (d.message.contains("must be qualified `flat`")
                        && d.message.split('`').nth(1).is_some_and(|input| input.contains('.'))));
            if !(stricter || link_only || lenient) {
                unexplained.push(format!("{}: {} glslang={} tidepack={} {:?}", dir.display(), program.id(), verdict.rejects, ours.compile_error, verdict.errors));
            }
        }
    }
    assert!(total >= 35, "{total} programs compared");
    assert!(agree * 10 >= total * 7, "agreement {agree}/{total}");
    assert!(unexplained.is_empty(), "{}", unexplained.join("\n"));
}
