//! The water as a medium: Beer–Lambert absorption with the pack's coefficients along the real
//! path lengths, the in-scattered light the pack's composite adds, and the sky light that
//! reaches a point under the surface.

use glam::DVec3;
use tidepack_reference::model::optics::{scattered_color, transmittance};
use tidepack_reference::{Absorption, ReferenceSettings};

use crate::fresnel::{WATER_IOR, interface};

/// The water's optical properties for one frame.
#[derive(Clone, Debug)]
pub struct Medium {
    /// The settings with Beer–Lambert chosen: the truth always absorbs exponentially, with
    /// the settings' `ABSORPTION_DENSITY` and lib/optics.glsl's PURE_WATER_ABSORPTION.
    settings: ReferenceSettings,
    /// In-scattered radiance: the pack's `scatteredColor` of the water's tint at full sky
    /// light, which the medium emits where it absorbs.
    pub scattered: DVec3,
    /// `sky_light_at_depth` every TABLE_STEP blocks, interpolated between.
    table: Vec<DVec3>,
}

const TABLE_STEP: f64 = 1.0 / 16.0;
const TABLE_DEPTH: f64 = 256.0;

impl Medium {
    pub fn new(settings: &ReferenceSettings, tint: DVec3, sky_color: DVec3) -> Medium {
        let settings = ReferenceSettings { absorption: Absorption::BeerLambert, ..settings.clone() };
        // The scenes' water has full sky light (lightmap 240, as the eye's brightness); the
        // pack's wave-dependent factor (0.65 + diffuse) is taken at its base, 1 (see
        // docs/truth.md).
        let mut medium = Medium { settings, scattered: scattered_color(tint, 1.0, sky_color), table: Vec::new() };
        medium.table = (0..=(TABLE_DEPTH / TABLE_STEP) as usize).map(|k| medium.sky_light_integral(k as f64 * TABLE_STEP)).collect();
        medium
    }

    /// [`Medium::sky_light_integral`] from the table (linear between entries, 1/16 block
    /// apart; the integrand is smooth in depth).
    pub fn sky_light_at_depth(&self, depth: f64) -> DVec3 {
        let f = depth.max(0.0) / TABLE_STEP;
        let k = f.floor() as usize;
        if k + 1 >= self.table.len() {
            return self.sky_light_integral(depth);
        }
        let w = f - k as f64;
        self.table[k] * (1.0 - w) + self.table[k + 1] * w
    }

    /// exp(−σ·L) per channel.
    pub fn transmittance(&self, length: f64) -> DVec3 {
        transmittance(length, &self.settings)
    }

    /// Radiance `far` seen through `length` of water: absorbed, plus the in-scattered light
    /// of the segment. With a source equal to `scattered` wherever the water absorbs, the
    /// radiative transfer equation integrates to exactly this along any path.
    pub fn through(&self, far: DVec3, length: f64) -> DVec3 {
        let t = self.transmittance(length);
        t * far + (DVec3::ONE - t) * self.scattered
    }

    /// The share of a uniform sky's irradiance that reaches a horizontal point `depth` below
    /// a flat surface: ∫ 2μ (1 − R(μ)) exp(−σ·depth/μ_w) dμ over the cosine μ in air, μ_w the
    /// refracted ray's cosine (midpoint rule, 256 nodes).
    pub fn sky_light_integral(&self, depth: f64) -> DVec3 {
        const NODES: usize = 256;
        let mut sum = DVec3::ZERO;
        for k in 0..NODES {
            let mu = (k as f64 + 0.5) / NODES as f64;
            let d = DVec3::new((1.0 - mu * mu).sqrt(), -mu, 0.0);
            let i = interface(d, DVec3::Y, 1.0, WATER_IOR);
            let mu_w = i.refracted.map_or(1.0, |r| -r.y);
            sum += 2.0 * mu * i.transmittance * self.transmittance(depth.max(0.0) / mu_w) / NODES as f64;
        }
        sum
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn absorption_follows_beer_lambert_with_the_pack_coefficients() {
        let m = Medium::new(&ReferenceSettings::converged(), DVec3::ONE, DVec3::ONE);
        let t = m.transmittance(10.0);
        let expected = (-DVec3::new(0.40, 0.057, 0.009) * 10.0).exp();
        assert!((t - expected).abs().max_element() < 1e-15, "{t}");
        // Two segments are one segment of their total length, scattering included.
        let c = DVec3::new(0.3, 0.6, 0.9);
        let (a, b) = (m.through(m.through(c, 3.0), 4.0), m.through(c, 7.0));
        assert!((a - b).abs().max_element() < 1e-14);
        // At the surface the diffuse transmittance of water (about 93%) gets through.
        let at_surface = m.sky_light_at_depth(0.0);
        assert!((at_surface.x - 0.934).abs() < 0.003, "{at_surface}");
        let (tabled, exact) = (m.sky_light_at_depth(7.3), m.sky_light_integral(7.3));
        assert!((tabled - exact).abs().max_element() < 1e-4, "{tabled} vs {exact}");
    }
}
