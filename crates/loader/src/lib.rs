//! A shader pack as OptiFine and Iris read it, without a GPU: the one model `validate`, `render`
//! and `build` share.
//!
//! Data flow: [`input`] (a folder or zip in memory, hostile input refused entry by entry) →
//! [`option_space`] (the options of [`option_lines`] and `const` lines of [`consts`], profiles,
//! a [`option_space::Configuration`]: option values, dimension, loader) → [`set_provider`] (the
//! files as the loader hands them to its preprocessor under one option set) with the loader's
//! [`macros`] → [`programs`] (which files are programs, per world folder, who runs them,
//! fallbacks) and [`loader`] (what each loader and version draws with what, in which order).
//! Around the GLSL: the uniforms and samplers the loaders set ([`known`]), [`properties`] (the one reader of `.properties` files, conditionals
//! included), what shaders.properties directs ([`directives`], [`custom_uniforms`]),
//! block.properties ([`blocks`]), the buffers' names, formats and clears ([`buffers`]) and the
//! shadow pass's settings and camera ([`shadow`]). What Iris rewrites in a stage's text before
//! the driver reads it: [`iris`].

pub mod blocks;
pub mod buffers;
pub mod consts;
pub mod coverage;
pub mod custom_uniforms;
pub mod directives;
pub mod input;
pub mod iris;
pub mod known;
pub mod loader;
pub mod macros;
pub mod option_lines;
pub mod option_space;
pub mod programs;
pub mod properties;
pub mod set_provider;
pub mod shadow;
pub mod texture_formats;
pub mod uniform_value;

pub use input::{Limits, PackFiles};
pub use loader::Loader;
pub use option_space::{Configuration, Dimension};
pub use set_provider::SetProvider;
