//! The sky, two ways. Along a straight line from the eye it is what the pack's G-buffer holds
//! there (the game's sky box in the sky colour, fogged as gbuffers_basic fogs it, with the
//! sun's and moon's textured quads added as gbuffers_skytextured adds them), so the sky
//! itself is no difference between the pack and the truth. Reached after a reflection or a
//! refraction it is the pack's own sky radiance (`skyRadiance` of lib/optics.glsl) plus the
//! sun (or the moon) as a disc of its real angular size.

use glam::{DVec2, DVec3};
use tidepack_reference::model::common::distance_fog;
use tidepack_reference::model::optics::sky_radiance;
use tidepack_reference::{Filter, Texture, Wrap};
use tidepack_scene::Scene;
use tidepack_scene::mesh::{self, BlockIds, PackVertex};

/// The sun's angular radius seen from the Earth (0.533° across).
pub const SUN_ANGULAR_RADIUS: f64 = 0.2665 * std::f64::consts::PI / 180.0;

/// The pack's sun glint (`specularLight`): (1, 0.95, 0.85)·8·max(r·l, 0)^256. Integrated over
/// the sphere of reflected directions, the lobe is 8·2π/257 per unit of its colour: that is
/// the irradiance the pack's sun delivers to a mirror, which the disc must match.
pub const GLINT_COLOUR: DVec3 = DVec3::new(1.0, 0.95, 0.85);
pub const GLINT_IRRADIANCE: f64 = 8.0 * std::f64::consts::TAU / 257.0;
/// `MOON_GLINT` of composite.fsh.
const MOON_GLINT: f64 = 0.1;

struct NoIds;

impl BlockIds for NoIds {
    fn id_of(&self, _: &str) -> i32 {
        -1
    }
}

/// A textured quad the game draws on the sky (two triangles of the mesh).
#[derive(Clone, Debug)]
struct Celestial {
    triangles: Vec<[(DVec3, DVec2); 3]>,
    texture: Texture,
    alpha: f64,
}

impl Celestial {
    fn of(vertices: &[PackVertex], (w, h, data): (u32, u32, Vec<u8>)) -> Celestial {
        let corner = |v: &PackVertex| {
            (DVec3::new(v.position[0] as f64, v.position[1] as f64, v.position[2] as f64), DVec2::new(v.uv0[0] as f64, v.uv0[1] as f64))
        };
        Celestial {
            triangles: vertices.chunks_exact(3).map(|t| [corner(&t[0]), corner(&t[1]), corner(&t[2])]).collect(),
            // The harness binds the sun's and moon's textures as it binds the atlas.
            texture: Texture::from_rgba8(w as usize, h as usize, &data, Filter::Nearest, Wrap::Repeat),
            alpha: vertices.first().map_or(0.0, |v| v.color[3] as f64),
        }
    }

    /// What the quad adds along the unit direction `d` from the eye (blend SRC_ALPHA, ONE).
    fn added(&self, d: DVec3) -> DVec3 {
        // OptiFine's alpha test of gbuffers programs drops the whole quad under heavy rain.
        if self.alpha < 0.1 {
            return DVec3::ZERO;
        }
        for [(p0, uv0), (p1, uv1), (p2, uv2)] in &self.triangles {
            let (e1, e2) = (*p1 - *p0, *p2 - *p0);
            let h = d.cross(e2);
            let det = e1.dot(h);
            if det.abs() < 1e-12 {
                continue;
            }
            let s = -*p0;
            let u = s.dot(h) / det;
            let q = s.cross(e1);
            let v = d.dot(q) / det;
            let t = e2.dot(q) / det;
            if t > 0.0 && u >= 0.0 && v >= 0.0 && u + v <= 1.0 {
                let uv = *uv0 + (*uv1 - *uv0) * u + (*uv2 - *uv0) * v;
                let texel = self.texture.sample(uv);
                return texel.truncate() * self.alpha;
            }
        }
        DVec3::ZERO
    }
}

