//! One scene rendered to files: what `tidepack render` runs. The final image (and optionally
//! the buffers composite reads) as PNG, and a JSON report with the time of every pass, the
//! adapter, the resolution, the dialect and the options in force; optionally the same frame
//! through the OpenGL driver and the comparison of the two.

use std::collections::BTreeMap;
use std::path::PathBuf;

use serde::Serialize;
use tidepack_pack::Dialect;

use crate::gpu::{self, StepReport};
use crate::images::{self, FloatImage, OVER_1_255};
use crate::program::{self, LoadedPack, PackSelection};
use tidepack_scene::scene::Scene;
use crate::{Gpu, HarnessError, Loader, gl, uniforms};
use crate::any_pack::{AnyPack, ScreenOutput};
use tidepack_scene::mesh;

/// What to render and where to put it.
#[derive(Clone, Debug)]
pub struct RenderJob {
    pub scene: PathBuf,
    /// The folder with pack.toml and shaders/.
    pub source_dir: PathBuf,
    pub dialect: Dialect,
    pub profile: Option<String>,
    /// `NAME` → value as written (`on`/`off` for switches).
    pub options: Vec<(String, String)>,
    /// The loader whose drawing the frame imitates.
    pub loader: Loader,
    /// Distant Horizons beside the loader (Iris).
    pub distant_horizons: bool,
    pub out_dir: PathBuf,
    /// Also write colortex0, colortex4, depthtex0 and depthtex1.
    pub buffers: bool,
    /// Also render through the OpenGL driver and compare.
    pub gl: bool,
    /// Also render the pack specialised for the scene (`build --scene`) and report its
    /// composite time against the general pack's.
    pub specialise: bool,
}

/// What every render report starts with: the scene, the loader imitated and the adapter.
#[derive(Clone, Debug, Serialize)]
pub struct RenderedScene {
    pub scene: String,
    pub scene_file: String,
    pub resolution: [u32; 2],
    /// The loader imitated (`optifine-1.12.2`, `iris`, ...).
    pub loader: String,
    pub adapter: AdapterReport,
}

impl RenderedScene {
    fn new(scene: &Scene, job_scene: &std::path::Path, loader: Loader, gpu: &Gpu) -> RenderedScene {
        let a = &gpu.adapter;
        RenderedScene {
            scene: scene.name.clone(),
            scene_file: job_scene.display().to_string(),
            resolution: scene.resolution,
            loader: loader.to_string(),
            adapter: AdapterReport {
                name: a.name.clone(),
                backend: format!("{:?}", a.backend),
                device_type: format!("{:?}", a.device_type),
                driver: format!("{} {}", a.driver, a.driver_info).trim().to_string(),
            },
        }
    }

    /// `case4_above_near at 640x360 (<what>) on llvmpipe (Vulkan, Cpu)`.
    pub fn describe(&self, what: &str) -> String {
        let a = &self.adapter;
        format!("{} at {}x{} ({what}) on {} ({}, {})", self.scene, self.resolution[0], self.resolution[1], a.name, a.backend, a.device_type)
    }
}

/// The JSON report (`<scene>.json`).
#[derive(Clone, Debug, Serialize)]
pub struct RenderReport {
    #[serde(flatten)]
    pub rendered: RenderedScene,
    /// `120` or `330`, as `--dialect` takes it.
    pub dialect: String,
    pub profile: String,
    /// Every option value in force (profile, then `--set`).
    pub options: std::collections::BTreeMap<String, String>,
    /// `gpu` when the adapter has timestamp queries, else `wall`.
    pub timing_source: String,
    pub passes: Vec<PassReport>,
    /// Composite time over the one-tap pass-through composite's, from the same frame.
    pub composite_over_passthrough: Option<f64>,
    /// Pixels of the composite output (RGBA32F) that are NaN or infinite.
    pub non_finite_pixels: usize,
    pub gl: Option<GlComparison>,
    pub specialisation: Option<SpecialisationReport>,
    /// Files written, relative to the output folder.
    pub files: Vec<String>,
}

#[derive(Clone, Debug, Serialize)]
pub struct AdapterReport {
    pub name: String,
    pub backend: String,
    pub device_type: String,
    pub driver: String,
}

#[derive(Clone, Debug, Serialize)]
pub struct PassReport {
    pub pass: String,
    /// GPU time when available, else wall time.
    pub ms: f64,
    pub gpu_ms: Option<f64>,
    pub wall_ms: f64,
}

#[derive(Clone, Debug, Serialize)]
pub struct GlComparison {
    pub renderer: String,
    /// Largest difference per channel (RGBA, 0..1 after clamping) between the OpenGL and wgpu
    /// images.
    pub max_difference: [f32; 4],
    /// Pixels differing by more than 1/255 in some colour channel.
    pub pixels_over_1_255: usize,
}

/// The pack specialised for a scene against the general pack, on the same scene.
#[derive(Clone, Debug, Serialize)]
pub struct SpecialisationReport {
    /// Uniforms folded into constants.
    pub folded: Vec<String>,
    /// Timed frames per pack (after one warm-up frame each), alternating between the packs.
    pub frames: usize,
    /// Median composite time of each pack, and of the pass-through composite, in ms.
    pub general_ms: f64,
    pub specialised_ms: f64,
    pub passthrough_ms: f64,
    /// general_ms / specialised_ms.
    pub speedup: f64,
    /// Largest difference per channel between the two final images: folding must not change
    /// the picture.
    pub max_difference: [f32; 4],
}

/// Renders `scene` with `general` (the pack `selection` loads) and with the pack specialised
/// for the scene, `frames` timed frames each in alternating rounds (so a change in machine load
/// hits both), and compares composite time and images.
pub fn specialisation_speedup(
    gpu: &Gpu,
    selection: &PackSelection,
    general: &LoadedPack,
    scene: &Scene,
    scene_label: &str,
    frames: usize,
) -> Result<SpecialisationReport, HarnessError> {
    let spec = uniforms::scene_specialisation(scene, scene_label);
    let specialised = if general.pack.distant_horizons {
        program::load_with_distant_horizons(selection, Some(&spec))?
    } else {
        program::load_for(selection, Some(&spec), general.loader())?
    };
    const ROUNDS: usize = 3;
    let per_round = frames.div_ceil(ROUNDS).max(1);
    let (mut general_ms, mut specialised_ms, mut passthrough_ms) = (Vec::new(), Vec::new(), Vec::new());
    let mut images = (None, None);
    for _ in 0..ROUNDS {
        for (pack, samples, image) in [(general, &mut general_ms, &mut images.0), (&specialised, &mut specialised_ms, &mut images.1)] {
            let frame = crate::render_wgpu_repeated(gpu, pack, scene, per_round + 1)?;
            // The first frame of each round pays for llvmpipe's lazy shader compilation.
            let composite = frame.passes.iter().find(|p| p.pass == "composite").ok_or_else(|| HarnessError::Pack("no composite pass".into()))?;
            samples.extend_from_slice(&composite.samples_ms[1..]);
            passthrough_ms.extend_from_slice(&frame.timing.passthrough_samples_ms[1..]);
            *image = Some(frame.image);
        }
    }
    let (Some(general_image), Some(specialised_image)) = images else {
        return Err(HarnessError::Wgpu("no frame was rendered".into()));
    };
    let (general_ms, specialised_ms) = (images::median(&general_ms), images::median(&specialised_ms));
    Ok(SpecialisationReport {
        folded: specialised.folded_uniforms.clone(),
        frames: per_round * ROUNDS,
        general_ms,
        specialised_ms,
        passthrough_ms: images::median(&passthrough_ms),
        speedup: general_ms / specialised_ms,
        max_difference: images::max_channel_difference(&general_image, &specialised_image),
    })
}

