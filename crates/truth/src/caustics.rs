//! Caustics by forward photon tracing: sunlight enters the exact wave surface, refracts
//! (Snell, Fresnel transmission), is absorbed along its real path (Beer–Lambert) and lands on
//! the first opaque surface below; landings on upward-facing surfaces are gathered on a grid
//! of floor irradiance over the water rectangle.
//!
//! Photons start on a regular lattice of the surface's horizontal projection, N per grid
//! cell along each axis. A photon stands for its lattice cell's share of the sun's flux through
//! the heightfield there: E·(s · (−∇h, 1))·dA (exact for a heightfield lit from above, wave
//! self-shadowing aside). Each landing is splatted onto the grid's nodes with bilinear (tent)
//! weights of one cell's width and divided by the cell's area, so a node holds flux per unit of
//! horizontal area; reading the grid interpolates bilinearly. The tent's partition of unity
//! makes the lattice of a flat surface, shifted in whole onto a horizontal floor, sum to
//! exactly the flat-surface transmitted irradiance at every node (`flat_factor` = 1), which
//! `tests` check.

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use crate::fresnel::{WATER_IOR, interface};
use crate::geometry::{Geometry, Hit};
use crate::medium::Medium;
use crate::surface::{SPAWN_OFFSET, WaterBody};

/// Photons per grid cell along each axis.
pub const PHOTONS_PER_CELL_AXIS: usize = 4;
/// The finest grid cell, in blocks: half a texel of the water texture.
pub const FINEST_CELL: f64 = 0.125;
/// Most grid nodes: larger water gets coarser cells (far water, where the pattern is far
/// below a pixel anyway).
pub const MAX_NODES: f64 = 500_000.0;

/// The floor irradiance under the water, in units of the sun's irradiance on a surface
/// facing it (the mesh lights a face with 0.55 of it: see `trace`).
#[derive(Clone, Debug)]
pub struct CausticGrid {
    min: DVec2,
    cell: f64,
    nodes: (usize, usize),
    /// Flux per unit of horizontal area, per channel, row-major in z.
    flux: Vec<DVec3>,
    /// Direction of the sunlight (from the sun).
    incoming: DVec3,
    /// The flat surface's refracted direction and Fresnel transmittance.
    flat_refracted: DVec3,
    flat_transmittance: f64,
}

impl CausticGrid {
    /// Traces the photons of `water` lit from `sun` (towards the sun); None when the sun is
    /// not above the horizon (no light enters from above).
    pub fn trace(water: &WaterBody, geometry: &Geometry, medium: &Medium, sun: DVec3) -> Option<CausticGrid> {
        if sun.y <= 0.0 {
            return None;
        }
        let size = water.max - water.min;
        let cell = FINEST_CELL.max((size.x * size.y / MAX_NODES).sqrt());
        let nodes = ((size.x / cell).ceil() as usize + 1, (size.y / cell).ceil() as usize + 1);
        let incoming = -sun;
        let flat = interface(incoming, DVec3::Y, 1.0, WATER_IOR);
        let mut grid = CausticGrid {
            min: water.min,
            cell,
            nodes,
            flux: vec![DVec3::ZERO; nodes.0 * nodes.1],
            incoming,
            flat_refracted: flat.refracted.expect("light from above always enters"),
            flat_transmittance: flat.transmittance,
        };
        let spacing = cell / PHOTONS_PER_CELL_AXIS as f64;
        let (px, pz) = ((size.x / spacing).floor() as usize, (size.y / spacing).floor() as usize);
        // Bands of photon rows on every core, each into a grid of its own, summed in band order:
        // the result does not depend on the scheduling.
        let bands = (rayon::current_num_threads() * 2).max(1).min(pz.max(1));
        let partials: Vec<Vec<DVec3>> = (0..bands)
            .into_par_iter()
            .map(|band| {
                let mut flux = vec![DVec3::ZERO; nodes.0 * nodes.1];
                for j in (band * pz / bands)..((band + 1) * pz / bands) {
                    for i in 0..px {
                        let xz = water.min + DVec2::new(i as f64 + 0.5, j as f64 + 0.5) * spacing;
                        if let Some((at, carried)) = photon(water, geometry, medium, incoming, xz) {
                            grid.splat(&mut flux, at, carried * spacing * spacing);
                        }
                    }
                }
                flux
            })
            .collect();
        for partial in partials {
            for (total, part) in grid.flux.iter_mut().zip(partial) {
                *total += part;
            }
        }
        Some(grid)
    }

    /// Adds `flux` landed at `xz` to the four nodes around it, as flux per unit area.
    fn splat(&self, flux: &mut [DVec3], xz: DVec2, carried: DVec3) {
        let f = (xz - self.min) / self.cell;
        let (i0, k0) = (f.x.floor(), f.y.floor());
        let (wx, wz) = (f.x - i0, f.y - k0);
        let area = self.cell * self.cell;
        for (di, dk, w) in [(0, 0, (1.0 - wx) * (1.0 - wz)), (1, 0, wx * (1.0 - wz)), (0, 1, (1.0 - wx) * wz), (1, 1, wx * wz)] {
            let (i, k) = (i0 as i64 + di, k0 as i64 + dk);
            if i >= 0 && k >= 0 && (i as usize) < self.nodes.0 && (k as usize) < self.nodes.1 {
                flux[k as usize * self.nodes.0 + i as usize] += carried * (w / area);
            }
        }
    }

