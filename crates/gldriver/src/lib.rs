//! A real OpenGL driver, headless: Mesa's OpenGL through EGL with no display (the
//! `EGL_PLATFORM_SURFACELESS_MESA` platform), a compatibility-profile context, and [`glow`] for
//! the calls. The shipped GLSL 120/330 compiles here exactly as on a player's Mesa driver.
//!
//! libEGL is loaded at run time (khronos-egl's `dynamic` feature), so nothing links at build
//! time; a machine without it gets a [`DriverError`] naming the Debian packages to install.
//!
//! A [`GlContext`] is current on the thread that created it and must stay on that thread
//! (it is neither `Send` nor `Sync`). Several threads may each create their own.

use std::fmt;

use glow::HasContext;
use khronos_egl as egl;

pub use glow;

/// Debian packages that provide Mesa's OpenGL through EGL without a display.
pub const DEBIAN_PACKAGES: &str = "libegl1 libegl-mesa0 libgl1-mesa-dri";

/// `EGL_PLATFORM_SURFACELESS_MESA` (EGL_MESA_platform_surfaceless).
const PLATFORM_SURFACELESS_MESA: egl::Enum = 0x31DD;

/// Why no OpenGL context could be had.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DriverError {
    pub message: String,
}

impl DriverError {
    fn new(what: impl fmt::Display) -> Self {
        DriverError {
            message: format!(
                "no headless OpenGL driver: {what} (install the Debian packages {DEBIAN_PACKAGES}: \
                 `apt-get install --no-install-recommends {DEBIAN_PACKAGES}`)"
            ),
        }
    }
}

impl fmt::Display for DriverError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for DriverError {}

/// Which step of building a program failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProgramStep {
    CompileVertex,
    CompileGeometry,
    CompileFragment,
    CompileCompute,
    Link,
    /// Making a shader or program object, which fails with the context, whatever the text.
    CreateObject,
}

impl fmt::Display for ProgramStep {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            ProgramStep::CompileVertex => "vertex shader compilation",
            ProgramStep::CompileGeometry => "geometry shader compilation",
            ProgramStep::CompileFragment => "fragment shader compilation",
            ProgramStep::CompileCompute => "compute shader compilation",
            ProgramStep::Link => "program link",
            ProgramStep::CreateObject => "creating a shader or program object",
        })
    }
}

/// The driver's own log of a failed compile or link.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DriverLog {
    pub step: ProgramStep,
    /// The info log exactly as the driver wrote it.
    pub log: String,
}

impl DriverLog {
    /// The log's messages with their lines, as Mesa writes them (`0:6(27): error: ...`).
    pub fn messages(&self) -> Vec<LogMessage> {
        parse_log(&self.log)
    }
}

impl fmt::Display for DriverLog {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} failed:\n{}", self.step, self.log.trim_end())
    }
}

impl std::error::Error for DriverLog {}

/// One message of a driver info log.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LogMessage {
    /// Source-string index (`0` for a single string).
    pub source: u32,
    /// 1-based line in the compiled text, as the driver numbers it (after `#line`).
    pub line: u32,
    /// 1-based column, when the driver gives one.
    pub column: Option<u32>,
    /// `error`, `warning`, …
    pub severity: String,
    pub message: String,
}

/// Parses Mesa's `S:L(C): severity: message` lines; lines in other forms are skipped.
pub fn parse_log(log: &str) -> Vec<LogMessage> {
    log.lines().filter_map(parse_log_line).collect()
}

fn parse_log_line(line: &str) -> Option<LogMessage> {
    let (source, rest) = line.split_once(':')?;
    let source: u32 = source.trim().parse().ok()?;
    let (position, rest) = rest.split_once(": ")?;
    let (line_no, column) = match position.split_once('(') {
        Some((l, c)) => (l.parse().ok()?, c.strip_suffix(')')?.parse().ok()),
        None => (position.parse().ok()?, None),
    };
    let (severity, message) = rest.split_once(": ").unwrap_or(("error", rest));
    Some(LogMessage { source, line: line_no, column, severity: severity.trim().to_string(), message: message.to_string() })
}

