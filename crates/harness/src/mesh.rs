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

use crate::scene::{OverlayKind, Scene};

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

/// Sprites of the mock block atlas (`gtexture`): uv rectangles inset from the sprite edges so
/// nearest sampling never reaches a neighbour. Glass and terrain take their colour from the
/// vertex colour over the opaque white sprite.
pub const WATER_SPRITE: [f32; 4] = [0.0625, 0.125, 0.4375, 0.875];
pub const WHITE_SPRITE: [f32; 4] = [0.5625, 0.125, 0.9375, 0.875];

/// Lightmap coordinates of everything in the scenes: no block light, full sky light.
const LIGHT: [f32; 4] = [0.0, 240.0, 0.0, 1.0];
const LIGHT_INT: [i32; 2] = [0, 240];

#[derive(Clone, Debug, Default)]
pub struct SceneMesh {
    /// Triangles; the colour is lit once here (ambient and sun).
    pub terrain: Vec<PackVertex>,
    /// Triangles, back to front.
    pub translucent: Vec<PackVertex>,
    /// Rain, clouds, particles and the translucent hand: triangles per kind, back to front.
    pub overlay: Vec<(OverlayKind, Vec<PackVertex>)>,
    /// The sky as the game draws it for gbuffers_skybasic: a box around the camera in the sky
    /// colour, inside the far plane, drawn before the terrain without writing depth.
    pub sky: Vec<PackVertex>,
}

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
    let mut terrain_quad = |corners: [DVec3; 4], normal: DVec3, color: [f64; 3]| {
        let light = 0.45 + 0.55 * normal.dot(sun).max(0.0);
        let c = [(color[0] * light) as f32, (color[1] * light) as f32, (color[2] * light) as f32, 1.0];
        for i in [0, 1, 2, 0, 2, 3] {
            mesh.terrain.push(PackVertex {
                position: rel(corners[i]),
                color: c,
                normal: [normal.x as f32, normal.y as f32, normal.z as f32],
                uv0: sprite_corner(WHITE_SPRITE, i),
                uv1: LIGHT,
                entity: [-1.0, -1.0, 0.0, 0.0],
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
                terrain_quad([p(x0, z0), p(x0, z1), p(x1, z1), p(x1, z0)], normal, color);
            }
        }
    }
    for b in &scene.terrain.boxes {
        for (corners, normal) in box_faces(DVec3::from(b.min), DVec3::from(b.max)) {
            terrain_quad(corners, normal, b.color);
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
    let reach = 0.5 * scene.camera.far;
    let [r, g, b] = scene.sky.sky_color.map(|c| c as f32);
    for (corners, normal) in box_faces(camera - DVec3::splat(reach), camera + DVec3::splat(reach)) {
        for i in [0, 1, 2, 0, 2, 3] {
            let p = corners[i] - camera;
            mesh.sky.push(PackVertex {
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
    for vertices in [&mut mesh.terrain, &mut mesh.translucent, &mut mesh.sky].into_iter().chain(mesh.overlay.iter_mut().map(|(_, v)| v)) {
        add_tangents_and_sprite_centres(vertices);
    }
    mesh
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

/// The mock block atlas: 32×16 RGBA8, a water sprite (left) and a glass sprite (right), each
/// one uniform colour (nearest sampling of a pattern would make the two renderers' texel
/// choices at sprite edges matter).
pub fn atlas() -> (u32, u32, Vec<u8>) {
    let (w, h) = (32u32, 16u32);
    let mut data = Vec::with_capacity((w * h * 4) as usize);
    for _y in 0..h {
        for x in 0..w {
            data.extend_from_slice(if x < 16 { &[204, 204, 204, 184] } else { &[255, 255, 255, 255] });
        }
    }
    (w, h, data)
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
