//! Rendering tests. They need lavapipe (Debian mesa-vulkan-drivers) and Mesa's EGL/OpenGL
//! (libegl1 libegl-mesa0 libgl1-mesa-dri); tools/test installs them. Without them every test
//! here fails with an error naming the missing package: they never skip.
//!
//! The five-case scenes assert properties of the water model, not colours of the current
//! shaders; only the golden images pin colours, one test per scene (regenerate with
//! TIDEPACK_BLESS=1).

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::OnceLock;

use tidepack_harness::images::{self, FloatImage};
use tidepack_harness::{Frame, LoadedPack, PackSelection, Scene, gl, program, render_wgpu};
use tidepack_pack::Dialect;

mod common;
use common::{gpu, root, scene};

fn scene_names() -> Vec<String> {
    let files = tidepack_harness::scene::scene_files(&root().join("tests/scenes")).unwrap_or_else(|e| panic!("{e}"));
    files.iter().filter_map(|p| Some(p.file_stem()?.to_string_lossy().into_owned())).collect()
}

fn pack(dialect: Dialect) -> &'static LoadedPack {
    static P120: OnceLock<LoadedPack> = OnceLock::new();
    static P330: OnceLock<LoadedPack> = OnceLock::new();
    let cell = if dialect == Dialect::Glsl120 { &P120 } else { &P330 };
    cell.get_or_init(|| {
        program::load(&PackSelection { source_dir: root().join("shaderpack"), dialect, profile: None, options: vec![] })
            .unwrap_or_else(|e| panic!("{e}"))
    })
}

/// The pack under Iris with Distant Horizons beside it.
fn pack_with_distant_horizons(dialect: Dialect) -> &'static LoadedPack {
    static P120: OnceLock<LoadedPack> = OnceLock::new();
    static P330: OnceLock<LoadedPack> = OnceLock::new();
    let cell = if dialect == Dialect::Glsl120 { &P120 } else { &P330 };
    cell.get_or_init(|| {
        let selection = PackSelection { source_dir: root().join("shaderpack"), dialect, profile: None, options: vec![] };
        program::load_with_distant_horizons(&selection, None).unwrap_or_else(|e| panic!("{e}"))
    })
}

/// The pack as the scene is drawn: a scene with Distant Horizons' LODs under Iris with the mod,
/// every other under the default loader.
fn pack_for(dialect: Dialect, scene: &Scene) -> &'static LoadedPack {
    if scene.distant_horizons.is_some() { pack_with_distant_horizons(dialect) } else { pack(dialect) }
}

/// Every scene rendered once (GLSL 330, default profile), shared by the tests.
fn frames() -> &'static BTreeMap<String, Frame> {
    static FRAMES: OnceLock<BTreeMap<String, Frame>> = OnceLock::new();
    FRAMES.get_or_init(|| {
        scene_names()
            .into_iter()
            .map(|name| {
                let s = scene(&name);
                let frame = render_wgpu(gpu(), pack_for(Dialect::Glsl330, &s), &s).unwrap_or_else(|e| panic!("{name}: {e}"));
                (name, frame)
            })
            .collect()
    })
}

/// The water mark gbuffers_water leaves in colortex4.r: 1 where water is the nearest
/// translucent, scaled by 3/4 for each glass face in front of it, 0 where no water drew.
fn mark(frame: &Frame, i: usize) -> f32 {
    frame.buffers.get(&4).expect("gbuffers_water writes colortex4").pixels[i][0]
}

/// Nothing translucent drew at this pixel: gbuffers_water's blend leaves colortex0's alpha at
/// 1 only there.
fn dry(frame: &Frame, i: usize) -> bool {
    frame.buffers[&0].pixels[i][3] == 1.0
}

/// Equal in the 8-bit image OptiFine's RGBA8 colortex0 holds (the float output of a
/// pass-through can differ from its RGBA8 input in the last bit through filtering).
fn same(a: [f32; 4], b: [f32; 4]) -> bool {
    (0..3).all(|c| images::to_unorm8(a[c]) == images::to_unorm8(b[c]))
}

fn failure_dir() -> PathBuf {
    root().join("target/harness-failures")
}