/// A linked program and whatever the driver logged while building it (warnings).
#[derive(Debug)]
pub struct GlProgram {
    pub raw: glow::Program,
    pub log: String,
}

/// What the driver says it is.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DriverInfo {
    pub vendor: String,
    pub renderer: String,
    pub version: String,
    pub glsl_version: String,
}

impl fmt::Display for DriverInfo {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} / {} / OpenGL {}", self.vendor, self.renderer, self.version)
    }
}

/// Compatibility-profile entry points glow does not wrap: the fixed-function matrix stacks and
/// client-state arrays that feed `gl_ModelViewMatrix`, `gl_Vertex`, `gl_Color`, … in legacy GLSL.
///
/// Every entry point is an `unsafe` function pointer, as every call of [`glow::HasContext`] is.
///
/// # Safety
///
/// For every call:
/// - the [`GlContext`] these pointers came from is current on the calling thread (the pointers
///   are plain `Copy` values and can outlive the context or reach another thread; calling them
///   there is undefined behaviour);
/// - `load_matrix_f` reads 16 `f32`s (column-major) through its pointer, which must be valid for
///   those reads;
/// - `vertex_pointer`, `color_pointer`, `normal_pointer` and `tex_coord_pointer` store their
///   pointer for later draws: with a buffer bound to `GL_ARRAY_BUFFER` it is a byte offset into
///   that buffer; with none it is a client address that must stay valid for every draw that
///   reads the array while it is enabled.
pub struct LegacyGl {
    pub matrix_mode: unsafe extern "system" fn(u32),
    pub load_matrix_f: unsafe extern "system" fn(*const f32),
    pub enable_client_state: unsafe extern "system" fn(u32),
    pub disable_client_state: unsafe extern "system" fn(u32),
    pub vertex_pointer: unsafe extern "system" fn(i32, u32, i32, *const std::ffi::c_void),
    pub color_pointer: unsafe extern "system" fn(i32, u32, i32, *const std::ffi::c_void),
    pub normal_pointer: unsafe extern "system" fn(u32, i32, *const std::ffi::c_void),
    pub tex_coord_pointer: unsafe extern "system" fn(i32, u32, i32, *const std::ffi::c_void),
    pub client_active_texture: unsafe extern "system" fn(u32),
    /// `glProvokingVertex` (OpenGL 3.2).
    pub provoking_vertex: unsafe extern "system" fn(u32),
    /// `glClipControl` (OpenGL 4.5 or ARB_clip_control), when the driver has it.
    pub clip_control: Option<unsafe extern "system" fn(u32, u32)>,
    /// `glFogf` and `glFogfv`: the fixed-function fog state `gl_Fog` reads.
    pub fog_f: unsafe extern "system" fn(u32, f32),
    pub fog_fv: unsafe extern "system" fn(u32, *const f32),
    /// `glClearTexImage` (OpenGL 4.4), when the driver has it: with a null pointer it clears a
    /// texture's level to zero, whatever its format and dimensions.
    pub clear_tex_image: Option<unsafe extern "system" fn(u32, i32, u32, u32, *const std::ffi::c_void)>,
    /// `glGetProgramResourceiv` (OpenGL 4.3), when the driver has it: glow's wrapper asks for
    /// the values with a buffer of none and is given none. Call it through
    /// [`GlContext::program_resource_i32`].
    program_resource_iv: Option<unsafe extern "system" fn(u32, u32, u32, i32, *const u32, i32, *mut i32, *mut i32)>,
}

