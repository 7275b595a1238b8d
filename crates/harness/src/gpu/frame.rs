//! The wgpu renderer: a small imitation of OptiFine's pipeline for one frame.
//!
//! 1. clear: every colour buffer to OptiFine's clear colour (colortex0 fog colour, colortex1
//!    white, the rest transparent black), depth to 1;
//! 2. terrain: the pack's terrain program (the first of gbuffers_terrain's fallback chain it
//!    has) draws the opaque geometry into its render targets and depthtex0; a pack with none
//!    gets the harness's own terrain shader, which writes colortex0, or every colour buffer
//!    where the loader draws a missing program into every draw buffer (OptiFine up to 1.16.5;
//!    [`crate::loader`]);
//! 3. depthtex0 is copied to depthtex1 (depth without translucents);
//! 4. gbuffers_water: the pack's program draws water and glass, blended as the loader reads
//!    shaders.properties and alpha-tested as the loader does, into its render targets and
//!    depthtex0;
//! 5. composite: the pack's program full-screen into colortex0's alternate buffer, here an
//!    RGBA32F target so NaN and Inf survive to the readback;
//! 6. optionally a one-tap pass-through composite into the same kind of target, the floor
//!    the composite's cost is measured against.
//!
//! Buffers are stored in OpenGL orientation (row 0 at the bottom): the vertex shaders flip y.

use std::collections::{BTreeMap, BTreeSet};
use std::time::Instant;

use crate::HarnessError;
use tidepack_loader::buffers::BufferClear;
use crate::images::FloatImage;
use tidepack_loader::loader::{self, Phase};
use tidepack_scene::mesh::{self, SceneMesh, Sprites};
use crate::program::{LoadedPack, LoadedProgram};
use tidepack_loader::directives::Blend;
use tidepack_scene::scene::Scene;
use crate::uniforms::{self, Pass};

use super::Gpu;
use super::bindings::{
    BindableTextures, DEPTH, DrawState, FullscreenQuad, HarnessTextures, OUT, PassKind, ProgramPipeline, ShadowTextures, UniformBinding, NO_MIPMAPS,
    view,
};
use crate::samplers::{SamplerNaming, colour_buffers_read};
use super::geometry::{GeometryDraw, depth_attachment};
use super::own::PassthroughPipeline;
use super::readback::{read_pass_ms, read_texture};

/// Median of pass times (NaN for none): what every timing report of the harness quotes.
pub fn median(samples: &[f64]) -> f64 {
    let mut sorted = samples.to_vec();
    sorted.sort_by(f64::total_cmp);
    let n = sorted.len();
    match n {
        0 => f64::NAN,
        _ if n % 2 == 1 => sorted[n / 2],
        _ => (sorted[n / 2 - 1] + sorted[n / 2]) / 2.0,
    }
}

/// Time of one pass.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PassTiming {
    pub pass: String,
    /// GPU time from timestamps, when the adapter has them (render passes only).
    pub gpu_ms: Option<f64>,
    /// Wall time from submit to completion.
    pub wall_ms: f64,
}

/// One rendered frame, every image bottom row first.
#[derive(Clone, Debug)]
pub struct Frame {
    /// Composite's output, read back from an RGBA32F target.
    pub image: FloatImage,
    /// The colour buffers before composite (colortex0 = the scene composite reads).
    pub buffers: BTreeMap<u8, FloatImage>,
    pub depth0: FloatImage,
    pub depth1: FloatImage,
    /// Output of the pass-through composite, when it ran.
    pub passthrough: Option<FloatImage>,
    pub timings: Vec<PassTiming>,
}

/// The frame's buffers.
struct FrameTargets {
    colors: BTreeMap<u8, (wgpu::Texture, wgpu::TextureFormat)>,
    depth0: wgpu::Texture,
    depth1: wgpu::Texture,
    /// Composite's colortex0 output.
    out: wgpu::Texture,
    passthrough: wgpu::Texture,
}

