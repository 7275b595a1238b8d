//! The stress sweep's memory (docs/stress.md, "Memory"): `composite_only` binds composite's
//! uniform blocks as read-only storage, so that lavapipe cannot recompile the shader with the
//! blocks' values inlined at every draw (and, in Mesa 22.3, keep every copy). These tests check
//! that the output is the same bit for bit as with the uniform binding and that resident memory
//! stays flat over many renders. Needs lavapipe (Debian mesa-vulkan-drivers; tools/test installs
//! it). No time is asserted.

use std::path::{Path, PathBuf};

use tidepack_harness::composite_only::{CompositeOnly, GBuffers, UniformBinding};
use tidepack_harness::uniforms::{self, Pass};
use tidepack_harness::{Gpu, LoadedPack, PackSelection, Scene, program, render_wgpu};
use tidepack_pack::Dialect;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn setup(width: u32, height: u32) -> (Gpu, LoadedPack, Scene, GBuffers) {
    let pack = program::load(&PackSelection { source_dir: root().join("shaderpack"), dialect: Dialect::Glsl330, profile: None, options: vec![] })
        .unwrap_or_else(|e| panic!("{e}"));
    let gpu = Gpu::new().unwrap_or_else(|e| panic!("{e}"));
    let scene = Scene::load(&root().join("tests/scenes/case4_above_near.toml")).unwrap_or_else(|e| panic!("{e}")).with_resolution(width, height);
    let frame = render_wgpu(&gpu, &pack, &scene).unwrap_or_else(|e| panic!("{e}"));
    let g = GBuffers::from_frame(&frame);
    (gpu, pack, scene, g)
}

fn rss_mib() -> f64 {
    tidepack_harness::resident_mib().expect("/proc/self/status VmRSS")
}

#[test]
fn storage_binding_gives_the_uniform_bindings_image_and_the_harness_frames() {
    let (gpu, pack, scene, g) = setup(32, 18);
    let values = uniforms::values(&scene, Pass::Fullscreen);
    let storage = CompositeOnly::with_binding(&gpu, &pack, 32, 18, &values, UniformBinding::ReadOnlyStorage).unwrap();
    let uniform = CompositeOnly::with_binding(&gpu, &pack, 32, 18, &values, UniformBinding::Uniform).unwrap();
    let a = storage.render(&gpu, &pack, &g, &values).unwrap();
    let b = uniform.render(&gpu, &pack, &g, &values).unwrap();
    let frame = render_wgpu(&gpu, &pack, &scene).unwrap();
    for (i, ((p, q), r)) in a.pixels.iter().zip(&b.pixels).zip(&frame.image.pixels).enumerate() {
        assert_eq!(p.map(f32::to_bits), q.map(f32::to_bits), "pixel {i}: storage {p:?} vs uniform {q:?}");
        assert_eq!(p.map(f32::to_bits), r.map(f32::to_bits), "pixel {i}: composite_only {p:?} vs harness frame {r:?}");
    }
    // The timed path renders the same image and reports one time per frame and pass.
    let timed = storage.time(&gpu, &pack, &g, &values, 3).unwrap();
    assert_eq!((timed.composite_ms.len(), timed.passthrough_ms.len()), (3, 3));
    assert!(timed.composite_ms.iter().chain(&timed.passthrough_ms).all(|t| t.is_finite() && *t >= 0.0));
    assert_eq!(timed.image.pixels, a.pixels);
}

#[test]
fn resident_memory_stays_flat_over_hundreds_of_renders() {
    let (gpu, pack, scene, g) = setup(16, 9);
    let values = uniforms::values(&scene, Pass::Fullscreen);
    let runner = CompositeOnly::new(&gpu, &pack, 16, 9, &values).unwrap();
    for _ in 0..20 {
        runner.render(&gpu, &pack, &g, &values).unwrap();
    }
    let before = rss_mib();
    for _ in 0..300 {
        runner.render(&gpu, &pack, &g, &values).unwrap();
    }
    let grown = rss_mib() - before;
    // With the leak, 300 renders grew by about 1000 MiB; without it, by nothing measurable.
    assert!(grown < 100.0, "resident memory grew by {grown:.0} MiB over 300 renders");
}