#[test]
fn the_scenes_cover_the_issue() {
    let names = scene_names();
    for required in [
        "case1_above_dry",
        "case2_under_down",
        "case3_under_up",
        "case4_above_near",
        "case5_above_far",
        "no_water",
        "glass",
        "far_from_origin",
    ] {
        assert!(names.iter().any(|n| n == required), "tests/scenes/{required}.toml is missing");
    }
    assert!(scene("case2_under_down").eye_in_water() && scene("case3_under_up").eye_in_water());
    assert!(!scene("case4_above_near").eye_in_water() && !scene("case5_above_far").eye_in_water());
    assert!(scene("far_from_origin").camera_position().x > 1e6);
}

/// Distant Horizons' water meets the game's without a seam: up each column of the screen's
/// middle, the colour steps no more from the game's last water pixel to the LODs' first than
/// between neighbouring rows of water on either side; and under a loader without the mod the
/// same scene has no LOD water at all.
#[test]
fn lod_water_meets_the_games_water_without_a_seam() {
    let name = "lod_water_beyond_chunks";
    let frame = &frames()[name];
    let (w, h) = (frame.image.width as usize, frame.image.height as usize);
    let luminance = |i: usize| {
        let p = frame.image.pixels[i];
        0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]
    };
    // The game's water holds depthtex0; the LODs' leaves it empty (they have their own).
    let water = |f: &Frame, i: usize| mark(f, i) > 0.875;
    let game = |i: usize| water(frame, i) && frame.depth0.pixels[i][0] < 1.0;
    let lod = |i: usize| water(frame, i) && frame.depth0.pixels[i][0] >= 1.0;
    let (mut at_boundary, mut beside) = (Vec::new(), Vec::new());
    for x in w / 4..3 * w / 4 {
        // Rows run bottom first: the game's water lies below the LODs' on screen.
        let Some(b) = (1..h).find(|&y| game((y - 1) * w + x) && lod(y * w + x)) else { continue };
        at_boundary.push((luminance(b * w + x) - luminance((b - 1) * w + x)).abs());
        for y in (b.saturating_sub(10)..b - 1).chain(b + 1..(b + 10).min(h - 1)) {
            if water(frame, y * w + x) && water(frame, (y + 1) * w + x) {
                beside.push((luminance((y + 1) * w + x) - luminance(y * w + x)).abs());
            }
        }
    }
    assert!(at_boundary.len() == w / 2, "the boundary crosses every middle column: {} of {}", at_boundary.len(), w / 2);
    let mean = |v: &[f32]| v.iter().sum::<f32>() / v.len() as f32;
    let (step, neighbours) = (mean(&at_boundary), mean(&beside));
    println!("{name}: mean step at the LOD boundary {step:.5}, between neighbouring rows beside it {neighbours:.5}");
    assert!(step <= 1.5 * neighbours, "a seam: the colour steps {step:.5} at the boundary against {neighbours:.5} beside it");
    let lods = (0..w * h).filter(|&i| lod(i)).count();
    assert!(lods > w * h / 20, "the LODs' water covers the far band: {lods} pixels");

    let s = scene(name);
    let without = render_wgpu(gpu(), pack(Dialect::Glsl330), &s).unwrap_or_else(|e| panic!("{name}: {e}"));
    let lod_without = (0..w * h).filter(|&i| water(&without, i) && without.depth0.pixels[i][0] >= 1.0).count();
    assert_eq!(lod_without, 0, "a loader without Distant Horizons draws no LODs");
}

#[test]
fn every_scene_renders_finite() {
    for (name, frame) in frames() {
        let bad = frame.image.non_finite();
        assert_eq!(bad, 0, "{name}: {bad} pixels of the RGBA32F composite output are NaN or Inf");
        assert!(frame.passes.iter().any(|p| p.pass == "composite"), "{name}: no composite pass");
    }
}

#[test]
fn no_water_scene_equals_its_input_exactly() {
    let frame = &frames()["no_water"];
    let input = &frame.buffers[&0];
    let differing = frame.image.pixels.iter().zip(&input.pixels).filter(|(a, b)| !same(**a, **b)).count();
    assert_eq!(differing, 0, "composite changed {differing} pixels of a scene without water");
    let max = images::max_channel_difference(&frame.image, input);
    assert!(max.iter().all(|d| *d < 1e-6), "the float output strays from the input by {max:?}");
    assert!(frame.buffers[&4].pixels.iter().all(|p| p[0] == 0.0), "no water, no glass: colortex4 stays clear");
    assert!((0..input.pixels.len()).all(|i| dry(frame, i)), "no water, no glass: colortex0's alpha stays 1");
}

