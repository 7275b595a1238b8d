//! What the composite pass reads: the G-buffers, the uniforms and the textures.

use glam::{DMat4, DVec3};

use crate::sampling::Texture;

/// The uniform values composite.fsh declares, in f64.
#[derive(Clone, Debug, PartialEq)]
pub struct Uniforms {
    pub gbuffer_projection: DMat4,
    pub gbuffer_projection_inverse: DMat4,
    pub gbuffer_model_view: DMat4,
    pub gbuffer_model_view_inverse: DMat4,
    pub camera_position: DVec3,
    pub shadow_light_position: DVec3,
    pub sun_position: DVec3,
    pub sky_color: DVec3,
    pub fog_color: DVec3,
    pub frame_time_counter: f64,
    pub is_eye_in_water: i32,
    pub eye_brightness_smooth: [i32; 2],
    pub rain_strength: f64,
    /// The render distance in blocks.
    pub far: f64,
}

impl Uniforms {
    /// From components by OptiFine name (column-major for matrices, as `uniform` data is
    /// laid out). A missing name or a wrong component count is an error naming it.
    pub fn from_named<'a>(value: impl Fn(&str) -> Option<&'a [f64]>) -> Result<Uniforms, String> {
        let get = |name: &str, n: usize| -> Result<&'a [f64], String> {
            let v = value(name).ok_or_else(|| format!("no value for uniform {name}"))?;
            if v.len() == n { Ok(v) } else { Err(format!("uniform {name} has {} components, not {n}", v.len())) }
        };
        let mat4 = |name: &str| get(name, 16).map(DMat4::from_cols_slice);
        let vec3 = |name: &str| get(name, 3).map(DVec3::from_slice);
        let scalar = |name: &str| get(name, 1).map(|v| v[0]);
        let ivec2 = get("eyeBrightnessSmooth", 2)?;
        Ok(Uniforms {
            gbuffer_projection: mat4("gbufferProjection")?,
            gbuffer_projection_inverse: mat4("gbufferProjectionInverse")?,
            gbuffer_model_view: mat4("gbufferModelView")?,
            gbuffer_model_view_inverse: mat4("gbufferModelViewInverse")?,
            camera_position: vec3("cameraPosition")?,
            shadow_light_position: vec3("shadowLightPosition")?,
            sun_position: vec3("sunPosition")?,
            sky_color: vec3("skyColor")?,
            fog_color: vec3("fogColor")?,
            frame_time_counter: scalar("frameTimeCounter")?,
            is_eye_in_water: scalar("isEyeInWater")? as i32,
            eye_brightness_smooth: [ivec2[0] as i32, ivec2[1] as i32],
            rain_strength: scalar("rainStrength")?,
            far: scalar("far")?,
        })
    }
}

/// Everything composite reads for one frame. The screen-sized textures share `width` x
/// `height`, row 0 at the bottom of the screen (OpenGL's orientation).
#[derive(Clone, Debug)]
pub struct Inputs {
    pub width: usize,
    pub height: usize,
    /// The scene behind the water (glass blended in); alpha 0 where a translucent drew.
    pub colortex0: Texture,
    /// Rain, clouds and the translucent hand: premultiplied colour, coverage in alpha.
    pub colortex3: Texture,
    /// Water mark (r; weakened by each glass in front of the water), the water's sky light (g)
    /// and its distance as a fraction of 4 · far (b).
    pub colortex4: Texture,
    /// The water's tint (rgb).
    pub colortex5: Texture,
    /// The water's plain colour (rgb), kept under glass.
    pub colortex6: Texture,
    /// Depth of the nearest surface (r), translucents included.
    pub depthtex0: Texture,
    /// Depth of the nearest opaque surface (r).
    pub depthtex1: Texture,
    /// The water texture bound to colortex7 (the height at 1, 2 and 4 times its frequency, foam).
    pub water: Texture,
    /// OptiFine's noisetex (caustics mode 1).
    pub noise: Texture,
    pub uniforms: Uniforms,
}

impl Inputs {
    /// Checks the screen-sized textures all have the frame's size.
    pub fn validate(&self) -> Result<(), String> {
        for (name, t) in [
            ("colortex0", &self.colortex0),
            ("colortex3", &self.colortex3),
            ("colortex4", &self.colortex4),
            ("colortex5", &self.colortex5),
            ("colortex6", &self.colortex6),
            ("depthtex0", &self.depthtex0),
            ("depthtex1", &self.depthtex1),
        ] {
            if (t.width, t.height) != (self.width, self.height) {
                return Err(format!("{name} is {}x{}, the frame {}x{}", t.width, t.height, self.width, self.height));
            }
        }
        Ok(())
    }
}
