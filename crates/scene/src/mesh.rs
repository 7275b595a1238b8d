//! Geometry of a scene: opaque terrain (for the pack's terrain program, or the harness's own
//! terrain shader where the pack has none), the translucent quads (water surface, glass panes)
//! for the pack's gbuffers_water, sorted back to front as Minecraft sorts translucent terrain,
//! the overlays (rain, clouds, particles, the hand) and, for any pack's frame, the sky.
//! Positions are relative to the camera (computed in f64), so scenes far from the origin lose
//! no precision before the shaders see them; gl_ModelViewMatrix is then gbufferModelView, as
//! with OptiFine's chunk offsets.

use glam::DVec3;
use rand_core::{Rng as _, SeedableRng as _};
use rand_xoshiro::SplitMix64;

use crate::scene::{BLOCK_SPRITES, LOD_CELL, Scene};
use tidepack_loader::loader::OverlayKind;
use tidepack_loader::macros::DH_BLOCKS;
use tidepack_loader::shadow::SunPath;

/// The vertex of the pack's gbuffers programs; every attribute a `gbuffers_*` vertex shader
/// can ask for is here (the pipeline binds those the shader declares).
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C)]
pub struct PackVertex {
    /// gl_Vertex (w = 1).
    pub position: [f32; 4],
    /// gl_Color.
    pub color: [f32; 4],
    /// gl_Normal.
    pub normal: [f32; 3],
    /// gl_MultiTexCoord0: atlas uv.
    pub uv0: [f32; 4],
    /// gl_MultiTexCoord1: lightmap coordinates, raw 0..240 (block, sky).
    pub uv1: [f32; 4],
    /// mc_Entity: x = block id from block.properties (-1 unmapped), y = render type (1 fluid, -1 other).
    pub entity: [f32; 4],
    /// vaUV2 of the 1.17+ core profile: the lightmap coordinates of `uv1` as integers.
    pub lightmap: [i32; 2],
    /// at_tangent: the direction of increasing atlas u on the face, w the handedness of
    /// (tangent, bitangent, normal).
    pub tangent: [f32; 4],
    /// mc_midTexCoord: the centre of the face's sprite in the atlas (w = 1).
    pub mid_uv: [f32; 4],
}

/// Byte offsets of the attributes of [`PackVertex`].
pub mod offsets {
    pub const POSITION: u64 = 0;
    pub const COLOR: u64 = 16;
    pub const NORMAL: u64 = 32;
    pub const UV0: u64 = 44;
    pub const UV1: u64 = 60;
    pub const ENTITY: u64 = 76;
    pub const LIGHTMAP: u64 = 92;
    pub const TANGENT: u64 = 100;
    pub const MID_UV: u64 = 116;
    pub const STRIDE: u64 = 132;
}

/// The generated block atlas (`gtexture`): a row of 16×16 sprites of our own, no game assets.
const SPRITE: u32 = 16;
const ATLAS_SPRITES: u32 = 8;
/// Width and height of the block atlas ([`atlas`]).
pub const ATLAS_SIZE: (u32, u32) = (SPRITE * ATLAS_SPRITES, SPRITE);

/// The uv rectangle of sprite `index`, inset two texels from its edges so nearest sampling
/// never reaches a neighbour.
const fn sprite_rect(index: u32) -> [f32; 4] {
    let width = (SPRITE * ATLAS_SPRITES) as f32;
    let left = (index * SPRITE) as f32;
    [(left + 2.0) / width, 2.0 / SPRITE as f32, (left + SPRITE as f32 - 2.0) / width, (SPRITE - 2) as f32 / SPRITE as f32]
}

/// Water: flat, translucent grey (the pack's colour comes from the vertex tint).
pub const WATER_SPRITE: [f32; 4] = sprite_rect(0);
/// Opaque white: glass panes and terrain without a block take the vertex colour as it is.
pub const WHITE_SPRITE: [f32; 4] = sprite_rect(1);

/// The atlas rectangle of `block`'s sprite.
pub fn block_sprite(block: &str) -> Option<[f32; 4]> {
    BLOCK_SPRITES.iter().find(|(name, _)| *name == block).map(|(_, index)| sprite_rect(*index))
}

/// Lightmap coordinates of everything in the scenes: no block light, full sky light.
const LIGHT: [f32; 4] = [0.0, 240.0, 0.0, 1.0];
const LIGHT_INT: [i32; 2] = [0, 240];

/// What `gtexture` holds for a draw: the block atlas, or the sun's or the moon's texture.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Sprites {
    #[default]
    Blocks,
    Sun,
    Moon,
}

