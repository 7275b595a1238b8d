//! composite.fsh and shaderpack/shaders/lib/*.glsl, function by function, in f64. Each item
//! names the GLSL function it mirrors; constants are the shader's.

use glam::{DMat3, DMat4, DVec2, DVec3, DVec4, Vec4Swizzles};

use crate::inputs::{Inputs, Uniforms};
use crate::sampling::Texture;
use crate::settings::{Absorption, CausticsMode, NormalMode, ReferenceSettings};

// lib/common.glsl
/// `TAU` as the shader writes it (its digits, not `std::f64::consts::TAU`'s).
#[allow(clippy::approx_constant)]
pub const TAU: f64 = 6.28318530718;

// lib/waves.glsl
pub const WAVE_TILE: f64 = 64.0;
const WAVE_VECTOR: DVec2 = DVec2::new(3.0 * (TAU / WAVE_TILE), 5.0 * (TAU / WAVE_TILE));
const WAVE_SPEED: f64 = TAU * 180.0 / 3600.0;
const WAVE_AMPLITUDE_ANALYTIC: f64 = 0.10;
const WAVE_NOISE_WEIGHT: f64 = 0.6;
const WAVE_MAX_HEIGHT: f64 = WAVE_AMPLITUDE_ANALYTIC * (1.0 + WAVE_NOISE_WEIGHT);
const WAVE_DRIFT: DVec2 = DVec2::new(36.0 / 3600.0, 24.0 / 3600.0);

// lib/optics.glsl
const WATER_F0: f64 = 0.02;
const WATER_IOR: f64 = 1.333;

// composite.fsh
const DEFAULT_WATER_TINT: DVec3 = DVec3::new(0.247, 0.463, 0.894);
const CAUSTIC_COLOR: DVec3 = DVec3::new(1.0, 0.97, 0.9);
const FOAM_COLOR: DVec3 = DVec3::new(0.9, 0.95, 1.0);
const INVISIBLE: f64 = 1.0 / 255.0;
const MOON_GLINT: f64 = 0.1;
const WATER_DISTANCE_RANGE: f64 = 4.0;

const UP: DVec3 = DVec3::new(0.0, 1.0, 0.0);

// ---- GLSL built-ins -------------------------------------------------------------------------

fn smoothstep(e0: f64, e1: f64, x: f64) -> f64 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

fn fract2(v: DVec2) -> DVec2 {
    v - v.floor()
}

/// GLSL `reflect(I, N)`.
fn reflect(i: DVec3, n: DVec3) -> DVec3 {
    i - 2.0 * n.dot(i) * n
}

fn mix3(a: DVec3, b: DVec3, t: f64) -> DVec3 {
    a + (b - a) * t
}

/// GLSL `mat3(m) * v`.
fn rotate(m: &DMat4, v: DVec3) -> DVec3 {
    DMat3::from_mat4(*m) * v
}

// ---- lib/common.glsl ------------------------------------------------------------------------

/// `isWaterNearest`.
pub fn is_water_nearest(mark: f64) -> bool {
    mark > 0.875
}

/// `isWaterBehindTranslucent`.
pub fn is_water_behind_translucent(mark: f64) -> bool {
    mark > 0.04 && mark <= 0.875
}

/// `distanceFog`.
fn distance_fog(view_distance: f64, render_distance: f64) -> f64 {
    let range = render_distance.max(1.0);
    ((view_distance - 0.75 * range) / (0.25 * range)).clamp(0.0, 1.0)
}

/// `safeNormalize`.
fn safe_normalize(v: DVec3, fallback: DVec3) -> DVec3 {
    let length_squared = v.dot(v);
    if length_squared > 1e-12 { v / length_squared.sqrt() } else { fallback }
}

/// `luminance`.
fn luminance(c: DVec3) -> f64 {
    c.dot(DVec3::new(0.2126, 0.7152, 0.0722))
}

/// `maxComponent`.
fn max_component(v: DVec3) -> f64 {
    v.max_element()
}

// ---- lib/space.glsl -------------------------------------------------------------------------

/// `divideByW`.
fn divide_by_w(p: DVec4) -> DVec3 {
    let w = if p.w.abs() > 1e-7 { p.w } else if p.w < 0.0 { -1e-7 } else { 1e-7 };
    p.xyz() / w
}

