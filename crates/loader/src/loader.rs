//! The loaders and versions the toolchain models, and what each does differently with a pack's
//! programs: which programs draw what (fallback chains), in which order, with which alpha tests
//! and blend keys. docs/loaders.md gives the sources.

use std::fmt;
use std::str::FromStr;

use serde::Deserialize;

/// gbuffers_terrain and the programs OptiFine and Iris fall back to for it, in order.
pub const TERRAIN_CHAIN: [&str; 4] = ["gbuffers_terrain", "gbuffers_textured_lit", "gbuffers_textured", "gbuffers_basic"];

/// gbuffers_water and its fallbacks, in order.
pub const WATER_CHAIN: [&str; 5] = ["gbuffers_water", "gbuffers_terrain", "gbuffers_textured_lit", "gbuffers_textured", "gbuffers_basic"];

/// gbuffers_entities (mobs, item frames) and its fallbacks (OptiFine's shaders.txt; Iris's
/// are the same for opaque entities).
pub const ENTITY_CHAIN: [&str; 4] = ["gbuffers_entities", "gbuffers_textured_lit", "gbuffers_textured", "gbuffers_basic"];

/// gbuffers_skybasic and its fallbacks.
pub const SKY_CHAIN: [&str; 2] = ["gbuffers_skybasic", "gbuffers_basic"];

/// gbuffers_skytextured (the sun and the moon) and its fallbacks.
pub const SKY_TEXTURED_CHAIN: [&str; 3] = ["gbuffers_skytextured", "gbuffers_textured", "gbuffers_basic"];

/// The full-screen programs OptiFine runs, by family, in frame order within each family
/// (`composite`, `composite1` … `composite99`), before `final`.
pub const FULLSCREEN_FAMILIES: [&str; 3] = ["prepare", "deferred", "composite"];

/// A loader and version whose behaviour the toolchain reproduces.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Loader {
    /// OptiFine for Minecraft 1.21 (HD U J1): core profile, legacy GLSL rewritten on load.
    #[default]
    OptiFine1_21,
    /// OptiFine for Minecraft 1.16.5 (HD U G8): the first with per-buffer blend modes.
    OptiFine1_16_5,
    /// OptiFine for Minecraft 1.12.2 (HD U G5): fixed-function alpha test on water.
    OptiFine1_12_2,
    /// OptiFine for Minecraft 1.8.9 (HD U M5).
    OptiFine1_8_9,
    /// Iris 1.4 and later on OpenGL 4.0 or newer.
    Iris,
}

/// What a loader draws with where the pack has no program for it (the chain of fallbacks ends
/// at none): the game's own shading.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MissingProgramDraws {
    /// Into colortex0 only (Iris's built-in fallback; OptiFine 1.17+'s vanilla shaders, whose
    /// other outputs are undefined and modelled as left alone).
    FirstBufferOnly,
    /// The same colour into every draw buffer bound, which is all the colour buffers the pack
    /// uses (OptiFine up to 1.16.5: fixed-function output goes to every draw buffer, and a
    /// missing program does not change the draw buffers the clear left).
    EveryBuffer,
}

/// Translucent geometry the game draws around the water whose programs and order differ between
/// loaders: which programs draw it ([`Loader::program_chain`]), and when ([`Loader::phase`]).
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[serde(rename_all = "lowercase")]
pub enum OverlayKind {
    Particles,
    Clouds,
    Rain,
    Hand,
}

impl OverlayKind {
    pub const ALL: [OverlayKind; 4] = [OverlayKind::Particles, OverlayKind::Clouds, OverlayKind::Rain, OverlayKind::Hand];
}

/// When the loader draws a kind of overlay geometry, relative to the terrain and the water.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Phase {
    BeforeTerrain,
    /// After the opaque terrain, before depthtex1 is copied and the water drawn.
    BeforeWater,
    /// After the water, before composite.
    AfterWater,
}

