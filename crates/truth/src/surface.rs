//! The water volume and its exact wave surface: the scene's water rectangle from its bottom up
//! to the pack's wave height field (lib/waves.glsl's `waveHeight`, through
//! `tidepack_reference::model::waves::wave_height`, the same water texture bilinearly
//! sampled, the same analytic wave), intersected by marching and refined to f64 precision.
//!
//! Coordinates are relative to the camera (the pack's player space); the wave is evaluated
//! at the camera-relative position plus the camera wrapped by the texture's period, as the
//! composite does (`wrappedCamera`), so scenes far from the origin see the same pattern.

use glam::{DVec2, DVec3};
use tidepack_reference::Texture;
use tidepack_reference::model::waves::{WAVE_MAX_HEIGHT, WAVE_TILE, wave_height};

/// Which boundary of the water volume a ray met.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Boundary {
    /// The wave surface.
    Top,
    /// A vertical side of the rectangle (flat, up to the wave surface at the edge).
    Side,
    /// The flat bottom of the volume.
    Bottom,
}

/// A crossing of the water volume's boundary.
#[derive(Clone, Copy, Debug)]
pub struct Crossing {
    pub t: f64,
    pub point: DVec3,
    /// Unit normal pointing out of the water.
    pub normal: DVec3,
    pub boundary: Boundary,
}

/// Horizontal distance between two samples of the march: a fifth of a texel of the water
/// texture (64 blocks over 256 texels), so that the bilinear surface cannot cross a ray twice
/// between samples unless the ray grazes it.
const MARCH_STEP: f64 = 0.05;
/// Step of the central differences of the normal: the bilinear field is piecewise smooth, so
/// the difference is its gradient except within this distance of a texel seam.
const GRADIENT_STEP: f64 = 1e-5;
/// Rays leave a surface from this far along themselves, so they do not meet it again at
/// their origin.
pub const SPAWN_OFFSET: f64 = 1e-7;

/// The scene's water in camera-relative coordinates.
#[derive(Clone, Debug)]
pub struct WaterBody {
    /// Flat surface height.
    pub level: f64,
    pub bottom: f64,
    pub min: DVec2,
    pub max: DVec2,
    /// Vertex tint of the water (the scene's biome colour).
    pub tint: DVec3,
    pub texture: Texture,
    pub time: f64,
    /// The camera's world x, z wrapped by the wave tile.
    pub wrap: DVec2,
    /// False: a flat surface at `level` (the closed-form checks).
    pub waves: bool,
}

impl WaterBody {
    /// The body of `scene`'s water, if it has one.
    pub fn of(scene: &tidepack_scene::Scene, texture: &Texture) -> Option<WaterBody> {
        let w = scene.water.as_ref()?;
        let camera = scene.camera_position();
        let origin = DVec3::from(scene.origin);
        let shift = origin - camera;
        let wrapped = camera - WAVE_TILE * (camera / WAVE_TILE).floor();
        Some(WaterBody {
            level: w.level + shift.y,
            bottom: w.bottom + shift.y,
            min: DVec2::new(w.min[0] + shift.x, w.min[1] + shift.z),
            max: DVec2::new(w.max[0] + shift.x, w.max[1] + shift.z),
            tint: DVec3::from(w.tint),
            texture: texture.clone(),
            time: scene.time.frame_time_counter,
            wrap: DVec2::new(wrapped.x, wrapped.z),
            waves: true,
        })
    }

    /// The wave's height above the flat level at camera-relative `xz`.
    pub fn height(&self, xz: DVec2) -> f64 {
        if !self.waves {
            return 0.0;
        }
        wave_height(&self.texture, xz + self.wrap, self.time)
    }

    pub fn surface_y(&self, xz: DVec2) -> f64 {
        self.level + self.height(xz)
    }

    /// The gradient of the height field (central differences of the exact field).
    pub fn gradient(&self, xz: DVec2) -> DVec2 {
        let e = GRADIENT_STEP;
        let dx = self.height(xz + DVec2::new(e, 0.0)) - self.height(xz - DVec2::new(e, 0.0));
        let dz = self.height(xz + DVec2::new(0.0, e)) - self.height(xz - DVec2::new(0.0, e));
        DVec2::new(dx, dz) / (2.0 * e)
    }

    /// The surface's upward unit normal at `xz`.
    pub fn normal(&self, xz: DVec2) -> DVec3 {
        let g = self.gradient(xz);
        DVec3::new(-g.x, 1.0, -g.y).normalize()
    }

    pub fn over(&self, xz: DVec2) -> bool {
        xz.x >= self.min.x && xz.x <= self.max.x && xz.y >= self.min.y && xz.y <= self.max.y
    }

