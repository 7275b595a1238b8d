//! Uniform values by their OptiFine names, and filling a lowered stage's `tp_Uniforms` block
//! by member name through naga's reflection of the module (offsets, strides and the block
//! size come from naga's layouter, never from a hand-written std140 table).
//!
//! A member the harness has no value for is an error naming it, never a silent zero.

use std::borrow::Cow;
use std::collections::BTreeMap;

use glam::{DMat3, DMat4, DVec3, DVec4};
use naga::{AddressSpace, ScalarKind, TypeInner, VectorSize};

use crate::HarnessError;
use tidepack_glsl::lower::{BOOL_UNIFORM_PREFIX, Interface, ResourceKind};
use tidepack_scene::mesh;
use tidepack_scene::scene::Scene;
use tidepack_loader::shadow::{ShadowSettings, SunPath};
pub use tidepack_loader::uniform_value::{Kind, Value};
use tidepack_pack::specialise::Specialisation;

/// Which pass the values are for: the legacy matrices differ.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pass {
    /// gbuffers: gl_ModelViewMatrix = gbufferModelView (positions relative to the camera).
    Gbuffers,
    /// Full-screen: a unit quad under an orthographic projection.
    Fullscreen,
    /// The shadow pass: gl_ModelViewMatrix = shadowModelView, gl_ProjectionMatrix =
    /// shadowProjection (positions relative to the camera, as in gbuffers).
    Shadow,
    /// The sun and the moon: as gbuffers, with the game's fog off (`fogMode` 0).
    Celestial,
    /// Distant Horizons' LODs (dh_terrain, dh_water): as gbuffers, under dhProjection, with
    /// the lightmap coordinates already in 0..1 (Iris's identity gl_TextureMatrix[1]).
    DistantHorizons,
}

/// Legacy matrices as the OpenGL compatibility API holds them for a pass.
#[derive(Clone, Copy, Debug)]
pub struct LegacyMatrices {
    pub model_view: DMat4,
    pub projection: DMat4,
    /// gl_TextureMatrix[0] and [1].
    pub texture: [DMat4; 2],
}

/// The lightmap texture matrix of vanilla Minecraft: raw 0..240 → 1/32..31/32.
pub fn lightmap_matrix() -> DMat4 {
    DMat4::from_translation(DVec3::splat(8.0 / 256.0)) * DMat4::from_scale(DVec3::new(1.0 / 256.0, 1.0 / 256.0, 1.0 / 256.0))
}

/// The legacy matrices of `pass`; the shadow pass's are `shadow_camera` (model-view,
/// projection).
fn legacy_matrices(scene: &Scene, pass: Pass, shadow_camera: (DMat4, DMat4)) -> LegacyMatrices {
    let (model_view, projection) = match pass {
        Pass::Gbuffers | Pass::Celestial => (scene.model_view(), scene.projection()),
        Pass::DistantHorizons => (scene.model_view(), scene.lod_projection()),
        Pass::Fullscreen => (DMat4::IDENTITY, DMat4::orthographic_rh_gl(0.0, 1.0, 0.0, 1.0, -1.0, 1.0)),
        Pass::Shadow => shadow_camera,
    };
    let texture = match pass {
        Pass::Gbuffers | Pass::Shadow | Pass::Celestial => [DMat4::IDENTITY, lightmap_matrix()],
        Pass::Fullscreen | Pass::DistantHorizons => [DMat4::IDENTITY, DMat4::IDENTITY],
    };
    LegacyMatrices { model_view, projection, texture }
}

/// `fogMode` for the game's linear distance fog.
const GL_LINEAR: i64 = 0x2601;

/// Every uniform the harness can fill for a scene and pass, by its OptiFine name, with
/// OptiFine's default shadow camera; the legacy matrices under their lowered names
/// (`tp_ModelViewMatrix`, …).
pub fn values(scene: &Scene, pass: Pass) -> BTreeMap<String, Value> {
    values_with_shadow(scene, pass, &ShadowSettings::default())
}

