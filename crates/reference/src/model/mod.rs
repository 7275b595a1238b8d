//! composite.fsh and shaderpack/shaders/lib/*.glsl, function by function, in f64: one module
//! per shader file, named like it (`waves` mirrors lib/waves.glsl, `composite` composite.fsh),
//! so the reference of a GLSL function is found in the module of its file. Each item names the
//! GLSL function it mirrors; constants are the shader's. lib/settings.glsl holds only options
//! (crate::settings reads them); lib/vanilla*.glsl serve the gbuffers programs, which the
//! reference does not model.

mod builtins;
pub mod caustics;
pub mod common;
pub mod composite;
pub mod optics;
pub mod reflections;
pub mod space;
pub mod waves;

pub use common::{TAU, is_water_behind_translucent, is_water_nearest};
pub use composite::shade_pixel;
pub use waves::WAVE_TILE;
