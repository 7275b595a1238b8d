//! The scene's solid geometry in f64, camera-relative: ground rectangles (sloped planes cut in
//! one-block cells), boxes, glass panes and overlay boxes, each intersected analytically. What a
//! surface looks like comes from the harness's own mesh (`tidepack_scene::mesh::build`): each
//! cell or face is matched to its quad there, and its vertex colour (already lit by the mesh),
//! atlas coordinates and lightmap coordinates are the GPU's, sampled from the generated atlas
//! and lightmap (`mesh::atlas`, `mesh::lightmap`) as the pack's gbuffers programs sample them.

use glam::{DVec2, DVec3, DVec4};
use tidepack_reference::{Filter, Texture, Wrap};
use tidepack_scene::Scene;
use tidepack_scene::mesh::{self, BlockIds, PackVertex};

/// The alpha test of OptiFine 1.17+ and Iris (`alphaTestRef`, as the harness sets it for
/// gbuffers): a texel below it is a hole.
const ALPHA_TEST: f64 = 0.1;

/// What a ray met.
#[derive(Clone, Copy, Debug)]
pub enum Hit {
    /// Terrain: the colour the pack's gbuffers program writes before fog (vertex colour ×
    /// atlas texel × lightmap) and the face's normal as the mesh lights it.
    /// `view_distance` is the pack's `viewDistance` there: the vertices' distances from the
    /// eye interpolated over the triangle, which vanilla.glsl fogs by.
    Opaque { t: f64, point: DVec3, normal: DVec3, colour: DVec3, vertex: DVec3, view_distance: f64 },
    /// A face of a glass pane: its colour (rgb × lightmap) and opacity.
    Glass { t: f64, point: DVec3, normal: DVec3, colour: DVec4 },
}

impl Hit {
    pub fn t(&self) -> f64 {
        match *self {
            Hit::Opaque { t, .. } | Hit::Glass { t, .. } => t,
        }
    }
}

/// A quad's attributes from the mesh: the affine map from position to atlas coordinates (exact
/// over the whole quad, which is a parallelogram) and its vertex colour.
#[derive(Clone, Copy, Debug)]
struct Attributes {
    p0: DVec3,
    e1: DVec3,
    e2: DVec3,
    uv0: DVec2,
    duv1: DVec2,
    duv2: DVec2,
    /// Inverse of the Gram matrix of (e1, e2).
    gram_inverse: [f64; 4],
    colour: DVec4,
    light_uv: DVec2,
    normal: DVec3,
    /// The distances of the quad's four corners from the eye.
    corner_distances: [f64; 4],
}

impl Attributes {
    /// From the six vertices of a quad (corners 0, 1, 2, 0, 2, 3).
    fn of(triangle: &[PackVertex]) -> Attributes {
        let p = |v: &PackVertex| DVec3::new(v.position[0] as f64, v.position[1] as f64, v.position[2] as f64);
        let uv = |v: &PackVertex| DVec2::new(v.uv0[0] as f64, v.uv0[1] as f64);
        let (p0, e1, e2) = (p(&triangle[0]), p(&triangle[1]) - p(&triangle[0]), p(&triangle[2]) - p(&triangle[0]));
        let (a, b, d) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
        let det = a * d - b * b;
        let c = triangle[0].color.map(|x| x as f64);
        // gl_TextureMatrix[1] of the harness: raw 0..240 → (raw + 8) / 256.
        let light_uv = DVec2::new(triangle[0].uv1[0] as f64 + 8.0, triangle[0].uv1[1] as f64 + 8.0) / 256.0;
        Attributes {
            p0,
            e1,
            e2,
            uv0: uv(&triangle[0]),
            duv1: uv(&triangle[1]) - uv(&triangle[0]),
            duv2: uv(&triangle[2]) - uv(&triangle[0]),
            gram_inverse: [d / det, -b / det, -b / det, a / det],
            colour: DVec4::from_array(c),
            light_uv,
            normal: DVec3::from_array(triangle[0].normal.map(|x| x as f64)),
            corner_distances: [0, 1, 2, 5].map(|i| p(&triangle[i]).length()),
        }
    }

    /// `p`'s coordinates along (e1, e2) from corner 0.
    fn coordinates(&self, p: DVec3) -> (f64, f64) {
        let q = p - self.p0;
        let (r1, r2) = (q.dot(self.e1), q.dot(self.e2));
        let [i00, i01, i10, i11] = self.gram_inverse;
        (i00 * r1 + i01 * r2, i10 * r1 + i11 * r2)
    }

    fn uv(&self, p: DVec3) -> DVec2 {
        let (s, t) = self.coordinates(p);
        self.uv0 + s * self.duv1 + t * self.duv2
    }