#[derive(Clone, Debug, Default)]
pub struct SceneMesh {
    /// Triangles; the colour is lit once here (ambient and sun).
    pub terrain: Vec<PackVertex>,
    /// Triangles, back to front.
    pub translucent: Vec<PackVertex>,
    /// Rain, clouds, particles and the translucent hand: triangles per kind, back to front.
    pub overlay: Vec<(OverlayKind, Vec<PackVertex>)>,
    /// Each entity of the scene, by its name: one draw each, opaque.
    pub entities: Vec<(String, Vec<PackVertex>)>,
    /// The sky as the game draws it for gbuffers_skybasic: a box around the camera in the sky
    /// colour, inside the far plane, drawn before the terrain without writing depth.
    pub sky: Vec<PackVertex>,
    /// The sun and the moon as the game draws them for gbuffers_skytextured: a quad each, 100
    /// blocks out on the sun's path, textured with [`sun`] and [`moon`] over their whole
    /// texture, faded by rain.
    pub sun: Vec<PackVertex>,
    pub moon: Vec<PackVertex>,
    /// Distant Horizons' opaque LODs and its water, triangles (the water back to front), for
    /// the pack's dh_terrain and dh_water. As Iris gives them: no texture coordinates, the
    /// lightmap coordinates already in 0..1, and Distant Horizons' material id (`dhMaterialId`)
    /// in `entity.x`.
    pub lod_terrain: Vec<PackVertex>,
    pub lod_translucent: Vec<PackVertex>,
}

/// The `DH_BLOCK_*` material of a block of the scenes.
fn lod_material(block: Option<&str>) -> f32 {
    let name = match block {
        Some("minecraft:stone") => "STONE",
        Some("minecraft:grass_block") => "GRASS",
        Some("minecraft:sand") => "SAND",
        Some("minecraft:dirt") => "DIRT",
        Some("minecraft:oak_leaves") => "LEAVES",
        Some("minecraft:water") => "WATER",
        _ => "UNKNOWN",
    };
    DH_BLOCKS.iter().position(|b| *b == name).expect("a DH_BLOCK_* name") as f32
}

/// Distant Horizons' lightmap coordinates as Iris gives them: (block + 0.5) / 16 and
/// (sky + 0.5) / 16, here no block light and full sky light.
const LOD_LIGHT: [f32; 4] = [0.5 / 16.0, 15.5 / 16.0, 0.0, 1.0];

/// Block ids the translucent geometry carries in `mc_Entity.x`.
pub trait BlockIds {
    /// The id of a block name (`minecraft:water`) in block.properties, -1 when unmapped.
    fn id_of(&self, block: &str) -> i32;
}

struct Quad {
    corners: [DVec3; 4],
    normal: DVec3,
    color: [f64; 4],
    sprite: [f32; 4],
    entity: [f32; 4],
}

