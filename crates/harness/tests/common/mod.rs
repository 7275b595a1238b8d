//! What the harness's test files share: the repository root, one wgpu device per test binary,
//! and the scenes of tests/scenes. Each test file uses only some of these.
#![allow(dead_code)]

use std::path::PathBuf;
use std::sync::OnceLock;

use tidepack_harness::{Gpu, Scene};

/// The repository root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The device every test of the binary shares (lavapipe without a GPU); a missing driver fails
/// the test naming the Debian package.
pub fn gpu() -> &'static Gpu {
    static GPU: OnceLock<Gpu> = OnceLock::new();
    GPU.get_or_init(|| Gpu::new().unwrap_or_else(|e| panic!("{e}")))
}

/// A scene of tests/scenes by name.
pub fn scene(name: &str) -> Scene {
    Scene::load(&root().join(format!("tests/scenes/{name}.toml"))).unwrap_or_else(|e| panic!("{name}: {e}"))
}
