//! `--driver`: the same programs compiled and linked by a real OpenGL driver (Mesa through
//! EGL, compatibility profile, no display), from the text OptiFine would hand it: includes
//! expanded, standard macros after `#version`, option lines rewritten. The driver's messages
//! are located in the pack's files; its verdict is compared with tidepack's.

use tidepack_gldriver::GlContext;
use tidepack_gldriver::glow::{self, HasContext};
use tidepack_loader::macros::StandardMacros;
use tidepack_loader::programs::with_loader_declarations;
use tidepack_glsl::{Code, Diagnostic, Location, Stage};

use tidepack_loader::programs::Program;

use crate::loader_text::as_loader_hands_it;

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
    /// Program ids the driver gave no verdict on, with why: it could not make a shader or
    /// program object (its context failed, not the pack's text).
    pub not_compared: Vec<String>,
}

/// Whether an error is one no GL driver can report (the loader's render-target directives).
pub fn is_loader_level(diag: &Diagnostic) -> bool {
    diag.message.contains("DRAWBUFFERS") || diag.message.contains("RENDERTARGETS")
}

/// One stage's text for the driver, with the map of its lines to the pack's files.
struct StageText {
    text: String,
    map: Vec<Option<Location>>,
    /// Where the stage asked for a newer GLSL than the driver has: the note saying so.
    version_note: Option<String>,
}

pub struct Driver {
    context: GlContext,
    macros: StandardMacros,
}

impl Driver {
    /// A headless context; the error names the packages to install.
    pub fn new(macros: &StandardMacros) -> Result<Driver, Diagnostic> {
        let context = GlContext::new().map_err(|e| Diagnostic::error(Code::Driver, e.message, None))?;
        Ok(Driver { context, macros: macros.clone() })
    }

    pub fn describe(&self) -> String {
        self.context.info().to_string()
    }

    /// OpenGL version of the context as (major, minor).
    fn gl_version(&self) -> (u32, u32) {
        let version = &self.context.info().version;
        let mut numbers = version.split(|c: char| !c.is_ascii_digit()).filter(|n| !n.is_empty()).map(|n| n.parse().unwrap_or(0));
        (numbers.next().unwrap_or(0), numbers.next().unwrap_or(0))
    }

    /// The highest `#version` the context compiles: from OpenGL 3.3 on GLSL's number of the
    /// OpenGL version (4.5 → 450); 150, 140 and 130 for 3.2, 3.1 and 3.0; 120 before.
    fn highest_glsl(&self) -> u32 {
        match self.gl_version() {
            (3, 2) => 150,
            (3, 1) => 140,
            (3, 0) => 130,
            (major, _) if major < 3 => 120,
            (major, minor) => major * 100 + minor * 10,
        }
    }

    /// A stage's text as the driver gets it: as the loader hands it
    /// ([`as_loader_hands_it`]), with what the loader declares, and a `#version` above the
    /// driver's lowered to its highest (see [`within_version`]); `None` when it cannot be
    /// expanded (tidepack's preprocessor reported that already).
    fn stage_text(&self, program: &Program, vertex: bool, path: &str, provider: &dyn tidepack_glsl::preprocess::FileProvider) -> Option<StageText> {
        let (text, map) = as_loader_hands_it(provider, path, &self.macros).ok()?;
        let highest = self.highest_glsl();
        let (text, asked) = within_version(declared(program, vertex, text), highest);
        let version_note = asked.map(|asked| {
            format!(
                "compiled as `#version {highest}`: this driver offers GLSL up to {}.{:02}; a driver with GLSL {}.{:02} reads `#version {asked}` as written",
                highest / 100,
                highest % 100,
                asked / 100,
                asked % 100
            )
        });
        Some(StageText { text, map, version_note })
    }

    /// Whether the context compiles tessellation (OpenGL 4.0) and compute (4.3) stages.
    fn supports(&self, path: &str) -> bool {
        let version = self.gl_version();
        if path.ends_with(".tcs") || path.ends_with(".tes") {
            version >= (4, 0)
        } else if path.ends_with(".csh") {
            version >= (4, 3)
        } else {
            version >= (3, 2)
        }
    }

    /// Warnings for the stages of `program` this driver cannot compile (left out of
    /// [`Driver::check`]).
    pub fn unsupported(&self, program: &Program) -> Vec<Diagnostic> {
        program
            .other_stages
            .iter()
            .chain(&program.compute)
            .filter(|p| !self.supports(p))
            .map(|p| {
                Diagnostic::warning(
                    Code::NotCompiled,
                    format!("{p} was only preprocessed: the OpenGL driver ({}) cannot compile this kind of stage", self.describe()),
                    Some(Location::line(p.clone(), 1)),
                )
            })
            .collect()
    }