pub fn build(scene: &Scene, ids: &dyn BlockIds) -> SceneMesh {
    let camera = scene.camera_position();
    let origin = DVec3::from(scene.origin);
    let sun = scene.sun_direction();
    let rel = |p: DVec3| -> [f32; 4] {
        let r = p + origin - camera;
        [r.x as f32, r.y as f32, r.z as f32, 1.0]
    };
    let mut mesh = SceneMesh::default();

    // Opaque terrain, lit once here (ambient + sun) so both renderers get identical colours.
    let mut terrain_quad = |corners: [DVec3; 4], normal: DVec3, color: [f64; 3], block: &Option<String>| {
        let light = 0.45 + 0.55 * normal.dot(sun).max(0.0);
        let c = [(color[0] * light) as f32, (color[1] * light) as f32, (color[2] * light) as f32, 1.0];
        let (sprite, id) = match block {
            Some(block) => (block_sprite(block).unwrap_or(WHITE_SPRITE), ids.id_of(block) as f32),
            None => (WHITE_SPRITE, -1.0),
        };
        for i in [0, 1, 2, 0, 2, 3] {
            mesh.terrain.push(PackVertex {
                position: rel(corners[i]),
                color: c,
                normal: [normal.x as f32, normal.y as f32, normal.z as f32],
                uv0: sprite_corner(sprite, i),
                uv1: LIGHT,
                entity: [id, -1.0, 0.0, 0.0],
                lightmap: LIGHT_INT,
                ..Default::default()
            });
        }
    };
    for g in &scene.terrain.ground {
        let height = |x: f64, z: f64| g.height + g.slope[0] * (x - g.min[0]) + g.slope[1] * (z - g.min[1]);
        let (nx, nz) = ((g.max[0] - g.min[0]).ceil() as i64, (g.max[1] - g.min[1]).ceil() as i64);
        let normal = DVec3::new(-g.slope[0], 1.0, -g.slope[1]).normalize();
        for i in 0..nx {
            for k in 0..nz {
                let x0 = g.min[0] + i as f64;
                let z0 = g.min[1] + k as f64;
                let x1 = (x0 + 1.0).min(g.max[0]);
                let z1 = (z0 + 1.0).min(g.max[1]);
                let shade = if (i + k) % 2 == 0 { 1.0 } else { 0.86 };
                let color = [g.color[0] * shade, g.color[1] * shade, g.color[2] * shade];
                let p = |x: f64, z: f64| DVec3::new(x, height(x, z), z);
                terrain_quad([p(x0, z0), p(x0, z1), p(x1, z1), p(x1, z0)], normal, color, &g.block);
            }
        }
    }
    for b in &scene.terrain.boxes {
        for (corners, normal) in box_faces(DVec3::from(b.min), DVec3::from(b.max)) {
            terrain_quad(corners, normal, b.color, &b.block);
        }
    }

    // Translucent quads: the water surface per block, glass pane faces.
    let mut quads = Vec::new();
    if let Some(w) = &scene.water {
        let id = ids.id_of("minecraft:water") as f32;
        let (nx, nz) = (((w.max[0] - w.min[0]) / w.cell).ceil() as i64, ((w.max[1] - w.min[1]) / w.cell).ceil() as i64);
        for i in 0..nx {
            for k in 0..nz {
                let x0 = w.min[0] + i as f64 * w.cell;
                let z0 = w.min[1] + k as f64 * w.cell;
                let x1 = (x0 + w.cell).min(w.max[0]);
                let z1 = (z0 + w.cell).min(w.max[1]);
                let y = w.level;
                quads.push(Quad {
                    corners: [DVec3::new(x0, y, z0), DVec3::new(x0, y, z1), DVec3::new(x1, y, z1), DVec3::new(x1, y, z0)],
                    normal: DVec3::Y,
                    color: [w.tint[0], w.tint[1], w.tint[2], 1.0],
                    sprite: WATER_SPRITE,
                    entity: [id, 1.0, 0.0, 0.0],
                });
            }
        }
    }
    for pane in &scene.glass {
        let id = ids.id_of(&pane.block) as f32;
        for (corners, normal) in box_faces(DVec3::from(pane.min), DVec3::from(pane.max)) {
            quads.push(Quad { corners, normal, color: pane.color, sprite: WHITE_SPRITE, entity: [id, -1.0, 0.0, 0.0] });
        }
    }
    let local_camera = camera - origin;
    mesh.translucent = back_to_front(quads, local_camera, &rel);
    let mut kinds: Vec<OverlayKind> = scene.overlay.iter().map(|o| o.kind).collect();
    kinds.sort();
    kinds.dedup();
    for kind in kinds {
        let quads: Vec<Quad> = scene
            .overlay
            .iter()
            .filter(|o| o.kind == kind)
            .flat_map(|o| {
                box_faces(DVec3::from(o.min), DVec3::from(o.max)).into_iter().map(|(corners, normal)| Quad {
                    corners,
                    normal,
                    color: o.color,
                    sprite: WHITE_SPRITE,
                    entity: [-1.0, -1.0, 0.0, 0.0],
                })
            })
            .collect();
        mesh.overlay.push((kind, back_to_front(quads, local_camera, &rel)));
    }
    for entity in &scene.entities {
        let quads = box_faces(DVec3::from(entity.min), DVec3::from(entity.max))
            .into_iter()
            .map(|(corners, normal)| Quad { corners, normal, color: entity.color, sprite: WHITE_SPRITE, entity: [-1.0, -1.0, 0.0, 0.0] })
            .collect();
        mesh.entities.push((entity.name.clone(), back_to_front(quads, local_camera, &rel)));
    }
    if let Some(lod) = &scene.distant_horizons {
        let cells = |min: [f64; 2], max: [f64; 2], y: f64| {
            let (nx, nz) = (((max[0] - min[0]) / LOD_CELL).ceil() as i64, ((max[1] - min[1]) / LOD_CELL).ceil() as i64);
            (0..nx).flat_map(move |i| (0..nz).map(move |k| {
                let (x0, z0) = (min[0] + i as f64 * LOD_CELL, min[1] + k as f64 * LOD_CELL);
                let (x1, z1) = ((x0 + LOD_CELL).min(max[0]), (z0 + LOD_CELL).min(max[1]));
                [DVec3::new(x0, y, z0), DVec3::new(x0, y, z1), DVec3::new(x1, y, z1), DVec3::new(x1, y, z0)]
            }))
        };
        let light = 0.45 + 0.55 * DVec3::Y.dot(sun).max(0.0);
        for g in &lod.ground {
            let color = [(g.color[0] * light) as f32, (g.color[1] * light) as f32, (g.color[2] * light) as f32, 1.0];
            let material = lod_material(g.block.as_deref());
            for corners in cells(g.min, g.max, g.height) {
                for i in [0, 1, 2, 0, 2, 3] {
                    mesh.lod_terrain.push(lod_vertex(rel(corners[i]), color, material));
                }
            }
        }
        let quads = lod
            .water
            .iter()
            .flat_map(|w| {
                let color = [w.tint[0], w.tint[1], w.tint[2], 1.0];
                cells(w.min, w.max, w.level).map(move |corners| Quad { corners, normal: DVec3::Y, color, sprite: WATER_SPRITE, entity: [0.0; 4] })
            })
            .collect();
        let material = lod_material(Some("minecraft:water"));
        mesh.lod_translucent =
            back_to_front(quads, camera - origin, &rel).into_iter().map(|v| lod_vertex(v.position, v.color, material)).collect();
    }
    mesh.sky = sky_box(scene);
    let (sun_quad, moon_quad) = sun_and_moon(scene);
    mesh.sun = sun_quad;
    mesh.moon = moon_quad;
    let all = [&mut mesh.terrain, &mut mesh.translucent, &mut mesh.sky, &mut mesh.sun, &mut mesh.moon];
    for vertices in all.into_iter().chain(mesh.overlay.iter_mut().map(|(_, v)| v)).chain(mesh.entities.iter_mut().map(|(_, v)| v)) {
        add_tangents_and_sprite_centres(vertices);
    }
    mesh
}

