//! What a program's sampler names refer to, as the loaders bind them: the frame's colour and
//! depth buffers, the shadow maps, the game's textures, a pack's custom textures, or nothing.
//! Both renderers bind by this; it holds no GPU object.

use std::collections::BTreeSet;

use tidepack_loader::buffers::{colour_buffer_number, shadow_colour_number};
use tidepack_loader::directives::TextureTarget;
use tidepack_loader::loader::Loader;

use crate::program::{LoadedProgram, PackResources, texture_resources};

/// What a sampler name in a program refers to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Source {
    /// The atlas of what is being drawn: blocks, or the sun's or moon's sprite.
    Atlas,
    /// The block atlas wherever it is read (`minecraft:textures/atlas/blocks.png`).
    BlockAtlas,
    Lightmap,
    Noise,
    Color(u8),
    Depth0,
    Depth1,
    /// Distant Horizons' depth: dhDepthTex0 (its water included) or dhDepthTex1 (without).
    LodDepth(u8),
    /// A custom texture of the pack (index into [`PackResources::custom_textures`]).
    Custom(usize),
    /// The normal map of a resource pack without one: flat, (0.5, 0.5, 1).
    FlatNormals,
    /// The specular map of a resource pack without one: zero.
    NoSpecular,
    /// shadowtex0 (everything the shadow pass drew) or shadowtex1 (without translucents).
    ShadowDepth(u8),
    /// shadowcolorN.
    ShadowColour(u8),
    /// A name OptiFine binds nothing to: transparent black.
    Unbound,
}

/// Which programs a `texture.<stage>.<name>` line of shaders.properties binds in, by the
/// program's name: OptiFine's `gbuffers` (the gbuffers programs and the shadow pass),
/// `deferred` and `composite` (the composite programs and final), and Iris's `prepare` and
/// `shadowcomp`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProgramStage {
    Gbuffers,
    ShadowComposite,
    Prepare,
    Deferred,
    Composite,
}

impl ProgramStage {
    /// The stage of the program named `program` (`world0/deferred2` too).
    pub fn of(program: &str) -> ProgramStage {
        let name = program.rsplit('/').next().unwrap_or(program);
        if name.starts_with("gbuffers_") || name.starts_with("dh_") || name == "shadow" || name.starts_with("shadow_") {
            ProgramStage::Gbuffers
        } else if name.starts_with("shadowcomp") {
            ProgramStage::ShadowComposite
        } else if name.starts_with("deferred") {
            ProgramStage::Deferred
        } else if name.starts_with("prepare") {
            ProgramStage::Prepare
        } else {
            ProgramStage::Composite
        }
    }

    /// Its name in `texture.<stage>.<name>`.
    pub fn in_properties(self) -> &'static str {
        match self {
            ProgramStage::Gbuffers => "gbuffers",
            ProgramStage::ShadowComposite => "shadowcomp",
            ProgramStage::Prepare => "prepare",
            ProgramStage::Deferred => "deferred",
            ProgramStage::Composite => "composite",
        }
    }

    /// A geometry program: its sampler names read the game's textures and the depth being drawn.
    pub fn is_gbuffers(self) -> bool {
        self == ProgramStage::Gbuffers
    }

    /// prepare, deferred, composite and final: the passes that bind the colour buffers, colortex0
    /// on unit 0.
    pub fn is_fullscreen(self) -> bool {
        matches!(self, ProgramStage::Prepare | ProgramStage::Deferred | ProgramStage::Composite)
    }
}

/// How sampler names resolve.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SamplerNaming {
    /// The frame's gbuffers and full-screen programs ([`resolve_any`]): every name OptiFine
    /// binds.
    Frame,
    /// The shadow pass's programs ([`resolve_in_shadow_pass`]).
    ShadowPass,
}

impl SamplerNaming {
    /// What `name` refers to in a program of this naming and `stage`.
    pub fn resolve(self, pack: &dyn PackResources, name: &str, stage: ProgramStage) -> Result<Source, String> {
        match self {
            SamplerNaming::Frame => resolve_any(pack, name, stage),
            SamplerNaming::ShadowPass => resolve_in_shadow_pass(pack, name),
        }
    }
}

