//! What composite read, handed to the reference: the same adapter as
//! crates/reference/tests/common/mod.rs (G-buffers at full precision, uniforms by OptiFine
//! name, the water and noise textures with the samplers gpu.rs binds them with).

use tidepack_harness::program::BufferFormat;
use tidepack_harness::uniforms::{self, Pass};
use tidepack_harness::{Frame, LoadedPack, Scene, mesh};
use tidepack_reference::{Filter, Inputs, ReferenceSettings, Texture, Uniforms, Wrap};

/// Converged settings with the slope range of the generated water texture.
pub fn converged_settings() -> ReferenceSettings {
    ReferenceSettings { slope_range: tidepack_pack::textures::water_texture().slope_range, ..ReferenceSettings::converged() }
}

fn colour_filter(format: BufferFormat) -> Result<Filter, String> {
    match format {
        BufferFormat::Rgba8 | BufferFormat::Rgba16 | BufferFormat::Rgba16F => Ok(Filter::Linear),
        other => Err(format!("the bench does not know whether {other:?} filters on this adapter")),
    }
}

pub fn inputs(pack: &LoadedPack, scene: &Scene, frame: &Frame) -> Result<Inputs, String> {
    let (w, h) = (frame.image.width as usize, frame.image.height as usize);
    let colour = |b: u8| -> Result<Texture, String> {
        let image = frame.buffers.get(&b).ok_or_else(|| format!("the frame has no colortex{b}"))?;
        Ok(Texture::from_f32(w, h, &image.pixels, colour_filter(pack.format_of(b))?, Wrap::ClampToEdge))
    };
    let depth = |image: &tidepack_harness::FloatImage| Texture::from_f32(w, h, &image.pixels, Filter::Nearest, Wrap::ClampToEdge);
    let custom = pack.custom_texture("colortex7", false).ok_or("the pack binds no water texture to colortex7")?;
    let water = Texture::from_rgba8(
        custom.width as usize,
        custom.height as usize,
        &custom.rgba,
        if custom.blur { Filter::Linear } else { Filter::Nearest },
        if custom.clamp { Wrap::ClampToEdge } else { Wrap::Repeat },
    );
    let (nw, nh, noise) = mesh::noise(256);
    let values = uniforms::values(scene, Pass::Fullscreen);
    let uniforms = Uniforms::from_named(|name| values.get(name).map(|v| v.data.as_slice()))?;
    Ok(Inputs {
        width: w,
        height: h,
        colortex0: colour(0)?,
        colortex4: colour(4)?,
        colortex5: colour(5)?,
        colortex6: colour(6)?,
        depthtex0: depth(&frame.depth0),
        depthtex1: depth(&frame.depth1),
        water,
        noise: Texture::from_rgba8(nw as usize, nh as usize, &noise, Filter::Linear, Wrap::Repeat),
        uniforms,
    })
}
