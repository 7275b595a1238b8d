//! shaderpack/shaders/lib/optics.glsl in f64: Fresnel, absorption, scattering, sky and glint.

use glam::DVec3;

use super::builtins::*;
use super::common::*;
use crate::settings::{Absorption, ReferenceSettings};

pub(crate) const WATER_F0: f64 = 0.02;
pub const WATER_IOR: f64 = 1.333;

/// `fresnelSchlick`.
pub(crate) fn fresnel_schlick(cos_theta: f64) -> f64 {
    let m = 1.0 - cos_theta.clamp(0.0, 1.0);
    let m2 = m * m;
    WATER_F0 + (1.0 - WATER_F0) * m2 * m2 * m
}

/// `fresnelExact`: unpolarised dielectric reflectance with relative index `eta`.
pub(crate) fn fresnel_exact(cos_theta: f64, eta: f64) -> f64 {
    let c = cos_theta.clamp(0.0, 1.0);
    let g2 = eta * eta - 1.0 + c * c;
    if g2 <= 0.0 {
        return 1.0;
    }
    let g = g2.sqrt();
    let a = (g - c) / (g + c);
    let b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    0.5 * a * a * (1.0 + b * b)
}

/// `fresnel`.
pub(crate) fn fresnel(cos_theta: f64, from_above: bool, exact: bool) -> f64 {
    if exact {
        return fresnel_exact(cos_theta, if from_above { WATER_IOR } else { 1.0 / WATER_IOR });
    }
    if !from_above {
        let sin_t2 = WATER_IOR * WATER_IOR * (1.0 - cos_theta * cos_theta);
        return if sin_t2 >= 1.0 { 1.0 } else { fresnel_schlick((1.0 - sin_t2).sqrt()) };
    }
    fresnel_schlick(cos_theta)
}

/// `transmittance`: the ramp or Beer–Lambert.
pub fn transmittance(path_length: f64, s: &ReferenceSettings) -> DVec3 {
    let l = path_length.clamp(0.0, 1e4);
    match s.absorption {
        Absorption::Ramp => {
            let lmax = s.depth_fade_distance;
            let b = ((lmax - l) / lmax).clamp(0.0, 1.0);
            let g = (b * (1.0 - l * (1.5 / lmax))).clamp(0.0, 1.0);
            let r = (b * (1.0 - l * (3.0 / lmax))).clamp(0.0, 1.0);
            DVec3::new(r * r, g * g, b * b)
        }
        Absorption::BeerLambert => {
            const PURE_WATER_ABSORPTION: DVec3 = DVec3::new(0.40, 0.057, 0.009);
            (-PURE_WATER_ABSORPTION * s.absorption_density * l).exp()
        }
    }
}

/// `scatteredColor`.
pub fn scattered_color(water_tint: DVec3, sky_light: f64, sky_color: DVec3) -> DVec3 {
    let daylight = 0.25 + 0.75 * (luminance(sky_color) * 1.5).clamp(0.0, 1.0);
    water_tint * 0.35 * (0.15 + 0.85 * sky_light) * daylight
}

/// `skyRadiance`.
pub fn sky_radiance(dir: DVec3, sky_color: DVec3, fog_color: DVec3) -> DVec3 {
    mix3(fog_color, sky_color, smoothstep(-0.05, 0.35, dir.y))
}

/// `specularLight`.
pub(crate) fn specular_light(reflected: DVec3, light_dir: DVec3, glint: f64, sky_color: DVec3, sky_light: f64) -> DVec3 {
    let visibility = smoothstep(-0.05, 0.15, light_dir.y) * sky_light * glint;
    let sun = reflected.dot(light_dir).max(0.0).powf(256.0) * 8.0;
    let sky = reflected.y.max(0.0).powf(4.0) * 0.15;
    DVec3::new(1.0, 0.95, 0.85) * sun * visibility + sky_color * sky * sky_light
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_fresnel_is_schlick_at_normal_incidence_and_total_past_the_critical_angle() {
        assert!((fresnel_exact(1.0, WATER_IOR) - 0.0204).abs() < 1e-4);
        assert!((fresnel_schlick(1.0) - WATER_F0).abs() < 1e-15);
        assert_eq!(fresnel_exact(0.3, 1.0 / WATER_IOR), 1.0);
        assert_eq!(fresnel(0.3, false, false), 1.0);
        assert!((fresnel_exact(0.0, WATER_IOR) - 1.0).abs() < 1e-12);
    }
}
