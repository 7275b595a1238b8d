//! Lowering of OptiFine GLSL (`#version 120`, `330 compatibility`, …) to the Vulkan GLSL 450
//! that naga reads.
//!
//! The lowering works on the preprocessed text, token by token, and never adds or removes a
//! line break: declarations it must add go on the `#version` line, declarations it replaces are
//! rewritten on their own lines. Lowered line N is therefore preprocessed line N, and the
//! preprocessor's source map locates every naga error in the pack's files.
//!
//! The rewrites (each pinned by a snapshot in tests/lowering):
//! - `#version …` becomes `#version 450`; `#extension` lines are dropped.
//! - `attribute` and vertex `in` get `layout(location = 8 + k)` in declaration order; the legacy
//!   vertex inputs (`gl_Vertex`, `gl_Normal`, `gl_Color`, `gl_MultiTexCoordN`) become reserved
//!   inputs at locations 0-7.
//! - `varying` and stage `in`/`out` get the program-wide location of their name (see
//!   [`VaryingLayout`]), so both stages agree; `gl_FrontColor`/`gl_Color` and `gl_TexCoord[i]`
//!   become reserved varyings.
//! - Fragment outputs: `gl_FragData[i]` and `gl_FragColor` become `layout(location = i) out vec4`;
//!   330 `out vec4 outColorN` gets location N, other outputs their declaration order (or their
//!   `layout(location)`); an output packed beside another by `component` gets a location of
//!   its own from [`PACKED_OUTPUT_LOCATION`].
//! - A `return`, `discard`, `break` or `continue` followed by more statements of its block
//!   becomes `if (true) return …`, so naga keeps the unreachable statements.
//! - Arrays of arrays get their sizes in the order naga's parser nests them (reversed); inside
//!   a function, a local integer constant of literals is written as its value inside `[…]`.
//! - In compute stages, `gl_WorkGroupSize` becomes the `uvec3` of the declared local size.
//! - `texture2D`, `texture2DLod`, `shadow2D`, … become `texture`, `textureLod`, and
//!   `vec4(vec3(texture(...)), 1.0)` for the shadow forms. Outside fragment stages, where GLSL
//!   samples the base level and naga refuses implicit levels, `texture(s, p)` (also from
//!   `texture2D`, `shadow2D`, …) becomes `textureLod(s, p, 0.0)`.
//! - A combined `uniform sampler2D s` becomes `texture2D s` plus `sampler tp_sampler_s`, and
//!   every use of `s` becomes `sampler2D(s, tp_sampler_s)`; a function taking a sampler takes
//!   both halves, and its call sites pass both. The old atlas name `texture` becomes `gtexture`.
//! - Loose uniforms move into one uniform block (members are visible without an instance name,
//!   so their uses do not change); legacy matrices (`gl_ModelViewMatrix`, …) join it as reserved
//!   members and `ftransform()` becomes their product with the vertex.
//!
//! - Matrix varyings travel as column vectors (`tp_<name>_<c>`) at consecutive locations; the
//!   pack's `main` becomes `tp_main` and a `main` appended to the last line copies the columns
//!   out (vertex) or rebuilds the matrix before calling it (fragment). Array varyings take one
//!   location per element.
//! - `gl_FogFragCoord`, `gl_FrontSecondaryColor`/`gl_SecondaryColor` become reserved varyings;
//!   `gl_Fog` a block member of a reserved struct type; `gl_MultiTexCoord3..7`, `gl_FogCoord`
//!   and vertex `gl_SecondaryColor` reserved inputs from [`RARE_LEGACY_INPUT_LOCATION`].
//! - `uniform bool b` becomes the block member `int tp_bool_b`, read as `(tp_bool_b != 0)`;
//!   uniforms of a struct type get a block of their own on their line; uniform initializers are
//!   dropped, their text kept in [`Interface::uniform_initializers`] (the value until the
//!   loader sets one).
//!
//! - Storage images (`layout(rgba16f) uniform image2D colorimg0;`) get a set and binding; an
//!   image without a format (allowed for `writeonly`) gets the 32-bit four-component format of
//!   its type. `memoryBarrier*()`/`groupMemoryBarrier()` and the `int`/`uint` `atomic*()`
//!   functions, which naga's GLSL front-end lacks, get stand-ins of the same signature on line 2
//!   when a stage calls them.
//! - `in`/`out` interface blocks lose the qualifiers of their members (naga reads none there)
//!   and each gets the locations the program's [`VaryingLayout`] gives it beside the varyings
//!   (matched across stages by block name), or, lowered alone, from [`INTERFACE_BLOCK_LOCATION`].
//! - The pack's buffer and uniform blocks with a `binding` go to their own descriptor sets in
//!   vertex and fragment stages ([`PACK_BUFFER_SET`]), clear of the lowered resources.
//! - Compute stages ([`lower_compute`]): uniforms, samplers and images as above (descriptor set
//!   [`COMPUTE_DESCRIPTOR_SET`]); `layout(local_size_…) in;`, `shared` and the `gl_*` compute
//!   built-ins are left as they are; no varyings or legacy built-ins.
//!
//! Reserved names all start with `tp_`.

use std::collections::{BTreeMap, BTreeSet, HashMap, HashSet};
use std::fmt::Write as _;

use crate::preprocess::literal_integer_expression;
use crate::token::{Token, TokenKind, argument_count, brace_depths, function_definitions, matching_close, tokenize};

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Stage {
    Vertex,
    Fragment,
}

impl Stage {
    /// The stage of an OptiFine shader file, by extension.
    pub fn from_path(path: &str) -> Option<Stage> {
        if path.ends_with(".vsh") {
            Some(Stage::Vertex)
        } else if path.ends_with(".fsh") {
            Some(Stage::Fragment)
        } else {
            None
        }
    }

    /// Descriptor set of the stage's resources; the stages of a program use different sets so
    /// their uniform blocks never collide.
    pub fn descriptor_set(self) -> u32 {
        match self {
            Stage::Vertex => 0,
            Stage::Fragment => 1,
        }
    }
}

/// Descriptor set of a compute stage's lowered resources (the pack's own `layout(binding = N)`
/// blocks stay in set 0).
pub const COMPUTE_DESCRIPTOR_SET: u32 = 2;

/// Descriptor set of the pack's own buffer blocks (`layout(std430, binding = N) buffer …`) in
/// vertex and fragment stages, clear of the sets the lowering uses there; uniform blocks with a
/// binding take the next one (OpenGL numbers the two kinds of binding apart).
pub const PACK_BUFFER_SET: u32 = 3;

/// Location of the first `in`/`out` interface block of a stage lowered without its program's
/// [`VaryingLayout`]: naga takes a block as one value whose members follow each other from
/// location 0 unless told otherwise, where they would collide with the varyings. Each further
/// block starts [`INTERFACE_BLOCK_STRIDE`] locations on.
pub const INTERFACE_BLOCK_LOCATION: u32 = 64;
pub const INTERFACE_BLOCK_STRIDE: u32 = 64;

/// Prefix of every name the lowering adds.
pub const RESERVED_PREFIX: &str = "tp_";
/// The block member a `uniform bool NAME` becomes: an int, `BOOL_UNIFORM_PREFIX` + NAME, read as
/// `!= 0` (a bool cannot live in a uniform buffer).
pub const BOOL_UNIFORM_PREFIX: &str = "tp_bool_";
/// Fragment outputs packed beside another by `layout(component = c)` are lowered to location
/// `PACKED_OUTPUT_LOCATION + 4 * location + c`, clear of every render target.
pub const PACKED_OUTPUT_LOCATION: u32 = 16;
/// First location of user vertex attributes; 0-7 are the legacy built-in inputs.
pub const FIRST_ATTRIBUTE_LOCATION: u32 = 8;

/// Legacy vertex inputs and their reserved names and locations.
/// The rarely used ones sit above the user attributes (from [`RARE_LEGACY_INPUT_LOCATION`]).
const LEGACY_INPUTS: [(&str, &str, &str, u32); 13] = [
    ("gl_Vertex", "tp_Vertex", "vec4", 0),
    ("gl_Color", "tp_Color", "vec4", 1),
    ("gl_Normal", "tp_Normal", "vec3", 2),
    ("gl_MultiTexCoord0", "tp_MultiTexCoord0", "vec4", 3),
    ("gl_MultiTexCoord1", "tp_MultiTexCoord1", "vec4", 4),
    ("gl_MultiTexCoord2", "tp_MultiTexCoord2", "vec4", 5),
    ("gl_MultiTexCoord3", "tp_MultiTexCoord3", "vec4", RARE_LEGACY_INPUT_LOCATION),
    ("gl_MultiTexCoord4", "tp_MultiTexCoord4", "vec4", RARE_LEGACY_INPUT_LOCATION + 1),
    ("gl_MultiTexCoord5", "tp_MultiTexCoord5", "vec4", RARE_LEGACY_INPUT_LOCATION + 2),
    ("gl_MultiTexCoord6", "tp_MultiTexCoord6", "vec4", RARE_LEGACY_INPUT_LOCATION + 3),
    ("gl_MultiTexCoord7", "tp_MultiTexCoord7", "vec4", RARE_LEGACY_INPUT_LOCATION + 4),
    ("gl_SecondaryColor", "tp_SecondaryColor", "vec4", RARE_LEGACY_INPUT_LOCATION + 5),
    ("gl_FogCoord", "tp_FogCoord", "float", RARE_LEGACY_INPUT_LOCATION + 6),
];

/// First location of the legacy vertex inputs packs rarely use (`gl_MultiTexCoord3..7`,
/// `gl_SecondaryColor`, `gl_FogCoord`), above any realistic number of user attributes.
pub const RARE_LEGACY_INPUT_LOCATION: u32 = 24;

/// Legacy varyings: the built-in name in each stage, the reserved varying and its type.
/// `gl_Color`/`gl_SecondaryColor` are varyings only in the fragment stage.
const LEGACY_VARYINGS: [(&str, &str, &str, &str); 3] = [
    ("gl_FrontColor", "gl_Color", "tp_FrontColor", "vec4"),
    ("gl_FrontSecondaryColor", "gl_SecondaryColor", "tp_FrontSecondaryColor", "vec4"),
    ("gl_FogFragCoord", "gl_FogFragCoord", "tp_FogFragCoord", "float"),
];

/// The legacy `gl_Fog` uniform becomes a block member of this struct type.
const FOG_STRUCT: &str = "struct tp_FogParameters { vec4 color; float density; float start; float end; float scale; };";

/// Legacy matrices and the uniform-block members that replace them.
const LEGACY_MATRICES: [(&str, &str, &str); 9] = [
    ("gl_ModelViewMatrix", "tp_ModelViewMatrix", "mat4"),
    ("gl_ProjectionMatrix", "tp_ProjectionMatrix", "mat4"),
    ("gl_ModelViewProjectionMatrix", "tp_ModelViewProjectionMatrix", "mat4"),
    ("gl_NormalMatrix", "tp_NormalMatrix", "mat3"),
    ("gl_TextureMatrix", "tp_TextureMatrix", "mat4[8]"),
    ("gl_ModelViewMatrixInverse", "tp_ModelViewMatrixInverse", "mat4"),
    ("gl_ProjectionMatrixInverse", "tp_ProjectionMatrixInverse", "mat4"),
    ("gl_ModelViewProjectionMatrixInverse", "tp_ModelViewProjectionMatrixInverse", "mat4"),
    ("gl_TextureMatrixInverse", "tp_TextureMatrixInverse", "mat4[8]"),
];

/// Sampling built-ins of old GLSL and their 450 names; `true` for the shadow forms, which
/// returned a `vec4` and now return a `float`.
const LEGACY_SAMPLING: &[(&str, &str, bool)] = &[
    ("texture1D", "texture", false),
    ("texture2D", "texture", false),
    ("texture3D", "texture", false),
    ("textureCube", "texture", false),
    ("texture2DLod", "textureLod", false),
    ("texture3DLod", "textureLod", false),
    ("textureCubeLod", "textureLod", false),
    ("texture2DProj", "textureProj", false),
    ("texture2DProjLod", "textureProjLod", false),
    ("texture2DGrad", "textureGrad", false),
    ("texture2DGradARB", "textureGrad", false),
    ("texture2DLodEXT", "textureLod", false),
    ("texture1DLod", "textureLod", false),
    ("texture3DProj", "textureProj", false),
    ("textureCubeGrad", "textureGrad", false),
    ("texture2DArray", "texture", false),
    ("texture2DArrayLod", "textureLod", false),
    // GL_EXT_gpu_shader4 forms.
    ("texelFetch2D", "texelFetch", false),
    ("texelFetch3D", "texelFetch", false),
    ("textureSize2D", "textureSize", false),
    ("textureSize3D", "textureSize", false),
    ("texture2DLodOffset", "textureLodOffset", false),
    ("texelFetch2DOffset", "texelFetchOffset", false),
    ("shadow2D", "texture", true),
    ("shadow2DLod", "textureLod", true),
    ("shadow2DProj", "textureProj", true),
];

/// Combined sampler types and their separate texture type and sampler type.
fn split_sampler_type(ty: &str) -> Option<(&'static str, &'static str)> {
    Some(match ty {
        "sampler1D" => ("texture1D", "sampler"),
        "sampler2D" => ("texture2D", "sampler"),
        "sampler3D" => ("texture3D", "sampler"),
        "samplerCube" => ("textureCube", "sampler"),
        "sampler2DShadow" => ("texture2D", "samplerShadow"),
        "sampler2DArray" => ("texture2DArray", "sampler"),
        "isampler1D" => ("itexture1D", "sampler"),
        "usampler1D" => ("utexture1D", "sampler"),
        "isampler2D" => ("itexture2D", "sampler"),
        "usampler2D" => ("utexture2D", "sampler"),
        "isampler3D" => ("itexture3D", "sampler"),
        "usampler3D" => ("utexture3D", "sampler"),
        "isampler2DArray" => ("itexture2DArray", "sampler"),
        "usampler2DArray" => ("utexture2DArray", "sampler"),
        _ => return None,
    })
}

/// Whether `name` is a lookup at the implicit level of detail (`texture`, `texture2D`,
/// `shadow2D`, …): the ones a third argument gives a bias, and whose level form is `name` + `Lod`.
pub(crate) fn is_implicit_level_lookup(name: &str) -> bool {
    name == "texture" || LEGACY_SAMPLING.iter().any(|&(old, new, _)| old == name && new == "texture")
}

/// The number of components of a float type (`float` 1, `vec2` … `vec4`).
pub fn float_components(ty: &str) -> Option<usize> {
    match ty {
        "float" => Some(1),
        "vec2" => Some(2),
        "vec3" => Some(3),
        "vec4" => Some(4),
        _ => None,
    }
}

/// GLSL's own types (scalars, vectors, matrices); anything else is a struct.
pub fn is_builtin_type(ty: &str) -> bool {
    matches!(ty, "float" | "int" | "uint" | "bool" | "double")
        || matrix_shape(ty).is_some()
        || ["vec", "ivec", "uvec", "bvec", "dvec"]
            .iter()
            .any(|p| ty.strip_prefix(p).is_some_and(|n| matches!(n, "2" | "3" | "4")))
}

fn is_varying_qualifier(word: &str) -> bool {
    matches!(word, "flat" | "smooth" | "noperspective" | "centroid" | "invariant")
}

pub fn is_memory_qualifier(word: &str) -> bool {
    matches!(word, "readonly" | "writeonly" | "coherent" | "volatile" | "restrict")
}

/// Whether `ty` names a storage image type (`image2D`, `uimage3D`, `iimageCube`, `imageBuffer`, …).
pub fn is_image_type(ty: &str) -> bool {
    ["image", "iimage", "uimage"].iter().any(|p| ty.strip_prefix(p).is_some_and(|rest| rest.starts_with(['1', '2', '3', 'C', 'B'])))
}

/// Storage image types and the format an image of that type gets when it declares none.
fn image_default_format(ty: &str) -> Option<&'static str> {
    const DIMS: [&str; 6] = ["1D", "2D", "3D", "Cube", "2DArray", "1DArray"];
    let (prefix, format) = if let Some(rest) = ty.strip_prefix("iimage") {
        (rest, "rgba32i")
    } else if let Some(rest) = ty.strip_prefix("uimage") {
        (rest, "rgba32ui")
    } else {
        (ty.strip_prefix("image")?, "rgba32f")
    };
    DIMS.contains(&prefix).then_some(format)
}

/// Built-in functions naga's GLSL front-end lacks, and stand-ins with their signatures.
const MISSING_BUILTINS: &[(&str, &str)] = &[
    ("memoryBarrier", "void memoryBarrier() {}"),
    ("memoryBarrierShared", "void memoryBarrierShared() {}"),
    ("memoryBarrierImage", "void memoryBarrierImage() {}"),
    ("memoryBarrierBuffer", "void memoryBarrierBuffer() {}"),
    ("memoryBarrierAtomicCounter", "void memoryBarrierAtomicCounter() {}"),
    ("groupMemoryBarrier", "void groupMemoryBarrier() {}"),
    ("atomicAdd", "int atomicAdd(inout int m, int v) { return m; } uint atomicAdd(inout uint m, uint v) { return m; }"),
    ("atomicMin", "int atomicMin(inout int m, int v) { return m; } uint atomicMin(inout uint m, uint v) { return m; }"),
    ("atomicMax", "int atomicMax(inout int m, int v) { return m; } uint atomicMax(inout uint m, uint v) { return m; }"),
    ("atomicAnd", "int atomicAnd(inout int m, int v) { return m; } uint atomicAnd(inout uint m, uint v) { return m; }"),
    ("atomicOr", "int atomicOr(inout int m, int v) { return m; } uint atomicOr(inout uint m, uint v) { return m; }"),
    ("atomicXor", "int atomicXor(inout int m, int v) { return m; } uint atomicXor(inout uint m, uint v) { return m; }"),
    (
        "atomicExchange",
        "int atomicExchange(inout int m, int v) { return m; } uint atomicExchange(inout uint m, uint v) { return m; }",
    ),
    // GLSL's geometric functions take a float too (genType); naga's only vectors. The
    // scalar forms as the GLSL specification defines them.
    ("dot", "float dot(float x, float y) { return x * y; }"),
    ("normalize", "float normalize(float x) { return x / abs(x); }"),
    ("reflect", "float reflect(float i, float n) { return i - 2.0 * n * i * n; }"),
    (
        "refract",
        "float refract(float i, float n, float eta) { float k = 1.0 - eta * eta * (1.0 - n * i * n * i); \
         return k < 0.0 ? 0.0 : eta * i - (eta * n * i + sqrt(k)) * n; }",
    ),
    ("faceforward", "float faceforward(float n, float i, float nref) { return nref * i < 0.0 ? n : -n; }"),
    (
        "modf",
        "float modf(float x, out float i) { i = trunc(x); return x - i; } \
         vec2 modf(vec2 x, out vec2 i) { i = trunc(x); return x - i; } \
         vec3 modf(vec3 x, out vec3 i) { i = trunc(x); return x - i; } \
         vec4 modf(vec4 x, out vec4 i) { i = trunc(x); return x - i; }",
    ),
    (
        "atomicCompSwap",
        "int atomicCompSwap(inout int m, int c, int v) { return m; } uint atomicCompSwap(inout uint m, uint c, uint v) { return m; }",
    ),
];