impl Loader {
    pub const ALL: [Loader; 5] =
        [Loader::OptiFine1_21, Loader::OptiFine1_16_5, Loader::OptiFine1_12_2, Loader::OptiFine1_8_9, Loader::Iris];

    pub fn name(self) -> &'static str {
        match self {
            Loader::OptiFine1_21 => "optifine-1.21",
            Loader::OptiFine1_16_5 => "optifine-1.16.5",
            Loader::OptiFine1_12_2 => "optifine-1.12.2",
            Loader::OptiFine1_8_9 => "optifine-1.8.9",
            Loader::Iris => "iris",
        }
    }

    /// Whether the driver gets a stage as the loader's own preprocessor left it. Iris runs every
    /// stage through its preprocessor (JCPP) before its transformer reads the text, so the
    /// driver sees no conditional or macro, and a `#version` inside the pack's `#if` (one per
    /// profile) reaches it alone, on top; OptiFine gives the driver the text with its includes
    /// expanded, conditionals and all, for the driver's preprocessor to read.
    pub fn preprocesses_for_driver(self) -> bool {
        self == Loader::Iris
    }

    /// Whether a stage's `uniform sampler2D gcolor;` or `texture;` is the albedo texture under the
    /// name `gtexture`: Iris's transformer renames such a declaration, and every use of the name
    /// that is not a call, to `gtexture` (keeping one declaration where both exist), and binds
    /// `gtexture` to the albedo in the world's programs.
    pub fn renames_albedo_sampler(self) -> bool {
        self == Loader::Iris
    }

    /// Whether a function whose name a stage never uses is removed before the driver compiles
    /// it: Iris's transformer drops every definition other than `main` whose name occurs once
    /// (IrisShaders/Iris `CompatibilityTransformer`), so what it references need not exist.
    pub fn removes_unused_functions(self) -> bool {
        self == Loader::Iris
    }

    /// Whether a stage's `#version` below 3.30 reaches the driver raised to 3.30: Iris's
    /// `TransformPatcher` raises every stage (and then replaces the legacy built-ins), so a
    /// `#version 130` stage may call `inverse()` (clorece/Allium's anisotropic filtering).
    pub fn raises_version_to_330(self) -> bool {
        self == Loader::Iris
    }

    /// What this loader's transformer does to the stages of `program` before the driver gets
    /// them. Only the programs that draw the world bind `gtexture`; in full-screen passes Iris's
    /// renamed sampler reads texture unit 0, colortex0, as `gcolor` does.
    pub fn transform(self, program: &str) -> crate::iris::Transform {
        crate::iris::Transform {
            renames_albedo_sampler: self.renames_albedo_sampler() && crate::programs::binds_as_gbuffers(program),
            removes_unused_functions: self.removes_unused_functions(),
            raises_version: self.raises_version_to_330(),
        }
    }

    /// Reads `blend.<program>.<buffer>`: OptiFine from 1.16.5 HD U G7, Iris from 1.4 with
    /// OpenGL 4.0. Older OptiFine skips such keys without a word.
    pub fn per_buffer_blend(self) -> bool {
        !matches!(self, Loader::OptiFine1_12_2 | Loader::OptiFine1_8_9)
    }

    /// The alpha test on gbuffers_water's output 0 when shaders.properties has no
    /// `alphaTest.gbuffers_water`: fixed-function `GREATER 0.1` up to Minecraft 1.12; none on
    /// 1.15 to 1.16.5; from 1.17 OptiFine adds `if (a < alphaTestRef) discard;` to writes of
    /// `gl_FragData[0]` and `gl_FragColor` (`legacy_outputs`), not to declared outputs.
    /// Iris draws water with the test off.
    pub fn default_water_alpha_test(self, legacy_outputs: bool) -> Option<f32> {
        match self {
            Loader::OptiFine1_12_2 | Loader::OptiFine1_8_9 => Some(0.1),
            Loader::OptiFine1_21 if legacy_outputs => Some(0.1),
            Loader::OptiFine1_21 | Loader::OptiFine1_16_5 | Loader::Iris => None,
        }
    }

    /// The alpha test on cutout terrain (leaves): fixed-function `GREATER 0.1` up to 1.16.5;
    /// from 1.17 OptiFine adds it only to programs writing `gl_FragData`/`gl_FragColor`
    /// (`legacy_outputs`); so does Iris, whose transformer appends the test to a compatibility
    /// stage's writes of `gl_FragData[0]` alone (IrisShaders/Iris `CommonTransformer`).
    pub fn cutout_alpha_test(self, legacy_outputs: bool) -> Option<f32> {
        match self {
            Loader::OptiFine1_21 | Loader::Iris if !legacy_outputs => None,
            _ => Some(0.1),
        }
    }

    /// The programs that may draw `kind`, in fallback order: the loader uses the first the pack
    /// has. OptiFine draws particles with gbuffers_textured_lit; Iris has gbuffers_particles.
    pub fn program_chain(self, kind: OverlayKind) -> &'static [&'static str] {
        match kind {
            OverlayKind::Particles if self == Loader::Iris => {
                &["gbuffers_particles", "gbuffers_textured_lit", "gbuffers_textured", "gbuffers_basic"]
            }
            OverlayKind::Particles => &["gbuffers_textured_lit", "gbuffers_textured", "gbuffers_basic"],
            OverlayKind::Clouds => &["gbuffers_clouds", "gbuffers_textured", "gbuffers_basic"],
            OverlayKind::Rain => &["gbuffers_weather", "gbuffers_textured_lit", "gbuffers_textured", "gbuffers_basic"],
            OverlayKind::Hand => {
                &["gbuffers_hand_water", "gbuffers_hand", "gbuffers_textured_lit", "gbuffers_textured", "gbuffers_basic"]
            }
        }
    }

    /// The programs that draw the opaque terrain (or, `translucent`, the water) into the shadow
    /// map, in fallback order. OptiFine draws everything with `shadow` (its shaders.txt: the
    /// programs shadow_solid and shadow_cutout "are not used"); Iris has shadow_solid and
    /// shadow_water.
    pub fn shadow_chain(self, translucent: bool) -> &'static [&'static str] {
        match (self, translucent) {
            (Loader::Iris, false) => &["shadow_solid", "shadow"],
            (Loader::Iris, true) => &["shadow_water", "shadow"],
            _ => &["shadow"],
        }
    }

    /// When `kind` is drawn. Up to Minecraft 1.12 OptiFine draws particles and rain before the
    /// water, and clouds the camera is below before the terrain; later versions draw all of
    /// them after the water. Iris draws opaque particles with the opaque world.
    pub fn phase(self, kind: OverlayKind, camera_below_clouds: bool, opaque: bool) -> Phase {
        let old = matches!(self, Loader::OptiFine1_12_2 | Loader::OptiFine1_8_9);
        match kind {
            OverlayKind::Particles | OverlayKind::Rain if old => Phase::BeforeWater,
            OverlayKind::Clouds if old && camera_below_clouds => Phase::BeforeTerrain,
            OverlayKind::Particles if self == Loader::Iris && opaque => Phase::BeforeWater,
            _ => Phase::AfterWater,
        }
    }

    pub fn missing_program_draws(self) -> MissingProgramDraws {
        match self {
            Loader::OptiFine1_16_5 | Loader::OptiFine1_12_2 | Loader::OptiFine1_8_9 => MissingProgramDraws::EveryBuffer,
            Loader::OptiFine1_21 | Loader::Iris => MissingProgramDraws::FirstBufferOnly,
        }
    }
}

