//! What a scene's water costs a pack: the scene drawn through wgpu with its water and with the
//! water taken out (everything else equal), alternating, in units of the one-tap pass-through
//! measured in the same frames. `tidepack compare` and the corpus table report it.

use crate::any_pack::{AnyPack, ScreenOutput};
use crate::images::{FloatImage, median};
use crate::{Gpu, HarnessError, Scene, gpu, mesh};

/// The timings of one pack on one scene, with and without its water.
#[derive(Clone, Debug)]
pub struct WaterCost {
    /// Median frame time with the water and without it (ms; GPU timestamps where the adapter
    /// has them), over the rounds.
    pub wet_ms: f64,
    pub dry_ms: f64,
    /// Median one-tap pass-through over every frame of both but each rendering's first.
    pub passthrough_ms: f64,
    /// Per round, the frame with water minus the frame without (ms).
    pub differences: Vec<f64>,
}

impl WaterCost {
    /// The frame with water over the pass-through.
    pub fn frame_cost(&self) -> f64 {
        self.wet_ms / self.passthrough_ms
    }

    /// The median difference over the pass-through: what the water costs the pack.
    pub fn water_cost(&self) -> f64 {
        median(&self.differences) / self.passthrough_ms
    }
}

/// `pack` drawing `scene` `rounds` times with its water and without, alternating, `frames`
/// frames each (the first of each rendering is left out of its median: llvmpipe compiles
/// then); and the first screen with water.
pub fn measure(gpu: &Gpu, pack: &AnyPack, scene: &Scene, frames: usize, rounds: usize) -> Result<(WaterCost, FloatImage), HarnessError> {
    let dry_scene = Scene { water: None, ..scene.clone() };
    let (wet_mesh, dry_mesh) = (mesh::build(scene, pack), mesh::build(&dry_scene, pack));
    let (mut wet, mut dry, mut passthrough, mut differences) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut screen = None;
    for _ in 0..rounds.max(1) {
        let w = gpu::render(gpu, pack, scene, &wet_mesh, ScreenOutput::AsLoader, frames)?;
        let d = gpu::render(gpu, pack, &dry_scene, &dry_mesh, ScreenOutput::AsLoader, frames)?;
        wet.push(w.timing.frame_ms);
        dry.push(d.timing.frame_ms);
        differences.push(w.timing.frame_ms - d.timing.frame_ms);
        passthrough.extend(w.timing.passthrough_samples_ms.iter().skip(1).chain(d.timing.passthrough_samples_ms.iter().skip(1)));
        screen.get_or_insert(w.image);
    }
    let cost = WaterCost { wet_ms: median(&wet), dry_ms: median(&dry), passthrough_ms: median(&passthrough), differences };
    Ok((cost, screen.expect("at least one round")))
}