/// A vertex of Distant Horizons' LODs (see [`SceneMesh::lod_terrain`]); they face up.
fn lod_vertex(position: [f32; 4], color: [f32; 4], material: f32) -> PackVertex {
    PackVertex {
        position,
        color,
        normal: [0.0, 1.0, 0.0],
        uv0: [0.0, 0.0, 0.0, 1.0],
        uv1: LOD_LIGHT,
        entity: [material, 0.0, 0.0, 0.0],
        lightmap: LIGHT_INT,
        tangent: [1.0, 0.0, 0.0, 1.0],
        mid_uv: [0.0, 0.0, 0.0, 1.0],
    }
}

/// The sky: a box in the sky colour around the camera, inside the far plane, seen from inside.
fn sky_box(scene: &Scene) -> Vec<PackVertex> {
    let camera = scene.camera_position();
    let mut sky = Vec::new();
    let reach = 0.5 * scene.camera.far;
    let [r, g, b] = scene.sky.sky_color.map(|c| c as f32);
    for (corners, normal) in box_faces(camera - DVec3::splat(reach), camera + DVec3::splat(reach)) {
        for i in [0, 1, 2, 0, 2, 3] {
            let p = corners[i] - camera;
            sky.push(PackVertex {
                position: [p.x as f32, p.y as f32, p.z as f32, 1.0],
                color: [r, g, b, 1.0],
                normal: [-normal.x as f32, -normal.y as f32, -normal.z as f32],
                uv0: sprite_corner(WHITE_SPRITE, i),
                uv1: LIGHT,
                entity: [-1.0, -1.0, 0.0, 0.0],
                lightmap: LIGHT_INT,
                ..Default::default()
            });
        }
    }
    sky
}

/// The sun and the moon as the game draws them.
fn sun_and_moon(scene: &Scene) -> (Vec<PackVertex>, Vec<PackVertex>) {
    // The game's sun and moon: in the frame rotated with the sun's path, the sun a 60-block
    // square at y = 100, the moon a 40-block one at y = -100 (vertices here already rotated, so
    // gl_ModelViewMatrix stays gbufferModelView).
    let path = SunPath::of_sun_direction(scene.sun_direction());
    let rotation = glam::DMat3::from_rotation_y(-90f64.to_radians())
        * glam::DMat3::from_rotation_z(path.rotation.to_radians())
        * glam::DMat3::from_rotation_x(path.celestial_angle * std::f64::consts::TAU);
    let alpha = (1.0 - scene.sky.rain_strength) as f32;
    let celestial_quad = |half: f64, y: f64| -> Vec<PackVertex> {
        let corners = [DVec3::new(-half, y, -half), DVec3::new(half, y, -half), DVec3::new(half, y, half), DVec3::new(-half, y, half)];
        let uv = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let normal = rotation * DVec3::new(0.0, -y.signum(), 0.0);
        [0, 1, 2, 0, 2, 3]
            .into_iter()
            .map(|i| {
                let p = rotation * corners[i];
                PackVertex {
                    position: [p.x as f32, p.y as f32, p.z as f32, 1.0],
                    color: [1.0, 1.0, 1.0, alpha],
                    normal: [normal.x as f32, normal.y as f32, normal.z as f32],
                    uv0: [uv[i][0], uv[i][1], 0.0, 1.0],
                    uv1: LIGHT,
                    entity: [-1.0, -1.0, 0.0, 0.0],
                    lightmap: LIGHT_INT,
                    ..Default::default()
                }
            })
            .collect()
    };
    (celestial_quad(30.0, 100.0), celestial_quad(20.0, -100.0))
}