/// [`values`] for a pack whose shadow camera `shadow` describes.
pub fn values_with_shadow(scene: &Scene, pass: Pass, shadow: &ShadowSettings) -> BTreeMap<String, Value> {
    let mut v = BTreeMap::new();
    let mut put = |name: &str, value: Value| {
        v.insert(name.to_string(), value);
    };
    let model_view = scene.model_view();
    let projection = scene.projection();
    let camera = scene.camera_position();
    let sun_world = scene.sun_direction() * 100.0;
    let to_view = |d: DVec3| model_view.transform_vector3(d);
    let sun = to_view(sun_world);
    let moon = -sun;
    put("gbufferModelView", Value::mat4(model_view));
    put("gbufferModelViewInverse", Value::mat4(model_view.inverse()));
    put("gbufferProjection", Value::mat4(projection));
    put("gbufferProjectionInverse", Value::mat4(projection.inverse()));
    put("gbufferPreviousModelView", Value::mat4(model_view));
    put("gbufferPreviousProjection", Value::mat4(projection));
    let (lod_distance, lod_near, lod_far) = scene.lod_planes();
    let lod_projection = scene.lod_projection();
    put("dhProjection", Value::mat4(lod_projection));
    put("dhProjectionInverse", Value::mat4(lod_projection.inverse()));
    put("dhPreviousProjection", Value::mat4(lod_projection));
    put("dhNearPlane", Value::float(lod_near));
    put("dhFarPlane", Value::float(lod_far));
    put("dhRenderDistance", Value::int(lod_distance.round() as i64));
    put("cameraPosition", Value::vec3(camera));
    put("previousCameraPosition", Value::vec3(camera));
    put("eyeAltitude", Value::float(camera.y));
    put("near", Value::float(scene.camera.near));
    put("far", Value::float(scene.camera.far));
    put("viewWidth", Value::float(scene.width() as f64));
    put("viewHeight", Value::float(scene.height() as f64));
    put("aspectRatio", Value::float(scene.width() as f64 / scene.height() as f64));
    let ticks = scene.time.world_time.rem_euclid(24000);
    put("worldTime", Value::int(ticks as i64));
    put("worldDay", Value::int((scene.time.world_time / 24000) as i64));
    put("moonPhase", Value::int(0));
    put("frameTimeCounter", Value::float(scene.time.frame_time_counter));
    put("frameTime", Value::float(1.0 / 60.0));
    put("frameCounter", Value::int(0));
    put("isEyeInWater", Value::int(if scene.eye_in_water() { 1 } else { 0 }));
    put("sunPosition", Value::vec3(sun));
    put("moonPosition", Value::vec3(moon));
    put("shadowLightPosition", Value::vec3(if sun_world.y >= 0.0 { sun } else { moon }));
    let sun_path = SunPath::of_sun_direction(scene.sun_direction());
    put("sunAngle", Value::float(sun_path.sun_angle()));
    put("shadowAngle", Value::float(sun_path.shadow_angle()));
    let shadow_camera = (sun_path.shadow_model_view(shadow.interval, camera), shadow.projection());
    put("shadowModelView", Value::mat4(shadow_camera.0));
    put("shadowModelViewInverse", Value::mat4(shadow_camera.0.inverse()));
    put("shadowProjection", Value::mat4(shadow_camera.1));
    put("shadowProjectionInverse", Value::mat4(shadow_camera.1.inverse()));
    put("upPosition", Value::vec3(to_view(DVec3::new(0.0, 100.0, 0.0))));
    put("skyColor", Value::vec3(DVec3::from(scene.sky.sky_color)));
    put("fogColor", Value::vec3(DVec3::from(scene.sky.fog_color)));
    // The game's linear fog as the legacy `gl_Fog` state holds it: from 0.75·far to far, the
    // curve the scenes' fog follows.
    let (fog_start, fog_end) = (0.75 * scene.camera.far, scene.camera.far);
    let [r, g, b] = scene.sky.fog_color;
    put("tp_Fog.color", Value::vec4(DVec4::new(r, g, b, 1.0)));
    put("tp_Fog.density", Value::float(1.0));
    put("tp_Fog.start", Value::float(fog_start));
    put("tp_Fog.end", Value::float(fog_end));
    put("tp_Fog.scale", Value::float(1.0 / (fog_end - fog_start)));
    // The same fog under the names OptiFine and Iris give it as uniforms.
    put("fogStart", Value::float(fog_start));
    put("fogEnd", Value::float(fog_end));
    put("fogDensity", Value::float(1.0));
    put("rainStrength", Value::float(scene.sky.rain_strength));
    put("wetness", Value::float(scene.sky.rain_strength));
    put("nightVision", Value::float(0.0));
    put("blindness", Value::float(0.0));
    put("darknessFactor", Value::float(0.0));
    put("screenBrightness", Value::float(1.0));
    put("eyeBrightness", Value::ivec2(0, 240));
    put("eyeBrightnessSmooth", Value::ivec2(0, 240));
    put("hideGUI", Value::int(1));
    // The scenes' player holds nothing in either hand: no item of item.properties (-1), no
    // light; and is not in a cave mood.
    put("heldItemId", Value::int(-1));
    put("heldItemId2", Value::int(-1));
    put("heldBlockLightValue", Value::int(0));
    put("heldBlockLightValue2", Value::int(0));
    put("playerMood", Value::float(0.0));
    // The scenes are set in a plains biome: its legacy id, category (CAT_PLAINS), rain
    // (PPT_RAIN), temperature and rainfall as the game defines them.
    put("biome", Value::int(1));
    put("biome_category", Value::int(5));
    put("biome_precipitation", Value::int(1));
    put("temperature", Value::float(0.8));
    put("rainfall", Value::float(0.4));
    // The game's fog is on (GL_LINEAR), but for the sun and moon; the pack's programs apply it.
    put("fogMode", Value::int(if pass == Pass::Celestial { 0 } else { GL_LINEAR }));
    // The scenes' player as the game has it (the values Iris and OptiFine document): a
    // right-handed survival player seen in first person, on the ground, at full health, hunger
    // and air, without armour; no entity, block entity or item being drawn (-1 each); no
    // lightning, thunder, boss fight or darkness.
    let forward = model_view.inverse().transform_vector3(DVec3::NEG_Z).normalize();
    let camera_int = camera.floor();
    for (name, value) in [
        ("entityId", Value::int(-1)),
        ("blockEntityId", Value::int(-1)),
        ("currentRenderedItemId", Value::int(-1)),
        ("entityColor", Value::vec4(DVec4::ZERO)),
        ("instanceId", Value::int(0)),
        ("bossBattle", Value::int(0)),
        ("darknessLightFactor", Value::float(0.0)),
        ("thunderStrength", Value::float(0.0)),
        ("lightningBoltPosition", Value::vec4(DVec4::ZERO)),
        ("currentPlayerHealth", Value::float(1.0)),
        ("maxPlayerHealth", Value::float(20.0)),
        ("currentPlayerHunger", Value::float(1.0)),
        ("maxPlayerHunger", Value::float(20.0)),
        ("currentPlayerAir", Value::float(1.0)),
        ("maxPlayerAir", Value::float(300.0)),
        ("currentPlayerArmor", Value::float(0.0)),
        ("maxPlayerArmor", Value::float(50.0)),
        ("firstPersonCamera", Value::int(1)),
        ("isSpectator", Value::int(0)),
        ("isRightHanded", Value::int(1)),
        ("is_sneaking", Value::int(0)),
        ("is_sprinting", Value::int(0)),
        ("is_hurt", Value::int(0)),
        ("is_invisible", Value::int(0)),
        ("is_burning", Value::int(0)),
        ("is_on_ground", Value::int(1)),
        ("constantMood", Value::float(0.0)),
        ("eyePosition", Value::vec3(camera)),
        ("relativeEyePosition", Value::vec3(DVec3::ZERO)),
        ("playerLookVector", Value::vec3(forward)),
        ("playerBodyVector", Value::vec3(forward)),
        ("cameraPositionInt", Value::ivec3(camera_int.x as i64, camera_int.y as i64, camera_int.z as i64)),
        ("cameraPositionFract", Value::vec3(camera - camera_int)),
        ("previousCameraPositionInt", Value::ivec3(camera_int.x as i64, camera_int.y as i64, camera_int.z as i64)),
        ("previousCameraPositionFract", Value::vec3(camera - camera_int)),
        ("pi", Value::float(std::f64::consts::PI)),
        // sRGB, the first of Iris's colour spaces.
        ("currentColorSpace", Value::int(0)),
    ] {
        put(name, value);
    }
    // The overworld of 1.18 and later: bedrock at -64, 384 blocks high, clouds at 192, a sky
    // and no ceiling, no ambient light of its own.
    for (name, value) in [
        ("bedrockLevel", Value::int(-64)),
        ("heightLimit", Value::int(384)),
        ("logicalHeightLimit", Value::int(384)),
        ("cloudHeight", Value::float(192.0)),
        ("hasCeiling", Value::int(0)),
        ("hasSkylight", Value::int(1)),
        ("ambientLight", Value::float(0.0)),
    ] {
        put(name, value);
    }
    // The game's fog is a cylinder around the camera above water and a sphere in it.
    put("fogShape", Value::int(if scene.eye_in_water() { 0 } else { 1 }));
    // The block atlas's size where it is bound (the world's draws); zero where another texture
    // is (the sun and moon) or none (full-screen passes), as OptiFine sets it.
    let (atlas_width, atlas_height) = match pass {
        Pass::Gbuffers | Pass::Shadow | Pass::DistantHorizons => mesh::ATLAS_SIZE,
        Pass::Fullscreen | Pass::Celestial => (0, 0),
    };
    put("atlasSize", Value::ivec2(i64::from(atlas_width), i64::from(atlas_height)));
    // MC_RENDER_STAGE_NONE; a draw of the world gets its own ([`DrawUniforms`]).
    put("renderStage", Value::int(0));
    // OptiFine from 1.17 tests the alpha of gbuffers programs against 0.1 (cutout textures).
    put("alphaTestRef", Value::float(if pass == Pass::Fullscreen { 0.0 } else { 0.1 }));
    let legacy = legacy_matrices(scene, pass, shadow_camera);
    let mvp = legacy.projection * legacy.model_view;
    let normal = DMat3::from_mat4(legacy.model_view).inverse().transpose();
    let mut textures = [DMat4::IDENTITY; 8];
    textures[..2].copy_from_slice(&legacy.texture);
    put("tp_ModelViewMatrix", Value::mat4(legacy.model_view));
    put("tp_ProjectionMatrix", Value::mat4(legacy.projection));
    put("tp_ModelViewProjectionMatrix", Value::mat4(mvp));
    put("tp_NormalMatrix", Value::mat3(normal));
    put("tp_TextureMatrix", Value::mat4_array(&textures));
    put("tp_ModelViewMatrixInverse", Value::mat4(legacy.model_view.inverse()));
    put("tp_ProjectionMatrixInverse", Value::mat4(legacy.projection.inverse()));
    put("tp_ModelViewProjectionMatrixInverse", Value::mat4(mvp.inverse()));
    put("tp_TextureMatrixInverse", Value::mat4_array(&textures.map(|m| m.inverse())));
    // The 1.17+ core profile's names for the same matrices; its vertex positions are relative
    // to chunkOffset, the origin of the harness's camera-relative vertices.
    put("modelViewMatrix", Value::mat4(legacy.model_view));
    put("modelViewMatrixInverse", Value::mat4(legacy.model_view.inverse()));
    put("projectionMatrix", Value::mat4(legacy.projection));
    put("projectionMatrixInverse", Value::mat4(legacy.projection.inverse()));
    put("normalMatrix", Value::mat3(normal));
    put("textureMatrix", Value::mat4(legacy.texture[0]));
    put("chunkOffset", Value::vec3(DVec3::ZERO));
    v
}

