//! The mock-uniform harness: renders the pack's programs headless through a small imitation of
//! a loader's pipeline in wgpu ([`gpu`]; which loader: [`tidepack_loader::loader`]), with uniforms filled by their
//! OptiFine names through naga's reflection ([`uniforms`]), for scenes described in TOML
//! ([`scene`]). The same scene can be drawn with the shipped GLSL 120/330 through a real OpenGL
//! compatibility context ([`gl`]) to prove the lowering changes nothing.
//!
//! What is rendered is the lowered form of exactly the shipped text ([`program`]); the only
//! changes are wrapper `main`s on the last line: on the vertex stage, to map OpenGL's clip space
//! to wgpu's; on gbuffers_water's fragment stage, the alpha test of a loader that applies one.

use std::fmt;

pub mod any_pack;
pub mod composite_only;
mod derivatives;
pub mod gl;
pub mod gl_frame;
pub mod gpu;
pub mod images;
pub mod job;
pub mod program;
pub mod raw_texture;
pub mod samplers;
mod shared_memory;
pub mod uniforms;
pub mod water_cost;

pub use gpu::{Frame, Gpu, StepReport};
pub use images::{median, quartiles};
pub use images::FloatImage;
pub use tidepack_loader::Loader;
pub use program::{LoadedPack, PackSelection};
pub use tidepack_scene::{Scene, mesh, scene};

/// This process's resident set size in MiB (Linux `/proc/self/status` VmRSS), if readable: the
/// memory figure the bench and the stress sweep report.
pub fn resident_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmRSS:"))?;
    line.split_whitespace().nth(1)?.parse::<f64>().ok().map(|kib| kib / 1024.0)
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum HarnessError {
    /// No Vulkan adapter (names the Debian package).
    NoAdapter(String),
    /// No headless OpenGL (names the Debian packages).
    NoGlDriver(String),
    Scene(String),
    /// A `--profile`, `--set` or other part of the configuration the pack does not have.
    Configuration(String),
    /// The pack does not generate, preprocess, lower or validate.
    Pack(String),
    /// A uniform, sampler or input the shaders declare that the harness cannot fill.
    Uniform(String),
    /// Something the pack asks for that the harness's pipeline does not imitate.
    Unsupported(String),
    Wgpu(String),
    /// The OpenGL driver refused the shipped text, or a GL call failed.
    Gl(String),
    Io(String),
}

impl fmt::Display for HarnessError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            HarnessError::NoAdapter(m) | HarnessError::NoGlDriver(m) => f.write_str(m),
            HarnessError::Scene(m) => write!(f, "scene: {m}"),
            HarnessError::Configuration(m) => f.write_str(m),
            HarnessError::Pack(m) => write!(f, "pack: {m}"),
            HarnessError::Uniform(m) => write!(f, "{m}"),
            HarnessError::Unsupported(m) => write!(f, "not supported by the harness: {m}"),
            HarnessError::Wgpu(m) => write!(f, "wgpu: {m}"),
            HarnessError::Gl(m) => write!(f, "OpenGL: {m}"),
            HarnessError::Io(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for HarnessError {}

impl From<tidepack_scene::SceneError> for HarnessError {
    fn from(e: tidepack_scene::SceneError) -> HarnessError {
        HarnessError::Scene(e.0)
    }
}

/// Renders one frame of `scene` with our pack through wgpu ([`gpu::render`]).
pub fn render_wgpu(gpu: &Gpu, pack: &LoadedPack, scene: &Scene) -> Result<Frame, HarnessError> {
    render_wgpu_repeated(gpu, pack, scene, 1)
}

/// Renders `frames` frames of `scene` with our pack through wgpu, pipelines made once, for
/// timing (see [`gpu::FrameTiming`]). The screen holds composite's output unrounded
/// ([`any_pack::ScreenOutput::Unrounded`]); every uniform and vertex input the programs
/// declare must have a value from the harness.
pub fn render_wgpu_repeated(gpu: &Gpu, pack: &LoadedPack, scene: &Scene, frames: usize) -> Result<Frame, HarnessError> {
    let frame = gpu::render(gpu, &pack.pack, scene, &pack.mesh(scene), any_pack::ScreenOutput::Unrounded, frames)?;
    complete(&frame.zeroed)?;
    Ok(frame)
}

/// Renders one frame of `scene` with our pack's shipped text through OpenGL, as
/// [`render_wgpu`] does through wgpu.
pub fn render_gl(ctx: &tidepack_gldriver::GlContext, pack: &LoadedPack, scene: &Scene) -> Result<gl_frame::GlFrame, HarnessError> {
    gl_frame::render(ctx, &pack.pack, scene, &pack.mesh(scene), any_pack::ScreenOutput::Unrounded)
}

/// Our pack's programs read only what the harness provides: a uniform or vertex input left
/// at zero is an error.
pub(crate) fn complete(zeroed: &[String]) -> Result<(), HarnessError> {
    match zeroed {
        [] => Ok(()),
        names => Err(HarnessError::Uniform(format!("the harness has no value for {}", names.join(", ")))),
    }
}