/// Triangles of `quads` sorted back to front by centre distance from `camera`; ties keep their
/// order (the sort is stable).
fn back_to_front(mut quads: Vec<Quad>, camera: DVec3, rel: &dyn Fn(DVec3) -> [f32; 4]) -> Vec<PackVertex> {
    let distance = |q: &Quad| ((q.corners[0] + q.corners[1] + q.corners[2] + q.corners[3]) * 0.25 - camera).length_squared();
    quads.sort_by(|a, b| distance(b).total_cmp(&distance(a)));
    let mut vertices = Vec::with_capacity(quads.len() * 6);
    for q in &quads {
        let color = q.color.map(|c| c as f32);
        let normal = [q.normal.x as f32, q.normal.y as f32, q.normal.z as f32];
        for i in [0, 1, 2, 0, 2, 3] {
            vertices.push(PackVertex {
                position: rel(q.corners[i]),
                color,
                normal,
                uv0: sprite_corner(q.sprite, i),
                uv1: LIGHT,
                entity: q.entity,
                lightmap: LIGHT_INT,
                ..Default::default()
            });
        }
    }
    vertices
}

/// Fills each triangle's `tangent` (from how its atlas coordinates run over it, made
/// perpendicular to the normal; any perpendicular where they do not run) and `mid_uv` (the
/// centre of the triangle's coordinate range, which for half a quad is the sprite's).
fn add_tangents_and_sprite_centres(vertices: &mut [PackVertex]) {
    for triangle in vertices.chunks_exact_mut(3) {
        let p = |v: &PackVertex| glam::Vec3::new(v.position[0], v.position[1], v.position[2]);
        let uv = |v: &PackVertex| glam::Vec2::new(v.uv0[0], v.uv0[1]);
        let normal = glam::Vec3::from(triangle[0].normal).normalize_or(glam::Vec3::Y);
        let (e1, e2) = (p(&triangle[1]) - p(&triangle[0]), p(&triangle[2]) - p(&triangle[0]));
        let (d1, d2) = (uv(&triangle[1]) - uv(&triangle[0]), uv(&triangle[2]) - uv(&triangle[0]));
        let det = d1.x * d2.y - d2.x * d1.y;
        let (tangent, handedness) = if det.abs() > 1e-12 {
            let t = (e1 * d2.y - e2 * d1.y) / det;
            let b = (e2 * d1.x - e1 * d2.x) / det;
            let t = (t - normal * normal.dot(t)).normalize_or(normal.any_orthonormal_vector());
            (t, if normal.cross(t).dot(b) < 0.0 { -1.0 } else { 1.0 })
        } else {
            (normal.any_orthonormal_vector(), 1.0)
        };
        let lo = uv(&triangle[0]).min(uv(&triangle[1])).min(uv(&triangle[2]));
        let hi = uv(&triangle[0]).max(uv(&triangle[1])).max(uv(&triangle[2]));
        let mid = (lo + hi) * 0.5;
        for v in triangle {
            v.tangent = [tangent.x, tangent.y, tangent.z, handedness];
            v.mid_uv = [mid.x, mid.y, 0.0, 1.0];
        }
    }
}

/// The texture coordinates of corner `i` of a quad (corners in the order of [`box_faces`]).
fn sprite_corner([u0, v0, u1, v1]: [f32; 4], i: usize) -> [f32; 4] {
    let [u, v] = [[u0, v0], [u0, v1], [u1, v1], [u1, v0]][i];
    [u, v, 0.0, 1.0]
}

