//! shaderpack/shaders/lib/waves.glsl in f64: the wave height, the surface bisection and the normal.

use glam::{DVec2, DVec3};

use super::builtins::*;
use super::common::*;
use crate::sampling::Texture;
use crate::settings::{NormalMode, ReferenceSettings};

pub const WAVE_TILE: f64 = 64.0;
pub(crate) const WAVE_VECTOR: DVec2 = DVec2::new(3.0 * (TAU / WAVE_TILE), 5.0 * (TAU / WAVE_TILE));
pub(crate) const WAVE_SPEED: f64 = TAU * 180.0 / 3600.0;
pub(crate) const WAVE_AMPLITUDE_ANALYTIC: f64 = 0.10;
pub(crate) const WAVE_NOISE_WEIGHT: f64 = 0.6;
pub const WAVE_MAX_HEIGHT: f64 = WAVE_AMPLITUDE_ANALYTIC * (1.0 + WAVE_NOISE_WEIGHT);
pub(crate) const WAVE_DRIFT: DVec2 = DVec2::new(36.0 / 3600.0, 24.0 / 3600.0);
pub(crate) const LANDING_GAP: f64 = 0.004;
pub(crate) const LANDING_STEP: f64 = 0.02;

/// `heightTexel`.
pub(crate) fn height_texel(water: &Texture, world_xz: DVec2, time: f64, scale: f64) -> f64 {
    let uv = 0.5 + scale * DVec2::new(world_xz.x, -world_xz.y) / WAVE_TILE + time * WAVE_DRIFT;
    water.sample(fract2(uv)).x
}

/// `analyticWave`.
pub(crate) fn analytic_wave(world_xz: DVec2, time: f64) -> f64 {
    let phase = WAVE_SPEED * time + WAVE_VECTOR.dot(world_xz);
    (phase - 0.5 * phase.cos()).sin()
}

/// `waveHeight`.
pub fn wave_height(water: &Texture, world_xz: DVec2, time: f64) -> f64 {
    let noise = height_texel(water, world_xz, time, 1.0) * 2.0 - 1.0;
    WAVE_AMPLITUDE_ANALYTIC * (analytic_wave(world_xz, time) + WAVE_NOISE_WEIGHT * noise)
}

/// `waveGradient`: the gradient of the wave height, the analytic wave's exactly, the height
/// texture's as its difference across the first octave's cross (±0.25 block), which is what one
/// lookup of the first height cross texture gives.
pub(crate) fn wave_gradient(water: &Texture, world_xz: DVec2, time: f64) -> DVec2 {
    let phase = WAVE_SPEED * time + WAVE_VECTOR.dot(world_xz);
    let analytic = (phase - 0.5 * phase.cos()).cos() * (1.0 + 0.5 * phase.sin()) * WAVE_VECTOR;
    let [h1, h2, h3, h4] = height_cross(water, world_xz, time, 0.0, 1);
    let difference = DVec2::new(h1 - h2, h3 - h4);
    WAVE_AMPLITUDE_ANALYTIC * (analytic + WAVE_NOISE_WEIGHT * 2.0 * difference / 0.5)
}

/// `refineSurface` (A1): Newton's search along the ray from the flat hit, kept inside the
/// bracket where the crossing must lie. With the pack's tolerance (`EARLY_OUTS`) a short Newton
/// step from near the surface ends it, as the shader's landing does.
pub(crate) fn refine_surface(water: &Texture, player_hit: DVec3, ray_dir: DVec3, camera_wrap: DVec3, time: f64, camera_above: bool, s: &ReferenceSettings) -> DVec3 {
    let plane_y = player_hit.y;
    let (mut near, mut far) = (-20.0 * WAVE_MAX_HEIGHT, 20.0 * WAVE_MAX_HEIGHT);
    let mut t = 0.0;
    for _ in 0..s.wave_refine_steps {
        let p = player_hit + ray_dir * t;
        let world_xz = DVec2::new(p.x, p.z) + DVec2::new(camera_wrap.x, camera_wrap.z);
        let gap = p.y - plane_y - wave_height(water, world_xz, time);
        if gap.abs() < s.surface_tolerance {
            break;
        }
        if (gap > 0.0) == camera_above {
            near = t;
        } else {
            far = t;
        }
        let slope = ray_dir.y - wave_gradient(water, world_xz, time).dot(DVec2::new(ray_dir.x, ray_dir.z));
        let mut next = 0.5 * (near + far);
        if slope.abs() > 1e-6 {
            let crossing = t - gap / slope;
            if crossing >= near && crossing <= far {
                next = crossing;
                // `LANDING_GAP`, `LANDING_STEP`: a short step from near the surface is the last.
                if s.surface_tolerance > 0.0 && gap.abs() < LANDING_GAP && (gap / slope).abs() < LANDING_STEP {
                    return player_hit + ray_dir * next;
                }
            }
        }
        t = next;
    }
    player_hit + ray_dir * t
}

