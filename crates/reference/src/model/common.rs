//! shaderpack/shaders/lib/common.glsl in f64: the water mark tests and small helpers.

use glam::DVec3;

/// `TAU` as the shader writes it (its digits, not `std::f64::consts::TAU`'s).
#[allow(clippy::approx_constant)]
pub const TAU: f64 = 6.28318530718;
pub(crate) const WATER_DISTANCE_RANGE: f64 = 4.0;
/// `vec3(0.0, 1.0, 0.0)`, the fallback direction the shaders hand `safeNormalize`.
pub(crate) const UP: DVec3 = DVec3::new(0.0, 1.0, 0.0);

/// `isWaterNearest`.
pub fn is_water_nearest(mark: f64) -> bool {
    mark > 0.875
}

/// `isWaterBehindTranslucent`.
pub fn is_water_behind_translucent(mark: f64) -> bool {
    mark > 0.04 && mark <= 0.875
}

/// `distanceFog`.
pub fn distance_fog(view_distance: f64, render_distance: f64) -> f64 {
    let range = render_distance.max(1.0);
    ((view_distance - 0.75 * range) / (0.25 * range)).clamp(0.0, 1.0)
}

/// `safeNormalize`.
pub(crate) fn safe_normalize(v: DVec3, fallback: DVec3) -> DVec3 {
    let length_squared = v.dot(v);
    if length_squared > 1e-12 { v / length_squared.sqrt() } else { fallback }
}

/// `luminance`.
pub(crate) fn luminance(c: DVec3) -> f64 {
    c.dot(DVec3::new(0.2126, 0.7152, 0.0722))
}

/// `maxComponent`.
pub(crate) fn max_component(v: DVec3) -> f64 {
    v.max_element()
}