/// The six faces of a box with outward normals.
fn box_faces(min: DVec3, max: DVec3) -> Vec<([DVec3; 4], DVec3)> {
    let p = |x: bool, y: bool, z: bool| {
        DVec3::new(if x { max.x } else { min.x }, if y { max.y } else { min.y }, if z { max.z } else { min.z })
    };
    vec![
        ([p(false, true, false), p(false, true, true), p(true, true, true), p(true, true, false)], DVec3::Y),
        ([p(false, false, false), p(true, false, false), p(true, false, true), p(false, false, true)], DVec3::NEG_Y),
        ([p(false, false, false), p(false, false, true), p(false, true, true), p(false, true, false)], DVec3::NEG_X),
        ([p(true, false, false), p(true, true, false), p(true, true, true), p(true, false, true)], DVec3::X),
        ([p(false, false, false), p(false, true, false), p(true, true, false), p(true, false, false)], DVec3::NEG_Z),
        ([p(false, false, true), p(true, false, true), p(true, true, true), p(false, true, true)], DVec3::Z),
    ]
}

/// The block atlas: a row of 16×16 RGBA8 sprites from a fixed seed. Water and white are one
/// uniform colour each (our own pack's frames and goldens draw with them, and nearest sampling
/// of a pattern would make the two renderers' texel choices at sprite edges matter there); the
/// blocks of [`BLOCK_SPRITES`] are noisy, leaves with transparent holes.
pub fn atlas() -> (u32, u32, Vec<u8>) {
    let (w, h) = ATLAS_SIZE;
    let mut rng = SplitMix64::seed_from_u64(0xA71A5);
    // Per sprite: base colour, texel-to-texel variation, and the share of transparent texels.
    let sprites: [([f64; 3], f64, f64); ATLAS_SPRITES as usize] = [
        ([0.8, 0.8, 0.8], 0.0, 0.0),     // water (alpha 184 below)
        ([1.0, 1.0, 1.0], 0.0, 0.0),     // white
        ([0.5, 0.5, 0.5], 0.25, 0.0),    // stone
        ([0.36, 0.6, 0.25], 0.2, 0.0),   // grass
        ([0.86, 0.81, 0.6], 0.12, 0.0),  // sand
        ([0.52, 0.37, 0.26], 0.2, 0.0),  // dirt
        ([0.3, 0.55, 0.2], 0.3, 0.3),    // oak leaves: cutout holes
        ([1.0, 1.0, 1.0], 0.0, 0.0),     // unused
    ];
    let mut texels = vec![[0u8; 4]; (w * h) as usize];
    for (index, (base, variation, holes)) in sprites.iter().enumerate() {
        for y in 0..SPRITE {
            for x in 0..SPRITE {
                let shade = 1.0 - variation * (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
                let hole = (rng.next_u64() >> 11) as f64 / ((1u64 << 53) as f64) < *holes;
                let alpha = match index {
                    0 => 184,
                    _ if hole => 0,
                    _ => 255,
                };
                let texel = base.map(|c| (c * shade * 255.0).round() as u8);
                texels[(y * w + index as u32 * SPRITE + x) as usize] = [texel[0], texel[1], texel[2], alpha];
            }
        }
    }
    (w, h, texels.concat())
}

/// The sun's texture: 32×32 RGBA8, a bright square in the middle quarter with a fading glow
/// around it, black elsewhere (the game adds it onto the sky).
pub fn sun() -> (u32, u32, Vec<u8>) {
    celestial_texture(|d| match d {
        d if d < 0.25 => [255, 250, 225],
        d if d < 0.5 => {
            let glow = (0.5 - d) * 2.0;
            [(220.0 * glow) as u8, (200.0 * glow) as u8, (140.0 * glow) as u8]
        }
        _ => [0, 0, 0],
    })
}

/// The moon's texture (full moon): 32×32 RGBA8, a grey square with darker speckles in the
/// middle third, black elsewhere.
pub fn moon() -> (u32, u32, Vec<u8>) {
    let mut rng = SplitMix64::seed_from_u64(0x300D);
    celestial_texture(move |d| {
        let shade = 200 - (rng.next_u64() >> 59) as u8 * 6;
        if d < 0.35 { [shade, shade, shade.saturating_add(8)] } else { [0, 0, 0] }
    })
}

/// A 32×32 texture whose colour depends on the distance from the centre (0 at the centre, 1
/// at the edges, square rings); alpha 255.
fn celestial_texture(mut colour: impl FnMut(f64) -> [u8; 3]) -> (u32, u32, Vec<u8>) {
    let size = 32u32;
    let mut data = Vec::with_capacity((size * size * 4) as usize);
    for y in 0..size {
        for x in 0..size {
            let ring = |c: u32| ((c as f64 + 0.5) / size as f64 * 2.0 - 1.0).abs();
            let [r, g, b] = colour(ring(x).max(ring(y)));
            data.extend([r, g, b, 255]);
        }
    }
    (size, size, data)
}

/// The mock lightmap: 16×16 RGBA8, u = block light (warm), v = sky light.
pub fn lightmap() -> (u32, u32, Vec<u8>) {
    let mut data = Vec::with_capacity(16 * 16 * 4);
    for v in 0..16 {
        for u in 0..16 {
            let sky = 0.05 + 0.95 * (v as f64 / 15.0);
            let block = u as f64 / 15.0;
            let r = (sky + block * 0.9).min(1.0);
            let g = (sky + block * 0.7).min(1.0);
            let b = (sky + block * 0.4).min(1.0);
            data.extend([r, g, b].map(|c| (c * 255.0).round() as u8));
            data.push(255);
        }
    }
    (16, 16, data)
}

/// OptiFine's `noisetex`: RGB white noise, 256×256, opaque; a fixed-seed generator so every
/// run and both renderers see the same texture.
pub fn noise(size: u32) -> (u32, u32, Vec<u8>) {
    let mut rng = SplitMix64::seed_from_u64(0x9E37_79B9_7F4A_7C15);
    let mut data = Vec::with_capacity((size * size * 4) as usize);
    for _ in 0..size * size {
        data.extend([0; 3].map(|_: u8| (rng.next_u64() >> 56) as u8));
        data.push(255);
    }
    (size, size, data)
}

/// The format of one [`PackVertex`] attribute as a vertex stage reads it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AttributeFormat {
    Float32x2,
    Float32x3,
    Float32x4,
    Sint32x2,
}