/// Renders the job's scene and writes the files; returns the report (also written as JSON).
pub fn run(job: &RenderJob) -> Result<RenderReport, HarnessError> {
    let scene = Scene::load(&job.scene)?;
    let selection = PackSelection {
        source_dir: job.source_dir.clone(),
        dialect: job.dialect,
        profile: job.profile.clone(),
        options: job.options.clone(),
    };
    let pack = if job.distant_horizons { program::load_with_distant_horizons(&selection, None)? } else { program::load_for(&selection, None, job.loader)? };
    let gpu = Gpu::new()?;
    let frame = crate::render_wgpu(&gpu, &pack, &scene)?;

    let stem = file_stem(&scene.name);
    std::fs::create_dir_all(&job.out_dir)
        .map_err(|e| HarnessError::Io(format!("cannot create {}: {e}", job.out_dir.display())))?;
    let mut files = Vec::new();
    let mut write = |suffix: &str, image: &FloatImage| -> Result<(), HarnessError> {
        let name = format!("{stem}{suffix}.png");
        image.write_png(&job.out_dir.join(&name), false)?;
        files.push(name);
        Ok(())
    };
    write("", &frame.image)?;
    if job.buffers {
        for b in [0u8, 4] {
            if let Some(image) = frame.buffers.get(&b) {
                write(&format!(".colortex{b}"), image)?;
            }
        }
        write(".depthtex0", &frame.depth0.depth_for_viewing())?;
        write(".depthtex1", &frame.depth1.depth_for_viewing())?;
    }
    let gl = if job.gl {
        let ctx = gl::context()?;
        let gl_frame = crate::render_gl(&ctx, &pack, &scene)?;
        write(".gl", &gl_frame.image)?;
        Some(GlComparison {
            renderer: ctx.info().to_string(),
            max_difference: images::max_channel_difference(&frame.image, &gl_frame.image),
            pixels_over_1_255: images::count_differing(&frame.image, &gl_frame.image, OVER_1_255),
        })
    } else {
        None
    };

    let specialisation = if job.specialise {
        Some(specialisation_speedup(&gpu, &selection, &pack, &scene, &job.scene.display().to_string(), SPECIALISATION_FRAMES)?)
    } else {
        None
    };

    let mut passes: Vec<PassReport> = frame.passes.iter().map(pass_report).collect();
    let passthrough_ms = frame.timing.passthrough_ms;
    passes.push(PassReport { pass: PASSTHROUGH.into(), ms: passthrough_ms, gpu_ms: gpu.timestamps.then_some(passthrough_ms), wall_ms: passthrough_ms });
    let ratio = match passes.iter().find(|p| p.pass == "composite") {
        Some(c) if passthrough_ms > 0.0 => Some(c.ms / passthrough_ms),
        _ => None,
    };
    let json_name = format!("{stem}.json");
    files.push(json_name.clone());
    let report = RenderReport {
        rendered: RenderedScene::new(&scene, &job.scene, pack.loader(), &gpu),
        dialect: match job.dialect {
            Dialect::Glsl120 => "120",
            Dialect::Glsl330 => "330",
        }
        .to_string(),
        profile: pack.profile.clone(),
        options: pack.options.iter().map(|(k, v)| (k.clone(), v.to_string())).collect(),
        timing_source: if gpu.timestamps { "gpu" } else { "wall" }.to_string(),
        passes,
        composite_over_passthrough: ratio,
        non_finite_pixels: frame.image.non_finite(),
        gl,
        specialisation,
        files,
    };
    let json = serde_json::to_string_pretty(&report).map_err(|e| HarnessError::Io(format!("report: {e}")))?;
    let json_path = job.out_dir.join(&json_name);
    std::fs::write(&json_path, json + "\n").map_err(|e| HarnessError::Io(format!("cannot write {}: {e}", json_path.display())))?;
    Ok(report)
}

/// A released pack rendered on a scene: what `tidepack render --pack` runs.
#[derive(Clone, Debug)]
pub struct AnyPackJob {
    pub scene: PathBuf,
    /// The pack folder or zip.
    pub pack: PathBuf,
    /// The loader, dimension, profile and option values to render with.
    pub configuration: tidepack_loader::Configuration,
    pub out_dir: PathBuf,
    /// Also write every colour buffer and both depth buffers as final read them.
    pub buffers: bool,
    /// Also render through the OpenGL driver and compare every step's textures.
    pub gl: bool,
    /// Frames to render for the timings (medians leave out the first).
    pub frames: usize,
    /// A folder of blessed screens (`<scene>.png`) to compare the screen with, by mean FLIP.
    pub expect: Option<PathBuf>,
    /// Write the screen into `expect` instead of comparing.
    pub bless: bool,
    /// The largest mean FLIP against the blessed screen that passes.
    pub max_flip: f64,
    /// With `gl`: the most pixels of one texture after one step that may differ between the
    /// two renderers by more than 1/255 before the run counts as a disagreement; `None` for
    /// [`gl_max_differing_pixels`] of the screen.
    pub gl_max_pixels: Option<usize>,
}

/// Pixels of one texture after one step that may differ between wgpu and OpenGL by more than
/// 1/255 before the renderers are said to disagree, on a screen of `width` x `height`: one in
/// 10,000, and at least 16. Where a lookup's result jumps, the last bit of its coordinate
/// decides (a nearest texel on a sprite's edge, a mipmap level chosen from derivatives a hair
/// apart); a wrong binding or mapping moves thousands.
pub fn gl_max_differing_pixels(width: u32, height: u32) -> usize {
    (width as usize * height as usize / 10_000).max(16)
}

