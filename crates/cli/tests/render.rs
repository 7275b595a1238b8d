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
    for pass in ["terrain (gbuffers_textured_lit)", "water (gbuffers_water)", "composite", "pass-through composite"] {
        let p = passes.iter().find(|p| p["pass"] == pass).unwrap_or_else(|| panic!("no {pass} in {json}"));
        assert!(p["ms"].as_f64().is_some_and(|ms| ms >= 0.0), "{json}");
    }
    assert_eq!(report["non_finite_pixels"], 0);
}

#[test]
fn a_bad_option_is_a_usage_error_shown_on_one_line() {
    let out = tempfile::tempdir().unwrap();
    let render_dry = |sets: &[&str]| {
        let mut command = Command::new(env!("CARGO_BIN_EXE_tidepack"));
        command.args(["render", "tests/scenes/case1_above_dry.toml"]);
        for set in sets {
            command.args(["--set", set]);
        }
        command.arg("--out").arg(out.path()).current_dir(repo_root()).output().expect("run tidepack")
    };
    let forged = "FOAM=x\r\nerror: forged\x1b[2J";
    let output = render_dry(&["NO_SUCH_OPTION=1", forged]);
    assert_eq!(output.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("NO_SUCH_OPTION"), "{stderr}");
    assert!(!out.path().join("case1_above_dry.png").exists());
    let output = render_dry(&[forged]);
    assert_eq!(output.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("x^M^Jerror: forged^[[2J") && !stderr.contains('\x1b') && !stderr.contains('\r'), "{stderr}");
    assert_eq!(stderr.lines().filter(|l| l.starts_with("error")).count(), 1, "{stderr}");
}

/// Writes a pack of `files` (paths inside `shaders/`) into a new temporary folder.
fn pack_of(files: &[(&str, &str)]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for (path, text) in files {
        let at = dir.path().join("shaders").join(path);
        std::fs::create_dir_all(at.parent().unwrap()).unwrap();
        std::fs::write(at, text).unwrap();
    }
    dir
}

const FULLSCREEN_VSH: &str = "#version 120\nvarying vec2 uv;\nvoid main() { gl_Position = ftransform(); uv = gl_MultiTexCoord0.xy; }\n";

fn render_pack(pack: &Path, out: &Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_tidepack"))
        .args(["render", "tests/scenes/case4_above_near.toml", "--pack"])
        .arg(pack)
        .arg("--out")
        .arg(out)
        .current_dir(repo_root())
        .output()
        .expect("run tidepack")
}

#[test]
fn render_pack_writes_the_screen_and_a_report_of_every_pass() {
    let out = tempfile::tempdir().unwrap();
    let output = render_pack(&repo_root().join("tests/packs/flip_chain"), out.path());
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{stdout}\n{}", String::from_utf8_lossy(&output.stderr));
    image::open(out.path().join("case4_above_near.png")).expect("the screen as PNG");
    let json = std::fs::read_to_string(out.path().join("case4_above_near.json")).expect("the JSON report");
    let report: serde_json::Value = serde_json::from_str(&json).expect("the report parses");
    let passes: Vec<&str> = report["passes"].as_array().expect("passes").iter().filter_map(|p| p["pass"].as_str()).collect();
    assert_eq!(passes, ["sky (the loader's own)", "terrain (gbuffers_terrain)", "depth copy", "deferred", "water (gbuffers_water)", "composite", "composite1", "final"]);
    assert_eq!(report["non_finite_pixels"], 0);
    // flip_chain has no program for the sun and the moon; all else is imitated.
    assert_eq!(
        report["not_modelled"],
        serde_json::json!(["the sun and the moon: without a program of gbuffers_skytextured's chain the game's own are not drawn"])
    );
}

#[test]
fn render_pack_fails_on_nan_and_names_the_pass() {
    let pack = pack_of(&[
        ("final.vsh", FULLSCREEN_VSH),
        ("final.fsh", "#version 120\nuniform float viewWidth;\nvoid main() { gl_FragColor = vec4(sqrt(-viewWidth)); }\n"),
    ]);
    let out = tempfile::tempdir().unwrap();
    let output = render_pack(pack.path(), out.path());
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stdout}\n{stderr}");
    assert!(stderr.contains("NaN or Inf"), "{stderr}");
    assert!(stdout.lines().any(|l| l.contains("final") && l.contains("screen: 230400 NaN/Inf")), "{stdout}");
}