#[test]
fn case1_pixels_not_behind_water_pass_through() {
    let frame = &frames()["case1_above_dry"];
    let input = &frame.buffers[&0];
    let dry: Vec<usize> = (0..input.pixels.len()).filter(|&i| dry(frame, i)).collect();
    assert!(dry.len() > input.pixels.len() / 2, "case 1 should show mostly dry land, got {} dry pixels", dry.len());
    let changed = dry.iter().filter(|&&i| !same(frame.image.pixels[i], input.pixels[i])).count();
    assert_eq!(changed, 0, "{changed} pixels with nothing translucent in front changed");
}

#[test]
fn under_water_every_opaque_pixel_is_shaded() {
    for name in ["case2_under_down", "case3_under_up"] {
        let frame = &frames()[name];
        let input = &frame.buffers[&0];
        let n = input.pixels.len();
        let changed = (0..n).filter(|&i| !same(frame.image.pixels[i], input.pixels[i])).count();
        assert!(changed * 100 >= n * 95, "{name}: with the camera under water only {changed} of {n} pixels changed");
    }
    // Looking up, the surface is seen from below.
    let up = &frames()["case3_under_up"];
    let surface = (0..up.image.pixels.len()).filter(|&i| mark(up, i) > 0.875).count();
    assert!(surface > 1000, "case 3 should see the water surface from below, got {surface} pixels");
}

#[test]
fn water_seen_from_above_is_shaded_near_and_far() {
    for name in ["case4_above_near", "case5_above_far", "far_from_origin"] {
        let frame = &frames()[name];
        let input = &frame.buffers[&0];
        let water: Vec<usize> = (0..input.pixels.len()).filter(|&i| mark(frame, i) > 0.875).collect();
        assert!(water.len() * 10 > input.pixels.len() * 3, "{name}: only {} water pixels", water.len());
        let changed = water.iter().filter(|&&i| !same(frame.image.pixels[i], input.pixels[i])).count();
        assert!(changed * 10 >= water.len() * 9, "{name}: only {changed} of {} water pixels got water shading", water.len());
        let dry: Vec<usize> = (0..input.pixels.len()).filter(|&i| dry(frame, i)).collect();
        let dry_changed = dry.iter().filter(|&&i| !same(frame.image.pixels[i], input.pixels[i])).count();
        assert_eq!(dry_changed, 0, "{name}: {dry_changed} pixels with no water in front changed");
    }
    // Case 5 reaches far water: some water pixels lie beyond 200 blocks.
    let far = &frames()["case5_above_far"];
    let s = scene("case5_above_far");
    let inverse = s.projection().inverse();
    let (w, h) = (s.width(), s.height());
    let distant = (0..far.image.pixels.len())
        .filter(|&i| mark(far, i) > 0.875)
        .filter(|&i| {
            let (x, y) = ((i as u32 % w) as f64 + 0.5, (i as u32 / w) as f64 + 0.5);
            let d = far.depth0.pixels[i][0] as f64;
            let ndc = glam::DVec4::new(x / w as f64 * 2.0 - 1.0, y / h as f64 * 2.0 - 1.0, d * 2.0 - 1.0, 1.0);
            let v = inverse * ndc;
            (v.truncate() / v.w).length() > 200.0
        })
        .count();
    assert!(distant > 500, "case 5 should show water beyond 200 blocks, got {distant} pixels");
}

#[test]
fn far_from_origin_looks_like_the_same_view_at_the_origin() {
    let near = frames()["case4_above_near"].image.to_rgba8_top_first();
    let far = frames()["far_from_origin"].image.to_rgba8_top_first();
    let psnr = images::psnr_rgb8(&near, &far);
    assert!(psnr > 30.0, "a million blocks out, the view differs from the origin's: PSNR {psnr:.1} dB");
}

/// A translucent other than water (glass, ice) is the nearest at this pixel.
fn is_glass(frame: &Frame, i: usize) -> bool {
    !dry(frame, i) && mark(frame, i) <= 0.875
}

/// The glass scene rendered without its panes: where its water mark says water, a glass pixel
/// of the real scene has water behind it.
fn glass_scene_without_glass() -> &'static Frame {
    static FRAME: OnceLock<Frame> = OnceLock::new();
    FRAME.get_or_init(|| {
        let mut s = scene("glass");
        s.glass.clear();
        render_wgpu(gpu(), pack(Dialect::Glsl330), &s).unwrap_or_else(|e| panic!("{e}"))
    })
}