/// `viewFromScreen`.
fn view_from_screen(uv: DVec2, depth: f64, projection_inverse: &DMat4) -> DVec3 {
    divide_by_w(*projection_inverse * (DVec3::new(uv.x, uv.y, depth) * 2.0 - 1.0).extend(1.0))
}

/// `screenFromView`.
fn screen_from_view(view: DVec3, projection: &DMat4) -> DVec3 {
    let clip = *projection * view.extend(1.0);
    if clip.w <= 1e-5 {
        return DVec3::splat(-1.0);
    }
    clip.xyz() / clip.w * 0.5 + 0.5
}

/// `depthAtDistance`.
fn depth_at_distance(uv: DVec2, distance: f64, projection: &DMat4, projection_inverse: &DMat4) -> f64 {
    let ray = safe_normalize(view_from_screen(uv, 0.5, projection_inverse), DVec3::new(0.0, 0.0, -1.0));
    let clip = *projection * (ray * distance.max(0.0)).extend(1.0);
    (divide_by_w(clip).z * 0.5 + 0.5).clamp(0.0, 1.0)
}

/// `playerFromView`.
fn player_from_view(view: DVec3, model_view_inverse: &DMat4) -> DVec3 {
    rotate(model_view_inverse, view) + model_view_inverse.w_axis.xyz()
}

/// `wrappedCamera`.
fn wrapped_camera(camera: DVec3, period: f64) -> DVec3 {
    camera - period * (camera / period).floor()
}

// ---- lib/waves.glsl -------------------------------------------------------------------------

/// `heightTexel`.
fn height_texel(water: &Texture, world_xz: DVec2, time: f64, scale: f64) -> f64 {
    let uv = 0.5 + scale * DVec2::new(world_xz.x, -world_xz.y) / WAVE_TILE + time * WAVE_DRIFT;
    water.sample(fract2(uv)).x
}

/// `analyticWave`.
fn analytic_wave(world_xz: DVec2, time: f64) -> f64 {
    let phase = WAVE_SPEED * time + WAVE_VECTOR.dot(world_xz);
    (phase - 0.5 * phase.cos()).sin()
}

/// `waveHeight`.
fn wave_height(water: &Texture, world_xz: DVec2, time: f64) -> f64 {
    let noise = height_texel(water, world_xz, time, 1.0) * 2.0 - 1.0;
    WAVE_AMPLITUDE_ANALYTIC * (analytic_wave(world_xz, time) + WAVE_NOISE_WEIGHT * noise)
}

/// `refineSurface` (A1): bisection along the ray from the flat hit towards the wave surface.
fn refine_surface(water: &Texture, player_hit: DVec3, ray_dir: DVec3, camera_wrap: DVec3, time: f64, camera_above: bool, s: &ReferenceSettings) -> DVec3 {
    let mut p = player_hit;
    let plane_y = player_hit.y;
    let mut step_length = 10.0 * WAVE_MAX_HEIGHT;
    for _ in 0..s.wave_refine_steps {
        let gap = p.y - plane_y - wave_height(water, DVec2::new(p.x, p.z) + DVec2::new(camera_wrap.x, camera_wrap.z), time);
        if gap.abs() < s.surface_tolerance {
            break;
        }
        let camera_side = (gap > 0.0) == camera_above;
        p += ray_dir * if camera_side { step_length } else { -step_length };
        step_length *= 0.5;
    }
    p
}

