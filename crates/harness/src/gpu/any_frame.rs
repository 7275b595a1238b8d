//! Any pack's frame ([`crate::any_pack::FramePlan`]) through wgpu, step by step: each step's
//! pipeline is built against the textures current at its turn. The screen is RGBA32F, so NaN
//! and Inf survive. Frames can be repeated for timing; after each step of the last one the
//! textures it wrote are read back and their NaN and Inf counted.

use std::collections::{BTreeMap, BTreeSet};
use std::time::Instant;

use crate::HarnessError;
use crate::any_pack::{AnyPack, FramePlan, PlannedWork};
use crate::images::FloatImage;
use crate::mesh::{SceneMesh, Sprites};
use crate::program::{LoadedProgram, PackResources};
use tidepack_loader::directives::Blend;
use crate::scene::Scene;
use crate::uniforms::{self, Pass};

use super::Gpu;
use super::bindings::{
    BindableTextures, DEPTH, DrawState, FullscreenQuad, HarnessTextures, NO_MIPMAPS, OUT, PassKind, ProgramPipeline, SamplerNaming,
    ShadowTextures, UniformBinding,
};
use super::geometry::GeometryDraw;
use super::own::{MipmapPipelines, PassthroughPipeline, mip_levels};
use super::frame::{median, record_clears};
use super::readback::{read_pass_ms, read_texture};

/// One pass of the frame as it ran.
#[derive(Clone, Debug, serde::Serialize)]
pub struct AnyPassReport {
    /// `terrain (gbuffers_terrain)`, `composite1`, `depth copy`, …
    pub pass: String,
    /// Wall time of the last frame's step.
    pub wall_ms: f64,
    /// GPU time from timestamps, when the adapter has them (last frame).
    pub gpu_ms: Option<f64>,
    /// Median over the frames after the first: GPU time where timestamps exist, else wall.
    pub median_ms: f64,
    /// NaN and Inf texels in each buffer the pass wrote (`colortex2`, `shadowcolor0`, `screen`);
    /// normalised formats cannot hold them.
    pub non_finite: BTreeMap<String, usize>,
    /// The textures the pass wrote, by the same names, for comparing renderers pass by pass.
    #[serde(skip)]
    pub images: Vec<(String, FloatImage)>,
}

/// What a frame costs against the one-tap pass-through composite, in the same run.
#[derive(Clone, Debug, serde::Serialize)]
pub struct FrameTiming {
    /// Frames rendered; medians leave out the first (llvmpipe compiles shaders at first use).
    pub frames: usize,
    /// Median of the sum of every step's time.
    pub frame_ms: f64,
    /// Median time of the one-tap pass-through of colortex0.
    pub passthrough_ms: f64,
}

/// A frame of any pack.
#[derive(Clone, Debug)]
pub struct AnyFrame {
    /// The screen: what final wrote, bottom row first.
    pub image: FloatImage,
    /// Each colour buffer's current texture when final ran.
    pub buffers: BTreeMap<u8, FloatImage>,
    pub depth0: FloatImage,
    pub depth1: FloatImage,
    pub passes: Vec<AnyPassReport>,
    pub timing: FrameTiming,
    /// What the pack uses that this frame did not imitate: the pack's own list, and the
    /// uniforms and vertex inputs left at zero.
    pub not_modelled: Vec<String>,
}

/// A colour buffer's two textures and which is current.
struct Buffer {
    textures: [wgpu::Texture; 2],
    /// The copy gbuffers programs sample.
    snapshot: wgpu::Texture,
    format: wgpu::TextureFormat,
}

/// A texture a step wrote.
enum WrittenTexture {
    /// One of a colour buffer's two textures: (buffer, index).
    Buffer(u8, usize),
    ShadowColour(u8),
    Screen,
}

/// A texture a step wrote, by name (`colortex2`, `shadowcolor0`, `screen`).
type Written = (String, WrittenTexture);

enum Work<'p> {
    Geometry { draw: GeometryDraw, current: &'p BTreeMap<u8, usize>, snapshots: &'p BTreeSet<u8> },
    DepthCopy,
    ShadowGeometry(GeometryDraw),
    ShadowDepthCopy,
    Fullscreen {
        program: &'p LoadedProgram,
        pipeline: ProgramPipeline,
        current: &'p BTreeMap<u8, usize>,
        into_screen: bool,
        /// Buffers whose current texture gets its mipmaps first.
        mipmaps: &'p BTreeSet<u8>,
    },
    ScreenCopy(PassthroughPipeline),
}

