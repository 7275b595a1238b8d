//! Scenes: TOML files describing a camera, the time, the sky, a body of water, opaque terrain,
//! stained-glass panes, and what the game draws after the translucent terrain (rain, clouds,
//! particles, the translucent hand). Everything derived from a scene (matrices, `isEyeInWater`) is
//! computed here in f64.

use std::path::{Path, PathBuf};

use glam::{DMat4, DVec3};
use serde::Deserialize;

use crate::SceneError;
use tidepack_loader::loader::{Loader, OverlayKind, Phase};
use tidepack_loader::shadow::SunPath;

/// The blocks a scene's terrain can be made of, and their sprites in the block atlas
/// ([`crate::mesh::atlas`]).
pub const BLOCK_SPRITES: [(&str, u32); 5] =
    [("minecraft:stone", 2), ("minecraft:grass_block", 3), ("minecraft:sand", 4), ("minecraft:dirt", 5), ("minecraft:oak_leaves", 6)];

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Defaults to the file name.
    #[serde(default)]
    pub name: String,
    #[serde(default)]
    pub description: String,
    /// Width and height in pixels.
    #[serde(deserialize_with = "exact")]
    pub resolution: [u32; 2],
    /// World offset added to every position in the file (camera, water, terrain, glass):
    /// the same scene far from the origin.
    #[serde(default, deserialize_with = "exact")]
    pub origin: [f64; 3],
    pub camera: Camera,
    pub time: Time,
    pub sky: Sky,
    pub water: Option<Water>,
    #[serde(default)]
    pub terrain: Terrain,
    #[serde(default)]
    pub glass: Vec<GlassPane>,
    /// Boxes drawn as rain, clouds, particles or the translucent hand.
    #[serde(default)]
    pub overlay: Vec<OverlayBox>,
    /// Entities (`[[entity]]`): mobs, item frames, each a box drawn through gbuffers_entities'
    /// chain with its `entityId`.
    #[serde(default, rename = "entity")]
    pub entities: Vec<EntityBox>,
    /// Distant Horizons' LODs past the game's chunks, drawn by a pack's dh_* programs where the
    /// loader is Iris with the mod.
    pub distant_horizons: Option<DistantHorizons>,
}

/// Distant Horizons' level-of-detail world: flat terrain and water beyond the game's render
/// distance, drawn with its own projection into its own depth buffers (Iris's dhDepthTex0
/// and dhDepthTex1), before the game's terrain and water.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DistantHorizons {
    /// `dhRenderDistance`: how far the LODs reach, in blocks.
    pub render_distance: f64,
    /// `dhNearPlane`, the near plane of Distant Horizons' projection, in blocks.
    #[serde(default = "default_lod_near")]
    pub near: f64,
    /// The LOD water: flat rectangles of [`LOD_CELL`]-block cells.
    #[serde(default)]
    pub water: Vec<LodWater>,
    /// LOD ground, in [`LOD_CELL`]-block cells, flat at each rectangle's height.
    #[serde(default)]
    pub ground: Vec<LodGround>,
}

/// Side of the quads of the LOD world, in blocks: Distant Horizons' LODs are coarse.
pub const LOD_CELL: f64 = 16.0;