    /// The vertex distances interpolated at `p` over the triangle (0, 1, 2) or (0, 2, 3) that
    /// holds it, as the rasteriser interpolates `viewDistance` (perspective-correct, so the
    /// 3D barycentric weights).
    fn view_distance(&self, p: DVec3) -> f64 {
        let (s, t) = self.coordinates(p);
        let [d0, d1, d2, d3] = self.corner_distances;
        // Corner 3 is (-1, 1) in these coordinates.
        if s >= 0.0 { (1.0 - s - t) * d0 + s * d1 + t * d2 } else { (1.0 - t) * d0 + (t + s) * d2 - s * d3 }
    }
}

#[derive(Clone, Debug)]
enum Shape {
    /// A ground: y = height + slope·(xz − min) over [min, max], cells of one block from `min`.
    Ground { min: DVec2, max: DVec2, height: f64, slope: DVec2, cells: (usize, usize), first: usize },
    Block { min: DVec3, max: DVec3, first: usize },
}

/// The box faces in the order of mesh.rs's `box_faces`: +y, −y, −x, +x, −z, +z.
const FACE_NORMALS: [DVec3; 6] = [DVec3::Y, DVec3::NEG_Y, DVec3::NEG_X, DVec3::X, DVec3::NEG_Z, DVec3::Z];

struct NoIds;

impl BlockIds for NoIds {
    fn id_of(&self, _: &str) -> i32 {
        -1
    }
}

/// The scene's geometry as the truth intersects it.
#[derive(Clone, Debug)]
pub struct Geometry {
    shapes: Vec<Shape>,
    quads: Vec<Attributes>,
    panes: Vec<(DVec3, DVec3, DVec4)>,
    overlays: Vec<(DVec3, DVec3)>,
    atlas: Texture,
    lightmap: Texture,
}

/// The slab test of a ray against a box: (t entering, entering face, t leaving, leaving face),
/// faces indexed as [`FACE_NORMALS`].
fn slabs(o: DVec3, d: DVec3, min: DVec3, max: DVec3) -> Option<(f64, usize, f64, usize)> {
    let (mut t0, mut f0, mut t1, mut f1) = (f64::NEG_INFINITY, 0, f64::INFINITY, 0);
    // Faces per axis: (low face, high face).
    let faces = [(2usize, 3usize), (1, 0), (4, 5)];
    for axis in 0..3 {
        let (low, high) = faces[axis];
        if d[axis] == 0.0 {
            if o[axis] < min[axis] || o[axis] > max[axis] {
                return None;
            }
            continue;
        }
        let (ta, tb) = ((min[axis] - o[axis]) / d[axis], (max[axis] - o[axis]) / d[axis]);
        let (near, near_face, far, far_face) = if ta < tb { (ta, low, tb, high) } else { (tb, high, ta, low) };
        if near > t0 {
            t0 = near;
            f0 = near_face;
        }
        if far < t1 {
            t1 = far;
            f1 = far_face;
        }
    }
    (t0 <= t1).then_some((t0, f0, t1, f1))
}

impl Geometry {
    pub fn of(scene: &Scene) -> Geometry {
        let built = mesh::build(scene, &NoIds);
        let shift = DVec3::from(scene.origin) - scene.camera_position();
        let quads: Vec<Attributes> = built.terrain.chunks_exact(6).map(Attributes::of).collect();
        let mut shapes = Vec::new();
        let mut first = 0;
        // mesh.rs emits the grounds' cells (x outer, z inner), then six faces per box.
        for g in &scene.terrain.ground {
            let cells = ((g.max[0] - g.min[0]).ceil().max(0.0) as usize, (g.max[1] - g.min[1]).ceil().max(0.0) as usize);
            shapes.push(Shape::Ground {
                min: DVec2::new(g.min[0] + shift.x, g.min[1] + shift.z),
                max: DVec2::new(g.max[0] + shift.x, g.max[1] + shift.z),
                height: g.height + shift.y,
                slope: DVec2::from(g.slope),
                cells,
                first,
            });
            first += cells.0 * cells.1;
        }
        for b in &scene.terrain.boxes {
            shapes.push(Shape::Block { min: DVec3::from(b.min) + shift, max: DVec3::from(b.max) + shift, first });
            first += 6;
        }
        assert_eq!(first, quads.len(), "the mesh's terrain quads are the grounds' cells and the boxes' faces");
        let rounded = |c: [f64; 4]| DVec4::from_array(c.map(|x| x as f32 as f64));
        let panes = scene.glass.iter().map(|p| (DVec3::from(p.min) + shift, DVec3::from(p.max) + shift, rounded(p.color))).collect();
        let overlays = scene.overlay.iter().map(|o| (DVec3::from(o.min) + shift, DVec3::from(o.max) + shift)).collect();
        let (aw, ah, atlas) = mesh::atlas();
        let (lw, lh, lightmap) = mesh::lightmap();
        Geometry {
            shapes,
            quads,
            panes,
            overlays,
            // The harness binds the atlas nearest + repeat and the lightmap linear + clamp.
            atlas: Texture::from_rgba8(aw as usize, ah as usize, &atlas, Filter::Nearest, Wrap::Repeat),
            lightmap: Texture::from_rgba8(lw as usize, lh as usize, &lightmap, Filter::Linear, Wrap::ClampToEdge),
        }
    }

