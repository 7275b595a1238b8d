//! The exit-code rule of every command (README, "Exit codes"): 0 clean, 1 findings, 2 the
//! command cannot run (bad argument, unreadable input), each with a one-line error.

use std::path::{Path, PathBuf};
use std::process::Command;

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").canonicalize().unwrap()
}

/// Runs `tidepack ARGS` in the repository root; returns the exit code and stderr.
fn tidepack(args: &[&str]) -> (Option<i32>, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_tidepack")).args(args).current_dir(repo_root()).output().expect("run tidepack");
    (out.status.code(), String::from_utf8_lossy(&out.stderr).into_owned())
}

#[test]
fn a_command_that_cannot_run_exits_2_with_a_one_line_error() {
    let out = tempfile::tempdir().unwrap();
    let out = out.path().to_str().unwrap();
    let cases: &[(&[&str], &str)] = &[
        (&["validate", "/nonexistent/pack"], "/nonexistent/pack"),
        (&["validate", "tests/validate/corpus/legacy120", "--allow", "nope"], "no diagnostic code `nope`"),
        (&["validate", "tests/validate/corpus/legacy120", "--gl-version", "four"], "four"),
        (&["validate", "tests/validate/corpus/legacy120", "--distant-horizons"], "needs --loader iris"),
        (&["build", "--source", "/nonexistent/pack", "--out", out], "holds no pack.toml"),
        (&["build", "--profile", "NOPE", "--out", out], "no profile named NOPE"),
        (&["render", "no_such_scene", "--out", out], "built-in scenes are"),
        (&["render", "case4_above_near", "--set", "NOPE=1", "--out", out], "NOPE"),
        (&["render", "case4_above_near", "--pack", "/nonexistent/pack", "--out", out], "/nonexistent/pack"),
        (&["stress", "--cases", "zero"], "zero"),
        (&["bench", "--nonsense"], "--nonsense"),
        (&["compare", "--pack", "/nonexistent/pack", "--out", out], "cannot read pack /nonexistent/pack"),
        (&["compare", "--scene", "/nonexistent/scene.toml", "--out", out], "/nonexistent/scene.toml"),
        (&["compare", "--scene", "README.md", "--out", out], "README.md"),
        (&["codes", "--nonsense"], "--nonsense"),
        (&["no-such-command"], "no-such-command"),
    ];
    for (args, said) in cases {
        let (code, stderr) = tidepack(args);
        assert_eq!(code, Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(said), "{args:?} should say {said:?}: {stderr}");
        let first = stderr.lines().find(|l| l.starts_with("error")).unwrap_or_else(|| panic!("{args:?}: no error line: {stderr}"));
        assert!(first.len() > "error: ".len(), "{args:?}: {stderr}");
    }
}

#[test]
fn findings_exit_1_and_a_clean_check_0() {
    let (code, stderr) = tidepack(&["validate", "tests/validate/planted/undeclared_identifier"]);
    assert_eq!(code, Some(1), "{stderr}");
    // What `render` rewrites for OpenGL (NVIDIA accepts it) stays an error for validate.
    let (code, stderr) = tidepack(&["validate", "tests/packs/lenient"]);
    assert_eq!(code, Some(1), "{stderr}");
    for refused in ["#extension after code", "hidden-builtin"] {
        assert!(stderr.contains(refused), "{refused}: {stderr}");
    }
    let (code, stderr) = tidepack(&["validate", "tests/validate/corpus/legacy120"]);
    assert_eq!(code, Some(0), "{stderr}");
    let (code, stderr) = tidepack(&["codes"]);
    assert_eq!(code, Some(0), "{stderr}");
}
