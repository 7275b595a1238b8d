//! The truth against closed forms (a flat surface from above, Snell's window from below) and
//! on every built-in scene.

use std::path::Path;

use glam::{DVec2, DVec3};
use tidepack_reference::ReferenceSettings;
use tidepack_reference::model::optics::{scattered_color, sky_radiance};
use tidepack_scene::Scene;
use tidepack_truth::fresnel::WATER_IOR;
use tidepack_truth::geometry::Hit;
use tidepack_truth::trace::{AMBIENT_LIGHT, Ray, Record, SUN_LIGHT};
use tidepack_truth::{Truth, TruthOptions, render};

/// A scene of flat-topped water over a flat floor, from the given camera.
fn flat_scene(camera: &str) -> Scene {
    let text = format!(
        r#"
resolution = [64, 48]
[camera]
{camera}
fov = 70.0
far = 96.0
[time]
world_time = 6000
frame_time_counter = 12.5
[sky]
sun_direction = [0.3, 0.9, -0.2]
sky_color = [0.47, 0.65, 1.0]
fog_color = [0.72, 0.82, 0.98]
[water]
level = 62.875
min = [-100.0, -100.0]
max = [100.0, 100.0]
bottom = 40.0
[[terrain.ground]]
min = [-100.0, -100.0]
max = [100.0, 100.0]
height = 54.0
color = [0.62, 0.56, 0.42]
"#
    );
    Scene::parse(&text, Path::new("flat.toml")).unwrap()
}

/// Unpolarised Fresnel reflectance from the textbook amplitudes, light from index n1 to n2.
fn fresnel(cos_i: f64, n1: f64, n2: f64) -> f64 {
    let sin_t = n1 / n2 * (1.0 - cos_i * cos_i).sqrt();
    if sin_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin_t * sin_t).sqrt();
    let rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    let rp = (n1 * cos_t - n2 * cos_i) / (n1 * cos_t + n2 * cos_i);
    0.5 * (rs * rs + rp * rp)
}

#[test]
fn a_flat_surface_is_the_fresnel_weighted_sum_of_the_reflected_sky_and_the_absorbed_floor() {
    let scene = flat_scene("position = [0.0, 70.0, 0.0]\nyaw = 180.0\npitch = 45.0");
    let settings = ReferenceSettings::converged();
    let truth = Truth::new(&scene, &settings, &TruthOptions { waves: false, ..TruthOptions::default() }).unwrap();
    let (level, floor) = (62.875 - 70.0, 54.0 - 70.0);
    let sky = DVec3::from(scene.sky.sky_color);
    let tint = DVec3::from(scene.water.as_ref().unwrap().tint);
    let absorption = |length: f64| (-DVec3::new(0.40, 0.057, 0.009) * length).exp();
    let sun = scene.sun_direction();
    let mut checked = 0;
    for y in (0..48).step_by(7) {
        for x in (0..64).step_by(9) {
            let d = truth.camera.direction(truth.camera.sample(x, y, 0, 0, 1));
            // Camera above: the flat surface at t, reflection about +y, Snell's refraction.
            let t = level / d.y;
            let cos_i = -d.y;
            let r = fresnel(cos_i, 1.0, WATER_IOR);
            let reflected = DVec3::new(d.x, -d.y, d.z);
            let horizontal = DVec2::new(d.x, d.z);
            let sin_t = horizontal.length() / WATER_IOR;
            let cos_t = (1.0 - sin_t * sin_t).sqrt();
            let refracted = DVec3::new(horizontal.x / WATER_IOR, -cos_t, horizontal.y / WATER_IOR);
            let in_water = (level - floor) / cos_t;
            let landing = d * t + refracted * in_water;
            // The floor's colour as the mesh gives it, dry, and under water: the sky's share
            // through the surface and the depth, the sun's refracted beam, absorbed.
            let Some(Hit::Opaque { colour, .. }) = truth.tracer.geometry.hit(landing + DVec3::Y, DVec3::NEG_Y, 0.0, 2.0) else { panic!("no floor") };
            let albedo = colour / (AMBIENT_LIGHT + SUN_LIGHT * sun.y);
            let sun_cos_t = (1.0 - (1.0 - sun.y * sun.y) / (WATER_IOR * WATER_IOR)).sqrt();
            let beam = (1.0 - fresnel(sun.y, 1.0, WATER_IOR)) * sun.y * absorption((level - floor) / sun_cos_t);
            let wet = albedo * (AMBIENT_LIGHT * truth.tracer.medium.sky_light_integral(level - floor) + SUN_LIGHT * beam);
            let scattered = scattered_color(tint, 1.0, sky);
            let seen_in_water = absorption(in_water) * wet + (DVec3::ONE - absorption(in_water)) * scattered;
            let expected = r * truth.tracer.sky.radiance(reflected) + (1.0 - r) / (WATER_IOR * WATER_IOR) * seen_in_water;
            let (colour, record) = truth.trace(d);
            assert!(record.touched_water);
            assert!((colour - expected).abs().max_element() < 1e-9, "pixel ({x}, {y}): {colour} vs the closed form {expected}");
            checked += 1;
        }
    }
    assert_eq!(checked, 8 * 7);
}

