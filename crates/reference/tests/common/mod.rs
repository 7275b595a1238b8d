//! The adapter from the harness to the reference: renders a scene with the pack on lavapipe and
//! hands over exactly what composite read (G-buffers at full precision, uniforms by OptiFine
//! name, the water and noise textures with the samplers gpu.rs binds them with).
//!
//! Rendering needs lavapipe (Debian mesa-vulkan-drivers; tools/test installs it). Without it
//! these tests fail with an error naming the package: they never skip.

#![allow(dead_code)]

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, OnceLock};

use glam::DVec3;
use tidepack_glsl::options::OptionValue;
use tidepack_harness::program::BufferFormat;
use tidepack_harness::uniforms::{self, Pass};
use tidepack_harness::{Frame, Gpu, LoadedPack, PackSelection, Scene, mesh, program, render_wgpu};
use tidepack_pack::Dialect;
use tidepack_reference::{Filter, Inputs, ReferenceSettings, Texture, Uniforms, Wrap};

pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

pub fn scene(name: &str) -> Scene {
    Scene::load(&root().join(format!("tests/scenes/{name}.toml"))).unwrap_or_else(|e| panic!("{e}"))
}

pub fn scene_names() -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(root().join("tests/scenes"))
        .expect("tests/scenes")
        .filter_map(|e| e.ok()?.path().file_stem().map(|s| s.to_string_lossy().into_owned()))
        .collect();
    names.sort();
    names
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
    render_wgpu(gpu(), pack(profile), &scene(scene_name), false).unwrap_or_else(|e| panic!("{scene_name} at {profile}: {e}"))
}

/// The pack's option values as the reference's settings (`WATER_TEXTURE_SLOPE_RANGE` from the
/// texture generator, as lib/generated.glsl gets it).
pub fn settings_of(pack: &LoadedPack) -> ReferenceSettings {
    let mut s = ReferenceSettings::from_options(|name| match pack.options.get(name)? {
        OptionValue::Switch(true) => Some(None),
        OptionValue::Switch(false) => None,
        OptionValue::Value(v) => Some(Some(v.clone())),
    })
    .unwrap_or_else(|e| panic!("{e}"));
    s.slope_range = tidepack_pack::textures::water_texture().slope_range;
    s
}

/// The filter gpu.rs binds a colour buffer's sampler with in a full-screen program: linear
/// and clamp when its format filters, nearest and clamp otherwise.
fn colour_filter(format: BufferFormat) -> Filter {
    match format {
        BufferFormat::Rgba8 | BufferFormat::Rgba16 | BufferFormat::Rgba16F => Filter::Linear,
        other => panic!("the adapter does not know whether {other:?} filters on this adapter"),
    }
}

/// What composite read when the harness rendered `frame`.
pub fn inputs(pack: &LoadedPack, scene: &Scene, frame: &Frame) -> Inputs {
    let (w, h) = (frame.image.width as usize, frame.image.height as usize);
    let colour = |b: u8| {
        let image = frame.buffers.get(&b).unwrap_or_else(|| panic!("the frame has no colortex{b}"));
        Texture::from_f32(w, h, &image.pixels, colour_filter(pack.format_of(b)), Wrap::ClampToEdge)
    };
    // Depth is not filterable: gpu.rs binds nearest + clamp.
    let depth = |image: &tidepack_harness::FloatImage| Texture::from_f32(w, h, &image.pixels, Filter::Nearest, Wrap::ClampToEdge);
    let custom = pack.custom_texture("colortex7", false).expect("the pack binds its water texture to colortex7");
    let water = Texture::from_rgba8(
        custom.width as usize,
        custom.height as usize,
        &custom.rgba,
        if custom.blur { Filter::Linear } else { Filter::Nearest },
        if custom.clamp { Wrap::ClampToEdge } else { Wrap::Repeat },
    );
    let (nw, nh, noise) = mesh::noise(256);
    let values = uniforms::values(scene, Pass::Fullscreen);
    let uniforms = Uniforms::from_named(|name| values.get(name).map(|v| v.data.as_slice())).unwrap_or_else(|e| panic!("{e}"));
    Inputs {
        width: w,
        height: h,
        colortex0: colour(0),
        colortex4: colour(4),
        colortex5: colour(5),
        colortex6: colour(6),
        depthtex0: depth(&frame.depth0),
        depthtex1: depth(&frame.depth1),
        water,
        noise: Texture::from_rgba8(nw as usize, nh as usize, &noise, Filter::Linear, Wrap::Repeat),
        uniforms,
    }
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
