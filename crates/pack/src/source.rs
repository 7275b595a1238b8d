//! The pack's sources on disk: `pack.toml` and the templates under `shaders/`.

use std::path::{Path, PathBuf};

use tidepack_glsl::{Code, Diagnostic, Location};

use crate::manifest::Manifest;

/// Largest template the build reads; anything bigger is a mistake, not a shader.
const MAX_TEMPLATE_BYTES: u64 = 4 << 20;

#[derive(Clone, Debug)]
pub struct Template {
    /// Path inside the pack's `shaders/` folder (`composite.fsh`, `lib/water.glsl`).
    pub path: String,
    /// Path shown in diagnostics (`shaderpack/shaders/composite.fsh`).
    pub display_path: String,
    pub text: String,
}

#[derive(Clone, Debug)]
pub struct PackSource {
    pub root: PathBuf,
    pub manifest_path: String,
    pub manifest_text: String,
    pub manifest: Manifest,
    /// Sorted by path.
    pub templates: Vec<Template>,
}

impl PackSource {
    /// Reads `root/pack.toml` and every file under `root/shaders`.
    pub fn load(root: &Path) -> Result<PackSource, Diagnostic> {
        let display = |p: &Path| p.display().to_string();
        let manifest_file = root.join("pack.toml");
        let manifest_path = display(&manifest_file);
        if !manifest_file.exists() {
            return Err(Diagnostic::error(
                Code::Usage,
                format!("{} holds no pack.toml, so it is not a tidepack pack source", display(root)),
                None,
            )
            .with_note(
                "the pack's sources are the shaderpack/ folder of a tidepack checkout; run from the checkout's root, or name \
                 the folder with --source PATH",
            ));
        }
        let manifest_text = read_text(&manifest_file)?;
        let manifest = Manifest::parse(&manifest_path, &manifest_text)?;
        let shaders = root.join("shaders");
        let mut files = Vec::new();
        collect_files(&shaders, &mut files)?;
        files.sort();
        let mut templates = Vec::with_capacity(files.len());
        for file in files {
            let relative = file.strip_prefix(&shaders).expect("collected under shaders/");
            let path = relative.components().map(|c| c.as_os_str().to_string_lossy()).collect::<Vec<_>>().join("/");
            templates.push(Template { path, display_path: display(&file), text: read_text(&file)? });
        }
        Ok(PackSource { root: root.to_path_buf(), manifest_path, manifest_text, manifest, templates })
    }

    pub fn template(&self, path: &str) -> Option<&Template> {
        self.templates.iter().find(|t| t.path == path)
    }
}

fn read_text(path: &Path) -> Result<String, Diagnostic> {
    let name = path.display().to_string();
    let meta = std::fs::metadata(path).map_err(|e| Diagnostic::error(Code::Template, format!("cannot read {name}: {e}"), None))?;
    if meta.len() > MAX_TEMPLATE_BYTES {
        return Err(Diagnostic::error(Code::Template, format!("{name} is {} bytes; sources are limited to {MAX_TEMPLATE_BYTES}", meta.len()), None));
    }
    let bytes = std::fs::read(path).map_err(|e| Diagnostic::error(Code::Template, format!("cannot read {name}: {e}"), None))?;
    String::from_utf8(bytes).map_err(|e| {
        let valid = &e.as_bytes()[..e.utf8_error().valid_up_to()];
        let line = valid.iter().filter(|&&b| b == b'\n').count() as u32 + 1;
        Diagnostic::error(Code::Template, "the file is not valid UTF-8", Some(Location::line(name, line)))
    })
}

fn collect_files(dir: &Path, out: &mut Vec<PathBuf>) -> Result<(), Diagnostic> {
    let entries = std::fs::read_dir(dir)
        .map_err(|e| Diagnostic::error(Code::Template, format!("cannot read the folder {}: {e}", dir.display()), None))?;
    for entry in entries {
        let entry = entry.map_err(|e| Diagnostic::error(Code::Template, format!("cannot read {}: {e}", dir.display()), None))?;
        let path = entry.path();
        let kind = entry.file_type().map_err(|e| Diagnostic::error(Code::Template, format!("{}: {e}", path.display()), None))?;
        if kind.is_dir() {
            collect_files(&path, out)?;
        } else if kind.is_file() && !entry.file_name().to_string_lossy().starts_with('.') {
            out.push(path);
        }
    }
    Ok(())
}
