//! `build --scene` folds the uniforms a scene fixes into constants; rendering the scene with
//! the specialised pack must give the picture of the general pack. Needs lavapipe (Debian
//! mesa-vulkan-drivers, installed by tools/test); fails, never skips, without it.

use std::path::{Path, PathBuf};

use tidepack_harness::{Gpu, PackSelection, Scene, images, program, render_wgpu, scene, uniforms};
use tidepack_pack::Dialect;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

#[test]
fn every_scene_renders_the_same_specialised_as_general() {
    let gpu = Gpu::new().unwrap_or_else(|e| panic!("{e}"));
    let scenes = scene::scene_files(&root().join("tests/scenes")).unwrap_or_else(|e| panic!("{e}"));
    assert!(scenes.len() >= 8, "{scenes:?}");
    for dialect in Dialect::ALL {
        let selection = PackSelection { source_dir: root().join("shaderpack"), dialect, profile: None, options: vec![] };
        let general = program::load(&selection).unwrap_or_else(|e| panic!("{e}"));
        for path in &scenes {
            let scene = Scene::load(path).unwrap_or_else(|e| panic!("{e}"));
            let spec = uniforms::scene_specialisation(&scene, &path.display().to_string());
            let specialised = program::load_specialised(&selection, Some(&spec)).unwrap_or_else(|e| panic!("{e}"));
            assert!(specialised.folded_uniforms.contains(&"isEyeInWater".to_string()), "{:?}", specialised.folded_uniforms);
            assert!(!specialised.folded_uniforms.contains(&"frameTimeCounter".to_string()));
            let a = render_wgpu(&gpu, &general, &scene).unwrap_or_else(|e| panic!("{e}"));
            let b = render_wgpu(&gpu, &specialised, &scene).unwrap_or_else(|e| panic!("{e}"));
            let over = images::count_differing(&a.image, &b.image, 1.0 / 255.0);
            assert_eq!(
                over,
                0,
                "{} ({dialect}): {over} pixels differ by more than 1/255 (max {:?})",
                scene.name,
                images::max_channel_difference(&a.image, &b.image)
            );
        }
    }
}