#[test]
fn under_water_snells_window_has_the_critical_angle_for_radius_and_beyond_it_reflection_is_total() {
    let scene = flat_scene("position = [0.0, 58.0, 0.0]\nyaw = 180.0\npitch = -90.0");
    assert!(scene.eye_in_water());
    let truth = Truth::new(&scene, &ReferenceSettings::converged(), &TruthOptions { waves: false, ..TruthOptions::default() }).unwrap();
    let critical = (1.0 / 1.333f64).asin();
    let up_at = |theta: f64| DVec3::new(theta.sin(), theta.cos(), 0.0);
    // Where the light from the sky stops: by bisection on the angle from the zenith.
    let (mut inside, mut outside) = (0.0, 1.5);
    for _ in 0..60 {
        let mid = 0.5 * (inside + outside);
        if truth.trace(up_at(mid)).1.left_water { inside = mid } else { outside = mid }
    }
    // Rays whose transmitted share falls below the tracer's pruning of 1e-4 are not followed:
    // T grows as the square root of the distance to the critical angle, so that is within 1e-7.
    assert!(outside <= critical + 1e-12 && critical - outside < 1e-7, "window radius {outside} vs asin(1/1.333) = {critical}");
    // Beyond the critical angle the surface is a perfect mirror: the colour is the reflected
    // ray's, absorbed over the way up.
    for k in 1..=20 {
        let theta = critical + k as f64 * (1.2 - critical) / 20.0;
        let d = up_at(theta);
        let (colour, record) = truth.trace(d);
        assert!(record.touched_water && !record.left_water, "at {theta} some light left the water");
        let t = (62.875 - 58.0) / d.y;
        let mirrored = Ray { origin: d * t, dir: DVec3::new(d.x, -d.y, d.z), in_water: true, straight: false, path: t, weight: 1.0, depth: 1 };
        let expected = truth.tracer.medium.through(truth.tracer.radiance(mirrored, &mut Record::default()), t);
        assert!((colour - expected).abs().max_element() < 1e-12, "at {theta}: {colour} vs {expected}");
    }
    // Inside the window the sky is seen, brighter by n² (radiance into the denser medium).
    let (zenith, _) = truth.trace(DVec3::Y);
    let r0 = ((WATER_IOR - 1.0) / (WATER_IOR + 1.0)).powi(2);
    let sky = sky_radiance(DVec3::Y, DVec3::from(scene.sky.sky_color), DVec3::from(scene.sky.fog_color));
    let medium = &truth.tracer.medium;
    let lower = medium.through(sky * (1.0 - r0) * WATER_IOR * WATER_IOR, 62.875 - 58.0);
    assert!((zenith - lower).min_element() > 0.0 && (zenith - lower).max_element() < 0.01, "{zenith} vs {lower} + a little floor");
    // Image-wise: every pixel of a wide view is in the window exactly when its ray is within
    // the critical angle of the zenith (a margin of 1e-6 rad for the pruning).
    let mut wide = scene.clone();
    wide.camera.fov = 130.0;
    let wide = Truth::new(&wide, &ReferenceSettings::converged(), &TruthOptions { waves: false, ..TruthOptions::default() }).unwrap();
    let (mut window, mut mirror) = (0, 0);
    for y in 0..48 {
        for x in 0..64 {
            let d = wide.camera.direction(wide.camera.sample(x, y, 0, 0, 1));
            let angle = d.y.acos();
            if (angle - critical).abs() < 1e-6 {
                continue;
            }
            let left = wide.trace(d).1.left_water;
            assert_eq!(left, angle < critical, "pixel ({x}, {y}) at {angle} rad from the zenith");
            if left { window += 1 } else { mirror += 1 }
        }
    }
    assert!(window > 300 && mirror > 300, "{window} in the window, {mirror} beyond");
}

