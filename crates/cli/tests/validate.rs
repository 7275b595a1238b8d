//! `tidepack validate` end to end: exit codes (0 clean, 1 shader errors, 2 unreadable input)
//! and the three output formats.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn tests_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/validate")
}

fn validate(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tidepack")).arg("validate").args(args).output().expect("run tidepack")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

#[test]
fn exit_codes_follow_the_verdict() {
    let clean = tests_dir().join("corpus/legacy120");
    let out = validate(&[clean.to_str().unwrap(), "--all-profiles"]);
    assert_eq!(out.status.code(), Some(0), "{}{}", text(&out.stdout), text(&out.stderr));
    assert!(text(&out.stdout).contains("0 errors, 0 warnings"), "{}", text(&out.stdout));

    let planted = tests_dir().join("planted/undeclared_identifier");
    let out = validate(&[planted.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let stderr = text(&out.stderr);
    assert!(stderr.contains("error: Unknown variable: colr"), "{stderr}");
    assert!(stderr.contains("undeclared_identifier/shaders/lib/color.glsl:4:"), "{stderr}");
    assert!(stderr.contains("return saturate3(colr);"), "snippet missing: {stderr}");

    let dir = tempfile::tempdir().unwrap();
    let garbage = dir.path().join("pack.zip");
    std::fs::write(&garbage, b"not a zip at all").unwrap();
    for bad in [garbage.to_str().unwrap(), "/nonexistent/pack"] {
        let out = validate(&[bad]);
        assert_eq!(out.status.code(), Some(2), "{bad}: {}", text(&out.stderr));
    }
    let out = validate(&[clean.to_str().unwrap(), "--profile", "NOPE"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("no profile `NOPE`"), "{}", text(&out.stderr));
}

#[test]
fn json_and_github_formats() {
    let planted = tests_dir().join("planted/varying_type_mismatch");
    let out = validate(&[planted.to_str().unwrap(), "--format", "json"]);
    assert_eq!(out.status.code(), Some(1));
    let json = text(&out.stdout);
    assert!(json.trim_start().starts_with('{') && json.trim_end().ends_with('}'), "{json}");
    assert!(json.contains("\"severity\": \"error\""), "{json}");
    assert!(json.contains("varying_type_mismatch/shaders/gbuffers_basic.fsh\", \"line\": 2"), "{json}");
    assert!(json.contains("\"program\": \"gbuffers_basic\", \"status\": \"invalid\""), "{json}");

    let out = validate(&[planted.to_str().unwrap(), "--format", "github"]);
    assert_eq!(out.status.code(), Some(1));
    let annotations = text(&out.stdout);
    let line = annotations.lines().find(|l| l.starts_with("::error ")).unwrap_or_else(|| panic!("{annotations}"));
    assert!(line.contains("file=") && line.contains("gbuffers_basic.fsh,line=2"), "{line}");

    // A warning (an output the render-target list drops) fails only with --deny-warnings.
    let drawbuffers = tests_dir().join("planted/wrong_drawbuffers");
    let out = validate(&[drawbuffers.to_str().unwrap(), "--format", "github"]);
    assert_eq!(out.status.code(), Some(0));
    assert!(text(&out.stdout).lines().any(|l| l.starts_with("::warning ") && l.contains("gbuffers_terrain.fsh,line=8")), "{}", text(&out.stdout));
    let out = validate(&[drawbuffers.to_str().unwrap(), "--deny-warnings"]);
    assert_eq!(out.status.code(), Some(1));
}