    /// Compiles and links one program (vertex, geometry, tessellation and fragment stages
    /// together; each compute stage alone); `Ok(())` when the driver accepts it, else its
    /// messages located in the pack's files. `Err` with an empty list when the text cannot be
    /// expanded (tidepack's preprocessor reported that already). The outer `Err` when the
    /// driver gave no verdict: it could not make a shader or program object (why).
    pub fn check(&self, program: &Program, provider: &dyn tidepack_glsl::preprocess::FileProvider) -> Result<Result<(), Vec<Diagnostic>>, String> {
        let mut results = Vec::new();
        let graphics: Vec<&String> = program.other_stages.iter().filter(|p| self.supports(p)).collect();
        if graphics.is_empty() {
            if !program.stages.is_empty() {
                results.push(self.check_vertex_fragment(program, provider));
            }
        } else {
            let mut files: Vec<(u32, &str)> = Vec::new();
            for (stage, path) in &program.stages {
                files.push((if *stage == Stage::Vertex { glow::VERTEX_SHADER } else { glow::FRAGMENT_SHADER }, path));
            }
            for path in graphics {
                let kind = match path.rsplit_once('.').map(|(_, e)| e) {
                    Some("gsh") => glow::GEOMETRY_SHADER,
                    Some("tcs") => glow::TESS_CONTROL_SHADER,
                    _ => glow::TESS_EVALUATION_SHADER,
                };
                files.push((kind, path));
            }
            results.push(self.check_stages(program, &files, provider));
        }
        for path in program.compute.iter().filter(|p| self.supports(p)) {
            results.push(self.check_stages(program, &[(glow::COMPUTE_SHADER, path)], provider));
        }
        let mut rejected = Vec::new();
        let mut unexpanded = false;
        for result in results {
            match result? {
                Ok(()) => {}
                Err(diags) if diags.is_empty() => unexpanded = true,
                Err(diags) => rejected.extend(diags),
            }
        }
        Ok(if !rejected.is_empty() || unexpanded { Err(rejected) } else { Ok(()) })
    }

    /// Compiles the given stages with glow and links them into one program.
    fn check_stages(
        &self,
        program: &Program,
        files: &[(u32, &str)],
        provider: &dyn tidepack_glsl::preprocess::FileProvider,
    ) -> Result<Result<(), Vec<Diagnostic>>, String> {
        let mut texts = Vec::new();
        for (kind, path) in files {
            let Some(stage) = self.stage_text(program, *kind == glow::VERTEX_SHADER, path, provider) else { return Ok(Err(Vec::new())) };
            texts.push((*kind, *path, stage));
        }
        let version_note = |path: &str| texts.iter().find(|(_, p, _)| *p == path).and_then(|(_, _, stage)| stage.version_note.clone());
        let gl = self.context.gl();
        let info = |what: String| format!("{what} by {}", self.describe());
        let located = |log: &str, path: &str, map: Option<&Vec<Option<Location>>>, what: String| -> Vec<Diagnostic> {
            let mut diags: Vec<Diagnostic> = tidepack_gldriver::parse_log(log)
                .into_iter()
                .filter(|m| m.severity.contains("error"))
                .map(|m| {
                    let at = map.and_then(|map| map.get(m.line.checked_sub(1)? as usize).cloned().flatten());
                    let diag = Diagnostic::error(Code::Driver, format!("the OpenGL driver rejects this: {}", m.message.trim()), at.or_else(|| Some(Location::line(path, 1))))
                        .with_note(info(what.clone()));
                    let diag = match version_note(path) {
                        Some(note) => diag.with_note(note),
                        None => diag,
                    };
                    if m.message.contains("geometry_shader4") {
                        diag.with_note("Mesa does not implement GL_ARB/EXT_geometry_shader4 (NVIDIA's driver does); geometry shaders written for `#version 150` or later compile on Mesa too")
                    } else {
                        diag
                    }
                })
                .collect();
            if diags.is_empty() {
                diags.push(
                    Diagnostic::error(Code::Driver, format!("the OpenGL driver rejects this program: {}", log.trim()), Some(Location::line(path, 1)))
                        .with_note(info(what)),
                );
            }
            diags
        };
        // SAFETY: plain GL calls on the context current on this thread, with objects made here.
        unsafe {
            let mut shaders = Vec::new();
            let mut failed = Vec::new();
            let mut not_created = None;
            for (kind, path, StageText { text, map, .. }) in &texts {
                let shader = match gl.create_shader(*kind) {
                    Ok(shader) => shader,
                    Err(log) => {
                        not_created = Some(format!("{} creation: {log}", stage_name(*kind)));
                        break;
                    }
                };
                gl.shader_source(shader, text);
                gl.compile_shader(shader);
                if gl.get_shader_compile_status(shader) {
                    shaders.push(shader);
                } else {
                    let log = gl.get_shader_info_log(shader);
                    failed.extend(located(&log, path, Some(map), format!("{} compilation", stage_name(*kind))));
                    gl.delete_shader(shader);
                }
            }
            if failed.is_empty() && not_created.is_none() {
                match gl.create_program() {
                    Ok(linked) => {
                        for &shader in &shaders {
                            gl.attach_shader(linked, shader);
                        }
                        gl.link_program(linked);
                        if !gl.get_program_link_status(linked) {
                            let log = gl.get_program_info_log(linked);
                            let entry = program.entry().unwrap_or(files[0].1);
                            failed.extend(located(&log, entry, None, "program link".into()));
                        }
                        for &shader in &shaders {
                            gl.detach_shader(linked, shader);
                        }
                        gl.delete_program(linked);
                    }
                    Err(log) => not_created = Some(format!("program creation: {log}")),
                }
            }
            for shader in shaders {
                gl.delete_shader(shader);
            }
            match not_created {
                Some(why) => Err(why),
                None => Ok(if failed.is_empty() { Ok(()) } else { Err(failed) }),
            }
        }
    }