/// Glass over land or sky gets no water effects: the water mark is 0 there (cleared, and only
/// scaled by glass), and composite passes the pixel through exactly. Checked both in the scene with water
/// (panes seen against the sky and the shore) and in the same scene without water.
#[test]
fn glass_pixels_with_no_water_behind_pass_through() {
    let frame = &frames()["glass"];
    let bare = glass_scene_without_glass();
    let input = &frame.buffers[&0];
    let glass: Vec<usize> = (0..input.pixels.len()).filter(|&i| is_glass(frame, i)).collect();
    let dry: Vec<usize> = glass.iter().copied().filter(|&i| mark(bare, i) <= 0.875).collect();
    assert!(dry.len() > 5000, "the glass scene should show panes with no water behind them, got {} pixels", dry.len());
    let marked = dry.iter().filter(|&&i| mark(frame, i) != 0.0).count();
    assert_eq!(marked, 0, "{marked} glass pixels with no water behind them carry a water mark");
    let changed = dry.iter().filter(|&&i| !same(frame.image.pixels[i], input.pixels[i])).count();
    let max = dry
        .iter()
        .map(|&i| (0..3).map(|c| (frame.image.pixels[i][c] - input.pixels[i][c]).abs()).fold(0.0f32, f32::max))
        .fold(0.0f32, f32::max);
    assert_eq!(changed, 0, "{changed} of {} glass pixels with no water behind them changed (max {max})", dry.len());
    assert!(max < 1e-6, "glass pixels with no water behind them stray from the input by {max}");

    // The same scene without water: no glass pixel may change.
    let mut dry_scene = scene("glass");
    dry_scene.water = None;
    let dry_frame = render_wgpu(gpu(), pack(Dialect::Glsl330), &dry_scene).unwrap_or_else(|e| panic!("{e}"));
    let glass: Vec<usize> = (0..dry_frame.image.pixels.len()).filter(|&i| is_glass(&dry_frame, i)).collect();
    assert!(glass.len() > 5000, "the dry glass scene should show the panes, got {} pixels", glass.len());
    let changed = glass.iter().filter(|&&i| !same(dry_frame.image.pixels[i], dry_frame.buffers[&0].pixels[i])).count();
    assert_eq!(changed, 0, "{changed} glass pixels changed in a scene without water");
}

/// Glass with water behind it shows the water's plain colour that water left in colortex6,
/// and nothing of the water surface's shading: the output is exactly composite's plain mix
/// mix(scene, colortex6.rgb, 0.6), with no reflection, highlight or foam on top.
#[test]
fn glass_over_water_shows_the_tint_and_no_surface_effects() {
    let frame = &frames()["glass"];
    let bare = glass_scene_without_glass();
    let input = &frame.buffers[&0];
    let c6 = &frame.buffers[&6];
    let glass: Vec<usize> = (0..input.pixels.len()).filter(|&i| is_glass(frame, i)).collect();
    let wet: Vec<usize> = glass.iter().copied().filter(|&i| mark(bare, i) > 0.875).collect();
    assert!(wet.len() > 2000, "the glass scene should show water through a pane, got {} pixels", wet.len());
    // Water behind the glass was drawn first (back to front), and the glass weakened its mark.
    // Pixels on the edge of a water quad may be covered differently: allow 0.5%.
    let missing = wet.iter().filter(|&&i| !(mark(frame, i) > 0.04 && mark(frame, i) <= 0.875)).count();
    assert!(missing * 200 <= wet.len(), "{missing} of {} glass pixels over water have no water colour in colortex6", wet.len());
    let mut tinted = 0;
    let mut off = Vec::new();
    for &i in &wet {
        let (scene_px, water, out) = (input.pixels[i], c6.pixels[i], frame.image.pixels[i]);
        let k = 0.6;
        let expected: [f32; 3] = [0, 1, 2].map(|c| scene_px[c] + (water[c] - scene_px[c]) * k);
        let d = (0..3).map(|c| (out[c] - expected[c]).abs()).fold(0.0f32, f32::max);
        if d > 1e-4 {
            off.push((i, d));
        }
        if !same(out, scene_px) {
            tinted += 1;
        }
    }
    assert!(
        off.is_empty(),
        "{} of {} glass pixels over water differ from the plain colortex6 mix (water-surface effects leaked), worst {:?}",
        off.len(),
        wet.len(),
        off.iter().map(|(_, d)| *d).fold(0.0f32, f32::max)
    );
    assert!(tinted * 10 >= wet.len() * 9, "only {tinted} of {} glass pixels over water show the water tint", wet.len());
}