/// The uniforms a loader sets for each draw of the world (OptiFine 1.17+ and Iris):
/// `renderStage`, the `MC_RENDER_STAGE_*` named `render_stage` (`SKY`, `SUN`, `TERRAIN_SOLID`,
/// …), and `entityId`, the drawn entity's id from entity.properties or -1.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DrawUniforms {
    pub render_stage: &'static str,
    pub entity_id: i32,
}

impl DrawUniforms {
    /// A draw of no entity.
    pub fn stage(render_stage: &'static str) -> DrawUniforms {
        DrawUniforms { render_stage, entity_id: -1 }
    }

    /// `values` with this draw's.
    pub fn applied(&self, values: &BTreeMap<String, Value>) -> BTreeMap<String, Value> {
        let number = tidepack_loader::macros::RENDER_STAGES.iter().position(|s| *s == self.render_stage).unwrap_or(0);
        let mut values = values.clone();
        values.insert("renderStage".to_string(), Value::int(number as i64));
        values.insert("entityId".to_string(), Value::int(i64::from(self.entity_id)));
        values
    }
}

/// The 1.17+ core profile's names for the legacy matrices, `renderStage` and `atlasSize`, which
/// differ between passes and draws: never folded.
const PER_PASS: [&str; 9] = [
    "atlasSize",
    "modelViewMatrix",
    "modelViewMatrixInverse",
    "projectionMatrix",
    "projectionMatrixInverse",
    "normalMatrix",
    "textureMatrix",
    "chunkOffset",
    "renderStage",
];