impl FrameTargets {
    /// Every colour buffer a program writes or composite reads, in its declared format.
    fn new(gpu: &Gpu, pack: &LoadedPack, size: wgpu::Extent3d) -> Result<FrameTargets, HarnessError> {
        let mut buffers: BTreeSet<u8> = BTreeSet::from([0]);
        buffers.extend(pack.water.render_targets.iter().copied());
        buffers.extend(pack.gbuffers.values().flat_map(|p| p.render_targets.iter().copied()));
        buffers.extend(colour_buffers_read(pack, &pack.composite, SamplerNaming::OwnFrame, false));
        let texture = |label: &str, format, usage| gpu.texture(label, size, format, usage);
        let attachment = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC;
        let mut colors = BTreeMap::new();
        for b in buffers {
            let format = gpu.texture_format(pack.format_of(b))?;
            colors.insert(b, (texture(&format!("colortex{b}"), format, attachment | wgpu::TextureUsages::TEXTURE_BINDING), format));
        }
        let depth = attachment | wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST;
        Ok(FrameTargets {
            colors,
            depth0: texture("depthtex0", DEPTH, depth),
            depth1: texture("depthtex1", DEPTH, depth),
            out: texture("composite output (colortex0 alternate, RGBA32F)", OUT, attachment),
            passthrough: texture("pass-through output", OUT, attachment),
        })
    }

    fn bindable<'a>(&'a self, harness: &'a HarnessTextures) -> BindableTextures<'a> {
        BindableTextures {
            naming: SamplerNaming::OwnFrame,
            harness,
            colors: &self.colors,
            depth0: &self.depth0,
            depth1: &self.depth1,
            shadow: ShadowTextures::empty(harness),
            sprites: Sprites::Blocks,
            mipmapped: &NO_MIPMAPS,
        }
    }
}

/// Renders one frame of `scene` with the pack's programs. Every wgpu validation error becomes
/// a [`HarnessError::Wgpu`].
pub fn render(gpu: &Gpu, pack: &LoadedPack, scene: &Scene, mesh: &SceneMesh, passthrough: bool) -> Result<Frame, HarnessError> {
    Ok(render_repeated(gpu, pack, scene, mesh, passthrough, 1)?.0)
}

/// Renders `frames` frames of `scene` with pipelines, buffers and textures made once, for
/// timing: returns the last frame and the pass times of every frame. The first frame's times
/// include the driver's lazy shader compilation (llvmpipe compiles fragment shader variants at
/// the first draw); later frames time the passes alone.
pub fn render_repeated(
    gpu: &Gpu,
    pack: &LoadedPack,
    scene: &Scene,
    mesh: &SceneMesh,
    passthrough: bool,
    frames: usize,
) -> Result<(Frame, Vec<Vec<PassTiming>>), HarnessError> {
    gpu.check_resolution(scene.width(), scene.height()).map_err(|e| match e {
        HarnessError::Scene(why) => HarnessError::Scene(format!("scene {}: {why}", scene.name)),
        other => other,
    })?;
    gpu.checked("frame", || render_frame(gpu, pack, scene, mesh, passthrough, frames.max(1)))?
}

/// One step of the frame after the clear, each its own submission.
enum Step<'a> {
    Geometry(&'a GeometryDraw),
    /// depthtex0 to depthtex1: depth without translucents.
    DepthCopy,
    Composite,
    Passthrough(&'a PassthroughPipeline),
}

impl Step<'_> {
    fn label(&self) -> &str {
        match self {
            Step::Geometry(draw) => &draw.label,
            Step::DepthCopy => "depth copy",
            Step::Composite => "composite",
            Step::Passthrough(_) => "pass-through composite",
        }
    }
}