fn default_lod_near() -> f64 {
    16.0
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LodWater {
    pub level: f64,
    #[serde(deserialize_with = "exact")]
    pub min: [f64; 2],
    #[serde(deserialize_with = "exact")]
    pub max: [f64; 2],
    /// The LOD's colour: Distant Horizons' vertex colour of its water.
    #[serde(default = "default_water_tint", deserialize_with = "exact")]
    pub tint: [f64; 3],
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LodGround {
    #[serde(deserialize_with = "exact")]
    pub min: [f64; 2],
    #[serde(deserialize_with = "exact")]
    pub max: [f64; 2],
    pub height: f64,
    #[serde(deserialize_with = "exact")]
    pub color: [f64; 3],
    /// What Distant Horizons calls the material (`dhMaterialId`): one of the blocks of
    /// [`BLOCK_SPRITES`], or unknown.
    pub block: Option<String>,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Camera {
    #[serde(deserialize_with = "exact")]
    pub position: [f64; 3],
    /// Degrees, Minecraft's convention: 0 looks towards +z, 90 towards -x.
    pub yaw: f64,
    /// Degrees, positive looks down.
    pub pitch: f64,
    /// Vertical field of view in degrees.
    pub fov: f64,
    /// The `near` uniform and the near plane (Minecraft: 0.05).
    #[serde(default = "default_near")]
    pub near: f64,
    /// The `far` uniform: render distance in blocks. The projection's far plane is 4 × far,
    /// as in Minecraft 1.18+.
    pub far: f64,
}

fn default_near() -> f64 {
    0.05
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Time {
    /// Ticks, 0..24000.
    pub world_time: i32,
    /// Seconds, 0..3600.
    pub frame_time_counter: f64,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sky {
    /// World-space direction towards the sun (normalised by the harness). Without it the sun
    /// stands where the game's clock puts it at `time.world_time` on a path tilted by
    /// `sun_path_rotation`.
    #[serde(default, deserialize_with = "exact")]
    pub sun_direction: [f64; 3],
    /// Degrees, as a pack's `sunPathRotation`; only with the sun placed by the clock.
    #[serde(default)]
    pub sun_path_rotation: Option<f64>,
    #[serde(deserialize_with = "exact")]
    pub sky_color: [f64; 3],
    #[serde(deserialize_with = "exact")]
    pub fog_color: [f64; 3],
    /// `rainStrength` and `wetness`: 0 clear, 1 full rain.
    #[serde(default)]
    pub rain_strength: f64,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Water {
    /// Height of the flat surface (Minecraft's still water top is block y + 0.875).
    pub level: f64,
    /// x, z corners of the water surface.
    #[serde(deserialize_with = "exact")]
    pub min: [f64; 2],
    #[serde(deserialize_with = "exact")]
    pub max: [f64; 2],
    /// The water volume's bottom, for `isEyeInWater` (default: far below).
    #[serde(default = "default_bottom")]
    pub bottom: f64,
    /// Biome tint of the water (vertex colour).
    #[serde(default = "default_water_tint", deserialize_with = "exact")]
    pub tint: [f64; 3],
    /// Side of the surface's quads in blocks (1 as in Minecraft; larger for huge far water).
    #[serde(default = "default_cell")]
    pub cell: f64,
}

fn default_cell() -> f64 {
    1.0
}

fn default_bottom() -> f64 {
    -64.0
}

fn default_water_tint() -> [f64; 3] {
    // Minecraft's default water colour, 0x3F76E4.
    [63.0 / 255.0, 118.0 / 255.0, 228.0 / 255.0]
}

#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Terrain {
    #[serde(default)]
    pub ground: Vec<Ground>,
    #[serde(default, rename = "box")]
    pub boxes: Vec<BoxShape>,
}

/// A (possibly sloped) ground surface over a rectangle, one quad per block, checkered.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Ground {
    #[serde(deserialize_with = "exact")]
    pub min: [f64; 2],
    #[serde(deserialize_with = "exact")]
    pub max: [f64; 2],
    /// Height at `min`.
    pub height: f64,
    /// Rise per block along x and z (a beach).
    #[serde(default, deserialize_with = "exact")]
    pub slope: [f64; 2],
    /// Tint, multiplying the block's sprite.
    #[serde(deserialize_with = "exact")]
    pub color: [f64; 3],
    /// A block of the harness's atlas (`minecraft:sand`, …: [`BLOCK_SPRITES`]),
    /// textured and given its id from the pack's block.properties; without one, plain colour.
    #[serde(default)]
    pub block: Option<String>,
}

/// An axis-aligned opaque box (walls, pool sides, pillars).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxShape {
    #[serde(deserialize_with = "exact")]
    pub min: [f64; 3],
    #[serde(deserialize_with = "exact")]
    pub max: [f64; 3],
    /// Tint, multiplying the block's sprite.
    #[serde(deserialize_with = "exact")]
    pub color: [f64; 3],
    /// As for [`Ground::block`].
    #[serde(default)]
    pub block: Option<String>,
}

/// A stained-glass pane: a thin box drawn with gbuffers_water.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GlassPane {
    #[serde(deserialize_with = "exact")]
    pub min: [f64; 3],
    #[serde(deserialize_with = "exact")]
    pub max: [f64; 3],
    /// Tint and opacity.
    #[serde(deserialize_with = "exact")]
    pub color: [f64; 4],
    /// Block name looked up in the pack's block.properties for `mc_Entity.x`.
    #[serde(default = "default_glass_block")]
    pub block: String,
}

/// A box of one colour drawn as rain, clouds, a particle or the translucent hand.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OverlayBox {
    pub kind: OverlayKind,
    #[serde(deserialize_with = "exact")]
    pub min: [f64; 3],
    #[serde(deserialize_with = "exact")]
    pub max: [f64; 3],
    /// Colour and opacity.
    #[serde(deserialize_with = "exact")]
    pub color: [f64; 4],
}

/// An entity as a box of one colour, drawn with the opaque world.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EntityBox {
    /// Its name in the game (`minecraft:zombie`, `item_frame`), looked up in the pack's
    /// entity.properties for `entityId`.
    pub name: String,
    #[serde(deserialize_with = "exact")]
    pub min: [f64; 3],
    #[serde(deserialize_with = "exact")]
    pub max: [f64; 3],
    /// Colour and opacity.
    #[serde(deserialize_with = "exact")]
    pub color: [f64; 4],
}