/// Resolves a sampler name as OptiFine binds it in any pack, in a program of `stage`. In
/// gbuffers programs colour buffers are read as they stood before the draw, and depthtex0 (the
/// buffer being drawn into) is read as depthtex1. A name the loader binds nothing to keeps the
/// uniform's initial value, texture unit 0: colortex0 in a full-screen pass (where both loaders
/// bind it there, Iris calling it the pass's default sampler), and transparent black elsewhere.
pub fn resolve_any(pack: &dyn PackResources, name: &str, stage: ProgramStage) -> Result<Source, String> {
    if let Some(i) = custom_texture_of(pack, name, stage, TextureTarget::D2) {
        return Ok(Source::Custom(i));
    }
    if let Some(bound) = pack.game_textures().iter().find(|t| t.stage == stage.in_properties() && same_unit(&t.unit, name)) {
        return Ok(bound.source);
    }
    Ok(match (name, stage.is_gbuffers()) {
        ("noisetex", _) => Source::Noise,
        ("gtexture" | "texture" | "tex", true) => Source::Atlas,
        ("lightmap", true) => Source::Lightmap,
        ("normals", true) => Source::FlatNormals,
        ("specular", true) => Source::NoSpecular,
        ("depthtex0" | "gdepthtex", false) => Source::Depth0,
        ("depthtex0" | "gdepthtex" | "depthtex1" | "depthtex2", _) => Source::Depth1,
        // `shadow` leaves the translucents out where the pack also reads `watershadow`.
        ("shadow", _) => Source::ShadowDepth(if pack.water_shadow() { 1 } else { 0 }),
        ("shadowtex0" | "watershadow", _) => Source::ShadowDepth(0),
        ("shadowtex1", _) => Source::ShadowDepth(1),
        // Iris's SEPARATE_HARDWARE_SAMPLERS: the shadow maps again, for comparison lookups.
        ("shadowtex0HW", _) if pack.loader() == Loader::Iris => Source::ShadowDepth(0),
        ("shadowtex1HW", _) if pack.loader() == Loader::Iris => Source::ShadowDepth(1),
        ("dhDepthTex" | "dhDepthTex0", _) => Source::LodDepth(0),
        ("dhDepthTex1", _) => Source::LodDepth(1),
        _ => match (colour_buffer_number(name), shadow_colour_number(name)) {
            (Some(n), _) => Source::Color(n),
            (None, Some(n)) => Source::ShadowColour(n),
            (None, None) if stage.is_fullscreen() => Source::Color(0),
            (None, None) => Source::Unbound,
        },
    })
}

/// The custom texture made as `target` that the sampler `name` reads in programs of `stage`.
/// A unit holds one texture per target, so a `sampler3D colortex7` reads the unit's 3D
/// texture while a `sampler2D colortex7` still reads the buffer. A colour buffer's unit goes
/// by both its names (`gaux1`, `colortex4`).
pub fn custom_texture_of(pack: &dyn PackResources, name: &str, stage: ProgramStage, target: TextureTarget) -> Option<usize> {
    pack.custom_textures().iter().position(|t| t.stage == stage.in_properties() && t.target == target && same_unit(&t.unit, name))
}

/// Whether two sampler names are one texture unit: the same name, or a colour buffer's two
/// names.
fn same_unit(unit: &str, name: &str) -> bool {
    unit == name || colour_buffer_number(unit).is_some_and(|n| colour_buffer_number(name) == Some(n))
}

/// A texture of the game that `texture.<stage>.<unit>=minecraft:…` binds to a unit.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GameTextureBinding {
    pub stage: String,
    pub unit: String,
    pub source: Source,
}

/// The harness's stand-in for a game texture shaders.properties names (OptiFine's
/// shaders.properties, "Resource pack" and "Dynamic"): the block atlas and its normal and
/// specular variants (the harness's resource pack has neither map), and the lightmap. `None`
/// for the textures of the game's assets, which the harness does not hold.
pub fn game_texture(path: &str) -> Option<Source> {
    match path.strip_prefix("minecraft:")?.trim_end_matches(".png") {
        "textures/atlas/blocks" => Some(Source::BlockAtlas),
        "textures/atlas/blocks_n" => Some(Source::FlatNormals),
        "textures/atlas/blocks_s" => Some(Source::NoSpecular),
        "dynamic/lightmap_1" => Some(Source::Lightmap),
        _ => None,
    }
}

/// Resolves a sampler name in the shadow pass: as in gbuffers programs, except that the
/// frame's colour and depth buffers are not bound there (custom textures are), and the shadow
/// maps read as nothing drawn, since they are being drawn.
pub fn resolve_in_shadow_pass(pack: &dyn PackResources, name: &str) -> Result<Source, String> {
    Ok(match resolve_any(pack, name, ProgramStage::Gbuffers)? {
        Source::Color(_) | Source::Depth0 | Source::Depth1 | Source::LodDepth(_) => Source::Unbound,
        source => source,
    })
}

/// The colour buffers a program samples, its sampler names resolved under `naming`.
pub fn colour_buffers_read(pack: &dyn PackResources, program: &LoadedProgram, naming: SamplerNaming) -> BTreeSet<u8> {
    let names = [&program.vertex, &program.fragment].into_iter().flat_map(|stage| texture_resources(&stage.interface)).map(|(name, _)| name);
    colour_buffers_named(pack, names, ProgramStage::of(&program.name), naming)
}

/// The colour buffers the sampler `names` of a program of `stage` read, resolved under `naming`.
pub fn colour_buffers_named(pack: &dyn PackResources, names: impl IntoIterator<Item = String>, stage: ProgramStage, naming: SamplerNaming) -> BTreeSet<u8> {
    names
        .into_iter()
        .filter_map(|name| match naming.resolve(pack, &name, stage) {
            Ok(Source::Color(n)) => Some(n),
            _ => None,
        })
        .collect()
}

