//! The tidepack shader pack: from the templates and manifest in `shaderpack/` to validated
//! OptiFine pack zips.
//!
//! - [`source`] reads `shaderpack/` ([`manifest`] is `pack.toml`).
//! - [`pack_options`] finds the options OptiFine will show and checks them against the manifest.
//! - [`dialect`] generates GLSL 120 and 330 text from each template; [`shipped`] assembles the
//!   whole pack per dialect in memory, with [`writers`] for the files made from the manifest and
//!   [`properties`] checking what the manifest passes on to shaders.properties.
//! - [`option_sets`] runs every program under every option set through the preprocessor, the
//!   lowering and naga.
//! - [`specialise`] folds the uniforms a scene fixes into constants (`build --scene`).
//! - [`textures`] generates the water texture the shaders sample.
//! - [`archive`] writes the deterministic zip; [`build`] ties it together.

pub mod archive;
pub mod build;
pub mod dialect;
pub mod docs;
pub mod manifest;
pub mod option_sets;
pub mod pack_options;
pub mod properties;
pub mod shipped;
pub mod source;
pub mod specialise;
pub mod textures;
pub mod writers;

pub use build::{BuildFailure, BuildOptions, BuildReport, build};
pub use dialect::Dialect;
