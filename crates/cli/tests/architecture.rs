//! docs/ARCHITECTURE.md's code map is kept true: every Rust file of the workspace is listed in
//! its crate's section, and no crate depends on, or names in its sources, what its section
//! says it must never import.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Every `.rs` file under `dir`, as paths relative to `base`, build outputs (a crate's own
/// `target/`, as crates/fuzz has) left out.
fn rust_files(dir: &Path, base: &Path, out: &mut Vec<String>) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() && path.file_name().is_some_and(|n| n == "target") {
            continue;
        }
        if path.is_dir() {
            rust_files(&path, base, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path.strip_prefix(base).unwrap().to_string_lossy().replace('\\', "/"));
        }
    }
}

/// The code map's sections by crate folder (`crates/glsl`), each section's text; a section
/// heading may name two crates.
fn sections(map: &str) -> BTreeMap<String, String> {
    let mut out = BTreeMap::new();
    let code_map = &map[map.find("## Code map").expect("a Code map section")..];
    let code_map = &code_map[..code_map[3..].find("\n## ").map_or(code_map.len(), |i| i + 3)];
    for section in code_map.split("\n### ").skip(1) {
        let heading = section.lines().next().unwrap_or("");
        for part in heading.split('`').skip(1).step_by(2) {
            if let Some(name) = part.strip_prefix("crates/") {
                out.insert(format!("crates/{name}"), section.to_string());
            }
        }
    }
    out
}

/// The crate folders of the workspace.
fn crate_dirs() -> Vec<PathBuf> {
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(root().join("crates")).unwrap().flatten().map(|e| e.path()).filter(|p| p.join("Cargo.toml").is_file()).collect();
    dirs.sort();
    dirs
}

#[test]
fn every_rust_file_is_in_its_crates_section_of_the_code_map() {
    let map = std::fs::read_to_string(root().join("docs/ARCHITECTURE.md")).unwrap();
    let sections = sections(&map);
    let mut missing = Vec::new();
    for dir in crate_dirs() {
        let name = format!("crates/{}", dir.file_name().unwrap().to_string_lossy());
        let Some(section) = sections.get(&name) else {
            missing.push(format!("{name}: no section"));
            continue;
        };
        let mut files = Vec::new();
        rust_files(&dir, &dir, &mut files);
        files.sort();
        for file in files {
            if !section.contains(&format!("`{file}`")) {
                missing.push(format!("{name}/{file}"));
            }
        }
    }
    assert!(missing.is_empty(), "docs/ARCHITECTURE.md's code map does not list:\n{}", missing.join("\n"));
}

/// What a crate must never depend on, by crate folder: package names.
const FORBIDDEN_DEPENDENCIES: [(&str, &[&str]); 8] = [
    ("glsl", &["tidepack-loader", "tidepack-scene", "tidepack-pack", "tidepack-validate", "tidepack-harness", "tidepack-gldriver", "wgpu", "glow", "khronos-egl"]),
    ("loader", &["tidepack-scene", "tidepack-pack", "tidepack-validate", "tidepack-harness", "tidepack-gldriver", "wgpu", "glow", "khronos-egl"]),
    ("scene", &["tidepack-pack", "tidepack-validate", "tidepack-harness", "wgpu", "glow", "khronos-egl", "naga"]),
    ("pack", &["tidepack-scene", "tidepack-validate", "tidepack-harness", "wgpu", "glow", "khronos-egl"]),
    ("validate", &["tidepack-pack", "tidepack-scene", "tidepack-harness", "wgpu"]),
    ("gldriver", &["tidepack-glsl", "tidepack-loader", "wgpu"]),
    ("harness", &["tidepack-validate"]),
    ("cli", &["wgpu"]),
];

/// The names in a Cargo.toml's `[dependencies]` table.
fn dependencies(manifest: &str) -> Vec<String> {
    let mut names = Vec::new();
    let mut in_dependencies = false;
    for line in manifest.lines() {
        let line = line.trim();
        if line.starts_with('[') {
            in_dependencies = line == "[dependencies]";
            continue;
        }
        if in_dependencies && let Some((name, _)) = line.split_once(['=', '.']) {
            if !name.trim().is_empty() && !name.starts_with('#') {
                names.push(name.trim().to_string());
            }
        }
    }
    names
}

#[test]
fn no_crate_depends_on_what_its_layer_forbids() {
    let mut found = Vec::new();
    for (dir, forbidden) in FORBIDDEN_DEPENDENCIES {
        let manifest = std::fs::read_to_string(root().join("crates").join(dir).join("Cargo.toml")).unwrap();
        for dependency in dependencies(&manifest) {
            if forbidden.contains(&dependency.as_str()) {
                found.push(format!("crates/{dir} depends on {dependency}"));
            }
        }
    }
    assert!(found.is_empty(), "{}", found.join("\n"));
}

/// The lines of `text` that are code, not comments.
fn code_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    text.lines().enumerate().filter(|(_, l)| !l.trim_start().starts_with("//")).map(|(i, l)| (i + 1, l))
}

#[test]
fn the_frame_plan_and_the_opengl_renderers_use_nothing_of_wgpu() {
    let harness = root().join("crates/harness/src");
    let mut found = Vec::new();
    for file in ["any_pack.rs", "gl.rs", "gl_frame.rs", "samplers.rs", "program.rs", "uniforms.rs"] {
        let text = std::fs::read_to_string(harness.join(file)).unwrap();
        for (line, code) in code_lines(&text) {
            if code.contains("crate::gpu") || code.contains("wgpu::") || code.contains("super::gpu") {
                found.push(format!("crates/harness/src/{file}:{line}: {}", code.trim()));
            }
        }
    }
    assert!(found.is_empty(), "GPU-free modules that reach into wgpu:\n{}", found.join("\n"));
}
