//! GLSL for OptiFine shader packs: tokenizer, OptiFine's preprocessor with a source map, option
//! declarations, the lowering of shipped GLSL 120/330 to the Vulkan GLSL 450 that naga reads, and
//! validation through naga with errors mapped back to the pack's files.
//!
//! Data flow: [`preprocess`] (includes, macros, conditionals; one output line per source line)
//! → [`lower`] (line-preserving token rewrites to GLSL 450) → [`naga_check`] (naga parse and
//! validation, errors mapped through the preprocessor's line map).

pub mod code;
pub mod compat;
pub mod diagnostic;
pub mod known_valid;
pub mod liveness;
pub mod lower;
pub mod messages;
pub mod naga_check;
pub mod preprocess;
pub mod terminal;
pub mod token;

pub use code::Code;
pub use diagnostic::{Diagnostic, Drivers, Location, Severity};
pub use lower::Stage;
