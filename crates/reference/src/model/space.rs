//! shaderpack/shaders/lib/space.glsl in f64: screen, view and player space.

use glam::{DMat4, DVec2, DVec3, DVec4, Vec4Swizzles};

use super::builtins::*;
use super::common::*;

/// `divideByW`.
pub(crate) fn divide_by_w(p: DVec4) -> DVec3 {
    let w = if p.w.abs() > 1e-7 { p.w } else if p.w < 0.0 { -1e-7 } else { 1e-7 };
    p.xyz() / w
}

/// `viewFromScreen`.
pub(crate) fn view_from_screen(uv: DVec2, depth: f64, projection_inverse: &DMat4) -> DVec3 {
    divide_by_w(*projection_inverse * (DVec3::new(uv.x, uv.y, depth) * 2.0 - 1.0).extend(1.0))
}

/// `screenFromClip` of the view-space point's clip position (the march steps the clip position
/// in f32; in f64 projecting each point is the same).
pub(crate) fn screen_from_view(view: DVec3, projection: &DMat4) -> DVec3 {
    let clip = *projection * view.extend(1.0);
    if clip.w <= 1e-5 {
        return DVec3::splat(-1.0);
    }
    clip.xyz() / clip.w * 0.5 + 0.5
}

/// `depthAtDistance`.
pub(crate) fn depth_at_distance(uv: DVec2, distance: f64, projection: &DMat4, projection_inverse: &DMat4) -> f64 {
    let ray = safe_normalize(view_from_screen(uv, 0.5, projection_inverse), DVec3::new(0.0, 0.0, -1.0));
    let clip = *projection * (ray * distance.max(0.0)).extend(1.0);
    (divide_by_w(clip).z * 0.5 + 0.5).clamp(0.0, 1.0)
}

/// `playerFromView`.
pub(crate) fn player_from_view(view: DVec3, model_view_inverse: &DMat4) -> DVec3 {
    rotate(model_view_inverse, view) + model_view_inverse.w_axis.xyz()
}

/// `wrappedCamera`.
pub(crate) fn wrapped_camera(camera: DVec3, period: f64) -> DVec3 {
    camera - period * (camera / period).floor()
}