    /// The vertex and fragment stages alone, through tidepack-gldriver.
    fn check_vertex_fragment(&self, program: &Program, provider: &dyn tidepack_glsl::preprocess::FileProvider) -> Result<Result<(), Vec<Diagnostic>>, String> {
        let mut texts = Vec::new();
        for (stage, path) in &program.stages {
            let Some(text) = self.stage_text(program, *stage == Stage::Vertex, path, provider) else { return Ok(Err(Vec::new())) };
            texts.push((*stage, path.clone(), text));
        }
        let vertex = texts.iter().find(|t| t.0 == Stage::Vertex);
        let fragment = texts.iter().find(|t| t.0 == Stage::Fragment);
        let result = match (vertex, fragment) {
            (Some(v), Some(f)) => self.context.compile_program(&v.2.text, None, &f.2.text, &[], &[]).map(|p| self.context.delete_program(p)),
            (Some(only), None) | (None, Some(only)) => self.context.compile_shader_only(only.0 == Stage::Vertex, &only.2.text).map(|_| ()),
            (None, None) => Ok(()),
        };
        let Err(log) = result else { return Ok(Ok(())) };
        let stage_text = match log.step {
            tidepack_gldriver::ProgramStep::CompileVertex => vertex,
            tidepack_gldriver::ProgramStep::CompileFragment => fragment,
            tidepack_gldriver::ProgramStep::CompileGeometry | tidepack_gldriver::ProgramStep::CompileCompute | tidepack_gldriver::ProgramStep::Link => None,
            tidepack_gldriver::ProgramStep::CreateObject => return Err(format!("{}: {}", log.step, log.log.trim())),
        };
        let info = format!("{} by {}", log.step, self.describe());
        let mut diags: Vec<Diagnostic> = log
            .messages()
            .into_iter()
            .filter(|m| m.severity.contains("error"))
            .map(|m| {
                let at = stage_text.and_then(|(_, _, t)| t.map.get(m.line.checked_sub(1)? as usize).cloned().flatten());
                let entry = stage_text.map(|t| t.1.clone()).or_else(|| program.stages.first().map(|s| s.1.clone()));
                let diag = Diagnostic::error(Code::Driver, format!("the OpenGL driver rejects this: {}", m.message.trim()), at.or_else(|| entry.map(|e| Location::line(e, 1))))
                    .with_note(info.clone());
                match stage_text.and_then(|(_, _, t)| t.version_note.clone()) {
                    Some(note) => diag.with_note(note),
                    None => diag,
                }
            })
            .collect();
        if diags.is_empty() {
            let entry = program.stages.first().map(|s| Location::line(s.1.clone(), 1));
            diags.push(
                Diagnostic::error(Code::Driver, format!("the OpenGL driver rejects this program: {}", log.log.trim()), entry).with_note(info),
            );
        }
        Ok(Err(diags))
    }
}

fn stage_name(kind: u32) -> &'static str {
    match kind {
        glow::VERTEX_SHADER => "vertex shader",
        glow::FRAGMENT_SHADER => "fragment shader",
        glow::GEOMETRY_SHADER => "geometry shader",
        glow::TESS_CONTROL_SHADER => "tessellation control shader",
        glow::TESS_EVALUATION_SHADER => "tessellation evaluation shader",
        _ => "compute shader",
    }
}

/// `text` with what the loader declares in the stage (see [`with_loader_declarations`]).
/// `text` with a `#version` above `highest` (a stage for a newer driver than this one) lowered
/// to `highest`, its profile kept, and the version it asked for; unchanged otherwise. GLSL 4.60
/// adds little to 4.50, so the driver here still checks nearly all of such a stage.
fn within_version(text: String, highest: u32) -> (String, Option<u32>) {
    let Some(start) = text.find("#version") else { return (text, None) };
    let line_end = text[start..].find('\n').map_or(text.len(), |e| start + e);
    let line = &text[start..line_end];
    let mut words = line.split_whitespace().skip(1);
    let Some(asked) = words.next().and_then(|n| n.parse::<u32>().ok()) else { return (text, None) };
    // A version that does not exist is refused by every driver: left for this one to say so.
    if asked <= highest || !tidepack_glsl::preprocess::GLSL_VERSIONS.contains(&asked) {
        return (text, None);
    }
    let profile: Vec<&str> = words.collect();
    let rewritten = if profile.is_empty() { format!("#version {highest}") } else { format!("#version {highest} {}", profile.join(" ")) };
    (format!("{}{rewritten}{}", &text[..start], &text[line_end..]), Some(asked))
}

fn declared(program: &Program, vertex: bool, text: String) -> String {
    if let std::borrow::Cow::Owned(declared) = with_loader_declarations(&program.name, vertex, &text) { declared } else { text }
}