/// The sky of one frame.
#[derive(Clone, Debug)]
pub struct Sky {
    pub sky_color: DVec3,
    pub fog_color: DVec3,
    /// The sky box's colour: sky colour fogged at its vertices' distance (√3 × half the
    /// render distance, the same at every corner, so the same everywhere on the box).
    box_colour: DVec3,
    sun: Celestial,
    moon: Celestial,
    /// Towards the light the pack's glint uses (`shadowLightPosition`: the sun by day, the
    /// moon by night).
    pub light_direction: DVec3,
    /// Radiance of the light's disc and the cosine of its angular radius.
    pub disc_radiance: DVec3,
    pub disc_cos: f64,
}

/// GLSL `smoothstep`.
fn smoothstep(e0: f64, e1: f64, x: f64) -> f64 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

impl Sky {
    pub fn of(scene: &Scene) -> Sky {
        let sky_color = DVec3::from(scene.sky.sky_color);
        let fog_color = DVec3::from(scene.sky.fog_color);
        let far = scene.camera.far;
        // gbuffers_basic fogs the sky box unless the eye is in water.
        let fog = if scene.eye_in_water() { 0.0 } else { distance_fog(3f64.sqrt() * 0.5 * far, far) };
        let built = mesh::build(scene, &NoIds);
        let sun = scene.sun_direction();
        let by_day = sun.y >= 0.0;
        let light_direction = if by_day { sun } else { -sun };
        // The glint's strength as the pack sets it: faded by rain and where the light sets
        // (`glintStrength`, `specularLight`'s visibility; full sky light).
        let visibility = smoothstep(-0.05, 0.15, light_direction.y) * (if by_day { 1.0 } else { MOON_GLINT }) * (1.0 - scene.sky.rain_strength.clamp(0.0, 1.0));
        let disc_cos = SUN_ANGULAR_RADIUS.cos();
        let solid_angle = std::f64::consts::TAU * (1.0 - disc_cos);
        Sky {
            sky_color,
            fog_color,
            box_colour: sky_color + (fog_color - sky_color) * fog,
            sun: Celestial::of(&built.sun, mesh::sun()),
            moon: Celestial::of(&built.moon, mesh::moon()),
            light_direction,
            disc_radiance: GLINT_COLOUR * GLINT_IRRADIANCE * visibility / solid_angle,
            disc_cos,
        }
    }

    /// The G-buffer's sky along the unit direction `d` from the eye, as colortex0's UNORM
    /// format holds it (clamped to 1).
    pub fn seen_directly(&self, d: DVec3) -> DVec3 {
        (self.box_colour + self.sun.added(d) + self.moon.added(d)).clamp(DVec3::ZERO, DVec3::ONE)
    }

    /// The sky's radiance along `d` after water or glass bent or mirrored the ray.
    pub fn radiance(&self, d: DVec3) -> DVec3 {
        let disc = if d.dot(self.light_direction) >= self.disc_cos { self.disc_radiance } else { DVec3::ZERO };
        sky_radiance(d, self.sky_color, self.fog_color) + disc
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_disc_delivers_the_irradiance_of_the_packs_glint() {
        let scene = Scene::load(std::path::Path::new("case4_above_near")).unwrap();
        let sky = Sky::of(&scene);
        // Integrate the disc over its solid angle numerically (rings about its centre).
        let l = sky.light_direction;
        let (u, v) = l.any_orthonormal_pair();
        let rings = 2000;
        let mut irradiance = DVec3::ZERO;
        for k in 0..rings {
            let theta = (k as f64 + 0.5) / rings as f64 * 2.0 * SUN_ANGULAR_RADIUS;
            let d = (l * theta.cos() + u * theta.sin()).normalize();
            let _ = v;
            irradiance += (sky.radiance(d) - sky_radiance(d, sky.sky_color, sky.fog_color)) * std::f64::consts::TAU * theta.sin() * (2.0 * SUN_ANGULAR_RADIUS / rings as f64);
        }
        let visibility = smoothstep(-0.05, 0.15, l.y);
        let expected = GLINT_COLOUR * GLINT_IRRADIANCE * visibility;
        assert!((irradiance - expected).abs().max_element() < 2e-3 * expected.max_element(), "{irradiance} vs {expected}");
        // Straight up the eye sees the sky box, fogged as the pack fogs it.
        let up = sky.seen_directly(DVec3::Y);
        assert!((up - (sky.sky_color + (sky.fog_color - sky.sky_color) * distance_fog(3f64.sqrt() * 48.0, 96.0))).length() < 1e-12);
    }
}