fn render_frame(
    gpu: &Gpu,
    pack: &LoadedPack,
    scene: &Scene,
    mesh: &SceneMesh,
    passthrough: bool,
    frames: usize,
) -> Result<(Frame, Vec<Vec<PassTiming>>), HarnessError> {
    let size = wgpu::Extent3d { width: scene.width(), height: scene.height(), depth_or_array_layers: 1 };
    let targets = FrameTargets::new(gpu, pack, size)?;
    let harness_textures = HarnessTextures::new(gpu, pack);
    let bindable = targets.bindable(&harness_textures);
    let gbuffers_values = uniforms::values(scene, Pass::Gbuffers);
    let geometry = |program: Option<&LoadedProgram>, state: &DrawState, vertices: &[mesh::PackVertex], label: String| {
        GeometryDraw::new(gpu, pack, pack.loader.missing_program_draws(), scene, &gbuffers_values, &bindable, program, state, vertices, label)
    };

    let no_blend = |_| Blend::Off;
    // Opaque terrain is drawn with blending off.
    let terrain = geometry(pack.terrain_program(), &DrawState { blend_of: &no_blend, depth_write: true }, &mesh.terrain, "terrain".into())?;
    let water_state = DrawState { blend_of: &|b| pack.blend_of(b), depth_write: true };
    let water = geometry(Some(&pack.water), &water_state, &mesh.translucent, "gbuffers_water".into())?;
    // Rain, clouds, particles and the hand, grouped by when the loader draws them.
    let mut overlays: BTreeMap<Phase, Vec<GeometryDraw>> = BTreeMap::new();
    for (kind, vertices) in &mesh.overlay {
        let program = pack.resolve(pack.loader.program_chain(*kind));
        let state = DrawState { blend_of: &|b| pack.gbuffers_blend_of(program, b), depth_write: loader::writes_depth(*kind) };
        let label = format!("{kind:?} ({})", program.map_or("the loader's own", |p| p.name.as_str()));
        overlays.entry(scene.overlay_phase(pack.loader, *kind)).or_default().push(geometry(program, &state, vertices, label)?);
    }
    let composite = ProgramPipeline::new(
        gpu,
        pack,
        &pack.composite,
        &uniforms::values(scene, Pass::Fullscreen),
        PassKind::Fullscreen { width: size.width, height: size.height },
        &bindable,
        UniformBinding::ReadOnlyStorage,
    )?;
    let copy_pipeline = if passthrough { Some(PassthroughPipeline::new(gpu, &targets.colors[&0].0)?) } else { None };
    let quad = FullscreenQuad::new(gpu);

    let phase = |p: Phase| overlays.get(&p).into_iter().flatten().map(Step::Geometry);
    let steps: Vec<Step> = phase(Phase::BeforeTerrain)
        .chain([Step::Geometry(&terrain)])
        .chain(phase(Phase::BeforeWater))
        .chain([Step::DepthCopy, Step::Geometry(&water)])
        .chain(phase(Phase::AfterWater))
        .chain([Step::Composite])
        .chain(copy_pipeline.as_ref().map(Step::Passthrough))
        .collect();
    let runs = run_steps(gpu, pack, scene, &targets, &steps, &composite, &quad, frames)?;
    let timings = runs.last().cloned().unwrap_or_default();

    let mut images = BTreeMap::new();
    for (b, (t, format)) in &targets.colors {
        images.insert(*b, read_texture(gpu, t, *format)?);
    }
    let frame = Frame {
        image: read_texture(gpu, &targets.out, OUT)?,
        buffers: images,
        depth0: read_texture(gpu, &targets.depth0, DEPTH)?,
        depth1: read_texture(gpu, &targets.depth1, DEPTH)?,
        passthrough: if passthrough { Some(read_texture(gpu, &targets.passthrough, OUT)?) } else { None },
        timings,
    };
    Ok((frame, runs))
}