impl fmt::Display for Loader {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Loader {
    type Err = String;

    fn from_str(s: &str) -> Result<Loader, String> {
        Loader::ALL.into_iter().find(|l| l.name() == s).ok_or_else(|| {
            let names: Vec<&str> = Loader::ALL.iter().map(|l| l.name()).collect();
            format!("unknown loader {s}; the loaders modelled: {}", names.join(", "))
        })
    }
}

/// Whether rain and snow write depth: not unless a pack sets `rain.depth=true`, which the
/// harness does not imitate.
pub fn writes_depth(kind: OverlayKind) -> bool {
    kind != OverlayKind::Rain
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_unknown_names_list_the_loaders() {
        for loader in Loader::ALL {
            assert_eq!(loader.name().parse::<Loader>(), Ok(loader));
        }
        let err = "optifine-1.7".parse::<Loader>().unwrap_err();
        assert!(err.contains("optifine-1.12.2") && err.contains("iris"), "{err}");
    }

    #[test]
    fn alpha_tests_follow_the_loader() {
        use crate::directives::alpha_test;
        use crate::properties::Properties;
        let water = |properties: &str, loader: Loader, legacy| {
            alpha_test(&Properties::parse_plain(properties), "gbuffers_water", loader.default_water_alpha_test(legacy))
        };
        let off = "alphaTest.gbuffers_water=off\n";
        assert_eq!(water(off, Loader::OptiFine1_12_2, true), Ok(None));
        assert_eq!(water("", Loader::OptiFine1_12_2, false), Ok(Some(0.1)));
        assert_eq!(water("", Loader::OptiFine1_16_5, true), Ok(None));
        assert_eq!(water("", Loader::OptiFine1_21, true), Ok(Some(0.1)));
        assert_eq!(water("", Loader::OptiFine1_21, false), Ok(None));
        assert_eq!(water("alphaTest.gbuffers_water=GREATER 0.5", Loader::Iris, false), Ok(Some(0.5)));
        assert!(water("alphaTest.gbuffers_water=LESS 0.5", Loader::Iris, false).is_err());
        // Cutout terrain: every loader tests it, OptiFine from 1.17 only in legacy outputs.
        assert_eq!(Loader::OptiFine1_16_5.cutout_alpha_test(false), Some(0.1));
        assert_eq!(Loader::OptiFine1_21.cutout_alpha_test(false), None);
        assert_eq!(Loader::OptiFine1_21.cutout_alpha_test(true), Some(0.1));
        assert_eq!(Loader::Iris.cutout_alpha_test(false), None);
        assert_eq!(Loader::Iris.cutout_alpha_test(true), Some(0.1));
    }

    #[test]
    fn draw_order_follows_the_loader() {
        use OverlayKind::*;
        assert_eq!(Loader::OptiFine1_12_2.phase(Rain, false, false), Phase::BeforeWater);
        assert_eq!(Loader::OptiFine1_8_9.phase(Particles, false, true), Phase::BeforeWater);
        assert_eq!(Loader::OptiFine1_12_2.phase(Clouds, true, false), Phase::BeforeTerrain);
        assert_eq!(Loader::OptiFine1_12_2.phase(Clouds, false, false), Phase::AfterWater);
        assert_eq!(Loader::OptiFine1_16_5.phase(Rain, false, false), Phase::AfterWater);
        assert_eq!(Loader::OptiFine1_21.phase(Clouds, true, false), Phase::AfterWater);
        assert_eq!(Loader::Iris.phase(Particles, false, true), Phase::BeforeWater);
        assert_eq!(Loader::Iris.phase(Particles, false, false), Phase::AfterWater);
        assert_eq!(Loader::OptiFine1_21.program_chain(Particles)[0], "gbuffers_textured_lit");
        assert_eq!(Loader::Iris.program_chain(Particles)[0], "gbuffers_particles");
        assert!(Loader::ALL.iter().all(|l| l.program_chain(Hand)[0] == "gbuffers_hand_water"));
    }
}