#[test]
fn every_built_in_scene_renders_finite_values_with_its_water_masked() {
    let settings = ReferenceSettings::converged();
    for name in tidepack_scene::scene::built_in_names() {
        let scene = Scene::load(Path::new(name)).unwrap();
        let image = render(&scene, &settings, &TruthOptions { stride: 8, ..TruthOptions::default() }).unwrap();
        let traced: Vec<usize> = (0..image.pixels.len()).filter(|&i| image.evaluated[i]).collect();
        assert_eq!(traced.len(), scene.width().div_ceil(8) as usize * scene.height().div_ceil(8) as usize, "{name}");
        for &i in &traced {
            let c = image.pixels[i];
            assert!(c.is_finite() && c.min_element() >= 0.0, "{name}: pixel {i} is {c}");
        }
        let water = traced.iter().filter(|&&i| image.water[i]).count();
        assert_eq!(water == 0, scene.water.is_none(), "{name}: {water} of {} traced pixels see water", traced.len());
        let overlays = traced.iter().filter(|&&i| image.overlay[i]).count();
        assert_eq!(overlays > 0, !scene.overlay.is_empty(), "{name}: {overlays} pixels under overlays");
    }
}

#[test]
fn dry_pixels_are_the_meshs_colours_fogged_as_vanilla_fogs_them() {
    // Looking along the shore from above, nothing touching water: the truth is the gbuffers
    // colour (white sprite, full sky light: the vertex colour) mixed towards the fog colour.
    let scene = Scene::load(Path::new("no_water")).unwrap();
    let truth = Truth::new(&scene, &ReferenceSettings::converged(), &TruthOptions::default()).unwrap();
    let far = scene.camera.far;
    let fog = DVec3::from(scene.sky.fog_color);
    let mut checked = 0;
    for (x, y) in [(320, 60), (100, 40), (600, 20), (320, 5)] {
        let d = truth.camera.direction(truth.camera.sample(x, y, 0, 0, 1));
        let (colour, record) = truth.trace(d);
        assert!(!record.touched_water);
        let Some(Hit::Opaque { vertex, view_distance, t, .. }) = truth.tracer.geometry.hit(DVec3::ZERO, d, 0.0, f64::INFINITY) else { continue };
        let f = ((view_distance - 0.75 * far) / (0.25 * far)).clamp(0.0, 1.0);
        assert!((view_distance - t).abs() < 0.05, "the interpolated distance {view_distance} is near the true {t}");
        assert!((colour - (vertex + (fog - vertex) * f)).abs().max_element() < 1e-12, "pixel ({x}, {y})");
        checked += 1;
    }
    assert!(checked >= 3, "{checked} pixels on terrain");
}