    /// Flux per unit horizontal area at `xz` (bilinear between the nodes).
    pub fn horizontal_flux(&self, xz: DVec2) -> DVec3 {
        let f = ((xz - self.min) / self.cell).max(DVec2::ZERO);
        let (i0, k0) = ((f.x.floor() as usize).min(self.nodes.0 - 1), (f.y.floor() as usize).min(self.nodes.1 - 1));
        let (i1, k1) = ((i0 + 1).min(self.nodes.0 - 1), (k0 + 1).min(self.nodes.1 - 1));
        let (wx, wz) = ((f.x - i0 as f64).clamp(0.0, 1.0), (f.y - k0 as f64).clamp(0.0, 1.0));
        let at = |i: usize, k: usize| self.flux[k * self.nodes.0 + i];
        (at(i0, k0) * (1.0 - wx) + at(i1, k0) * wx) * (1.0 - wz) + (at(i0, k1) * (1.0 - wx) + at(i1, k1) * wx) * wz
    }

    /// Irradiance on an upward-facing surface of normal `normal` at `p`.
    pub fn irradiance(&self, p: DVec3, normal: DVec3) -> DVec3 {
        self.horizontal_flux(DVec2::new(p.x, p.z)) * normal.y
    }

    /// What a flat surface at `level` would deliver to `p` (normal `normal`): the refracted
    /// beam E·(1 − R)·cosθi/cosθt, on the face by its cosine, absorbed over the path from the
    /// flat surface. Also the truth's irradiance on faces the grid does not cover (walls).
    pub fn flat_irradiance(&self, p: DVec3, normal: DVec3, level: f64, medium: &Medium) -> DVec3 {
        let t = self.flat_refracted;
        let beam = self.flat_transmittance * (-self.incoming.y) / (-t.y);
        let path = ((level - p.y) / (-t.y)).max(0.0);
        medium.transmittance(path) * beam * normal.dot(-t).max(0.0)
    }

    /// The caustic factor: the traced irradiance over the flat surface's.
    pub fn factor(&self, p: DVec3, normal: DVec3, level: f64, medium: &Medium) -> DVec3 {
        self.irradiance(p, normal) / self.flat_irradiance(p, normal, level, medium)
    }
}

/// One photon from the surface above `xz`: where it lands on an upward-facing surface and the
/// flux per unit of launch area it carries there.
fn photon(water: &WaterBody, geometry: &Geometry, medium: &Medium, incoming: DVec3, xz: DVec2) -> Option<(DVec2, DVec3)> {
    let g = water.gradient(xz);
    let m = DVec3::new(-g.x, 1.0, -g.y);
    // Flux through the heightfield per unit of horizontal area.
    let entering = (-incoming).dot(m);
    if entering <= 0.0 {
        return None;
    }
    let start = DVec3::new(xz.x, water.surface_y(xz), xz.y);
    let crossing = interface(incoming, m.normalize(), 1.0, WATER_IOR);
    let dir = crossing.refracted?;
    // Light leaving through a side or the bottom before it lands is lost.
    let exit = water.crossing(start, dir, true, f64::INFINITY).map_or(f64::INFINITY, |c| c.t);
    match geometry.hit(start, dir, SPAWN_OFFSET, exit)? {
        Hit::Opaque { t, point, normal, .. } if normal.y > 0.5 => {
            Some((DVec2::new(point.x, point.z), medium.transmittance(t) * (entering * crossing.transmittance)))
        }
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use tidepack_reference::ReferenceSettings;
    use tidepack_scene::Scene;

    #[test]
    fn a_flat_surface_gives_the_flat_transmitted_irradiance_everywhere() {
        let scene = Scene::load(std::path::Path::new("case4_above_near")).unwrap();
        let texture = crate::water_texture().unwrap();
        let mut water = WaterBody::of(&scene, &texture).unwrap();
        water.waves = false;
        let geometry = Geometry::of(&scene);
        let medium = Medium::new(&ReferenceSettings::converged(), water.tint, DVec3::from(scene.sky.sky_color));
        let grid = CausticGrid::trace(&water, &geometry, &medium, scene.sun_direction()).unwrap();
        // The sea floor west of the pool (y = 54; camera-relative y = -13), away from its
        // walls, the wall in the water's shadow and the rectangle's edges.
        let mut worst: f64 = 0.0;
        let mut checked = 0;
        for i in 0..40 {
            for k in 0..40 {
                let p = DVec3::new(-28.0 + 0.47 * i as f64, -13.0, -28.0 + 0.8 * k as f64 + 2.0);
                let f = grid.factor(p, DVec3::Y, water.level, &medium);
                worst = worst.max((f - DVec3::ONE).abs().max_element());
                checked += 1;
            }
        }
        assert_eq!(checked, 1600);
        assert!(worst < 1e-9, "the flat factor strays by {worst}");
        // With the waves the pattern varies, but its mean over the same floor stays near 1:
        // refraction moves light around without making or losing any (within a few percent
        // for the light that changes Fresnel loss and path length).
        water.waves = true;
        let waves = CausticGrid::trace(&water, &geometry, &medium, scene.sun_direction()).unwrap();
        let (mut sum, mut lo, mut hi) = (0.0, f64::MAX, f64::MIN);
        let n = 200;
        for i in 0..n {
            for k in 0..n {
                let p = DVec3::new(-28.0 + 16.0 * i as f64 / n as f64, -13.0, -26.0 + 30.0 * k as f64 / n as f64);
                let f = waves.factor(p, DVec3::Y, water.level, &medium).y;
                sum += f;
                lo = lo.min(f);
                hi = hi.max(f);
            }
        }
        let mean = sum / (n * n) as f64;
        assert!((mean - 1.0).abs() < 0.05, "mean caustic factor {mean}");
        assert!(hi > 1.2 && lo < 0.85, "the waves focus light: factor {lo}..{hi}");
    }
}
