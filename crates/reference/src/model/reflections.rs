//! shaderpack/shaders/lib/reflections.glsl in f64: the screen-space reflection march.

use glam::{DVec2, DVec3, DVec4, Vec4Swizzles};

use super::composite::Frame;
use super::space::*;

pub(crate) fn off_screen(screen: DVec3) -> bool {
    screen.z < 0.0 || screen.x < 0.0 || screen.y < 0.0 || screen.x > 1.0 || screen.y > 1.0
}

/// `traceReflection`: the reflected scene colour (rgb) and its weight (a; 0 on a miss).
pub(crate) fn trace_reflection(f: &Frame, start: DVec3, dir: DVec3, cos_to_normal: f64) -> DVec4 {
    let (projection, inverse) = (&f.u.gbuffer_projection, &f.u.gbuffer_projection_inverse);
    let scene_at = |screen: DVec3| view_from_screen(DVec2::new(screen.x, screen.y), f.depth1(DVec2::new(screen.x, screen.y)), inverse);
    let mut step_length = 7.0 / (cos_to_normal * cos_to_normal).max(0.6);
    let mut travelled = 0.5 * step_length;
    let mut previous = 0.0;
    let mut tolerance = 16.0;
    for _ in 0..f.s.ssr_steps {
        let p = start + dir * travelled;
        let screen = screen_from_view(p, projection);
        if off_screen(screen) {
            return DVec4::ZERO;
        }
        let scene = scene_at(screen);
        let gap = scene - p;
        if gap.dot(gap) < tolerance && p.z <= scene.z + 0.5 {
            let (mut lo, mut hi) = (previous, travelled);
            for _ in 0..f.s.ssr_refine_steps {
                let mid = 0.5 * (lo + hi);
                let q = start + dir * mid;
                let q_scene = scene_at(screen_from_view(q, projection));
                if q.z < q_scene.z {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            let hit = screen_from_view(start + dir * hi, projection);
            let hit_uv = DVec2::new(hit.x, hit.y).clamp(DVec2::ZERO, DVec2::ONE);
            let ndc = hit_uv * 2.0 - 1.0;
            let border = (1.0 - (0.01 + ndc.dot(ndc)).powf(0.25)).clamp(0.0, 1.0);
            return f.colortex0(hit_uv).xyz().extend(border);
        }
        previous = travelled;
        tolerance *= 1.1;
        step_length *= 1.2;
        travelled += step_length;
    }
    DVec4::ZERO
}
