//! The adapter from the harness to the reference (cargo feature `harness`): hands over exactly
//! what composite read (G-buffers at full precision, uniforms by OptiFine name, the water and
//! noise textures with the samplers gpu/bindings.rs binds them with), and the pack's settings.
//!
//! One copy for the bench, the stress sweep and this crate's tests. Behind a feature so that the
//! reference itself builds on glam alone: the harness brings wgpu.

use std::collections::BTreeMap;

use tidepack_loader::option_lines::OptionValue;
use tidepack_loader::buffers::BufferFormat;
use tidepack_harness::uniforms::{self, Pass, Value};
use tidepack_harness::raw_texture::Texels;
use tidepack_harness::{FloatImage, Frame, LoadedPack, Scene, mesh};

use crate::{Filter, Inputs, ReferenceSettings, Texture, Uniforms, Wrap};

/// The pack's option values as the reference's settings.
pub fn settings_of(pack: &LoadedPack) -> Result<ReferenceSettings, String> {
    ReferenceSettings::from_options(|name| match pack.options.get(name)? {
        OptionValue::Switch(true) => Some(None),
        OptionValue::Switch(false) => None,
        OptionValue::Value(v) => Some(Some(v.clone())),
    })
}

/// The filter gpu/bindings.rs binds a colour buffer's sampler with in a full-screen program: linear
/// when its format filters, nearest otherwise (integer formats never filter; always clamp). Whether RGBA32F filters depends on
/// the adapter (wgpu's `FLOAT32_FILTERABLE`): `float32_filterable` says so, and `None` (not
/// known) makes an RGBA32F buffer an error.
pub fn colour_filter(format: BufferFormat, float32_filterable: Option<bool>) -> Result<Filter, String> {
    match (format, float32_filterable) {
        (BufferFormat::Rgba8 | BufferFormat::Rgba16 | BufferFormat::Rgba16F, _) | (BufferFormat::Rgba32F, Some(true)) => Ok(Filter::Linear),
        (BufferFormat::Rgba32F, Some(false)) => Ok(Filter::Nearest),
        (BufferFormat::Rgba32F, None) => Err("it is not known whether Rgba32F filters on this adapter".to_string()),
        (BufferFormat::Rgba32Ui | BufferFormat::Rgba32I, _) => Ok(Filter::Nearest),
    }
}

/// The textures composite reads that do not come from the frame: the pack's water texture
/// (colortex7, sampler from its `.mcmeta`) and the harness's noise texture (linear + repeat).
#[derive(Clone, Debug)]
pub struct Textures {
    pub water: Texture,
    pub noise: Texture,
}

impl Textures {
    pub fn of(pack: &LoadedPack) -> Result<Textures, String> {
        let custom = pack.custom_texture("colortex7", tidepack_harness::samplers::ProgramStage::Composite).ok_or("the pack binds no water texture to colortex7")?;
        let Texels::Rgba8(rgba) = &custom.texels else { return Err("the pack's water texture on colortex7 is not an RGBA8 image".into()) };
        let water = Texture::from_rgba8(
            custom.width as usize,
            custom.height as usize,
            rgba,
            if custom.blur { Filter::Linear } else { Filter::Nearest },
            if custom.clamp { Wrap::ClampToEdge } else { Wrap::Repeat },
        );
        let (nw, nh, noise) = mesh::noise(256);
        Ok(Textures { water, noise: Texture::from_rgba8(nw as usize, nh as usize, &noise, Filter::Linear, Wrap::Repeat) })
    }
}

/// Which uniform values the reference gets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Precision {
    /// The harness's f64 values.
    Exact,
    /// Rounded to f32 first: what the shader received.
    F32,
}

/// The reference's uniforms from the harness's values by OptiFine name.
pub fn uniforms_of(values: &BTreeMap<String, Value>, precision: Precision) -> Result<Uniforms, String> {
    match precision {
        Precision::Exact => Uniforms::from_named(|name| values.get(name).map(|v| v.data.as_slice())),
        Precision::F32 => {
            let rounded: BTreeMap<&str, Vec<f64>> =
                values.iter().map(|(k, v)| (k.as_str(), v.data.iter().map(|&x| x as f32 as f64).collect())).collect();
            Uniforms::from_named(|name| rounded.get(name).map(|v| v.as_slice()))
        }
    }
}

/// The inputs from G-buffers (colour buffers by number, both depth buffers; the frame's size is
/// depthtex0's), the textures and the uniforms. Depth does not filter: nearest + clamp, as
/// gpu/bindings.rs binds it; colour buffers get [`colour_filter`] and clamp.
pub fn from_gbuffers(
    pack: &LoadedPack,
    colours: &BTreeMap<u8, FloatImage>,
    depth0: &FloatImage,
    depth1: &FloatImage,
    float32_filterable: Option<bool>,
    textures: &Textures,
    uniforms: Uniforms,
) -> Result<Inputs, String> {
    let (w, h) = (depth0.width as usize, depth0.height as usize);
    let colour = |b: u8| -> Result<Texture, String> {
        let image = colours.get(&b).ok_or_else(|| format!("the G-buffers have no colortex{b}"))?;
        let filter = colour_filter(pack.format_of(b), float32_filterable).map_err(|e| format!("colortex{b}: {e}"))?;
        Ok(Texture::from_f32(w, h, &image.pixels, filter, Wrap::ClampToEdge))
    };
    let depth = |image: &FloatImage| Texture::from_f32(w, h, &image.pixels, Filter::Nearest, Wrap::ClampToEdge);
    Ok(Inputs {
        width: w,
        height: h,
        colortex0: colour(0)?,
        colortex3: colour(3)?,
        colortex4: colour(4)?,
        colortex5: colour(5)?,
        colortex6: colour(6)?,
        depthtex0: depth(depth0),
        depthtex1: depth(depth1),
        water: textures.water.clone(),
        noise: textures.noise.clone(),
        uniforms,
    })
}

/// What composite read when the harness rendered `frame` of `scene` (exact uniforms; an RGBA32F
/// colour buffer is an error, its filtering on the adapter not being known here).
pub fn inputs(pack: &LoadedPack, scene: &Scene, frame: &Frame) -> Result<Inputs, String> {
    let uniforms = uniforms_of(&uniforms::values(scene, Pass::Fullscreen), Precision::Exact)?;
    from_gbuffers(pack, &frame.buffers, &frame.depth0, &frame.depth1, None, &Textures::of(pack)?, uniforms)
}