    /// Whether `p` lies in the water.
    pub fn contains(&self, p: DVec3) -> bool {
        let xz = DVec2::new(p.x, p.z);
        self.over(xz) && p.y > self.bottom && p.y < self.surface_y(xz)
    }

    /// The first crossing of the volume's boundary along `origin + t·dir`, `t` in
    /// (SPAWN_OFFSET, t_max), for a ray inside the water (`inside`) or outside it.
    pub fn crossing(&self, origin: DVec3, dir: DVec3, inside: bool, t_max: f64) -> Option<Crossing> {
        let mut best: Option<Crossing> = None;
        let consider = |best: &mut Option<Crossing>, c: Crossing| {
            if c.t > SPAWN_OFFSET && c.t < t_max && best.is_none_or(|b| c.t < b.t) {
                *best = Some(c);
            }
        };
        // The sides and the bottom: planes, met from the side `inside` says.
        let at = |t: f64| origin + dir * t;
        for (axis, sign) in [(0usize, -1.0), (0, 1.0), (2, -1.0), (2, 1.0)] {
            let d = dir[axis];
            let plane = if sign < 0.0 { self.min[if axis == 0 { 0 } else { 1 }] } else { self.max[if axis == 0 { 0 } else { 1 }] };
            // Outward normal `sign` along the axis: leaving moves with it, entering against it.
            if d == 0.0 || (inside && d * sign <= 0.0) || (!inside && d * sign >= 0.0) {
                continue;
            }
            let t = (plane - origin[axis]) / d;
            let p = at(t);
            let xz = DVec2::new(p.x, p.z);
            let other_ok = if axis == 0 { xz.y >= self.min.y && xz.y <= self.max.y } else { xz.x >= self.min.x && xz.x <= self.max.x };
            if other_ok && p.y >= self.bottom && p.y <= self.surface_y(xz) {
                let mut normal = DVec3::ZERO;
                normal[axis] = sign;
                consider(&mut best, Crossing { t, point: p, normal, boundary: Boundary::Side });
            }
        }
        if (inside && dir.y < 0.0) || (!inside && dir.y > 0.0) {
            let t = (self.bottom - origin.y) / dir.y;
            let p = at(t);
            if self.over(DVec2::new(p.x, p.z)) {
                consider(&mut best, Crossing { t, point: p, normal: DVec3::NEG_Y, boundary: Boundary::Bottom });
            }
        }
        let limit = best.map_or(t_max, |b| b.t);
        if let Some(t) = self.top_crossing(origin, dir, inside, limit) {
            let p = at(t);
            consider(&mut best, Crossing { t, point: p, normal: self.normal(DVec2::new(p.x, p.z)), boundary: Boundary::Top });
        }
        best
    }

    /// The first `t` in (SPAWN_OFFSET, t_max) where the ray passes the wave surface from the
    /// side `inside` names to the other, over the rectangle: a march of MARCH_STEP
    /// horizontal steps through the slab the waves can reach, then a bracketed root search
    /// (regula falsi with the Illinois correction, and halving where it stalls) to f64
    /// precision.
    pub fn top_crossing(&self, origin: DVec3, dir: DVec3, inside: bool, t_max: f64) -> Option<f64> {
        let reach = WAVE_MAX_HEIGHT * (1.0 + 1e-9) + 1e-12;
        let (mut lo, mut hi) = (SPAWN_OFFSET, t_max);
        // Clip to the slab level ± reach and to the rectangle.
        let mut clip = |o: f64, d: f64, a: f64, b: f64| {
            if d == 0.0 {
                if o < a || o > b {
                    hi = -1.0;
                }
                return;
            }
            let (t0, t1) = ((a - o) / d, (b - o) / d);
            lo = lo.max(t0.min(t1));
            hi = hi.min(t0.max(t1));
        };
        clip(origin.y, dir.y, self.level - reach, self.level + reach);
        clip(origin.x, dir.x, self.min.x, self.max.x);
        clip(origin.z, dir.z, self.min.y, self.max.y);
        if hi <= lo || hi.is_nan() || lo.is_nan() {
            return None;
        }
        // Gap above the surface: positive in the air, negative in the water.
        let gap = |t: f64| {
            let p = origin + dir * t;
            p.y - self.surface_y(DVec2::new(p.x, p.z))
        };
        let on_start_side = |g: f64| if inside { g < 0.0 } else { g > 0.0 };
        let horizontal = DVec2::new(dir.x, dir.z).length();
        let step = if horizontal > 1e-12 { MARCH_STEP / horizontal } else { hi - lo };
        let steps = ((hi - lo) / step).ceil().clamp(1.0, 1e6) as usize;
        let (mut t0, mut g0) = (lo, gap(lo));
        let mut started = on_start_side(g0);
        for k in 1..=steps {
            let t1 = if k == steps { hi } else { lo + (hi - lo) * k as f64 / steps as f64 };
            let g1 = gap(t1);
            if started && !on_start_side(g1) {
                return Some(refine(&gap, t0, g0, t1, g1));
            }
            started |= on_start_side(g1);
            (t0, g0) = (t1, g1);
        }
        None
    }
}