impl AttributeFormat {
    /// Components per vertex.
    pub fn components(self) -> i32 {
        match self {
            AttributeFormat::Float32x2 | AttributeFormat::Sint32x2 => 2,
            AttributeFormat::Float32x3 => 3,
            AttributeFormat::Float32x4 => 4,
        }
    }
}

/// The vertex input Iris reads Distant Horizons' material id from (in x), which the harness
/// declares where a dh_* program uses `dhMaterialId`; the LOD vertices carry the id in
/// `entity`.
pub const LOD_MATERIAL_INPUT: &str = "irisExtra";

/// Where a vertex stage's input of this shipped name is in [`PackVertex`], and its format.
pub fn attribute_source(name: &str) -> Option<(AttributeFormat, u64)> {
    Some(match name {
        "gl_Vertex" => (AttributeFormat::Float32x4, offsets::POSITION),
        "gl_Color" => (AttributeFormat::Float32x4, offsets::COLOR),
        "gl_Normal" => (AttributeFormat::Float32x3, offsets::NORMAL),
        "gl_MultiTexCoord0" => (AttributeFormat::Float32x4, offsets::UV0),
        "gl_MultiTexCoord1" => (AttributeFormat::Float32x4, offsets::UV1),
        "mc_Entity" => (AttributeFormat::Float32x4, offsets::ENTITY),
        LOD_MATERIAL_INPUT => (AttributeFormat::Float32x4, offsets::ENTITY),
        "at_tangent" => (AttributeFormat::Float32x4, offsets::TANGENT),
        "mc_midTexCoord" => (AttributeFormat::Float32x4, offsets::MID_UV),
        // The 1.17+ core profile's names for the same data (positions relative to the chunk
        // at chunkOffset, which is the origin of the harness's camera-relative vertices).
        "vaPosition" => (AttributeFormat::Float32x3, offsets::POSITION),
        "vaColor" => (AttributeFormat::Float32x4, offsets::COLOR),
        "vaNormal" => (AttributeFormat::Float32x3, offsets::NORMAL),
        "vaUV0" => (AttributeFormat::Float32x2, offsets::UV0),
        "vaUV2" => (AttributeFormat::Sint32x2, offsets::LIGHTMAP),
        _ => return None,
    })
}

/// The data for a vertex input named `name` that the shipped text may place itself at
/// `declared` (`layout(location = N)`): by its name ([`attribute_source`]), or else, as NVIDIA's
/// driver aliases the generic locations 0, 2, 3, 8 and 9 to the legacy position, normal, colour
/// and first two texture coordinates, the legacy input at that location.
pub fn input_source(name: &str, declared: Option<u32>) -> Option<(AttributeFormat, u64)> {
    let aliased = |location| match location {
        0 => Some("gl_Vertex"),
        2 => Some("gl_Normal"),
        3 => Some("gl_Color"),
        8 => Some("gl_MultiTexCoord0"),
        9 => Some("gl_MultiTexCoord1"),
        _ => None,
    };
    attribute_source(name).or_else(|| attribute_source(declared.and_then(aliased)?))
}