/// Enums of the compatibility API that glow does not define.
pub mod legacy {
    pub const MODELVIEW: u32 = 0x1700;
    pub const PROJECTION: u32 = 0x1701;
    pub const TEXTURE: u32 = 0x1702;
    pub const VERTEX_ARRAY: u32 = 0x8074;
    pub const NORMAL_ARRAY: u32 = 0x8075;
    pub const COLOR_ARRAY: u32 = 0x8076;
    pub const TEXTURE_COORD_ARRAY: u32 = 0x8078;
    /// glClipControl origins and depth modes.
    pub const LOWER_LEFT: u32 = 0x8CA1;
    pub const UPPER_LEFT: u32 = 0x8CA2;
    pub const NEGATIVE_ONE_TO_ONE: u32 = 0x935E;
    pub const ZERO_TO_ONE: u32 = 0x935F;
    /// glFog parameters.
    pub const FOG_DENSITY: u32 = 0x0B62;
    pub const FOG_START: u32 = 0x0B63;
    pub const FOG_END: u32 = 0x0B64;
    pub const FOG_COLOR: u32 = 0x0B66;
    /// glProvokingVertex conventions.
    pub const FIRST_VERTEX_CONVENTION: u32 = 0x8E4D;
    pub const LAST_VERTEX_CONVENTION: u32 = 0x8E4E;
}

impl LegacyGl {
    fn load(egl: &egl::DynamicInstance<egl::EGL1_5>) -> Result<LegacyGl, DriverError> {
        fn get<T: Copy>(egl: &egl::DynamicInstance<egl::EGL1_5>, name: &str) -> Result<T, DriverError> {
            let f = egl
                .get_proc_address(name)
                .ok_or_else(|| DriverError::new(format!("the OpenGL driver has no {name} (not a compatibility profile)")))?;
            debug_assert_eq!(std::mem::size_of::<T>(), std::mem::size_of::<extern "system" fn()>());
            // SAFETY: T is the `unsafe extern "system" fn` type of this GL entry point's signature;
            // both are one function pointer. Calling it stays unsafe (see `LegacyGl`).
            Ok(unsafe { std::mem::transmute_copy::<extern "system" fn(), T>(&f) })
        }
        Ok(LegacyGl {
            matrix_mode: get(egl, "glMatrixMode")?,
            load_matrix_f: get(egl, "glLoadMatrixf")?,
            enable_client_state: get(egl, "glEnableClientState")?,
            disable_client_state: get(egl, "glDisableClientState")?,
            vertex_pointer: get(egl, "glVertexPointer")?,
            color_pointer: get(egl, "glColorPointer")?,
            normal_pointer: get(egl, "glNormalPointer")?,
            tex_coord_pointer: get(egl, "glTexCoordPointer")?,
            client_active_texture: get(egl, "glClientActiveTexture")?,
            provoking_vertex: get(egl, "glProvokingVertex")?,
            clip_control: get(egl, "glClipControl").ok(),
            fog_f: get(egl, "glFogf")?,
            fog_fv: get(egl, "glFogfv")?,
            clear_tex_image: get(egl, "glClearTexImage").ok(),
            program_resource_iv: get(egl, "glGetProgramResourceiv").ok(),
        })
    }
}

/// A current, headless OpenGL compatibility context.
pub struct GlContext {
    egl: egl::DynamicInstance<egl::EGL1_5>,
    display: egl::Display,
    context: egl::Context,
    gl: glow::Context,
    legacy: LegacyGl,
    info: DriverInfo,
    /// Contexts must stay on their thread.
    _not_send: std::marker::PhantomData<*const ()>,
}

