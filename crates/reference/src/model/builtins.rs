//! The GLSL built-ins the shaders call, in f64 (glam has no `smoothstep`, `reflect` or
//! `mat3(m) * v` of its own).

use glam::{DMat3, DMat4, DVec2, DVec3};

pub(crate) fn smoothstep(e0: f64, e1: f64, x: f64) -> f64 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

pub(crate) fn fract2(v: DVec2) -> DVec2 {
    v - v.floor()
}

/// GLSL `reflect(I, N)`.
pub(crate) fn reflect(i: DVec3, n: DVec3) -> DVec3 {
    i - 2.0 * n.dot(i) * n
}

pub(crate) fn mix3(a: DVec3, b: DVec3, t: f64) -> DVec3 {
    a + (b - a) * t
}

/// GLSL `mat3(m) * v`.
pub(crate) fn rotate(m: &DMat4, v: DVec3) -> DVec3 {
    DMat3::from_mat4(*m) * v
}
