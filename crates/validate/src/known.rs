//! The uniforms and samplers OptiFine sets, by name (OptiFine's `shaders.txt`). A name not here
//! compiles and links but OptiFine never sets it: a uniform reads 0, a sampler reads unit 0.

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

/// The type OptiFine sets for a known uniform.
pub fn uniform_type(name: &str) -> Option<&'static str> {
    UNIFORMS.iter().find(|(n, _)| *n == name).map(|(_, t)| *t)
}

pub fn is_sampler(name: &str) -> bool {
    SAMPLERS.contains(&name)
}