/// The four height samples at `±e` in x and z, each the sum of the octaves in use.
fn height_cross(water: &Texture, world_xz: DVec2, time: f64, distance: f64, octaves: u32) -> [f64; 4] {
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
fn wave_normal(water: &Texture, world_xz: DVec2, time: f64, distance: f64, s: &ReferenceSettings) -> (DVec3, f64) {
    let flatten = 1.0 + 0.05 * distance;
    match s.normal_mode {
        NormalMode::StoredSlope => {
            let uv = 0.5 + DVec2::new(world_xz.x, -world_xz.y) / WAVE_TILE + time * WAVE_DRIFT;
            let texel = water.sample(fract2(uv));
            let slope = (DVec2::new(texel.y, texel.z) * 2.0 - 1.0) * s.slope_range * WAVE_NOISE_WEIGHT * WAVE_AMPLITUDE_ANALYTIC * 2.0 / WAVE_TILE;
            let diffuse = 0.35 + 0.4 * (texel.x - 0.5);
            (safe_normalize(DVec3::new(-slope.x, flatten, slope.y), UP), diffuse)
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

// ---- lib/optics.glsl ------------------------------------------------------------------------

/// `fresnelSchlick`.
fn fresnel_schlick(cos_theta: f64) -> f64 {
    let m = 1.0 - cos_theta.clamp(0.0, 1.0);
    let m2 = m * m;
    WATER_F0 + (1.0 - WATER_F0) * m2 * m2 * m
}

/// `fresnelExact`: unpolarised dielectric reflectance with relative index `eta`.
fn fresnel_exact(cos_theta: f64, eta: f64) -> f64 {
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
fn fresnel(cos_theta: f64, from_above: bool, exact: bool) -> f64 {
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
fn transmittance(path_length: f64, s: &ReferenceSettings) -> DVec3 {
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
fn scattered_color(water_tint: DVec3, sky_light: f64, sky_color: DVec3) -> DVec3 {
    let daylight = 0.25 + 0.75 * (luminance(sky_color) * 1.5).clamp(0.0, 1.0);
    water_tint * 0.35 * (0.15 + 0.85 * sky_light) * daylight
}

/// `skyRadiance`.
fn sky_radiance(dir: DVec3, sky_color: DVec3, fog_color: DVec3) -> DVec3 {
    mix3(fog_color, sky_color, smoothstep(-0.05, 0.35, dir.y))
}

/// `specularLight`.
fn specular_light(reflected: DVec3, light_dir: DVec3, glint: f64, sky_color: DVec3, sky_light: f64) -> DVec3 {
    let visibility = smoothstep(-0.05, 0.15, light_dir.y) * sky_light * glint;
    let sun = reflected.dot(light_dir).max(0.0).powf(256.0) * 8.0;
    let sky = reflected.y.max(0.0).powf(4.0) * 0.15;
    DVec3::new(1.0, 0.95, 0.85) * sun * visibility + sky_color * sky * sky_light
}

// ---- lib/reflections.glsl -------------------------------------------------------------------

fn off_screen(screen: DVec3) -> bool {
    screen.z < 0.0 || screen.x < 0.0 || screen.y < 0.0 || screen.x > 1.0 || screen.y > 1.0
}

/// `traceReflection`: the reflected scene colour (rgb) and its weight (a; 0 on a miss).
fn trace_reflection(f: &Frame, start: DVec3, dir: DVec3, cos_to_normal: f64) -> DVec4 {
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

// ---- lib/caustics.glsl ----------------------------------------------------------------------

/// `causticsFromHeight` (A6).
fn caustics_from_height(water: &Texture, world_xz: DVec2, time: f64, samples: u32) -> f64 {
    let mut sum = 0.0;
    let mut scale = 1.0;
    for _ in 0..samples {
        let uv = 0.5 + scale * DVec2::new(world_xz.x, -world_xz.y) / WAVE_TILE;
        let a = water.sample(fract2(uv + time * WAVE_DRIFT)).x;
        let b = water.sample(fract2(uv * 1.5 - time * DVec2::new(WAVE_DRIFT.y, WAVE_DRIFT.x))).x;
        let c = (1.0 - (a + b - 1.0).abs()).clamp(0.0, 1.0);
        let c3 = c * c * c;
        sum += c3 * c3 * c3;
        scale *= 2.0;
    }
    sum / samples as f64
}

/// `causticsFromNoise` (D).
fn caustics_from_noise(noise: &Texture, world_xz: DVec2, time: f64, samples: u32) -> f64 {
    let mut sum = 0.0;
    let mut scale = 1.0;
    for _ in 0..samples {
        let uv = scale * world_xz / WAVE_TILE;
        let a = noise.sample(fract2(uv + time * WAVE_DRIFT)).x;
        let b = noise.sample(fract2(uv - time * WAVE_DRIFT)).x;
        sum += (a * 2.0 - 1.0) + (b * 2.0 - 1.0);
        scale *= 2.0;
    }
    sum / samples as f64
}

// ---- composite.fsh --------------------------------------------------------------------------

/// One frame's inputs with the settings, shared by the per-pixel functions.
struct Frame<'a> {
    i: &'a Inputs,
    u: &'a Uniforms,
    s: &'a ReferenceSettings,
}

impl Frame<'_> {
    fn colortex0(&self, uv: DVec2) -> DVec4 {
        self.i.colortex0.sample(uv)
    }

    fn depth1(&self, uv: DVec2) -> f64 {
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

    #[test]
    fn the_surface_bisection_converges_to_the_wave_height() {
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
    }
}
