//! `render --pack`: any pack's pipeline (crates/harness/src/any_pack.rs, gpu/frame.rs,
//! gl_frame.rs) on packs of our own in tests/packs, each a minimal reproduction of what released
//! packs do: a flip chain of deferred and composite programs reading and writing the same
//! buffer, a float buffer with its own clear colour, a program without DRAWBUFFERS, the
//! 1.17+ core profile's vertex attributes and matrices, and a shadow pass read every way packs
//! read it.

use tidepack_harness::any_pack::{AnyPack, FramePlan, PlannedWork, ScreenOutput};
use tidepack_loader::Configuration;
use tidepack_loader::buffers::BufferClear;
use tidepack_harness::gpu::{self as wgpu_frame, Frame};
use tidepack_harness::program::PackResources as _;
use tidepack_loader::buffers::BufferFormat;
use tidepack_harness::{Loader, Scene, gl, gl_frame, images, mesh};

mod common;
use common::{gpu, root, scene};

/// What the report says of a pack without a program for the sun and the moon.
const NO_SUN_PROGRAM: &str = "the sun and the moon: without a program of gbuffers_skytextured's chain the game's own are not drawn";

fn pack(name: &str, loader: Loader) -> AnyPack {
    AnyPack::load(&root().join("tests/packs").join(name), &Configuration { loader, ..Configuration::default() }).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn render(pack: &AnyPack, scene: &Scene) -> Frame {
    wgpu_frame::render(gpu(), pack, scene, &mesh::build(scene, pack), ScreenOutput::AsLoader, 1).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn the_plan_runs_the_programs_in_optifines_order_and_flips_what_full_screen_passes_write() {
    let pack = pack("flip_chain", Loader::default());
    assert!(pack.failed.is_empty(), "{:?}", pack.failed);
    let scene = scene("case4_above_near");
    let mesh = mesh::build(&scene, &pack);
    let plan = FramePlan::new(&pack, &scene, &mesh, ScreenOutput::AsLoader);
    let labels: Vec<&str> = plan.steps.iter().map(|s| s.label.as_str()).collect();
    assert_eq!(
        labels,
        ["sky (the loader's own)", "terrain (gbuffers_terrain)", "depth copy", "deferred", "water (gbuffers_water)", "composite", "composite1", "final"]
    );
    // Which texture of colortex0 each full-screen program reads: composite the one the
    // geometry drew into, composite1 the one composite wrote, final the one composite1 wrote.
    let reads: Vec<(&str, usize)> = plan
        .steps
        .iter()
        .filter_map(|s| match &s.work {
            PlannedWork::Fullscreen { program, current, .. } => Some((program.name.as_str(), current[&0])),
            _ => None,
        })
        .collect();
    assert_eq!(reads, [("deferred", 0), ("composite", 0), ("composite1", 1), ("final", 0)]);
    assert_eq!(pack.clear_of(3), BufferClear::Color([0.0, 0.0, 1.0, 1.0]));
    assert_eq!(pack.format_of(3), BufferFormat::Rgba16F);
}

#[test]
fn each_step_of_the_flip_chain_reads_what_the_one_before_wrote() {
    let pack = pack("flip_chain", Loader::default());
    let frame = render(&pack, &scene("case4_above_near"));
    assert_eq!(frame.not_modelled, [NO_SUN_PROGRAM], "everything else is imitated");
    let written = |pass: &str, texture: &str| {
        let step = frame.passes.iter().find(|p| p.pass == pass).unwrap_or_else(|| panic!("no step {pass}"));
        step.images.iter().find(|(name, _)| name == texture).map(|(_, image)| image.clone()).unwrap_or_else(|| panic!("{pass} wrote no {texture}"))
    };
    let composite = written("composite", "colortex0");
    let composite1 = written("composite1", "colortex0");
    let mut worst = 0f32;
    for (a, b) in composite.pixels.iter().zip(&composite1.pixels) {
        for c in 0..3 {
            // composite1 = sqrt(composite), through an RGBA8 buffer.
            worst = worst.max((a[c].sqrt() - b[c]).abs());
        }
    }
    assert!(worst <= images::OVER_1_255, "composite1 is not sqrt of composite's output: {}", worst * 255.0);
    let d = images::max_channel_difference(&composite1, &frame.image);
    assert!(d.iter().all(|c| *c < 1e-6), "final passes colortex0 through, not {d:?}");
    for pass in &frame.passes {
        assert!(pass.non_finite.values().all(|n| *n == 0), "{}: {:?}", pass.pass, pass.non_finite);
    }
}

/// OpenGL redrawing each step from wgpu's textures: with wgpu's own, every step agrees; with
/// composite's colortex0 replaced, composite1 (which reads it) draws from the replacement.
#[test]
fn opengl_draws_each_step_from_the_reference_frames_textures() {
    let ctx = gl::context().unwrap_or_else(|e| panic!("{e}"));
    let pack = pack("flip_chain", Loader::default());
    let scene = scene("case4_above_near");
    let mesh = mesh::build(&scene, &pack);
    let wgpu = render(&pack, &scene);
    let mut reference: Vec<Vec<(String, images::FloatImage)>> = wgpu.passes.iter().map(|p| p.images.clone()).collect();
    let draw = |r: &[Vec<(String, images::FloatImage)>]| {
        let reference = gl_frame::Reference { steps: r.iter().map(Vec::as_slice).collect(), depth0: &wgpu.depth0, depth1: &wgpu.depth1, depth_written: Vec::new(), nudge: 0.0, trace_derivatives: false };
        gl_frame::render_from(&ctx, &pack, &scene, &mesh, ScreenOutput::AsLoader, &reference).unwrap_or_else(|e| panic!("{e}"))
    };
    let faithful = draw(&reference);
    for (pass, (_, gl_images)) in wgpu.passes.iter().zip(&faithful.steps) {
        for ((texture, a), (_, b)) in pass.images.iter().zip(gl_images) {
            assert_eq!(images::count_differing(a, b, images::OVER_1_255), 0, "{} {texture}", pass.pass);
        }
    }
    let composite = wgpu.passes.iter().position(|p| p.pass == "composite").expect("a composite step");
    assert_eq!(wgpu.passes[composite + 1].pass, "composite1");
    for (texture, image) in &mut reference[composite] {
        assert_eq!(texture, "colortex0");
        image.pixels.iter_mut().for_each(|p| *p = [1.0, 0.0, 1.0, 1.0]);
    }
    let replaced = draw(&reference);
    let (before, after) = (&faithful.steps[composite + 1].1[0].1, &replaced.steps[composite + 1].1[0].1);
    let pixels = (scene.width() * scene.height()) as usize;
    assert!(images::count_differing(before, after, 0.1) > pixels / 2, "composite1 did not read the replaced colortex0");
    assert_eq!(images::count_differing(&faithful.steps[composite].1[0].1, &replaced.steps[composite].1[0].1, 0.0), 0, "composite itself is drawn alike");
}

/// OpenGL drawing each full-screen step traced (tests/packs/tile_lookups): composite1's
/// mipmapped lookup inside the `if` that splits the quads of columns 100 and 101 leaves exactly
/// those two columns undefined, and so does its tile function's lookup on columns 200 and 201,
/// where each fragment of a quad runs it in another call; its other lookups (one in a buffer
/// without mipmaps, one under an `if` every fragment takes) leave nothing undefined, nor does
/// composite.
#[test]
fn opengl_traced_marks_the_quads_a_branch_splits_around_a_mipmapped_lookup() {
    let ctx = gl::context().unwrap_or_else(|e| panic!("{e}"));
    let pack = pack("tile_lookups", Loader::default());
    assert!(pack.failed.is_empty(), "{:?}", pack.failed);
    let scene = scene("case4_above_near");
    let mesh = mesh::build(&scene, &pack);
    let wgpu = render(&pack, &scene);
    let reference = gl_frame::Reference {
        steps: wgpu.passes.iter().map(|p| p.images.as_slice()).collect(),
        depth0: &wgpu.depth0,
        depth1: &wgpu.depth1,
        depth_written: Vec::new(),
        nudge: 0.0,
        trace_derivatives: true,
    };
    let traced = gl_frame::render_from(&ctx, &pack, &scene, &mesh, ScreenOutput::AsLoader, &reference).unwrap_or_else(|e| panic!("{e}"));
    let step = |pass: &str| wgpu.passes.iter().position(|p| p.pass == pass).unwrap_or_else(|| panic!("no step {pass}"));
    let undefined_columns = |pass: &str, texture: &str| {
        assert!(traced.traced[step(pass)], "{pass} was not drawn traced");
        let image = &traced.steps[step(pass)].1.iter().find(|(name, _)| name == texture).unwrap_or_else(|| panic!("{pass} wrote no {texture}")).1;
        let mut columns = std::collections::BTreeMap::new();
        for (i, p) in image.pixels.iter().enumerate() {
            if p[0] > 0.5 {
                *columns.entry(i as u32 % image.width).or_insert(0u32) += 1;
            }
        }
        columns
    };
    assert_eq!(undefined_columns("composite1", "colortex2"), std::collections::BTreeMap::from([(100, scene.height()), (101, scene.height()), (200, scene.height()), (201, scene.height())]));
    assert!(undefined_columns("composite", "colortex1").is_empty());
}

#[test]
fn opengl_draws_every_step_as_wgpu_does_for_every_loader() {
    let ctx = gl::context().unwrap_or_else(|e| panic!("{e}"));
    let mut failures = Vec::new();
    for name in ["flip_chain", "core_profile", "shadow_map", "mipmaps", "gather"] {
        for loader in [Loader::default(), Loader::Iris] {
            let pack = pack(name, loader);
            for scene_name in ["case4_above_near", "rain_over_lake", "blocks/shore"] {
                // Where a lookup's result jumps, the last bit of its coordinate decides: a depth
                // comparison whose reference lands on a shadow-map texel's own depth (where the
                // wall meets the sand under shore's low sun), a nearest texel on a sprite's edge
                // (shore's textured blocks). At most one pixel in 10,000 (a wrong binding or
                // mapping moves thousands); everything else within 1/255.
                let scene = scene(scene_name);
                let scene_pixels = (scene.width() * scene.height()) as usize;
                let allowed = if name == "shadow_map" || scene_name == "blocks/shore" { scene_pixels / 10_000 } else { 0 };
                let mesh = mesh::build(&scene, &pack);
                let wgpu = wgpu_frame::render(gpu(), &pack, &scene, &mesh, ScreenOutput::AsLoader, 1).unwrap_or_else(|e| panic!("{e}"));
                let gl = gl_frame::render(&ctx, &pack, &scene, &mesh, ScreenOutput::AsLoader).unwrap_or_else(|e| panic!("{e}"));
                assert_eq!(wgpu.passes.len(), gl.steps.len());
                for (pass, (_, gl_images)) in wgpu.passes.iter().zip(&gl.steps) {
                    for ((texture, a), (_, b)) in pass.images.iter().zip(gl_images) {
                        let over = images::count_differing(a, b, images::OVER_1_255);
                        if over > allowed {
                            failures.push(format!("{name} {loader} {scene_name} {}: {texture}: {over} pixels over 1/255", pass.pass));
                        }
                    }
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn the_shadow_pass_draws_the_terrain_copies_its_depth_then_draws_the_water() {
    let pack = pack("shadow_map", Loader::default());
    assert!(pack.failed.is_empty(), "{:?}", pack.failed);
    assert!(pack.shadow_pass);
    let settings = pack.shadow_settings;
    assert_eq!((settings.declared_resolution, settings.distance, settings.hardware_filtering), (512, 48.0, true));
    assert_eq!(pack.shadow_clear_of(1), BufferClear::Color([0.0, 0.0, 0.0, 1.0]));
    assert_eq!(pack.shadow_clear_of(0).shadow_colour(), [1.0; 4]);
    let scene = scene("case4_above_near");
    let mesh = mesh::build(&scene, &pack);
    let plan = FramePlan::new(&pack, &scene, &mesh, ScreenOutput::AsLoader);
    let labels: Vec<&str> = plan.steps.iter().map(|s| s.label.as_str()).collect();
    assert_eq!(labels[..4], ["shadow terrain (shadow)", "shadowtex0 to shadowtex1", "shadow water (shadow)", "sky (the loader's own)"]);
    assert_eq!(plan.shadow_buffers.iter().copied().collect::<Vec<_>>(), [0, 1]);

    let frame = render(&pack, &scene);
    let written = |pass: &str, texture: &str| {
        let step = frame.passes.iter().find(|p| p.pass == pass).unwrap_or_else(|| panic!("no step {pass}"));
        step.images.iter().find(|(name, _)| name == texture).map(|(_, image)| image.clone()).unwrap_or_else(|| panic!("{pass} wrote no {texture}"))
    };
    // The terrain covers part of the 96-block shadow volume; the water marks its own texels.
    let terrain = written("shadow terrain (shadow)", "shadowcolor0");
    let drawn = terrain.pixels.iter().filter(|p| p[..3] != [1.0; 3]).count();
    assert!(drawn > terrain.pixels.len() / 20 && drawn < terrain.pixels.len(), "terrain drew {drawn} of {} shadow texels", terrain.pixels.len());
    let water = written("shadow water (shadow)", "shadowcolor1");
    let marked = water.pixels.iter().filter(|p| p[0] == 1.0).count();
    assert!(marked > 0 && marked < drawn, "water marked {marked} shadow texels");
    assert_eq!(terrain.width, 512);
}

#[test]
fn shadow_names_the_map_without_water_where_the_pack_reads_watershadow() {
    use tidepack_harness::samplers::{ProgramStage, Source, resolve_any};
    let load = |composite: &str| {
        let files = tidepack_loader::input::pack_from_memory(
            "test/shaders/",
            [
                ("composite.fsh".to_string(), composite.as_bytes().to_vec()),
                ("composite.vsh".to_string(), b"#version 120\nvoid main() { gl_Position = ftransform(); }\n".to_vec()),
            ],
        );
        AnyPack::from_files(&files, &Configuration::default()).unwrap()
    };
    let plain = load("#version 120\nuniform sampler2D shadow;\nvoid main() { gl_FragData[0] = texture2D(shadow, vec2(0.5)); }\n");
    let with_water = load(
        "#version 120\nuniform sampler2D shadow;\nuniform sampler2D watershadow;\n\
         void main() { gl_FragData[0] = texture2D(shadow, vec2(0.5)) + texture2D(watershadow, vec2(0.5)); }\n",
    );
    assert_eq!(resolve_any(&plain, "shadow", ProgramStage::Composite), Ok(Source::ShadowDepth(0)));
    assert_eq!(resolve_any(&with_water, "shadow", ProgramStage::Composite), Ok(Source::ShadowDepth(1)));
    assert_eq!(resolve_any(&with_water, "watershadow", ProgramStage::Composite), Ok(Source::ShadowDepth(0)));
    assert_eq!(resolve_any(&with_water, "shadowcolor", ProgramStage::Composite), Ok(Source::ShadowColour(0)));
    // Without a shadow program the loader's own shading would draw the map: named, not drawn.
    assert!(!with_water.shadow_pass);
    assert!(with_water.not_modelled.iter().any(|l| l.contains("without a shadow program")), "{:?}", with_water.not_modelled);
}

/// A sampler name no loader binds keeps texture unit 0: colortex0 in a full-screen pass (final's
/// `texture` in XorDev's DOF-Shaderpack), transparent black in gbuffers programs, where unit 0
/// holds the atlas under its own names, and in shadowcomp.
#[test]
fn a_sampler_no_loader_binds_reads_unit_0_colortex0_in_full_screen_passes() {
    use tidepack_harness::samplers::{ProgramStage, Source, resolve_any};
    let files = tidepack_loader::input::pack_from_memory(
        "test/shaders/",
        [
            ("final.fsh".to_string(), b"#version 120\nuniform sampler2D texture;\nvoid main() { gl_FragData[0] = texture2D(texture, vec2(0.5)); }\n".to_vec()),
            ("final.vsh".to_string(), b"#version 120\nvoid main() { gl_Position = ftransform(); }\n".to_vec()),
        ],
    );
    let pack = AnyPack::from_files(&files, &Configuration::default()).unwrap();
    for stage in [ProgramStage::Prepare, ProgramStage::Deferred, ProgramStage::Composite] {
        assert_eq!(resolve_any(&pack, "texture", stage), Ok(Source::Color(0)), "{stage:?}");
        assert_eq!(resolve_any(&pack, "specular", stage), Ok(Source::Color(0)), "{stage:?}");
    }
    assert_eq!(resolve_any(&pack, "specular", ProgramStage::Gbuffers), Ok(Source::NoSpecular));
    assert_eq!(resolve_any(&pack, "anything", ProgramStage::Gbuffers), Ok(Source::Unbound));
    assert_eq!(resolve_any(&pack, "anything", ProgramStage::ShadowComposite), Ok(Source::Unbound));
    assert!(!pack.not_modelled.iter().any(|n| n.contains("sampler texture")), "{:?}", pack.not_modelled);
}

#[test]
fn a_program_that_asks_for_mipmaps_reads_them_and_the_others_do_not() {
    let pack = pack("mipmaps", Loader::default());
    assert_eq!(pack.mipmaps.keys().collect::<Vec<_>>(), ["composite1"]);
    assert_eq!(pack.mipmaps["composite1"].iter().copied().collect::<Vec<_>>(), [2]);
    let frame = render(&pack, &scene("case4_above_near"));
    let written = |pass: &str, texture: &str| {
        let step = frame.passes.iter().find(|p| p.pass == pass).unwrap_or_else(|| panic!("no step {pass}"));
        step.images.iter().find(|(name, _)| name == texture).map(|(_, image)| image.clone()).unwrap_or_else(|| panic!("{pass} wrote no {texture}"))
    };
    // How far neighbouring pixels differ, at most, in the middle of the image (green).
    let roughness = |image: &images::FloatImage| {
        let (w, h) = (image.width as usize, image.height as usize);
        let mut worst = 0f32;
        for y in h / 4..3 * h / 4 {
            for x in w / 4..3 * w / 4 {
                worst = worst.max((image.pixels[y * w + x][1] - image.pixels[y * w + x + 1][1]).abs());
            }
        }
        worst
    };
    // The terrain drew with renderStage MC_RENDER_STAGE_TERRAIN_SOLID (8) in its blue.
    let terrain = written("terrain (gbuffers_terrain)", "colortex0");
    let stage = terrain.pixels[(terrain.height as usize / 2) * terrain.width as usize + terrain.width as usize / 2][2];
    assert!((stage * 255.0 - 8.0).abs() < 1e-3, "renderStage {}", stage * 255.0);
    let checker = written("composite", "colortex2");
    let averaged = written("composite1", "colortex0");
    assert!(roughness(&checker) > 0.3, "the checker: {}", roughness(&checker));
    assert!(roughness(&averaged) < 0.05, "level 4 of its mipmaps: {}", roughness(&averaged));
    // final reads colortex2 without mipmaps: the checker itself, in the screen's alpha.
    let differing: Vec<(usize, f32, f32)> =
        frame.image.pixels.iter().zip(&checker.pixels).enumerate().filter(|(_, (s, c))| (s[3] - c[1]).abs() > 1e-6).map(|(i, (s, c))| (i, s[3], c[1])).collect();
    assert!(differing.is_empty(), "{} pixels differ, the first: {:?}", differing.len(), &differing[..differing.len().min(5)]);
}

#[test]
fn the_core_profile_gets_the_same_geometry_as_the_legacy_built_ins() {
    // core_profile draws with vaPosition, vaColor, vaUV0 and vaUV2 under modelViewMatrix,
    // projectionMatrix and chunkOffset what flip_chain draws with ftransform() and gl_Color.
    let scene = scene("case4_above_near");
    let legacy = render(&pack("flip_chain", Loader::default()), &scene);
    let core = render(&pack("core_profile", Loader::default()), &scene);
    assert_eq!(core.not_modelled, [NO_SUN_PROGRAM], "everything else is imitated");
    let terrain = |frame: &Frame| {
        let step = frame.passes.iter().find(|p| p.pass.starts_with("terrain")).expect("a terrain step");
        step.images[0].1.clone()
    };
    let d = images::max_channel_difference(&terrain(&legacy), &terrain(&core));
    assert!(d.iter().all(|c| *c <= 1.0 / 255.0), "terrain colour differs by {d:?}");
}

/// Our own pack's composite draws into the unrounded screen: the plan's last colortex0 write
/// goes to the RGBA32F screen instead of colortex0 and a copy, so the screen is the loader's
/// before rounding to colortex0's RGBA8, and colortex0 keeps what the geometry drew.
#[test]
fn the_unrounded_screen_is_the_loaders_screen_before_rounding() {
    use tidepack_harness::program::{self, PackSelection};
    use tidepack_pack::Dialect;
    for dialect in [Dialect::Glsl120, Dialect::Glsl330] {
        let selection = PackSelection { source_dir: root().join("shaderpack"), dialect, profile: None, options: vec![] };
        let ours = program::load(&selection).unwrap_or_else(|e| panic!("{e}"));
        for name in ["case4_above_near", "rain_over_lake", "glass_over_land"] {
            let scene = scene(name);
            let mesh = ours.mesh(&scene);
            let steps = |screen| -> Vec<String> {
                FramePlan::new(&ours.pack, &scene, &mesh, screen).steps.iter().map(|s| s.label.clone()).collect()
            };
            let (as_loader, unrounded) = (steps(ScreenOutput::AsLoader), steps(ScreenOutput::Unrounded));
            assert_eq!(as_loader.last().map(String::as_str), Some("colortex0 to the screen (no final)"));
            assert_eq!(unrounded, as_loader[..as_loader.len() - 1], "{dialect:?} {name}");
            let render = |screen| wgpu_frame::render(gpu(), &ours.pack, &scene, &mesh, screen, 1).unwrap_or_else(|e| panic!("{e}"));
            let (rounded, exact) = (render(ScreenOutput::AsLoader), render(ScreenOutput::Unrounded));
            // Rounding to colortex0's RGBA8 moves a channel by up to half a step; llvmpipe's
            // shading into an RGBA8 target moves some by up to one step. At a few pixels (two of
            // case 4's in GLSL 120, by 5 steps) more: the two compiles of composite round the
            // secant surface search's divisions differently in the last bit, and a pixel whose
            // shading jumps with the surface point (a refracted lookup or SSR hit at an edge)
            // takes the other side of the jump.
            let steps = |a: &[f32; 4], b: &[f32; 4]| (0..4).map(|c| images::to_unorm8(a[c]).abs_diff(images::to_unorm8(b[c]))).max().unwrap_or(0);
            let differences: Vec<u8> = rounded.image.pixels.iter().zip(&exact.image.pixels).map(|(a, b)| steps(a, b)).collect();
            let (worst, over_one) = (differences.iter().max().copied().unwrap_or(0), differences.iter().filter(|d| **d > 1).count());
            let at: Vec<(usize, usize)> = differences.iter().enumerate().filter(|(_, d)| **d > 2).map(|(i, _)| (i % scene.width() as usize, i / scene.width() as usize)).collect();
            assert!(over_one <= 4, "{dialect:?} {name}: largest difference {worst}/255, {over_one} pixels over 1/255, over 2/255 at {at:?}");
            let drawn = exact.passes.iter().flat_map(|p| &p.images).rfind(|(texture, _)| texture == "colortex0").expect("colortex0 drawn");
            assert_eq!(exact.buffers[&0].pixels, drawn.1.pixels, "{dialect:?} {name}: colortex0 is what the geometry left");
        }
    }
}

/// A pack that only NVIDIA's leniency compiles (tests/packs/lenient): a sampler named `texture`
/// called through texture() under 1.30, texture() under 1.20, an `#extension` after code (one of
/// them inside an `#if`), a reserved word as a name, words after `#ifndef NAME` and after `#else`,
/// a precision qualifier under 1.20, a GLSL ES 1.00 stage whose only statement is a discard, a
/// `const` from a uniform, a sampler chosen by `?:`, and
/// values left undefined (a
/// vertex output only an `if` writes; a draw buffer never written, which OpenGL is kept from
/// writing, as wgpu does not write it). OpenGL draws it with the rewrites loaders and lenient drivers
/// apply, each listed at its file and line, and agrees with wgpu, which draws the lowering's
/// reading of the same text.
#[test]
fn what_only_lenient_drivers_compile_is_rewritten_for_opengl_listed_and_drawn_alike() {
    let pack = pack("lenient", Loader::default());
    assert!(pack.failed.is_empty(), "{:?}", pack.failed);
    let rewrites = pack.gl_rewrites();
    for expected in [
        "gbuffers_terrain: gbuffers_terrain.fsh:5: the sampler `texture`",
        "composite: composite.fsh:1: #version 120 raised to 130 for `texture()`",
        "composite: composite.fsh:7: `#extension GL_EXT_gpu_shader4 : enable` after code moved up",
        "composite: composite.fsh:12: `output`, a reserved word, renamed to `output_` (3 uses)",
        "composite: composite.fsh:16: `#ifndef WARM` ignores what follows: `&& defined COLD` removed",
        "composite: composite.fsh:18: `#else` ignores what follows: `if defined WARM` removed",
        "composite: composite.fsh:22: `#extension GL_ARB_shader_texture_lod : enable` after code moved up",
        "gbuffers_terrain: gbuffers_terrain.vsh:12: precision qualifiers, reserved words in GLSL 120, removed (1)",
        "gbuffers_terrain: gbuffers_terrain.vsh:8: outputs not written whole on every path set to 0 at the start of main",
        "gbuffers_water: gbuffers_water.fsh:1: #version 100 (GLSL ES 1.00) compiled as desktop #version 120",
        "composite1: composite1.fsh:7: `const` dropped from `texel`",
        "composite1: composite1.fsh:10: `texture()` of a sampler chosen by `?:`, which GLSL refuses, made a choice of two lookups",
    ] {
        assert!(rewrites.iter().any(|r| r.starts_with(expected)), "{expected:?} is not among {rewrites:#?}");
    }
    assert_eq!(rewrites.len(), 12, "{rewrites:#?}");
    let ctx = gl::context().unwrap_or_else(|e| panic!("{e}"));
    let scene = scene("case4_above_near");
    let mesh = mesh::build(&scene, &pack);
    let wgpu = wgpu_frame::render(gpu(), &pack, &scene, &mesh, ScreenOutput::AsLoader, 1).unwrap_or_else(|e| panic!("{e}"));
    let gl = gl_frame::render(&ctx, &pack, &scene, &mesh, ScreenOutput::AsLoader).unwrap_or_else(|e| panic!("Mesa refuses the rewritten text: {e}"));
    for (pass, (_, gl_images)) in wgpu.passes.iter().zip(&gl.steps) {
        for ((texture, a), (_, b)) in pass.images.iter().zip(gl_images) {
            assert_eq!(images::count_differing(a, b, images::OVER_1_255), 0, "{} {texture}", pass.pass);
        }
    }
}

/// What NVIDIA's driver does implicitly (tests/packs/nvidia_implicit): inputs placed at the
/// generic locations it aliases to the legacy position, colour and texture coordinate, a vec4
/// stored in a float, a uint returned from a float function, a lookup offset that is not a
/// constant, a vector compared with a scalar, a `mix` of vectors with a bool, a `const` local
/// initialised from a parameter, a bias in a vertex stage, a function named as a statement with
/// no call, and an output never written. Both
/// renderers read the inputs from the vertex's data and convert the values as NVIDIA does (the
/// conversions listed at their lines), and agree at every step.
#[test]
fn what_nvidia_does_implicitly_both_renderers_do_alike() {
    let pack = pack("nvidia_implicit", Loader::default());
    assert!(pack.failed.is_empty(), "{:?}", pack.failed);
    let rewrites = pack.gl_rewrites();
    for expected in [
        "gbuffers_terrain: gbuffers_terrain.fsh:13: `count / 4u` converted with float()",
        "gbuffers_terrain: gbuffers_terrain.fsh:16: `const` dropped from `halfLight`",
        "gbuffers_terrain: gbuffers_terrain.fsh:20: `texture(gtexture, uv)` converted with float()",
        "gbuffers_terrain: gbuffers_terrain.fsh:22: a lookup with an offset that is not a constant",
        "gbuffers_terrain: gbuffers_terrain.fsh:23: `0` converted with vec2()",
        "gbuffers_terrain: gbuffers_terrain.fsh:24: `sign(uv.x - 2.0)` converted with vec3()",
        "gbuffers_terrain: gbuffers_terrain.fsh:25: `lessThan(uv, vec2(-1.0)) || greaterThan(uv, vec2(2.0))`, which NVIDIA takes component by component",
        "gbuffers_terrain: gbuffers_terrain.fsh:26: `tint.b > 0.25` converted with bvec3()",
        "gbuffers_terrain: gbuffers_terrain.vsh:14: `texture2D()` with a bias in a vertex stage",
        "gbuffers_terrain: gbuffers_terrain.vsh:21: `blurredColour;`, a function named without a call",
    ] {
        assert!(rewrites.iter().any(|r| r.starts_with(expected)), "{expected:?} is not among {rewrites:#?}");
    }
    assert_eq!(rewrites.len(), 10, "{rewrites:#?}");
    let (report, screen) = render_job("nvidia_implicit");
    let gl = report.gl.as_ref().expect("an OpenGL frame");
    assert!(gl.refused.is_none(), "{:?}", gl.refused);
    for step in &gl.steps {
        assert!(step.pixels_over_1_255.values().all(|&n| n == 0), "{step:?}");
    }
    // The never-written output's buffer is no step's.
    assert!(gl.steps.iter().all(|s| !s.pixels_over_1_255.contains_key("colortex1")), "{:?}", gl.steps);
    // The aliased inputs read what the legacy ones do: the same pack reading gl_Vertex, gl_Color
    // and gl_MultiTexCoord0 draws the same screen.
    let legacy = std::env::temp_dir().join(format!("tidepack-nvidia-legacy-{}", std::process::id()));
    std::fs::create_dir_all(legacy.join("shaders")).unwrap_or_else(|e| panic!("{e}"));
    for file in ["gbuffers_terrain.fsh", "composite.vsh", "composite.fsh"] {
        std::fs::copy(root().join("tests/packs/nvidia_implicit/shaders").join(file), legacy.join("shaders").join(file)).unwrap_or_else(|e| panic!("{e}"));
    }
    let vertex = std::fs::read_to_string(root().join("tests/packs/nvidia_implicit/shaders/gbuffers_terrain.vsh")).unwrap_or_else(|e| panic!("{e}"));
    let vertex = vertex.replace("layout(location = 0) in vec4 position;", "#define position gl_Vertex");
    let vertex = vertex.replace("layout(location = 3) in vec4 vertexColor;", "#define vertexColor gl_Color");
    let vertex = vertex.replace("layout(location = 8) in vec4 texCoord;", "#define texCoord gl_MultiTexCoord0");
    std::fs::write(legacy.join("shaders/gbuffers_terrain.vsh"), vertex).unwrap_or_else(|e| panic!("{e}"));
    let legacy_pack = AnyPack::load(&legacy, &Configuration::default()).unwrap_or_else(|e| panic!("{e}"));
    let scene = scene("case4_above_near");
    let (aliased, named) = (render(&pack, &scene).image, render(&legacy_pack, &scene).image);
    std::fs::remove_dir_all(&legacy).ok();
    assert_eq!(images::count_differing(&aliased, &named, 0.0), 0);
    assert_eq!(screen.dimensions(), (aliased.width, aliased.height));
}

/// A struct passed between the stages (tests/packs/struct_varying): naga spreads it over its
/// fields, which transform feedback cannot record by those names, so OpenGL links the program
/// as shipped; both renderers read the vertex stage's values.
#[test]
fn a_struct_varying_arrives_in_both_renderers() {
    let (report, screen) = render_job("struct_varying");
    let gl = report.gl.as_ref().expect("an OpenGL frame");
    assert!(gl.refused.is_none(), "{:?}", gl.refused);
    assert!(gl.steps.iter().all(|s| s.pixels_over_1_255.values().all(|&n| n == 0)), "{:?}", gl.steps);
    let wrong = screen.pixels().filter(|p| p.0 != [64, 128, 191, 255]).count();
    assert_eq!(wrong, 0, "pixels other than the vertex stage's (0.25, 0.5, 0.75)");
}

/// Nine vertex inputs of the pack's own (tests/packs/many_attributes): the ninth is past
/// OpenGL's 16 attribute locations at the lowering's location, so OpenGL takes it at a free one
/// below; both renderers draw the terrain alike, with no driver error.
#[test]
fn a_vertex_stage_with_nine_inputs_of_its_own_draws_alike_in_both_renderers() {
    let (report, screen) = render_job("many_attributes");
    let gl = report.gl.as_ref().expect("an OpenGL frame");
    assert!(gl.refused.is_none(), "{:?}", gl.refused);
    assert!(!gl.steps.is_empty());
    assert!(gl.steps.iter().all(|s| s.pixels_over_1_255.values().all(|&n| n == 0)), "{:?}", gl.steps);
    assert!(screen.pixels().any(|p| p.0[..3] != [0, 0, 0]), "the terrain is on screen");
}

/// Custom textures by stage (tests/packs/deferred_texture): `texture.deferred.colortex5` (red)
/// is bound in deferred and `texture.composite.colortex6` (blue) in composite, in both
/// renderers, and neither is listed as not imitated.
#[test]
fn a_deferred_custom_texture_is_bound_in_deferred_programs_in_both_renderers() {
    let (report, screen) = render_job("deferred_texture");
    let gl = report.gl.as_ref().expect("an OpenGL frame");
    assert!(gl.refused.is_none(), "{:?}", gl.refused);
    assert!(gl.steps.iter().all(|s| s.pixels_over_1_255.values().all(|&n| n == 0)), "{:?}", gl.steps);
    assert!(!report.not_modelled.iter().any(|line| line.contains("texture.")), "{:?}", report.not_modelled);
    assert!(screen.pixels().all(|p| p.0[2] == 255), "composite's blue is not everywhere");
    assert_eq!(screen.get_pixel(10, 10).0, [255, 0, 255, 255], "deferred's red in the sky's corner");
}

/// Raw textures (tests/packs/raw_textures): a 3D RGBA8 volume and a 1D half-float line, each
/// on a unit that also names a colour buffer, read by a `sampler3D` and a `sampler1D` in both
/// renderers, and the block atlas's normal map bound by its `minecraft:` path; none is listed
/// as not imitated.
#[test]
fn raw_textures_are_read_by_samplers_of_their_type_in_both_renderers() {
    let (report, screen) = render_job("raw_textures");
    let gl = report.gl.as_ref().expect("an OpenGL frame");
    assert!(gl.refused.is_none(), "{:?}", gl.refused);
    assert!(gl.steps.iter().all(|s| s.pixels_over_1_255.values().all(|&n| n == 0)), "{:?}", gl.steps);
    assert!(!report.not_modelled.iter().any(|line| line.contains("texture.")), "{:?}", report.not_modelled);
    assert!(screen.pixels().all(|p| p.0 == [200, 100, 51, 255]), "{:?}", screen.get_pixel(0, 0));
}

/// Entities (tests/packs/entities, with its own scene): each drawn by gbuffers_entities after
/// the terrain with its `entityId` from entity.properties: the zombie it lists (2000, red) on
/// the right, the pig it does not (-1, green) on the left, in both renderers.
#[test]
fn entities_are_drawn_with_their_ids_in_both_renderers() {
    let (report, screen) = render_job_in("entities", &root().join("tests/packs/entities/scene.toml"), Configuration::default());
    let gl = report.gl.as_ref().expect("an OpenGL frame");
    assert!(gl.refused.is_none(), "{:?}", gl.refused);
    assert!(gl.steps.iter().all(|s| s.pixels_over_1_255.values().all(|&n| n == 0)), "{:?}", gl.steps);
    let (w, h) = screen.dimensions();
    let count = |rgb: [u8; 3], left: bool| screen.enumerate_pixels().filter(|(x, y, p)| p.0[..3] == rgb && (*x < w / 2) == left && *y < h).count();
    assert!(count([255, 0, 0], false) > 100, "the zombie (2000) on the right: {}", count([255, 0, 0], false));
    assert!(count([0, 255, 0], true) > 100, "the pig (-1) on the left: {}", count([0, 255, 0], true));
    assert_eq!(count([255, 0, 0], true) + count([0, 255, 0], false), 0, "an entity drawn with the other's id");
}

/// gl_FrontFacing as the game has it (tests/packs/front_facing): the game culls back faces, so
/// every face on screen is a front face, red; both renderers agree.
#[test]
fn the_faces_on_screen_are_front_faces_in_both_renderers() {
    let (report, screen) = render_job("front_facing");
    let gl = report.gl.as_ref().expect("an OpenGL frame");
    assert!(gl.refused.is_none(), "{:?}", gl.refused);
    assert!(gl.steps.iter().all(|s| s.pixels_over_1_255.values().all(|&n| n == 0)), "{:?}", gl.steps);
    let count = |rgb: [u8; 3]| screen.pixels().filter(|p| p.0[..3] == rgb).count();
    assert_eq!(count([0, 0, 255]), 0, "back faces on screen");
    assert!(count([255, 0, 0]) > screen.pixels().len() / 2, "{} front-face pixels", count([255, 0, 0]));
}

/// A depth buffer read through `sampler2D` past its first channel (tests/packs/depth_as_luminance)
/// reads as OptiFine's compatibility profile has it, (d, d, d, 1), in both renderers: green is
/// red, blue one minus it, alpha 1.
#[test]
fn depth_read_as_a_colour_is_luminance_in_both_renderers() {
    let (report, screen) = render_job("depth_as_luminance");
    let gl = report.gl.as_ref().expect("an OpenGL frame");
    assert!(gl.refused.is_none(), "{:?}", gl.refused);
    assert!(gl.steps.iter().all(|s| s.pixels_over_1_255.values().all(|&n| n == 0)), "{:?}", gl.steps);
    let luminance = screen.pixels().filter(|p| p.0[1] == p.0[0] && (i32::from(p.0[2]) - (255 - i32::from(p.0[0]))).abs() <= 1 && p.0[3] == 255).count();
    assert_eq!(luminance, screen.pixels().len(), "pixels whose green is not their red");
    assert!(screen.pixels().any(|p| p.0[0] < 255), "the terrain's depth is on screen");
}

/// Our own programs need none of those rewrites.
#[test]
fn our_pack_is_given_to_opengl_as_written() {
    for dialect in [tidepack_pack::Dialect::Glsl120, tidepack_pack::Dialect::Glsl330] {
        let selection = tidepack_harness::PackSelection { source_dir: root().join("shaderpack"), dialect, profile: None, options: vec![] };
        let loaded = tidepack_harness::program::load(&selection).unwrap_or_else(|e| panic!("{e}"));
        let rewritten = loaded.pack.gl_rewrites();
        assert!(rewritten.is_empty(), "{rewritten:#?}");
    }
}

/// A `#version` the pack chooses inside an `#if` of an include (tests/packs/version_chosen_in_include),
/// which composite.fsh includes by an unquoted path, as Iris alone reads it: under Iris, whose
/// preprocessor resolves it, both renderers draw the program, OpenGL from Iris's preprocessed
/// text, where the chosen `#version` is the first line that is not blank (a driver reading the
/// pack's text as it stands would take the other branch's).
#[test]
fn a_version_chosen_in_an_if_is_given_first_under_iris() {
    let configuration = Configuration { loader: Loader::Iris, ..Configuration::default() };
    let (report, _) = render_job_with("version_chosen_in_include", configuration);
    assert!(report.renderer.name == "wgpu", "{:?}", report.renderer);
    let gl = report.gl.as_ref().expect("an OpenGL frame");
    assert!(gl.refused.is_none(), "{:?}", gl.refused);
    assert!(gl.steps.iter().all(|s| s.pixels_over_1_255.values().all(|&n| n == 0)), "{:?}", gl.steps);
}

/// A stage as Iris hands it to the driver (tests/packs/read_as_iris_reads_it): its
/// preprocessor's output, so that Mesa never meets the float in `#if` or the function-like
/// macro named `a` beside `(colour.a)`, which its own preprocessor refuses; `#version 130`
/// raised to 3.30 compatibility, where `inverse()` exists and `flat varying` is written `flat
/// in`/`flat out`; and `IRIS_FEATURE_CUSTOM_IMAGES` defined, as shaders.properties asks for it
/// behind a `#define` that only a branch not taken makes (magenta where it is missing). Both
/// renderers draw the same screen.
#[test]
fn a_stage_reaches_opengl_as_iris_hands_it() {
    let configuration = Configuration { loader: Loader::Iris, ..Configuration::default() };
    let (report, screen) = render_job_with("read_as_iris_reads_it", configuration);
    let gl = report.gl.as_ref().expect("an OpenGL frame");
    assert!(gl.refused.is_none(), "{:?}", gl.refused);
    assert!(gl.steps.iter().all(|s| s.pixels_over_1_255.values().all(|&n| n == 0)), "{:?}", gl.steps);
    let raised = "`#version 130` raised to `#version 330 compatibility`, as Iris raises every stage to GLSL 3.30, `attribute` and `varying` written `in` and `out`";
    assert!(report.gl_rewrites.iter().filter(|r| r.contains(raised)).count() == 2, "{:?}", report.gl_rewrites);
    assert!(screen.pixels().all(|p| p.0[..3] != [255, 0, 255]), "the feature macro is missing");
}

/// A pack written on Windows for NVIDIA (tests/packs/windows_habits): an include named in
/// another case than its file, which Windows' file system reads, and a `flat varying` in a stage
/// raised to GLSL 1.30 for its `switch`. Both renderers draw each face in its colour, and the
/// report lists both readings.
#[test]
fn a_pack_made_on_windows_renders_with_its_readings_listed() {
    let (report, screen) = render_job("windows_habits");
    let gl = report.gl.as_ref().expect("an OpenGL frame");
    assert!(gl.refused.is_none(), "{:?}", gl.refused);
    assert!(gl.steps.iter().all(|s| s.pixels_over_1_255.values().all(|&n| n == 0)), "{:?}", gl.steps);
    let said = |what: &str| report.gl_rewrites.iter().any(|r| r.contains(what));
    assert!(said("`lib/Shading.glsl` read from `lib/shading.glsl`"), "{:?}", report.gl_rewrites);
    assert!(said("`varying` after an interpolation qualifier, which GLSL 1.30 refuses, made `out`"), "{:?}", report.gl_rewrites);
    // The top faces, green, fill the lower half of the shore scene.
    assert!(screen.pixels().filter(|p| p.0[..3] == [0, 255, 0]).count() > screen.pixels().len() / 4);
}

/// `render --pack` of tests/packs/`name` on case4_above_near, two frames, with `--gl`: the
/// report and the screen.
fn render_job(name: &str) -> (tidepack_harness::job::AnyPackReport, image::RgbaImage) {
    render_job_with(name, Configuration::default())
}

/// [`render_job`] under `configuration`.
fn render_job_with(name: &str, configuration: Configuration) -> (tidepack_harness::job::AnyPackReport, image::RgbaImage) {
    render_job_in(name, &root().join("tests/scenes/case4_above_near.toml"), configuration)
}

/// [`render_job_with`] of the scene file `scene`.
fn render_job_in(name: &str, scene: &std::path::Path, configuration: Configuration) -> (tidepack_harness::job::AnyPackReport, image::RgbaImage) {
    let out = std::env::temp_dir().join(format!("tidepack-{name}-{}", std::process::id()));
    let job = tidepack_harness::job::AnyPackJob {
        scene: scene.to_path_buf(),
        pack: root().join("tests/packs").join(name),
        configuration,
        out_dir: out.clone(),
        buffers: false,
        gl: true,
        frames: 2,
        expect: None,
        bless: false,
        max_flip: 0.03,
        gl_max_pixels: None,
    };
    let report = tidepack_harness::job::run_any_pack(&job).unwrap_or_else(|e| panic!("{name}: {e}"));
    let screen_file = format!("{}.png", tidepack_harness::Scene::load(scene).unwrap_or_else(|e| panic!("{e}")).name);
    let screen = image::open(out.join(&screen_file)).unwrap_or_else(|e| panic!("{e}")).to_rgba8();
    std::fs::remove_dir_all(&out).ok();
    (report, screen)
}

/// A pack whose final passes more varyings between its stages than Vulkan on lavapipe takes
/// (tests/packs/beyond_wgpu, 32): wgpu cannot draw the frame, so OpenGL draws it as the primary
/// renderer, every varying arriving, and the report names the renderer, why, and its times.
#[test]
fn opengl_draws_the_frame_where_wgpu_cannot() {
    let (report, screen) = render_job("beyond_wgpu");
    assert!(report.renderer.name.starts_with("OpenGL"), "{:?}", report.renderer);
    let why = report.renderer.wgpu_cannot_draw.as_deref().unwrap_or_default();
    assert!(why.contains("final") && why.contains("max_inter_stage_shader_variables"), "{why}");
    assert!(report.failed_programs.is_empty(), "{:?}", report.failed_programs);
    // wgpu draws every step before final from OpenGL's inputs, and agrees; final is OpenGL's.
    let gl = report.gl.as_ref().expect("the steps compared");
    let left: Vec<&str> = gl.wgpu_cannot_draw.iter().map(|(step, _)| step.as_str()).collect();
    assert_eq!(left, ["final"], "{:?}", gl.wgpu_cannot_draw);
    assert!(gl.steps.iter().any(|s| s.pass.starts_with("water")), "{:?}", gl.steps);
    assert!(gl.steps.iter().all(|s| s.pixels_over_1_255.values().all(|&n| n == 0)), "{:?}", gl.steps);
    assert_eq!(report.passes.last().map(|p| p.pass.as_str()), Some("final"));
    assert!(report.timing.frame_ms > 0.0 && report.timing.passthrough_ms > 0.0, "{:?}", report.timing);
    // The 32 varyings' red parts sum to 1: the screen is full red wherever final drew.
    let centre = screen.get_pixel(screen.width() / 2, screen.height() / 2);
    assert_eq!(centre[0], 255, "{centre:?}");
}

/// A shadow colour buffer read through a shadow sampler (tests/packs/shadow_sampler_on_colour):
/// wgpu cannot bind it, so OpenGL draws that composite alone, the buffer bound as the loaders
/// bind it, and wgpu draws and agrees on every step before it.
#[test]
fn a_shadow_sampler_over_a_colour_buffer_is_drawn_by_opengl() {
    let (report, _) = render_job("shadow_sampler_on_colour");
    assert!(report.renderer.name.starts_with("OpenGL"), "{:?}", report.renderer);
    assert!(report.failed_programs.is_empty(), "{:?}", report.failed_programs);
    let gl = report.gl.as_ref().expect("the steps compared");
    assert_eq!(gl.wgpu_cannot_draw.len(), 1, "{:?}", gl.wgpu_cannot_draw);
    let (step, why) = &gl.wgpu_cannot_draw[0];
    assert_eq!(step, "composite");
    assert!(why.contains("composite.fsh: shadowcolor0 is read as a shadow sampler but is not a depth buffer"), "{why}");
    assert!(!why.contains("tp_"), "{why}");
    assert!(gl.steps.iter().any(|s| s.pass.starts_with("water")), "{:?}", gl.steps);
    assert!(gl.steps.iter().all(|s| s.pixels_over_1_255.values().all(|&n| n == 0)), "{:?}", gl.steps);
}

/// An unsigned integer buffer (tests/packs/integer_buffer: composite packs bits into an R32UI
/// colortex1, composite1 unpacks them through a `usampler2D`). OpenGL stores it as RGBA32UI and
/// draws the frame, every value arriving whole; wgpu's frames hold no integer buffer, and the
/// report says so.
#[test]
fn an_integer_buffer_keeps_its_bits() {
    let (report, screen) = render_job("integer_buffer");
    assert!(report.renderer.name.starts_with("OpenGL"), "{:?}", report.renderer);
    assert!(report.failed_programs.is_empty(), "{:?}", report.failed_programs);
    assert!(report.not_modelled.iter().any(|n| n == "colortex1Format = R32UI: stored as Rgba32Ui"), "{:?}", report.not_modelled);
    let gl = report.gl.as_ref().expect("an OpenGL frame");
    assert!(gl.wgpu_cannot_draw.iter().any(|(_, why)| why.contains("integer buffer")), "{:?}", gl.wgpu_cannot_draw);
    let magenta = screen.pixels().filter(|p| p.0 == [255, 0, 255, 255]).count();
    assert_eq!(magenta, 0, "pixels whose bits did not arrive whole");
    // Bright pixels carry the flag in green, the others none: both are on the screen.
    let flagged = screen.pixels().filter(|p| p.0[1] == 255).count();
    let unflagged = screen.pixels().filter(|p| p.0[1] == 0).count();
    assert!(flagged > 0 && unflagged > 0 && flagged + unflagged == screen.pixels().len(), "{flagged} flagged, {unflagged} not");
}

/// A struct instance declared without a value and read before anything writes it
/// (tests/packs/unset_global: declared with its struct, holding a nested struct and an array):
/// OpenGL is given it as 0, as wgpu has it, the rewrite is listed, and the two agree.
#[test]
fn struct_instances_declared_without_a_value_are_zero_in_both_renderers() {
    let (report, _) = render_job("unset_global");
    let expected = "composite: composite.fsh:15: struct instances declared without a value set to 0 (undefined in GLSL; 0 as wgpu has them): `surface`";
    assert!(report.gl_rewrites.iter().any(|r| r == expected), "{:#?}", report.gl_rewrites);
    let gl = report.gl.as_ref().expect("an OpenGL frame");
    assert!(gl.steps.iter().all(|s| s.pixels_over_1_255.values().all(|&n| n == 0)), "{:?}", gl.steps);
}

/// The fog uniforms (tests/packs/fog_uniforms): `fogStart` and `fogEnd` hold the game's linear
/// fog, the one the legacy `gl_Fog` state has, in both renderers.
#[test]
fn fog_uniforms_hold_the_games_fog() {
    let (report, screen) = render_job("fog_uniforms");
    let gl = report.gl.as_ref().expect("an OpenGL frame");
    assert!(gl.refused.is_none(), "{:?}", gl.refused);
    assert!(gl.steps.iter().all(|s| s.pixels_over_1_255.values().all(|&n| n == 0)), "{:?}", gl.steps);
    let fogged = screen.pixels().filter(|p| p.0 == [191, 255, 255, 255]).count();
    assert!(fogged > screen.pixels().len() / 10, "{fogged} terrain pixels with fogStart = 0.75 far, fogEnd = far");
}

/// The biome's uniforms (tests/packs/biome_uniform): a custom uniform on `biome`, its category
/// and precipitation says plains, and `temperature` and `rainfall` are the plains' 0.8 and 0.4.
/// A custom `uniform bool` (the still camera) is true in both renderers, and uniforms the
/// loader does not set hold their initializers in both.
#[test]
fn biome_uniforms_say_plains() {
    let (report, screen) = render_job("biome_uniform");
    assert!(!report.not_modelled.iter().any(|n| n.contains("biome") || n.contains("cameraStill")), "{:?}", report.not_modelled);
    // The custom `uniform bool` is true in both renderers.
    let gl = report.gl.as_ref().expect("an OpenGL frame");
    assert!(gl.steps.iter().all(|s| s.pixels_over_1_255.values().all(|&n| n == 0)), "{:?}", gl.steps);
    // Blue is 0.8 * 0.4 = 0.32 of 255.
    let plains = screen.pixels().filter(|p| p.0[0] == 0 && p.0[1] == 255 && p.0[2].abs_diff(82) <= 1).count();
    assert!(plains > screen.pixels().len() / 10, "{plains} terrain pixels in the plains");
}

/// `N` in a DRAWBUFFERS list (tests/packs/drawn_into_no_buffer): that output is drawn into no
/// buffer and the next into colortex0, in both renderers.
#[test]
fn an_output_listed_as_n_is_drawn_into_no_buffer() {
    let (report, screen) = render_job("drawn_into_no_buffer");
    assert!(report.failed_programs.is_empty(), "{:?}", report.failed_programs);
    let gl = report.gl.as_ref().expect("an OpenGL frame");
    assert!(gl.refused.is_none(), "{:?}", gl.refused);
    assert!(gl.steps.iter().all(|s| s.pixels_over_1_255.values().all(|&n| n == 0)), "{:?}", gl.steps);
    let green = screen.pixels().filter(|p| p.0 == [0, 255, 0, 255]).count();
    let red = screen.pixels().filter(|p| p.0[0] == 255 && p.0[1] == 0).count();
    assert!(green > screen.pixels().len() / 10 && red == 0, "{green} green, {red} red pixels");
}

/// A program with a geometry stage (tests/packs/geometry_stage), which naga cannot read: OpenGL
/// draws the frame, running the geometry stage between the vertex and fragment stages, and the
/// report says why wgpu does not.
#[test]
fn opengl_runs_a_geometry_stage() {
    let (report, screen) = render_job("geometry_stage");
    assert!(report.renderer.name.starts_with("OpenGL"), "{:?}", report.renderer);
    let why = report.renderer.wgpu_cannot_draw.as_deref().unwrap_or_default();
    assert!(why.contains("a geometry stage (gbuffers_terrain.gsh)"), "{why}");
    assert!(report.failed_programs.is_empty(), "{:?}", report.failed_programs);
    assert!(!report.not_modelled.iter().any(|n| n.contains("geometry")), "{:?}", report.not_modelled);
    // Only the geometry stage writes the green the terrain shows.
    let green = screen.pixels().filter(|p| p.0[0] == 0 && p.0[1] == 255 && p.0[2] == 0).count();
    assert!(green > screen.pixels().len() / 10, "{green} green pixels");
}

/// A frame OpenGL draws because wgpu cannot draw one program (tests/packs/geometry_stage_beside_wgpu:
/// the terrain's geometry stage): wgpu draws every other step from OpenGL's textures and depth
/// buffers, the water depth-tested against the terrain OpenGL drew, and the two agree there.
#[test]
fn wgpu_draws_the_steps_it_can_beside_opengl() {
    let (report, screen) = render_job("geometry_stage_beside_wgpu");
    assert!(report.renderer.name.starts_with("OpenGL"), "{:?}", report.renderer);
    let gl = report.gl.as_ref().expect("the steps compared");
    let left: Vec<&str> = gl.wgpu_cannot_draw.iter().map(|(step, _)| step.as_str()).collect();
    assert_eq!(left, ["terrain (gbuffers_terrain)"], "{:?}", gl.wgpu_cannot_draw);
    assert!(gl.wgpu_cannot_draw[0].1.contains("a geometry stage (gbuffers_terrain.gsh)"), "{:?}", gl.wgpu_cannot_draw);
    let compared: Vec<&str> = gl.steps.iter().map(|s| s.pass.as_str()).collect();
    assert!(compared.contains(&"water (gbuffers_water)") && compared.contains(&"composite"), "{compared:?}");
    assert!(gl.steps.iter().all(|s| s.pixels_over_1_255.values().all(|&n| n == 0)), "{:?}", gl.steps);
    assert_eq!(report.gl_disagreement, None);
    // The report names who drew each step.
    use tidepack_harness::job::StepRenderers;
    let by = |step: &str| report.step_renderers.iter().find(|(s, _)| s == step).map(|(_, by)| *by);
    assert_eq!(by("terrain (gbuffers_terrain)"), Some(StepRenderers::OpenGl));
    assert_eq!(by("water (gbuffers_water)"), Some(StepRenderers::OpenGlWithWgpu));
    assert_eq!(by("composite"), Some(StepRenderers::OpenGlWithWgpu));
    // The terrain's green, and the water halved by composite where it lies in front of it.
    let green = screen.pixels().filter(|p| p.0 == [0, 255, 0, 255]).count();
    let water = screen.pixels().filter(|p| p.0 == [0, 0, 128, 255]).count();
    assert!(green > 1000 && water > screen.pixels().len() / 2, "{green} green, {water} water pixels");
}

/// The shadow pass drawn by OpenGL alone (tests/packs/shadow_geometry_stage_beside_wgpu: its
/// geometry stage): wgpu's composite reads the shadow map OpenGL drew, handed over after each
/// shadow step, and shows its depth as OpenGL's does.
#[test]
fn wgpu_reads_the_shadow_map_opengl_drew() {
    let (report, screen) = render_job("shadow_geometry_stage_beside_wgpu");
    let gl = report.gl.as_ref().expect("the steps compared");
    let left: Vec<&str> = gl.wgpu_cannot_draw.iter().map(|(step, _)| step.as_str()).collect();
    assert_eq!(left, ["shadow terrain (shadow)", "shadow water (shadow)"], "{:?}", gl.wgpu_cannot_draw);
    assert!(gl.steps.iter().any(|s| s.pass == "composite"), "{:?}", gl.steps);
    assert!(gl.steps.iter().all(|s| s.pixels_over_1_255.values().all(|&n| n == 0)), "{:?}", gl.steps);
    // The shadow map's depth, nearer than its far plane where the terrain and water drew.
    let drawn = screen.pixels().filter(|p| p.0[0] < 250).count();
    assert!(drawn > 1000, "{drawn} pixels of the shadow map hold a surface");
}

/// Outputs declared at locations no draw buffer has (tests/packs/outputs_past_draw_buffers:
/// 8 and 9, never written) are dropped as the loaders drop them: wgpu draws the frame and
/// OpenGL agrees.
#[test]
fn outputs_past_the_draw_buffers_are_dropped() {
    let (report, screen) = render_job("outputs_past_draw_buffers");
    assert!(report.failed_programs.is_empty(), "{:?}", report.failed_programs);
    assert_eq!(report.renderer.name, "wgpu", "{:?}", report.renderer);
    assert_eq!(report.gl_disagreement, None);
    assert!(report.step_renderers.iter().all(|(_, by)| *by == tidepack_harness::job::StepRenderers::WgpuWithOpenGl), "{:?}", report.step_renderers);
    assert!(report.gl.as_ref().is_some_and(|g| g.refused.is_none() && !g.steps.is_empty()), "{:?}", report.gl);
    assert_eq!(screen.get_pixel(screen.width() / 2, screen.height() / 2).0, [0, 0, 255, 255]);
}

/// A buffer block both stages declare at one binding (tests/packs/shared_buffer_block) is one
/// buffer both see: wgpu draws the program, and OpenGL agrees.
#[test]
fn a_buffer_block_both_stages_declare_is_one_buffer() {
    let (report, _) = render_job_with("shared_buffer_block", Configuration { loader: Loader::Iris, ..Configuration::default() });
    assert!(report.failed_programs.is_empty(), "{:?}", report.failed_programs);
    assert!(report.renderer.wgpu_cannot_draw.is_none(), "{:?}", report.renderer.wgpu_cannot_draw);
    let gl = report.gl.as_ref().expect("an OpenGL frame");
    assert!(gl.refused.is_none(), "{:?}", gl.refused);
    assert!(gl.steps.iter().all(|s| s.pixels_over_1_255.values().all(|&n| n == 0)), "{:?}", gl.steps);
    assert!(report.step_renderers.iter().any(|(step, renderer)| step.starts_with("terrain") && matches!(renderer, tidepack_harness::job::StepRenderers::WgpuWithOpenGl)), "{:?}", report.step_renderers);
}

/// Iris's buffer object shared by two programs (tests/packs/buffer_across_programs): the
/// terrain stores blue into it, and composite reads that back over the whole screen. OpenGL
/// holds it across the frame and draws both; wgpu, which gives each program a buffer of its
/// own, says why it does not.
#[test]
fn a_buffer_object_written_by_one_program_is_read_by_the_next() {
    let (report, screen) = render_job_with("buffer_across_programs", Configuration { loader: Loader::Iris, ..Configuration::default() });
    assert!(report.failed_programs.is_empty(), "{:?}", report.failed_programs);
    assert!(report.renderer.wgpu_cannot_draw.as_deref().is_some_and(|why| why.contains("other programs share")), "{:?}", report.renderer);
    assert_eq!(screen.get_pixel(screen.width() / 2, screen.height() / 2).0, [0, 0, 255, 255]);
}

/// A storage image (tests/packs/storage_image: an Iris custom image that composite stores into)
/// beside samplers of four other kinds: OpenGL draws the program, each sampler on a texture
/// unit of its own and the image on an image unit, reading zero as wgpu's empty textures do; the
/// renderers agree on every other step, and the report says the image is not held.
#[test]
fn a_storage_image_is_drawn_by_opengl_beside_samplers_of_other_kinds() {
    let (report, screen) = render_job("storage_image");
    assert!(report.failed_programs.is_empty(), "{:?}", report.failed_programs);
    let gl = report.gl.as_ref().expect("an OpenGL frame");
    assert!(gl.refused.is_none(), "{:?}", gl.refused);
    assert!(gl.steps.iter().all(|s| s.pixels_over_1_255.values().all(|&n| n == 0)), "{:?}", gl.steps);
    assert!(report.step_renderers.iter().any(|(step, renderer)| step == "composite" && matches!(renderer, tidepack_harness::job::StepRenderers::OpenGl)), "{:?}", report.step_renderers);
    assert!(report.not_modelled.iter().any(|n| n.starts_with("image marks in composite: bound empty")), "{:?}", report.not_modelled);
    assert_eq!(screen.get_pixel(screen.width() / 2, screen.height() - 10).0, [0, 255, 0, 255]);
}

/// Compute stages (tests/packs/compute): composite.csh runs before composite's own stages and
/// changes colortex0 in place through `colorimg0`, one invocation per pixel; composite1_a.csh,
/// a program of compute stages alone on fixed work groups, runs after composite on the texture
/// composite wrote. OpenGL dispatches them and draws the frame; each compute step is its own.
/// Under Iris, begin.csh (Iris's begin pass) runs first.
#[test]
fn compute_stages_run_before_their_program_and_write_the_buffer_in_place() {
    let pack = pack("compute", Loader::default());
    assert!(pack.failed.is_empty(), "{:?}", pack.failed);
    let scene = scene("case4_above_near");
    let mesh = mesh::build(&scene, &pack);
    let plan = FramePlan::new(&pack, &scene, &mesh, ScreenOutput::AsLoader);
    let labels: Vec<&str> = plan.steps.iter().map(|s| s.label.as_str()).collect();
    assert_eq!(
        labels,
        [
            "sky (the loader's own)",
            "terrain (gbuffers_terrain)",
            "depth copy",
            "water (gbuffers_terrain)",
            "composite (composite.csh)",
            "composite",
            "composite1 (composite1_a.csh)",
            "colortex0 to the screen (no final)"
        ]
    );
    let (report, screen) = render_job("compute");
    assert!(report.failed_programs.is_empty(), "{:?}", report.failed_programs);
    assert!(report.renderer.name.starts_with("OpenGL"), "{:?}", report.renderer);
    assert!(report.renderer.wgpu_cannot_draw.as_deref().is_some_and(|why| why.contains("composite.csh: a compute stage")), "{:?}", report.renderer);
    assert!(!report.not_modelled.iter().any(|n| n.contains("compute")), "{:?}", report.not_modelled);
    let terrain = screen.get_pixel(screen.width() / 2, screen.height() - 10).0;
    assert!(terrain[..2] == [255, 255] && terrain[2].abs_diff(128) <= 1, "{terrain:?}");
    let row = screen.height() - 1;
    assert_eq!(screen.get_pixel(3, row).0, [0, 0, 255, 255]);
    assert_ne!(screen.get_pixel(16, row).0, [0, 0, 255, 255]);
    assert_eq!(screen.get_pixel(35, row).0, terrain, "OptiFine runs no begin pass");
    // Iris runs begin.csh first, at the start of the frame.
    let iris = Configuration { loader: Loader::Iris, ..Configuration::default() };
    let pack = AnyPack::load(&root().join("tests/packs/compute"), &iris).unwrap_or_else(|e| panic!("{e}"));
    let plan = FramePlan::new(&pack, &scene, &mesh, ScreenOutput::AsLoader);
    assert_eq!(plan.steps[0].label, "begin (begin.csh)");
    let (report, screen) = render_job_with("compute", iris);
    assert!(report.failed_programs.is_empty(), "{:?}", report.failed_programs);
    assert_eq!(screen.get_pixel(35, row).0, [255, 255, 255, 255]);
}

/// A compute stage dispatched over more work groups along x than llvmpipe takes at once
/// (tests/packs/many_work_groups: 230,400 against 65,535) runs in parts that see the group ids
/// and count of the whole dispatch: every pixel of the screen is red.
#[test]
fn a_dispatch_past_the_drivers_group_count_runs_in_parts_as_one() {
    let (report, screen) = render_job("many_work_groups");
    assert!(report.failed_programs.is_empty(), "{:?}", report.failed_programs);
    let red = screen.pixels().filter(|p| p.0 == [255, 0, 0, 255]).count();
    assert_eq!(red, screen.pixels().len(), "pixels the parts left unpainted");
}

/// shadowcomp draws after the shadow pass into the shadow colour buffers, reading them as the
/// shadow pass left them (tests/packs/shadow_composite: shadowcolor0 becomes its complement and
/// shadowcolor1 its copy); then shadowcomp1.csh turns shadowcolor1 into the complement too,
/// through `shadowcolorimg1`. Both halves of the screen show the complement of the shadow
/// pass's colour, and the colour buffers only they read are made.
#[test]
fn shadowcomp_draws_into_the_shadow_colour_buffers_reading_them_as_they_were() {
    let pack = pack("shadow_composite", Loader::default());
    assert!(pack.failed.is_empty() && pack.shadow_pass, "{:?}", pack.failed);
    let scene = scene("case4_above_near");
    let mesh = mesh::build(&scene, &pack);
    let plan = FramePlan::new(&pack, &scene, &mesh, ScreenOutput::AsLoader);
    let labels: Vec<&str> = plan.steps.iter().map(|s| s.label.as_str()).collect();
    assert_eq!(labels[..5], ["shadow terrain (shadow)", "shadowtex0 to shadowtex1", "shadow water (shadow)", "shadowcomp", "shadowcomp1 (shadowcomp1.csh)"]);
    assert!(plan.buffers.contains(&9) && plan.buffers.contains(&10), "the colour buffers only shadowcomp reads are made: {:?}", plan.buffers);
    let (report, screen) = render_job("shadow_composite");
    assert!(report.failed_programs.is_empty() && report.gl_disagreement.is_none(), "{:?} {:?}", report.failed_programs, report.gl_disagreement);
    assert!(!report.not_modelled.iter().any(|n| n.contains("shadowcomp")), "{:?}", report.not_modelled);
    let row = screen.height() / 2;
    let (left, right) = (screen.get_pixel(10, row).0, screen.get_pixel(screen.width() - 10, row).0);
    // The shadow pass draws (0.25, 0.5, 0.75): its complement is (191, 127, 64).
    for (channel, complement) in [191u8, 127, 64].into_iter().enumerate() {
        assert!(left[channel].abs_diff(complement) <= 1 && right[channel].abs_diff(complement) <= 1, "{left:?} and {right:?}, not both the complement");
    }
}

/// A compute stage needing more `shared` memory than llvmpipe gives a work group
/// (tests/packs/large_shared_memory: 36,868 bytes against 32,768) runs with its `shared`
/// variables in storage buffers, one slice per group, and the report lists the rewrite: every
/// group sees its own table and its invocations see each other's writes, so the screen is green.
#[test]
fn shared_memory_past_llvmpipes_limit_is_kept_in_buffers_one_slice_per_group() {
    let (report, screen) = render_job("large_shared_memory");
    assert!(report.failed_programs.is_empty(), "{:?}", report.failed_programs);
    assert!(report.gl_rewrites.iter().any(|r| r.starts_with("composite: composite.csh: `shared` variables of 36868 bytes")), "{:?}", report.gl_rewrites);
    let green = screen.pixels().filter(|p| p.0 == [0, 255, 0, 255]).count();
    assert_eq!(green, screen.pixels().len(), "pixels of groups that saw another's table or an unwritten row");
}

/// Under Iris the storage image of tests/packs/storage_image is the custom image its
/// shaders.properties declares: composite stores 1 into each of its 16x16 texels, and final
/// reads it back through `markSampler`, so the screen is white; OpenGL holds it and draws both.
#[test]
fn a_custom_image_is_held_under_iris_and_read_back_through_its_sampler() {
    let (report, screen) = render_job_with("storage_image", Configuration { loader: Loader::Iris, ..Configuration::default() });
    assert!(report.failed_programs.is_empty(), "{:?}", report.failed_programs);
    assert!(!report.not_modelled.iter().any(|n| n.contains("marks")), "{:?}", report.not_modelled);
    assert!(report.step_renderers.iter().any(|(step, renderer)| step == "final" && matches!(renderer, tidepack_harness::job::StepRenderers::OpenGl)), "{:?}", report.step_renderers);
    assert_eq!(screen.get_pixel(screen.width() / 2, screen.height() - 10).0, [255, 255, 255, 255]);
}

/// A program naga refuses and OpenGL compiles (tests/packs/beyond_naga: textureLod on an
/// unsigned-integer sampler) loads: OpenGL draws the frame, and the report gives naga's reason
/// at the pack's file and line, in GLSL's words.
#[test]
fn a_program_only_opengl_reads_is_drawn_by_opengl() {
    let (report, screen) = render_job("beyond_naga");
    assert!(report.failed_programs.is_empty(), "{:?}", report.failed_programs);
    assert!(report.renderer.name.starts_with("OpenGL"), "{:?}", report.renderer);
    let why = report.renderer.wgpu_cannot_draw.as_deref().unwrap_or_default();
    assert!(why.contains("final.fsh:9") && why.contains("sampling an integer texture"), "{why}");
    assert_eq!(screen.get_pixel(screen.width() / 2, screen.height() / 2).0, [0, 255, 0, 255]);
}