#[test]
fn render_pack_fails_when_a_program_the_loader_runs_does_not_load() {
    let pack = pack_of(&[
        ("composite.vsh", FULLSCREEN_VSH),
        ("composite.fsh", "#version 120\nvarying vec2 uv;\nvoid main() {\n    gl_FragData[0] = vec4(uv, missing, 1.0);\n}\n"),
    ]);
    let out = tempfile::tempdir().unwrap();
    let output = render_pack(pack.path(), out.path());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("composite does not load") && stderr.contains("composite.fsh:4"), "{stderr}");
}

/// A pack whose programs sit where OptiFine does not look (an Iris `dimension.properties`
/// folder) draws the game's own shading: that is no rendering of the pack.
#[test]
fn render_pack_fails_when_the_loader_loads_no_program_of_the_pack() {
    let pack = pack_of(&[
        ("dimension.properties", "dimension.dimension_overworld = *\n"),
        ("dimension_overworld/composite.vsh", FULLSCREEN_VSH),
        ("dimension_overworld/composite.fsh", "#version 120\nvarying vec2 uv;\nvoid main() {\n    gl_FragData[0] = vec4(uv, 0.0, 1.0);\n}\n"),
    ]);
    let out = tempfile::tempdir().unwrap();
    let output = render_pack(pack.path(), out.path());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("optifine-1.21 loads no program of this pack (none in shaders/)"), "{stderr}");
}

#[test]
fn render_pack_compares_the_screen_with_a_blessed_one() {
    let out = tempfile::tempdir().unwrap();
    let blessed = tempfile::tempdir().unwrap();
    let pack = repo_root().join("tests/packs/flip_chain");
    let run = |extra: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_tidepack"))
            .args(["render", "tests/scenes/case4_above_near.toml", "--pack"])
            .arg(&pack)
            .arg("--out")
            .arg(out.path())
            .arg("--expect")
            .arg(blessed.path())
            .args(extra)
            .current_dir(repo_root())
            .output()
            .expect("run tidepack")
    };
    let missing = run(&[]);
    assert_eq!(missing.status.code(), Some(2), "no blessed screen yet: {}", String::from_utf8_lossy(&missing.stderr));
    assert!(String::from_utf8_lossy(&missing.stderr).contains("--bless"));
    assert!(run(&["--bless"]).status.success());
    let same = run(&[]);
    assert!(same.status.success(), "{}", String::from_utf8_lossy(&same.stderr));
    assert!(String::from_utf8_lossy(&same.stdout).contains("mean FLIP 0.00000"));

    // A blessed screen that differs everywhere fails, with the FLIP map and the difference written.
    let path = blessed.path().join("case4_above_near.png");
    let mut image = image::open(&path).unwrap().to_rgba8();
    for p in image.pixels_mut() {
        p.0 = [255 - p.0[0], 255 - p.0[1], 255 - p.0[2], 255];
    }
    image.save(&path).unwrap();
    let different = run(&[]);
    assert_eq!(different.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&different.stderr).contains("mean FLIP"), "{}", String::from_utf8_lossy(&different.stderr));
    for file in ["case4_above_near.flip.png", "case4_above_near.difference.png"] {
        assert!(out.path().join(file).exists(), "{file}");
    }
}

/// A pack's own text in render's report (its "not imitated" list quotes shaders.properties
/// and the buffer formats a pack names) is shown, never acted on by the terminal.
#[test]
fn render_pack_prints_a_packs_control_characters_escaped() {
    let pack = pack_of(&[
        ("final.vsh", FULLSCREEN_VSH),
        ("final.fsh", "#version 120\nuniform sampler2D colortex0;\nvarying vec2 uv;\nvoid main() { gl_FragColor = texture2D(colortex0, uv); }\n"),
        ("shaders.properties", "#if UNDEFINED_\x1b[2J_MACRO(1) > 2\nclouds=off\n#endif\n"),
    ]);
    let out = tempfile::tempdir().unwrap();
    let output = render_pack(pack.path(), out.path());
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stdout}\n{stderr}");
    assert!(stdout.contains("^[[2J"), "the properties problem is listed, escaped: {stdout}");
    assert!(!stdout.contains('\x1b') && !stderr.contains('\x1b'), "{stdout:?}\n{stderr:?}");
}