/// Where wgpu and OpenGL part: the first step, in frame order, with a texture over the limit.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Disagreement {
    pub pass: String,
    /// The fragment stage's file of the step's program, when the step ran one.
    pub file: Option<String>,
    pub texture: String,
    /// Pixels differing by more than 1/255 in some colour channel.
    pub pixels: usize,
    /// Those of them that are the pack's own arithmetic noise
    /// ([`GlStepComparison::sensitive_pixels`]), which the limit does not count.
    pub sensitive: usize,
    /// Those of them where GLSL leaves the result undefined
    /// ([`GlStepComparison::undefined_pixels`]), which the limit does not count either.
    pub undefined: usize,
    /// The largest difference of any channel, in 1/255.
    pub max_difference_255: f32,
    /// The limit it passed.
    pub max_pixels: usize,
}

impl GlStepsComparison {
    /// The first step where a texture differs between the renderers on more than `max_pixels`
    /// pixels; None when they agree throughout (or OpenGL refused the pack, so nothing was
    /// compared).
    pub fn first_disagreement(&self, max_pixels: usize) -> Option<Disagreement> {
        self.steps.iter().find_map(|step| {
            let sensitive = |texture: &str| step.sensitive_pixels.get(texture).copied().unwrap_or(0);
            let undefined = |texture: &str| step.undefined_pixels.get(texture).copied().unwrap_or(0);
            step.pixels_over_1_255.iter().find(|(texture, n)| **n - sensitive(texture) - undefined(texture) > max_pixels).map(|(texture, &pixels)| Disagreement {
                pass: step.pass.clone(),
                file: None,
                texture: texture.clone(),
                pixels,
                sensitive: sensitive(texture),
                undefined: undefined(texture),
                max_difference_255: step.max_difference_255.get(texture).map_or(f32::NAN, |d| d.iter().copied().fold(0.0, f32::max)),
                max_pixels,
            })
        })
    }

    /// Takes the steps wgpu could not draw (`cannot_draw`, per step) out of the comparison into
    /// `wgpu_cannot_draw`: wgpu's textures there are OpenGL's own.
    fn set_aside(&mut self, cannot_draw: &[Option<String>]) {
        let mut kept = Vec::new();
        for (k, step) in std::mem::take(&mut self.steps).into_iter().enumerate() {
            match cannot_draw.get(k).cloned().flatten() {
                Some(why) => self.wgpu_cannot_draw.push((step.pass, why)),
                None => kept.push(step),
            }
        }
        self.steps = kept;
    }

    /// Records, per step and texture, how many of the pixels where the renderers differ are the
    /// pack's own arithmetic noise ([`noise_pixels`]), from `nudged`: OpenGL's frame drawn
    /// from the same inputs as `gl` with every float uniform, float literal and vertex attribute
    /// nudged, once by each of [`NUDGES`]; and how many of the others GLSL leaves undefined,
    /// from `undefined` ([`undefined_pixels`]).
    fn discount_noise_and_undefined(&mut self, wgpu: &[StepReport], gl: &crate::gl_frame::GlFrame, nudged: &[crate::gl_frame::GlFrame], undefined: &[BTreeMap<String, Vec<bool>>]) {
        for (k, (step, (pass, (_, gl_images)))) in self.steps.iter_mut().zip(wgpu.iter().zip(&gl.steps)).enumerate() {
            for (i, ((name, ours), (_, theirs))) in pass.images.iter().zip(gl_images).enumerate() {
                let moved: Vec<&FloatImage> = nudged.iter().filter_map(|frame| frame.steps.get(k).and_then(|(_, images)| images.get(i)).map(|(_, image)| image)).collect();
                let noise = noise_pixels(ours, theirs, &moved);
                let sensitive = noise.iter().filter(|n| **n).count();
                if sensitive > 0 {
                    step.sensitive_pixels.insert(name.clone(), sensitive);
                }
                let Some(mask) = undefined.get(k).and_then(|step| step.get(name)) else { continue };
                let apart = images::differing_pixels(ours, theirs, OVER_1_255);
                let undefined = apart.iter().zip(mask).zip(&noise).filter(|((a, u), n)| **a && **u && !**n).count();
                if undefined > 0 {
                    step.undefined_pixels.insert(name.clone(), undefined);
                }
            }
        }
    }
}

/// Per pixel, whether `ours` and `theirs` differ there by more than 1/255 as the pack's own
/// arithmetic noise: where `theirs` and one of `moved` (theirs drawn again, each
/// nudged another way) differ too, and those whose [`NOISE_BLOCK`]-pixel block holds such a
/// pixel and has the same mean in both renderers to within 1/255 (the last bits of the
/// arithmetic decide there, as the nudges show, and what they decide averages to the same
/// picture). Where the nudges move more than [`MAX_SENSITIVE_SHARE`] of the image (the step is
/// noise throughout: a dither, a hash of every pixel), those of every block whose means agree,
/// and no other.
fn noise_pixels(ours: &FloatImage, theirs: &FloatImage, moved: &[&FloatImage]) -> Vec<bool> {
    let apart = images::differing_pixels(ours, theirs, OVER_1_255);
    let mut unstable = vec![false; apart.len()];
    for image in moved {
        for (u, m) in unstable.iter_mut().zip(images::differing_pixels(theirs, image, OVER_1_255)) {
            *u |= m;
        }
    }
    let noise_throughout = unstable.iter().filter(|u| **u).count() as f64 > MAX_SENSITIVE_SHARE * unstable.len() as f64;
    // A block's means agree to within 1/255 and what a nudge alone moves that block's mean by.
    let mut nudge_moves_mean = vec![0.0f32; apart.len()];
    for image in moved {
        for (most, d) in nudge_moves_mean.iter_mut().zip(images::block_mean_differences(theirs, image, NOISE_BLOCK)) {
            *most = most.max(d);
        }
    }
    let means_agree: Vec<bool> = images::block_mean_differences(ours, theirs, NOISE_BLOCK).iter().zip(&nudge_moves_mean).map(|(d, nudged)| *d <= OVER_1_255 + nudged).collect();
    let sensitive_blocks = images::blocks_holding(&unstable, ours.width, ours.height, NOISE_BLOCK);
    let noise = (0..apart.len()).map(|i| if noise_throughout { means_agree[i] } else { unstable[i] || (means_agree[i] && sensitive_blocks[i]) });
    apart.iter().zip(noise).map(|(a, n)| *a && n).collect()
}

/// Per step of `traced` (OpenGL's frame drawn with [`crate::gl_frame::Reference::trace_derivatives`])
/// and per texture it wrote: the pixels where the step's implicit derivatives are undefined,
/// because the fragments of their 2x2 quad ran different sequences of implicit-derivative calls
/// (a lookup inside an `if` they take differently). Steps not drawn traced have none.
fn undefined_pixels(traced: &crate::gl_frame::GlFrame) -> Vec<BTreeMap<String, Vec<bool>>> {
    traced
        .steps
        .iter()
        .zip(&traced.traced)
        .map(|((_, images), &was_traced)| {
            let masks = images.iter().map(|(name, image)| (name.clone(), image.pixels.iter().map(|p| p[0] > 0.5).collect()));
            if was_traced { masks.collect() } else { BTreeMap::new() }
        })
        .collect()
}