fn default_glass_block() -> String {
    "minecraft:white_stained_glass".into()
}

/// A fixed-size array that must be written with exactly `N` values (serde's own array
/// reading stops after `N` and ignores the rest).
fn exact<'de, D, T, const N: usize>(deserializer: D) -> Result<[T; N], D::Error>
where
    D: serde::Deserializer<'de>,
    T: Deserialize<'de>,
{
    let values = Vec::<T>::deserialize(deserializer)?;
    let found = values.len();
    values.try_into().map_err(|_| serde::de::Error::invalid_length(found, &format!("{N} values").as_str()))
}

/// The first NaN or infinite float of a parsed scene, as a dotted path (`camera.position[1]`).
fn first_non_finite(value: &toml::Value, path: &str) -> Option<(String, f64)> {
    match value {
        toml::Value::Float(f) if !f.is_finite() => Some((path.to_string(), *f)),
        toml::Value::Array(items) => {
            items.iter().enumerate().find_map(|(i, item)| first_non_finite(item, &format!("{path}[{i}]")))
        }
        toml::Value::Table(table) => table.iter().find_map(|(key, item)| {
            let inner = if path.is_empty() { key.clone() } else { format!("{path}.{key}") };
            first_non_finite(item, &inner)
        }),
        _ => None,
    }
}

/// The scene files (`*.toml`) of a folder, sorted by name.
pub fn scene_files(dir: &Path) -> Result<Vec<PathBuf>, SceneError> {
    let entries = std::fs::read_dir(dir).map_err(|e| SceneError(format!("cannot read {}: {e}", dir.display())))?;
    let mut files: Vec<PathBuf> =
        entries.filter_map(|e| Some(e.ok()?.path())).filter(|p| p.extension().is_some_and(|x| x == "toml")).collect();
    files.sort();
    Ok(files)
}

/// How far from the origin the game lets anything be: Minecraft's world border.
pub const WORLD_BORDER: f64 = 30_000_000.0;