impl PackVertex {
    /// The vertex with its position, colour, normal and texture coordinates moved by `relative`
    /// of themselves; the block ids and the integer lightmap kept.
    pub fn nudged(&self, relative: f32) -> PackVertex {
        let scale = |v: &mut [f32]| v.iter_mut().for_each(|x| *x *= 1.0 + relative);
        let mut v = *self;
        scale(&mut v.position[..3]);
        scale(&mut v.color);
        scale(&mut v.normal);
        scale(&mut v.uv0);
        scale(&mut v.uv1);
        v
    }
}

impl SceneMesh {
    /// Every vertex [`PackVertex::nudged`].
    pub fn nudged(&self, relative: f32) -> SceneMesh {
        let all = |vertices: &[PackVertex]| vertices.iter().map(|v| v.nudged(relative)).collect::<Vec<_>>();
        SceneMesh {
            terrain: all(&self.terrain),
            translucent: all(&self.translucent),
            overlay: self.overlay.iter().map(|(kind, vertices)| (*kind, all(vertices))).collect(),
            entities: self.entities.iter().map(|(name, vertices)| (name.clone(), all(vertices))).collect(),
            sky: all(&self.sky),
            sun: all(&self.sun),
            moon: all(&self.moon),
            lod_terrain: all(&self.lod_terrain),
            lod_translucent: all(&self.lod_translucent),
        }
    }
}

/// The full-screen quad OptiFine draws: x, y in 0..1 under an orthographic projection,
/// texture coordinates 0..1, as two triangles.
pub fn fullscreen_quad() -> Vec<PackVertex> {
    let corner = |x: f32, y: f32| PackVertex {
        position: [x, y, 0.0, 1.0],
        color: [1.0; 4],
        normal: [0.0, 0.0, 1.0],
        uv0: [x, y, 0.0, 1.0],
        uv1: [0.0, 0.0, 0.0, 1.0],
        entity: [-1.0, -1.0, 0.0, 0.0],
        lightmap: [0, 0],
        tangent: [1.0, 0.0, 0.0, 1.0],
        mid_uv: [0.5, 0.5, 0.0, 1.0],
    };
    [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 0.0), (1.0, 1.0), (0.0, 1.0)].iter().map(|&(x, y)| corner(x, y)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    struct NoIds;
    impl BlockIds for NoIds {
        fn id_of(&self, _: &str) -> i32 {
            -1
        }
    }

    #[test]
    fn the_sun_and_the_moon_stand_100_blocks_out_on_either_side() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/scenes/blocks/shore.toml");
        let scene = Scene::load(&path).unwrap();
        let mesh = build(&scene, &NoIds);
        let centre = |quad: &[PackVertex]| {
            let sum = quad.iter().fold(glam::Vec3::ZERO, |s, v| s + glam::Vec3::new(v.position[0], v.position[1], v.position[2]));
            (sum / quad.len() as f32).as_dvec3()
        };
        let sun = scene.sun_direction();
        assert!((centre(&mesh.sun) - sun * 100.0).length() < 1e-3, "{:?}", centre(&mesh.sun));
        assert!((centre(&mesh.moon) + sun * 100.0).length() < 1e-3, "{:?}", centre(&mesh.moon));
    }

    #[test]
    fn faces_carry_a_unit_tangent_along_the_atlas_u_and_their_sprite_centre() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/scenes/case4_above_near.toml");
        let mesh = build(&Scene::load(&path).unwrap(), &NoIds);
        let white_centre = [(WHITE_SPRITE[0] + WHITE_SPRITE[2]) / 2.0, (WHITE_SPRITE[1] + WHITE_SPRITE[3]) / 2.0];
        let water_centre = [(WATER_SPRITE[0] + WATER_SPRITE[2]) / 2.0, (WATER_SPRITE[1] + WATER_SPRITE[3]) / 2.0];
        for v in mesh.terrain.iter().chain(&mesh.translucent) {
            let t = glam::Vec3::new(v.tangent[0], v.tangent[1], v.tangent[2]);
            assert!((t.length() - 1.0).abs() < 1e-5 && t.dot(glam::Vec3::from(v.normal)).abs() < 1e-5, "{v:?}");
            assert!(v.tangent[3].abs() == 1.0);
            assert!([white_centre, water_centre].iter().any(|c| (v.mid_uv[0] - c[0]).abs() < 1e-6 && (v.mid_uv[1] - c[1]).abs() < 1e-6), "{v:?}");
        }
        // The water surface: u runs along +x over each cell (sprite_corner's corner order).
        let water = mesh.translucent.iter().find(|v| v.normal == [0.0, 1.0, 0.0]).unwrap();
        assert_eq!(water.tangent, [1.0, 0.0, 0.0, water.tangent[3]]);
    }
}