/// Side of the blocks [`noise_pixels`] compares by their means where a step is noise
/// throughout: 64 pixels, over which a dither of a few levels averages out.
pub const NOISE_BLOCK: u32 = 8;

/// The relative nudge of [`GlStepsComparison::discount_noise_and_undefined`]: 2^-21, four units in the
/// last place of a float, about what two compilers' roundings of the same expression differ by
/// (a fused multiply-add, a reciprocal for a division, another polynomial for `sin`).
pub const NUDGE: f64 = 1.0 / (1u32 << 21) as f64;

/// The nudges OpenGL's frame is drawn again with where the renderers part: up and down by
/// [`NUDGE`] and by twice it, and up by three times it. Which pixels one nudge moves depends on
/// its sign and size as much as on the arithmetic, so each samples other roundings a second
/// compiler may make.
pub const NUDGES: [f64; 5] = [NUDGE, -NUDGE, 2.0 * NUDGE, -2.0 * NUDGE, 3.0 * NUDGE];

/// The largest share of a texture OpenGL may move under [`NUDGE`] for its pixels to be compared
/// one by one: past it the step is noise throughout (grain, a hash of every pixel), compared by
/// block means.
pub const MAX_SENSITIVE_SHARE: f64 = 0.05;

/// The screen against a blessed one.
#[derive(Clone, Debug, Serialize)]
pub struct ExpectedScreen {
    /// The blessed image.
    pub path: String,
    /// Mean FLIP (0: identical, 1: as different as can be); `None` when the screen was blessed.
    pub mean_flip: Option<f64>,
    pub max_flip: f64,
    pub passed: bool,
}

/// One step of the OpenGL frame against the wgpu frame.
#[derive(Clone, Debug, Serialize)]
pub struct GlStepComparison {
    pub pass: String,
    /// Per texture the step wrote: the largest difference of each channel (RGBA), in 1/255.
    pub max_difference_255: BTreeMap<String, [f32; 4]>,
    /// Per texture: pixels differing by more than 1/255 in some channel.
    pub pixels_over_1_255: BTreeMap<String, usize>,
    /// Per texture, when the renderers part there: how many of those pixels are the pack's own
    /// arithmetic noise ([`noise_pixels`]), where the last bit of its arithmetic decides the
    /// result, as GLSL allows compilers to round it.
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    pub sensitive_pixels: BTreeMap<String, usize>,
    /// Per texture, when the renderers part there: how many of the others lie where GLSL
    /// leaves the step's result undefined ([`undefined_pixels`]).
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    pub undefined_pixels: BTreeMap<String, usize>,
}

/// The OpenGL frame of any pack against the wgpu frame.
#[derive(Clone, Debug, Serialize)]
pub struct GlStepsComparison {
    pub renderer: String,
    pub steps: Vec<GlStepComparison>,
    /// Programs OpenGL drew with its own depth range (outputs transform feedback cannot record).
    pub own_depth_mapping: Vec<String>,
    /// What the driver refused (a program that does not compile or link), when it did: then
    /// there are no steps to compare.
    pub refused: Option<String>,
    /// Where OpenGL is the primary renderer: the steps wgpu cannot draw, with why, which OpenGL
    /// alone drew and are not among `steps` (`every step` where wgpu drew none).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub wgpu_cannot_draw: Vec<(String, String)>,
}

/// The renderer whose frame a report's screen, passes and times are.
#[derive(Clone, Debug, Serialize)]
pub struct PrimaryRenderer {
    /// `wgpu`, or `OpenGL (<driver>)` where wgpu cannot draw the frame: then OpenGL draws every
    /// step.
    pub name: String,
    /// Why wgpu cannot draw the frame (a pipeline it refuses, a program naga cannot translate
    /// for it), when OpenGL drew it.
    pub wgpu_cannot_draw: Option<String>,
    /// What OpenGL refused, when it could not draw the frame either and wgpu drew it without
    /// the programs naga cannot read (listed as programs that do not load).
    pub opengl_refused: Option<String>,
}

/// Where NaN or Inf first appeared in a frame.
#[derive(Clone, Debug, Serialize)]
pub struct NonFinite {
    /// The step, as the frame names it (`composite2`, `water (gbuffers_water)`).
    pub step: String,
    /// The fragment stage's file of the step's program, when the step ran one.
    pub file: Option<String>,
    pub texture: String,
    pub pixels: usize,
}

impl std::fmt::Display for NonFinite {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let file = self.file.as_ref().map_or(String::new(), |file| format!(", by {file}"));
        write!(f, "first written at the step {} into {} ({} pixels){file}", self.step, self.texture, self.pixels)
    }
}

/// The first of `passes` that wrote NaN or Inf, with the fragment file of its program.
fn first_non_finite(passes: &[crate::gpu::StepReport], pack: &crate::any_pack::AnyPack) -> Option<NonFinite> {
    passes.iter().find_map(|step| {
        let (texture, &pixels) = step.non_finite.iter().find(|(_, n)| **n > 0)?;
        Some(NonFinite { step: step.pass.clone(), file: step_file(pack, &step.pass), texture: texture.clone(), pixels })
    })
}

/// The fragment stage's file of the program a step ran: a step is labelled with its program's
/// name (`composite2`) or ends with it in brackets (`water (gbuffers_water)`).
fn step_file(pack: &crate::any_pack::AnyPack, step: &str) -> Option<String> {
    pack.programs().find(|p| step == p.name || step.ends_with(&format!("({})", p.name))).map(|p| p.fragment.path.clone())
}

