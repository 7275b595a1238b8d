//! Scenes `tidepack render` cannot render faithfully are refused before any work, with the
//! file and the reason. Needs lavapipe (Debian mesa-vulkan-drivers) for the device limits.

#![cfg(feature = "render")]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").canonicalize().unwrap()
}

/// Renders case4 with `edit` applied to its text; returns the output and how long it took.
fn render_edited(edit: impl Fn(&str) -> String) -> (Output, Duration, PathBuf, tempfile::TempDir) {
    let work = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(repo_root().join("tests/scenes/case4_above_near.toml")).unwrap();
    let edited = edit(&text);
    assert_ne!(edited, text);
    let scene = work.path().join("edited.toml");
    std::fs::write(&scene, edited).unwrap();
    let started = Instant::now();
    let output = Command::new(env!("CARGO_BIN_EXE_tidepack"))
        .arg("render")
        .arg(&scene)
        .arg("--out")
        .arg(work.path().join("out"))
        .current_dir(repo_root())
        .output()
        .expect("run tidepack");
    (output, started.elapsed(), scene, work)
}

#[test]
fn a_resolution_over_the_device_limits_is_refused_up_front() {
    let (output, took, _, work) = render_edited(|t| t.replacen("resolution = [640, 360]", "resolution = [8192, 8192]", 1));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success(), "{stderr}");
    assert!(stderr.contains("resolution 8192x8192 is too large") && stderr.contains("max_buffer_size"), "{stderr}");
    assert!(stderr.contains("scene case4_above_near:"), "the error does not name the scene: {stderr}");
    assert!(stderr.contains("largest square resolution is 4096x4096"), "{stderr}");
    assert!(took < Duration::from_secs(10), "refused only after {took:?}");
    assert!(!work.path().join("out").exists(), "a refused scene wrote output");
}

#[test]
fn non_finite_scene_values_are_refused_with_the_field() {
    let (output, _, scene, _work) = render_edited(|t| t.replacen("yaw = 180.0", "yaw = nan", 1));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success(), "{stderr}");
    assert!(stderr.contains(&scene.display().to_string()) && stderr.contains("camera.yaw is NaN"), "{stderr}");
}
