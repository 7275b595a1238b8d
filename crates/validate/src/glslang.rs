//! glslangValidator (the Khronos reference front-end, Debian `glslang-tools`) on the text
//! the loader would hand the driver, for comparing verdicts. It compiles each stage alone (no
//! link), and is stricter than drivers about version rules (line continuations need GLSL 4.20).

use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

use tidepack_glsl::Stage;
use tidepack_glsl::preprocess::FileProvider;

use tidepack_loader::macros::StandardMacros;
use tidepack_loader::programs::Program;

use crate::loader_text::as_loader_hands_it;

/// glslangValidator's verdict on a program's stages.
#[derive(Clone, Debug, Default)]
pub struct GlslangVerdict {
    pub rejects: bool,
    /// Its `ERROR:` lines.
    pub errors: Vec<String>,
    /// Time spent in the glslangValidator processes.
    pub elapsed: Duration,
}

/// Runs glslangValidator on each stage as the loader of `macros` hands it to the driver (files
/// written under `scratch`). `Ok(None)` when the text cannot be expanded (missing include,
/// cycle); `Err` when glslangValidator cannot run.
pub fn check(program: &Program, provider: &dyn FileProvider, macros: &StandardMacros, scratch: &Path) -> Result<Option<GlslangVerdict>, String> {
    let mut verdict = GlslangVerdict::default();
    for (i, (stage, path)) in program.stages.iter().enumerate() {
        let Ok((text, _)) = as_loader_hands_it(provider, path, macros) else { return Ok(None) };
        let file = scratch.join(format!("stage{i}.glsl"));
        std::fs::write(&file, text).map_err(|e| format!("cannot write {}: {e}", file.display()))?;
        let started = Instant::now();
        let out = Command::new("glslangValidator")
            .args(["-S", if *stage == Stage::Vertex { "vert" } else { "frag" }])
            .arg(&file)
            .output()
            .map_err(|e| format!("cannot run glslangValidator (Debian package glslang-tools): {e}"))?;
        verdict.elapsed += started.elapsed();
        if !out.status.success() {
            verdict.rejects = true;
            let stdout = String::from_utf8_lossy(&out.stdout);
            verdict.errors.extend(stdout.lines().filter(|l| l.starts_with("ERROR: 0:")).map(|l| format!("{path}: {l}")));
        }
    }
    Ok(Some(verdict))
}