/// The four height samples at `±e` in x and z, each the sum of the octaves in use.
pub(crate) fn height_cross(water: &Texture, world_xz: DVec2, time: f64, distance: f64, octaves: u32) -> [f64; 4] {
    const E: f64 = 0.25;
    let offsets = [DVec2::new(E, 0.0), DVec2::new(-E, 0.0), DVec2::new(0.0, E), DVec2::new(0.0, -E)];
    let mut h = offsets.map(|o| height_texel(water, world_xz + o, time, 1.0));
    let (mut weight, mut scale) = (0.75, 2.0);
    for _ in 1..octaves {
        if distance >= 500.0 {
            break;
        }
        for (hk, o) in h.iter_mut().zip(offsets) {
            *hk += weight * height_texel(water, world_xz + o, time, scale);
        }
        weight *= 0.75;
        scale *= 2.0;
    }
    h
}

/// `waveNormal` (A2): the normal (world axes) and the diffuse intensity.
pub(crate) fn wave_normal(water: &Texture, world_xz: DVec2, time: f64, distance: f64, s: &ReferenceSettings) -> (DVec3, f64) {
    let flatten = 1.0 + 0.05 * distance;
    match s.normal_mode {
        NormalMode::StoredSlope => {
            // The first octave's height cross alone (one lookup of the first height cross texture).
            const E: f64 = 0.25;
            let [h1, h2, h3, h4] = height_cross(water, world_xz, time, distance, 1);
            let slope = WAVE_AMPLITUDE_ANALYTIC * WAVE_NOISE_WEIGHT * 2.0 * DVec2::new(h1 - h2, h3 - h4) / (2.0 * E);
            let diffuse = 0.35 + 0.4 * (height_texel(water, world_xz, time, 1.0) - 0.5);
            (safe_normalize(DVec3::new(-slope.x, flatten, -slope.y), UP), diffuse)
        }
        NormalMode::HeightSamples => {
            const E: f64 = 0.25;
            let [h1, h2, h3, h4] = height_cross(water, world_xz, time, distance, s.normal_octaves);
            let travel = WAVE_SPEED * time;
            let dx = (h1 - h2) * (1.0 + 0.3 * travel.cos());
            let dz = (h3 - h4) * (1.0 + 0.3 * travel.sin());
            let a1 = analytic_wave(world_xz + DVec2::new(2.1, 0.0), time);
            let a2 = analytic_wave(world_xz - DVec2::new(2.1, 0.0), time);
            let a3 = analytic_wave(world_xz + DVec2::new(0.0, 2.1), time);
            let a4 = analytic_wave(world_xz - DVec2::new(0.0, 2.1), time);
            let diffuse = 0.35 + 0.05 * (h1 + h2 + h3 + h4) + 0.05 * (a1 + a2 + a3 + a4);
            let slope_x = WAVE_AMPLITUDE_ANALYTIC * (WAVE_NOISE_WEIGHT * 2.0 * dx / (2.0 * E) + (a1 - a2) / 4.2);
            let slope_z = WAVE_AMPLITUDE_ANALYTIC * (WAVE_NOISE_WEIGHT * 2.0 * dz / (2.0 * E) + (a3 - a4) / 4.2);
            (safe_normalize(DVec3::new(-slope_x, flatten, -slope_z), UP), diffuse)
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec4;

    use super::*;

    /// lib/waves.glsl reads the four height samples of each octave from one lookup of a height
    /// cross texture: bilinear filtering being linear, the lookup must give their differences
    /// and sum exactly.
    #[test]
    fn one_height_cross_lookup_gives_the_four_height_samples() {
        let decode = |png: &[u8]| {
            let image = image::load_from_memory(png).unwrap().to_rgba8();
            Texture::from_rgba8(image.width() as usize, image.height() as usize, image.as_raw(), crate::Filter::Linear, crate::Wrap::Repeat)
        };
        let generated = tidepack_pack::textures::water_texture();
        let water = decode(&generated.png);
        let crosses: Vec<Texture> = generated.height_cross.iter().map(|png| decode(png)).collect();
        const BIAS: f64 = 128.0 / 255.0;
        for k in 0..400 {
            let world_xz = DVec2::new((k as f64 * 7.31) % 64.0, (k as f64 * 3.77) % 64.0);
            let time = k as f64 * 9.13;
            for (octave, cross) in crosses.iter().enumerate() {
                let scale = (1 << octave) as f64;
                let h = height_cross(&water, world_xz, time, 0.0, 1 + octave as u32);
                let lower = height_cross(&water, world_xz, time, 0.0, octave as u32);
                // This octave's own samples, weighted as waveNormal weights it.
                let weight = 0.75f64.powi(octave as i32);
                let own: Vec<f64> = h.iter().zip(lower).map(|(all, below)| if octave == 0 { *all } else { (all - below) / weight }).collect();
                let uv = 0.5 + scale * DVec2::new(world_xz.x, -world_xz.y) / WAVE_TILE + time * WAVE_DRIFT;
                let texel = cross.sample(fract2(uv));
                let expected = [own[0] - own[1], own[2] - own[3], own.iter().sum::<f64>()];
                let looked_up = [texel.x - BIAS, BIAS - texel.y, 4.0 * texel.z + texel.w - BIAS];
                for (e, l) in expected.iter().zip(looked_up) {
                    assert!((e - l).abs() < 1e-12, "octave {octave} at {world_xz}, time {time}: {expected:?} vs {looked_up:?}");
                }
                // The surface search reads the height from the first octave's B (lib/waves.glsl).
                if octave == 0 {
                    let height = height_texel(&water, world_xz, time, 1.0);
                    assert!((texel.z - height).abs() < 1e-12, "B is not the height at {world_xz}, time {time}: {} vs {height}", texel.z);
                }
            }
        }
    }

    #[test]
    fn the_surface_search_converges_to_the_wave_height() {
        let water = Texture::new(1, 1, vec![DVec4::splat(0.5)], crate::Filter::Linear, crate::Wrap::Repeat);
        let hit = DVec3::new(3.0, -5.0, -4.0);
        let dir = hit.normalize();
        let p = refine_surface(&water, hit, dir, DVec3::ZERO, 12.5, true, &ReferenceSettings::converged());
        let expected = hit.y + wave_height(&water, DVec2::new(p.x, p.z), 12.5);
        assert!((p.y - expected).abs() < 1e-12, "{} vs {expected}", p.y);
        // With the pack's tolerance it stops as soon as it is that close.
        let pack = ReferenceSettings { surface_tolerance: crate::settings::SURFACE_TOLERANCE, ..ReferenceSettings::converged() };
        let q = refine_surface(&water, hit, dir, DVec3::ZERO, 12.5, true, &pack);
        let expected = hit.y + wave_height(&water, DVec2::new(q.x, q.z), 12.5);
        assert!((q.y - expected).abs() < crate::settings::SURFACE_TOLERANCE, "{} vs {expected}", q.y);
        // Newton's search meets that tolerance within 3 lookups on a view ray as steep as a near
        // pixel's, and within HIGH's 8 on one grazing at 3 degrees.
        for (dir, steps) in [(hit.normalize(), 3), (DVec3::new(0.0, -0.05, -1.0).normalize(), 8)] {
            let q = refine_surface(&water, hit, dir, DVec3::ZERO, 12.5, true, &ReferenceSettings { wave_refine_steps: steps, ..pack.clone() });
            let gap = q.y - hit.y - wave_height(&water, DVec2::new(q.x, q.z), 12.5);
            assert!(gap.abs() < crate::settings::SURFACE_TOLERANCE, "{steps} steps along {dir}: gap {gap}");
        }
    }

    /// The landing (a short Newton step from near the surface ends the search with no lookup
    /// after it) stays within the tolerance on the pack's own height texture, at every
    /// elevation from steep to grazing.
    #[test]
    fn a_landed_search_is_within_the_tolerance_on_the_pack_texture() {
        let image = image::load_from_memory(&tidepack_pack::textures::water_texture().png).unwrap().to_rgba8();
        let water = Texture::from_rgba8(image.width() as usize, image.height() as usize, image.as_raw(), crate::Filter::Linear, crate::Wrap::Repeat);
        let pack = ReferenceSettings { surface_tolerance: crate::settings::SURFACE_TOLERANCE, wave_refine_steps: 8, ..ReferenceSettings::converged() };
        let mut worst: f64 = 0.0;
        for elevation in [60.0_f64, 30.0, 15.0, 8.0, 4.0] {
            for k in 0..500 {
                let azimuth = k as f64 * 2.399;
                let (sin_e, cos_e) = elevation.to_radians().sin_cos();
                let dir = DVec3::new(cos_e * azimuth.cos(), -sin_e, cos_e * azimuth.sin());
                let hit = DVec3::new((k as f64 * 7.31) % 64.0, -3.0, (k as f64 * 3.77) % 64.0);
                let time = k as f64 * 9.13;
                let q = refine_surface(&water, hit, dir, DVec3::ZERO, time, true, &pack);
                let gap = q.y - hit.y - wave_height(&water, DVec2::new(q.x, q.z), time);
                worst = worst.max(gap.abs());
            }
        }
        assert!(worst < crate::settings::SURFACE_TOLERANCE, "largest gap {worst}");
    }
}
