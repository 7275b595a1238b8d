//! The shadow pass's camera as OptiFine and Iris set it up: the sun's place in the sky
//! (celestial angle and sun-path tilt) recovered from a scene's sun direction, the pack's
//! shadow-map constants, and the `shadowModelView` / `shadowProjection` matrices built from
//! them. Facts from OptiFine's `Shaders.setCameraShadow` and shaders.txt, and Iris's
//! `ShadowMatrices`; docs/harness.md ("The shadow pass") lists them.

use glam::{DMat4, DVec3};

use crate::consts;

/// The near and far planes of both loaders' shadow projection.
const NEAR: f64 = 0.05;
const FAR: f64 = 256.0;

/// Where the shadow camera stands: this many blocks from the player towards the light.
const LIGHT_DISTANCE: f64 = 100.0;

/// The largest shadow map the harness draws; a pack asking for more is drawn at a lower
/// "Shadow Quality" (OptiFine's resolution multiplier), which the report names.
pub const MAX_RESOLUTION: u32 = 1024;

/// A pack's shadow-map constants, OptiFine's defaults where it declares none.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadowSettings {
    /// `shadowMapResolution` as declared.
    pub declared_resolution: u32,
    /// `shadowDistance`: half the side of the orthographic shadow volume, in blocks.
    pub distance: f64,
    /// `shadowIntervalSize`: the grid the camera snaps to, in blocks (0: no snapping).
    pub interval: f64,
    /// `shadowMapFov`: a perspective shadow camera of this field of view, in degrees.
    pub fov: Option<f64>,
    /// `shadowHardwareFiltering`: `sampler2DShadow` lookups filter the comparison linearly.
    pub hardware_filtering: bool,
    /// `shadowtexNearest`: the shadow maps read through `sampler2D` unfiltered (OptiFine
    /// filters them linearly otherwise).
    pub nearest: bool,
    /// `sunPathRotation` as declared, in degrees.
    pub sun_path_rotation: Option<f64>,
}

impl Default for ShadowSettings {
    fn default() -> ShadowSettings {
        ShadowSettings {
            declared_resolution: 1024,
            distance: 160.0,
            interval: 2.0,
            fov: None,
            hardware_filtering: false,
            nearest: false,
            sun_path_rotation: None,
        }
    }
}

impl ShadowSettings {
    /// Reads the constants from preprocessed program texts, as OptiFine reads every line of
    /// every program it loads: `const int shadowMapResolution = 2048;` and the legacy
    /// `/* SHADOWRES:2048 */` forms. The last declaration wins.
    pub fn from_texts<'t>(texts: impl IntoIterator<Item = &'t str>) -> ShadowSettings {
        let mut settings = ShadowSettings::default();
        for text in texts {
            for line in text.lines() {
                let line = line.trim();
                if let Some((name, value)) = consts::declaration(line, 0).map(|d| (d.name, d.value)).or_else(|| legacy_property(line)) {
                    settings.apply(name, value);
                }
            }
        }
        settings
    }

    fn apply(&mut self, name: &str, value: &str) {
        let number = || value.trim_end_matches(['f', 'F']).parse::<f64>().ok().filter(|v| v.is_finite());
        match name {
            "shadowMapResolution" | "SHADOWRES" => {
                if let Some(v) = number().filter(|v| *v >= 1.0 && *v <= 65536.0) {
                    self.declared_resolution = v as u32;
                }
            }
            "shadowDistance" | "SHADOWHPL" => {
                if let Some(v) = number().filter(|v| *v > 0.0) {
                    self.distance = v;
                    self.fov = None;
                }
            }
            "shadowMapFov" | "SHADOWFOV" => {
                if let Some(v) = number().filter(|v| *v > 0.0 && *v < 180.0) {
                    self.fov = Some(v);
                }
            }
            "shadowIntervalSize" => {
                if let Some(v) = number().filter(|v| *v >= 0.0) {
                    self.interval = v;
                }
            }
            "shadowHardwareFiltering" | "shadowHardwareFiltering0" | "shadowHardwareFiltering1" if value == "true" => {
                self.hardware_filtering = true;
            }
            "shadowtexNearest" | "shadowtex0Nearest" | "shadowtex1Nearest" | "shadow0MinMagNearest" | "shadow1MinMagNearest" if value == "true" => {
                self.nearest = true;
            }
            "sunPathRotation" => self.sun_path_rotation = number(),
            _ => {}
        }
    }

    /// The side of the shadow map the harness draws and the resolution multiplier that gives it
    /// (1, or the power of two bringing it down to [`MAX_RESOLUTION`]).
    pub fn drawn_resolution(&self) -> (u32, f64) {
        let mut multiplier = 1.0;
        while self.declared_resolution as f64 * multiplier > MAX_RESOLUTION as f64 {
            multiplier /= 2.0;
        }
        (((self.declared_resolution as f64 * multiplier).round() as u32).max(1), multiplier)
    }

    /// `shadowProjection`: orthographic over ±`distance` blocks, or the perspective of
    /// `shadowMapFov`; depth from 0.05 to 256 blocks in front of the shadow camera.
    pub fn projection(&self) -> DMat4 {
        match self.fov {
            Some(fov) => DMat4::perspective_rh_gl(fov.to_radians(), 1.0, NEAR, FAR),
            None => DMat4::orthographic_rh_gl(-self.distance, self.distance, -self.distance, self.distance, NEAR, FAR),
        }
    }
}

