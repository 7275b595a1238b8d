//! The recursive path of one camera ray: to the nearest of terrain, glass and the water's
//! boundary; at water both the reflected and the refracted ray are followed (weighted by the
//! exact Fresnel shares), through glass the pane's two blended layers and its slab
//! reflection, and every stretch in water is absorbed and in-scattered by its real length.

use glam::{DVec2, DVec3};
use tidepack_reference::model::common::distance_fog;

use crate::caustics::CausticGrid;
use crate::fresnel::{GLASS_IOR, WATER_IOR, interface, reflect, slab_reflectance};
use crate::geometry::{Geometry, Hit};
use crate::medium::Medium;
use crate::sky::Sky;
use crate::surface::{SPAWN_OFFSET, WaterBody};

/// The share of a vertex colour that is the sky's light in mesh.rs's lighting,
/// `0.45 + 0.55·max(n·sun, 0)`; the rest is the sun's (irradiance 1 on a face towards it).
pub const AMBIENT_LIGHT: f64 = 0.45;
pub const SUN_LIGHT: f64 = 0.55;

/// Branches whose weight falls below this are not followed (their light is below 1/10000 of
/// the pixel's scale, the sun's disc aside).
const PRUNE: f64 = 1e-4;

/// A ray and what it has been through.
#[derive(Clone, Copy, Debug)]
pub struct Ray {
    pub origin: DVec3,
    pub dir: DVec3,
    pub in_water: bool,
    /// Still the straight line from the eye (only glass crossed): the sky is then the one the
    /// pack's G-buffer holds, and fog goes by the pack's interpolated vertex distance.
    pub straight: bool,
    /// Length travelled from the eye.
    pub path: f64,
    /// The product of the shares taken so far.
    pub weight: f64,
    pub depth: u32,
}

/// What a camera ray's tree of rays did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Record {
    /// Some ray met the water's boundary or travelled in the water.
    pub touched_water: bool,
    /// Some ray crossed from the water into the air.
    pub left_water: bool,
}

/// One frame's scene, prepared for tracing.
pub struct Tracer {
    pub geometry: Geometry,
    pub water: Option<WaterBody>,
    pub medium: Medium,
    pub sky: Sky,
    pub caustics: Option<CausticGrid>,
    /// Towards the sun, as the mesh lights terrain.
    pub sun: DVec3,
    /// The game's fog: off with the eye in water (lib/vanilla.glsl).
    pub fog: bool,
    pub far: f64,
    pub fog_color: DVec3,
    pub max_depth: u32,
    /// Radiance crossing into a medium of another index is scaled by the square of the
    /// indices' ratio (the invariance of L/n²).
    pub radiance_scaling: bool,
}

impl Tracer {
    /// The radiance arriving along `ray` (towards its origin).
    pub fn radiance(&self, ray: Ray, record: &mut Record) -> DVec3 {
        if ray.depth > self.max_depth {
            // Give up with what a long path would bring: the water's own light in water, the
            // sky in the air.
            return if ray.in_water { self.medium.scattered } else { self.sky.radiance(ray.dir) };
        }
        record.touched_water |= ray.in_water;
        let hit = self.geometry.hit(ray.origin, ray.dir, SPAWN_OFFSET, f64::INFINITY);
        let t_hit = hit.map_or(f64::INFINITY, |h| h.t());
        let crossing = self.water.as_ref().and_then(|w| w.crossing(ray.origin, ray.dir, ray.in_water, t_hit));
        let (colour, length) = if let Some(c) = crossing {
            record.touched_water = true;
            (self.at_water(&ray, c.t, c.point, c.normal, record), c.t)
        } else if let Some(hit) = hit {
            (self.at_surface(&ray, hit, record), hit.t())
        } else if ray.in_water {
            // Water without end (only where the volume's boundary was missed numerically).
            return self.medium.scattered;
        } else if ray.straight {
            return self.sky.seen_directly(ray.dir);
        } else {
            return self.sky.radiance(ray.dir);
        };
        if ray.in_water { self.medium.through(colour, length) } else { colour }
    }

