//! Any text as a scene file: parsed, checked and turned into a mesh, within the mesh budget.
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::path::Path;
use tidepack_scene::{Scene, mesh};

struct NoIds;

impl mesh::BlockIds for NoIds {
    fn id_of(&self, _: &str) -> i32 {
        -1
    }
}

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    if let Ok(scene) = Scene::parse(text, Path::new("fuzz.toml")) {
        let _ = mesh::build(&scene, &NoIds);
    }
});