/// `/* SHADOWRES:2048 */` → ("SHADOWRES", "2048").
fn legacy_property(line: &str) -> Option<(&str, &str)> {
    let inner = line.strip_prefix("/*")?.strip_suffix("*/")?.trim();
    let (name, value) = inner.split_once(':')?;
    Some((name.trim(), value.trim()))
}

/// The sun's path through the sky: where it is today (the celestial angle, a fraction of a day
/// from noon) and the tilt of its path about the east-west axis (`sunPathRotation`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SunPath {
    /// 0 at noon, 0.25 at sunset, 0.5 at midnight, 0.75 at sunrise.
    pub celestial_angle: f64,
    /// Degrees.
    pub rotation: f64,
}

impl SunPath {
    /// The path on which the game puts the sun at world direction `sun` (towards the sun, any
    /// length). The game's sun is `Ry(-90°)·Rz(rotation)·Rx(360°·celestial_angle)·(0, 1, 0)` =
    /// `(-sin a, cos a·cos r, -cos a·sin r)`; the tilt is taken within ±90°.
    pub fn of_sun_direction(sun: DVec3) -> SunPath {
        let s = sun.normalize_or(DVec3::Y);
        let sign = if s.y < 0.0 { -1.0 } else { 1.0 };
        let rotation = if s.y == 0.0 && s.z == 0.0 { 0.0 } else { (-s.z * sign).atan2(s.y * sign).to_degrees() };
        let cos_a = sign * (s.y * s.y + s.z * s.z).sqrt();
        let angle = (-s.x).atan2(cos_a);
        SunPath { celestial_angle: (angle / std::f64::consts::TAU).rem_euclid(1.0), rotation }
    }

    /// The path on the game's clock: Minecraft's celestial angle of `world_time` (ticks; 6000 is
    /// noon), which runs slower around noon and midnight, tilted by `rotation` degrees.
    pub fn of_world_time(world_time: i64, rotation: f64) -> SunPath {
        let day = (world_time.rem_euclid(24000) as f64 / 24000.0 - 0.25).rem_euclid(1.0);
        let eased = 0.5 - (day * std::f64::consts::PI).cos() / 2.0;
        SunPath { celestial_angle: (day * 2.0 + eased) / 3.0, rotation }
    }

    /// The world direction towards the sun (unit length).
    pub fn sun_direction(&self) -> DVec3 {
        let a = self.celestial_angle * std::f64::consts::TAU;
        let r = self.rotation.to_radians();
        DVec3::new(-a.sin(), a.cos() * r.cos(), -a.cos() * r.sin())
    }

    /// `sunAngle`: 0 at sunrise, 0.25 at noon, 0.5 at sunset.
    pub fn sun_angle(&self) -> f64 {
        let c = self.celestial_angle;
        if c < 0.75 { c + 0.25 } else { c - 0.75 }
    }

    /// `shadowAngle`: `sunAngle` by day, `sunAngle - 0.5` by night (the moon casts shadows).
    pub fn shadow_angle(&self) -> f64 {
        let sun = self.sun_angle();
        if sun <= 0.5 { sun } else { sun - 0.5 }
    }