#[test]
fn the_same_scene_twice_gives_the_same_bytes() {
    let s = scene("case4_above_near");
    let a = render_wgpu(gpu(), pack(Dialect::Glsl330), &s).unwrap_or_else(|e| panic!("{e}"));
    let b = render_wgpu(gpu(), pack(Dialect::Glsl330), &s).unwrap_or_else(|e| panic!("{e}"));
    let bits = |f: &FloatImage| f.pixels.iter().flat_map(|p| p.map(f32::to_bits)).collect::<Vec<u32>>();
    assert!(bits(&a.image) == bits(&b.image), "two renders of one scene differ");
    assert_eq!(a.image.to_rgba8_top_first(), b.image.to_rgba8_top_first());
}

#[test]
fn a_uniform_the_harness_cannot_fill_is_an_error_naming_it() {
    let mut values = tidepack_harness::uniforms::values(&scene("case4_above_near"), tidepack_harness::uniforms::Pass::Fullscreen);
    values.remove("gbufferProjectionInverse");
    let pack = pack(Dialect::Glsl330);
    let module = pack.composite().fragment.module().unwrap_or_else(|e| panic!("{e}"));
    let err = tidepack_harness::uniforms::fill_block(module, &values, "composite.fsh").err().expect("must fail");
    assert!(err.to_string().contains("gbufferProjectionInverse"), "{err}");
}

/// One golden-image test per scene, each with the largest mean FLIP it accepts against
/// `tests/golden/<scene>.png`. `every_scene_has_a_golden_test` keeps this list equal to
/// `tests/scenes`.
macro_rules! golden_tests {
    ($($scene:ident: $max_mean_flip:expr,)*) => {
        const GOLDEN_SCENES: &[&str] = &[$(stringify!($scene)),*];
        mod golden {
            $(
                #[test]
                fn $scene() {
                    super::golden(stringify!($scene), $max_mean_flip);
                }
            )*
        }
    };
}

// Each scene's budget is the mean FLIP that uniform noise of PSNR 40 dB (the gate of the single
// PSNR test these replace) gives on its golden image, floored to 0.001. A difference of 1/255 in
// every channel of every pixel (a rounding difference) stays under it (0.011 to 0.016 FLIP); a
// shift of 3/255 everywhere (0.073 to 0.084) fails. FLIP weighs a difference by the image around
// it, so the same noise costs each scene a different mean.
golden_tests! {
    case1_above_dry: 0.033,
    case2_under_down: 0.026,
    case3_under_up: 0.027,
    case4_above_near: 0.028,
    case5_above_far: 0.033,
    clouds_over_far_water: 0.032,
    far_from_origin: 0.028,
    glass: 0.032,
    glass_over_land: 0.034,
    hand_glass_over_water: 0.029,
    lod_water_beyond_chunks: 0.030,
    no_water: 0.037,
    particle_over_water: 0.028,
    rain_over_lake: 0.028,
}

#[test]
fn every_scene_has_a_golden_test() {
    let mut listed: Vec<String> = GOLDEN_SCENES.iter().map(|s| s.to_string()).collect();
    let mut scenes = scene_names();
    listed.sort_unstable();
    scenes.sort_unstable();
    assert_eq!(listed, scenes, "golden_tests! in render.rs must name every scene of tests/scenes");
}

