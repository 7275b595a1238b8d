//! The uniforms and samplers OptiFine sets, by name (OptiFine's `shaders.txt`), and those Iris
//! sets besides (Iris's `uniforms/` sources). A name not here compiles and links but the loader
//! never sets it: a uniform reads 0, a sampler reads unit 0.

use crate::loader::Loader;

/// Uniforms and their GLSL types.
pub const UNIFORMS: &[(&str, &str)] = &[
    ("heldItemId", "int"), ("heldItemId2", "int"), ("heldBlockLightValue", "int"), ("heldBlockLightValue2", "int"),
    ("fogMode", "int"), ("fogShape", "int"), ("fogStart", "float"), ("fogEnd", "float"), ("fogDensity", "float"),
    ("fogColor", "vec3"), ("skyColor", "vec3"), ("worldTime", "int"), ("worldDay", "int"), ("moonPhase", "int"),
    ("frameCounter", "int"), ("frameTime", "float"), ("frameTimeCounter", "float"), ("sunAngle", "float"),
    ("shadowAngle", "float"), ("rainStrength", "float"), ("aspectRatio", "float"), ("viewWidth", "float"),
    ("viewHeight", "float"), ("near", "float"), ("far", "float"), ("sunPosition", "vec3"), ("moonPosition", "vec3"),
    ("shadowLightPosition", "vec3"), ("upPosition", "vec3"), ("cameraPosition", "vec3"),
    ("previousCameraPosition", "vec3"), ("gbufferModelView", "mat4"), ("gbufferModelViewInverse", "mat4"),
    ("gbufferPreviousModelView", "mat4"), ("gbufferProjection", "mat4"), ("gbufferProjectionInverse", "mat4"),
    ("gbufferPreviousProjection", "mat4"), ("shadowProjection", "mat4"), ("shadowProjectionInverse", "mat4"),
    ("shadowModelView", "mat4"), ("shadowModelViewInverse", "mat4"), ("wetness", "float"), ("eyeAltitude", "float"),
    ("eyeBrightness", "ivec2"), ("eyeBrightnessSmooth", "ivec2"), ("terrainTextureSize", "ivec2"),
    ("terrainIconSize", "int"), ("isEyeInWater", "int"), ("nightVision", "float"), ("blindness", "float"),
    ("screenBrightness", "float"), ("hideGUI", "int"), ("centerDepthSmooth", "float"), ("atlasSize", "ivec2"),
    ("spriteBounds", "vec4"), ("entityColor", "vec4"), ("entityId", "int"), ("blockEntityId", "int"),
    ("blendFunc", "ivec4"), ("instanceId", "int"), ("playerMood", "float"), ("renderStage", "int"),
    ("bossBattle", "int"), ("darknessFactor", "float"), ("darknessLightFactor", "float"),
    ("modelViewMatrix", "mat4"), ("modelViewMatrixInverse", "mat4"), ("projectionMatrix", "mat4"),
    ("projectionMatrixInverse", "mat4"), ("textureMatrix", "mat4"), ("normalMatrix", "mat3"),
    ("chunkOffset", "vec3"), ("modelOffset", "vec3"), ("alphaTestRef", "float"),
];

/// Sampler names OptiFine binds (aliases included).
pub const SAMPLERS: &[&str] = &[
    "texture", "gtexture", "tex", "lightmap", "normals", "specular", "shadow", "watershadow", "shadowtex0",
    "shadowtex1", "depthtex0", "depthtex1", "depthtex2", "gdepthtex", "gcolor", "gdepth", "gnormal", "composite",
    "gaux1", "gaux2", "gaux3", "gaux4", "colortex0", "colortex1", "colortex2", "colortex3", "colortex4", "colortex5",
    "colortex6", "colortex7", "colortex8", "colortex9", "colortex10", "colortex11", "colortex12", "colortex13",
    "colortex14", "colortex15", "shadowcolor", "shadowcolor0", "shadowcolor1", "noisetex",
];