/// Uniforms that change from frame to frame while a scene is shown: never folded.
const ANIMATION_CLOCK: [&str; 3] = ["frameTimeCounter", "frameTime", "frameCounter"];

/// What `build --scene` folds: every OptiFine uniform the scene fixes (camera, matrices,
/// sky, `isEyeInWater`, ...), but not the animation clock, the legacy matrices under either
/// name nor `renderStage`, which differ between passes. `label` names the scene in the folded
/// lines.
pub fn scene_specialisation(scene: &Scene, label: &str) -> Specialisation {
    let constants = values(scene, Pass::Fullscreen)
        .into_iter()
        .filter(|(name, _)| !name.starts_with("tp_") && !ANIMATION_CLOCK.contains(&name.as_str()) && !PER_PASS.contains(&name.as_str()))
        .filter_map(|(name, value)| Some((name, value.glsl_initialiser()?)))
        .collect();
    Specialisation { scene: label.to_string(), constants }
}

/// The uniform block of a module, filled: (set, binding, bytes).
pub struct FilledBlock {
    pub group: u32,
    pub binding: u32,
    pub bytes: Vec<u8>,
    /// Member names in declaration order.
    pub members: Vec<String>,
}

/// The value a uniform's initializer gives where it is a literal or a constructor of literals
/// (`5`, `- 0.5`, `vec3 ( 1.0 , 0.5 , 0.0 )`, `true`), for a scalar or vector type `ty`; None
/// for anything else (an expression, a matrix).
pub fn initializer_value(ty: &str, text: &str) -> Option<Value> {
    let (kind, rows) = match ty {
        "float" => (Kind::Float, 1),
        "int" | "uint" | "bool" => (Kind::Int, 1),
        _ => {
            let (base, n) = ty.split_at(ty.len().checked_sub(1)?);
            let rows: u8 = n.parse().ok().filter(|n| (2..=4).contains(n))?;
            match base {
                "vec" => (Kind::Float, rows),
                "ivec" | "uvec" | "bvec" => (Kind::Int, rows),
                _ => return None,
            }
        }
    };
    let scalar = |text: &str| -> Option<f64> {
        let text = text.replace(' ', "");
        match text.as_str() {
            "true" => Some(1.0),
            "false" => Some(0.0),
            _ => text.trim_end_matches(['f', 'F', 'u', 'U']).parse::<f64>().ok().filter(|v| v.is_finite()),
        }
    };
    let text = text.trim();
    let args: Vec<&str> = match text.strip_prefix(ty).map(str::trim) {
        Some(call) => call.strip_prefix('(')?.strip_suffix(')')?.split(',').collect(),
        None => vec![text],
    };
    let mut data = args.iter().map(|a| scalar(a)).collect::<Option<Vec<f64>>>()?;
    if data.len() == 1 {
        data = vec![data[0]; rows as usize];
    }
    if kind == Kind::Int {
        data = data.into_iter().map(f64::trunc).collect();
    }
    (data.len() == rows as usize).then_some(Value { kind, columns: 1, rows, array: None, data })
}