impl GlContext {
    /// Loads libEGL, opens the surfaceless display and makes a compatibility context (at
    /// least OpenGL 3.3) current on this thread.
    pub fn new() -> Result<GlContext, DriverError> {
        // SAFETY: libEGL.so.1 is the system's EGL loader; its symbols follow the EGL API.
        let egl = unsafe { egl::DynamicInstance::<egl::EGL1_5>::load_required() }.map_err(|e| match e {
            egl::LoadError::Library(e) => DriverError::new(format!("cannot load libEGL.so.1 ({e})")),
            egl::LoadError::InvalidVersion { provided, .. } => {
                DriverError::new(format!("libEGL provides EGL {provided:?}, EGL 1.5 is needed"))
            }
        })?;
        // SAFETY: the surfaceless platform takes no native display.
        let display = unsafe { egl.get_platform_display(PLATFORM_SURFACELESS_MESA, egl::DEFAULT_DISPLAY, &[egl::ATTRIB_NONE]) }
            .map_err(|e| DriverError::new(format!("EGL has no surfaceless Mesa platform ({e}); libegl-mesa0 is Mesa's EGL")))?;
        egl.initialize(display).map_err(|e| DriverError::new(format!("eglInitialize on the surfaceless display failed ({e})")))?;
        let made = Self::make_context(&egl, display);
        let (context, gl) = match made {
            Ok(v) => v,
            Err(e) => {
                let _ = egl.terminate(display);
                return Err(e);
            }
        };
        // SAFETY: the context is current on this thread.
        let info = unsafe {
            DriverInfo {
                vendor: gl.get_parameter_string(glow::VENDOR),
                renderer: gl.get_parameter_string(glow::RENDERER),
                version: gl.get_parameter_string(glow::VERSION),
                glsl_version: gl.get_parameter_string(glow::SHADING_LANGUAGE_VERSION),
            }
        };
        let legacy = match LegacyGl::load(&egl) {
            Ok(l) => l,
            Err(e) => {
                let _ = egl.make_current(display, None, None, None);
                let _ = egl.destroy_context(display, context);
                return Err(e);
            }
        };
        Ok(GlContext { egl, display, context, gl, legacy, info, _not_send: std::marker::PhantomData })
    }

    fn make_context(
        egl: &egl::DynamicInstance<egl::EGL1_5>,
        display: egl::Display,
    ) -> Result<(egl::Context, glow::Context), DriverError> {
        egl.bind_api(egl::OPENGL_API).map_err(|e| DriverError::new(format!("EGL cannot bind the OpenGL API ({e})")))?;
        let config_attribs = [egl::RENDERABLE_TYPE, egl::OPENGL_BIT, egl::SURFACE_TYPE, 0, egl::NONE];
        let config = egl
            .choose_first_config(display, &config_attribs)
            .map_err(|e| DriverError::new(format!("eglChooseConfig failed ({e})")))?
            .ok_or_else(|| DriverError::new("EGL offers no OpenGL config without a surface"))?;
        let context_attribs = [
            egl::CONTEXT_MAJOR_VERSION,
            3,
            egl::CONTEXT_MINOR_VERSION,
            3,
            egl::CONTEXT_OPENGL_PROFILE_MASK,
            egl::CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT,
            egl::NONE,
        ];
        let context = egl.create_context(display, config, None, &context_attribs).map_err(|e| {
            DriverError::new(format!(
                "no OpenGL 3.3 compatibility context ({e}); libgl1-mesa-dri holds Mesa's software rasteriser"
            ))
        })?;
        if let Err(e) = egl.make_current(display, None, None, Some(context)) {
            let _ = egl.destroy_context(display, context);
            return Err(DriverError::new(format!("eglMakeCurrent without a surface failed ({e})")));
        }
        // SAFETY: the context is current; eglGetProcAddress returns its entry points.
        let gl = unsafe {
            glow::Context::from_loader_function(|name| {
                egl.get_proc_address(name).map_or(std::ptr::null(), |f| f as *const std::ffi::c_void)
            })
        };
        Ok((context, gl))
    }

    /// One integer property of resource `index` of `interface` in `program`
    /// (`glGetProgramResourceiv`, OpenGL 4.3); None where the driver has no such call.
    pub fn program_resource_i32(&self, program: glow::Program, interface: u32, index: u32, property: u32) -> Option<i32> {
        let query = self.legacy.program_resource_iv?;
        let mut value = 0i32;
        let mut written = 0i32;
        // SAFETY: the context is current on this thread (it is not Send); one property is asked
        // for and one value's room given.
        unsafe { query(program.0.get(), interface, index, 1, &property, 1, &mut written, &mut value) };
        (written == 1).then_some(value)
    }

