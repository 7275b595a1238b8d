//! `tidepack compare` end to end: our pack beside a small pack of our own (tests/packs) on one
//! scene. Checks the files, that the water costs ours something, and the page's table and
//! pictures. Timings are never asserted beyond their sign.
//!
//! Needs lavapipe (Debian mesa-vulkan-drivers; tools/test installs it): without it this test
//! fails with an error naming the package. It never skips.

use std::path::Path;

use tidepack_bench::compare::{self, CompareConfig};

#[test]
fn our_pack_and_another_draw_a_scene_with_and_without_water() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let out = tempfile::tempdir().unwrap();
    let report = out.path().join("docs/compare.md");
    std::fs::create_dir_all(report.parent().unwrap()).unwrap();
    let config = CompareConfig {
        source_dir: root.join("shaderpack"),
        packs: vec![root.join("tests/packs/core_profile")],
        scenes: vec![(root.join("tests/scenes/case4_above_near.toml"), "near water".into())],
        frames: 2,
        rounds: 2,
        out_dir: out.path().join("compare"),
        report: Some(report.clone()),
        command: "test".into(),
    };
    let result = compare::run(&config).unwrap_or_else(|e| panic!("{e}"));
    let ours_name = &result.packs[0];
    assert!(ours_name.starts_with("Tidepack-") && ours_name.ends_with("-glsl330.zip"), "{:?}", result.packs);
    assert_eq!(result.packs[1], "core_profile");
    assert!(result.failures.is_empty(), "{:?}", result.failures);
    assert_eq!(result.measurements.len(), 2);
    let ours = &result.measurements[0];
    // Water over most of the screen: our composite shades it, the dry scene passes through.
    assert!(ours.water_cost > 0.5, "{ours:?}");
    assert!(ours.frame_cost > ours.water_cost, "{ours:?}");
    for m in &result.measurements {
        assert_eq!(m.non_finite_pixels, 0, "{m:?}");
        assert!(config.out_dir.join(&m.picture).is_file(), "{}", m.picture);
    }
    let row = image::open(config.out_dir.join(&result.rows[0].1)).unwrap();
    assert_eq!((row.width(), row.height()), (2 * 320 + 6, 180));
    let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(config.out_dir.join("compare.json")).unwrap()).unwrap();
    assert_eq!(json["measurements"].as_array().unwrap().len(), 2);
    let page = std::fs::read_to_string(&report).unwrap();
    assert!(page.contains(&format!("| {ours_name} |")) && page.contains("| core_profile |"), "{page}");
    assert!(page.contains("(compare/case4_above_near.png)"), "{page}");
    assert!(out.path().join("docs/compare/case4_above_near.png").is_file());
}