/// `values` with the value of each uniform of `interface` that the loader leaves unset and that
/// its declaration initialises ([`initializer_value`]): what the driver holds there.
pub fn with_initializers<'v>(values: &'v BTreeMap<String, Value>, interface: &Interface) -> Cow<'v, BTreeMap<String, Value>> {
    let initial: Vec<(String, Value)> = interface
        .uniform_initializers
        .iter()
        .filter(|(name, _)| !values.contains_key(*name))
        .filter_map(|(name, text)| match interface.resources.get(name) {
            Some(ResourceKind::Uniform { ty }) => initializer_value(ty, text).map(|v| (name.clone(), v)),
            _ => None,
        })
        .collect();
    if initial.is_empty() {
        return Cow::Borrowed(values);
    }
    let mut with = values.clone();
    with.extend(initial);
    Cow::Owned(with)
}

/// Finds the module's uniform block and writes every member from `values`. `stage_name`
/// names the stage in errors; a member without a value is an error.
pub fn fill_block(module: &naga::Module, values: &BTreeMap<String, Value>, stage_name: &str) -> Result<Option<FilledBlock>, HarnessError> {
    let (block, missing) = fill(module, values, stage_name, true)?;
    if !missing.is_empty() {
        return Err(HarnessError::Uniform(format!(
            "{stage_name} declares uniform{} the harness cannot fill: {}",
            if missing.len() == 1 { "" } else { "s" },
            missing.join(", ")
        )));
    }
    Ok(block)
}