/// The JSON report of [`run_any_pack`] (`<scene>.json`).
#[derive(Clone, Debug, Serialize)]
pub struct AnyPackReport {
    #[serde(flatten)]
    pub rendered: RenderedScene,
    pub pack: String,
    /// The folder the programs came from (`world0` or `""`).
    pub world: String,
    /// The renderer that drew every pass below.
    pub renderer: PrimaryRenderer,
    /// Each pass as it ran, in frame order, with its NaN and Inf counts.
    pub passes: Vec<crate::gpu::StepReport>,
    /// The frame against the one-tap pass-through composite, measured in the same run.
    pub timing: crate::gpu::FrameTiming,
    pub expected: Option<ExpectedScreen>,
    /// Pixels of the screen that are NaN or infinite.
    pub non_finite_pixels: usize,
    /// The first step that wrote NaN or Inf into a buffer, when one did.
    pub first_non_finite: Option<NonFinite>,
    /// What the pack uses that the frame did not imitate.
    pub not_modelled: Vec<String>,
    /// Programs the loader would run that did not load, with why.
    pub failed_programs: Vec<(String, String)>,
    /// How many of the pack's own programs the frame loaded: 0 where the loader's shading
    /// alone draws it (a pack whose programs sit where this loader does not look).
    pub pack_programs: usize,
    pub gl: Option<GlStepsComparison>,
    /// Where the renderers part beyond the job's limit, if they do.
    pub gl_disagreement: Option<Disagreement>,
    /// With `gl`: what the text given to OpenGL had rewritten of what only lenient compilers
    /// accept (`program: path:line: what`), and of what passes a limit of the driver's
    /// (`program: path: what`); wgpu draws the program as the lowering reads it.
    pub gl_rewrites: Vec<String>,
    /// Per step, in frame order: which renderer drew it, and whether the other drew it too
    /// and was compared ([`StepRenderers`]).
    pub step_renderers: Vec<(String, StepRenderers)>,
    /// Files written, relative to the output folder.
    pub files: Vec<String>,
}

/// Who drew a step of a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StepRenderers {
    /// wgpu alone (no `--gl`).
    Wgpu,
    /// wgpu, and OpenGL from wgpu's inputs, compared.
    WgpuWithOpenGl,
    /// OpenGL, and wgpu from OpenGL's inputs, compared.
    OpenGlWithWgpu,
    /// OpenGL alone: wgpu cannot draw the step (or, without `--gl`, the frame).
    OpenGl,
}

impl StepRenderers {
    /// Who drew each of `passes`, the primary renderer's steps, given the comparison made.
    fn of(passes: &[StepReport], opengl_primary: bool, gl: Option<&GlStepsComparison>) -> Vec<(String, StepRenderers)> {
        let compared = |step: &str| gl.is_some_and(|g| g.refused.is_none() && g.steps.iter().any(|s| s.pass == step));
        passes
            .iter()
            .map(|p| {
                let by = match (opengl_primary, compared(&p.pass)) {
                    (false, true) => StepRenderers::WgpuWithOpenGl,
                    (false, false) => StepRenderers::Wgpu,
                    (true, true) => StepRenderers::OpenGlWithWgpu,
                    (true, false) => StepRenderers::OpenGl,
                };
                (p.pass.clone(), by)
            })
            .collect()
    }

    /// As the command prints it.
    pub fn describe(self) -> &'static str {
        match self {
            StepRenderers::Wgpu => "wgpu",
            StepRenderers::WgpuWithOpenGl => "wgpu; OpenGL compared",
            StepRenderers::OpenGlWithWgpu => "OpenGL; wgpu compared",
            StepRenderers::OpenGl => "OpenGL alone",
        }
    }
}

