//! Dielectric interfaces: Snell's law and the exact unpolarised Fresnel equations, with the
//! transmittance computed from the transmission amplitudes (not as 1 − R), so that energy
//! conservation is something the tests check rather than assume.

use glam::DVec3;

/// Refractive index of water: the pack's (`WATER_IOR` of lib/optics.glsl).
pub const WATER_IOR: f64 = tidepack_reference::model::optics::WATER_IOR;

/// Refractive index of the stained-glass panes: soda-lime glass. The pack gives glass no
/// index (it blends it without bending), so the truth's choice is the common one.
pub const GLASS_IOR: f64 = 1.5;

/// What one interface does to a ray: the share reflected and the share transmitted (as
/// power, i.e. irradiance-weighted), and the refracted direction unless the reflection is
/// total.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interface {
    pub reflectance: f64,
    pub transmittance: f64,
    pub refracted: Option<DVec3>,
}

/// Mirror `d` about the plane of normal `n` (any side).
pub fn reflect(d: DVec3, n: DVec3) -> DVec3 {
    d - 2.0 * d.dot(n) * n
}

/// The interface seen along unit direction `d` arriving at a surface with unit normal `n`
/// (either orientation), from a medium of index `n1` into one of index `n2`.
///
/// The amplitudes are the Fresnel equations' (s and p); the transmitted power share carries
/// the factor n2·cosθt / (n1·cosθi) of the beam's change of cross-section and speed.
pub fn interface(d: DVec3, n: DVec3, n1: f64, n2: f64) -> Interface {
    // Orient the normal against the ray.
    let n = if d.dot(n) > 0.0 { -n } else { n };
    let cos_i = (-d.dot(n)).clamp(0.0, 1.0);
    let eta = n1 / n2;
    let sin_t2 = eta * eta * (1.0 - cos_i * cos_i);
    if sin_t2 >= 1.0 {
        return Interface { reflectance: 1.0, transmittance: 0.0, refracted: None };
    }
    let cos_t = (1.0 - sin_t2).sqrt();
    let rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    let rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
    let ts = 2.0 * n1 * cos_i / (n1 * cos_i + n2 * cos_t);
    let tp = 2.0 * n1 * cos_i / (n2 * cos_i + n1 * cos_t);
    let reflectance = 0.5 * (rs * rs + rp * rp);
    // At grazing incidence (cos_i = 0) the beam carries no power across: T = 0, R = 1.
    let transmittance = if cos_i > 0.0 { 0.5 * (ts * ts + tp * tp) * (n2 * cos_t) / (n1 * cos_i) } else { 0.0 };
    let refracted = (eta * d + (eta * cos_i - cos_t) * n).normalize();
    Interface { reflectance, transmittance, refracted: Some(refracted) }
}

/// Reflectance of a thin non-absorbing slab (both faces, every internal reflection summed
/// incoherently): R + T²R / (1 − R²) = 2R / (1 + R), with R the single face's at the angle
/// of incidence `cos_i` from a medium `n1` onto a slab of index `n2`. The light leaves the
/// slab parallel to how it came, so the slab changes no direction.
pub fn slab_reflectance(cos_i: f64, n1: f64, n2: f64) -> f64 {
    let d = DVec3::new((1.0 - cos_i * cos_i).max(0.0).sqrt(), -cos_i, 0.0);
    let r = interface(d, DVec3::Y, n1, n2).reflectance;
    2.0 * r / (1.0 + r)
}

/// The critical angle seen from inside a medium of index `n` against air.
pub fn critical_angle(n: f64) -> f64 {
    (1.0 / n).asin()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ray(theta: f64) -> DVec3 {
        DVec3::new(theta.sin(), -theta.cos(), 0.0)
    }

    #[test]
    fn reflected_and_transmitted_power_add_up_to_one_at_every_angle_both_ways() {
        for (n1, n2) in [(1.0, WATER_IOR), (WATER_IOR, 1.0), (1.0, GLASS_IOR), (GLASS_IOR, 1.0), (WATER_IOR, GLASS_IOR)] {
            for k in 0..=900 {
                let theta = (k as f64 / 900.0) * std::f64::consts::FRAC_PI_2;
                let i = interface(ray(theta), DVec3::Y, n1, n2);
                assert!((0.0..=1.0).contains(&i.reflectance), "{n1}->{n2} at {theta}: R = {}", i.reflectance);
                assert!((i.reflectance + i.transmittance - 1.0).abs() < 1e-12, "{n1}->{n2} at {theta}: R + T = {}", i.reflectance + i.transmittance);
            }
        }
    }

    #[test]
    fn snell_holds_and_normal_incidence_matches_the_closed_form() {
        let i = interface(ray(0.0), DVec3::Y, 1.0, WATER_IOR);
        let r0 = ((WATER_IOR - 1.0) / (WATER_IOR + 1.0)).powi(2);
        assert!((i.reflectance - r0).abs() < 1e-15);
        // The pack's own exact Fresnel agrees at every angle from above.
        for k in 0..90 {
            let theta = (k as f64).to_radians();
            let t = interface(ray(theta), DVec3::Y, 1.0, WATER_IOR);
            let sin_t = t.refracted.unwrap().x;
            assert!((theta.sin() - WATER_IOR * sin_t).abs() < 1e-12, "Snell at {k} degrees");
            let g2: f64 = WATER_IOR * WATER_IOR - 1.0 + theta.cos().powi(2);
            let (c, g) = (theta.cos(), g2.sqrt());
            let a = (g - c) / (g + c);
            let b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
            assert!((t.reflectance - 0.5 * a * a * (1.0 + b * b)).abs() < 1e-12, "Fresnel at {k} degrees");
        }
    }

    #[test]
    fn beyond_the_critical_angle_reflection_is_total() {
        let critical = critical_angle(WATER_IOR);
        assert!((critical - (1.0 / 1.333f64).asin()).abs() < 1e-15);
        let below = interface(ray(critical - 1e-6), DVec3::Y, WATER_IOR, 1.0);
        let beyond = interface(ray(critical + 1e-6), DVec3::Y, WATER_IOR, 1.0);
        assert!(below.refracted.is_some() && below.reflectance < 1.0);
        assert!(beyond.refracted.is_none() && beyond.reflectance == 1.0 && beyond.transmittance == 0.0);
        // A slab reflects more than one face and never more than everything.
        let slab = slab_reflectance(1.0, 1.0, GLASS_IOR);
        assert!((slab - 2.0 * 0.04 / 1.04).abs() < 1e-12, "{slab}");
    }
}
