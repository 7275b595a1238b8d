//! The bench end to end at a tiny resolution: one scene, two option sets. Checks that every
//! output exists and parses, that the errors are finite, that ULTRA (the profile closest to
//! the converged reference) scores better than LOW against it, and that the truth scores the
//! model's own error beside it. Timings are never asserted.
//!
//! Needs lavapipe (Debian mesa-vulkan-drivers; tools/test installs it): without it this test
//! fails with an error naming the package. It never skips.

use std::path::{Path, PathBuf};

use tidepack_bench::{BenchConfig, RunSpec};

/// One scene at 96x54, two timed frames, every pixel of the reference, no report.
fn small_config(scene: &str, out_dir: PathBuf) -> BenchConfig {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    BenchConfig {
        source_dir: root.join("shaderpack"),
        scenes_dir: root.join("tests/scenes"),
        scene_filter: vec![scene.into()],
        frames: 2,
        resolution: Some([96, 54]),
        reference_stride: 1,
        out_dir,
        runs: None,
        report: None,
        command: "test".into(),
        progress: false,
        specialise: false,
    }
}

#[test]
fn quick_bench_writes_parseable_outputs_and_ultra_beats_low() {
    let out = tempfile::tempdir().unwrap();
    let report = out.path().join("docs/accuracy.md");
    std::fs::create_dir_all(report.parent().unwrap()).unwrap();
    let config = BenchConfig {
        runs: Some(vec![RunSpec::profile("LOW"), RunSpec::profile("ULTRA")]),
        report: Some(report.clone()),
        ..small_config("case4_above_near", out.path().join("bench"))
    };
    let result = tidepack_bench::run(&config).unwrap_or_else(|e| panic!("{e}"));
    let dir = out.path().join("bench");

    let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(dir.join("bench.json")).unwrap()).unwrap();
    assert_eq!(json["rows"].as_array().unwrap().len(), 2);
    assert_eq!(json["aggregates"].as_array().unwrap().len(), 2);

    let csv = std::fs::read_to_string(dir.join("bench.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    let columns = lines[0].split(',').count();
    assert_eq!(lines.len(), 1 + 2 + 2, "{csv}");
    for line in &lines[1..] {
        let fields: Vec<&str> = line.split(',').collect();
        assert_eq!(fields.len(), columns, "{line}");
        for f in &fields[6..13] {
            let v: f64 = f.parse().unwrap_or_else(|_| panic!("{f} in {line}"));
            assert!(v.is_finite(), "{line}");
        }
    }
    for png in [
        "pareto.png",
        "heatmaps/case4_above_near-LOW.png",
        "heatmaps/case4_above_near-ULTRA.png",
        "heatmaps/case4_above_near-ULTRA-truth.png",
        "truth/case4_above_near.png",
        "truth/case4_above_near-LOW.png",
    ] {
        let image = image::open(dir.join(png)).unwrap_or_else(|e| panic!("{png}: {e}"));
        assert!(image.width() > 0, "{png}");
    }
    let md = std::fs::read_to_string(&report).unwrap();
    assert!(md.contains("| LOW |") && md.contains("| ULTRA |"), "{md}");
    assert!(out.path().join("docs/accuracy-pareto.png").exists());
    // Both references are reported: the truth's section, columns and pictures beside the report.
    assert!(md.contains("## Against the truth") && md.contains("truth mean FLIP"), "{md}");
    assert!(md.contains("(accuracy-truth/case4_above_near-LOW.png)"), "{md}");
    assert!(out.path().join("docs/accuracy-truth/case4_above_near-LOW.png").exists());
    let compared = result.truth_pixels["case4_above_near"];
    assert!(compared > 96 * 54 / 2, "the pool fills most of case4's view, yet {compared} pixels were compared");
    for line in &lines[1..] {
        let fields: Vec<&str> = line.split(',').collect();
        for f in &fields[columns - 4..] {
            let v: f64 = f.parse().unwrap_or_else(|_| panic!("truth field {f} in {line}"));
            assert!(v.is_finite() || *f == "inf", "{line}");
        }
    }

    let low = &result.rows.iter().find(|r| r.run.name == "LOW").unwrap().error;
    let ultra = &result.rows.iter().find(|r| r.run.name == "ULTRA").unwrap().error;
    for e in [low, ultra] {
        assert!(e.max_abs.is_finite() && e.rmse.is_finite() && e.mean_flip.is_finite() && !e.psnr.is_nan(), "{e:?}");
    }
    println!("LOW {low:?}\nULTRA {ultra:?}");
    let truth = |name: &str| result.rows.iter().find(|r| r.run.name == name).unwrap().truth_error.unwrap();
    println!("against the truth: LOW {:?}\nULTRA {:?}", truth("LOW"), truth("ULTRA"));
    // The two references measure different things: ULTRA is its own model nearly converged,
    // and still a model of the light (no sunlight lost on its way down to the floor, no bending
    // of the floor's geometry, a screen-space mirror), so the truth is farther from it.
    assert!(truth("ULTRA").rmse > 10.0 * ultra.rmse, "truth {:?} vs converged {ultra:?}", truth("ULTRA"));
    assert!(truth("ULTRA").mean_flip > ultra.mean_flip, "truth {:?} vs converged {ultra:?}", truth("ULTRA"));
    assert!(ultra.rmse < low.rmse, "ULTRA {ultra:?} LOW {low:?}");
    assert!(ultra.mean_flip < low.mean_flip, "ULTRA {ultra:?} LOW {low:?}");
}

#[test]
fn specialising_for_the_scene_changes_no_error() {
    let out = tempfile::tempdir().unwrap();
    let config = |specialise: bool| BenchConfig {
        runs: Some(vec![RunSpec::profile("MEDIUM")]),
        specialise,
        ..small_config("case2_under_down", out.path().join(if specialise { "specialised" } else { "general" }))
    };
    let general = tidepack_bench::run(&config(false)).unwrap_or_else(|e| panic!("{e}"));
    let specialised = tidepack_bench::run(&config(true)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(general.rows.len(), 1);
    assert_eq!(specialised.rows.len(), 1);
    let (g, s) = (&general.rows[0], &specialised.rows[0]);
    // The folded constants are the values the uniforms held: same image, same error.
    assert!((g.error.max_abs - s.error.max_abs).abs() <= 1.0 / 255.0, "{:?} vs {:?}", g.error, s.error);
    assert!((g.error.rmse - s.error.rmse).abs() <= 1e-4, "{:?} vs {:?}", g.error, s.error);
    assert!(s.composite_ms > 0.0 && s.passthrough_ms > 0.0);
}

/// A scene name that is not there is an error naming it and the scenes there are.
#[test]
fn an_unknown_scene_is_named_with_the_available_ones() {
    let out = tempfile::tempdir().unwrap();
    let error = tidepack_bench::scene_files(&small_config("nope", out.path().to_path_buf())).unwrap_err();
    assert!(error.contains("no scene named nope") && error.contains("case4_above_near"), "{error}");
}
