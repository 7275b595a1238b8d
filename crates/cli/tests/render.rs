//! `tidepack render` as a user runs it: one scene to a PNG and a JSON report. Needs lavapipe
//! (Debian mesa-vulkan-drivers); without it the command fails naming the package, and so does
//! this test.

#![cfg(feature = "render")]

use std::path::{Path, PathBuf};
use std::process::Command;

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").canonicalize().unwrap()
}

#[test]
fn render_writes_the_image_and_a_report() {
    let out = tempfile::tempdir().unwrap();
    let output = Command::new(env!("CARGO_BIN_EXE_tidepack"))
        .args(["render", "tests/scenes/case4_above_near.toml", "--dialect", "120", "--profile", "MEDIUM", "--set", "FOAM=off", "--buffers", "--out"])
        .arg(out.path())
        .current_dir(repo_root())
        .output()
        .expect("run tidepack");
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "tidepack render failed:\n{stdout}\n{stderr}");
    assert!(stdout.contains("composite"), "{stdout}");

    let png = out.path().join("case4_above_near.png");
    let image = image::open(&png).unwrap_or_else(|e| panic!("{}: {e}", png.display()));
    assert_eq!((image.width(), image.height()), (640, 360));
    for buffer in ["colortex0", "colortex4", "depthtex0", "depthtex1"] {
        let p = out.path().join(format!("case4_above_near.{buffer}.png"));
        image::open(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
    }

    let json = std::fs::read_to_string(out.path().join("case4_above_near.json")).expect("the JSON report");
    let report: serde_json::Value = serde_json::from_str(&json).expect("the report parses");
    assert_eq!(report["scene"], "case4_above_near");
    assert_eq!(report["resolution"], serde_json::json!([640, 360]));
    assert_eq!(report["dialect"], "120");
    assert_eq!(report["profile"], "MEDIUM");
    assert_eq!(report["options"]["FOAM"], "off", "{json}");
    assert!(report["adapter"]["name"].as_str().is_some_and(|n| !n.is_empty()), "{json}");
    assert!(report["adapter"]["backend"].is_string() && report["adapter"]["device_type"].is_string());
    let passes = report["passes"].as_array().expect("passes");
    for pass in ["terrain", "gbuffers_water", "composite", "pass-through composite"] {
        let p = passes.iter().find(|p| p["pass"] == pass).unwrap_or_else(|| panic!("no {pass} in {json}"));
        assert!(p["ms"].as_f64().is_some_and(|ms| ms >= 0.0), "{json}");
    }
    assert_eq!(report["non_finite_pixels"], 0);
}

#[test]
fn a_bad_option_is_an_error() {
    let out = tempfile::tempdir().unwrap();
    let output = Command::new(env!("CARGO_BIN_EXE_tidepack"))
        .args(["render", "tests/scenes/case1_above_dry.toml", "--set", "NO_SUCH_OPTION=1", "--out"])
        .arg(out.path())
        .current_dir(repo_root())
        .output()
        .expect("run tidepack");
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("NO_SUCH_OPTION"));
    assert!(!out.path().join("case1_above_dry.png").exists());
}