/// Renders the job's scene with any pack and writes the files; returns the report (also
/// written as JSON).
pub fn run_any_pack(job: &AnyPackJob) -> Result<AnyPackReport, HarnessError> {
    let scene = Scene::load(&job.scene)?;
    let mut pack = crate::any_pack::AnyPack::load(&job.pack, &job.configuration)?;
    let gpu = Gpu::new()?;
    let mesh = mesh::build(&scene, &pack);
    let wgpu_renderer = PrimaryRenderer { name: "wgpu".into(), wgpu_cannot_draw: None, opengl_refused: None };
    // With OpenGL as the primary renderer: its last frame, which wgpu's steps are drawn from.
    let mut opengl_last = None;
    let (frame, renderer) = match gpu::render(&gpu, &pack, &scene, &mesh, ScreenOutput::AsLoader, job.frames) {
        Ok(frame) => (frame, wgpu_renderer),
        Err(cannot @ (HarnessError::Unsupported(_) | HarnessError::Wgpu(_))) => {
            let by_opengl = gl::context().and_then(|ctx| Ok((opengl_frame(&ctx, &pack, &scene, &mesh, job.frames)?, ctx.info().to_string())));
            match by_opengl {
                Ok(((frame, last), driver)) => {
                    opengl_last = Some(last);
                    (frame, PrimaryRenderer { name: format!("OpenGL ({driver})"), wgpu_cannot_draw: Some(cannot.to_string()), opengl_refused: None })
                }
                // Neither draws it whole: without the programs naga cannot read (they do not
                // load, and the report says so), wgpu may.
                Err(refused) if pack.set_aside_unreadable() => match gpu::render(&gpu, &pack, &scene, &mesh, ScreenOutput::AsLoader, job.frames) {
                    Ok(frame) => (frame, PrimaryRenderer { opengl_refused: Some(refused.to_string()), ..wgpu_renderer }),
                    Err(e) => {
                        // The error is OpenGL's already: its message once.
                        let refused = match refused {
                            HarnessError::Gl(m) => m,
                            other => other.to_string(),
                        };
                        return Err(HarnessError::Gl(format!("{refused}; and wgpu cannot draw the frame: {e}")));
                    }
                },
                Err(HarnessError::NoGlDriver(_)) => return Err(cannot),
                Err(HarnessError::Gl(refused)) => return Err(HarnessError::Gl(format!("{refused}; and wgpu cannot draw the frame: {cannot}"))),
                Err(refused) => return Err(HarnessError::Gl(format!("{refused}; and wgpu cannot draw the frame: {cannot}"))),
            }
        }
        Err(e) => return Err(e),
    };
    let gl_primary = renderer.wgpu_cannot_draw.is_some();
    // The renderers are compared step by step, each step drawn by both from the same inputs, so
    // that the step where they part is the one that differs, not one further down that spreads
    // an earlier step's few pixels: OpenGL draws each step from wgpu's textures
    // (gl_frame::render_from), or, where OpenGL is the primary renderer, wgpu draws each step it
    // can from OpenGL's (gpu::render_from) and leaves the others to it.
    let gl_context = if job.gl { Some(gl::context()?) } else { None };
    // (wgpu's frame drawn from OpenGL's steps, or why wgpu drew none of them), with OpenGL primary.
    let mut stepped = None;
    let mut driver_limit_rewrites: Vec<String> = opengl_last.as_ref().map(|last| last.rewrites.clone()).unwrap_or_default();
    let gl = match (&gl_context, opengl_last) {
        (None, _) => None,
        (Some(ctx), None) => {
            let reference = reference_of(&frame.passes, &frame.depth0, &frame.depth1, 0.0);
            Some((ctx.info().to_string(), crate::gl_frame::render_from(ctx, &pack, &scene, &mesh, ScreenOutput::AsLoader, &reference)))
        }
        (Some(ctx), Some(last)) => {
            stepped = Some(gpu::render_from(&gpu, &pack, &scene, &mesh, ScreenOutput::AsLoader, &last.as_reference(0.0)));
            Some((ctx.info().to_string(), Ok(last)))
        }
    };
    let stem = file_stem(&scene.name);
    std::fs::create_dir_all(&job.out_dir)
        .map_err(|e| HarnessError::Io(format!("cannot create {}: {e}", job.out_dir.display())))?;
    let mut files = Vec::new();
    let mut write = |suffix: &str, image: &FloatImage| -> Result<(), HarnessError> {
        let name = format!("{stem}{suffix}.png");
        image.write_png(&job.out_dir.join(&name), false)?;
        files.push(name);
        Ok(())
    };
    write("", &frame.image)?;
    let mut rgba8_files = Vec::new();
    let mut write_rgba8 = |suffix: &str, width: u32, height: u32, rgba: &[u8]| -> Result<(), HarnessError> {
        let name = format!("{stem}{suffix}.png");
        images::write_rgba8_png(&job.out_dir.join(&name), width, height, rgba)?;
        rgba8_files.push(name);
        Ok(())
    };
    if job.buffers {
        for (b, image) in &frame.buffers {
            write(&format!(".colortex{b}"), image)?;
        }
        write(".depthtex0", &frame.depth0.depth_for_viewing())?;
        write(".depthtex1", &frame.depth1.depth_for_viewing())?;
    }
    let gl_max_pixels = job.gl_max_pixels.unwrap_or_else(|| gl_max_differing_pixels(frame.image.width, frame.image.height));
    let gl = match (gl, stepped) {
        // wgpu drew none of the steps from OpenGL's (its textures cannot be made, say): nothing
        // is compared, and the report says why.
        (Some((renderer, _)), Some(Err(cannot))) => {
            Some(GlStepsComparison { renderer, steps: Vec::new(), own_depth_mapping: Vec::new(), refused: None, wgpu_cannot_draw: vec![("every step".into(), cannot.to_string())] })
        }
        (Some((renderer, Ok(gl_frame))), stepped) => {
            let (wgpu_frame, cannot_draw) = match &stepped {
                Some(Ok(stepped)) => (&stepped.frame, stepped.cannot_draw.as_slice()),
                _ => (&frame, &[][..]),
            };
            write(".gl", &gl_frame.image)?;
            driver_limit_rewrites.extend(gl_frame.rewrites.iter().filter(|r| !driver_limit_rewrites.contains(r)).cloned().collect::<Vec<_>>());
            let mut comparison = compare_steps(renderer, &wgpu_frame.passes, &gl_frame)?;
            let mut nudged = Vec::new();
            let mut undefined = Vec::new();
            if let (Some(ctx), Some(_)) = (&gl_context, comparison.first_disagreement(gl_max_pixels)) {
                // OpenGL again, nudged, each step from the inputs it had in the frame compared.
                nudged = NUDGES
                    .iter()
                    .map(|&nudge| {
                        let reference = if gl_primary {
                            gl_frame.as_reference(nudge)
                        } else {
                            reference_of(&wgpu_frame.passes, &wgpu_frame.depth0, &wgpu_frame.depth1, nudge)
                        };
                        crate::gl_frame::render_from(ctx, &pack, &scene, &mesh.nudged(nudge as f32), ScreenOutput::AsLoader, &reference)
                    })
                    .collect::<Result<Vec<_>, _>>()?;
                // And once traced, from the same inputs.
                let reference = if gl_primary { gl_frame.as_reference(0.0) } else { reference_of(&wgpu_frame.passes, &wgpu_frame.depth0, &wgpu_frame.depth1, 0.0) };
                // Where the driver refuses a traced text, no pixel is taken for undefined.
                match crate::gl_frame::render_from(ctx, &pack, &scene, &mesh, ScreenOutput::AsLoader, &crate::gl_frame::Reference { trace_derivatives: true, ..reference }) {
                    Ok(traced) => undefined = undefined_pixels(&traced),
                    Err(HarnessError::Gl(_)) => {}
                    Err(e) => return Err(e),
                }
                comparison.discount_noise_and_undefined(&wgpu_frame.passes, &gl_frame, &nudged, &undefined);
            }
            comparison.set_aside(cannot_draw);
            // Where they part: both renderers' texture and the pixels over 1/255, to look at
            // (white where they count against the limit, grey where they are the pack's noise).
            if let Some(parted) = comparison.first_disagreement(gl_max_pixels) {
                let step = wgpu_frame.passes.iter().position(|p| p.pass == parted.pass).expect("the step was compared");
                let image_of = |images: &[(String, FloatImage)]| images.iter().find(|(name, _)| *name == parted.texture).map(|(_, i)| i.clone());
                if let (Some(ours), Some(theirs)) = (image_of(&wgpu_frame.passes[step].images), image_of(&gl_frame.steps[step].1)) {
                    let moved: Vec<FloatImage> = nudged.iter().filter_map(|frame| frame.steps.get(step).and_then(|(_, images)| image_of(images))).collect();
                    let undefined_here = undefined.get(step).and_then(|masks| masks.get(&parted.texture));
                    let noise: Vec<bool> = noise_pixels(&ours, &theirs, &moved.iter().collect::<Vec<_>>())
                        .iter()
                        .enumerate()
                        .map(|(i, n)| *n || undefined_here.is_some_and(|mask| mask[i]))
                        .collect();
                    write(".parted.wgpu", &ours)?;
                    write(".parted.opengl", &theirs)?;
                    write_rgba8(".parted.mask", ours.width, ours.height, &images::differing_mask_rgba8(&ours, &theirs, OVER_1_255, &noise))?;
                }
            }
            Some(comparison)
        }
        // The driver refusing a program is a finding about the pack, reported with the frame.
        (Some((renderer, Err(HarnessError::Gl(refused)))), _) => {
            Some(GlStepsComparison { renderer, steps: Vec::new(), own_depth_mapping: Vec::new(), refused: Some(refused), wgpu_cannot_draw: Vec::new() })
        }
        (Some((_, Err(e))), _) => return Err(e),
        (None, _) => None,
    };
    let expected = match &job.expect {
        Some(dir) => Some(compare_with_blessed(&frame.image, dir, &stem, job, &mut write_rgba8)?),
        None => None,
    };
    files.extend(rgba8_files);
    let json_name = format!("{stem}.json");
    files.push(json_name.clone());
    let report = AnyPackReport {
        gl_disagreement: gl.as_ref().and_then(|g| g.first_disagreement(gl_max_pixels)).map(|d| Disagreement { file: step_file(&pack, &d.pass), ..d }),
        step_renderers: StepRenderers::of(&frame.passes, gl_primary, gl.as_ref()),
        gl_rewrites: if job.gl || gl_primary { pack.gl_rewrites().into_iter().chain(driver_limit_rewrites).collect() } else { Vec::new() },
        renderer,
        gl,
        expected,
        timing: frame.timing.clone(),
        rendered: RenderedScene::new(&scene, &job.scene, pack.loader, &gpu),
        pack: job.pack.display().to_string(),
        world: pack.world.clone(),
        non_finite_pixels: frame.image.non_finite(),
        first_non_finite: first_non_finite(&frame.passes, &pack),
        passes: frame.passes,
        not_modelled: frame.not_modelled,
        failed_programs: pack.failed.clone(),
        pack_programs: pack.gbuffers.len() + pack.fullscreen.len() + pack.shadow.len(),
        files,
    };
    let json = serde_json::to_string_pretty(&report).map_err(|e| HarnessError::Io(format!("report: {e}")))?;
    let json_path = job.out_dir.join(&json_name);
    std::fs::write(&json_path, json + "\n").map_err(|e| HarnessError::Io(format!("cannot write {}: {e}", json_path.display())))?;
    Ok(report)
}

