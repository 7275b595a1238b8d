//! Renders a scene with the pack on lavapipe and hands the reference exactly what composite read,
//! through the adapter in `tidepack_reference::harness` (this crate's `harness` feature, which
//! the tests get from the crate's dev-dependency on itself); its errors panic here.
//!
//! Rendering needs lavapipe (Debian mesa-vulkan-drivers; tools/test installs it). Without it
//! these tests fail with an error naming the package: they never skip.

#![allow(dead_code)]

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, OnceLock};

use glam::DVec3;
use tidepack_harness::{Frame, Gpu, LoadedPack, PackSelection, Scene, program, render_wgpu};
use tidepack_pack::Dialect;
use tidepack_reference::{Inputs, ReferenceSettings, harness};

pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

pub fn scene(name: &str) -> Scene {
    Scene::load(&root().join(format!("tests/scenes/{name}.toml"))).unwrap_or_else(|e| panic!("{e}"))
}

/// The golden scenes of our own pack (tests/scenes/*.toml; not the subfolders' scenes for
/// released packs).
pub fn scene_names() -> Vec<String> {
    tidepack_harness::scene::scene_files(&root().join("tests/scenes"))
        .unwrap_or_else(|e| panic!("{e}"))
        .iter()
        .filter_map(|p| p.file_stem().map(|s| s.to_string_lossy().into_owned()))
        .collect()
}

fn gpu() -> &'static Gpu {
    static GPU: OnceLock<Gpu> = OnceLock::new();
    GPU.get_or_init(|| Gpu::new().unwrap_or_else(|e| panic!("{e}")))
}

/// The pack (GLSL 330) at a profile, loaded once per profile.
pub fn pack(profile: &str) -> &'static LoadedPack {
    static PACKS: OnceLock<Mutex<BTreeMap<String, &'static LoadedPack>>> = OnceLock::new();
    let mut packs = PACKS.get_or_init(Default::default).lock().unwrap_or_else(|e| e.into_inner());
    packs.entry(profile.to_string()).or_insert_with(|| {
        let selection = PackSelection {
            source_dir: root().join("shaderpack"),
            dialect: Dialect::Glsl330,
            profile: Some(profile.to_string()),
            options: vec![],
        };
        Box::leak(Box::new(program::load(&selection).unwrap_or_else(|e| panic!("{profile}: {e}"))))
    })
}

/// A scene rendered by the harness with the pack at a profile.
pub fn frame(scene_name: &str, profile: &str) -> Frame {
    render_wgpu(gpu(), pack(profile), &scene(scene_name)).unwrap_or_else(|e| panic!("{scene_name} at {profile}: {e}"))
}

/// The pack's option values as the reference's settings.
pub fn settings_of(pack: &LoadedPack) -> ReferenceSettings {
    harness::settings_of(pack).unwrap_or_else(|e| panic!("{e}"))
}

/// What composite read when the harness rendered `frame`.
pub fn inputs(pack: &LoadedPack, scene: &Scene, frame: &Frame) -> Inputs {
    harness::inputs(pack, scene, frame).unwrap_or_else(|e| panic!("{e}"))
}

/// Differences of two images over a set of pixels, rgb channels.
#[derive(Clone, Copy, Debug)]
pub struct Difference {
    pub max_abs: f64,
    pub rmse: f64,
    /// 10 log10(1 / MSE): peak 1.0 of linear colour.
    pub psnr: f64,
    /// Pixels with a channel differing by more than 1/255 (visible in an 8-bit image).
    pub visible: usize,
    pub pixels: usize,
}

pub fn difference(a: impl Fn(usize) -> DVec3, b: impl Fn(usize) -> DVec3, indices: &[usize]) -> Difference {
    let (mut max_abs, mut squares, mut visible) = (0.0f64, 0.0f64, 0);
    for &i in indices {
        let d = (a(i) - b(i)).abs();
        max_abs = max_abs.max(d.max_element());
        squares += d.length_squared();
        if d.max_element() > 1.0 / 255.0 {
            visible += 1;
        }
    }
    let mse = squares / (3 * indices.len()) as f64;
    Difference { max_abs, rmse: mse.sqrt(), psnr: 10.0 * (1.0 / mse).log10(), visible, pixels: indices.len() }
}

pub fn gpu_rgb(frame: &Frame, i: usize) -> DVec3 {
    let p = frame.image.pixels[i];
    DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64)
}