/// [`fill_block`], leaving zero the members without a value, or whose declared type is not the
/// type of the value (a loader's `glUniform` of the wrong type sets nothing), as a loader
/// leaves uniforms it does not set; returns their shipped names, with the type clash where
/// there is one.
pub fn fill_block_leaving_zero(
    module: &naga::Module,
    values: &BTreeMap<String, Value>,
    stage_name: &str,
) -> Result<(Option<FilledBlock>, Vec<String>), HarnessError> {
    fill(module, values, stage_name, false)
}

fn fill(
    module: &naga::Module,
    values: &BTreeMap<String, Value>,
    stage_name: &str,
    strict: bool,
) -> Result<(Option<FilledBlock>, Vec<String>), HarnessError> {
    let mut layouter = naga::proc::Layouter::default();
    layouter
        .update(module.to_ctx())
        .map_err(|e| HarnessError::Pack(format!("{stage_name}: naga cannot lay out the uniform block: {e}")))?;
    let mut found = None;
    for (_, global) in module.global_variables.iter() {
        if global.space != AddressSpace::Uniform {
            continue;
        }
        let Some(binding) = &global.binding else { continue };
        let TypeInner::Struct { members, span } = &module.types[global.ty].inner else {
            return Err(HarnessError::Unsupported(format!(
                "{stage_name}: uniform {} is not a block; the lowering puts loose uniforms in tp_Uniforms",
                global.name.as_deref().unwrap_or("?")
            )));
        };
        if found.is_some() {
            return Err(HarnessError::Unsupported(format!("{stage_name}: more than one uniform block")));
        }
        let size = (*span as usize).next_multiple_of(16);
        let mut bytes = vec![0u8; size];
        let mut names = Vec::new();
        let mut missing = Vec::new();
        for member in members {
            let name = member.name.clone().unwrap_or_default();
            names.push(name.clone());
            // A `uniform bool` is an int member, set from the value of the pack's name as a loader
            // sets a bool: 0 is false, anything else true.
            if let Some(pack_name) = name.strip_prefix(BOOL_UNIFORM_PREFIX) {
                match values.get(pack_name).filter(|v| v.array.is_none() && v.columns == 1 && v.rows == 1) {
                    Some(v) => {
                        let as_int = Value::int(i64::from(v.data.first().is_some_and(|&x| x != 0.0)));
                        write_member(module, &layouter, member.ty, member.offset as usize, &as_int, &mut bytes)
                            .map_err(|m| HarnessError::Uniform(format!("{stage_name}: uniform {pack_name}: {m}")))?;
                    }
                    None => missing.push(pack_name.to_string()),
                }
                continue;
            }
            // A struct member (`gl_Fog`) is filled field by field from `name.field` values.
            let fields: Vec<(String, naga::Handle<naga::Type>, u32)> = match &module.types[member.ty].inner {
                TypeInner::Struct { members: fields, .. } => fields
                    .iter()
                    .map(|f| (format!("{name}.{}", f.name.as_deref().unwrap_or("")), f.ty, member.offset + f.offset))
                    .collect(),
                _ => vec![(name.clone(), member.ty, member.offset)],
            };
            if fields.iter().any(|(key, ..)| !values.contains_key(key)) {
                missing.push(shipped_name(&name));
                continue;
            }
            let written = fields
                .iter()
                .try_for_each(|(key, ty, offset)| write_member(module, &layouter, *ty, *offset as usize, &values[key], &mut bytes));
            if let Err(m) = written {
                if strict {
                    return Err(HarnessError::Uniform(format!("{stage_name}: uniform {}: {m}", shipped_name(&name))));
                }
                missing.push(format!("{} ({m})", shipped_name(&name)));
            }
        }
        found = Some((FilledBlock { group: binding.group, binding: binding.binding, bytes, members: names }, missing));
    }
    Ok(match found {
        Some((block, missing)) => (Some(block), missing),
        None => (None, Vec::new()),
    })
}