    /// `shadowModelView` for a camera at world position `camera`: 100 blocks towards the light
    /// that casts shadows, looking back along it, rotated with the sun's path and moved by the
    /// camera's place within a grid cell of `interval` blocks (so shadows do not swim as the
    /// player walks). Positions reach the shadow pass relative to the camera, as in gbuffers.
    pub fn shadow_model_view(&self, interval: f64, camera: DVec3) -> DMat4 {
        let mut angle = -360.0 * self.celestial_angle;
        if self.sun_angle() > 0.5 {
            angle += 180.0;
        }
        let mut m = DMat4::from_translation(DVec3::new(0.0, 0.0, -LIGHT_DISTANCE))
            * DMat4::from_rotation_x(90f64.to_radians())
            * DMat4::from_rotation_z(angle.to_radians())
            * DMat4::from_rotation_x(self.rotation.to_radians());
        if interval > 0.0 {
            // As the loaders compute it: a truncating remainder, so negative positions give
            // negative offsets.
            let half = interval / 2.0;
            let offset = DVec3::new(camera.x % interval - half, camera.y % interval - half, camera.z % interval - half);
            m *= DMat4::from_translation(offset);
        }
        m
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sun_direction_gives_back_its_path() {
        for (celestial_angle, rotation) in [(0.0, 0.0), (0.1, 25.0), (0.8, -40.0), (0.3, 10.0), (0.6, 0.0)] {
            let path = SunPath { celestial_angle, rotation };
            let a = celestial_angle * std::f64::consts::TAU;
            let r = f64::to_radians(rotation);
            let sun = DVec3::new(-a.sin(), a.cos() * r.cos(), -a.cos() * r.sin());
            let found = SunPath::of_sun_direction(sun * 3.0);
            assert!((found.celestial_angle - path.celestial_angle).abs() < 1e-9, "{found:?} for {path:?}");
            assert!((found.rotation - path.rotation).abs() < 1e-9, "{found:?} for {path:?}");
        }
        let dawn = SunPath { celestial_angle: 0.78, rotation: 0.0 };
        assert!((dawn.sun_angle() - 0.03).abs() < 1e-12 && (dawn.shadow_angle() - 0.03).abs() < 1e-12);
        let dusk_moon = SunPath { celestial_angle: 0.3, rotation: 0.0 };
        assert!((dusk_moon.sun_angle() - 0.55).abs() < 1e-12 && (dusk_moon.shadow_angle() - 0.05).abs() < 1e-12);
    }

    #[test]
    fn the_game_clock_puts_the_sun_where_minecraft_does() {
        // Noon overhead, sunrise (tick 0) in the east (+x) a little above the horizon (the eased
        // angle), sunset in the west, midnight below.
        let noon = SunPath::of_world_time(6000, 0.0);
        assert!((noon.celestial_angle - 0.0).abs() < 1e-12 && (noon.sun_direction() - DVec3::Y).length() < 1e-12);
        let sunrise = SunPath::of_world_time(0, 0.0);
        assert!((sunrise.celestial_angle - 0.7845177968644246).abs() < 1e-9, "{sunrise:?}");
        assert!(sunrise.sun_direction().x > 0.97 && sunrise.sun_direction().y > 0.2);
        assert!(SunPath::of_world_time(12000, 0.0).sun_direction().x < -0.97);
        assert!((SunPath::of_world_time(18000, 0.0).sun_direction() + DVec3::Y).length() < 1e-12);
        let tilted = SunPath::of_world_time(3000, -40.0);
        let back = SunPath::of_sun_direction(tilted.sun_direction());
        assert!((back.celestial_angle - tilted.celestial_angle).abs() < 1e-9 && (back.rotation + 40.0).abs() < 1e-9);
    }

    #[test]
    fn the_shadow_model_view_matches_the_loaders_at_dawn() {
        // Iris's own check of ShadowMatrices (shadowAngle 0.03451777, interval 2, no tilt, the
        // camera below), in column-major order, to its tolerance of 0.0005.
        let expected = [
            0.21545040607452393,
            5.820481518981069e-8,
            0.9765146970748901,
            0.0,
            -0.9765147466795349,
            1.2841844920785661e-8,
            0.21545039117336273,
            0.0,
            0.0,
            -0.9999999403953552,
            5.960464477539063e-8,
            0.0,
            0.38002151250839233,
            1.0264281034469604,
            -100.4463119506836,
            1.0,
        ];
        let path = SunPath { celestial_angle: 0.03451777 + 0.75, rotation: 0.0 };
        let m = path.shadow_model_view(2.0, DVec3::new(0.646045982837677, 82.53274536132812, -514.0264282226562));
        for (got, want) in m.to_cols_array().iter().zip(expected) {
            assert!((got - want).abs() < 5e-4, "{m:?}");
        }
    }

    #[test]
    fn the_light_looks_down_the_shadow_cameras_axis() {
        let path = SunPath { celestial_angle: 0.1, rotation: 30.0 };
        let a = 0.1 * std::f64::consts::TAU;
        let r = 30f64.to_radians();
        let sun = DVec3::new(-a.sin(), a.cos() * r.cos(), -a.cos() * r.sin());
        let towards_light = path.shadow_model_view(0.0, DVec3::ZERO).transform_vector3(sun);
        assert!((towards_light - DVec3::Z).length() < 1e-9, "{towards_light}");
    }

    #[test]
    fn reads_the_constants_and_their_legacy_forms() {
        let settings = ShadowSettings::from_texts([
            "const int shadowMapResolution = 2048; // [1024 2048]\nconst float shadowDistance = 120.0f;\n",
            "const float shadowIntervalSize = 4.0;\nconst bool shadowHardwareFiltering = true;\nconst float sunPathRotation = -40.0;\n",
        ]);
        assert_eq!(
            settings,
            ShadowSettings {
                declared_resolution: 2048,
                distance: 120.0,
                interval: 4.0,
                fov: None,
                hardware_filtering: true,
                nearest: false,
                sun_path_rotation: Some(-40.0)
            }
        );
        assert_eq!(settings.drawn_resolution(), (1024, 0.5));
        let legacy = ShadowSettings::from_texts(["/* SHADOWRES:512 */\n/* SHADOWFOV:90.0 */\n"]);
        assert_eq!((legacy.declared_resolution, legacy.fov), (512, Some(90.0)));
        assert_eq!(legacy.drawn_resolution(), (512, 1.0));
        let absurd = ShadowSettings::from_texts(["const int shadowMapResolution = 0;\nconst float shadowDistance = -5.0;\n"]);
        assert_eq!(absurd, ShadowSettings::default());
    }
}