    /// The opaque surface of quad `q` at `p`: None where the alpha test drops the texel.
    fn opaque(&self, q: usize, t: f64, p: DVec3) -> Option<Hit> {
        let a = &self.quads[q];
        let texel = self.atlas.sample(a.uv(p));
        if a.colour.w * texel.w < ALPHA_TEST {
            return None;
        }
        let light = self.lightmap.sample(a.light_uv).truncate();
        let vertex = a.colour.truncate();
        Some(Hit::Opaque { t, point: p, normal: a.normal, colour: vertex * texel.truncate() * light, vertex, view_distance: a.view_distance(p) })
    }

    /// The nearest opaque surface or glass face along `o + t·d`, t in (t_min, t_max).
    pub fn hit(&self, o: DVec3, d: DVec3, t_min: f64, t_max: f64) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        let mut limit = t_max;
        for shape in &self.shapes {
            let mut lo = t_min;
            // At most a few holes per shape: each failed alpha test moves on past it.
            for _ in 0..64 {
                let Some((t, q)) = self.shape_hit(shape, o, d, lo, limit) else { break };
                match self.opaque(q, t, o + d * t) {
                    Some(hit) => {
                        limit = t;
                        best = Some(hit);
                        break;
                    }
                    None => lo = t,
                }
            }
        }
        for &(min, max, colour) in &self.panes {
            if let Some((t0, f0, t1, f1)) = slabs(o, d, min, max) {
                let (t, face) = if t0 > t_min { (t0, f0) } else { (t1, f1) };
                // A texel clearer than 1/255 covers nothing (lib/translucent.glsl).
                if t > t_min && t < limit && colour.w >= 1.0 / 255.0 {
                    limit = t;
                    let light = self.lightmap.sample(DVec2::new(8.0, 248.0) / 256.0).truncate();
                    best = Some(Hit::Glass { t, point: o + d * t, normal: FACE_NORMALS[face], colour: (colour.truncate() * light).extend(colour.w) });
                }
            }
        }
        best
    }

    /// The entry (or, from inside, exit) of `shape` along the ray in (t_min, t_max), with the
    /// mesh quad there.
    fn shape_hit(&self, shape: &Shape, o: DVec3, d: DVec3, t_min: f64, t_max: f64) -> Option<(f64, usize)> {
        match *shape {
            Shape::Ground { min, max, height, slope, cells, first } => {
                let f0 = o.y - height - slope.x * (o.x - min.x) - slope.y * (o.z - min.y);
                let rate = d.y - slope.x * d.x - slope.y * d.z;
                if rate == 0.0 {
                    return None;
                }
                let t = -f0 / rate;
                if !(t > t_min && t < t_max) {
                    return None;
                }
                let p = o + d * t;
                if p.x < min.x || p.x > max.x || p.z < min.y || p.z > max.y {
                    return None;
                }
                let i = ((p.x - min.x).floor().max(0.0) as usize).min(cells.0 - 1);
                let k = ((p.z - min.y).floor().max(0.0) as usize).min(cells.1 - 1);
                Some((t, first + i * cells.1 + k))
            }
            Shape::Block { min, max, first } => {
                let (t0, f0, t1, f1) = slabs(o, d, min, max)?;
                let (t, face) = if t0 > t_min { (t0, f0) } else { (t1, f1) };
                (t > t_min && t < t_max).then_some((t, first + face))
            }
        }
    }

    /// Whether an overlay box (rain, clouds, particles, the hand) lies along the ray before
    /// `t_max`: the truth leaves overlays out and masks these pixels.
    pub fn overlay_before(&self, o: DVec3, d: DVec3, t_max: f64) -> bool {
        self.overlays.iter().any(|&(min, max)| slabs(o, d, min, max).is_some_and(|(t0, _, t1, _)| t1 > 0.0 && t0 < t_max))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ground_cell_has_the_mesh_colour_and_atlas_texel() {
        let scene = Scene::load(std::path::Path::new("case4_above_near")).unwrap();
        let g = Geometry::of(&scene);
        let built = mesh::build(&scene, &NoIds);
        // Straight down from the camera: the sea floor between the pool and the beach.
        let hit = g.hit(DVec3::ZERO, DVec3::NEG_Y, 0.0, 1e4).unwrap();
        let Hit::Opaque { t, colour, vertex, normal, .. } = hit else { panic!("{hit:?}") };
        assert!((t - 13.0).abs() < 1e-12 && normal == DVec3::Y, "{t}");
        // The cell under the camera (x = 0, z = -2 in a ground from (-9, -7)): i = 9, k = 5.
        let q = 9 * 15 + 5 + 23 * 40 + 23 * 40;
        let c = built.terrain[6 * q].color;
        assert_eq!(vertex, DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64));
        // No block: the white sprite, and full sky light, so the colour is the vertex colour.
        assert!((colour - vertex).abs().max_element() < 1e-12, "{colour} vs {vertex}");
    }
}