impl Work<'_> {
    /// A texture copy, not a render pass (no timestamps).
    fn is_copy(&self) -> bool {
        matches!(self, Work::DepthCopy | Work::ShadowDepthCopy)
    }
}

/// Renders `frames` frames of `scene` with any pack's programs, pipelines made once; returns
/// the last with the medians of the others' times.
pub fn render_any(gpu: &Gpu, pack: &AnyPack, scene: &Scene, mesh: &SceneMesh, frames: usize) -> Result<AnyFrame, HarnessError> {
    gpu.check_resolution(scene.width(), scene.height())
        .map_err(|e| HarnessError::Scene(format!("scene {}: {e}", scene.name)))?;
    gpu.checked("frame", || render_any_checked(gpu, pack, scene, mesh, frames))?
}

fn render_any_checked(gpu: &Gpu, pack: &AnyPack, scene: &Scene, mesh: &SceneMesh, frames: usize) -> Result<AnyFrame, HarnessError> {
    let device = &gpu.device;
    let plan = FramePlan::new(pack, scene, mesh);
    let size = wgpu::Extent3d { width: scene.width(), height: scene.height(), depth_or_array_layers: 1 };
    let texture = |label: &str, format, usage| gpu.texture(label, size, format, usage);
    let every_use = wgpu::TextureUsages::RENDER_ATTACHMENT
        | wgpu::TextureUsages::TEXTURE_BINDING
        | wgpu::TextureUsages::COPY_SRC
        | wgpu::TextureUsages::COPY_DST;
    let mut buffers: BTreeMap<u8, Buffer> = BTreeMap::new();
    // Mipmapped buffers have full mip chains; programs draw into, and read, the first level.
    let levels = mip_levels(scene.width(), scene.height());
    for &b in &plan.buffers {
        let format = gpu.texture_format(pack.format_of(b))?;
        let label = |what: &str| format!("colortex{b} {what}");
        let levels = if plan.mipmapped.contains(&b) { levels } else { 1 };
        let flipped = |what: &str| gpu.texture_with_levels(&label(what), size, format, every_use, levels);
        buffers.insert(
            b,
            Buffer {
                textures: [flipped("A"), flipped("B")],
                snapshot: texture(&label("as gbuffers read it"), format, every_use),
                format,
            },
        );
    }
    let depth0 = texture("depthtex0", DEPTH, every_use);
    let depth1 = texture("depthtex1", DEPTH, every_use);
    let screen = texture("screen (RGBA32F)", OUT, every_use);
    let harness_textures = HarnessTextures::new(gpu, pack);
    let mipmap_pipelines = MipmapPipelines::new(gpu, plan.mipmapped.iter().map(|b| buffers[b].format))?;
    // The shadow maps: one texel each, cleared, when the frame has no shadow pass.
    let shadow_side = if pack.shadow_pass { pack.shadow_settings.drawn_resolution().0 } else { 1 };
    let shadow_size = wgpu::Extent3d { width: shadow_side, height: shadow_side, depth_or_array_layers: 1 };
    let shadow_texture = |label: &str, format| gpu.texture(label, shadow_size, format, every_use);
    let shadow_depth = [shadow_texture("shadowtex0", DEPTH), shadow_texture("shadowtex1", DEPTH)];
    let shadow_depth_read = [shadow_texture("shadowtex0 as sampler2D reads it", OUT), shadow_texture("shadowtex1 as sampler2D reads it", OUT)];
    // shadowtex0 as sampler2D reads it after each shadow draw; shadowtex1's is copied with it.
    let depth_as_luminance = PassthroughPipeline::depth_as_luminance(gpu, &shadow_depth[0])?;
    let mut shadow_colours = BTreeMap::new();
    for &b in &plan.shadow_buffers {
        let format = gpu.texture_format(pack.shadow_format_of(b))?;
        shadow_colours.insert(b, (shadow_texture(&format!("shadowcolor{b}"), format), format));
    }
    let shadow = ShadowTextures {
        depth: [&shadow_depth[0], &shadow_depth[1]],
        depth_read: [&shadow_depth_read[0], &shadow_depth_read[1]],
        colours: &shadow_colours,
    };
    let quad = FullscreenQuad::new(gpu);

    let mut not_modelled = pack.not_modelled.clone();
    let mut note = |line: String| {
        if !not_modelled.contains(&line) {
            not_modelled.push(line);
        }
    };
    // The pack's custom uniforms join the standard ones, once per kind of pass.
    let (gbuffers_values, problems) = pack.uniform_values(scene, Pass::Gbuffers);
    let (fullscreen_values, _) = pack.uniform_values(scene, Pass::Fullscreen);
    let (shadow_values, _) = pack.uniform_values(scene, Pass::Shadow);
    let (celestial_values, _) = pack.uniform_values(scene, Pass::Celestial);
    if let Some(line) = pack.sun_path_note(scene) {
        note(line);
    }
    for problem in &problems {
        note(format!("{problem} (the uniform stays zero)"));
    }
    let snapshot_colors: BTreeMap<u8, (wgpu::Texture, wgpu::TextureFormat)> =
        buffers.iter().map(|(b, buffer)| (*b, (buffer.snapshot.clone(), buffer.format))).collect();

    // Each step's pipeline, and what to count NaN and Inf in afterwards.
    let mut steps: Vec<(&str, Work, Vec<Written>)> = Vec::new();
    let mut zeroed_inputs = Vec::new();
    // Uniforms the harness has no value for stay zero, as a loader leaves uniforms it does not set.
    let mut zeroed_uniforms = Vec::new();
    for step in &plan.steps {
        let (work, written) = match &step.work {
            PlannedWork::Geometry { program, vertices, default_blend, depth_write, current, snapshots, sprites, pass, render_stage } => {
                let values = uniforms::with_render_stage(if *pass == Pass::Celestial { &celestial_values } else { &gbuffers_values }, render_stage);
                let blend_of = |b: u8| pack.blend_of(*program, b, default_blend);
                let state = DrawState { blend_of: &blend_of, depth_write: *depth_write };
                // depthtex0 is the buffer being drawn into: gbuffers programs read depthtex1.
                let textures = BindableTextures {
                    naming: SamplerNaming::AnyPack,
                    harness: &harness_textures,
                    colors: &snapshot_colors,
                    depth0: &depth1,
                    depth1: &depth1,
                    shadow,
                    sprites: *sprites,
                    mipmapped: &NO_MIPMAPS,
                };
                let missing = pack.loader.missing_program_draws();
                let draw = GeometryDraw::new(gpu, pack, missing, scene, &values, &textures, *program, &state, vertices, step.label.clone())?;
                if let Some(pipeline) = draw.pipeline() {
                    zeroed_inputs.extend(pipeline.zeroed_inputs.iter().cloned());
                    zeroed_uniforms.extend(pipeline.zeroed_uniforms.iter().cloned());
                }
                let written = draw.buffers().iter().map(|b| (format!("colortex{b}"), WrittenTexture::Buffer(*b, current[b]))).collect();
                (Work::Geometry { draw, current, snapshots }, written)
            }
            PlannedWork::DepthCopy => (Work::DepthCopy, Vec::new()),
            PlannedWork::ShadowGeometry { program, vertices, render_stage } => {
                let values = uniforms::with_render_stage(&shadow_values, render_stage);
                let blend_of = |b: u8| pack.blend_of(Some(program), b, &Blend::Off);
                let state = DrawState { blend_of: &blend_of, depth_write: true };
                // The shadow maps being drawn read as nothing drawn; the frame's buffers are not bound.
                let textures = BindableTextures {
                    naming: SamplerNaming::ShadowPass,
                    harness: &harness_textures,
                    colors: &shadow_colours,
                    depth0: &depth1,
                    depth1: &depth1,
                    shadow: ShadowTextures::empty(&harness_textures),
                    sprites: Sprites::Blocks,
                    mipmapped: &NO_MIPMAPS,
                };
                let missing = pack.loader.missing_program_draws();
                let draw = GeometryDraw::new(gpu, pack, missing, scene, &values, &textures, Some(program), &state, vertices, step.label.clone())?;
                if let Some(pipeline) = draw.pipeline() {
                    zeroed_inputs.extend(pipeline.zeroed_inputs.iter().cloned());
                    zeroed_uniforms.extend(pipeline.zeroed_uniforms.iter().cloned());
                }
                let written = draw.buffers().iter().map(|b| (format!("shadowcolor{b}"), WrittenTexture::ShadowColour(*b))).collect();
                (Work::ShadowGeometry(draw), written)
            }
            PlannedWork::ShadowDepthCopy => (Work::ShadowDepthCopy, Vec::new()),
            PlannedWork::Fullscreen { program, current, into_screen, mipmaps } => {
                let reading: BTreeMap<u8, (wgpu::Texture, wgpu::TextureFormat)> =
                    buffers.iter().map(|(b, buffer)| (*b, (buffer.textures[current[b]].clone(), buffer.format))).collect();
                let formats: BTreeMap<u8, wgpu::TextureFormat> =
                    if *into_screen { BTreeMap::from([(0, OUT)]) } else { buffers.iter().map(|(b, buffer)| (*b, buffer.format)).collect() };
                let blend_of = |b: u8| pack.blend_of(Some(program), b, &Blend::Off);
                let textures = BindableTextures {
                    naming: SamplerNaming::AnyPack,
                    harness: &harness_textures,
                    colors: &reading,
                    depth0: &depth0,
                    depth1: &depth1,
                    shadow,
                    sprites: Sprites::Blocks,
                    mipmapped: mipmaps,
                };
                let kind = PassKind::FullscreenInto { formats: &formats, blend_of: &blend_of };
                let pipeline = ProgramPipeline::new(gpu, pack, program, &fullscreen_values, kind, &textures, UniformBinding::ReadOnlyStorage)?;
                zeroed_uniforms.extend(pipeline.zeroed_uniforms.iter().cloned());
                let written = if *into_screen {
                    vec![("screen".to_string(), WrittenTexture::Screen)]
                } else {
                    program.render_targets.iter().map(|b| (format!("colortex{b}"), WrittenTexture::Buffer(*b, 1 - current[b]))).collect()
                };
                (Work::Fullscreen { program, pipeline, current, into_screen: *into_screen, mipmaps }, written)
            }
            PlannedWork::ScreenCopy { current } => {
                (Work::ScreenCopy(PassthroughPipeline::new(gpu, &buffers[&0].textures[*current])?), vec![("screen".to_string(), WrittenTexture::Screen)])
            }
        };
        steps.push((step.label.as_str(), work, written));
    }
    for name in zeroed_uniforms {
        note(format!("uniform {name}: zero (the harness has no value for it)"));
    }
    for input in zeroed_inputs {
        note(format!("vertex input {input}: zero (the harness's vertices do not carry it)"));
    }

    // Run `frames` frames, each followed by a one-tap pass-through of colortex0 to a texture of
    // its own (the floor the frame's cost is measured against); the textures are read back, and
    // their NaN and Inf counted, after every step of the last frame only.
    let floor_target = texture("pass-through output (RGBA32F)", OUT, every_use);
    let floor = PassthroughPipeline::new(gpu, &buffers[&0].textures[plan.current[&0]])?;
    let render_passes = steps.iter().filter(|(_, work, _)| !work.is_copy()).count() as u32 + 1;
    let queries = gpu.timestamps.then(|| {
        device.create_query_set(&wgpu::QuerySetDescriptor { label: Some("pass timestamps"), ty: wgpu::QueryType::Timestamp, count: render_passes * 2 })
    });
    let new_encoder = || device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: None });
    let submit = |encoder: wgpu::CommandEncoder| -> Result<f64, HarnessError> {
        let started = Instant::now();
        gpu.queue.submit([encoder.finish()]);
        device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| HarnessError::Wgpu(format!("waiting for the GPU: {e}")))?;
        Ok(started.elapsed().as_secs_f64() * 1000.0)
    };
    let frames = frames.max(1);
    let mut reports: Vec<AnyPassReport> = Vec::new();
    // Per frame: each step's time (GPU where timestamps exist, else wall) and the floor's.
    let mut step_ms: Vec<Vec<f64>> = vec![Vec::new(); steps.len()];
    let mut floor_ms = Vec::new();
    for frame in 0..frames {
        let last = frame + 1 == frames;
        let mut encoder = new_encoder();
        // Both textures of every buffer, as the pack's directives say.
        let colours: Vec<(&wgpu::Texture, [f64; 4])> =
            buffers.iter().flat_map(|(b, buffer)| buffer.textures.iter().map(move |t| (t, pack.clear_of(*b).colour(*b, scene.sky.fog_color)))).collect();
        record_clears(&mut encoder, &colours, &depth0);
        let mut shadow_clears: Vec<(&wgpu::Texture, [f64; 4])> =
            shadow_colours.iter().map(|(b, (t, _))| (t, pack.shadow_clear_of(*b).shadow_colour())).collect();
        shadow_clears.extend(shadow_depth_read.iter().map(|t| (t, [1.0; 4])));
        record_clears(&mut encoder, &shadow_clears, &shadow_depth[0]);
        record_clears(&mut encoder, &[], &shadow_depth[1]);
        submit(encoder)?;
        let mut timed = 0u32;
        let mut stamp = |timestamps: bool| {
            let q = queries.as_ref().filter(|_| timestamps)?;
            timed += 1;
            Some(wgpu::RenderPassTimestampWrites {
                query_set: q,
                beginning_of_pass_write_index: Some(2 * (timed - 1)),
                end_of_pass_write_index: Some(2 * (timed - 1) + 1),
            })
        };
        let mut walls = Vec::new();
        for (label, work, written) in &steps {
            let mut encoder = new_encoder();
            let stamps = stamp(!work.is_copy());
            match work {
                Work::Geometry { draw, current, snapshots } => {
                    for b in *snapshots {
                        let buffer = &buffers[b];
                        encoder.copy_texture_to_texture(buffer.textures[current[b]].as_image_copy(), buffer.snapshot.as_image_copy(), size);
                    }
                    draw.record(&mut encoder, &|b| &buffers[&b].textures[current[&b]], &depth0, stamps);
                }
                Work::DepthCopy => encoder.copy_texture_to_texture(depth0.as_image_copy(), depth1.as_image_copy(), size),
                Work::ShadowGeometry(draw) => {
                    draw.record(&mut encoder, &|b| &shadow_colours[&b].0, &shadow_depth[0], stamps);
                    depth_as_luminance.record(&mut encoder, &shadow_depth_read[0], None);
                }
                Work::ShadowDepthCopy => {
                    encoder.copy_texture_to_texture(shadow_depth[0].as_image_copy(), shadow_depth[1].as_image_copy(), shadow_size);
                    encoder.copy_texture_to_texture(shadow_depth_read[0].as_image_copy(), shadow_depth_read[1].as_image_copy(), shadow_size);
                }
                Work::Fullscreen { program, pipeline, current, into_screen, mipmaps } => {
                    for b in *mipmaps {
                        mipmap_pipelines.record(gpu, &mut encoder, &buffers[b].textures[current[b]]);
                    }
                    let target = |b: u8| if *into_screen { &screen } else { &buffers[&b].textures[1 - current[&b]] };
                    pipeline.record_fullscreen_into(&mut encoder, program, &target, wgpu::LoadOp::Load, &quad, stamps);
                }
                Work::ScreenCopy(copy) => copy.record(&mut encoder, &screen, stamps),
            }
            let wall_ms = submit(encoder)?;
            walls.push(wall_ms);
            if last {
                let mut non_finite = BTreeMap::new();
                let mut images = Vec::new();
                for (name, texture) in written {
                    let image = match texture {
                        WrittenTexture::Screen => read_texture(gpu, &screen, OUT)?,
                        WrittenTexture::Buffer(b, i) => read_texture(gpu, &buffers[b].textures[*i], buffers[b].format)?,
                        WrittenTexture::ShadowColour(b) => read_texture(gpu, &shadow_colours[b].0, shadow_colours[b].1)?,
                    };
                    non_finite.insert(name.clone(), image.non_finite());
                    images.push((name.clone(), image));
                }
                reports.push(AnyPassReport { pass: label.to_string(), wall_ms, gpu_ms: None, median_ms: 0.0, non_finite, images });
            }
        }
        let mut encoder = new_encoder();
        floor.record(&mut encoder, &floor_target, stamp(true));
        walls.push(submit(encoder)?);
        let gpu_ms = match &queries {
            Some(q) => Some(read_pass_ms(gpu, q, render_passes)?),
            None => None,
        };
        // The timestamps are in order of the timed passes; the depth copies have wall time only.
        let mut gpu_iter = gpu_ms.iter().flatten().copied();
        for (i, (_, work, _)) in steps.iter().enumerate() {
            let gpu_time = if work.is_copy() { None } else { gpu_iter.next() };
            step_ms[i].push(gpu_time.unwrap_or(walls[i]));
            if last {
                reports[i].gpu_ms = gpu_time;
            }
        }
        floor_ms.push(gpu_iter.next().unwrap_or(walls[steps.len()]));
    }
    // The first frame pays for llvmpipe's lazy shader compilation: medians leave it out.
    let settled = |samples: &[f64]| median(if samples.len() > 1 { &samples[1..] } else { samples });
    for (report, samples) in reports.iter_mut().zip(&step_ms) {
        report.median_ms = settled(samples);
    }
    let frame_ms: Vec<f64> = (0..frames).map(|f| step_ms.iter().map(|s| s[f]).sum()).collect();
    let timing = FrameTiming { frames, frame_ms: settled(&frame_ms), passthrough_ms: settled(&floor_ms) };

    let mut images = BTreeMap::new();
    for (b, buffer) in &buffers {
        images.insert(*b, read_texture(gpu, &buffer.textures[plan.current[b]], buffer.format)?);
    }
    not_modelled.sort();
    not_modelled.dedup();
    Ok(AnyFrame {
        image: read_texture(gpu, &screen, OUT)?,
        buffers: images,
        depth0: read_texture(gpu, &depth0, DEPTH)?,
        depth1: read_texture(gpu, &depth1, DEPTH)?,
        passes: reports,
        timing,
        not_modelled,
    })
}