/// The functions of `GL_AMD_shader_trinary_minmax`, built-ins where a stage enables it, which
/// naga lacks.
const TRINARY_MINMAX: [&str; 3] = ["min3", "max3", "mid3"];

/// Stand-ins of a [`TRINARY_MINMAX`] function for every type it takes (genType, genIType,
/// genUType), as the extension defines it.
fn trinary_minmax_stand_in(name: &str) -> String {
    let body = match name {
        "min3" => "min(min(a, b), c)",
        "max3" => "max(max(a, b), c)",
        _ => "max(min(a, b), min(max(a, b), c))",
    };
    ["float", "vec2", "vec3", "vec4", "int", "ivec2", "ivec3", "ivec4", "uint", "uvec2", "uvec3", "uvec4"]
        .iter()
        .map(|ty| format!("{ty} {name}({ty} a, {ty} b, {ty} c) {{ return {body}; }}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// `textureGather*` and `textureQueryLod` on a `sampler2D`, which naga's GLSL front-end lacks.
/// The gathers are exact for a texture that clamps to its edge (the frame's buffers): component
/// `c` of the four texels bilinear filtering would weigh at `p`, in GLSL's order (i0 j1, i1 j1,
/// i1 j0, i0 j0). `textureQueryLod` samples the texture once (its result is not rendered).
const GATHER_STAND_INS: [(&str, &str); 3] = [
    (
        "textureGather",
        "vec4 textureGather(texture2D t, sampler s, vec2 p) { return tp_gather(t, s, p, ivec2(0), 0); } \
         vec4 textureGather(texture2D t, sampler s, vec2 p, int c) { return tp_gather(t, s, p, ivec2(0), c); }",
    ),
    (
        "textureGatherOffset",
        "vec4 textureGatherOffset(texture2D t, sampler s, vec2 p, ivec2 o) { return tp_gather(t, s, p, o, 0); } \
         vec4 textureGatherOffset(texture2D t, sampler s, vec2 p, ivec2 o, int c) { return tp_gather(t, s, p, o, c); }",
    ),
    ("textureQueryLod", "vec2 textureQueryLod(texture2D t, sampler s, vec2 p) { return textureLod(sampler2D(t, s), p, 0.0).xy; }"),
];

/// The gather both `textureGather` stand-ins call, put before them.
const GATHER: &str = "vec4 tp_gather(texture2D t, sampler s, vec2 p, ivec2 o, int c) { \
    ivec2 last = textureSize(sampler2D(t, s), 0) - 1; ivec2 i = ivec2(floor(p * vec2(last + 1) - 0.5)) + o; \
    vec4 t00 = texelFetch(sampler2D(t, s), clamp(i, ivec2(0), last), 0); \
    vec4 t10 = texelFetch(sampler2D(t, s), clamp(i + ivec2(1, 0), ivec2(0), last), 0); \
    vec4 t01 = texelFetch(sampler2D(t, s), clamp(i + ivec2(0, 1), ivec2(0), last), 0); \
    vec4 t11 = texelFetch(sampler2D(t, s), clamp(i + ivec2(1, 1), ivec2(0), last), 0); \
    return vec4(t01[c], t11[c], t10[c], t00[c]); }";

/// Built-ins naga cannot evaluate in a constant expression (drivers can).
const NOT_CONSTANT_FOLDED: &[&str] = &[
    "mix", "smoothstep", "exp2", "log2", "reflect", "refract", "faceforward", "transpose", "determinant", "inverse",
    "outerProduct", "matrixCompMult", "ldexp",
];

/// Built-ins whose constant evaluation in naga refuses arguments outside their domain.
const RANGE_CHECKED_BUILTINS: &[&str] = &["normalize", "sqrt", "inversesqrt", "log", "log2", "pow", "acos", "asin", "acosh", "atanh"];

/// Type names of Vulkan GLSL that are ordinary identifiers in OpenGL GLSL.
const VULKAN_ONLY_KEYWORDS: &[&str] = &[
    "sampler",
    "samplerShadow",
    "texture1D",
    "texture2D",
    "texture3D",
    "textureCube",
    "texture2DArray",
    "texture1DArray",
    "itexture2D",
    "utexture2D",
    "itexture3D",
    "utexture3D",
    "subpassInput",
];

/// Words that can stand before an identifier in a statement without declaring it.
pub fn is_statement_keyword(word: &str) -> bool {
    matches!(word, "return" | "else" | "do" | "case" | "goto")
}

fn is_precision(word: &str) -> bool {
    matches!(word, "highp" | "mediump" | "lowp")
}

/// Program-wide varying locations: every varying name of both stages, sorted, each starting
/// after the locations the previous one takes (an array takes one per element, a matrix one
/// per column).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct VaryingLayout {
    pub locations: BTreeMap<String, u32>,
}

impl VaryingLayout {
    /// Builds the layout from the preprocessed texts of a program's stages.
    pub fn for_program(stages: &[(Stage, &str, u32)]) -> Result<VaryingLayout, LowerError> {
        let mut sizes: BTreeMap<String, u32> = BTreeMap::new();
        for &(stage, text, version) in stages {
            for (name, size) in varyings_of(text, stage, version)? {
                let slot = sizes.entry(name).or_insert(size);
                *slot = (*slot).max(size);
            }
        }
        let mut next = 0u32;
        let mut locations = BTreeMap::new();
        for (name, size) in sizes {
            locations.insert(name, next);
            next = next.saturating_add(size);
        }
        Ok(VaryingLayout { locations })
    }

    /// The location of `name`; one the layout was not built with (a stage lowered alone) gets
    /// a location past every other, so the lowering never fails on it.
    pub fn location_of(&self, name: &str) -> u32 {
        match self.locations.get(name) {
            Some(&location) => location,
            None => self.locations.values().max().map_or(0, |last| last.saturating_add(4)),
        }
    }
}

/// `int`, `uint` and their vectors.
fn is_integer_type(ty: &str) -> bool {
    matches!(ty, "int" | "uint") || ["ivec", "uvec"].iter().any(|p| ty.starts_with(p))
}

/// A varying as a stage declares it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct VaryingDecl {
    pub name: String,
    /// The GLSL type, without array size.
    pub ty: String,
    /// Array size when declared as an array (`0` for an unsized or non-literal size).
    pub array: Option<u32>,
    /// Interpolation qualifiers as written (`flat `, `centroid `, …).
    pub interpolation: String,
    /// 1-based line of the declaration in the preprocessed text.
    pub line: u32,
}

impl VaryingDecl {
    /// Locations the varying takes: one per array element, times one per matrix column or
    /// the locations of a struct's members (`structs`: those of the stage's struct types).
    pub fn locations(&self, structs: &BTreeMap<String, u32>) -> u32 {
        self.array.unwrap_or(1).max(1).saturating_mul(type_locations(&self.ty, structs))
    }
}

/// Locations one value of `ty` takes as a varying: a matrix one per column, a struct the sum
/// of its members', anything else one.
fn type_locations(ty: &str, structs: &BTreeMap<String, u32>) -> u32 {
    matrix_shape(ty).map(|(columns, _)| columns).or_else(|| structs.get(ty).copied()).unwrap_or(1)
}

/// The locations each struct type of a stage takes as a varying, from its definition
/// (`struct S { vec3 a; mat2 b[2]; } ;`): its members' locations summed, nested structs
/// counted by their own definitions.
fn struct_locations(sig: &[&Token<'_>]) -> BTreeMap<String, u32> {
    let mut structs = BTreeMap::new();
    let mut i = 0;
    while i + 2 < sig.len() {
        if !(sig[i].is_ident("struct") && sig[i + 1].kind == TokenKind::Ident && sig[i + 2].is_punct("{")) {
            i += 1;
            continue;
        }
        let (total, after) = member_locations(sig, i + 3, &structs);
        structs.insert(sig[i + 1].text.to_string(), total);
        i = after;
    }
    structs
}

/// The locations the members of a struct or block take, from `sig[first]` (after its `{`) to
/// its `}`, with at least one; and the index after the last member.
fn member_locations(sig: &[&Token<'_>], first: usize, structs: &BTreeMap<String, u32>) -> (u32, usize) {
    let mut total = 0u32;
    let mut j = first;
    // One member declaration per `;`: qualifiers, a type, then names with array suffixes.
    while j < sig.len() && !sig[j].is_punct("}") {
        let end = (j..sig.len()).find(|&k| sig[k].is_punct(";") || sig[k].is_punct("}")).unwrap_or(sig.len());
        let member = &sig[j..end];
        // A member's own `layout(…)` (GLSL 4.40) names no type.
        let after_layout = if member.first().is_some_and(|t| t.is_ident("layout")) { member.iter().position(|t| t.is_punct(")")).map_or(0, |c| c + 1) } else { 0 };
        let words: Vec<usize> = (after_layout..member.len()).filter(|&k| member[k].kind == TokenKind::Ident).collect();
        let type_at = words
            .iter()
            .copied()
            .find(|&k| !is_precision(member[k].text) && !matches!(member[k].text, "flat" | "smooth" | "noperspective" | "centroid" | "const" | "varying" | "sample" | "invariant"));
        if let Some(type_at) = type_at {
            let per_value = type_locations(member[type_at].text, structs);
            let mut k = type_at + 1;
            while k < member.len() {
                if member[k].kind == TokenKind::Ident {
                    let mut count = 1u32;
                    while k + 1 < member.len() && member[k + 1].is_punct("[") {
                        let Some(close) = (k + 2..member.len()).find(|&c| member[c].is_punct("]")) else { break };
                        let inner: Vec<&str> = member[k + 2..close].iter().map(|t| t.text).collect();
                        let size = literal_integer_expression(&inner.join(" ")).and_then(|n| u32::try_from(n).ok()).unwrap_or(1);
                        count = count.saturating_mul(size.max(1));
                        k = close;
                    }
                    total = total.saturating_add(per_value.saturating_mul(count));
                }
                k += 1;
            }
        }
        j = if end < sig.len() && sig[end].is_punct(";") { end + 1 } else { end };
    }
    (total.max(1), j)
}

/// The key of an `in`/`out` interface block in a [`VaryingLayout`]: GLSL matches blocks across
/// stages by their block name, and no varying can be named with a space.
fn interface_block_key(block_name: &str) -> String {
    format!("block {block_name}")
}

/// Each `in`/`out` interface block of a stage (`out VertexData { … } v;`) by its
/// [`interface_block_key`], with the locations its members take.
fn interface_block_locations(sig: &[&Token<'_>], structs: &BTreeMap<String, u32>) -> Vec<(String, u32)> {
    (0..sig.len().saturating_sub(2))
        .filter(|&i| matches!(sig[i].text, "in" | "out") && sig[i + 1].kind == TokenKind::Ident && sig[i + 2].is_punct("{"))
        .map(|i| (interface_block_key(sig[i + 1].text), member_locations(sig, i + 3, structs).0))
        .collect()
}

/// A matrix varying, which travels as its columns: the matrix the stage reads and writes is
/// the global `matrix`; its columns are `{columns_in}tp_{member}_{c}` (`columns_in` is a block
/// instance's `name.`, or empty).
struct MatrixVarying {
    matrix: String,
    columns_in: String,
    member: String,
    column_ty: String,
    columns: u32,
}

/// Columns and rows of a float matrix type (`mat3` → 3×3, `mat2x4` → 2 columns of 4).
fn matrix_shape(ty: &str) -> Option<(u32, u32)> {
    let dims = ty.strip_prefix("mat")?;
    let digit = |c: &str| c.parse::<u32>().ok().filter(|n| (2..=4).contains(n));
    match dims.split_once('x') {
        Some((c, r)) => Some((digit(c)?, digit(r)?)),
        None => digit(dims).map(|n| (n, n)),
    }
}

/// `[N]` with N a literal or an expression of literals (`[5 * 5]` from macros): `Some(N)`; any
/// other array suffix: `Some(0)`; none: `None`.
fn array_size(suffix: &str) -> Option<u32> {
    let inner = suffix.trim().strip_prefix('[')?.strip_suffix(']')?;
    Some(literal_integer_expression(inner).and_then(|n| u32::try_from(n).ok()).unwrap_or(0))
}

/// An array suffix (`[A][B]`) in the order naga reads it: naga makes `T x[A][B]` B arrays of
/// `T[A]`, where GLSL means A arrays of `T[B]`, so the sizes go in reverse. Anything but a
/// row of `[…]` is returned as it is.
fn naga_dimensions(suffix: &str) -> String {
    let mut groups = Vec::new();
    let mut depth = 0;
    let mut start = 0;
    for (i, c) in suffix.char_indices() {
        match c {
            '[' => {
                if depth == 0 {
                    start = i;
                }
                depth += 1;
            }
            ']' => {
                depth -= 1;
                if depth == 0 {
                    groups.push(&suffix[start..=i]);
                }
            }
            c if depth == 0 && !c.is_whitespace() => return suffix.to_string(),
            _ => {}
        }
    }
    if depth != 0 {
        return suffix.to_string();
    }
    groups.iter().rev().copied().collect()
}

/// The varyings a stage declares, in declaration order.
pub fn varying_declarations(text: &str, stage: Stage, version: u32) -> Result<Vec<VaryingDecl>, LowerError> {
    let tokens = tokenize(text).map_err(|e| LowerError { line: e.line, message: e.message })?;
    let mut found = Vec::new();
    for stmt in top_level_statements(&tokens) {
        if let Some(decl) = Declaration::parse(&tokens, &stmt)
            && decl.storage(stage, version) == Storage::Varying
        {
            for (name, suffix) in &decl.names {
                found.push(VaryingDecl {
                    name: name.to_string(),
                    ty: decl.ty.to_string(),
                    array: array_size(suffix),
                    interpolation: decl.interpolation(),
                    line: tokens[stmt.sig[0]].line,
                });
            }
        }
    }
    Ok(found)
}

/// The work group size a compute stage declares (`layout(local_size_x = 16, …) in;`), sizes
/// left out 1; None where it declares none, or one that is not a number.
pub fn local_size(tokens: &[Token<'_>]) -> Option<[u32; 3]> {
    let sig: Vec<&Token<'_>> = tokens.iter().filter(|t| !t.is_trivia()).collect();
    let mut size = [1u32; 3];
    let mut declared = false;
    for w in sig.windows(3) {
        let axis = match w[0].text {
            "local_size_x" => 0,
            "local_size_y" => 1,
            "local_size_z" => 2,
            _ => continue,
        };
        if w[1].is_punct("=") {
            size[axis] = w[2].text.trim_end_matches(['u', 'U']).parse().ok()?;
            declared = true;
        }
    }
    declared.then_some(size)
}

/// Names of the varyings a stage declares or uses through legacy built-ins, and the
/// [`interface_block_key`] of each of its `in`/`out` blocks, with the number of locations each
/// takes.
pub fn varyings_of(text: &str, stage: Stage, version: u32) -> Result<Vec<(String, u32)>, LowerError> {
    let tokens = tokenize(text).map_err(|e| LowerError { line: e.line, message: e.message })?;
    let sig: Vec<&Token<'_>> = tokens.iter().filter(|t| !t.is_trivia()).collect();
    let structs = struct_locations(&sig);
    let mut names: Vec<(String, u32)> =
        varying_declarations(text, stage, version)?.iter().map(|d| (d.name.clone(), d.locations(&structs))).collect();
    names.extend(interface_block_locations(&sig, &structs));
    for (i, t) in sig.iter().enumerate() {
        if let Some(reserved) = legacy_varying(t.text, stage) {
            names.push((reserved.to_string(), 1));
        } else if t.text == "gl_TexCoord" {
            let index = constant_index(&sig, i).ok_or_else(|| LowerError {
                line: t.line,
                message: "gl_TexCoord needs a constant index".into(),
            })?;
            names.push((format!("tp_TexCoord{index}"), 1));
        }
    }
    names.sort();
    names.dedup();
    Ok(names)
}

/// The reserved varying a legacy built-in stands for in `stage`, if it is one.
fn legacy_varying(name: &str, stage: Stage) -> Option<&'static str> {
    LEGACY_VARYINGS.iter().find_map(|&(vertex, fragment, reserved, _)| {
        let builtin = if stage == Stage::Vertex { vertex } else { fragment };
        (builtin == name).then_some(reserved)
    })
}

/// `[N]` after `sig[i]` with a literal N.
fn constant_index(sig: &[&Token<'_>], i: usize) -> Option<u32> {
    match (sig.get(i + 1), sig.get(i + 2), sig.get(i + 3)) {
        (Some(o), Some(n), Some(c)) if o.is_punct("[") && n.kind == TokenKind::Number && c.is_punct("]") => {
            n.text.trim_end_matches(['u', 'U']).parse().ok()
        }
        _ => None,
    }
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LowerError {
    /// 1-based line in the preprocessed (and lowered) text.
    pub line: u32,
    pub message: String,
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ResourceKind {
    /// A member of the stage's uniform block, with its GLSL type.
    Uniform { ty: String },
    /// The texture half of a split combined sampler; `binding + 1` holds the sampler.
    Texture { ty: String, comparison: bool, binding: u32 },
}

/// What the lowered stage expects from whoever runs it.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Interface {
    /// Uniforms and textures by their names in the shipped text.
    pub resources: BTreeMap<String, ResourceKind>,
    /// Vertex inputs (shipped names, legacy ones as `gl_*`) and their locations.
    pub inputs: BTreeMap<String, u32>,
    /// Vertex inputs the shipped text places itself (`layout(location = 2) in vec4 normal;`),
    /// at the location it gives.
    pub declared_input_locations: BTreeMap<String, u32>,
    /// Fragment outputs by location: the shipped output name (`gl_FragData[1]`, `outColor1`).
    pub outputs: BTreeMap<u32, String>,
    /// Storage images by their names in the shipped text, with their types (`image2D`).
    pub images: BTreeMap<String, String>,
    /// Uniforms declared with an initializer (`uniform int gamut = 5;`), by name: the
    /// initializer's text, the value until the loader sets one.
    pub uniform_initializers: BTreeMap<String, String>,
}

#[derive(Clone, Debug)]
pub struct Lowered {
    pub text: String,
    pub interface: Interface,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Storage {
    Uniform,
    Attribute,
    Varying,
    FragmentOutput,
    Other,
}

/// A top-level statement: significant-token indices from its first token to its `;` or `{`.
struct Statement {
    sig: Vec<usize>,
}

/// Splits the top level into statements, skipping directive lines and function bodies.
fn top_level_statements(tokens: &[Token<'_>]) -> Vec<Statement> {
    let mut bodies = function_definitions(tokens).into_iter().peekable();
    let mut out = Vec::new();
    let mut current = Vec::new();
    let mut at_line_start = true;
    let mut in_directive = false;
    for (i, t) in tokens.iter().enumerate() {
        if t.kind == TokenKind::Newline {
            at_line_start = true;
            in_directive = false;
            continue;
        }
        if t.is_trivia() {
            continue;
        }
        if at_line_start && t.is_punct("#") {
            in_directive = true;
        }
        at_line_start = false;
        if in_directive {
            continue;
        }
        while bodies.peek().is_some_and(|body| body.close < i) {
            bodies.next();
        }
        let body = bodies.peek();
        if body.is_some_and(|body| body.open < i) {
            continue;
        }
        current.push(i);
        // Struct and interface-block braces stay inside the statement up to its `;`.
        if t.is_punct(";") || body.is_some_and(|body| body.open == i) {
            out.push(Statement { sig: std::mem::take(&mut current) });
        }
    }
    out
}

/// A top-level variable declaration: qualifiers, a type and declarators.
struct Declaration<'a> {
    qualifiers: Vec<&'a str>,
    /// Index (into `tokens`) of `layout`, if present, and of its closing `)`.
    layout: Option<(usize, usize)>,
    ty: &'a str,
    /// Declarator names with the text after the name up to the next `,`/`;` (array sizes).
    names: Vec<(&'a str, String)>,
    /// Per declarator: the token indices of its `=` and of the `,` or `;` that ends it.
    initializers: Vec<Option<(usize, usize)>>,
}

impl<'a> Declaration<'a> {
    fn parse(tokens: &[Token<'a>], stmt: &Statement) -> Option<Declaration<'a>> {
        let sig = &stmt.sig;
        if !tokens[*sig.last()?].is_punct(";") {
            return None;
        }
        let mut qualifiers = Vec::new();
        let mut layout = None;
        let mut k = 0;
        loop {
            let t = &tokens[*sig.get(k)?];
            if t.is_ident("layout") {
                let open = k + 1;
                let close = (open..sig.len()).find(|&j| tokens[sig[j]].is_punct(")"))?;
                layout = Some((sig[k], sig[close]));
                k = close + 1;
            } else if matches!(t.text, "attribute" | "varying" | "uniform" | "in" | "out" | "const" | "shared")
                || is_memory_qualifier(t.text)
                || is_varying_qualifier(t.text)
                || is_precision(t.text)
            {
                qualifiers.push(t.text);
                k += 1;
            } else {
                break;
            }
        }
        let ty = &tokens[*sig.get(k)?];
        if ty.kind != TokenKind::Ident || ty.text == "struct" || tokens[*sig.get(k + 1)?].is_punct("{") {
            return None;
        }
        // Function prototypes are not declarations of variables.
        if sig.iter().any(|&j| tokens[j].is_punct("(")) && !qualifiers.contains(&"const") {
            let first_paren = sig.iter().position(|&j| tokens[j].is_punct("("))?;
            if first_paren == k + 2 {
                return None;
            }
        }
        // `vec3[9] x` declares what `vec3 x[9]` does: the size moves to each declarator, after
        // its own (`vec3[2] x[3]` is `vec3 x[3][2]`).
        let mut type_suffix = String::new();
        let mut j = k + 1;
        if tokens[*sig.get(j)?].is_punct("[") {
            let close = (j..sig.len()).find(|&m| tokens[sig[m]].is_punct("]"))?;
            type_suffix = sig[j..=close].iter().map(|&m| tokens[m].text).collect();
            j = close + 1;
            if sig.get(j + 1).is_some_and(|&m| tokens[m].is_punct("(")) {
                // `vec3[2] f(…);`: a prototype of a function returning an array.
                return None;
            }
        }
        let mut names = Vec::new();
        let mut initializers = Vec::new();
        while j < sig.len() {
            let name = &tokens[sig[j]];
            if name.kind != TokenKind::Ident {
                // Forms the lowering leaves alone.
                return None;
            }
            let mut suffix = String::new();
            let mut depth = 0;
            let mut equals = None;
            let mut end = None;
            j += 1;
            while j < sig.len() {
                let t = &tokens[sig[j]];
                if depth == 0 && (t.is_punct(",") || t.is_punct(";")) {
                    end = Some(sig[j]);
                    j += 1;
                    break;
                }
                if t.is_punct("=") && depth == 0 && equals.is_none() {
                    equals = Some(sig[j]);
                }
                if t.is_punct("(") || t.is_punct("[") || t.is_punct("{") {
                    depth += 1;
                } else if t.is_punct(")") || t.is_punct("]") || t.is_punct("}") {
                    depth -= 1;
                }
                if equals.is_none() {
                    suffix.push_str(t.text);
                }
                j += 1;
            }
            suffix.push_str(&type_suffix);
            names.push((name.text, suffix));
            initializers.push(equals.zip(end));
        }
        Some(Declaration { qualifiers, layout, ty: ty.text, names, initializers })
    }

    fn storage(&self, stage: Stage, version: u32) -> Storage {
        let has = |q: &str| self.qualifiers.contains(&q);
        if has("uniform") {
            Storage::Uniform
        } else if has("attribute") || (has("in") && stage == Stage::Vertex) {
            Storage::Attribute
        } else if has("varying") || (has("out") && stage == Stage::Vertex) || (has("in") && stage == Stage::Fragment)
        {
            Storage::Varying
        } else if has("out") && stage == Stage::Fragment && version >= 130 {
            Storage::FragmentOutput
        } else {
            Storage::Other
        }
    }

    /// Interpolation qualifiers to keep (`flat`, `centroid`, …).
    fn interpolation(&self) -> String {
        self.qualifiers.iter().filter(|q| is_varying_qualifier(q)).map(|q| format!("{q} ")).collect()
    }

    /// `N` of an explicit `layout(key = N)` (`location`, `component`).
    fn layout_value(&self, tokens: &[Token<'_>], key: &str) -> Option<u32> {
        let (start, end) = self.layout?;
        let sig: Vec<&Token<'_>> = tokens[start..=end].iter().filter(|t| !t.is_trivia()).collect();
        sig.windows(3)
            .find(|w| w[0].is_ident(key) && w[1].is_punct("="))
            .and_then(|w| w[2].text.parse().ok())
    }
}

/// Which global names are samplers, and what functions take samplers where.
#[derive(Default)]
struct Symbols {
    /// Shipped sampler name → (lowered texture name, combined type).
    samplers: HashMap<String, (String, String)>,
    /// Function name → for each parameter position, whether an overload takes a sampler there.
    sampler_functions: HashMap<String, Vec<bool>>,
    /// `uniform bool` names; they live in the block as `int tp_bool_<name>`.
    bool_uniforms: HashSet<String>,
}

/// Lowers one preprocessed stage; a `lenient` one ([`crate::preprocess::Preprocessed::lenient`])
/// as NVIDIA reads what GLSL refuses (a bias in a vertex stage's lookup is its level).
pub fn lower(text: &str, stage: Stage, varyings: &VaryingLayout, lenient: bool) -> Result<Lowered, LowerError> {
    lower_any(text, stage, false, varyings, lenient)
}

/// Lowers one preprocessed compute stage (`.csh`): uniforms into a block, samplers split,
/// images given bindings, everything else as written (compute stages have no varyings).
pub fn lower_compute(text: &str) -> Result<Lowered, LowerError> {
    lower_any(text, Stage::Vertex, true, &VaryingLayout::default(), false)
}

fn lower_any(text: &str, stage: Stage, compute: bool, varyings: &VaryingLayout, lenient: bool) -> Result<Lowered, LowerError> {
    let tokens = tokenize(text).map_err(|e| LowerError { line: e.line, message: e.message })?;
    let mut blanked = without_unchecked_qualifiers(text, &tokens);
    // Blanking keeps every byte where it was, so that edits, by the tokens' offsets, apply after.
    let significant: Vec<usize> = (0..tokens.len()).filter(|&i| !tokens[i].is_trivia()).collect();
    let sig: Vec<&Token> = significant.iter().map(|&i| &tokens[i]).collect();
    let mut edits: Vec<(std::ops::Range<usize>, String)> = Vec::new();
    if lenient {
        let mut names: Vec<std::ops::Range<usize>> =
            crate::compat::functions_named_as_statements(&sig).into_iter().map(|k| sig[k].offset..sig[k].offset + sig[k].text.len()).collect();
        // A function returning a sampler, which NVIDIA takes, goes; its calls read the sampler.
        let sampler_functions = crate::compat::functions_returning_samplers(&sig);
        names.extend(sampler_functions.iter().map(|f| sig[f.start].offset..sig[f.close].offset + 1));
        if !names.is_empty() {
            blanked = Some(crate::token::blanked(blanked.as_deref().unwrap_or(text), &names));
        }
        for k in 0..sig.len().saturating_sub(2) {
            let Some(f) = sampler_functions.iter().find(|f| sig[k].is_ident(f.name) && !(f.start..=f.close).contains(&k)) else { continue };
            if sig[k + 1].is_punct("(") && sig[k + 2].is_punct(")") {
                edits.push((sig[k].offset..sig[k + 2].offset + 1, f.returned.to_string()));
            }
        }
        // Default values of parameters, which NVIDIA takes, written out in the calls.
        let (defaults, _) = crate::compat::default_arguments_spelled_out(&tokens, &significant);
        edits.extend(defaults.into_iter().map(|(i, with)| (tokens[i].offset..tokens[i].offset + tokens[i].text.len(), with)));
    }
    edits.extend(struct_names_hidden_by_variables(&sig));
    // A local declaration of several arrays (`vec3 normals[6], points[6];`), each declarator
    // its own declaration: naga's front end sizes the first alone.
    edits.extend(local_array_declarators_split(&sig));
    // A local `const int` in an array size or an index (`float lights[n * n];`) becomes its
    // value's expression: naga's front end reads sizes where locals are not in scope.
    edits.extend(local_constants_in_brackets(text, &sig));
    // `gl_FragDepth` read and never written keeps the depth the fragment was rasterised at:
    // naga would make it the depth output, unset.
    if stage == Stage::Fragment && !compute {
        edits.extend(crate::token::depth_read_never_written(&sig).into_iter().map(|k| (sig[k].offset..sig[k].offset + sig[k].text.len(), "gl_FragCoord.z".to_string())));
    }
    if !edits.is_empty() {
        blanked = Some(crate::token::edited(blanked.as_deref().unwrap_or(text), edits));
    }
    let tokens = match &blanked {
        Some(blanked) => tokenize(blanked).map_err(|e| LowerError { line: e.line, message: e.message })?,
        None => tokens,
    };
    let mut lowering = Lowering {
        tokens: &tokens,
        stage,
        compute,
        lenient,
        version: 0,
        replacements: BTreeMap::new(),
        header: String::new(),
        block: Vec::new(),
        symbols: Symbols::default(),
        interface: Interface::default(),
        next_binding: 1,
        interface_blocks: 0,
        varyings,
        prelude: String::new(),
        matrix_varyings: Vec::new(),
        global_initializers: Vec::new(),
        unconst: HashSet::new(),
    };
    lowering.run()?;
    Ok(Lowered { text: lowering.render(), interface: lowering.interface })
}

/// Edits giving a struct type that a variable of the same name hides its own name (`struct
/// maskData {…} mask;` beside a local `float maskData`, rre36/glsl_rshader): GLSL lets the
/// variable hide the type in its scope, naga's front end reads the name as the type
/// everywhere. The type's uses (after `struct`, before a declared name or `[`, before `(` of a
/// constructor) become `tp_struct_NAME`; the variable's stay.
fn struct_names_hidden_by_variables(sig: &[&Token]) -> Vec<(std::ops::Range<usize>, String)> {
    let structs: BTreeSet<&str> = sig.windows(2).filter(|w| w[0].is_ident("struct") && w[1].kind == TokenKind::Ident).map(|w| w[1].text).collect();
    let declares_variable = |k: usize, name: &str| {
        k > 0
            && sig[k].is_ident(name)
            && (is_builtin_type(sig[k - 1].text) || structs.contains(sig[k - 1].text))
            && sig.get(k + 1).is_some_and(|t| t.is_punct("=") || t.is_punct(";") || t.is_punct(","))
    };
    let mut edits = Vec::new();
    for name in structs.iter().filter(|name| (0..sig.len()).any(|k| declares_variable(k, name))) {
        for k in (0..sig.len()).filter(|&k| sig[k].is_ident(name)) {
            let next = sig.get(k + 1);
            let type_use = (k > 0 && sig[k - 1].is_ident("struct"))
                || next.is_some_and(|t| t.kind == TokenKind::Ident || t.is_punct("(") || t.is_punct("["));
            if type_use && !declares_variable(k, name) {
                edits.push((sig[k].offset..sig[k].offset + sig[k].text.len(), format!("{RESERVED_PREFIX}struct_{name}")));
            }
        }
    }
    edits
}

/// Edits splitting each local declaration without initializers whose later declarators are
/// arrays (`vec3 normals[6], points[6];`) into one declaration per declarator on the same line
/// (`vec3 normals[6]; vec3 points[6];`): each `,` becomes `; TYPE`.
fn local_array_declarators_split(sig: &[&Token]) -> Vec<(std::ops::Range<usize>, String)> {
    let mut edits = Vec::new();
    let mut depth = 0u32;
    for k in 0..sig.len() {
        match sig[k].text {
            "{" => depth += 1,
            "}" => depth = depth.saturating_sub(1),
            _ => {}
        }
        let statement_start = k > 0 && sig[k - 1].ends_statement();
        let declares = sig[k].kind == TokenKind::Ident
            && !is_statement_keyword(sig[k].text)
            && !sig[k].is_ident("const")
            && sig.get(k + 1).is_some_and(|n| n.kind == TokenKind::Ident);
        if depth == 0 || !statement_start || !declares {
            continue;
        }
        let Some(end) = (k..sig.len()).find(|&j| sig[j].ends_statement()) else { continue };
        let statement = &sig[k..end];
        if !sig[end].is_punct(";") || statement.iter().any(|t| t.is_punct("=") || t.is_punct("(")) {
            continue;
        }
        let commas: Vec<usize> = (k..end).filter(|&j| sig[j].is_punct(",")).collect();
        if commas.is_empty() || !commas.iter().any(|&c| sig.get(c + 2).is_some_and(|t| t.is_punct("["))) {
            continue;
        }
        for c in commas {
            edits.push((sig[c].offset..sig[c].offset + 1, format!("; {}", sig[k].text)));
        }
    }
    edits
}

/// A block that returns an uninitialised value of the type named `type_name`: where control
/// never gets, or where a function is known to pass, it gives naga the `return` of a value of
/// any type (a struct has no constructor from one number).
pub(crate) fn undefined_return(type_name: &str) -> String {
    format!("{{ {type_name} tp_undefined; return tp_undefined; }}")
}

/// Longest initializer [`local_constants_in_brackets`] writes in place of a constant's name.
const MAX_INLINED_CONSTANT_BYTES: usize = 1024;

/// Edits replacing, inside `[` `]`, each name of a local `const int` or `const uint` declared
/// earlier in the same function (`const int n = int(4.0 + 0.001);`) by its type and initializer
/// (`int(int(4.0 + 0.001))`), where that initializer holds no line break; the initializers of
/// such constants are read with the earlier ones already replaced.
fn local_constants_in_brackets(text: &str, sig: &[&Token]) -> Vec<(std::ops::Range<usize>, String)> {
    let mut edits = Vec::new();
    let mut constants: HashMap<&str, String> = HashMap::new();
    let (mut depth, mut brackets) = (0u32, 0u32);
    for k in 0..sig.len() {
        match sig[k].text {
            "{" => depth += 1,
            "}" => {
                depth = depth.saturating_sub(1);
                if depth == 0 {
                    constants.clear();
                }
            }
            "[" => brackets += 1,
            "]" => brackets = brackets.saturating_sub(1),
            _ => {}
        }
        if depth > 0
            && sig[k].is_ident("const")
            && let (Some(ty), Some(name), Some(equals)) = (sig.get(k + 1), sig.get(k + 2), sig.get(k + 3))
            && matches!(ty.text, "int" | "uint")
            && name.kind == TokenKind::Ident
            && equals.is_punct("=")
            && let Some(end) = (k + 4..sig.len()).find(|&j| sig[j].is_punct(";") || sig[j].is_punct(","))
            && sig[end].is_punct(";")
            && end > k + 4
        {
            let mut value = String::new();
            for t in &sig[k + 4..end] {
                value.push_str(constants.get(t.text).filter(|_| t.kind == TokenKind::Ident).map_or(t.text, String::as_str));
                value.push(' ');
            }
            let initializer = &text[sig[k + 4].offset..sig[end].offset];
            // A chain of constants each read twice in the next doubles at every step.
            if !initializer.contains('\n') && value.len() <= MAX_INLINED_CONSTANT_BYTES {
                constants.insert(name.text, format!("{}({})", ty.text, value.trim_end()));
            }
        }
        if brackets > 0
            && sig[k].kind == TokenKind::Ident
            && !(k > 0 && sig[k - 1].is_punct("."))
            && let Some(value) = constants.get(sig[k].text)
        {
            edits.push((sig[k].offset..sig[k].offset + sig[k].text.len(), value.clone()));
        }
    }
    edits
}

/// `text` with the qualifiers that change no type blanked out, every line and column kept;
/// `None` without any:
/// - precision qualifiers (`lowp vec2 coord`) and default precision statements (`precision
///   mediump float;`): they change nothing on desktop GLSL, and naga takes a qualifier on a
///   global declaration alone;
/// - `coherent`, `volatile` and `restrict`, which order memory accesses (naga: "Not implemented:
///   variable qualifier" on a buffer block).
fn without_unchecked_qualifiers(text: &str, tokens: &[Token]) -> Option<String> {
    let span = |(first, last): (usize, usize)| tokens[first].offset..tokens[last].offset + tokens[last].text.len();
    let memory = (0..tokens.len()).filter(|&i| matches!(tokens[i].text, "coherent" | "volatile" | "restrict") && tokens[i].kind == TokenKind::Ident);
    let spans: Vec<std::ops::Range<usize>> =
        crate::token::precision_qualifiers(tokens).into_iter().chain(memory.map(|i| (i, i))).map(span).collect();
    if spans.is_empty() {
        return None;
    }
    Some(crate::token::blanked(text, &spans))
}

struct Lowering<'t, 'a> {
    tokens: &'t [Token<'a>],
    /// Meaningless when `compute`.
    stage: Stage,
    /// A compute stage: no varyings, outputs or legacy built-ins.
    compute: bool,
    /// Read as NVIDIA reads it (see [`lower`]).
    lenient: bool,
    version: u32,
    /// Token index → (end index exclusive, replacement text).
    replacements: BTreeMap<usize, (usize, String)>,
    /// Declarations added to the `#version` line.
    header: String,
    /// Members of the uniform block.
    block: Vec<String>,
    symbols: Symbols,
    interface: Interface,
    next_binding: u32,
    /// `in`/`out` interface blocks lowered so far (each gets a location of its own).
    interface_blocks: u32,
    varyings: &'t VaryingLayout,
    /// Type definitions the uniform block needs, put before it.
    prelude: String,
    /// Matrix varyings, passed as column vectors.
    matrix_varyings: Vec<MatrixVarying>,
    /// Globals whose initializer runs at the start of `main` (`tp_init_<name>()`), in
    /// declaration order.
    global_initializers: Vec<String>,
    /// `const` declarations that become plain variables: naga evaluates both branches of a
    /// constant `?:` and fails on the one not taken, and cannot fold some built-ins; drivers
    /// do both.
    unconst: HashSet<String>,
}

impl<'a> Lowering<'_, 'a> {
    fn descriptor_set(&self) -> u32 {
        if self.compute { COMPUTE_DESCRIPTOR_SET } else { self.stage.descriptor_set() }
    }

    /// A lookup with a bias (token `i`) in a stage with no implicit level.
    fn bias_outside_fragment(&self, i: usize) -> LowerError {
        self.err(
            i,
            format!(
                "{name}() takes a bias only in fragment shaders; this {stage} stage has no level to bias (Mesa: \"no matching \
                 function for call to `{name}'\"): read a level with {name}Lod(…, 0.0)",
                name = self.tokens[i].text,
                stage = if self.compute { "compute" } else { "vertex" }
            ),
        )
    }

    /// The number of arguments of the call whose `(` is `sig[open]`.
    fn call_arguments(&self, sig: &[usize], open: usize) -> usize {
        argument_count(sig, self.tokens, open)
    }

    fn err(&self, index: usize, message: impl Into<String>) -> LowerError {
        LowerError { line: self.tokens[index].line, message: message.into() }
    }

    /// Replaces tokens `start..end` with `text`, keeping the line breaks they spanned that
    /// `text` does not hold (at its end), so that a construct written over several lines
    /// (`vec3[\n]`, a declaration) still covers as many lines.
    fn replace(&mut self, start: usize, end: usize, mut text: String) {
        let breaks = (start..end.min(self.tokens.len())).map(|i| self.tokens[i].newlines() as usize).sum::<usize>();
        let held = text.matches('\n').count();
        text.extend(std::iter::repeat_n('\n', breaks.saturating_sub(held)));
        self.replacements.insert(start, (end, text));
    }

    fn run(&mut self) -> Result<(), LowerError> {
        let version_index = self.find_version()?;
        self.lower_initializer_lists();
        self.lower_array_constructor_sizes();
        self.reverse_array_dimensions();
        self.inline_local_constant_sizes();
        self.drop_const_naga_cannot_fold();
        self.convert_bool_vector_constructors();
        let statements = top_level_statements(self.tokens);
        for (name, _) in GATHER_STAND_INS {
            // The stand-ins take the sampler's two halves, like the pack's own functions.
            self.symbols.sampler_functions.insert(name.to_string(), vec![true, false, false, false, false]);
        }
        for stmt in &statements {
            self.collect_function_signature(stmt);
        }
        let mut attribute_count = 0;
        let mut output_order = 0;
        let legacy_outputs_written =
            self.stage == Stage::Fragment && self.tokens.iter().any(|t| t.is_ident("gl_FragColor") || t.is_ident("gl_FragData"));
        // Locations into which outputs are packed by `component`.
        let mut packed_outputs: HashSet<u32> = HashSet::new();
        // Function headers seen so far, as token text.
        let mut seen_headers: HashSet<String> = HashSet::new();
        for stmt in &statements {
            if let [only] = stmt.sig[..]
                && self.tokens[only].is_punct(";")
            {
                // An empty declaration after a function body: drivers accept it, naga does not.
                self.replace(only, only + 1, String::new());
                continue;
            }
            self.move_bound_block(stmt);
            let Some(decl) = Declaration::parse(self.tokens, stmt) else {
                if self.lower_interface_block(stmt)? {
                    continue;
                }
                // GLSL allows a function to be declared again; naga refuses a second prototype.
                let signature: Vec<&str> = stmt.sig.iter().map(|&i| self.tokens[i].text).collect();
                let header = &signature[..signature.len() - 1];
                let is_prototype = signature.last() == Some(&";") && header.contains(&"(");
                if is_prototype && !seen_headers.insert(header.join(" ")) {
                    let (start, end) = (stmt.sig[0], *stmt.sig.last().unwrap() + 1);
                    self.replace(start, end, String::new());
                    continue;
                }
                if signature.last() == Some(&"{") {
                    seen_headers.insert(header.join(" "));
                }
                self.lower_function_header(stmt);
                continue;
            };
            let start = stmt.sig[0];
            let end = *stmt.sig.last().unwrap() + 1;
            let storage = match decl.storage(self.stage, self.version) {
                Storage::Uniform => Storage::Uniform,
                _ if self.compute => Storage::Other,
                other => other,
            };
            // `out float gl_FragDepth;` (or with a conservative-depth layout) redeclares a
            // built-in; naga has it already, and it is no stage input or output of the pack's.
            let redeclares_builtin = decl.names.iter().all(|(name, _)| name.starts_with("gl_"));
            if redeclares_builtin && matches!(storage, Storage::Attribute | Storage::Varying | Storage::FragmentOutput) {
                self.replace(start, end, String::new());
                continue;
            }
            match storage {
                Storage::Uniform => self.lower_uniform(&decl, start, end)?,
                Storage::Attribute => {
                    let mut text = String::new();
                    let declared = decl.layout_value(self.tokens, "location");
                    for (name, suffix) in &decl.names {
                        let location = FIRST_ATTRIBUTE_LOCATION + attribute_count;
                        attribute_count += 1;
                        self.interface.inputs.insert(name.to_string(), location);
                        if let Some(declared) = declared {
                            self.interface.declared_input_locations.insert(name.to_string(), declared);
                        }
                        write!(text, "layout(location = {location}) in {} {name}{}; ", decl.ty, naga_dimensions(suffix)).unwrap();
                    }
                    self.replace(start, end, text.trim_end().to_string());
                }
                Storage::Varying => {
                    let direction = if self.stage == Stage::Vertex { "out" } else { "in" };
                    let mut text = String::new();
                    for (name, suffix) in &decl.names {
                        if self.stage == Stage::Fragment && !decl.qualifiers.contains(&"flat") {
                            self.integer_input_must_be_flat(start, decl.ty, name)?;
                        }
                        let location = self.varyings.locations.get(*name).copied().ok_or_else(|| {
                            self.err(start, format!("varying `{name}` is missing from the program's varying layout"))
                        })?;
                        if let Some((columns, rows)) = matrix_shape(decl.ty) {
                            // naga takes no matrices as stage inputs or outputs: pass the columns.
                            if !suffix.is_empty() {
                                return Err(self.err(start, format!("arrays of matrices as varyings (`{name}{suffix}`) are not supported")));
                            }
                            let column_ty = format!("vec{rows}");
                            write!(text, "{} {name}; ", decl.ty).unwrap();
                            for c in 0..columns {
                                write!(
                                    text,
                                    "layout(location = {}) {}{direction} {column_ty} {RESERVED_PREFIX}{name}_{c}; ",
                                    location.saturating_add(c),
                                    decl.interpolation()
                                )
                                .unwrap();
                            }
                            self.matrix_varyings.push(MatrixVarying {
                                matrix: name.to_string(),
                                columns_in: String::new(),
                                member: name.to_string(),
                                column_ty,
                                columns,
                            });
                            continue;
                        }
                        // An integer vertex output need not be `flat` from GLSL 1.50 on (the
                        // fragment input says so, and drivers match it); naga wants it on both.
                        let flat = if self.stage == Stage::Vertex && is_integer_type(decl.ty) && !decl.qualifiers.contains(&"flat") {
                            "flat "
                        } else {
                            ""
                        };
                        write!(
                            text,
                            "layout(location = {location}) {flat}{}{direction} {} {name}{}; ",
                            decl.interpolation(),
                            decl.ty,
                            naga_dimensions(suffix)
                        )
                        .unwrap();
                    }
                    self.replace(start, end, text.trim_end().to_string());
                }
                Storage::FragmentOutput => {
                    let mut text = String::new();
                    for (name, suffix) in &decl.names {
                        if legacy_outputs_written && self.tokens.iter().filter(|t| t.is_ident(name)).count() == 1 {
                            // Declared beside gl_FragColor/gl_FragData and never written: drivers
                            // link it to nothing, where naga would see two outputs at one location.
                            continue;
                        }
                        let location = name
                            .strip_prefix("outColor")
                            .and_then(|n| n.parse().ok())
                            .or_else(|| decl.layout_value(self.tokens, "location"))
                            .unwrap_or(output_order);
                        output_order += 1;
                        // Outputs packed into one location by `component` (GLSL 4.40) share it;
                        // naga has no components, so each packed output gets a location of its
                        // own above the render targets.
                        let component = decl.layout_value(self.tokens, "component").unwrap_or(0);
                        let lowered_location = if component > 0 {
                            PACKED_OUTPUT_LOCATION.saturating_add(location.saturating_mul(4)).saturating_add(component)
                        } else {
                            location
                        };
                        match self.interface.outputs.get(&location) {
                            Some(previous) if component == 0 && !packed_outputs.contains(&location) => {
                                return Err(self.err(start, format!("`{name}` and `{previous}` both write output {location}")));
                            }
                            Some(_) => {}
                            None => {
                                self.interface.outputs.insert(location, name.to_string());
                            }
                        }
                        if component > 0 {
                            packed_outputs.insert(location);
                        }
                        write!(text, "layout(location = {lowered_location}) out {} {name}{}; ", decl.ty, naga_dimensions(suffix)).unwrap();
                    }
                    self.replace(start, end, text.trim_end().to_string());
                }
                Storage::Other => self.move_initializers_into_main(&decl),
            }
        }
        self.rewrite_bodies()?;
        self.finish_header(version_index);
        Ok(())
    }

    /// An `in` or `out` interface block (`out Data { flat int id; vec2 uv; } v;`): naga's parser
    /// reads no qualifiers on block members, so they are blanked (columns kept). In a fragment
    /// stage an integer member must be `flat`. Returns whether
    /// `stmt` is such a block.
    fn lower_interface_block(&mut self, stmt: &Statement) -> Result<bool, LowerError> {
        let sig = &stmt.sig;
        let Some(open) = sig.iter().position(|&i| self.tokens[i].is_punct("{")) else { return Ok(false) };
        let head: Vec<&str> = sig[..open].iter().map(|&i| self.tokens[i].text).collect();
        let Some(direction) = head.iter().position(|w| matches!(*w, "in" | "out")) else { return Ok(false) };
        // `in`/`out`, then the block name right before `{`, with only qualifiers or a layout
        // before the direction.
        if open < 1 || direction + 2 != open || self.tokens[sig[open - 1]].kind != TokenKind::Ident {
            return Ok(false);
        }
        if let Some(q) = (0..direction).find(|&q| is_varying_qualifier(head[q])) {
            return Err(self.err(
                sig[q],
                format!("`{}` cannot qualify a block, only its members (Mesa refuses it as a syntax error)", head[q]),
            ));
        }
        if !head.contains(&"layout") {
            let laid_out = self.varyings.locations.get(&interface_block_key(head[open - 1])).copied();
            let location = laid_out.unwrap_or_else(|| INTERFACE_BLOCK_LOCATION.saturating_add(self.interface_blocks.saturating_mul(INTERFACE_BLOCK_STRIDE)));
            self.interface_blocks += 1;
            let at = sig[direction];
            self.replace(at, at + 1, format!("layout(location = {location}) {}", head[direction]));
        }
        let fragment_input = self.stage == Stage::Fragment && head[direction] == "in" && !self.compute;
        let block_name = head[open - 1];
        // The statement ends at the first member's `;`: read the members from the tokens.
        let sig: Vec<usize> = (sig[open]..self.tokens.len()).filter(|&i| !self.tokens[i].is_trivia()).collect();
        let open = 0;
        let mut member_start = open + 1;
        let mut k = open + 1;
        while k < sig.len() && !self.tokens[sig[k]].is_punct("}") {
            let t = self.tokens[sig[k]];
            if t.is_punct(";") {
                member_start = k + 1;
            } else if k == member_start
                && t.is_ident("layout")
                && let Some(close) = sig.get(k + 1).filter(|&&i| self.tokens[i].is_punct("(")).and_then(|_| matching_close(&sig, self.tokens, k + 1))
            {
                // A member's own layout (`layout(location = 1) vec2 uv;`, GLSL 4.40): naga
                // reads none, and places the members one after another from the block's.
                let width = self.tokens[sig[k]..=sig[close]].iter().map(|t| t.text.len()).sum::<usize>();
                self.replace(sig[k], sig[close] + 1, " ".repeat(width));
                member_start = close + 1;
                k = close;
            } else if k >= member_start && (is_varying_qualifier(t.text) || is_precision(t.text) || t.text == "sample") {
                // Qualifiers lead the member; the first other word is its type.
                if (member_start..k).all(|j| {
                    let w = self.tokens[sig[j]].text;
                    is_varying_qualifier(w) || is_precision(w) || w == "sample"
                }) {
                    self.replace(sig[k], sig[k] + 1, " ".repeat(t.text.len()));
                }
            } else if fragment_input && t.kind == TokenKind::Ident {
                let qualifiers = &sig[member_start..k];
                let is_type = qualifiers.iter().all(|&j| {
                    let w = self.tokens[j].text;
                    is_varying_qualifier(w) || is_precision(w) || w == "sample"
                });
                if is_type && !qualifiers.iter().any(|&j| self.tokens[j].text == "flat") {
                    let member = sig.get(k + 1).map_or("", |&j| self.tokens[j].text);
                    self.integer_input_must_be_flat(sig[k], t.text, &format!("{block_name}.{member}"))?;
                }
            }
            k += 1;
        }
        // naga takes no matrices as stage inputs or outputs, in a block or not: a matrix member
        // passes its columns, and the matrix becomes a global the `main` wrapper fills from them
        // (vertex: the columns from it), as for a plain matrix varying. Without an instance name
        // (`out Data { flat mat3 tbn; };`) the global has the member's name; with one
        // (`out Data { mat4 mv; } v;`) it is `tp_v_mv`, and every `v.mv` reads it.
        let unnamed = sig.get(k + 1).is_some_and(|&i| self.tokens[i].is_punct(";"));
        let instance = (!unnamed && sig.get(k + 2).is_some_and(|&i| self.tokens[i].is_punct(";")))
            .then(|| sig.get(k + 1).map(|&i| self.tokens[i]))
            .flatten()
            .filter(|t| t.kind == TokenKind::Ident);
        if (unnamed || instance.is_some()) && !self.compute {
            let mut matrices = String::new();
            let mut start = open + 1;
            for end in (open + 1..k).filter(|&j| self.tokens[sig[j]].is_punct(";")) {
                let words: Vec<usize> = (start..end)
                    .filter(|&j| {
                        let w = self.tokens[sig[j]].text;
                        !(is_varying_qualifier(w) || is_precision(w) || w == "sample")
                    })
                    .collect();
                start = end + 1;
                let [ty, name] = words[..] else { continue };
                let (ty, name) = (self.tokens[sig[ty]].text, (sig[ty], sig[name]));
                let member = self.tokens[name.1];
                let Some((columns, rows)) = matrix_shape(ty) else { continue };
                if member.kind != TokenKind::Ident {
                    continue;
                }
                let column_ty = format!("vec{rows}");
                let cols: Vec<String> = (0..columns).map(|c| format!("{column_ty} {RESERVED_PREFIX}{}_{c}", member.text)).collect();
                self.replace(name.0, name.1 + 1, cols.join("; "));
                let (matrix, columns_in) = match instance {
                    Some(instance) => {
                        let matrix = format!("{RESERVED_PREFIX}{}_{}", instance.text, member.text);
                        self.rename_member_uses(sig[k + 2], instance.text, member.text, &matrix);
                        (matrix, format!("{}.", instance.text))
                    }
                    None => (member.text.to_string(), String::new()),
                };
                write!(matrices, " {ty} {matrix};").unwrap();
                self.matrix_varyings.push(MatrixVarying { matrix, columns_in, member: member.text.to_string(), column_ty, columns });
            }
            if !matrices.is_empty() {
                let semicolon = sig[if unnamed { k + 1 } else { k + 2 }];
                self.replace(semicolon, semicolon + 1, format!(";{matrices}"));
            }
        }
        Ok(true)
    }

    /// Every `instance.member` after token `after` becomes `global`.
    fn rename_member_uses(&mut self, after: usize, instance: &str, member: &str, global: &str) {
        let sig: Vec<usize> = (after + 1..self.tokens.len()).filter(|&i| !self.tokens[i].is_trivia()).collect();
        for w in sig.windows(3) {
            let [a, dot, m] = [w[0], w[1], w[2]];
            if self.tokens[a].is_ident(instance) && self.tokens[dot].is_punct(".") && self.tokens[m].is_ident(member) {
                self.replace(a, m + 1, global.to_string());
            }
        }
    }

    /// A buffer or uniform block with an explicit `binding` in a vertex or fragment stage goes
    /// to a set of its own ([`PACK_BUFFER_SET`]): in the stage's set it would collide with the
    /// lowered uniforms and samplers. Compute stages keep it in set 0 (theirs is set 2).
    fn move_bound_block(&mut self, stmt: &Statement) {
        let sig = &stmt.sig;
        let words: Vec<&str> = sig.iter().map(|&i| self.tokens[i].text).collect();
        if self.compute || words.first() != Some(&"layout") || !words.contains(&"{") {
            return;
        }
        let Some(close) = words.iter().position(|w| *w == ")") else { return };
        let layout = &words[..close];
        if !layout.contains(&"binding") || layout.contains(&"set") {
            return;
        }
        let set = match words[close..].iter().find(|w| matches!(**w, "buffer" | "uniform")) {
            Some(&"buffer") => PACK_BUFFER_SET,
            Some(_) => PACK_BUFFER_SET + 1,
            None => return,
        };
        self.replace(sig[close], sig[close] + 1, format!(", set = {set})"));
    }

    /// GLSL 1.30 §4.3.4: fragment inputs of an integer type must be `flat` (Mesa and glslang
    /// refuse the stage); naga would make them flat by itself.
    fn integer_input_must_be_flat(&self, at: usize, ty: &str, name: &str) -> Result<(), LowerError> {
        if is_integer_type(ty) && self.version >= 130 {
            return Err(self.err(
                at,
                format!("fragment input `{name}` is an integer ({ty}) and must be qualified `flat` (GLSL 1.30 §4.3.4; drivers refuse the shader)"),
            ));
        }
        Ok(())
    }

    fn find_version(&mut self) -> Result<usize, LowerError> {
        let sig: Vec<usize> = (0..self.tokens.len()).filter(|&i| !self.tokens[i].is_trivia()).take(3).collect();
        match sig.as_slice() {
            [hash, word, number, ..]
                if self.tokens[*hash].is_punct("#") && self.tokens[*word].is_ident("version") =>
            {
                self.version = self.tokens[*number]
                    .text
                    .parse()
                    .map_err(|_| self.err(*number, "#version needs a number"))?;
                Ok(*hash)
            }
            _ => Err(LowerError { line: 1, message: "a shader must start with #version".into() }),
        }
    }

    /// Global variables with initializers: drivers run the initializers at the start of
    /// `main`, naga wants constant expressions there. Each initializer moves into a function
    /// `tp_init_<name>()` on its own line (so errors in it keep their line), and the `main`
    /// wrapper assigns the globals in declaration order.
    fn move_initializers_into_main(&mut self, decl: &Declaration<'a>) {
        let is_const = decl.qualifiers.contains(&"const") && !decl.names.iter().any(|(n, _)| self.unconst.contains(*n));
        if is_const || decl.qualifiers.contains(&"shared") {
            return;
        }
        let qualifiers: String = decl.qualifiers.iter().filter(|q| **q != "const").map(|q| format!("{q} ")).collect();
        for ((name, suffix), initializer) in decl.names.iter().zip(&decl.initializers) {
            let Some((equals, end)) = *initializer else { continue };
            if suffix.contains("[]") || self.is_literal_expression(equals + 1, end) {
                continue;
            }
            let after = if self.tokens[end].is_punct(",") { format!(" {qualifiers}{}", decl.ty) } else { String::new() };
            self.replace(equals, equals + 1, format!("; {}{} {RESERVED_PREFIX}init_{name}() {{ return ", decl.ty, naga_dimensions(suffix)));
            self.replace(end, end + 1, format!("; }}{after}"));
            self.global_initializers.push(name.to_string());
        }
    }

    /// Whether the tokens in `start..end` are built of literals, operators and GLSL's own type
    /// constructors only (`vec3(0.5, 1.0, 0.0) * 2.0`): an initializer naga takes as written.
    /// Moving every initializer into a function of its own would cost naga one copy of every
    /// global per function.
    fn is_literal_expression(&self, start: usize, end: usize) -> bool {
        self.tokens[start..end].iter().filter(|t| !t.is_trivia()).all(|t| match t.kind {
            TokenKind::Number => true,
            TokenKind::Ident => matches!(t.text, "true" | "false") || is_builtin_type(t.text),
            _ => ["(", ")", ",", "+", "-", "*", "/"].iter().any(|p| t.is_punct(p)),
        })
    }

    /// Drops `const` from declarations whose initializer naga cannot fold (a `?:`, a built-in of
    /// [`NOT_CONSTANT_FOLDED`], an index in a global's initializer) when no constant expression
    /// needs their value (no array size, `case` label or other constant's initializer names them).
    fn drop_const_naga_cannot_fold(&mut self) {
        let sig: Vec<usize> = (0..self.tokens.len()).filter(|&i| !self.tokens[i].is_trivia()).collect();
        // One-declarator constants: (index of `const`, declared name, tokens of the initializer,
        // whether naga cannot fold it).
        let mut constants: Vec<(usize, &str, std::ops::Range<usize>, bool)> = Vec::new();
        // Every constant's initializer, with its entry in `constants` if it has one.
        let mut const_initializers: Vec<(std::ops::Range<usize>, Option<usize>)> = Vec::new();
        let closing = self.closing_brackets(&sig);
        let depth_of_token = brace_depths(self.tokens);
        // Brace depth at each significant token.
        let depths: Vec<i32> = sig.iter().map(|&i| depth_of_token[i]).collect();
        for (k, &i) in sig.iter().enumerate() {
            if !self.tokens[i].is_ident("const") {
                continue;
            }
            // The declaration's end: a `;` (a `)` closing a parameter list ends a parameter).
            let mut depth = 0;
            let Some(end) = (k..sig.len()).find(|&j| match self.tokens[sig[j]].text {
                "(" => {
                    depth += 1;
                    false
                }
                ")" => {
                    depth -= 1;
                    depth < 0
                }
                ";" | "{" | "}" => true,
                _ => false,
            }) else {
                continue;
            };
            if !self.tokens[sig[end]].is_punct(";") {
                continue;
            }
            let Some(equals) = (k..end).find(|&j| self.tokens[sig[j]].is_punct("=")) else { continue };
            let one_declarator = self.paren_balanced_commas(&sig[equals..end]);
            let name = self.tokens[sig[equals - 1]];
            if !(one_declarator && name.kind == TokenKind::Ident) {
                const_initializers.push((equals + 1..end, None));
                continue;
            }
            let unfoldable = (equals + 1..end).any(|j| {
                let t = self.tokens[sig[j]];
                t.is_punct("?")
                    || (NOT_CONSTANT_FOLDED.contains(&t.text) && self.tokens[sig[j + 1]].is_punct("("))
                    || (depths[k] == 0 && self.indexes(&sig, &closing, j))
            });
            const_initializers.push((equals + 1..end, Some(constants.len())));
            constants.push((i, name.text, equals + 1..end, unfoldable));
        }
        // Where each constant's name appears, by significant-token index.
        let index_of: HashMap<&str, usize> = constants.iter().enumerate().map(|(n, c)| (c.1, n)).collect();
        let mut uses: Vec<Vec<usize>> = vec![Vec::new(); constants.len()];
        for (k, &i) in sig.iter().enumerate() {
            if let Some(&n) = index_of.get(self.tokens[i].text) {
                uses[n].push(k);
            }
        }
        // A constant computed from one that becomes a variable becomes a variable too.
        let mut variable: Vec<bool> = constants.iter().map(|c| c.3).collect();
        let mut pending: Vec<usize> = (0..constants.len()).filter(|&n| variable[n]).collect();
        while let Some(n) = pending.pop() {
            for &k in &uses[n] {
                if let Some((_, Some(user))) = const_initializers.iter().find(|(r, _)| r.contains(&k))
                    && !variable[*user]
                {
                    variable[*user] = true;
                    pending.push(*user);
                }
            }
        }
        // Unless a constant expression needs it: an array size, a `case` label or the
        // initializer of a constant that stays one.
        loop {
            let mut changed = false;
            for n in 0..constants.len() {
                if !variable[n] {
                    continue;
                }
                let needed = uses[n].iter().any(|&k| {
                    let in_constant = const_initializers
                        .iter()
                        .any(|(r, entry)| r.contains(&k) && entry.is_none_or(|e| !variable[e]) && *entry != Some(n));
                    let after_case = k > 0 && self.tokens[sig[k - 1]].is_ident("case");
                    in_constant || after_case || self.inside_brackets(&sig, k)
                });
                if needed {
                    variable[n] = false;
                    changed = true;
                }
            }
            if !changed {
                break;
            }
        }
        for (n, &(const_index, name, ..)) in constants.iter().enumerate() {
            if variable[n] {
                self.unconst.insert(name.to_string());
                self.replace(const_index, const_index + 1, String::new());
            }
        }
    }

    /// Whether significant token `k` opens an index (`a[1]`), not an array type (`float[3](…)`).
    /// naga's parser crashes on a constant index in a global constant's initializer (it looks
    /// the index up in the wrong expression arena), so such constants are not kept constant.
    fn indexes(&self, sig: &[usize], closing: &[Option<usize>], k: usize) -> bool {
        closing[k].is_some_and(|c| sig.get(c + 1).is_none_or(|&n| !self.tokens[n].is_punct("(")))
    }

    /// For each significant token that is a `[`, the significant index of its `]`.
    fn closing_brackets(&self, sig: &[usize]) -> Vec<Option<usize>> {
        let mut closing = vec![None; sig.len()];
        let mut open = Vec::new();
        for (k, &i) in sig.iter().enumerate() {
            match self.tokens[i].text {
                "[" => open.push(k),
                "]" => {
                    if let Some(o) = open.pop() {
                        closing[o] = Some(k);
                    }
                }
                _ => {}
            }
        }
        closing
    }

    /// Whether every `,` of the tokens sits inside parentheses (one declarator).
    fn paren_balanced_commas(&self, sig: &[usize]) -> bool {
        let mut depth = 0;
        for &i in sig {
            match self.tokens[i].text {
                "(" | "[" | "{" => depth += 1,
                ")" | "]" | "}" => depth -= 1,
                "," if depth == 0 => return false,
                _ => {}
            }
        }
        true
    }

    /// Whether significant token `k` stands inside `[...]`.
    fn inside_brackets(&self, sig: &[usize], k: usize) -> bool {
        let mut depth = 0i32;
        for &i in sig[..k].iter().rev() {
            match self.tokens[i].text {
                "]" => depth += 1,
                "[" if depth == 0 => return true,
                "[" => depth -= 1,
                ";" | "{" | "}" => return false,
                _ => {}
            }
        }
        false
    }

    /// `T x[3] = { a, b, c };` (GLSL 4.20's initializer lists, which naga lacks) becomes
    /// `T x[3] = T[3](a, b, c);`, and `vec3 v = { a, b, c };` becomes `vec3(a, b, c)`; the braces
    /// of an array's elements become constructors of the element type, those of a matrix's
    /// columns (`mat3 m = { {…}, {…}, {…} };`) column vectors. A list whose type the
    /// declaration does not spell out (a struct's members) is left to naga.
    fn lower_initializer_lists(&mut self) {
        let sig: Vec<usize> = (0..self.tokens.len()).filter(|&i| !self.tokens[i].is_trivia()).collect();
        let text = |k: usize| sig.get(k).map_or("", |&i| self.tokens[i].text);
        // A declaration has at least a type and a name before its `=`.
        for k in 2..sig.len() {
            if !(text(k) == "=" && text(k + 1) == "{") {
                continue;
            }
            // `T name = {`, `T name[N] = {` or `T[N] name = {`.
            // (element type, array size as written, the `[` of the size, index of the name)
            let (element, size, open, name_at) = if text(k - 1) == "]" {
                let Some(open) = (0..k - 1).rev().find(|&j| text(j) == "[") else { continue };
                let size: String = (open + 1..k - 1).map(text).collect();
                (open.checked_sub(2).map(text), Some(size), Some(open), open.saturating_sub(1))
            } else if text(k - 2) == "]" {
                let Some(open) = (0..k - 2).rev().find(|&j| text(j) == "[") else { continue };
                let size: String = (open + 1..k - 2).map(text).collect();
                (open.checked_sub(1).map(text), Some(size), Some(open), k - 1)
            } else {
                (Some(text(k - 2)), None, None, k - 1)
            };
            let Some(element) = element.filter(|t| is_builtin_type(t)) else { continue };
            if self.tokens[sig[name_at]].kind != TokenKind::Ident {
                continue;
            }
            // The type of a list nested one level: an array's element, a matrix's column.
            let nested = match (&size, matrix_shape(element)) {
                (Some(_), _) => Some(element.to_string()),
                (None, Some((_, rows))) => Some(format!("vec{rows}")),
                (None, None) => None,
            };
            let mut depth = 0;
            let mut count = 0;
            let mut close = None;
            for (j, &at) in sig.iter().enumerate().skip(k + 1) {
                match text(j) {
                    "{" => {
                        depth += 1;
                        if let (2, Some(nested)) = (depth, &nested) {
                            self.replace(at, at + 1, format!("{nested}("));
                        }
                    }
                    "}" => {
                        depth -= 1;
                        if depth == 0 {
                            close = Some(j);
                            break;
                        }
                        if depth == 1 && nested.is_some() {
                            self.replace(at, at + 1, ")".into());
                        }
                    }
                    "," if depth == 1 => count += 1,
                    _ => {}
                }
            }
            let Some(close) = close else { continue };
            let elements = count + usize::from(text(close - 1) != ",");
            let constructor = match (&size, open) {
                (Some(size), Some(open)) if size.is_empty() => {
                    // The declaration's `[]` takes the size the list gives it.
                    self.replace(sig[open], sig[open + 1] + 1, format!("[{elements}]"));
                    format!("{element}[{elements}](")
                }
                (Some(size), _) => format!("{element}[{size}]("),
                (None, _) => format!("{element}("),
            };
            self.replace(sig[k + 1], sig[k + 1] + 1, constructor);
            // A trailing `,` is allowed in a list, not in a constructor.
            if text(close - 1) == "," {
                self.replace(sig[close - 1], sig[close - 1] + 1, String::new());
            }
            self.replace(sig[close], sig[close] + 1, ")".into());
        }
    }

    /// `vec3(a < b)`: GLSL makes a vector from a bool (1.0 or 0.0 in every component); naga
    /// types the conversion as a float and never splats it. The one bool argument of a vector
    /// constructor (a comparison or a logical operation at its top level) is converted to the
    /// vector's component type first: `vec3(float(a < b))`.
    fn convert_bool_vector_constructors(&mut self) {
        let sig: Vec<usize> = (0..self.tokens.len()).filter(|&i| !self.tokens[i].is_trivia()).collect();
        for k in 0..sig.len().saturating_sub(1) {
            let scalar = match self.tokens[sig[k]].text {
                "vec2" | "vec3" | "vec4" => "float",
                "ivec2" | "ivec3" | "ivec4" => "int",
                "uvec2" | "uvec3" | "uvec4" => "uint",
                _ => continue,
            };
            if !self.tokens[sig[k + 1]].is_punct("(") {
                continue;
            }
            let mut depth = 0usize;
            let mut close = None;
            let mut boolean = false;
            let mut other_top_level = false;
            for (j, &i) in sig.iter().enumerate().skip(k + 1) {
                let text = self.tokens[i].text;
                match text {
                    "(" | "[" | "{" => depth += 1,
                    ")" | "]" | "}" => {
                        depth -= 1;
                        if depth == 0 {
                            close = Some(j);
                            break;
                        }
                    }
                    _ if depth == 1 && self.tokens[i].kind == TokenKind::Punct => match text {
                        "<" | ">" | "<=" | ">=" | "==" | "!=" | "&&" | "||" | "^^" => boolean = true,
                        "!" if j == k + 2 => boolean = true,
                        "," | "?" | ":" | "=" | ";" => other_top_level = true,
                        _ => {}
                    },
                    _ => {}
                }
            }
            let Some(close) = close else { continue };
            let (open, close) = (sig[k + 1], sig[close]);
            if boolean && !other_top_level && !self.covered(open) && !self.covered(close) {
                self.replace(open, open + 1, format!("({scalar}("));
                self.replace(close, close + 1, "))".into());
            }
        }
    }

    /// `T[](a, b, c)` becomes `T[3](a, b, c)`, and the unsized `[]` of the declaration it
    /// initialises gets the same size: GLSL sizes arrays from their constructor, naga does not.
    /// An unsized declaration initialised by a sized constructor (`T x[] = T[3](…)`) gets the
    /// constructor's size too.
    fn lower_array_constructor_sizes(&mut self) {
        let sig: Vec<usize> = (0..self.tokens.len()).filter(|&i| !self.tokens[i].is_trivia()).collect();
        let punct = |k: usize, p: &str| sig.get(k).is_some_and(|&i| self.tokens[i].is_punct(p));
        for k in 1..sig.len() {
            if !(self.tokens[sig[k - 1]].kind == TokenKind::Ident && punct(k, "[")) {
                continue;
            }
            if !punct(k + 1, "]") {
                // `T[N](`: one size group, then the constructor's arguments.
                let Some(close) = (k + 1..sig.len()).find(|&j| matches!(self.tokens[sig[j]].text, "]" | "[" | ";" | "{" | "}")) else {
                    continue;
                };
                if punct(close, "]") && punct(close + 1, "(") && !self.covered(sig[k]) {
                    let size: String = sig[k + 1..close].iter().map(|&i| self.tokens[i].text).collect();
                    self.size_unsized_declarator(&sig, k, &size);
                }
                continue;
            }
            if !punct(k + 2, "(") {
                continue;
            }
            let mut depth = 0;
            let mut count = 0;
            let mut empty = true;
            for &i in &sig[k + 2..] {
                match self.tokens[i].text {
                    "(" | "[" | "{" => depth += 1,
                    ")" | "]" | "}" => {
                        depth -= 1;
                        if depth == 0 {
                            break;
                        }
                    }
                    "," if depth == 1 => count += 1,
                    _ => {}
                }
                if depth >= 1 && !self.tokens[i].is_punct("(") || depth > 1 {
                    empty = false;
                }
            }
            let size = if empty { 0 } else { count + 1 };
            self.replace(sig[k], sig[k + 1] + 1, format!("[{size}]"));
            self.size_unsized_declarator(&sig, k, &size.to_string());
        }
    }

    /// The unsized `[]` of the declaration whose initializer has a constructor at `sig[k]`
    /// (between the statement's start and the constructor) becomes `[size]`.
    fn size_unsized_declarator(&mut self, sig: &[usize], k: usize, size: &str) {
        let punct = |k: usize, p: &str| sig.get(k).is_some_and(|&i| self.tokens[i].is_punct(p));
        for j in (0..k).rev() {
            let t = self.tokens[sig[j]];
            if matches!(t.text, ";" | "{" | "}") {
                break;
            }
            if t.is_punct("[") && punct(j + 1, "]") && !punct(j + 2, "(") {
                self.replace(sig[j], sig[j + 1] + 1, format!("[{size}]"));
            }
        }
    }

    /// Arrays of arrays declared (`T x[A][B]`, `T[A][B] x`) or constructed (`T[A][B](…)`) get
    /// their sizes in naga's order ([`naga_dimensions`]); indexing (`x[i][j]`) stays as written.
    /// Declarations the lowering rewrites whole write their suffix through the same function.
    fn reverse_array_dimensions(&mut self) {
        let sig: Vec<usize> = (0..self.tokens.len()).filter(|&i| !self.tokens[i].is_trivia()).collect();
        let token = |k: usize| sig.get(k).map(|&i| self.tokens[i]);
        let closing = self.closing_brackets(&sig);
        let mut k = 0;
        while k < sig.len() {
            let mut j = k + 1;
            let mut groups = 0;
            while let Some(Some(close)) = closing.get(j) {
                groups += 1;
                j = close + 1;
            }
            let is_name = token(k).is_some_and(|t| t.kind == TokenKind::Ident);
            // A declarator follows its type; a type with sizes is followed by a name or `(`.
            let declarator = k > 0 && token(k - 1).is_some_and(|p| p.kind == TokenKind::Ident && !is_statement_keyword(p.text));
            let sized_type = token(j).is_some_and(|n| n.kind == TokenKind::Ident || n.is_punct("("));
            let (start, end) = (sig.get(k + 1).copied().unwrap_or(0), sig.get(j - 1).map_or(0, |&i| i + 1));
            if is_name && groups >= 2 && (declarator || sized_type) && !(start..end).any(|i| self.covered(i)) {
                let written: String = sig[k + 1..j].iter().map(|&i| self.tokens[i].text).collect();
                self.replace(start, end, naga_dimensions(&written));
            }
            k = j.max(k + 1);
        }
    }

    /// naga's parser cannot size an array by a local constant (`const int n = 3; float w[n];`);
    /// drivers can. Inside a function, a local `const int` or `uint` of literals is written as its
    /// value where it stands inside `[…]`.
    fn inline_local_constant_sizes(&mut self) {
        let sig: Vec<usize> = (0..self.tokens.len()).filter(|&i| !self.tokens[i].is_trivia()).collect();
        let text = |k: usize| sig.get(k).map_or("", |&i| self.tokens[i].text);
        let depth_of_token = brace_depths(self.tokens);
        let mut values: HashMap<&str, String> = HashMap::new();
        for k in 0..sig.len() {
            if depth_of_token[sig[k]] == 0 {
                // Between functions: the last one's constants are out of scope.
                values.clear();
                continue;
            }
            let name = self.tokens[sig[k]];
            if text(k) == "const" && matches!(text(k + 1), "int" | "uint") && text(k + 3) == "=" {
                let Some(end) = (k + 4..sig.len()).find(|&j| text(j) == ";") else { continue };
                let written: Vec<&str> = (k + 4..end).map(text).collect();
                if let Some(value) = literal_integer_expression(&written.join(" ")) {
                    let suffix = if text(k + 1) == "uint" { "u" } else { "" };
                    values.insert(text(k + 2), format!("{value}{suffix}"));
                }
            } else if let Some(value) = values.get(name.text)
                && !self.covered(sig[k])
                && self.inside_brackets(&sig, k)
            {
                let value = value.clone();
                self.replace(sig[k], sig[k] + 1, value);
            }
        }
    }

    fn collect_function_signature(&mut self, stmt: &Statement) {
        let Some(open) = stmt.sig.iter().position(|&i| self.tokens[i].is_punct("(")) else { return };
        if open == 0 || !self.tokens[stmt.sig[open - 1]].kind.eq(&TokenKind::Ident) {
            return;
        }
        let name = self.tokens[stmt.sig[open - 1]].text;
        let params = self.parameters(&stmt.sig[open..]);
        if params.iter().any(|p| p.sampler.is_some()) {
            // Overloads merge: a sampler argument can only go to a sampler parameter, so a
            // position any overload takes a sampler at passes both halves.
            let positions = self.symbols.sampler_functions.entry(name.to_string()).or_default();
            for (k, p) in params.iter().enumerate() {
                if k == positions.len() {
                    positions.push(false);
                }
                positions[k] |= p.sampler.is_some();
            }
        }
    }

    /// Parameters of a parameter list starting at `(`.
    fn parameters(&self, sig: &[usize]) -> Vec<Parameter> {
        let mut params = Vec::new();
        let mut depth = 0;
        let mut current: Vec<usize> = Vec::new();
        for &i in sig {
            let t = &self.tokens[i];
            if t.is_punct("(") {
                depth += 1;
                if depth == 1 {
                    continue;
                }
            } else if t.is_punct(")") {
                depth -= 1;
                if depth == 0 {
                    params.push(self.parameter(&current));
                    break;
                }
            } else if t.is_punct(",") && depth == 1 {
                params.push(self.parameter(&current));
                current.clear();
                continue;
            }
            current.push(i);
        }
        params.retain(|p| !(p.tokens.is_empty() || p.tokens.len() == 1 && self.tokens[p.tokens[0]].is_ident("void")));
        params
    }

    fn parameter(&self, tokens: &[usize]) -> Parameter {
        let ty = tokens.iter().map(|&i| &self.tokens[i]).find(|t| split_sampler_type(t.text).is_some());
        let name = tokens.last().map(|&i| self.tokens[i].text.to_string()).unwrap_or_default();
        Parameter { tokens: tokens.to_vec(), sampler: ty.map(|t| (t.text.to_string(), name)) }
    }

    /// Splits the sampler parameters of a function definition or prototype, and drops `const`
    /// from parameters (`const in float x`: drivers accept it, naga does not).
    fn lower_function_header(&mut self, stmt: &Statement) {
        let Some(open) = stmt.sig.iter().position(|&i| self.tokens[i].is_punct("(")) else { return };
        let is_header = open >= 2
            && self.tokens[stmt.sig[open - 1]].kind == TokenKind::Ident
            && !stmt.sig[..open].iter().any(|&i| self.tokens[i].is_punct("="));
        if !is_header {
            return;
        }
        for param in self.parameters(&stmt.sig[open..]) {
            if param.sampler.is_none() {
                for &i in &param.tokens {
                    if self.tokens[i].is_ident("const") {
                        self.replace(i, i + 1, String::new());
                    }
                }
            }
            let Some((ty, name)) = &param.sampler else { continue };
            let (texture_ty, sampler_ty) = split_sampler_type(ty).unwrap();
            let start = param.tokens[0];
            let end = *param.tokens.last().unwrap() + 1;
            let name = self.lowered_name(name);
            self.replace(start, end, format!("{texture_ty} {name}, {sampler_ty} {RESERVED_PREFIX}sampler_{name}"));
        }
    }

    /// `layout(rgba16f) uniform writeonly image2D img;` → the same with a set and binding (any
    /// of the pack's own replaced), and a format when it has none.
    fn lower_image(&mut self, decl: &Declaration<'a>, start: usize, end: usize, default_format: &str) -> Result<(), LowerError> {
        let mut args: Vec<String> = Vec::new();
        if let Some((open, close)) = decl.layout {
            // Tokens from after `layout (` to before `)`, split at top-level commas.
            let inner: Vec<&Token<'_>> = self.tokens[open + 1..close].iter().filter(|t| !t.is_trivia()).skip(1).collect();
            for part in inner.split(|t| t.is_punct(",")) {
                let text: Vec<&str> = part.iter().map(|t| t.text).collect();
                if !text.is_empty() && !matches!(text[0], "binding" | "set") {
                    args.push(text.join(" "));
                }
            }
        }
        let has_format = args.iter().any(|a| !a.contains('=') && a.starts_with(['r', 'R']));
        if !has_format {
            args.push(default_format.to_string());
        }
        let memory: String =
            decl.qualifiers.iter().filter(|q| is_memory_qualifier(q)).map(|q| format!("{q} ")).collect();
        let mut text = String::new();
        for (name, suffix) in &decl.names {
            if !suffix.is_empty() {
                return Err(self.err(start, format!("image arrays (`{name}{suffix}`) are not supported")));
            }
            let binding = self.next_binding;
            self.next_binding += 1;
            write!(
                text,
                "layout({}, set = {}, binding = {binding}) uniform {memory}{} {name}; ",
                args.join(", "),
                self.descriptor_set(),
                decl.ty
            )
            .unwrap();
            self.interface.images.insert(name.to_string(), decl.ty.to_string());
        }
        self.replace(start, end, text.trim_end().to_string());
        Ok(())
    }

    fn lower_uniform(&mut self, decl: &Declaration<'a>, start: usize, end: usize) -> Result<(), LowerError> {
        // A uniform's initializer only sets its value before the loader does: drop it (the
        // declarator suffix stops before `=`), and keep its text for the harness to fill the
        // uniform with where the loader sets nothing.
        for ((name, _), initializer) in decl.names.iter().zip(&decl.initializers) {
            if let Some((equals, end)) = *initializer {
                let text: Vec<&str> = (equals + 1..end).filter(|&i| !self.tokens[i].is_trivia()).map(|i| self.tokens[i].text).collect();
                self.interface.uniform_initializers.insert(name.to_string(), text.join(" "));
            }
        }
        let set = self.descriptor_set();
        if let Some(default_format) = image_default_format(decl.ty) {
            return self.lower_image(decl, start, end, default_format);
        }
        if let Some((texture_ty, sampler_ty)) = split_sampler_type(decl.ty) {
            let mut text = String::new();
            for (name, suffix) in &decl.names {
                if !suffix.is_empty() {
                    return Err(self.err(start, format!("sampler arrays (`{name}{suffix}`) are not supported")));
                }
                // `texture` names the atlas in old packs but hides texture() in GLSL 450.
                let lowered = if *name == "texture" { "gtexture" } else { name };
                let binding = self.next_binding;
                self.next_binding += 2;
                write!(
                    text,
                    "layout(set = {set}, binding = {binding}) uniform {texture_ty} {lowered}; \
                     layout(set = {set}, binding = {}) uniform {sampler_ty} {RESERVED_PREFIX}sampler_{lowered}; ",
                    binding + 1
                )
                .unwrap();
                self.symbols.samplers.insert(name.to_string(), (lowered.to_string(), decl.ty.to_string()));
                self.interface.resources.insert(
                    name.to_string(),
                    ResourceKind::Texture {
                        ty: texture_ty.to_string(),
                        comparison: sampler_ty == "samplerShadow",
                        binding,
                    },
                );
            }
            self.replace(start, end, text.trim_end().to_string());
            return Ok(());
        }
        if decl.ty == "bool" {
            // A bool cannot live in a uniform buffer: store an int and read it as a bool.
            for (name, suffix) in &decl.names {
                if !suffix.is_empty() {
                    return Err(self.err(start, format!("bool uniform arrays (`{name}{suffix}`) are not supported")));
                }
                self.block.push(format!("int {BOOL_UNIFORM_PREFIX}{name};"));
                self.symbols.bool_uniforms.insert(name.to_string());
                self.interface.resources.insert(name.to_string(), ResourceKind::Uniform { ty: "bool".into() });
            }
            self.replace(start, end, String::new());
            return Ok(());
        }
        if !is_builtin_type(decl.ty) {
            // A struct type is defined in the pack's text, after the shared block's line: give
            // these uniforms a block of their own on their declaration's line.
            let binding = self.next_binding;
            self.next_binding += 1;
            let mut members = String::new();
            for (name, suffix) in &decl.names {
                write!(members, "{} {name}{}; ", decl.ty, naga_dimensions(suffix)).unwrap();
                self.interface.resources.insert(name.to_string(), ResourceKind::Uniform { ty: format!("{}{suffix}", decl.ty) });
            }
            let text = format!(
                "layout(std140, set = {set}, binding = {binding}) uniform {RESERVED_PREFIX}Uniforms{binding} {{ {}}};",
                members
            );
            self.replace(start, end, text);
            return Ok(());
        }
        for (name, suffix) in &decl.names {
            self.block.push(format!("{} {name}{};", decl.ty, naga_dimensions(suffix)));
            self.interface.resources.insert(name.to_string(), ResourceKind::Uniform { ty: format!("{}{suffix}", decl.ty) });
        }
        self.replace(start, end, String::new());
        Ok(())
    }

    /// Rewrites uses inside every statement and function body.
    fn rewrite_bodies(&mut self) -> Result<(), LowerError> {
        let sig: Vec<usize> = (0..self.tokens.len()).filter(|&i| !self.tokens[i].is_trivia()).collect();
        let constants = self.constant_names(&sig);
        // Sampler parameters in scope: name → combined type; reset at each function's end.
        let mut local_samplers: HashMap<String, String> = HashMap::new();
        let mut brace_depth = 0;
        let mut paren_depth = 0;
        // Calls of sampler-taking functions: (function, paren depth inside the call, argument index).
        let mut calls: Vec<(String, i32, usize)> = Vec::new();
        // Global samplers and bools hidden by a local or parameter of the same name, with the
        // brace depth of the scope that declares it.
        let mut hidden: Vec<(String, i32)> = Vec::new();
        // A local that will hide a global at the end of its declarator: (name, brace depth,
        // paren depth of the declaration).
        let mut pending_local: Option<(String, i32, i32)> = None;
        // Inside a `const` declaration, whose initializer must stay a constant expression.
        let mut in_constant = false;
        // Paren depth at which a lookup's closing `)` is replaced, and its replacement.
        let mut closers: Vec<(i32, &'static str)> = Vec::new();
        // Outside fragment stages there are no derivatives: naga refuses implicit-level
        // sampling there, where GLSL samples the base level. Make the level explicit.
        let implicit_level = !self.compute && self.stage == Stage::Fragment;
        let mut k = 0;
        while k < sig.len() {
            let i = sig[k];
            let t = self.tokens[i];
            if self.covered(i) {
                // Inside a declaration already rewritten; track parameter samplers of headers.
                k += 1;
                continue;
            }
            if t.text == ";" {
                in_constant = false;
            } else if t.text == "const" {
                in_constant = true;
            }
            if matches!(t.text, ";" | ",")
                && let Some((name, depth, parens)) = pending_local.take()
            {
                if parens == paren_depth {
                    hidden.push((name, depth));
                } else {
                    pending_local = Some((name, depth, parens));
                }
            }
            match t.text {
                "{" => brace_depth += 1,
                "}" => {
                    brace_depth -= 1;
                    hidden.retain(|(_, depth)| *depth <= brace_depth);
                    if brace_depth == 0 {
                        local_samplers.clear();
                        hidden.clear();
                    }
                }
                "(" => paren_depth += 1,
                ")" => {
                    if let Some(&(depth, closer)) = closers.last()
                        && depth == paren_depth
                    {
                        self.replace(i, i + 1, closer.to_string());
                        closers.pop();
                    }
                    if calls.last().is_some_and(|c| c.1 == paren_depth) {
                        calls.pop();
                    }
                    paren_depth -= 1;
                }
                "," => {
                    if let Some(call) = calls.last_mut()
                        && call.1 == paren_depth
                    {
                        call.2 += 1;
                    }
                }
                _ => {}
            }
            if t.kind != TokenKind::Ident {
                k += 1;
                continue;
            }
            let next = sig.get(k + 1).map(|&j| self.tokens[j]);
            let followed_by_call = next.is_some_and(|n| n.is_punct("("));
            let previous = k.checked_sub(1).map(|j| self.tokens[sig[j]]);
            if previous.is_some_and(|p| p.is_punct(".")) {
                // A field or swizzle (`pixel.shadow` beside a sampler `shadow`) names no global;
                // a field named like a naga keyword is renamed as its declaration is.
                self.rename_vulkan_keyword(i);
                k += 1;
                continue;
            }
            if brace_depth > 0 && matches!(t.text, "return" | "discard" | "break" | "continue") && self.ends_block_early(&sig, k) {
                // naga drops the statements after it, but not the expressions of the calls among
                // them, and then refuses the function ("expression not visited"); drivers compile
                // the unreachable code. Behind an always-true `if`, naga keeps it.
                self.replace(i, i + 1, format!("if (true) {}", t.text));
            }
            let after_type = previous.is_some_and(|p| p.kind == TokenKind::Ident || p.is_punct("]"));
            if brace_depth == 0 && followed_by_call && after_type {
                if t.text == "main" && self.needs_main_wrapper() {
                    // The real `main` (added at the end) runs the global initializers and
                    // copies the matrix varyings' columns.
                    self.replace(i, i + 1, format!("{RESERVED_PREFIX}main"));
                }
                // A function header: remember its sampler parameters for the body; other
                // parameters named like a global sampler or bool hide it there.
                let open = k + 1;
                let close = (open..sig.len()).find(|&j| self.tokens[sig[j]].is_punct(")")).unwrap_or(open);
                for p in self.parameters(&sig[open..=close]) {
                    if let Some((ty, name)) = p.sampler {
                        local_samplers.insert(name, ty);
                    } else if let Some(&last) = p.tokens.last() {
                        let name = self.tokens[last].text;
                        if self.hides_a_global(name) {
                            hidden.push((name.to_string(), 1));
                        }
                    }
                }
                for &j in &sig[open..=close] {
                    self.rename_vulkan_keyword(j);
                }
                k = close + 1;
                continue;
            }
            if brace_depth > 0
                && !followed_by_call
                && previous.is_some_and(|p| p.kind == TokenKind::Ident && !is_statement_keyword(p.text))
                && next.is_some_and(|n| matches!(n.text, "=" | ";" | "," | "["))
                && self.hides_a_global(t.text)
            {
                // A local declared with a global's name: it hides the global once its
                // declarator ends (its own initializer still sees the global).
                pending_local = Some((t.text.to_string(), brace_depth, paren_depth));
                self.rename_vulkan_keyword(i);
                k += 1;
                continue;
            }
            if hidden.iter().any(|(name, _)| name == t.text) {
                self.rename_vulkan_keyword(i);
                k += 1;
                continue;
            }
            if let Some((_, new_name, shadow)) = LEGACY_SAMPLING.iter().find(|(old, ..)| *old == t.text)
                && followed_by_call
            {
                let base_level = !implicit_level && *new_name == "texture";
                // A third argument is a bias, which only a fragment stage has derivatives for.
                // NVIDIA takes it as the level, there being none to bias.
                let bias_as_level = base_level && self.call_arguments(&sig, k + 1) > 2;
                if bias_as_level && !self.lenient {
                    return Err(self.bias_outside_fragment(i));
                }
                let new_name = if base_level { "textureLod" } else { new_name };
                let level = if base_level && !bias_as_level { ", 0.0" } else { "" };
                if *shadow {
                    self.replace(i, i + 1, format!("vec4(vec3({new_name}"));
                    closers.push((paren_depth + 1, if level.is_empty() { ")), 1.0)" } else { ", 0.0)), 1.0)" }));
                } else {
                    self.replace(i, i + 1, new_name.to_string());
                    if !level.is_empty() {
                        closers.push((paren_depth + 1, ", 0.0)"));
                    }
                }
            } else if t.text == "texture" && followed_by_call && !implicit_level {
                let bias_as_level = self.call_arguments(&sig, k + 1) > 2;
                if bias_as_level && !self.lenient {
                    return Err(self.bias_outside_fragment(i));
                }
                self.replace(i, i + 1, "textureLod".to_string());
                if !bias_as_level {
                    closers.push((paren_depth + 1, ", 0.0)"));
                }
            } else if followed_by_call && self.symbols.sampler_functions.contains_key(t.text) {
                if let Some((name, stand_in)) = GATHER_STAND_INS.iter().find(|(name, _)| *name == t.text) {
                    if name.starts_with("textureGather") {
                        self.add_header(GATHER.to_string());
                    }
                    self.add_header((*stand_in).to_string());
                }
                calls.push((t.text.to_string(), paren_depth + 1, 0));
            } else if let Some(ty) = local_samplers.get(t.text).cloned() {
                let passes_both = self.passes_sampler_halves(&calls, paren_depth);
                self.replace(i, i + 1, combined_use(&self.lowered_name(t.text), &ty, passes_both));
            } else if let Some((lowered, ty)) = self.symbols.samplers.get(t.text).cloned()
                && !(t.text == "texture" && followed_by_call)
            {
                let passes_both = self.passes_sampler_halves(&calls, paren_depth);
                self.replace(i, i + 1, combined_use(&lowered, &ty, passes_both));
            } else if self.symbols.bool_uniforms.contains(t.text) {
                self.replace(i, i + 1, format!("({BOOL_UNIFORM_PREFIX}{} != 0)", t.text));
            } else if !followed_by_call && self.is_keyword_only_to_naga(t.text) {
                self.rename_vulkan_keyword(i);
            } else if followed_by_call
                && !in_constant
                && RANGE_CHECKED_BUILTINS.contains(&t.text)
                && self.constant_arguments(&sig, k + 1, &constants)
            {
                // naga evaluates a built-in of constant arguments while parsing and refuses
                // values outside its domain (`normalize(vec3(0.0))`, often in a branch not
                // taken); drivers fold them to NaN or leave them to run time. A stand-in that
                // calls the built-in on its parameter keeps the type check without the folding.
                let arity = if t.text == "pow" { 2 } else { 1 };
                let mut stand_in = String::new();
                for ty in ["float", "vec2", "vec3", "vec4"] {
                    let params: Vec<String> = (0..arity).map(|n| format!("{ty} a{n}")).collect();
                    let args: Vec<String> = (0..arity).map(|n| format!("a{n}")).collect();
                    // naga has no scalar normalize; for a scalar it is the sign.
                    let builtin = if t.text == "normalize" && ty == "float" { "sign" } else { t.text };
                    write!(stand_in, "{ty} {RESERVED_PREFIX}rt_{}({}) {{ return {builtin}({}); }} ", t.text, params.join(", "), args.join(", ")).unwrap();
                }
                self.add_header(stand_in.trim_end().to_string());
                self.replace(i, i + 1, format!("{RESERVED_PREFIX}rt_{}", t.text));
            } else {
                self.rewrite_builtin(&sig, k)?;
            }
            k += 1;
        }
        Ok(())
    }

    /// Whether the jump statement (`return`, `discard`, …) at significant token `k` stands in a
    /// block, not as the body of an `if`/`else`/loop, and statements of the same block follow it.
    fn ends_block_early(&self, sig: &[usize], k: usize) -> bool {
        let in_block = k > 0 && matches!(self.tokens[sig[k - 1]].text, ";" | "{" | "}" | ":");
        let Some(end) = (k..sig.len()).find(|&j| self.tokens[sig[j]].is_punct(";")) else { return false };
        in_block && sig.get(end + 1).is_some_and(|&j| !matches!(self.tokens[j].text, "}" | "case" | "default"))
    }

    /// Whether the call whose `(` is significant token `open` has only literals, constructors,
    /// calls and `constants` as arguments (no variables).
    fn constant_arguments(&self, sig: &[usize], open: usize, constants: &HashSet<String>) -> bool {
        let mut depth = 0;
        for (k, &i) in sig.iter().enumerate().skip(open) {
            let t = self.tokens[i];
            match t.text {
                "(" => depth += 1,
                ")" => {
                    depth -= 1;
                    if depth == 0 {
                        return true;
                    }
                }
                _ if t.kind == TokenKind::Ident => {
                    let called = sig.get(k + 1).is_some_and(|&j| self.tokens[j].is_punct("("));
                    if !called && !constants.contains(t.text) {
                        return false;
                    }
                }
                _ => {}
            }
        }
        false
    }

    /// The names `const` declarations give (`const vec3 a = …, b = …;`), wherever they stand:
    /// naga folds expressions of them while parsing, as it folds literals.
    fn constant_names(&self, sig: &[usize]) -> HashSet<String> {
        let mut names = HashSet::new();
        let mut in_constant = false;
        for (k, &i) in sig.iter().enumerate() {
            let t = self.tokens[i];
            match t.text {
                "const" => in_constant = true,
                ";" | "{" | "}" | "(" | ")" => in_constant = false,
                _ if in_constant && t.kind == TokenKind::Ident && sig.get(k + 1).is_some_and(|&j| matches!(self.tokens[j].text, "=" | "[")) => {
                    names.insert(t.text.to_string());
                }
                _ => {}
            }
        }
        names
    }

    /// Whether a local or parameter of this name hides a global the lowering rewrites.
    fn hides_a_global(&self, name: &str) -> bool {
        self.symbols.samplers.contains_key(name) || self.symbols.bool_uniforms.contains(name)
    }

    /// Whether `word` is an identifier in the stage's GLSL version but a keyword to naga:
    /// Vulkan GLSL's type names, and qualifiers later versions added.
    fn is_keyword_only_to_naga(&self, word: &str) -> bool {
        let keyword_since = match word {
            "sample" => 400,
            "restrict" | "readonly" | "writeonly" => 420,
            "buffer" | "shared" => 430,
            _ => return VULKAN_ONLY_KEYWORDS.contains(&word),
        };
        self.version < keyword_since
    }

    /// The name a pack's identifier has in the lowered text.
    fn lowered_name(&self, name: &str) -> String {
        if self.is_keyword_only_to_naga(name) { format!("{RESERVED_PREFIX}kw_{name}") } else { name.to_string() }
    }

    /// An identifier that the stage's GLSL allows but naga reads as a keyword (`sampler`,
    /// `texture2D`, `sample` before GLSL 4.00, …) gets a reserved name.
    fn rename_vulkan_keyword(&mut self, index: usize) {
        let t = self.tokens[index];
        if t.kind == TokenKind::Ident && self.is_keyword_only_to_naga(t.text) && !self.covered(index) {
            self.replace(index, index + 1, format!("{RESERVED_PREFIX}kw_{}", t.text));
        }
    }

    fn needs_main_wrapper(&self) -> bool {
        !self.matrix_varyings.is_empty() || !self.global_initializers.is_empty()
    }

    /// Whether the current argument of the innermost call goes to a sampler parameter.
    fn passes_sampler_halves(&self, calls: &[(String, i32, usize)], paren_depth: i32) -> bool {
        calls.last().is_some_and(|(f, depth, arg)| {
            *depth == paren_depth && self.symbols.sampler_functions[f].get(*arg).copied().unwrap_or(false)
        })
    }

    fn covered(&self, index: usize) -> bool {
        self.replacements.range(..=index).next_back().is_some_and(|(&start, &(end, _))| start <= index && index < end)
    }

    fn rewrite_builtin(&mut self, sig: &[usize], k: usize) -> Result<(), LowerError> {
        let i = sig[k];
        let name = self.tokens[i].text;
        let stage = self.stage;
        let called = sig.get(k + 1).is_some_and(|&j| self.tokens[j].is_punct("("));
        if let Some((_, stand_in)) = MISSING_BUILTINS.iter().find(|(n, _)| *n == name)
            && called
        {
            self.add_header((*stand_in).to_string());
            return Ok(());
        }
        if called && TRINARY_MINMAX.contains(&name) && self.enables_extension("GL_AMD_shader_trinary_minmax") && !self.defines_function(name) {
            self.add_header(trinary_minmax_stand_in(name));
            return Ok(());
        }
        if self.compute {
            if name == "gl_WorkGroupSize"
                && let Some(size) = self.local_size()
            {
                // A constant in GLSL (array sizes use it); naga reads it at run time.
                self.replace(i, i + 1, size);
            }
            return Ok(());
        }
        if let Some(varying) = legacy_varying(name, stage) {
            let ty = LEGACY_VARYINGS.iter().find(|v| v.2 == varying).map_or("vec4", |v| v.3);
            let location = self.varyings.location_of(varying);
            let direction = if stage == Stage::Vertex { "out" } else { "in" };
            self.add_header(format!("layout(location = {location}) {direction} {ty} {varying};"));
            self.replace(i, i + 1, varying.into());
            return Ok(());
        }
        if let Some(&(_, new, ty, location)) = LEGACY_INPUTS.iter().find(|(old, ..)| *old == name) {
            if stage != Stage::Vertex {
                return Err(self.err(i, format!("{name} is a vertex-shader input")));
            }
            self.interface.inputs.insert(name.to_string(), location);
            self.add_header(format!("layout(location = {location}) in {ty} {new};"));
            self.replace(i, i + 1, new.to_string());
            return Ok(());
        }
        if let Some(&(_, new, ty)) = LEGACY_MATRICES.iter().find(|(old, ..)| *old == name) {
            let (base, array) = ty.split_once('[').map_or((ty, String::new()), |(b, a)| (b, format!("[{a}")));
            let member = format!("{base} {new}{array};");
            if !self.block.contains(&member) {
                self.block.push(member);
                self.interface.resources.insert(name.to_string(), ResourceKind::Uniform { ty: ty.to_string() });
            }
            self.replace(i, i + 1, new.to_string());
            return Ok(());
        }
        match name {
            // GLSL 4.50's flag of the fragments run only for their neighbours' derivatives. naga
            // has no such variable; a fragment that writes its outputs is never one, so false.
            "gl_HelperInvocation" if stage == Stage::Fragment && self.version >= 450 => self.replace(i, i + 1, "false".into()),
            "gl_VertexID" | "gl_InstanceID" if stage == Stage::Vertex => {
                // Vulkan GLSL's names; naga reads them as `uint`, GLSL's are `int`.
                let vulkan = if name == "gl_VertexID" { "gl_VertexIndex" } else { "gl_InstanceIndex" };
                self.replace(i, i + 1, format!("int({vulkan})"));
            }
            "ftransform" => {
                let called = |j: usize, p: &str| sig.get(j).is_some_and(|&t| self.tokens[t].is_punct(p));
                if !(called(k + 1, "(") && called(k + 2, ")")) {
                    return Err(self.err(i, "ftransform takes no arguments: call it as ftransform()"));
                }
                let close = k + 2;
                for member in ["mat4 tp_ModelViewProjectionMatrix;"] {
                    if !self.block.iter().any(|m| m == member) {
                        self.block.push(member.to_string());
                        self.interface
                            .resources
                            .insert("gl_ModelViewProjectionMatrix".into(), ResourceKind::Uniform { ty: "mat4".into() });
                    }
                }
                self.interface.inputs.insert("gl_Vertex".into(), 0);
                self.add_header("layout(location = 0) in vec4 tp_Vertex;".into());
                self.replace(i, sig[close] + 1, "(tp_ModelViewProjectionMatrix * tp_Vertex)".into());
            }
            "gl_FragData" | "gl_FragColor" => {
                let sig_tokens: Vec<&Token<'_>> = sig.iter().map(|&j| &self.tokens[j]).collect();
                let (location, end) = if name == "gl_FragColor" {
                    (0, i + 1)
                } else {
                    let index = constant_index(&sig_tokens, k)
                        .ok_or_else(|| self.err(i, "gl_FragData needs a constant index"))?;
                    (index, sig[k + 3] + 1)
                };
                let shipped = if name == "gl_FragColor" { name.to_string() } else { format!("gl_FragData[{location}]") };
                self.interface.outputs.insert(location, shipped);
                self.add_header(format!("layout(location = {location}) out vec4 tp_FragData{location};"));
                self.replace(i, end, format!("tp_FragData{location}"));
            }
            "gl_Fog" => {
                if self.prelude.is_empty() {
                    self.prelude.push_str(FOG_STRUCT);
                    self.block.push(format!("tp_FogParameters {RESERVED_PREFIX}Fog;"));
                    self.interface.resources.insert("gl_Fog".into(), ResourceKind::Uniform { ty: "gl_FogParameters".into() });
                }
                self.replace(i, i + 1, format!("{RESERVED_PREFIX}Fog"));
            }
            "gl_TexCoord" => {
                let sig_tokens: Vec<&Token<'_>> = sig.iter().map(|&j| &self.tokens[j]).collect();
                let index =
                    constant_index(&sig_tokens, k).ok_or_else(|| self.err(i, "gl_TexCoord needs a constant index"))?;
                let varying = format!("tp_TexCoord{index}");
                let location = self.varyings.location_of(&varying);
                let direction = if stage == Stage::Vertex { "out" } else { "in" };
                self.add_header(format!("layout(location = {location}) {direction} vec4 {varying};"));
                self.replace(i, sig[k + 3] + 1, varying);
            }
            _ => {}
        }
        Ok(())
    }

    /// The work group size the stage declares ([`local_size`]) as a `uvec3` constructor.
    fn local_size(&self) -> Option<String> {
        local_size(self.tokens).map(|size| format!("uvec3({}u, {}u, {}u)", size[0], size[1], size[2]))
    }

    /// Whether the stage has an `#extension NAME` line that does not disable it.
    fn enables_extension(&self, name: &str) -> bool {
        crate::token::extension_directives(self.tokens).iter().any(|d| d.name == name && d.enables())
    }

    /// Whether the stage defines a function called `name` itself.
    fn defines_function(&self, name: &str) -> bool {
        function_definitions(self.tokens).iter().any(|d| self.tokens[d.name].is_ident(name))
    }

    fn add_header(&mut self, decl: String) {
        if !self.header.contains(&decl) {
            self.header.push(' ');
            self.header.push_str(&decl);
        }
    }

    fn finish_header(&mut self, version_index: usize) {
        // naga reads the rest of the `#version` line as part of the directive, so the added
        // declarations open line 2 instead, which after preprocessing is ordinary top-level code.
        let mut line = self.prelude.clone();
        if !self.block.is_empty() {
            write!(
                line,
                " layout(std140, set = {}, binding = 0) uniform {RESERVED_PREFIX}Uniforms {{ {} }};",
                self.descriptor_set(),
                self.block.join(" ")
            )
            .unwrap();
        }
        line.push_str(&self.header);
        let line = line.trim_start();
        let end = (version_index..self.tokens.len()).find(|&i| self.tokens[i].kind == TokenKind::Newline).unwrap_or(self.tokens.len());
        match self.tokens.get(end) {
            Some(newline) => self.replace(version_index, end + 1, format!("#version 450{}{line} ", newline.text)),
            // Nothing follows the `#version` line, so nothing needs the declarations, and a line
            // for them would move every line count.
            None => self.replace(version_index, end, "#version 450".into()),
        }
        // `#extension` lines mean nothing to naga.
        let mut at_line_start = true;
        for i in 0..self.tokens.len() {
            let t = &self.tokens[i];
            if t.kind == TokenKind::Newline {
                at_line_start = true;
                continue;
            }
            if t.is_trivia() {
                continue;
            }
            if at_line_start && t.is_punct("#") && i != version_index {
                let end = (i..self.tokens.len()).find(|&j| self.tokens[j].kind == TokenKind::Newline).unwrap_or(self.tokens.len());
                self.replace(i, end, String::new());
            }
            at_line_start = false;
        }
    }

    fn render(&self) -> String {
        let mut out = String::with_capacity(self.tokens.iter().map(|t| t.text.len()).sum::<usize>() + self.header.len() + 256);
        let mut i = 0;
        while i < self.tokens.len() {
            if let Some((end, text)) = self.replacements.get(&i) {
                out.push_str(text);
                i = *end;
            } else {
                out.push_str(self.tokens[i].text);
                i += 1;
            }
        }
        let trailer = self.main_wrapper();
        if !trailer.is_empty() {
            // On the last line, so no line break is added.
            let at = if out.ends_with('\n') { out.trim_end_matches(['\n', '\r']).len() } else { out.len() };
            out.insert_str(at, &trailer);
        }
        out
    }

    /// The `main` that wraps the pack's (renamed) one to copy matrix varyings from or to their
    /// column vectors; empty when the stage has no matrix varyings.
    fn main_wrapper(&self) -> String {
        if !self.needs_main_wrapper() {
            return String::new();
        }
        let initializers: String =
            self.global_initializers.iter().map(|name| format!(" {name} = {RESERVED_PREFIX}init_{name}();")).collect();
        let mut copies = String::new();
        for MatrixVarying { matrix, columns_in, member, column_ty, columns } in &self.matrix_varyings {
            let cols: Vec<String> = (0..*columns).map(|c| format!("{columns_in}{RESERVED_PREFIX}{member}_{c}")).collect();
            match self.stage {
                Stage::Vertex => {
                    for (c, col) in cols.iter().enumerate() {
                        write!(copies, " {col} = {column_ty}({matrix}[{c}]);").unwrap();
                    }
                }
                Stage::Fragment => {
                    let ty = format!("mat{columns}x{}", &column_ty[3..]);
                    write!(copies, " {matrix} = {ty}({});", cols.join(", ")).unwrap();
                }
            }
        }
        match self.stage {
            Stage::Vertex => format!(" void main() {{{initializers} {RESERVED_PREFIX}main();{copies} }}"),
            Stage::Fragment => format!(" void main() {{{initializers}{copies} {RESERVED_PREFIX}main(); }}"),
        }
    }
}

struct Parameter {
    tokens: Vec<usize>,
    /// Combined sampler type and parameter name, for sampler parameters.
    sampler: Option<(String, String)>,
}

/// The text that replaces a use of a combined sampler: the constructed combined sampler, or both
/// halves when the use is an argument for a sampler parameter.
fn combined_use(lowered: &str, ty: &str, pass_both: bool) -> String {
    if pass_both {
        format!("{lowered}, {RESERVED_PREFIX}sampler_{lowered}")
    } else {
        format!("{ty}({lowered}, {RESERVED_PREFIX}sampler_{lowered})")
    }
}

/// The GLSL names a message about lowered text means: `tp_FragData1` → `gl_FragData[1]`, `tp_sampler_x` → `x`, `tp_Vertex` → `gl_Vertex`, …
pub fn unlower_names(message: &str) -> String {
    /// The legacy built-in a reserved name stands for, given the part after the prefix
    /// (`gl_Vertex` for `Vertex`).
    fn builtin_of_reserved(name: &str) -> Option<&'static str> {
        let reserved = |r: &str| r.strip_prefix(RESERVED_PREFIX) == Some(name);
        LEGACY_INPUTS
            .iter()
            .find(|i| reserved(i.1))
            .map(|i| i.0)
            .or_else(|| LEGACY_VARYINGS.iter().find(|v| reserved(v.2)).map(|v| v.0))
            .or_else(|| LEGACY_MATRICES.iter().find(|m| reserved(m.1)).map(|m| m.0))
            .or(match name {
                "Fog" => Some("gl_Fog"),
                "FogParameters" => Some("gl_FogParameters"),
                _ => None,
            })
    }
    let prefix = RESERVED_PREFIX;
    let mut out = String::with_capacity(message.len());
    let mut rest = message;
    while let Some(at) = rest.find(prefix) {
        let word_start = at == 0 || !rest.as_bytes()[at - 1].is_ascii_alphanumeric() && rest.as_bytes()[at - 1] != b'_';
        out.push_str(&rest[..at]);
        let tail = &rest[at + prefix.len()..];
        let len = tail.find(|c: char| !c.is_ascii_alphanumeric() && c != '_').unwrap_or(tail.len());
        let name = &tail[..len];
        if !word_start {
            out.push_str(prefix);
            out.push_str(name);
        } else if let Some(n) = name.strip_prefix("FragData") {
            out.push_str(&format!("gl_FragData[{n}]"));
        } else if let Some(n) = name.strip_prefix("TexCoord").filter(|n| !n.is_empty()) {
            out.push_str(&format!("gl_TexCoord[{n}]"));
        } else if let Some(builtin) = builtin_of_reserved(name) {
            out.push_str(builtin);
        } else if name == "main" {
            out.push_str("main");
        } else if let Some(x) =
            ["sampler_", "bool_", "kw_", "init_", "scalar_", "rt_", "struct_"].iter().find_map(|p| name.strip_prefix(p))
        {
            out.push_str(x);
        } else {
            // Not a name the lowering makes: the pack's own identifier, as written.
            out.push_str(prefix);
            out.push_str(name);
        }
        rest = &tail[len..];
    }
    out.push_str(rest);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A struct type hidden by a local variable of its name (rre36/glsl_rshader's `maskData`):
    /// the type takes a name of its own, the variable keeps its own, and naga reads the stage.
    #[test]
    fn a_struct_type_hidden_by_a_variable_takes_its_own_name() {
        let text = "#version 330\nstruct maskData { bool terrain; } mask;\nuniform float level;\nout vec4 colour;\nvoid main() {\n    maskData m = maskData(true);\n    float maskData = level;\n    mask.terrain = (maskData > 0.125);\n    colour = vec4(m.terrain && mask.terrain);\n}\n";
        let lowered = lower(text, Stage::Fragment, &VaryingLayout::default(), false).expect("lowers").text;
        assert!(lowered.contains("struct tp_struct_maskData {") && lowered.contains("tp_struct_maskData m = tp_struct_maskData(true)"), "{lowered}");
        assert!(lowered.contains("float maskData = ") && lowered.contains("(maskData > 0.125)"), "{lowered}");
        let module = naga::front::glsl::Frontend::default().parse(&naga::front::glsl::Options::from(naga::ShaderStage::Fragment), &lowered);
        assert!(module.is_ok(), "{module:?}\n{lowered}");
    }

    #[test]
    fn reserved_names_read_as_the_packs() {
        assert_eq!(unlower_names("found Identifier(\"tp_FragData0\")"), "found Identifier(\"gl_FragData[0]\")");
        assert_eq!(unlower_names("tp_sampler_colortex0 and tp_Vertex, tp_TexCoord3; stp_x"), "colortex0 and gl_Vertex, gl_TexCoord[3]; stp_x");
        assert_eq!(unlower_names("`tp_bool_heavyFog` is read"), "`heavyFog` is read");
        assert_eq!(unlower_names("tp_ModelViewMatrix * tp_FogFragCoord, tp_Fog.color, tp_rt_textureLod"), "gl_ModelViewMatrix * gl_FogFragCoord, gl_Fog.color, textureLod");
        // A pack's own identifier that happens to start with the prefix stays as written.
        assert_eq!(unlower_names("Unknown variable: tp_missing"), "Unknown variable: tp_missing");
    }

    /// Found by the `lower` fuzz target: brackets with a line break between them, sized by
    /// the lowering.
    #[test]
    fn local_constants_in_array_sizes_are_written_out_within_a_bound() {
        let text = "#version 430\nvoid main() {\n    const int side = 2;\n    const int cells = side * side;\n    float w[cells];\n}\n";
        let lowered = lower(text, Stage::Fragment, &VaryingLayout::default(), false).unwrap();
        assert!(lowered.text.contains("float w[int(int(2) * int(2))];"), "{}", lowered.text);
        // Each constant read twice in the next would double the text 64 times over.
        let mut chain = String::from("#version 430\nvoid main() {\n    const int c0 = 2;\n");
        for k in 1..64 {
            chain.push_str(&format!("    const int c{k} = c{} * c{};\n", k - 1, k - 1));
        }
        chain.push_str("    float w[c63];\n}\n");
        let lowered = lower(&chain, Stage::Fragment, &VaryingLayout::default(), false).unwrap();
        assert!(lowered.text.len() < chain.len() + 2 * MAX_INLINED_CONSTANT_BYTES, "{} bytes", lowered.text.len());
        assert_eq!(lowered.text.lines().count(), chain.lines().count());
    }

    #[test]
    fn a_replacement_keeps_the_line_breaks_it_covers() {
        let text = "#version 120\nconst float weights[\n] = float[\n](1.0, 2.0);\nvoid main() { gl_FragColor = vec4(weights[1]); }\n";
        let lowered = lower(text, Stage::Fragment, &VaryingLayout::default(), false).unwrap();
        assert_eq!(lowered.text.matches('\n').count(), text.matches('\n').count(), "{}", lowered.text);
        let lowered = lower("#version 3\n[\n]l[](", Stage::Fragment, &VaryingLayout::default(), false);
        assert!(lowered.is_err() || lowered.unwrap().text.matches('\n').count() == 2);
    }

    /// Found by the `lower` fuzz target: a stage that ends on its `#version` line, with no
    /// line break after it.
    #[test]
    fn a_stage_that_is_only_its_version_line_keeps_its_line_count() {
        for text in ["#version 120", "#version 120 \u{FFFD}\u{FFFD}", "#version 330 compatibility\n"] {
            if let Ok(lowered) = lower(text, Stage::Fragment, &VaryingLayout::default(), false) {
                assert_eq!(lowered.text.matches('\n').count(), text.matches('\n').count(), "{text:?} -> {:?}", lowered.text);
            }
        }
    }

    #[test]
    fn outputs_declared_beside_gl_frag_color_and_never_written_are_dropped() {
        let text = "#version 430 compatibility\nlayout(location = 0) out vec4 unused0;\nlayout(location = 1) out vec4 unused1;\n\
                    void main() { gl_FragColor = vec4(1.0); }\n";
        let lowered = lower(text, Stage::Fragment, &VaryingLayout::default(), false).unwrap();
        assert!(!lowered.text.contains("unused0") && !lowered.text.contains("unused1"), "{}", lowered.text);
        assert_eq!(lowered.interface.outputs.len(), 1, "{:?}", lowered.interface.outputs);
        assert_eq!(lowered.text.matches('\n').count(), text.matches('\n').count());
    }

    #[test]
    fn the_fragment_depth_read_and_never_written_is_the_fragments_own() {
        let text = "#version 450 compatibility\nlayout(location = 0) out vec4 colour;\nvoid main() { colour = vec4(gl_FragDepth - 0.5); }\n";
        let lowered = lower(text, Stage::Fragment, &VaryingLayout::default(), false).unwrap();
        assert!(lowered.text.contains("vec4(gl_FragCoord.z - 0.5)") && !lowered.text.contains("gl_FragDepth"), "{}", lowered.text);
        let written = text.replace("colour = vec4(gl_FragDepth - 0.5);", "gl_FragDepth = 0.5; colour = vec4(gl_FragDepth);");
        assert!(lower(&written, Stage::Fragment, &VaryingLayout::default(), false).unwrap().text.contains("gl_FragDepth = 0.5"));
    }

    #[test]
    fn nvidia_only_functions_are_read_leniently() {
        let text = "#version 120\nuniform sampler2D gaux4;\nsampler2D depthSource() {\n    return gaux4;\n}\n\
                    vec2 move(in vec2 at = vec2(0.5), in float by = 1.0) { return at * by; }\n\
                    void main() { gl_FragColor = texture2D(depthSource(), move()) + vec4(move(vec2(1.0)), move(vec2(1.0), 2.0)); }\n";
        let lowered = lower(text, Stage::Fragment, &VaryingLayout::default(), true).unwrap();
        assert!(!lowered.text.contains("depthSource") && !lowered.text.contains("= vec2(0.5)"), "{}", lowered.text);
        assert!(lowered.text.contains("move(vec2 ( 0.5 ), 1.0)") && lowered.text.contains("move(vec2(1.0), 1.0)"), "{}", lowered.text);
        assert_eq!(lowered.text.matches('\n').count(), text.matches('\n').count());
        // Read strictly, they stay for naga to refuse.
        assert!(lower(text, Stage::Fragment, &VaryingLayout::default(), false).unwrap().text.contains("depthSource"));
    }

    #[test]
    fn a_vector_made_from_a_bool_converts_it_first() {
        let text = "#version 330\nout vec4 color;\nuniform float r;\nvoid main() { vec3 disk = vec3(r < 0.5); ivec2 on = ivec2(!(r > 1.0)); \
                    vec2 kept = vec2(r < 0.5 ? 1.0 : 0.0); color = vec4(disk, float(on.x) + kept.x); }\n";
        let lowered = lower(text, Stage::Fragment, &VaryingLayout::default(), false).unwrap();
        assert!(lowered.text.contains("vec3(float(r < 0.5))"), "{}", lowered.text);
        assert!(lowered.text.contains("ivec2(int(!(r > 1.0)))"), "{}", lowered.text);
        assert!(lowered.text.contains("vec2(r < 0.5 ? 1.0 : 0.0)"), "{}", lowered.text);
        assert_eq!(lowered.text.matches('\n').count(), text.matches('\n').count());
    }

    #[test]
    fn struct_and_matrix_varyings_take_a_location_per_member_and_column() {
        let vertex = "#version 400 compatibility\nstruct Inner { vec2 a[3]; };\nstruct Fog { vec3 color; mat3 basis; Inner inner; float density, height; };\n\
                      flat out Fog fog;\nout mat4 frame;\nout vec2 uv;\nvoid main() { gl_Position = vec4(0.0); }\n";
        let layout = VaryingLayout::for_program(&[(Stage::Vertex, vertex, 400)]).unwrap();
        // fog: 1 + 3 + 3 + 2 = 9 locations, frame: 4, in name order.
        assert_eq!(layout.locations, BTreeMap::from([("fog".to_string(), 0), ("frame".to_string(), 9), ("uv".to_string(), 13)]));
        // A member's bracket left open is malformed, and stops nothing.
        for broken in ["struct S { vec2 a[", "struct S { vec2 a[3; }; out S s;", "struct S { vec2 a[]; }; out S s;"] {
            let _ = VaryingLayout::for_program(&[(Stage::Vertex, broken, 400)]);
        }
    }

    #[test]
    fn interface_blocks_take_their_members_locations_beside_the_varyings_in_both_stages() {
        let vertex = "#version 430 compatibility\nout VertexData { vec4 color; flat int id; mat2 m; } v;\nout vec2 uv;\n\
                      void main() { v.color = vec4(1.0); v.id = 1; v.m = mat2(1.0); uv = vec2(0.0); gl_Position = vec4(0.0); }\n";
        let fragment = "#version 430 compatibility\nin VertexData { vec4 color; flat int id; mat2 m; } v;\nin vec2 uv;\n\
                        void main() { gl_FragColor = v.color * float(v.id) + vec4(uv, v.m[0]); }\n";
        let layout = VaryingLayout::for_program(&[(Stage::Vertex, vertex, 430), (Stage::Fragment, fragment, 430)]).unwrap();
        // color 1, id 1, m two columns: 4 locations, then uv.
        assert_eq!(layout.locations, BTreeMap::from([("block VertexData".to_string(), 0), ("uv".to_string(), 4)]));
        for (stage, text) in [(Stage::Vertex, vertex), (Stage::Fragment, fragment)] {
            let lowered = lower(text, stage, &layout, false).unwrap();
            assert!(lowered.text.contains("layout(location = 0) "), "{}", lowered.text);
            assert!(!lowered.text.contains(&format!("location = {INTERFACE_BLOCK_LOCATION}")), "{}", lowered.text);
        }
    }

    #[test]
    fn a_block_members_own_layout_is_blanked_and_its_type_still_counted() {
        let vertex = "#version 460 compatibility\nout VertexData { layout(location = 0) noperspective vec2 coord; layout(location = 1) mat2 m; } v;\n\
                      void main() { v.coord = vec2(0.0); v.m = mat2(1.0); gl_Position = vec4(0.0); }\n";
        let layout = VaryingLayout::for_program(&[(Stage::Vertex, vertex, 460)]).unwrap();
        assert_eq!(layout.locations, BTreeMap::from([("block VertexData".to_string(), 0)]));
        let lowered = lower(vertex, Stage::Vertex, &layout, false).unwrap();
        assert!(!lowered.text.contains("layout(location = 1)"), "{}", lowered.text);
        assert_eq!(lowered.text.matches('\n').count(), vertex.matches('\n').count());
    }

    #[test]
    fn trinary_minmax_gets_stand_ins_only_where_the_extension_is_enabled_and_the_stage_has_none() {
        let enabled = "#version 450\n#extension GL_AMD_shader_trinary_minmax : require\nout vec4 color;\nuniform vec3 v;\n\
                       void main() { color = vec4(max3(v.x, v.y, v.z), min3(v, v, v)); }\n";
        let lowered = lower(enabled, Stage::Fragment, &VaryingLayout::default(), false).unwrap();
        assert!(lowered.text.contains("float max3(float a, float b, float c) { return max(max(a, b), c); }"), "{}", lowered.text);
        assert!(lowered.text.contains("vec3 min3(vec3 a, vec3 b, vec3 c) { return min(min(a, b), c); }"), "{}", lowered.text);
        let own = "#version 450\n#extension GL_AMD_shader_trinary_minmax : enable\nout vec4 color;\nuniform vec3 v;\n\
                   float max3(vec3 x) { return max(max(x.x, x.y), x.z); }\nvoid main() { color = vec4(max3(v)); }\n";
        assert!(!lower(own, Stage::Fragment, &VaryingLayout::default(), false).unwrap().text.contains("max3(float a"));
        let without = "#version 450\nout vec4 color;\nuniform vec3 v;\nvoid main() { color = vec4(max3(v.x, v.y, v.z)); }\n";
        assert!(!lower(without, Stage::Fragment, &VaryingLayout::default(), false).unwrap().text.contains("max3(float a"));
    }

    /// Found by the `lower` fuzz target: a stage lowered alone uses legacy varyings the layout
    /// was not built with.
    #[test]
    fn a_legacy_varying_outside_the_layout_gets_a_location_of_its_own() {
        let text = "#version 120\nvoid main() {\n    gl_Position = ftransform();\n    gl_FrontColor = gl_Color;\n    gl_TexCoord[0] = gl_MultiTexCoord0;\n}\n";
        let lowered = lower(text, Stage::Vertex, &VaryingLayout::default(), false).unwrap();
        assert_eq!(lowered.text.matches('\n').count(), text.matches('\n').count());
        assert!(lowered.text.contains("out vec4 tp_FrontColor;") && lowered.text.contains("out vec4 tp_TexCoord0;"), "{}", lowered.text);
    }

    /// A bias in a vertex stage: an error in GLSL's terms, and in a lenient stage the level,
    /// as NVIDIA reads it.
    #[test]
    fn a_bias_in_a_vertex_stage_is_the_level_when_read_leniently() {
        let text = "#version 120\nuniform sampler2D tex;\nvoid main() { gl_Position = texture2D(tex, vec2(0.5), 2.0) + texture(tex, vec2(0.5), 1.0) + texture2D(tex, vec2(0.5)); }\n";
        let error = lower(text, Stage::Vertex, &VaryingLayout::default(), false).unwrap_err();
        assert!(error.message.starts_with("texture2D() takes a bias only in fragment shaders"), "{}", error.message);
        let lowered = lower(text, Stage::Vertex, &VaryingLayout::default(), true).unwrap();
        assert_eq!(lowered.text.matches("vec2(0.5), 2.0)").count(), 1, "{}", lowered.text);
        assert_eq!(lowered.text.matches("vec2(0.5), 1.0)").count(), 1, "{}", lowered.text);
        assert_eq!(lowered.text.matches("vec2(0.5), 0.0)").count(), 1, "{}", lowered.text);
        assert_eq!(lowered.text.matches("textureLod(").count(), 3, "{}", lowered.text);
    }
}