/// The frame drawn by OpenGL as the primary renderer, `frames` times: the last frame's images,
/// and each step's and the pass-through's settled median wall time; and the last frame as drawn.
fn opengl_frame(
    ctx: &tidepack_gldriver::GlContext,
    pack: &AnyPack,
    scene: &Scene,
    mesh: &mesh::SceneMesh,
    frames: usize,
) -> Result<(gpu::Frame, crate::gl_frame::GlFrame), HarnessError> {
    let mut rendered = Vec::new();
    for _ in 0..frames.max(1) {
        rendered.push(crate::gl_frame::render(ctx, pack, scene, mesh, ScreenOutput::AsLoader)?);
    }
    let last = rendered.last().expect("one frame at least");
    let passes: Vec<StepReport> = last
        .steps
        .iter()
        .enumerate()
        .map(|(i, (pass, images))| {
            let samples_ms: Vec<f64> = rendered.iter().map(|f| f.step_ms[i]).collect();
            StepReport {
                pass: pass.clone(),
                wall_ms: last.step_ms[i],
                gpu_ms: None,
                median_ms: images::settled_median(&samples_ms),
                samples_ms,
                non_finite: images.iter().map(|(name, image)| (name.clone(), image.non_finite())).collect(),
                images: images.clone(),
            }
        })
        .collect();
    let frame_ms: Vec<f64> = rendered.iter().map(|f| f.step_ms.iter().sum()).collect();
    let passthrough_samples_ms: Vec<f64> = rendered.iter().map(|f| f.passthrough_ms).collect();
    let timing = gpu::FrameTiming {
        frames: rendered.len(),
        frame_ms: images::settled_median(&frame_ms),
        passthrough_ms: images::settled_median(&passthrough_samples_ms),
        passthrough_samples_ms,
    };
    let last = rendered.pop().expect("one frame at least");
    let frame = gpu::Frame {
        image: last.image.clone(),
        buffers: last.buffers.clone(),
        depth0: last.depth0.clone(),
        depth1: last.depth1.clone(),
        passes,
        timing,
        not_modelled: pack.not_modelled.clone(),
        zeroed: Vec::new(),
    };
    Ok((frame, last))
}

/// A wgpu frame as the reference OpenGL draws each step from.
fn reference_of<'f>(passes: &'f [StepReport], depth0: &'f FloatImage, depth1: &'f FloatImage, nudge: f64) -> crate::gl_frame::Reference<'f> {
    crate::gl_frame::Reference { steps: passes.iter().map(|p| p.images.as_slice()).collect(), depth0, depth1, depth_written: Vec::new(), nudge, trace_derivatives: false }
}

/// The OpenGL frame's textures against the wgpu frame's steps, step by step.
fn compare_steps(renderer: String, wgpu: &[StepReport], gl: &crate::gl_frame::GlFrame) -> Result<GlStepsComparison, HarnessError> {
    if wgpu.len() != gl.steps.len() {
        return Err(HarnessError::Gl(format!("the OpenGL frame ran {} steps, the wgpu frame {}", gl.steps.len(), wgpu.len())));
    }
    let mut steps = Vec::new();
    for (pass, (label, gl_images)) in wgpu.iter().zip(&gl.steps) {
        let mut max_difference_255 = BTreeMap::new();
        let mut pixels_over_1_255 = BTreeMap::new();
        for ((name, a), (_, b)) in pass.images.iter().zip(gl_images) {
            let d = images::max_channel_difference(a, b);
            max_difference_255.insert(name.clone(), d.map(|c| c * 255.0));
            pixels_over_1_255.insert(name.clone(), images::count_differing(a, b, OVER_1_255));
        }
        steps.push(GlStepComparison { pass: label.clone(), max_difference_255, pixels_over_1_255, sensitive_pixels: BTreeMap::new(), undefined_pixels: BTreeMap::new() });
    }
    Ok(GlStepsComparison { renderer, steps, own_depth_mapping: gl.own_depth_mapping.clone(), refused: None, wgpu_cannot_draw: Vec::new() })
}

/// Writes an RGBA8 image beside the screen: (file suffix, width, height, pixels top row first).
type WriteRgba8<'a> = dyn FnMut(&str, u32, u32, &[u8]) -> Result<(), HarnessError> + 'a;

/// Blesses the screen into `dir`, or compares it with the blessed one there by mean FLIP and
/// writes the FLIP error map and an 8× amplified difference beside the screen.
fn compare_with_blessed(
    screen: &FloatImage,
    dir: &std::path::Path,
    stem: &str,
    job: &AnyPackJob,
    write: &mut WriteRgba8,
) -> Result<ExpectedScreen, HarnessError> {
    let path = dir.join(format!("{stem}.png"));
    let (width, height) = (screen.width, screen.height);
    let actual = screen.to_rgba8_top_first();
    if job.bless {
        std::fs::create_dir_all(dir).map_err(|e| HarnessError::Io(format!("cannot create {}: {e}", dir.display())))?;
        images::write_rgba8_png(&path, width, height, &actual)?;
        return Ok(ExpectedScreen { path: path.display().to_string(), mean_flip: None, max_flip: job.max_flip, passed: true });
    }
    let (w, h, expected) = images::read_rgba8_png(&path)
        .map_err(|e| HarnessError::Io(format!("{e}; write the blessed screens with --bless first")))?;
    if (w, h) != (width, height) {
        return Err(HarnessError::Scene(format!("{} is {w}x{h}, the screen {width}x{height}", path.display())));
    }
    let (actual_rgb, expected_rgb) = (images::rgba8_to_rgb8(&actual), images::rgba8_to_rgb8(&expected));
    let map = images::flip_map(&actual_rgb, &expected_rgb, width, height);
    let mean_flip = images::mean_flip(&map);
    write(".flip", width, height, &images::flip_heatmap_rgba8(&map))?;
    write(".difference", width, height, &images::difference_rgb8(&actual, &expected))?;
    Ok(ExpectedScreen { path: path.display().to_string(), mean_flip: Some(mean_flip), max_flip: job.max_flip, passed: mean_flip <= job.max_flip })
}