/// Most quads a scene's mesh may have: each takes six vertices of about 100 bytes, so the
/// mesh stays near 120 MiB (the scenes of tests/scenes have at most 11,040).
pub const MAX_QUADS: usize = 200_000;

/// Largest scene file read: the scenes of tests/scenes are under 4 KiB.
pub const MAX_SCENE_BYTES: u64 = 1 << 20;

include!(concat!(env!("OUT_DIR"), "/built_in_scenes.rs"));

/// The names of the scenes the binary carries (tests/scenes/*.toml).
pub fn built_in_names() -> Vec<&'static str> {
    BUILT_IN_SCENES.iter().map(|(name, _)| *name).collect()
}

/// The text of the built-in scene `path` names, when it is a bare name.
fn built_in(path: &Path) -> Option<&'static str> {
    let mut components = path.components();
    let name = match (components.next(), components.next()) {
        (Some(std::path::Component::Normal(name)), None) => name.to_str()?,
        _ => return None,
    };
    let name = name.strip_suffix(".toml").unwrap_or(name);
    BUILT_IN_SCENES.iter().find(|(n, _)| *n == name).map(|(_, text)| *text)
}

impl Scene {
    /// When `loader` draws the scene's boxes of `kind`.
    pub fn overlay_phase(&self, loader: Loader, kind: OverlayKind) -> Phase {
        let boxes = self.overlay.iter().filter(|o| o.kind == kind);
        let camera_below = boxes.clone().all(|o| o.min[1] > self.camera.position[1]);
        let opaque = boxes.clone().all(|o| o.color[3] >= 1.0);
        loader.phase(kind, camera_below, opaque)
    }

    /// The model-view-projection of the harness's own terrain shader (f64, then f32), the same
    /// for both renderers.
    pub fn terrain_mvp(&self) -> [f32; 16] {
        (self.projection() * self.model_view()).to_cols_array().map(|v| v as f32)
    }

