//! The pack's options as parameters of the reference (shaderpack/shaders/lib/settings.glsl).

/// How the normal is found (`NORMAL_MODE`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NormalMode {
    /// 0: one lookup: the height texture's slopes across the first height cross (no analytic wave, no second octave).
    StoredSlope,
    /// 1: height samples around the point.
    HeightSamples,
}

/// `ABSORPTION_MODEL`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Absorption {
    /// 0: the clamped linear ramp of docs/water-model.md A5.
    Ramp,
    /// 1: Beer–Lambert per channel.
    BeerLambert,
}

/// `CAUSTICS_MODE`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CausticsMode {
    /// 0: two samples of the water height texture.
    HeightTexture,
    /// 1: two samples of OptiFine's noise texture.
    NoiseTexture,
}

/// Every option the composite reads. Step counts are iteration knobs (their error is what the
/// reference measures); the rest defines the look and is taken from the configuration compared.
#[derive(Clone, Debug, PartialEq)]
pub struct ReferenceSettings {
    /// `WAVE_REFINE_STEPS`: bisection steps of `refineSurface`.
    pub wave_refine_steps: u32,
    /// `SURFACE_TOLERANCE` of waves.glsl: the bisection stops once the height gap is below
    /// it (0: it never stops early, as in the converged settings and with `EARLY_OUTS` off).
    pub surface_tolerance: f64,
    /// `EARLY_OUTS`: above water, a pixel whose colortex0 alpha is 1 passes through; caustics
    /// and the reflection march are skipped when they would add less than 1/255 (off in the
    /// converged settings).
    pub early_outs: bool,
    pub normal_mode: NormalMode,
    /// `NORMAL_OCTAVES`.
    pub normal_octaves: u32,
    /// `REFLECTIONS`.
    pub reflections: bool,
    /// `SSR_STEPS`: march steps of `traceReflection`.
    pub ssr_steps: u32,
    /// `SSR_REFINE_STEPS`: bisection steps after a hit.
    pub ssr_refine_steps: u32,
    /// `SPECULAR`.
    pub specular: bool,
    /// `FRESNEL_EXACT`: exact dielectric Fresnel instead of Schlick.
    pub fresnel_exact: bool,
    /// `REFRACTION`.
    pub refraction: bool,
    /// `REFRACTION_STRENGTH`.
    pub refraction_strength: f64,
    /// `DEPTH_FADE`.
    pub depth_fade: bool,
    pub absorption: Absorption,
    /// `DEPTH_FADE_DISTANCE` (ramp model).
    pub depth_fade_distance: f64,
    /// `ABSORPTION_DENSITY` (Beer–Lambert model).
    pub absorption_density: f64,
    /// `CAUSTICS`.
    pub caustics: bool,
    pub caustics_mode: CausticsMode,
    /// `CAUSTIC_SAMPLES`: sample pairs (octaves) of the pattern, averaged.
    pub caustic_samples: u32,
    /// `CAUSTICS_STRENGTH`.
    pub caustics_strength: f64,
    /// `FOAM`.
    pub foam: bool,
    /// `FAR_HAZE`.
    pub far_haze: bool,
}

impl Default for ReferenceSettings {
    fn default() -> Self {
        ReferenceSettings::converged()
    }
}

/// `SURFACE_TOLERANCE` of waves.glsl, in blocks.
pub const SURFACE_TOLERANCE: f64 = 0.0005;

impl ReferenceSettings {
    /// The ULTRA look with converged iteration counts, exact Fresnel and Beer–Lambert: the
    /// ground truth. 64 bisection steps put the wave surface within 1.6 * 2^-63 blocks; 48 march
    /// steps take every reflected ray off the screen or past the far plane long before the
    /// last step (the step grows by 1.2 per step); 32 refinement steps pin a hit to 2^-32 of
    /// its bracket.
    pub fn converged() -> ReferenceSettings {
        ReferenceSettings {
            wave_refine_steps: 64,
            surface_tolerance: 0.0,
            early_outs: false,
            normal_mode: NormalMode::HeightSamples,
            normal_octaves: 2,
            reflections: true,
            ssr_steps: 48,
            ssr_refine_steps: 32,
            specular: true,
            fresnel_exact: true,
            refraction: true,
            refraction_strength: 0.04,
            depth_fade: true,
            absorption: Absorption::BeerLambert,
            depth_fade_distance: 48.0,
            absorption_density: 1.0,
            caustics: true,
            caustics_mode: CausticsMode::HeightTexture,
            caustic_samples: 3,
            caustics_strength: 0.40,
            foam: true,
            far_haze: true,
        }
    }

    /// Every iteration count doubled (the convergence check).
    pub fn doubled(&self) -> ReferenceSettings {
        ReferenceSettings {
            wave_refine_steps: self.wave_refine_steps * 2,
            ssr_steps: self.ssr_steps * 2,
            ssr_refine_steps: self.ssr_refine_steps * 2,
            ..self.clone()
        }
    }

    /// The settings of a pack option set, looked up by `#define` name: `Some(None)` for a
    /// switch that is on, `Some(Some(value))` for a value, `None` for a switch that is off or
    /// a name that is absent. A value that is missing or does not parse is an error naming it.
    pub fn from_options(option: impl Fn(&str) -> Option<Option<String>>) -> Result<ReferenceSettings, String> {
        let switch = |name: &str| option(name).is_some();
        let number = |name: &str| -> Result<f64, String> {
            match option(name) {
                Some(Some(v)) => v.parse::<f64>().map_err(|e| format!("option {name} = {v}: {e}")),
                _ => Err(format!("option {name} has no value")),
            }
        };
        let count = |name: &str| -> Result<u32, String> {
            let v = number(name)?;
            if v >= 0.0 && v.fract() == 0.0 { Ok(v as u32) } else { Err(format!("option {name} = {v} is not a count")) }
        };
        Ok(ReferenceSettings {
            wave_refine_steps: count("WAVE_REFINE_STEPS")?,
            surface_tolerance: if switch("EARLY_OUTS") { SURFACE_TOLERANCE } else { 0.0 },
            early_outs: switch("EARLY_OUTS"),
            normal_mode: if count("NORMAL_MODE")? == 0 { NormalMode::StoredSlope } else { NormalMode::HeightSamples },
            normal_octaves: count("NORMAL_OCTAVES")?,
            reflections: switch("REFLECTIONS"),
            ssr_steps: count("SSR_STEPS")?,
            ssr_refine_steps: count("SSR_REFINE_STEPS")?,
            specular: switch("SPECULAR"),
            fresnel_exact: switch("FRESNEL_EXACT"),
            refraction: switch("REFRACTION"),
            refraction_strength: number("REFRACTION_STRENGTH")?,
            depth_fade: switch("DEPTH_FADE"),
            absorption: if count("ABSORPTION_MODEL")? == 0 { Absorption::Ramp } else { Absorption::BeerLambert },
            depth_fade_distance: number("DEPTH_FADE_DISTANCE")?,
            absorption_density: number("ABSORPTION_DENSITY")?,
            caustics: switch("CAUSTICS"),
            caustics_mode: if count("CAUSTICS_MODE")? == 0 { CausticsMode::HeightTexture } else { CausticsMode::NoiseTexture },
            caustic_samples: count("CAUSTIC_SAMPLES")?,
            caustics_strength: number("CAUSTICS_STRENGTH")?,
            foam: switch("FOAM"),
            far_haze: switch("FAR_HAZE"),
        })
    }
}
