//! Embeds the repository's scenes (tests/scenes/*.toml) so that an installed `tidepack` renders
//! them by name, anywhere: writes `$OUT_DIR/built_in_scenes.rs`, a table of (name, text).

use std::path::Path;

fn main() {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/scenes");
    println!("cargo::rerun-if-changed={}", folder.display());
    let mut scenes: Vec<(String, String)> = std::fs::read_dir(&folder)
        .map(|entries| {
            entries
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x == "toml"))
                .filter_map(|p| Some((p.file_stem()?.to_str()?.to_string(), p.canonicalize().ok()?.to_str()?.to_string())))
                .collect()
        })
        .unwrap_or_default();
    scenes.sort();
    let mut table = String::from("/// Written by crates/scene/build.rs from tests/scenes/*.toml.\npub const BUILT_IN_SCENES: &[(&str, &str)] = &[\n");
    for (name, path) in &scenes {
        println!("cargo::rerun-if-changed={path}");
        table.push_str(&format!("    ({name:?}, include_str!({path:?})),\n"));
    }
    table.push_str("];\n");
    let out = Path::new(&std::env::var("OUT_DIR").expect("cargo sets OUT_DIR")).join("built_in_scenes.rs");
    std::fs::write(out, table).expect("OUT_DIR is writable");
}
