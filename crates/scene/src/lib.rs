//! The scenes the harness renders, without a GPU: [`scene`] reads a scene's TOML (camera, sun
//! or time of day, water, terrain, glass, overlays) with its matrices in f64, and [`mesh`] turns
//! it into the vertices a pack's programs draw, with the generated block atlas, sun and moon.

use std::fmt;

pub mod mesh;
pub mod scene;

pub use scene::Scene;

/// A scene that cannot be read or does not make sense; the message names the file and field.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneError(pub String);

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for SceneError {}
