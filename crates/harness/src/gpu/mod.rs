//! The wgpu side of the harness, by concern:
//!
//! - [`device`]: the adapter and device, the formats and resolutions they allow, and the
//!   validation-error scope every call runs in;
//! - [`bindings`]: one program of the pack as a pipeline, its sampler names resolved as
//!   OptiFine names them and bound with its uniform blocks; used by the frame and by
//!   [`crate::composite_only`] alike;
//! - [`frame`]: a whole frame of any pack, ours included ([`crate::any_pack::FramePlan`]),
//!   step by step;
//! - [`geometry`]: one gbuffers draw, by the pack's program or the loader's own colour;
//! - [`own`]: the harness's own shaders (a loader's fixed-function colour, the pass-through);
//! - [`readback`]: textures and timestamps back to the CPU.

pub mod bindings;
pub mod device;
pub mod frame;
pub mod geometry;
pub mod own;
pub mod readback;

pub use bindings::UniformBinding;
pub use device::{Gpu, VULKAN_PACKAGE};
pub use frame::{Frame, FrameTiming, StepReport, SteppedFrame, render, render_from};
pub use readback::read_texture;