/// The shipped name of a block member (`tp_ModelViewMatrix` → `gl_ModelViewMatrix`).
pub fn shipped_name(member: &str) -> String {
    if let Some(pack_name) = member.strip_prefix(BOOL_UNIFORM_PREFIX) {
        return pack_name.to_string();
    }
    match member.strip_prefix("tp_") {
        Some(rest) => format!("gl_{rest}"),
        None => member.to_string(),
    }
}

fn vector_len(size: VectorSize) -> u8 {
    size as u8
}

/// The GLSL shape of a uniform of type `ty` as a [`Value`] with no data, with its array
/// element type, array stride and scalar kind.
fn declared_shape(module: &naga::Module, ty: naga::Handle<naga::Type>) -> Result<(Value, naga::Handle<naga::Type>, usize, ScalarKind), String> {
    let (element_ty, count, stride) = match &module.types[ty].inner {
        TypeInner::Array { base, size: naga::ArraySize::Constant(n), stride } => (*base, Some(n.get()), *stride as usize),
        _ => (ty, None, 0),
    };
    let element = &module.types[element_ty].inner;
    let (scalar, columns, rows) = match *element {
        TypeInner::Scalar(s) => (s, 1u8, 1u8),
        TypeInner::Vector { size, scalar } => (scalar, 1, vector_len(size)),
        TypeInner::Matrix { columns, rows, scalar } => (scalar, vector_len(columns), vector_len(rows)),
        _ => return Err(format!("type {:?} is not supported by the harness", element)),
    };
    let kind = match scalar.kind {
        ScalarKind::Float if scalar.width == 4 => Kind::Float,
        ScalarKind::Sint | ScalarKind::Uint if scalar.width == 4 => Kind::Int,
        ScalarKind::Bool => return Err("bool uniforms are not supported".into()),
        _ => return Err(format!("{}-byte scalars are not supported", scalar.width)),
    };
    Ok((Value { kind, columns, rows, array: count, data: Vec::new() }, element_ty, stride, scalar.kind))
}