/// Compares the scene's render with its golden image by mean FLIP (NVIDIA's perceptual metric,
/// LDR), or rewrites the golden image when blessing. On failure the render, the golden image,
/// an 8× amplified difference and the FLIP error map (magma colours) are written to
/// target/harness-failures/golden/<scene>/, which the message names.
fn golden(name: &str, max_mean_flip: f64) {
    let frame = &frames()[name];
    let (width, height) = (frame.image.width, frame.image.height);
    let actual = opaque(&frame.image.to_rgba8_top_first());
    let path = root().join(format!("tests/golden/{name}.png"));
    if blessing() {
        images::write_rgba8_png(&path, width, height, &actual).unwrap();
        return;
    }
    let (w, h, expected) = images::read_rgba8_png(&path)
        .unwrap_or_else(|e| panic!("{e}; render the golden images with TIDEPACK_BLESS=1 cargo test -p tidepack-harness --test render golden"));
    let dir = failure_dir().join("golden").join(name);
    let write = |file: &str, bytes: &[u8]| images::write_rgba8_png(&dir.join(file), width, height, bytes).unwrap();
    if (w, h) != (width, height) {
        write("actual.png", &actual);
        panic!("{name}: the golden image is {w}x{h}, the render {width}x{height} (render in {}; TIDEPACK_BLESS=1 regenerates it)", dir.display());
    }
    let map = images::flip_map(&images::rgba8_to_rgb8(&actual), &images::rgba8_to_rgb8(&expected), width, height);
    let mean = images::mean_flip(&map);
    println!("{name}: mean FLIP {mean:.6} (at most {max_mean_flip})");
    if mean > max_mean_flip {
        write("actual.png", &actual);
        write("expected.png", &expected);
        write("diff.png", &images::difference_rgb8(&actual, &expected));
        write("flip.png", &images::flip_heatmap_rgba8(&map));
        panic!(
            "{name}: mean FLIP {mean:.5} > {max_mean_flip} against tests/golden/{name}.png (PSNR {:.1} dB); \
             actual, expected, diff and FLIP map in {} (TIDEPACK_BLESS=1 regenerates the golden image)",
            images::psnr_rgb8(&actual, &expected),
            dir.display()
        );
    }
}

/// Whether to rewrite the golden images: `TIDEPACK_BLESS` set to anything but empty or `0`, the
/// rule every test that reads it follows (docs/ARCHITECTURE.md, "Tests").
fn blessing() -> bool {
    std::env::var("TIDEPACK_BLESS").is_ok_and(|v| !v.is_empty() && v != "0")
}

fn opaque(rgba: &[u8]) -> Vec<u8> {
    let mut v = rgba.to_vec();
    v.chunks_exact_mut(4).for_each(|p| p[3] = 255);
    v
}

/// The proof that the lowering changes nothing: the shipped text through Mesa's OpenGL gives
/// the same image as its lowered form through wgpu, for every scene and both dialects, every
/// pixel within 1/255 in every channel. The GL path maps depth as the wgpu path does
/// (`gl::DepthMapping::Harness`), so both depth buffers hold the same bits; with OpenGL's own
/// depth mapping the last bits of depth differ and composite amplifies that at a few pixels
/// (docs/harness.md).
#[test]
fn opengl_and_wgpu_agree_on_every_scene() {
    let ctx = gl::context().unwrap_or_else(|e| panic!("{e}"));
    let mut report = Vec::new();
    let mut failures = Vec::new();
    for dialect in [Dialect::Glsl330, Dialect::Glsl120] {
        for name in scene_names() {
            let s = scene(&name);
            let wgpu_frame = if dialect == Dialect::Glsl330 {
                frames()[&name].clone()
            } else {
                render_wgpu(gpu(), pack_for(dialect, &s), &s).unwrap_or_else(|e| panic!("{name}: {e}"))
            };
            let gl_frame = tidepack_harness::render_gl(&ctx, pack_for(dialect, &s), &s)
                .unwrap_or_else(|e| panic!("{name} ({dialect}): {e}"));
            assert_eq!(gl_frame.image.non_finite(), 0, "{name}: NaN/Inf from OpenGL");
            let max = images::max_channel_difference(&wgpu_frame.image, &gl_frame.image);
            let over = images::count_differing(&wgpu_frame.image, &gl_frame.image, images::OVER_1_255);
            let depth_bits = |a: &FloatImage, b: &FloatImage| a.pixels.iter().zip(&b.pixels).filter(|(p, q)| p[0].to_bits() != q[0].to_bits()).count();
            let (d0, d1) = (depth_bits(&wgpu_frame.depth0, &gl_frame.depth0), depth_bits(&wgpu_frame.depth1, &gl_frame.depth1));
            report.push(format!(
                "{dialect:>24} {name:<18} max diff (x/255) {:?}, {over} pixels over 1/255, depth0/depth1 differ in {d0}/{d1} pixels",
                max.map(|d| (d * 255.0 * 100.0).round() / 100.0)
            ));
            if over > 0 {
                let dir = failure_dir();
                let slug = dialect.slug();
                gl_frame.image.write_png(&dir.join(format!("{name}.{slug}.gl.png")), false).unwrap();
                wgpu_frame.image.write_png(&dir.join(format!("{name}.{slug}.wgpu.png")), false).unwrap();
                let diff = images::difference_rgb8(&gl_frame.image.to_rgba8_top_first(), &wgpu_frame.image.to_rgba8_top_first());
                images::write_rgba8_png(&dir.join(format!("{name}.{slug}.diff.png")), s.width(), s.height(), &diff).unwrap();
                failures.push(format!(
                    "{name} ({dialect}): max {max:?}, {over} pixels over 1/255; depth0/depth1 differ in {d0}/{d1} pixels (images in {})",
                    dir.display()
                ));
            }
        }
    }
    println!("{}", report.join("\n"));
    assert!(failures.is_empty(), "OpenGL and wgpu disagree by more than 1/255:\n{}", failures.join("\n"));
}