/// The root of `f` in [a, b], where f(a) and f(b) differ in sign (or f(b) = 0): regula falsi
/// with the Illinois halving of the stale end, and bisection whenever it fails to halve the
/// bracket, down to adjacent doubles. Returns the end on the far side (f(b)'s), so the point
/// lies on or just past the surface.
fn refine(f: &dyn Fn(f64) -> f64, mut a: f64, mut fa: f64, mut b: f64, mut fb: f64) -> f64 {
    let mut side = 0i32;
    for _ in 0..200 {
        if fb == 0.0 || (b - a).abs() <= 4.0 * f64::EPSILON * b.abs().max(1e-300) {
            break;
        }
        let width = (b - a).abs();
        let mut c = (a * fb - b * fa) / (fb - fa);
        if !(c > a.min(b) && c < a.max(b)) {
            c = 0.5 * (a + b);
        }
        let fc = f(c);
        if (fc > 0.0) == (fb > 0.0) && fc != 0.0 {
            b = c;
            fb = fc;
            if side == 1 {
                fa *= 0.5;
            }
            side = 1;
        } else {
            a = c;
            fa = fc;
            if side == -1 {
                fb *= 0.5;
            }
            side = -1;
            if fc == 0.0 {
                return c;
            }
        }
        if (b - a).abs() > 0.5 * width {
            // Stalled: halve.
            let m = 0.5 * (a + b);
            let fm = f(m);
            if (fm > 0.0) == (fb > 0.0) {
                b = m;
                fb = fm;
            } else {
                a = m;
                fa = fm;
            }
            side = 0;
        }
    }
    b
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec4;
    use tidepack_reference::{Filter, Wrap};

    fn body(texture: Texture) -> WaterBody {
        WaterBody {
            level: -4.0,
            bottom: -20.0,
            min: DVec2::splat(-30.0),
            max: DVec2::splat(30.0),
            tint: DVec3::ONE,
            texture,
            time: 12.5,
            wrap: DVec2::new(3.0, 5.0),
            waves: true,
        }
    }

    #[test]
    fn the_crossing_lies_on_the_exact_surface_to_f64_precision() {
        let water = body(crate::water_texture().unwrap());
        for (k, dir) in [DVec3::new(0.1, -1.0, -0.4), DVec3::new(0.0, -0.15, -1.0), DVec3::new(0.7, -0.2, 0.3)].into_iter().enumerate() {
            let dir = dir.normalize();
            let c = water.crossing(DVec3::ZERO, dir, false, 1e4).expect("the ray meets the water");
            assert_eq!(c.boundary, Boundary::Top);
            let gap = c.point.y - water.surface_y(DVec2::new(c.point.x, c.point.z));
            assert!(gap.abs() < 1e-12, "ray {k}: gap {gap}");
            assert!(c.normal.y > 0.9 && (c.normal.length() - 1.0).abs() < 1e-12);
            // From just below along the reversed ray, the way out is the same point.
            let below = c.point + dir * 1e-3;
            let back = water.crossing(below, -dir, true, 1e4).unwrap();
            assert!((back.point - c.point).length() < 1e-9, "ray {k}: {} vs {}", back.point, c.point);
        }
    }

    #[test]
    fn a_uniform_texture_gives_the_analytic_wave_and_its_normal() {
        let flat = Texture::new(1, 1, vec![DVec4::splat(0.5)], Filter::Linear, Wrap::Repeat);
        let water = body(flat);
        let xz = DVec2::new(1.3, -2.1);
        let g = water.gradient(xz);
        // The height is 0.1·sin(φ − cos φ / 2) with φ = ωt + k·(xz + wrap).
        let k = DVec2::new(3.0, 5.0) * (tidepack_reference::model::TAU / WAVE_TILE);
        let phase = tidepack_reference::model::TAU * 180.0 / 3600.0 * 12.5 + k.dot(xz + water.wrap);
        let slope = 0.1 * (phase - 0.5 * phase.cos()).cos() * (1.0 + 0.5 * phase.sin());
        assert!((g - k * slope).length() < 1e-8, "{g} vs {}", k * slope);
        // A ray from the side enters through the side face below the surface.
        let c = water.crossing(DVec3::new(-40.0, -10.0, 0.0), DVec3::X, false, 1e3).unwrap();
        assert_eq!(c.boundary, Boundary::Side);
        assert!((c.point.x + 30.0).abs() < 1e-12 && c.normal == DVec3::NEG_X);
        assert!(water.contains(c.point + DVec3::X * 1e-6));
    }
}
