//! The pack as each imitated loader draws it (crates/loader/src/loader.rs, docs/loaders.md):
//! water shaded where it lies, nothing else changed, in both dialects. Each loader differs in
//! how it reads shaders.properties (per-buffer blend modes), the alpha test it puts on the
//! translucent layer, and where it draws what the pack has no program for.

use tidepack_harness::program::{self, PackSelection};
use tidepack_harness::{Frame, LoadedPack, Loader, gl, images, render_wgpu};
use tidepack_pack::Dialect;

mod common;
use common::{gpu, root, scene};

fn pack(loader: Loader, dialect: Dialect) -> LoadedPack {
    let selection = PackSelection { source_dir: root().join("shaderpack"), dialect, profile: None, options: vec![] };
    program::load_for(&selection, None, loader).unwrap_or_else(|e| panic!("{loader}: {e}"))
}

fn same(a: [f32; 4], b: [f32; 4]) -> bool {
    (0..3).all(|c| images::to_unorm8(a[c]) == images::to_unorm8(b[c]))
}

/// Every loader in both dialects: `check(loader, dialect, frame of each scene)`.
fn for_every_loader(scenes: &[&str], check: impl Fn(Loader, Dialect, &[(String, Frame)]) -> Result<(), String>) {
    let mut failures = Vec::new();
    for loader in Loader::ALL {
        for dialect in [Dialect::Glsl120, Dialect::Glsl330] {
            let pack = pack(loader, dialect);
            let frames: Vec<(String, Frame)> = scenes
                .iter()
                .map(|&name| (name.to_string(), render_wgpu(gpu(), &pack, &scene(name)).unwrap_or_else(|e| panic!("{loader} {name}: {e}"))))
                .collect();
            if let Err(why) = check(loader, dialect, &frames) {
                failures.push(format!("{loader} ({dialect:?}): {why}"));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Water seen from above is shaded with every loader: the blend the pack relies on is one every
/// loader reads (not per buffer), and no loader's alpha test discards the water.
#[test]
fn water_is_shaded_with_every_loader() {
    for_every_loader(&["case4_above_near", "no_water"], |_, _, frames| {
        let (_, near) = &frames[0];
        let input = &near.buffers[&0];
        let n = input.pixels.len();
        let changed = (0..n).filter(|&i| !same(near.image.pixels[i], input.pixels[i])).count();
        if changed * 10 < n * 3 {
            return Err(format!("case4_above_near: only {changed} of {n} pixels shaded; the water is not drawn"));
        }
        let (_, dry) = &frames[1];
        let changed = (0..dry.image.pixels.len()).filter(|&i| !same(dry.image.pixels[i], dry.buffers[&0].pixels[i])).count();
        if changed > 0 {
            return Err(format!("no_water: {changed} pixels changed"));
        }
        Ok(())
    });
}

/// Land and glass with no water behind stay as drawn, and only the water is shaded, with every
/// loader: what a loader draws for the pack's missing programs must not reach the water's data.
/// Where water lies comes from the frame the default loader draws.
#[test]
fn only_water_is_shaded_with_every_loader() {
    let scenes = ["case1_above_dry", "glass", "glass_over_land"];
    let default_pack = pack(Loader::default(), Dialect::Glsl330);
    let water: Vec<Vec<bool>> = scenes
        .iter()
        .map(|&name| {
            let frame = render_wgpu(gpu(), &default_pack, &scene(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
            frame.buffers[&4].pixels.iter().map(|p| p[0] > 0.04).collect()
        })
        .collect();
    for_every_loader(&scenes, |_, _, frames| {
        for ((name, frame), water) in frames.iter().zip(&water) {
            let input = &frame.buffers[&0];
            let changed = (0..input.pixels.len()).filter(|&i| !water[i] && !same(frame.image.pixels[i], input.pixels[i])).count();
            if changed > 0 {
                return Err(format!("{name}: {changed} pixels with no water in front or behind glass changed"));
            }
        }
        Ok(())
    });
}

/// Rain, clouds and the translucent hand over water, with every loader: where they cover the water, the picture is
/// the water as shaded without them, with them blended on top (`base · (1 − coverage) + colour
/// · coverage`, the premultiplied colour and coverage being what they left in colortex3): within
/// 2/255 but at the edges of what covers the water, where the refraction's filtered sample
/// straddles it (at most 1% of the pixels, within 16/255). Composite takes them out of
/// colortex0 wherever it samples the scene behind the water, and uses the water's own distance
/// where they wrote their depth over it.
#[test]
fn rain_clouds_and_the_hand_stay_over_the_shaded_water() {
    let scenes = ["rain_over_lake", "clouds_over_far_water", "hand_glass_over_water"];
    for_every_loader(&scenes, |loader, dialect, frames| {
        let pack = pack(loader, dialect);
        for (name, frame) in frames {
            let mut bare = scene(name);
            bare.overlay.clear();
            let base = render_wgpu(gpu(), &pack, &bare).map_err(|e| e.to_string())?;
            let over = &frame.buffers[&3];
            let covered: Vec<usize> = (0..over.pixels.len())
                .filter(|&i| over.pixels[i][3] > 0.0 && base.buffers[&4].pixels[i][0] > 0.875)
                .collect();
            if covered.len() < 200 {
                return Err(format!("{name}: only {} pixels of water covered", covered.len()));
            }
            let visible = covered.iter().filter(|&&i| !same(frame.image.pixels[i], base.image.pixels[i])).count();
            if visible * 10 < covered.len() * 9 {
                return Err(format!("{name}: only {visible} of {} covered water pixels show what covers them", covered.len()));
            }
            let mut off = 0;
            let mut worst = 0.0f32;
            for &i in &covered {
                let (o, b, out) = (over.pixels[i], base.image.pixels[i], frame.image.pixels[i]);
                let d = (0..3).map(|c| (out[c] - (b[c] * (1.0 - o[3]) + o[c])).abs()).fold(0.0f32, f32::max);
                worst = worst.max(d);
                if d > 2.0 / 255.0 {
                    off += 1;
                }
            }
            if off * 100 > covered.len() || worst > 16.0 / 255.0 {
                return Err(format!(
                    "{name}: {off} of {} covered water pixels are not the shaded water with the overlay on top (worst {:.1}/255)",
                    covered.len(),
                    worst * 255.0
                ));
            }
        }
        Ok(())
    });
}

/// An opaque particle in front of the water shows as drawn (its colour, fully), with every
/// loader.
#[test]
fn an_opaque_particle_over_water_shows_as_drawn() {
    for_every_loader(&["particle_over_water"], |_, _, frames| {
        let (_, frame) = &frames[0];
        let color = scene("particle_over_water").overlay[0].color;
        let particle: Vec<usize> = (0..frame.image.pixels.len())
            .filter(|&i| (0..3).all(|c| (frame.buffers[&0].pixels[i][c] - color[c] as f32).abs() < 0.5 / 255.0))
            .collect();
        if particle.len() < 100 {
            return Err(format!("the particle covers only {} pixels of colortex0", particle.len()));
        }
        let changed = particle.iter().filter(|&&i| !same(frame.image.pixels[i], frame.buffers[&0].pixels[i])).count();
        if changed > 0 {
            return Err(format!("{changed} of {} particle pixels were shaded as water", particle.len()));
        }
        Ok(())
    });
}

/// Mesa's OpenGL draws what wgpu draws for every loader, within 1/255: the scenes where loaders
/// differ (a missing program's drawing, alpha test, blend keys, rain drawn before or after the
/// water), in both dialects.
#[test]
fn opengl_and_wgpu_agree_for_every_loader() {
    let ctx = gl::context().unwrap_or_else(|e| panic!("{e}"));
    for_every_loader(&["glass_over_land", "rain_over_lake"], |loader, dialect, frames| {
        let pack = pack(loader, dialect);
        for (name, frame) in frames {
            let s = scene(name);
            let gl_frame = tidepack_harness::render_gl(&ctx, &pack, &s).map_err(|e| format!("{name}: {e}"))?;
            let over = images::count_differing(&frame.image, &gl_frame.image, images::OVER_1_255);
            if over > 0 {
                let max = images::max_channel_difference(&frame.image, &gl_frame.image);
                return Err(format!("{name}: {over} pixels differ by more than 1/255 (max {max:?})"));
            }
        }
        Ok(())
    });
}