    /// The scene in the file at `path`; where there is no such file and `path` is a bare
    /// name (`case4_above_near`, with or without `.toml`), the built-in scene of that name.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        let unreadable = |why: String| SceneError(format!("cannot read scene {}: {why}", path.display()));
        let meta = match std::fs::metadata(path) {
            Ok(meta) => meta,
            Err(e) => {
                return match built_in(path) {
                    Some(text) => Scene::parse(text, path),
                    None => Err(unreadable(format!("{e}; the built-in scenes are {}", built_in_names().join(", ")))),
                };
            }
        };
        if !meta.is_file() {
            return Err(unreadable("not a regular file".into()));
        }
        if meta.len() > MAX_SCENE_BYTES {
            return Err(unreadable(format!("{} bytes, over the {MAX_SCENE_BYTES}-byte budget for a scene file", meta.len())));
        }
        let text = std::fs::read_to_string(path).map_err(|e| unreadable(e.to_string()))?;
        Scene::parse(&text, path)
    }

    /// A scene from the text of its TOML file; `path` names it in messages and gives the
    /// scene's name when the file has none.
    pub fn parse(text: &str, path: &Path) -> Result<Scene, SceneError> {
        let parsed: toml::Table =
            toml::from_str(text).map_err(|e| SceneError(format!("{}: {e}", path.display())))?;
        let sun_given = parsed.get("sky").and_then(|sky| sky.get("sun_direction")).is_some();
        // Every float feeds a matrix, a uniform or a mesh: one NaN or infinity renders a wrong
        // picture without any error further on.
        if let Some((field, value)) = first_non_finite(&toml::Value::Table(parsed), "") {
            return Err(SceneError(format!("{}: {field} is {value}; scene values must be finite numbers", path.display())));
        }
        let mut scene: Scene =
            toml::from_str(text).map_err(|e| SceneError(format!("{}: {e}", path.display())))?;
        match (sun_given, scene.sky.sun_path_rotation) {
            (true, Some(_)) => {
                return Err(SceneError(format!(
                    "{}: give sky.sun_direction or sky.sun_path_rotation (the sun placed by time.world_time), not both",
                    path.display()
                )));
            }
            (true, None) => {}
            (false, rotation) => {
                let path = SunPath::of_world_time(scene.time.world_time as i64, rotation.unwrap_or(0.0));
                scene.sky.sun_direction = path.sun_direction().to_array();
            }
        }
        if scene.name.is_empty() {
            scene.name = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
        }
        scene.check().map_err(|e| SceneError(format!("{}: {e}", path.display())))?;
        Ok(scene)
    }

    fn check(&self) -> Result<(), String> {
        if self.name.chars().any(|c| c.is_control()) {
            return Err(format!("name {:?} holds a control character; a scene's name is one line of text", self.name));
        }
        if let Some((what, at)) = self.farthest_point().filter(|(_, at)| *at > WORLD_BORDER) {
            return Err(format!(
                "{what} reaches {at:e} blocks from the world's origin; everything lies within Minecraft's world border, {WORLD_BORDER:e} blocks"
            ));
        }
        let quads = self.quads();
        if quads > MAX_QUADS as f64 {
            return Err(format!("the scene makes {quads:.0} quads of terrain, water and glass, more than the budget of {MAX_QUADS}"));
        }
        let [w, h] = self.resolution;
        // The upper bound depends on the device (Gpu::check_resolution), checked before rendering.
        if w == 0 || h == 0 {
            return Err(format!("resolution {w}x{h}: width and height must be at least 1"));
        }
        let c = &self.camera;
        if !(c.fov > 1.0 && c.fov < 179.0) || c.near <= 0.0 || c.far <= c.near {
            return Err("camera needs 1 < fov < 179, near > 0 and far > near".into());
        }
        if self.water.as_ref().is_some_and(|w| w.cell.is_nan() || w.cell < 1.0) {
            return Err("water.cell must be at least 1 block".into());
        }
        if let Some(lod) = &self.distant_horizons
            && !(lod.near > 0.0 && lod.render_distance > c.far && lod.near < lod.render_distance)
        {
            return Err("distant_horizons needs near > 0 and render_distance beyond both near and camera.far".into());
        }
        if !(0.0..=1.0).contains(&self.sky.rain_strength) {
            return Err("sky.rain_strength must lie in 0..1".into());
        }
        if DVec3::from(self.sky.sun_direction).length() < 1e-9 {
            return Err("sky.sun_direction must not be zero".into());
        }
        if let Some(entity) = self.entities.iter().find(|e| e.name.is_empty() || e.name.chars().any(|c| c.is_whitespace() || c.is_control())) {
            return Err(format!("entity name {:?}: an entity is named as the game names it, one word such as minecraft:zombie", entity.name));
        }
        let lod_blocks = self.distant_horizons.iter().flat_map(|lod| lod.ground.iter().map(|g| &g.block));
        let blocks = self.terrain.ground.iter().map(|g| &g.block).chain(self.terrain.boxes.iter().map(|b| &b.block)).chain(lod_blocks);
        for block in blocks.flatten() {
            if !BLOCK_SPRITES.iter().any(|(name, _)| name == block) {
                let known: Vec<&str> = BLOCK_SPRITES.iter().map(|(name, _)| *name).collect();
                return Err(format!("block {block} is not in the harness's atlas; it has {}", known.join(", ")));
            }
        }
        Ok(())
    }

    /// Same scene at another resolution.
    pub fn with_resolution(mut self, width: u32, height: u32) -> Scene {
        self.resolution = [width, height];
        self
    }

    pub fn width(&self) -> u32 {
        self.resolution[0]
    }

    pub fn height(&self) -> u32 {
        self.resolution[1]
    }

    /// The camera's world position (origin applied).
    /// The part of the scene farthest from the world's origin on any axis, with that distance.
    fn farthest_point(&self) -> Option<(&'static str, f64)> {
        let origin = DVec3::from(self.origin);
        let at = |p: [f64; 3]| (DVec3::from(p) + origin).abs().max_element();
        let flat = |p: [f64; 2], y: f64| at([p[0], y, p[1]]);
        let mut parts: Vec<(&'static str, f64)> = vec![("the camera", at(self.camera.position))];
        if let Some(w) = &self.water {
            parts.push(("the water", flat(w.min, w.level).max(flat(w.max, w.bottom))));
        }
        parts.extend(self.terrain.ground.iter().map(|g| ("the ground", flat(g.min, g.height).max(flat(g.max, g.height)))));
        parts.extend(self.terrain.boxes.iter().map(|b| ("a terrain box", at(b.min).max(at(b.max)))));
        parts.extend(self.glass.iter().map(|g| ("a glass pane", at(g.min).max(at(g.max)))));
        parts.extend(self.overlay.iter().map(|o| ("an overlay box", at(o.min).max(at(o.max)))));
        parts.extend(self.entities.iter().map(|e| ("an entity", at(e.min).max(at(e.max)))));
        if let Some(lod) = &self.distant_horizons {
            parts.extend(lod.water.iter().map(|w| ("the LOD water", flat(w.min, w.level).max(flat(w.max, w.level)))));
            parts.extend(lod.ground.iter().map(|g| ("the LOD ground", flat(g.min, g.height).max(flat(g.max, g.height)))));
        }
        parts.into_iter().max_by(|a, b| a.1.total_cmp(&b.1))
    }

    /// The quads the mesh of this scene has, counted before it is built: a block of ground or
    /// a cell of water each, six per box and pane.
    pub fn quads(&self) -> f64 {
        let cells = |min: [f64; 2], max: [f64; 2], cell: f64| ((max[0] - min[0]) / cell).ceil().max(0.0) * ((max[1] - min[1]) / cell).ceil().max(0.0);
        let ground: f64 = self.terrain.ground.iter().map(|g| cells(g.min, g.max, 1.0)).sum();
        let water = self.water.as_ref().map_or(0.0, |w| cells(w.min, w.max, w.cell));
        let lod: f64 = self.distant_horizons.iter().map(|lod| {
            lod.water.iter().map(|w| cells(w.min, w.max, LOD_CELL)).sum::<f64>() + lod.ground.iter().map(|g| cells(g.min, g.max, LOD_CELL)).sum::<f64>()
        }).sum();
        ground + water + lod + 6.0 * (self.terrain.boxes.len() + self.glass.len() + self.overlay.len() + self.entities.len()) as f64
    }

    pub fn camera_position(&self) -> DVec3 {
        DVec3::from(self.camera.position) + DVec3::from(self.origin)
    }

    /// Whether the camera is inside the water volume: OptiFine's `isEyeInWater == 1`.
    pub fn eye_in_water(&self) -> bool {
        let Some(w) = &self.water else { return false };
        let p = DVec3::from(self.camera.position);
        p.x >= w.min[0] && p.x <= w.max[0] && p.z >= w.min[1] && p.z <= w.max[1] && p.y < w.level && p.y > w.bottom
    }

    /// gbufferModelView: rotation only (positions reach the shaders relative to the camera).
    pub fn model_view(&self) -> DMat4 {
        let c = &self.camera;
        DMat4::from_rotation_x(c.pitch.to_radians()) * DMat4::from_rotation_y((c.yaw + 180.0).to_radians())
    }

    /// gbufferProjection: OpenGL perspective (clip z from -w to w), far plane 4 × far.
    pub fn projection(&self) -> DMat4 {
        let c = &self.camera;
        let aspect = self.width() as f64 / self.height() as f64;
        DMat4::perspective_rh_gl(c.fov.to_radians(), aspect, c.near, c.far * 4.0)
    }

    pub fn sun_direction(&self) -> DVec3 {
        DVec3::from(self.sky.sun_direction).normalize()
    }

    /// `dhRenderDistance`, `dhNearPlane` and `dhFarPlane`: the scene's LOD band's, or without one
    /// a band that ends where the game's chunks do (what Iris sets with the mod drawing nothing
    /// beyond them). The far plane is Iris's: the render distance and 512 blocks, times √2 so
    /// that the corners are not cut off.
    pub fn lod_planes(&self) -> (f64, f64, f64) {
        let (render_distance, near) = match &self.distant_horizons {
            Some(lod) => (lod.render_distance, lod.near),
            None => (self.camera.far, default_lod_near().min(self.camera.far * 0.5)),
        };
        (render_distance, near, (render_distance + 512.0) * std::f64::consts::SQRT_2)
    }

    /// dhProjection: the camera's perspective between Distant Horizons' near and far planes.
    pub fn lod_projection(&self) -> DMat4 {
        let (_, near, far) = self.lod_planes();
        let aspect = self.width() as f64 / self.height() as f64;
        DMat4::perspective_rh_gl(self.camera.fov.to_radians(), aspect, near, far)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn case4() -> String {
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/scenes/case4_above_near.toml")).unwrap()
    }

    #[test]
    fn every_scene_of_tests_scenes_is_built_in_and_loads_by_name_anywhere() {
        let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/scenes");
        let mut on_disk: Vec<String> = std::fs::read_dir(&folder)
            .unwrap()
            .filter_map(|e| e.ok()?.path().file_stem()?.to_str().map(String::from))
            .filter(|n| folder.join(format!("{n}.toml")).is_file())
            .collect();
        on_disk.sort();
        assert_eq!(built_in_names(), on_disk);
        // A bare name is looked up as a file first: tests run in crates/scene, which has none.
        let by_name = Scene::load(Path::new("case4_above_near"));
        let with_extension = Scene::load(Path::new("case4_above_near.toml"));
        let missing = Scene::load(Path::new("no_such_scene")).map(|_| ()).unwrap_err().to_string();
        let nested = Scene::load(Path::new("scenes/case4_above_near.toml")).map(|_| ()).unwrap_err().to_string();
        assert_eq!(by_name.unwrap().name, "case4_above_near");
        assert!(with_extension.is_ok());
        assert!(missing.contains("no_such_scene") && missing.contains("built-in scenes are") && missing.contains("rain_over_lake"), "{missing}");
        assert!(nested.contains("scenes/case4_above_near.toml"), "{nested}");
    }

    #[test]
    fn a_scene_that_is_no_file_or_too_large_is_refused_before_it_is_read() {
        let dir = tempfile::tempdir().unwrap();
        let err = Scene::load(dir.path()).map(|_| ()).unwrap_err().to_string();
        assert!(err.contains("not a regular file"), "{err}");
        let big = dir.path().join("big.toml");
        std::fs::write(&big, vec![b'#'; MAX_SCENE_BYTES as usize + 1]).unwrap();
        let err = Scene::load(&big).map(|_| ()).unwrap_err().to_string();
        assert!(err.contains("budget for a scene file"), "{err}");
    }

    fn load_text(text: &str) -> Result<Scene, String> {
        let dir = std::env::temp_dir().join(format!("tidepack-scene-{}-{:x}", std::process::id(), text.len()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("edited.toml");
        std::fs::write(&path, text).unwrap();
        let result = Scene::load(&path).map_err(|e| e.to_string());
        std::fs::remove_dir_all(&dir).unwrap();
        result
    }

    #[test]
    fn non_finite_values_are_refused_with_the_field_and_file() {
        assert!(load_text(&case4()).is_ok());
        for (from, to, field) in [
            ("position = [0.0, 67.0, -2.0]", "position = [0.0, nan, -2.0]", "camera.position[1] is NaN"),
            ("yaw = 180.0", "yaw = inf", "camera.yaw is inf"),
            ("far = 96.0", "far = -inf", "camera.far is -inf"),
            ("frame_time_counter = 12.5", "frame_time_counter = nan", "time.frame_time_counter is NaN"),
            ("level = 62.875", "level = nan", "water.level is NaN"),
            ("sun_direction = [0.35, 0.85, -0.40]", "sun_direction = [0.35, inf, -0.40]", "sky.sun_direction[1] is inf"),
            ("height = 40.0", "height = nan", "terrain.ground[4].height is NaN"),
        ] {
            let text = case4().replacen(from, to, 1);
            let error = load_text(&text).unwrap_err();
            assert!(error.contains(field) && error.contains("edited.toml"), "{to}: {error}");
        }
    }

    #[test]
    fn sizes_are_budgeted_before_the_mesh_is_built() {
        let wide = case4().replacen("min = [-32.0, -32.0]\nmax = [32.0, 22.0]", "min = [-1e6, -1e6]\nmax = [1e6, 1e6]", 1);
        let error = load_text(&wide).unwrap_err();
        assert!(error.contains("budget of 200000") && error.contains("edited.toml"), "{error}");
        // Found by the scene fuzz target: 810,000 cells of water made a mesh of over 600 MiB.
        let broad = case4().replacen("min = [-32.0, -32.0]\nmax = [32.0, 22.0]", "min = [-450.0, -450.0]\nmax = [450.0, 450.0]", 1);
        let error = load_text(&broad).unwrap_err();
        assert!(error.contains("814058 quads") && error.contains("budget of 200000"), "{error}");
        let far = case4().replacen("position = [0.0, 67.0, -2.0]", "position = [1e308, 67.0, -2.0]", 1);
        let error = load_text(&far).unwrap_err();
        assert!(error.contains("the camera") && error.contains("world border"), "{error}");
        let forged = case4().replacen("name = \"case4_above_near\"", "name = \"x\\r\\nerror: forged\"", 1);
        let error = load_text(&forged).unwrap_err();
        assert!(error.contains("control character"), "{error}");
    }

    #[test]
    fn without_a_sun_direction_the_clock_places_the_sun() {
        let night = load_text(&std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/scenes/blocks/shore_night.toml")).unwrap()).unwrap();
        let expected = SunPath::of_world_time(14000, 20.0).sun_direction();
        assert!((night.sun_direction() - expected).length() < 1e-12 && night.sun_direction().y < 0.0, "{:?}", night.sun_direction());
        let both = case4().replacen("sun_direction = [0.35, 0.85, -0.40]", "sun_direction = [0.35, 0.85, -0.40]\nsun_path_rotation = 10.0", 1);
        let error = load_text(&both).unwrap_err();
        assert!(error.contains("not both") && error.contains("edited.toml"), "{error}");
    }

    #[test]
    fn terrain_blocks_must_be_in_the_atlas() {
        let shore = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/scenes/blocks/shore.toml")).unwrap();
        assert!(load_text(&shore).is_ok());
        let error = load_text(&shore.replacen("minecraft:stone", "minecraft:bedrock", 1)).unwrap_err();
        assert!(error.contains("minecraft:bedrock") && error.contains("minecraft:sand") && error.contains("edited.toml"), "{error}");
    }

    #[test]
    fn arrays_take_exactly_their_number_of_values() {
        let error = load_text(&case4().replacen("resolution = [640, 360]", "resolution = [640, 360, 2]", 1)).unwrap_err();
        assert!(error.contains("invalid length 3") && error.contains("2 values") && error.contains("edited.toml"), "{error}");
        let error = load_text(&case4().replacen("yaw = 180.0", "yaw = 180.0\nposition2 = 1", 1)).unwrap_err();
        assert!(error.contains("position2"), "{error}");
        let error = load_text(&case4().replacen("sun_direction = [0.35, 0.85, -0.40]", "sun_direction = [0.35, 0.85]", 1)).unwrap_err();
        assert!(error.contains("invalid length 2") && error.contains("3 values"), "{error}");
    }
}