fn write_member(
    module: &naga::Module,
    layouter: &naga::proc::Layouter,
    ty: naga::Handle<naga::Type>,
    offset: usize,
    value: &Value,
    bytes: &mut [u8],
) -> Result<(), String> {
    let (declared, element_ty, stride, kind) = declared_shape(module, ty)?;
    let (columns, rows, count) = (declared.columns, declared.rows, declared.array);
    let column_stride = if columns > 1 { layouter[element_ty].size as usize / columns as usize } else { 0 };
    if declared.kind != value.kind || columns != value.columns || rows != value.rows || count != value.array {
        return Err(format!("declared {}, the harness provides {}", declared.glsl_type(), value.glsl_type()));
    }
    let per_element = columns as usize * rows as usize;
    for e in 0..count.unwrap_or(1) as usize {
        for c in 0..columns as usize {
            for r in 0..rows as usize {
                let v = value.data[e * per_element + c * rows as usize + r];
                let at = offset + e * stride + c * column_stride + r * 4;
                let word = match kind {
                    ScalarKind::Float => (v as f32).to_bits(),
                    ScalarKind::Sint => (v as i32) as u32,
                    _ => v as u32,
                };
                bytes[at..at + 4].copy_from_slice(&word.to_le_bytes());
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A pack that divides by `atlasSize` (rayferric's generated normal maps step a tenth of a
    /// texel) gets the atlas's size where the atlas is bound, and zero in full-screen passes.
    #[test]
    fn the_atlas_size_is_set_where_the_atlas_is_bound() {
        let scene = Scene::load(std::path::Path::new("case4_above_near")).unwrap();
        let (w, h) = mesh::ATLAS_SIZE;
        assert_eq!(values(&scene, Pass::Gbuffers)["atlasSize"], Value::ivec2(i64::from(w), i64::from(h)));
        assert_eq!(values(&scene, Pass::Fullscreen)["atlasSize"], Value::ivec2(0, 0));
        assert_eq!(values(&scene, Pass::Celestial)["atlasSize"], Value::ivec2(0, 0));
        let look = values(&scene, Pass::Gbuffers)["playerLookVector"].data.clone();
        assert!((look.iter().map(|x| x * x).sum::<f64>() - 1.0).abs() < 1e-9, "{look:?}");
    }

    #[test]
    fn initializers_of_literals_and_constructors_are_read() {
        assert_eq!(initializer_value("int", "5"), Some(Value::int(5)));
        assert_eq!(initializer_value("float", "- 0.5f"), Some(Value::float(-0.5)));
        assert_eq!(initializer_value("vec3", "vec3 ( 1.0 , 0.5 , 0.0 )"), Some(Value::vec3(DVec3::new(1.0, 0.5, 0.0))));
        assert_eq!(initializer_value("vec4", "vec4 ( 0.25 )").map(|v| v.data), Some(vec![0.25; 4]));
        assert_eq!(initializer_value("bool", "true"), Some(Value::int(1)));
        assert_eq!(initializer_value("ivec2", "ivec2 ( 2 , 4 )"), Some(Value::ivec2(2, 4)));
        // Expressions and matrices are not read.
        assert_eq!(initializer_value("float", "1.0 / 3.0"), None);
        assert_eq!(initializer_value("mat3", "mat3 ( 1.0 )"), None);
        assert_eq!(initializer_value("vec3", "vec3 ( 1.0 , 2.0 )"), None);
    }
}