/// The highlight on the water follows the light: the moon (the shadow light at night, here
/// where the sun stood by day) glints at a tenth of the sun, and full rain hides the sun's
/// glint, leaving only the sky's broad lobe. Measured as the largest difference SPECULAR makes
/// to a pixel.
#[test]
fn the_glint_follows_the_light() {
    let without = program::load(&PackSelection {
        source_dir: root().join("shaderpack"),
        dialect: Dialect::Glsl330,
        profile: None,
        options: vec![("SPECULAR".into(), "off".into())],
    })
    .unwrap_or_else(|e| panic!("{e}"));
    let peak = |s: &Scene| -> f32 {
        let on = render_wgpu(gpu(), pack(Dialect::Glsl330), s).unwrap_or_else(|e| panic!("{e}"));
        let off = render_wgpu(gpu(), &without, s).unwrap_or_else(|e| panic!("{e}"));
        on.image.pixels.iter().zip(&off.image.pixels).map(|(a, b)| (0..3).map(|c| a[c] - b[c]).fold(0.0f32, f32::max)).fold(0.0, f32::max)
    };
    let day = scene("case4_above_near");
    let mut night = day.clone();
    night.sky.sun_direction = day.sky.sun_direction.map(|v| -v);
    let mut rain = day.clone();
    rain.sky.rain_strength = 1.0;
    let (day_peak, night_peak, rain_peak) = (peak(&day), peak(&night), peak(&rain));
    assert!(day_peak > 0.1, "the sun should glint on the water: peak {day_peak}");
    let moon = night_peak / day_peak;
    assert!((0.07..=0.13).contains(&moon), "the moon glints at {moon:.3} of the sun (peaks {night_peak} and {day_peak})");
    assert!(rain_peak < 0.1 * day_peak, "in full rain the glint peaks at {rain_peak}, the clear sun's at {day_peak}");
}

/// Water meets the game's fog where the terrain does: from three quarters of the render
/// distance `far` it fades into the fog colour, and at `far` and beyond it is the fog colour.
#[test]
fn distant_water_fades_into_the_fog_at_the_render_distance() {
    let frame = &frames()["case5_above_far"];
    let s = scene("case5_above_far");
    let inverse = s.projection().inverse();
    let (w, h) = (s.width(), s.height());
    let far = s.camera.far;
    let fog = s.sky.fog_color;
    let mut beyond = 0;
    for i in 0..frame.image.pixels.len() {
        if frame.buffers[&4].pixels[i][0] <= 0.875 {
            continue;
        }
        let (x, y) = ((i as u32 % w) as f64 + 0.5, (i as u32 / w) as f64 + 0.5);
        let d = frame.depth0.pixels[i][0] as f64;
        let v = inverse * glam::DVec4::new(x / w as f64 * 2.0 - 1.0, y / h as f64 * 2.0 - 1.0, d * 2.0 - 1.0, 1.0);
        if (v.truncate() / v.w).length() >= far * 1.01 {
            beyond += 1;
            let out = frame.image.pixels[i];
            let off = (0..3).map(|c| (out[c] as f64 - fog[c]).abs()).fold(0.0, f64::max);
            assert!(off < 1.0 / 255.0, "water {i} beyond far is {out:?}, not the fog colour {fog:?}");
        }
    }
    assert!(beyond > 500, "case 5 should show water beyond the render distance, got {beyond} pixels");
}

