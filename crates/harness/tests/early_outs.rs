//! The composite's early-outs (option `EARLY_OUTS`) skip only work whose result cannot show, so
//! switching them off must leave the picture as it is, apart from the few pixels where the
//! bisection's early stop moves a reflection across a depth edge. Times of both are in
//! docs/skipping.md. Needs lavapipe (Debian mesa-vulkan-drivers, installed by tools/test);
//! fails, never skips, without it.

use std::path::{Path, PathBuf};

use tidepack_harness::{Gpu, PackSelection, Scene, images, program, render_wgpu, scene};
use tidepack_pack::Dialect;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Share of pixels allowed to differ by more than 2/255: measured at most 0.19% (case4).
const MAX_SHARE_DIFFERENT: f64 = 0.005;

#[test]
fn switching_the_early_outs_off_leaves_the_picture() {
    let gpu = Gpu::new().unwrap_or_else(|e| panic!("{e}"));
    let scenes = scene::scene_files(&root().join("tests/scenes")).unwrap_or_else(|e| panic!("{e}"));
    assert!(scenes.len() >= 8, "{scenes:?}");
    let selection = |options: Vec<(String, String)>| PackSelection {
        source_dir: root().join("shaderpack"),
        dialect: Dialect::Glsl330,
        profile: None,
        options,
    };
    let with = program::load(&selection(vec![])).unwrap_or_else(|e| panic!("{e}"));
    let without = program::load(&selection(vec![("EARLY_OUTS".into(), "off".into())])).unwrap_or_else(|e| panic!("{e}"));
    for path in &scenes {
        let scene = Scene::load(path).unwrap_or_else(|e| panic!("{e}"));
        let a = render_wgpu(&gpu, &with, &scene).unwrap_or_else(|e| panic!("{e}"));
        let b = render_wgpu(&gpu, &without, &scene).unwrap_or_else(|e| panic!("{e}"));
        let over = images::count_differing(&a.image, &b.image, 2.0 / 255.0);
        let share = over as f64 / a.image.pixels.len() as f64;
        assert!(
            share <= MAX_SHARE_DIFFERENT,
            "{}: {over} pixels ({:.3}%) differ by more than 2/255 with EARLY_OUTS off (max {:?})",
            scene.name,
            100.0 * share,
            images::max_channel_difference(&a.image, &b.image)
        );
    }
}
