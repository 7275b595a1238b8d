//! GLSL for OptiFine shader packs: tokenizer, OptiFine's preprocessor with a source map, option
//! declarations, the lowering of shipped GLSL 120/330 to the Vulkan GLSL 450 that naga reads, and
//! validation through naga with errors mapped back to the pack's files.

pub mod diagnostic;
pub mod preprocess;
pub mod token;

pub use diagnostic::{Diagnostic, Location, Severity};