    /// The ray leaving `point` along `dir` after `ray` went `t` to it and kept `share`: in the
    /// same medium and no longer straight unless the caller says otherwise.
    fn child(&self, ray: &Ray, point: DVec3, dir: DVec3, t: f64, share: f64) -> Ray {
        Ray { origin: point, dir, in_water: ray.in_water, straight: false, path: ray.path + t, weight: ray.weight * share, depth: ray.depth + 1 }
    }

    /// At the water's boundary: Fresnel's reflected and transmitted shares of both rays.
    fn at_water(&self, ray: &Ray, t: f64, point: DVec3, normal: DVec3, record: &mut Record) -> DVec3 {
        let (n1, n2) = if ray.in_water { (WATER_IOR, 1.0) } else { (1.0, WATER_IOR) };
        let i = interface(ray.dir, normal, n1, n2);
        let mut colour = DVec3::ZERO;
        if ray.weight * i.reflectance >= PRUNE {
            let reflected = self.child(ray, point, reflect(ray.dir, normal), t, i.reflectance);
            colour += i.reflectance * self.radiance(reflected, record);
        }
        if let Some(dir) = i.refracted
            && ray.weight * i.transmittance >= PRUNE
        {
            if ray.in_water {
                record.left_water = true;
            }
            let scale = if self.radiance_scaling { (n1 / n2) * (n1 / n2) } else { 1.0 };
            let refracted = Ray { in_water: !ray.in_water, ..self.child(ray, point, dir, t, i.transmittance) };
            colour += i.transmittance * scale * self.radiance(refracted, record);
        }
        colour
    }

    fn at_surface(&self, ray: &Ray, hit: Hit, record: &mut Record) -> DVec3 {
        match hit {
            Hit::Opaque { t, point, normal, colour, view_distance, .. } => {
                let lit = if ray.in_water { self.under_water(point, normal, colour) } else { colour };
                if !self.fog {
                    return lit;
                }
                let distance = if ray.straight { view_distance } else { ray.path + t };
                let f = distance_fog(distance, self.far);
                lit + (self.fog_color - lit) * f
            }
            Hit::Glass { t, point, normal, colour } => {
                // The pack blends each face the ray crosses over what lies behind (no culling):
                // a layer of the pane's colour at its opacity. The pane, a thin slab, also
                // reflects at the face the ray enters by: 2R/(1+R), direction unchanged through.
                let behind = self.radiance(Ray { straight: ray.straight, ..self.child(ray, point, ray.dir, t, 1.0 - colour.w) }, record);
                let layered = colour.truncate() * colour.w + behind * (1.0 - colour.w);
                let cos_i = -ray.dir.dot(normal);
                if cos_i <= 0.0 {
                    return layered;
                }
                let outside = if ray.in_water { WATER_IOR } else { 1.0 };
                let r = slab_reflectance(cos_i, outside, GLASS_IOR);
                let reflected = if ray.weight * r >= PRUNE {
                    self.radiance(self.child(ray, point, reflect(ray.dir, normal), t, r), record)
                } else {
                    DVec3::ZERO
                };
                r * reflected + (1.0 - r) * layered
            }
        }
    }

    /// An opaque surface under water: the mesh's colour split into its albedo and its light,
    /// the sky's share through the surface and the water above, the sun's from the caustic
    /// grid (upward faces) or the flat surface's refracted beam (walls).
    pub fn under_water(&self, point: DVec3, normal: DVec3, colour: DVec3) -> DVec3 {
        let Some(water) = &self.water else { return colour };
        let dry = AMBIENT_LIGHT + SUN_LIGHT * normal.dot(self.sun).max(0.0);
        let albedo = colour / dry;
        let depth = (water.surface_y(DVec2::new(point.x, point.z)) - point.y).max(0.0);
        let ambient = AMBIENT_LIGHT * self.medium.sky_light_at_depth(depth);
        let sun = match &self.caustics {
            Some(grid) if normal.y > 0.5 => grid.irradiance(point, normal),
            Some(grid) => grid.flat_irradiance(point, normal, water.level, &self.medium),
            None => DVec3::ZERO,
        };
        albedo * (ambient + SUN_LIGHT * sun)
    }
}