    /// The fixed-function entry points of the compatibility profile, this context current.
    pub fn legacy(&self) -> &LegacyGl {
        self.make_current();
        &self.legacy
    }

    pub fn info(&self) -> &DriverInfo {
        &self.info
    }

    /// The OpenGL functions, this context made current on this thread.
    pub fn gl(&self) -> &glow::Context {
        self.make_current();
        &self.gl
    }

    /// Makes this context current where another one (or none) is: a thread may hold several
    /// (a validator's driver beside a renderer's), and each is made current before it is used.
    fn make_current(&self) {
        if self.egl.get_current_context() != Some(self.context) {
            let _ = self.egl.make_current(self.display, None, None, Some(self.context));
        }
    }

    /// Compiles a vertex, an optional geometry and a fragment shader exactly as given, binds the
    /// named vertex attributes (`glBindAttribLocation`) and fragment outputs
    /// (`glBindFragDataLocation`) to their locations, and links. A failure returns the driver's
    /// log.
    pub fn compile_program(
        &self,
        vertex_text: &str,
        geometry_text: Option<&str>,
        fragment_text: &str,
        attributes: &[(&str, u32)],
        frag_data: &[(&str, u32)],
    ) -> Result<GlProgram, DriverLog> {
        self.link(&[(glow::VERTEX_SHADER, Some(vertex_text)), (glow::GEOMETRY_SHADER, geometry_text), (glow::FRAGMENT_SHADER, Some(fragment_text))], attributes, frag_data, &[])
    }

    /// Compiles a compute shader exactly as given and links it alone. A failure returns the
    /// driver's log.
    pub fn compile_compute_program(&self, compute_text: &str) -> Result<GlProgram, DriverLog> {
        self.link(&[(glow::COMPUTE_SHADER, Some(compute_text))], &[], &[], &[])
    }

    /// Compiles a vertex shader exactly as given and links it alone, recording the named outputs
    /// (`gl_Position` and user outputs) interleaved in that order through transform feedback
    /// (`glTransformFeedbackVaryings`, `GL_INTERLEAVED_ATTRIBS`). Draw with it under
    /// `GL_RASTERIZER_DISCARD` to capture exactly what the vertex stage computed.
    pub fn compile_capture_program(
        &self,
        vertex_text: &str,
        attributes: &[(&str, u32)],
        captured: &[&str],
    ) -> Result<GlProgram, DriverLog> {
        self.link(&[(glow::VERTEX_SHADER, Some(vertex_text))], attributes, &[], captured)
    }