/// Runs the frame's steps `frames` times after OptiFine's clears; each run's pass timings,
/// every step but the depth copy a render pass timed by GPU timestamps where the adapter has
/// them, each step also by the wall clock.
#[allow(clippy::too_many_arguments)]
fn run_steps(
    gpu: &Gpu,
    pack: &LoadedPack,
    scene: &Scene,
    targets: &FrameTargets,
    steps: &[Step],
    composite: &ProgramPipeline,
    quad: &FullscreenQuad,
    frames: usize,
) -> Result<Vec<Vec<PassTiming>>, HarnessError> {
    let device = &gpu.device;
    let size = targets.depth0.size();
    let render_passes = steps.iter().filter(|s| !matches!(s, Step::DepthCopy)).count() as u32;
    let queries = gpu.timestamps.then(|| {
        device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("pass timestamps"),
            ty: wgpu::QueryType::Timestamp,
            count: render_passes * 2,
        })
    });
    let stamps = |i: u32| {
        queries.as_ref().map(|q| wgpu::RenderPassTimestampWrites {
            query_set: q,
            beginning_of_pass_write_index: Some(2 * i),
            end_of_pass_write_index: Some(2 * i + 1),
        })
    };
    let submit = |encoder: wgpu::CommandEncoder| -> Result<f64, HarnessError> {
        let started = Instant::now();
        gpu.queue.submit([encoder.finish()]);
        gpu.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| HarnessError::Wgpu(format!("waiting for the GPU: {e}")))?;
        Ok(started.elapsed().as_secs_f64() * 1000.0)
    };
    let new_encoder = || device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: None });

    let mut runs: Vec<Vec<PassTiming>> = Vec::new();
    for _ in 0..frames {
        let mut wall = Vec::new();
        gpu.checked("rendering", || -> Result<(), HarnessError> {
            let mut encoder = new_encoder();
            // OptiFine's clears: colortex0 the fog colour, colortex1 white, the rest transparent.
            let colours: Vec<(&wgpu::Texture, [f64; 4])> =
                targets.colors.iter().map(|(b, (t, _))| (t, BufferClear::Default.colour(*b, scene.sky.fog_color))).collect();
            record_clears(&mut encoder, &colours, &targets.depth0);
            submit(encoder)?;
            let mut timed = 0;
            for step in steps {
                let mut encoder = new_encoder();
                let stamp = if matches!(step, Step::DepthCopy) { None } else { stamps(timed) };
                timed += u32::from(stamp.is_some());
                match step {
                    Step::Geometry(draw) => draw.record(&mut encoder, &|b| &targets.colors[&b].0, &targets.depth0, stamp),
                    Step::DepthCopy => encoder.copy_texture_to_texture(targets.depth0.as_image_copy(), targets.depth1.as_image_copy(), size),
                    Step::Composite => composite.record_fullscreen(&mut encoder, &pack.composite, &targets.out, quad, stamp),
                    Step::Passthrough(p) => p.record(&mut encoder, &targets.passthrough, stamp),
                }
                wall.push(submit(encoder)?);
            }
            Ok(())
        })??;
        let mut gpu_ms = match &queries {
            Some(q) => read_pass_ms(gpu, q, render_passes)?.into_iter(),
            None => Vec::new().into_iter(),
        };
        let timings = steps
            .iter()
            .zip(wall)
            .map(|(step, wall_ms)| PassTiming {
                pass: step.label().to_string(),
                gpu_ms: if matches!(step, Step::DepthCopy) { None } else { gpu_ms.next() },
                wall_ms,
            })
            .collect();
        runs.push(timings);
    }
    Ok(runs)
}

/// Clears each texture to its colour (RGBA) and `depth0` to 1, eight attachments a pass.
pub(crate) fn record_clears(encoder: &mut wgpu::CommandEncoder, colours: &[(&wgpu::Texture, [f64; 4])], depth0: &wgpu::Texture) {
    let depth0_view = view(depth0);
    let views: Vec<(wgpu::TextureView, wgpu::Color)> =
        colours.iter().map(|(t, [r, g, b, a])| (view(t), wgpu::Color { r: *r, g: *g, b: *b, a: *a })).collect();
    let attachments: Vec<Option<wgpu::RenderPassColorAttachment>> = views
        .iter()
        .map(|(v, colour)| {
            Some(wgpu::RenderPassColorAttachment {
                view: v,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations { load: wgpu::LoadOp::Clear(*colour), store: wgpu::StoreOp::Store },
            })
        })
        .collect();
    for chunk in attachments.chunks(8) {
        encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("clear"),
            color_attachments: chunk,
            depth_stencil_attachment: Some(depth_attachment(&depth0_view, true)),
            ..Default::default()
        });
    }
}