fn pass_report(step: &StepReport) -> PassReport {
    PassReport { pass: step.pass.clone(), ms: step.median_ms, gpu_ms: step.gpu_ms, wall_ms: step.wall_ms }
}

/// The report's name of the one-tap pass-through of colortex0 each frame is timed against.
const PASSTHROUGH: &str = "pass-through composite";

/// Timed frames per pack behind `render --specialise`.
const SPECIALISATION_FRAMES: usize = 9;

/// A scene or pack name made safe as a file name.
pub fn file_stem(name: &str) -> String {
    let s: String = name.chars().map(|c| if c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.') { c } else { '_' }).collect();
    if s.is_empty() || s.starts_with('.') { format!("scene{s}") } else { s }
}

#[cfg(test)]
mod tests {
    #[test]
    fn scene_names_become_safe_file_names() {
        assert_eq!(super::file_stem("case1_above_dry"), "case1_above_dry");
        assert_eq!(super::file_stem("../x y"), "scene.._x_y");
        assert_eq!(super::file_stem(""), "scene");
    }

    /// Pixels where OpenGL moves under the nudge are not counted against the renderers; where the
    /// nudge moves much of the texture, pixels whose block has the same mean in both are not.
    #[test]
    fn differences_that_are_the_packs_own_noise_are_sensitive() {
        let noise_count = |ours: &FloatImage, theirs: &FloatImage, moved: &[&FloatImage]| super::noise_pixels(ours, theirs, moved).iter().filter(|n| **n).count();
        use crate::images::FloatImage;
        let image = |changed: &[usize]| {
            let mut pixels = vec![[0.5f32, 0.5, 0.5, 1.0]; 256];
            for &i in changed {
                pixels[i][0] = 0.9;
            }
            FloatImage { width: 16, height: 16, pixels }
        };
        let (ours, theirs) = (image(&[]), image(&[0, 1, 2, 3, 4, 5, 6, 7, 8, 9]));
        // OpenGL nudged moves four of the ten pixels where the renderers part, and one other.
        let mut moved = theirs.clone();
        for i in [0, 1, 2, 3, 50] {
            moved.pixels[i][0] = 0.5;
        }
        assert_eq!(noise_count(&ours, &theirs, &[&moved]), 4);
        assert_eq!(noise_count(&ours, &theirs, &[&theirs]), 0);
        // A nudge the other way moves three more: each nudge adds the pixels it moves.
        let mut other_way = theirs.clone();
        for i in [4, 5, 6] {
            other_way.pixels[i][0] = 0.6;
        }
        assert_eq!(noise_count(&ours, &theirs, &[&moved, &other_way]), 7);
        // Pixels apart beside moved ones, in a block whose means agree, are noise too; in a block
        // whose mean they shift, they are not (above: ten bright pixels shift their block's).
        let (faint_ours, mut faint_theirs) = (image(&[]), image(&[]));
        for i in [0, 1, 2, 3, 4] {
            faint_theirs.pixels[i][0] = 0.52;
        }
        faint_theirs.pixels[5][0] = 0.48;
        let mut faint_moved = faint_theirs.clone();
        faint_moved.pixels[0][0] = 0.5;
        assert_eq!(noise_count(&faint_ours, &faint_theirs, &[&faint_moved]), 6);
        assert_eq!(noise_count(&faint_ours, &faint_theirs, &[&faint_theirs]), 0);
        // Where a nudge moves a block's mean as far as the renderers part on it, the pixels apart
        // in that block are noise: the nudge darkens the second row of the first block as much
        // as the bright pixels 0 to 7 brighten it, and leaves the second block (pixels 8, 9) be.
        let mut second_row_moved = theirs.clone();
        for i in 16..24 {
            second_row_moved.pixels[i][0] = 0.1;
        }
        assert_eq!(noise_count(&ours, &theirs, &[&second_row_moved]), 8);
        // Past 5% of the texture moved, the step is noise throughout, and the ten pixels brighten
        // their blocks' means, which the nudge moves in other blocks: not noise.
        for i in 200..220 {
            moved.pixels[i][0] = 0.1;
        }
        assert_eq!(noise_count(&ours, &theirs, &[&moved]), 0);
        // A dither that averages to the same mean over each 8x8 block is noise.
        let mut dithered = ours.clone();
        for (i, p) in dithered.pixels.iter_mut().enumerate() {
            p[0] += if (i + i / 16) % 2 == 0 { 0.02 } else { -0.02 };
        }
        assert_eq!(noise_count(&ours, &dithered, &[&moved]), 256);
    }

    /// A frame whose composite parts on most of the screen (the all-black OpenGL screen beside a
    /// plausible wgpu one): the first step over the limit is named, not a later one, and a step
    /// within the limit is agreement.
    #[test]
    fn the_first_step_where_the_renderers_part_is_named() {
        use super::{Disagreement, GlStepComparison, GlStepsComparison};
        let step = |pass: &str, texture: &str, pixels: usize, worst: f32| GlStepComparison {
            pass: pass.into(),
            max_difference_255: [(texture.to_string(), [worst, 0.0, 0.0, 0.0])].into(),
            pixels_over_1_255: [(texture.to_string(), pixels)].into(),
            sensitive_pixels: Default::default(),
            undefined_pixels: Default::default(),
        };
        let frame = GlStepsComparison {
            renderer: "llvmpipe".into(),
            steps: vec![step("gbuffers_terrain", "colortex0", 3, 1.5), step("composite", "colortex0", 17_654, 67.0), step("final", "screen", 20_000, 70.0)],
            own_depth_mapping: vec![],
            refused: None,
            wgpu_cannot_draw: vec![],
        };
        assert_eq!(
            frame.first_disagreement(16),
            Some(Disagreement { pass: "composite".into(), file: None, texture: "colortex0".into(), pixels: 17_654, sensitive: 0, undefined: 0, max_difference_255: 67.0, max_pixels: 16 })
        );
        assert_eq!(frame.first_disagreement(2).map(|d| d.pass), Some("gbuffers_terrain".into()));
        assert_eq!(frame.first_disagreement(20_000), None);
        let refused = GlStepsComparison { steps: vec![], refused: Some("link error".into()), ..frame.clone() };
        assert_eq!(refused.first_disagreement(0), None);
        // A step wgpu could not draw is set aside, not compared: its textures are OpenGL's own.
        let mut beside = frame;
        beside.set_aside(&[None, Some("naga cannot read composite".into()), None]);
        assert_eq!(beside.wgpu_cannot_draw, [("composite".to_string(), "naga cannot read composite".to_string())]);
        assert_eq!(beside.first_disagreement(16).map(|d| d.pass), Some("final".into()));
    }
}