    /// Compiles each of `sources` (a shader kind and its text, if the program has one) and
    /// links them.
    fn link(
        &self,
        sources: &[(u32, Option<&str>)],
        attributes: &[(&str, u32)],
        frag_data: &[(&str, u32)],
        captured: &[&str],
    ) -> Result<GlProgram, DriverLog> {
        let gl = self.gl();
        // SAFETY: plain GL calls on the current context with objects created here.
        unsafe {
            let mut shaders = Vec::new();
            for &(kind, text) in sources {
                let Some(text) = text else { continue };
                let step = match kind {
                    glow::VERTEX_SHADER => ProgramStep::CompileVertex,
                    glow::GEOMETRY_SHADER => ProgramStep::CompileGeometry,
                    glow::COMPUTE_SHADER => ProgramStep::CompileCompute,
                    _ => ProgramStep::CompileFragment,
                };
                match self.compile_shader(kind, text, step) {
                    Ok(shader) => shaders.push(shader),
                    Err(e) => {
                        for shader in shaders {
                            gl.delete_shader(shader);
                        }
                        return Err(e);
                    }
                }
            }
            let program = match gl.create_program() {
                Ok(program) => program,
                Err(log) => {
                    for shader in shaders {
                        gl.delete_shader(shader);
                    }
                    return Err(DriverLog { step: ProgramStep::CreateObject, log });
                }
            };
            for &shader in &shaders {
                gl.attach_shader(program, shader);
            }
            for (name, location) in attributes {
                gl.bind_attrib_location(program, *location, name);
            }
            for (name, location) in frag_data {
                gl.bind_frag_data_location(program, *location, name);
            }
            if !captured.is_empty() {
                gl.transform_feedback_varyings(program, captured, glow::INTERLEAVED_ATTRIBS);
            }
            gl.link_program(program);
            let linked = gl.get_program_link_status(program);
            let log = gl.get_program_info_log(program);
            let mut logs: Vec<String> = Vec::new();
            for shader in shaders {
                logs.push(gl.get_shader_info_log(shader));
                gl.detach_shader(program, shader);
                gl.delete_shader(shader);
            }
            if !linked {
                gl.delete_program(program);
                return Err(DriverLog { step: ProgramStep::Link, log });
            }
            logs.push(log);
            let log = logs.into_iter().filter(|l| !l.trim().is_empty()).collect::<Vec<_>>().join("\n");
            Ok(GlProgram { raw: program, log })
        }
    }

    /// Compiles one shader alone (no link), for checking a single stage.
    pub fn compile_shader_only(&self, vertex: bool, text: &str) -> Result<String, DriverLog> {
        let (kind, step) =
            if vertex { (glow::VERTEX_SHADER, ProgramStep::CompileVertex) } else { (glow::FRAGMENT_SHADER, ProgramStep::CompileFragment) };
        // SAFETY: plain GL calls on the current context.
        unsafe {
            let shader = self.compile_shader(kind, text, step)?;
            let log = self.gl.get_shader_info_log(shader);
            self.gl.delete_shader(shader);
            Ok(log)
        }
    }

    unsafe fn compile_shader(&self, kind: u32, text: &str, step: ProgramStep) -> Result<glow::Shader, DriverLog> {
        let gl = self.gl();
        // SAFETY: the caller holds the current context.
        unsafe {
            let shader = gl.create_shader(kind).map_err(|log| DriverLog { step: ProgramStep::CreateObject, log })?;
            gl.shader_source(shader, text);
            gl.compile_shader(shader);
            if !gl.get_shader_compile_status(shader) {
                let log = gl.get_shader_info_log(shader);
                gl.delete_shader(shader);
                return Err(DriverLog { step, log });
            }
            Ok(shader)
        }
    }

    /// Deletes a program made by [`GlContext::compile_program`].
    pub fn delete_program(&self, program: GlProgram) {
        // SAFETY: the program belongs to this context.
        unsafe { self.gl().delete_program(program.raw) }
    }
}

impl Drop for GlContext {
    fn drop(&mut self) {
        // Released only where it is current, so that another context current on this thread
        // stays so.
        if self.egl.get_current_context() == Some(self.context) {
            let _ = self.egl.make_current(self.display, None, None, None);
        }
        let _ = self.egl.destroy_context(self.display, self.context);
        // The display is shared by every context of the process (eglGetPlatformDisplay returns
        // the same handle), so it is not terminated here: another thread may still use it.
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_mesa_log_lines() {
        let log = "0:6(27): error: `foo' undeclared\n0:7(1): warning: unused\nnot a message\n0:9: error: no column";
        let messages = parse_log(log);
        assert_eq!(messages.len(), 3);
        assert_eq!(messages[0], LogMessage {
            source: 0,
            line: 6,
            column: Some(27),
            severity: "error".into(),
            message: "`foo' undeclared".into()
        });
        assert_eq!(messages[1].severity, "warning");
        assert_eq!(messages[2].line, 9);
        assert_eq!(messages[2].column, None);
    }
}
