//! `--driver`: the same programs compiled and linked by a real OpenGL driver (Mesa through
//! EGL, compatibility profile, no display), from the text OptiFine would hand it: includes
//! expanded, standard macros after `#version`, option lines rewritten. The driver's messages
//! are located in the pack's files; its verdict is compared with tidepack's.

use tidepack_gldriver::GlContext;
use tidepack_glsl::macros::StandardMacros;
use tidepack_glsl::preprocess::expand_includes_mapped;
use tidepack_glsl::{Diagnostic, Location, Stage};

use crate::Program;

/// How the driver's verdicts compare with tidepack's, per program and option set.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct DriverSummary {
    /// `vendor / renderer / OpenGL version`.
    pub driver: String,
    pub both_accept: usize,
    pub both_reject: usize,
    /// Program ids (with option set) only the driver rejects.
    pub only_driver_rejects: Vec<String>,
    /// Program ids only tidepack rejects (compile-level errors; render-target checks, which
    /// no driver makes, do not count).
    pub only_tidepack_rejects: Vec<String>,
}

/// Whether an error is one no GL driver can report (the loader's render-target directives).
pub fn is_loader_level(diag: &Diagnostic) -> bool {
    diag.message.contains("DRAWBUFFERS") || diag.message.contains("RENDERTARGETS")
}

pub struct Driver {
    context: GlContext,
    defines: String,
}

impl Driver {
    /// A headless context; the error names the packages to install.
    pub fn new(macros: &StandardMacros) -> Result<Driver, Diagnostic> {
        let context = GlContext::new().map_err(|e| Diagnostic::error(e.message, None))?;
        Ok(Driver { context, defines: macros.define_lines() })
    }

    pub fn describe(&self) -> String {
        self.context.info().to_string()
    }

    /// Compiles and links one program; `Ok(())` when the driver accepts it, else its messages
    /// located in the pack's files. `Err` with an empty list when the text cannot be expanded
    /// (tidepack's preprocessor reported that already).
    pub fn check(&self, program: &Program, provider: &dyn tidepack_glsl::preprocess::FileProvider) -> Result<(), Vec<Diagnostic>> {
        let mut texts = Vec::new();
        for (stage, path) in &program.stages {
            match expand_includes_mapped(provider, path, &self.defines) {
                Ok((text, map)) => texts.push((*stage, path.clone(), text, map)),
                Err(_) => return Err(Vec::new()),
            }
        }
        let vertex = texts.iter().find(|t| t.0 == Stage::Vertex);
        let fragment = texts.iter().find(|t| t.0 == Stage::Fragment);
        let result = match (vertex, fragment) {
            (Some(v), Some(f)) => self.context.compile_program(&v.2, &f.2, &[], &[]).map(|p| self.context.delete_program(p)),
            (Some(only), None) | (None, Some(only)) => self.context.compile_shader_only(only.0 == Stage::Vertex, &only.2).map(|_| ()),
            (None, None) => Ok(()),
        };
        let Err(log) = result else { return Ok(()) };
        let stage_text = match log.step {
            tidepack_gldriver::ProgramStep::CompileVertex => vertex,
            tidepack_gldriver::ProgramStep::CompileFragment => fragment,
            tidepack_gldriver::ProgramStep::Link => None,
        };
        let info = format!("{} by {}", log.step, self.describe());
        let mut diags: Vec<Diagnostic> = log
            .messages()
            .into_iter()
            .filter(|m| m.severity.contains("error"))
            .map(|m| {
                let at = stage_text.and_then(|(_, _, _, map)| map.get(m.line.checked_sub(1)? as usize).cloned().flatten());
                let entry = stage_text.map(|t| t.1.clone()).or_else(|| program.stages.first().map(|s| s.1.clone()));
                Diagnostic::error(format!("the OpenGL driver rejects this: {}", m.message.trim()), at.or_else(|| entry.map(|e| Location::line(e, 1))))
                    .with_note(info.clone())
            })
            .collect();
        if diags.is_empty() {
            let entry = program.stages.first().map(|s| Location::line(s.1.clone(), 1));
            diags.push(
                Diagnostic::error(format!("the OpenGL driver rejects this program: {}", log.log.trim()), entry).with_note(info),
            );
        }
        Err(diags)
    }
}
