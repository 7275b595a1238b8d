//! shaderpack/shaders/composite.fsh in f64: the per-pixel shading that calls the lib modules.

use glam::{DVec2, DVec3, DVec4, Vec4Swizzles};

use super::builtins::*;
use super::caustics::*;
use super::common::*;
use super::optics::*;
use super::reflections::*;
use super::space::*;
use super::waves::*;
use crate::inputs::{Inputs, Uniforms};
use crate::settings::{CausticsMode, ReferenceSettings};

const DEFAULT_WATER_TINT: DVec3 = DVec3::new(0.247, 0.463, 0.894);
const CAUSTIC_COLOR: DVec3 = DVec3::new(1.0, 0.97, 0.9);
const FOAM_COLOR: DVec3 = DVec3::new(0.9, 0.95, 1.0);
const INVISIBLE: f64 = 1.0 / 255.0;
const MOON_GLINT: f64 = 0.1;

/// One frame's inputs with the settings, shared by the per-pixel functions.
pub(crate) struct Frame<'a> {
    pub(crate) i: &'a Inputs,
    pub(crate) u: &'a Uniforms,
    pub(crate) s: &'a ReferenceSettings,
}

impl Frame<'_> {
    pub(crate) fn colortex0(&self, uv: DVec2) -> DVec4 {
        self.i.colortex0.sample(uv)
    }

    pub(crate) fn depth1(&self, uv: DVec2) -> f64 {
        self.i.depthtex1.sample(uv).x
    }

    fn time(&self) -> f64 {
        self.u.frame_time_counter
    }

    fn camera_wrap(&self) -> DVec3 {
        wrapped_camera(self.u.camera_position, WAVE_TILE)
    }

    fn view_from_screen(&self, uv: DVec2, depth: f64) -> DVec3 {
        view_from_screen(uv, depth, &self.u.gbuffer_projection_inverse)
    }

    fn player_from_view(&self, view: DVec3) -> DVec3 {
        player_from_view(view, &self.u.gbuffer_model_view_inverse)
    }

    /// `eyePosition`.
    fn eye_position(&self) -> DVec3 {
        self.u.gbuffer_model_view_inverse.w_axis.xyz()
    }

    /// `glintStrength`.
    fn glint_strength(&self) -> f64 {
        let moon = self.u.shadow_light_position.dot(self.u.sun_position) < 0.0;
        (if moon { MOON_GLINT } else { 1.0 }) * (1.0 - self.u.rain_strength.clamp(0.0, 1.0))
    }

    /// `lightDirection`.
    fn light_direction(&self) -> DVec3 {
        safe_normalize(rotate(&self.u.gbuffer_model_view_inverse, self.u.shadow_light_position), UP)
    }

    fn transmittance(&self, path_length: f64) -> DVec3 {
        transmittance(path_length, self.s)
    }

    /// `withCaustics`.
    fn with_caustics(&self, lit: DVec3, world_xz: DVec2, visibility: f64) -> DVec3 {
        if !self.s.caustics || (self.s.early_outs && visibility < INVISIBLE) {
            return lit;
        }
        match self.s.caustics_mode {
            CausticsMode::HeightTexture => {
                let intensity = caustics_from_height(&self.i.water, world_xz, self.time(), self.s.caustic_samples) * self.s.caustics_strength;
                lit + CAUSTIC_COLOR * intensity * max_component(lit) * visibility
            }
            CausticsMode::NoiseTexture => {
                let pattern = caustics_from_noise(&self.i.noise, world_xz, self.time(), self.s.caustic_samples);
                lit * (1.0 + self.s.caustics_strength * pattern * visibility).max(0.0)
            }
        }
    }

    /// `throughWater`.
    fn through_water(&self, color: DVec3, path_length: f64, scattered: DVec3) -> DVec3 {
        if !self.s.depth_fade {
            return color;
        }
        let t = self.transmittance(path_length);
        t * color + (1.0 - t) * scattered
    }

    /// `sceneBehindOverlay`.
    fn scene_behind_overlay(&self, uv: DVec2) -> DVec3 {
        let over = self.i.colortex3.sample(uv);
        (self.colortex0(uv).xyz() - over.xyz()) / (1.0 - over.w).max(INVISIBLE)
    }

    /// `shadeFromAbove`: cases 4 and 5.
    fn shade_from_above(&self, uv: DVec2, depth0: f64, tint: DVec3, sky_light: f64) -> DVec3 {
        let (u, s) = (self.u, self.s);
        let view0 = self.view_from_screen(uv, depth0);
        let distance0 = view0.length();
        let haze = 1.0 - distance_fog(distance0, u.far);
        if s.far_haze && haze <= 0.0 {
            return u.fog_color;
        }
        let player0 = self.player_from_view(view0);
        let ray_dir = safe_normalize(player0 - self.eye_position(), DVec3::new(0.0, -1.0, 0.0));
        let camera_wrap = self.camera_wrap();
        let time = self.time();

        let surface = refine_surface(&self.i.water, player0, ray_dir, camera_wrap, time, true, s);
        let surface_xz = DVec2::new(surface.x + camera_wrap.x, surface.z + camera_wrap.z);
        let (normal, diffuse) = wave_normal(&self.i.water, surface_xz, time, distance0, s);
        let normal_view = rotate(&u.gbuffer_model_view, normal);
        let cos_view = (-ray_dir).dot(normal).clamp(0.0, 1.0);
        let scattered = scattered_color(tint, sky_light, u.sky_color) * (0.65 + diffuse);

        let mut depth1 = self.depth1(uv);
        let mut scene_uv = uv;
        if s.refraction {
            let opacity = 1.0 - self.transmittance(self.view_from_screen(uv, depth1).length() - distance0).z;
            let candidate = (uv + DVec2::new(normal_view.x, normal_view.y) * s.refraction_strength * opacity).clamp(DVec2::ZERO, DVec2::ONE);
            let candidate_depth = self.depth1(candidate);
            if candidate_depth > depth0 {
                scene_uv = candidate;
                depth1 = candidate_depth;
            }
        }
        let view1 = self.view_from_screen(scene_uv, depth1);
        let player1 = self.player_from_view(view1);
        let path_in_water = player1.distance(surface).max(0.0);
        let floor_visible = depth1 < 1.0;
        let mut below = self.scene_behind_overlay(scene_uv);
        if floor_visible {
            let xz = DVec2::new(player1.x + camera_wrap.x, player1.z + camera_wrap.z);
            below = self.with_caustics(below, xz, self.transmittance(path_in_water).z);
        }
        below = self.through_water(below, path_in_water, scattered);

        let reflected = reflect(ray_dir, normal);
        let mut reflection = sky_radiance(reflected, u.sky_color, u.fog_color) * (0.2 + 0.8 * sky_light);
        let reflectance = fresnel(cos_view, true, s.fresnel_exact);
        // As in the pack: the march is skipped when the reflected scene could not show.
        let reflection_weight = if s.far_haze { reflectance * haze } else { reflectance };
        if s.reflections && !(s.early_outs && reflection_weight < INVISIBLE) {
            let flatter = DVec3::new(normal.x, normal.y * (5.0 + 0.025 * distance0), normal.z);
            let march_normal = rotate(&u.gbuffer_model_view, safe_normalize(flatter, UP));
            let start = (u.gbuffer_model_view * surface.extend(1.0)).xyz();
            let march_dir = reflect(safe_normalize(view0, DVec3::new(0.0, 0.0, -1.0)), march_normal);
            let hit = trace_reflection(self, start, march_dir, march_dir.dot(march_normal));
            reflection = mix3(reflection, hit.xyz(), hit.w);
        }
        let mut color = mix3(below, reflection, reflectance);

        let mut foam = 0.0;
        if s.foam {
            let water_depth = if floor_visible { (surface.y - player1.y).max(0.0) } else { 1e4 };
            let coastal = (0.8 * (1.0 - water_depth / 1.5)).max(0.0);
            let crest = smoothstep(0.55, 0.75, diffuse);
            let foam_uv = 0.5 + 4.0 * DVec2::new(surface_xz.x + normal.x, -(surface_xz.y + normal.z)) / WAVE_TILE;
            foam = coastal.max(crest) * (32.0 / distance0.max(1.0)).min(1.0) * self.i.water.sample(fract2(foam_uv)).w;
            color = mix3(color, FOAM_COLOR * (0.2 + 0.8 * sky_light) * (0.3 + 0.7 * luminance(u.sky_color)), foam);
        }
        if s.specular {
            let foam_free = 1.0 - foam;
            color += specular_light(reflected, self.light_direction(), self.glint_strength(), u.sky_color, sky_light) * reflectance * foam_free * foam_free * foam_free;
        }
        if s.far_haze {
            color = mix3(u.fog_color, color, haze);
        }
        color
    }

    /// `shadeFromBelow`: case 3.
    fn shade_from_below(&self, uv: DVec2, depth0: f64, sky_light: f64, scattered: DVec3) -> DVec3 {
        let s = self.s;
        let view0 = self.view_from_screen(uv, depth0);
        let distance0 = view0.length();
        let player0 = self.player_from_view(view0);
        let ray_dir = safe_normalize(player0 - self.eye_position(), UP);
        let camera_wrap = self.camera_wrap();
        let surface = refine_surface(&self.i.water, player0, ray_dir, camera_wrap, self.time(), false, s);
        let surface_xz = DVec2::new(surface.x + camera_wrap.x, surface.z + camera_wrap.z);
        let (normal, diffuse) = wave_normal(&self.i.water, surface_xz, self.time(), distance0, s);
        let cos_view = ray_dir.dot(normal).clamp(0.0, 1.0);

        let depth1 = self.depth1(uv);
        let mut scene_uv = uv;
        if s.refraction {
            let behind = (self.view_from_screen(uv, depth1).length() - distance0).max(0.0);
            let normal_view = rotate(&self.u.gbuffer_model_view, normal);
            scene_uv = (uv + DVec2::new(normal_view.x, normal_view.y) * s.refraction_strength * (behind / 8.0).clamp(0.0, 1.0)).clamp(DVec2::ZERO, DVec2::ONE);
        }
        let above = self.colortex0(scene_uv).xyz();
        let mut color = mix3(above, scattered, fresnel(cos_view, false, s.fresnel_exact));
        if s.foam {
            color = mix3(color, FOAM_COLOR * 0.5 * sky_light, smoothstep(0.6, 0.8, diffuse) * 0.5);
        }
        self.through_water(color, distance0, scattered)
    }

    /// `shadeUnderwater`: case 2.
    fn shade_underwater(&self, uv: DVec2, depth0: f64, color: DVec3, opaque: bool, scattered: DVec3) -> DVec3 {
        let view0 = self.view_from_screen(uv, depth0);
        let distance0 = view0.length();
        let mut color = color;
        if opaque {
            let player0 = self.player_from_view(view0);
            let wrap = self.camera_wrap();
            color = self.with_caustics(color, DVec2::new(player0.x + wrap.x, player0.z + wrap.z), self.transmittance(distance0).z);
        }
        self.through_water(color, distance0, scattered)
    }

    /// composite's `main` at one screen position: rgb (alpha is the scene's, passed through).
    fn shade(&self, uv: DVec2) -> DVec3 {
        let i = self.i;
        let scene = i.colortex0.sample(uv);
        let water_record = i.colortex4.sample(uv);
        let water = is_water_nearest(water_record.x);
        let depth0 = i.depthtex0.sample(uv).x;
        if self.u.is_eye_in_water != 1 {
            // As in the pack: colortex0's alpha stays 1 where gbuffers_water drew nothing.
            if self.s.early_outs && scene.w >= 1.0 {
                return scene.xyz();
            }
            let behind_glass = is_water_behind_translucent(water_record.x);
            if !water && !behind_glass {
                return scene.xyz();
            }
            // Rain, clouds and the hand over the water: premultiplied in colortex3, coverage in alpha.
            let drawn_over = i.colortex3.sample(uv);
            let uncovered = 1.0 - drawn_over.w;
            let behind = (scene.xyz() - drawn_over.xyz()) / uncovered.max(INVISIBLE);
            let shaded = if water {
                // Where rain, clouds or the hand wrote their depth, the surface's comes from the
                // distance the water kept.
                let depth0 = if drawn_over.w > 0.0 {
                    let distance = water_record.z * WATER_DISTANCE_RANGE * self.u.far.max(1.0);
                    depth_at_distance(uv, distance, &self.u.gbuffer_projection, &self.u.gbuffer_projection_inverse)
                } else {
                    depth0
                };
                self.shade_from_above(uv, depth0, i.colortex5.sample(uv).xyz(), water_record.y)
            } else {
                mix3(behind, i.colortex6.sample(uv).xyz(), 0.6)
            };
            return shaded * uncovered + drawn_over.xyz();
        }
        let eye_sky_light = (self.u.eye_brightness_smooth[1] as f64 / 240.0).clamp(0.0, 1.0);
        if water {
            let scattered = scattered_color(i.colortex5.sample(uv).xyz(), eye_sky_light, self.u.sky_color);
            return self.shade_from_below(uv, depth0, water_record.y, scattered);
        }
        let scattered = scattered_color(DEFAULT_WATER_TINT, eye_sky_light, self.u.sky_color);
        let opaque = scene.w > 0.5 && depth0 < 1.0;
        self.shade_underwater(uv, depth0, scene.xyz(), opaque, scattered)
    }
}

/// The composite's colour at pixel (x, y), y counted from the bottom, sampled at the pixel
/// centre as the full-screen quad's `screenUv` interpolates it.
pub fn shade_pixel(inputs: &Inputs, settings: &ReferenceSettings, x: usize, y: usize) -> DVec3 {
    let frame = Frame { i: inputs, u: &inputs.uniforms, s: settings };
    let uv = DVec2::new((x as f64 + 0.5) / inputs.width as f64, (y as f64 + 0.5) / inputs.height as f64);
    frame.shade(uv)
}