/// Uniforms Iris sets that OptiFine does not, and their GLSL types (Iris's `bool` ones are set
/// with glUniform1i, so an `int` declaration reads them too).
pub const IRIS_UNIFORMS: &[(&str, &str)] = &[
    ("biome", "int"), ("biome_category", "int"), ("biome_precipitation", "int"), ("rainfall", "float"), ("temperature", "float"),
    ("cameraPositionFract", "vec3"), ("cameraPositionInt", "ivec3"), ("previousCameraPositionFract", "vec3"),
    ("previousCameraPositionInt", "ivec3"), ("constantMood", "float"), ("currentRenderedItemId", "int"), ("dhFarPlane", "float"),
    ("dhNearPlane", "float"), ("dhRenderDistance", "int"), ("dhProjection", "mat4"), ("dhProjectionInverse", "mat4"),
    ("dhPreviousProjection", "mat4"), ("gtextureSize", "ivec2"), ("isRightHanded", "bool"), ("is_burning", "bool"),
    ("is_hurt", "bool"), ("is_invisible", "bool"), ("is_on_ground", "bool"), ("is_sneaking", "bool"), ("is_sprinting", "bool"),
    ("pi", "float"), ("heldBlockLightColor", "vec3"), ("heldBlockLightColor2", "vec3"), ("ambientLight", "float"),
    ("bedrockLevel", "int"), ("cloudHeight", "float"), ("cloudTime", "float"), ("currentColorSpace", "int"),
    ("currentPlayerAir", "float"), ("currentPlayerArmor", "float"), ("currentPlayerHealth", "float"),
    ("currentPlayerHunger", "float"), ("maxPlayerAir", "float"), ("maxPlayerArmor", "float"), ("maxPlayerHealth", "float"),
    ("maxPlayerHunger", "float"), ("currentSelectedBlockId", "int"), ("currentSelectedBlockPos", "vec3"), ("eyePosition", "vec3"),
    ("firstPersonCamera", "bool"), ("hasCeiling", "bool"), ("hasSkylight", "bool"), ("heightLimit", "int"),
    ("logicalHeightLimit", "int"), ("isSpectator", "bool"), ("lightningBoltPosition", "vec4"), ("playerBodyVector", "vec3"),
    ("playerLookVector", "vec3"), ("relativeEyePosition", "vec3"), ("thunderStrength", "float"), ("currentDate", "ivec3"),
    ("currentTime", "ivec3"), ("currentYearTime", "ivec2"),
];

/// Samplers Iris binds that OptiFine does not: Distant Horizons' depth buffers.
pub const IRIS_SAMPLERS: &[&str] = &["dhDepthTex", "dhDepthTex0", "dhDepthTex1"];

/// The type OptiFine sets for a known uniform.
pub fn uniform_type(name: &str) -> Option<&'static str> {
    UNIFORMS.iter().find(|(n, _)| *n == name).map(|(_, t)| *t)
}

/// The type `loader` sets for a uniform it knows.
pub fn uniform_type_for(name: &str, loader: Loader) -> Option<&'static str> {
    let iris = || IRIS_UNIFORMS.iter().find(|(n, _)| *n == name).map(|(_, t)| *t);
    uniform_type(name).or_else(|| if loader == Loader::Iris { iris() } else { None })
}

/// Whether `loader` binds a sampler of this name.
pub fn is_sampler_for(name: &str, loader: Loader) -> bool {
    is_sampler(name) || (loader == Loader::Iris && IRIS_SAMPLERS.contains(&name))
}

/// The loader's name as messages give it.
pub fn loader_name(loader: Loader) -> &'static str {
    if loader == Loader::Iris { "Iris" } else { "OptiFine" }
}

/// Image names OptiFine and Iris bind for `imageLoad`/`imageStore` (`colorimg0-15`,
/// `shadowcolorimg0-1`).
pub fn is_image(name: &str) -> bool {
    let numbered = |prefix: &str, count: u32| {
        name.strip_prefix(prefix).and_then(|n| (!n.starts_with('0') || n == "0").then(|| n.parse::<u32>().ok()).flatten()).is_some_and(|n| n < count)
    };
    numbered("colorimg", 16) || numbered("shadowcolorimg", 2)
}

pub fn is_sampler(name: &str) -> bool {
    SAMPLERS.contains(&name)
}

/// Why `sampler` reads something else than its name says in `program` (OptiFine binds units by
/// program group), or `None` when it is available there.
pub fn sampler_unavailable(program: &str, sampler: &str) -> Option<&'static str> {
    let gbuffers_style = crate::programs::binds_as_gbuffers(program);
    let low_colortex = matches!(sampler, "colortex0" | "colortex1" | "colortex2" | "colortex3" | "gcolor" | "gdepth" | "gnormal" | "composite");
    let atlas_units = matches!(sampler, "texture" | "gtexture" | "tex" | "lightmap" | "normals" | "specular");
    if gbuffers_style && low_colortex {
        Some("gbuffers and shadow programs cannot read colortex0-3: units 0-3 hold the atlas, lightmap, normals and specular maps there")
    } else if !gbuffers_style && atlas_units {
        Some("only gbuffers and shadow programs have the atlas, lightmap, normals and specular maps; here that unit holds a colortex buffer")
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samplers_by_program_group() {
        assert!(sampler_unavailable("gbuffers_water", "colortex1").is_some());
        assert!(sampler_unavailable("gbuffers_water", "colortex4").is_none());
        assert!(sampler_unavailable("dh_water", "lightmap").is_none());
        assert!(sampler_unavailable("gbuffers_water", "gtexture").is_none());
        assert!(sampler_unavailable("composite2", "lightmap").is_some());
        assert!(sampler_unavailable("composite2", "colortex1").is_none());
        assert!(sampler_unavailable("shadow", "tex").is_none());
        assert!(sampler_unavailable("shadow_water", "tex").is_none());
    }

    #[test]
    fn images_by_name() {
        assert!(is_image("colorimg0") && is_image("colorimg15") && is_image("shadowcolorimg1"));
        assert!(!is_image("colorimg16") && !is_image("colorimg01") && !is_image("shadowcolorimg2") && !is_image("img"));
    }
}
