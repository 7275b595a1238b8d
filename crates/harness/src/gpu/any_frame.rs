//! Any pack's frame ([`crate::any_pack`]), pass by pass, as OptiFine 1.16.5 and later draw it:
//!
//! 1. clear: each colour buffer as its directives say (colortex0 the fog colour, colortex1
//!    white, the rest transparent black, or its `ClearColor`), depth to 1;
//! 2. prepare*: full-screen;
//! 3. the loader's overlay phase before the terrain; terrain (gbuffers_terrain's chain); the
//!    phase before the water;
//! 4. depthtex0 to depthtex1;
//! 5. deferred*: full-screen;
//! 6. gbuffers_water's chain draws water and glass; the phase after the water;
//! 7. composite*: full-screen;
//! 8. final into the screen (RGBA32F, so NaN and Inf survive), or colortex0 copied there when
//!    the pack has no final.
//!
//! Every colour buffer has two textures. gbuffers programs draw into the buffer's current one;
//! a full-screen program reads the current ones and writes the other of each buffer it draws
//! into, which then becomes current (OptiFine's flip). A gbuffers program that samples a colour
//! buffer reads a copy taken just before its draw (in the game it would read the buffer it
//! draws into, which GL leaves undefined).
//!
//! After each pass the buffers it wrote are read back and their NaN and Inf counted.

use std::collections::{BTreeMap, BTreeSet};
use std::time::Instant;

use crate::HarnessError;
use crate::any_pack::{AnyPack, BufferClear};
use crate::images::FloatImage;
use crate::loader::Phase;
use crate::mesh::{PackVertex, SceneMesh};
use crate::program::{Blend, DEFAULT_TRANSLUCENT_BLEND, LoadedProgram, PackResources, TERRAIN_CHAIN, WATER_CHAIN};
use crate::scene::Scene;
use crate::uniforms::{self, Pass, Value};

use super::Gpu;
use super::bindings::{
    BindableTextures, DEPTH, DrawState, FullscreenQuad, HarnessTextures, OUT, PassKind, ProgramPipeline, SamplerNaming, UniformBinding,
    colour_buffers_read, view,
};
use super::frame::overlay_phase;
use super::geometry::{GeometryDraw, depth_attachment};
use super::own::PassthroughPipeline;
use super::readback::{read_pass_ms, read_texture};

/// One pass of the frame as it ran.
#[derive(Clone, Debug, serde::Serialize)]
pub struct AnyPassReport {
    /// `terrain (gbuffers_terrain)`, `composite1`, `depth copy`, …
    pub pass: String,
    pub wall_ms: f64,
    /// GPU time from timestamps, when the adapter has them.
    pub gpu_ms: Option<f64>,
    /// NaN and Inf texels in each buffer the pass wrote (`colortex2`, `screen`), float buffers
    /// only (normalised formats cannot hold them).
    pub non_finite: BTreeMap<String, usize>,
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
    /// Whether NaN and Inf can be stored (float formats).
    float: bool,
}

enum Work {
    Geometry { draw: GeometryDraw, current: BTreeMap<u8, usize>, snapshots: BTreeSet<u8> },
    DepthCopy,
    Fullscreen { program: usize, pipeline: ProgramPipeline, current: BTreeMap<u8, usize>, into_screen: bool },
    ScreenCopy(PassthroughPipeline),
}

struct Step {
    label: String,
    work: Work,
    /// What to count NaN and Inf in afterwards: (name, buffer and texture index) or the screen.
    written: Vec<(String, Option<(u8, usize)>)>,
}

/// Renders one frame of `scene` with any pack's programs.
pub fn render_any(gpu: &Gpu, pack: &AnyPack, scene: &Scene, mesh: &SceneMesh) -> Result<AnyFrame, HarnessError> {
    gpu.check_resolution(scene.width(), scene.height())
        .map_err(|e| HarnessError::Scene(format!("scene {}: {e}", scene.name)))?;
    gpu.checked("frame", || render_any_checked(gpu, pack, scene, mesh))?
}

fn render_any_checked(gpu: &Gpu, pack: &AnyPack, scene: &Scene, mesh: &SceneMesh) -> Result<AnyFrame, HarnessError> {
    let device = &gpu.device;
    let size = wgpu::Extent3d { width: scene.width(), height: scene.height(), depth_or_array_layers: 1 };
    let texture = |label: &str, format: wgpu::TextureFormat, usage: wgpu::TextureUsages| {
        device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage,
            view_formats: &[],
        })
    };
    let every_use = wgpu::TextureUsages::RENDER_ATTACHMENT
        | wgpu::TextureUsages::TEXTURE_BINDING
        | wgpu::TextureUsages::COPY_SRC
        | wgpu::TextureUsages::COPY_DST;

    // Every colour buffer a program writes or reads.
    let final_program = pack.fullscreen.iter().position(|p| p.name == "final");
    let mut used: BTreeSet<u8> = BTreeSet::from([0]);
    for program in pack.gbuffers.values() {
        used.extend(program.render_targets.iter().copied());
        used.extend(colour_buffers_read(pack, program, SamplerNaming::AnyPack, true));
    }
    for (i, program) in pack.fullscreen.iter().enumerate() {
        if Some(i) != final_program {
            used.extend(program.render_targets.iter().copied());
        }
        used.extend(colour_buffers_read(pack, program, SamplerNaming::AnyPack, false));
    }
    let mut buffers: BTreeMap<u8, Buffer> = BTreeMap::new();
    for b in used {
        let format = gpu.texture_format(pack.format_of(b))?;
        let label = |what: &str| format!("colortex{b} {what}");
        buffers.insert(
            b,
            Buffer {
                textures: [texture(&label("A"), format, every_use), texture(&label("B"), format, every_use)],
                snapshot: texture(&label("as gbuffers read it"), format, every_use),
                format,
                float: matches!(format, wgpu::TextureFormat::Rgba16Float | wgpu::TextureFormat::Rgba32Float),
            },
        );
    }
    let depth0 = texture("depthtex0", DEPTH, every_use);
    let depth1 = texture("depthtex1", DEPTH, every_use);
    let screen = texture("screen (RGBA32F)", OUT, every_use);
    let harness_textures = HarnessTextures::new(gpu, pack);
    let quad = FullscreenQuad::new(gpu);

    let mut not_modelled = pack.not_modelled.clone();
    let with_zeros = |program: &LoadedProgram, pass: Pass, not_modelled: &mut Vec<String>| -> BTreeMap<String, Value> {
        let mut values = uniforms::values(scene, pass);
        for stage in [&program.vertex, &program.fragment] {
            for (name, zero) in uniforms::zeros_for_unfilled(&stage.module, &values) {
                let line = format!("uniform {}: zero (the harness has no value for it)", uniforms::shipped_name(&name));
                if !not_modelled.contains(&line) {
                    not_modelled.push(line);
                }
                values.insert(name, zero);
            }
        }
        values
    };

    // The frame's steps, each pipeline built against the textures current at its turn.
    let mut current: BTreeMap<u8, usize> = buffers.keys().map(|b| (*b, 0)).collect();
    let snapshot_colors: BTreeMap<u8, (wgpu::Texture, wgpu::TextureFormat)> =
        buffers.iter().map(|(b, buffer)| (*b, (buffer.snapshot.clone(), buffer.format))).collect();
    let mut steps: Vec<Step> = Vec::new();
    let gbuffers_values_for = |program: Option<&LoadedProgram>, not_modelled: &mut Vec<String>| match program {
        Some(p) => with_zeros(p, Pass::Gbuffers, not_modelled),
        None => uniforms::values(scene, Pass::Gbuffers),
    };
    let geometry = |steps: &mut Vec<Step>,
                        current: &BTreeMap<u8, usize>,
                        program: Option<&LoadedProgram>,
                        default_blend: &Blend,
                        depth_write: bool,
                        vertices: &[PackVertex],
                        what: &str,
                        not_modelled: &mut Vec<String>|
     -> Result<(), HarnessError> {
        let values = gbuffers_values_for(program, not_modelled);
        let blend_of = |b: u8| pack.blend_of(program, b, default_blend);
        let state = DrawState { blend_of: &blend_of, depth_write };
        let textures = BindableTextures {
            naming: SamplerNaming::AnyPack,
            harness: &harness_textures,
            colors: &snapshot_colors,
            depth0: &depth1,
            depth1: &depth1,
        };
        let label = format!("{what} ({})", program.map_or("the loader's own", |p| p.name.as_str()));
        let missing = pack.loader.missing_program_draws();
        let draw = GeometryDraw::new(gpu, pack, missing, scene, &values, &textures, program, &state, vertices, label.clone())?;
        if let Some(Some(pipeline)) = program.map(|_| draw.pipeline()) {
            for input in &pipeline.zeroed_inputs {
                let line = format!("vertex input {input}: zero (the harness's vertices do not carry it)");
                if !not_modelled.contains(&line) {
                    not_modelled.push(line);
                }
            }
        }
        let snapshots = program.map(|p| colour_buffers_read(pack, p, SamplerNaming::AnyPack, true)).unwrap_or_default();
        let written = draw.buffers().iter().map(|b| (format!("colortex{b}"), Some((*b, current[b])))).collect();
        steps.push(Step { label, work: Work::Geometry { draw, current: current.clone(), snapshots }, written });
        Ok(())
    };
    let fullscreen = |steps: &mut Vec<Step>, current: &mut BTreeMap<u8, usize>, index: usize, not_modelled: &mut Vec<String>| -> Result<(), HarnessError> {
        let program = &pack.fullscreen[index];
        let into_screen = Some(index) == final_program;
        let values = with_zeros(program, Pass::Fullscreen, not_modelled);
        let reading: BTreeMap<u8, (wgpu::Texture, wgpu::TextureFormat)> =
            buffers.iter().map(|(b, buffer)| (*b, (buffer.textures[current[b]].clone(), buffer.format))).collect();
        let formats: BTreeMap<u8, wgpu::TextureFormat> =
            if into_screen { BTreeMap::from([(0, OUT)]) } else { buffers.iter().map(|(b, buffer)| (*b, buffer.format)).collect() };
        let no_blend = Blend::Off;
        let blend_of = |b: u8| pack.blend_of(Some(program), b, &no_blend);
        let textures = BindableTextures { naming: SamplerNaming::AnyPack, harness: &harness_textures, colors: &reading, depth0: &depth0, depth1: &depth1 };
        let pipeline = ProgramPipeline::new(
            gpu,
            pack,
            program,
            &values,
            PassKind::FullscreenInto { formats: &formats, blend_of: &blend_of },
            &textures,
            UniformBinding::ReadOnlyStorage,
        )?;
        let before = current.clone();
        let written = if into_screen {
            vec![("screen".to_string(), None)]
        } else {
            let mut written = Vec::new();
            for b in &program.render_targets {
                let flipped = 1 - before[b];
                current.insert(*b, flipped);
                written.push((format!("colortex{b}"), Some((*b, flipped))));
            }
            written
        };
        steps.push(Step { label: program.name.clone(), work: Work::Fullscreen { program: index, pipeline, current: before, into_screen }, written });
        Ok(())
    };
    let family = |prefix: &str| -> Vec<usize> {
        (0..pack.fullscreen.len()).filter(|&i| pack.fullscreen[i].name.starts_with(prefix)).collect()
    };
    for i in family("prepare") {
        fullscreen(&mut steps, &mut current, i, &mut not_modelled)?;
    }
    let overlays_in = |phase: Phase| mesh.overlay.iter().filter(move |(kind, _)| overlay_phase(pack.loader, scene, *kind) == phase);
    let no_blend = Blend::Off;
    for (kind, vertices) in overlays_in(Phase::BeforeTerrain) {
        let program = pack.resolve(pack.loader.program_chain(*kind));
        geometry(&mut steps, &current, program, &DEFAULT_TRANSLUCENT_BLEND, crate::loader::writes_depth(*kind), vertices, &format!("{kind:?}"), &mut not_modelled)?;
    }
    geometry(&mut steps, &current, pack.resolve(&TERRAIN_CHAIN), &no_blend, true, &mesh.terrain, "terrain", &mut not_modelled)?;
    for (kind, vertices) in overlays_in(Phase::BeforeWater) {
        let program = pack.resolve(pack.loader.program_chain(*kind));
        geometry(&mut steps, &current, program, &DEFAULT_TRANSLUCENT_BLEND, crate::loader::writes_depth(*kind), vertices, &format!("{kind:?}"), &mut not_modelled)?;
    }
    steps.push(Step { label: "depth copy".into(), work: Work::DepthCopy, written: Vec::new() });
    for i in family("deferred") {
        fullscreen(&mut steps, &mut current, i, &mut not_modelled)?;
    }
    geometry(&mut steps, &current, pack.resolve(&WATER_CHAIN), &DEFAULT_TRANSLUCENT_BLEND, true, &mesh.translucent, "water", &mut not_modelled)?;
    for (kind, vertices) in overlays_in(Phase::AfterWater) {
        let program = pack.resolve(pack.loader.program_chain(*kind));
        geometry(&mut steps, &current, program, &DEFAULT_TRANSLUCENT_BLEND, crate::loader::writes_depth(*kind), vertices, &format!("{kind:?}"), &mut not_modelled)?;
    }
    for i in family("composite") {
        fullscreen(&mut steps, &mut current, i, &mut not_modelled)?;
    }
    match final_program {
        Some(i) => fullscreen(&mut steps, &mut current, i, &mut not_modelled)?,
        None => {
            let colortex0 = &buffers[&0].textures[current[&0]];
            steps.push(Step {
                label: "colortex0 to the screen (no final)".into(),
                work: Work::ScreenCopy(PassthroughPipeline::new(gpu, colortex0)?),
                written: vec![("screen".to_string(), None)],
            });
        }
    }

    // Run.
    let render_passes = steps.iter().filter(|s| !matches!(s.work, Work::DepthCopy)).count() as u32;
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
    let mut encoder = new_encoder();
    record_clears(&mut encoder, pack, scene, &buffers, &depth0);
    submit(encoder)?;
    let mut reports = Vec::new();
    let mut timed = 0u32;
    for step in &steps {
        let mut encoder = new_encoder();
        let stamps = match (&queries, &step.work) {
            (_, Work::DepthCopy) | (None, _) => None,
            (Some(q), _) => {
                timed += 1;
                Some(wgpu::RenderPassTimestampWrites {
                    query_set: q,
                    beginning_of_pass_write_index: Some(2 * (timed - 1)),
                    end_of_pass_write_index: Some(2 * (timed - 1) + 1),
                })
            }
        };
        match &step.work {
            Work::Geometry { draw, current, snapshots } => {
                for b in snapshots {
                    let buffer = &buffers[b];
                    encoder.copy_texture_to_texture(buffer.textures[current[b]].as_image_copy(), buffer.snapshot.as_image_copy(), size);
                }
                draw.record(&mut encoder, &|b| &buffers[&b].textures[current[&b]], &depth0, stamps);
            }
            Work::DepthCopy => encoder.copy_texture_to_texture(depth0.as_image_copy(), depth1.as_image_copy(), size),
            Work::Fullscreen { program, pipeline, current, into_screen } => {
                let target = |b: u8| if *into_screen { &screen } else { &buffers[&b].textures[1 - current[&b]] };
                let program = &pack.fullscreen[*program];
                pipeline.record_fullscreen_into(&mut encoder, program, &target, wgpu::LoadOp::Load, &quad, stamps);
            }
            Work::ScreenCopy(copy) => copy.record(&mut encoder, &screen, stamps),
        }
        let wall_ms = submit(encoder)?;
        let mut non_finite = BTreeMap::new();
        for (name, texture) in &step.written {
            let count = match texture {
                None => read_texture(gpu, &screen, OUT)?.non_finite(),
                Some((b, i)) if buffers[b].float => read_texture(gpu, &buffers[b].textures[*i], buffers[b].format)?.non_finite(),
                Some(_) => 0,
            };
            non_finite.insert(name.clone(), count);
        }
        reports.push(AnyPassReport { pass: step.label.clone(), wall_ms, gpu_ms: None, non_finite });
    }
    if let Some(q) = &queries {
        let mut gpu_ms = read_pass_ms(gpu, q, render_passes)?.into_iter();
        for (report, step) in reports.iter_mut().zip(&steps) {
            if !matches!(step.work, Work::DepthCopy) {
                report.gpu_ms = gpu_ms.next();
            }
        }
    }

    let mut images = BTreeMap::new();
    for (b, buffer) in &buffers {
        images.insert(*b, read_texture(gpu, &buffer.textures[current[b]], buffer.format)?);
    }
    not_modelled.sort();
    not_modelled.dedup();
    Ok(AnyFrame {
        image: read_texture(gpu, &screen, OUT)?,
        buffers: images,
        depth0: read_texture(gpu, &depth0, DEPTH)?,
        depth1: read_texture(gpu, &depth1, DEPTH)?,
        passes: reports,
        not_modelled,
    })
}

/// Clears both textures of every colour buffer as the pack's directives say, and depth to 1.
fn record_clears(encoder: &mut wgpu::CommandEncoder, pack: &AnyPack, scene: &Scene, buffers: &BTreeMap<u8, Buffer>, depth0: &wgpu::Texture) {
    let fog = scene.sky.fog_color;
    let views: Vec<(u8, wgpu::TextureView)> =
        buffers.iter().flat_map(|(b, buffer)| buffer.textures.iter().map(move |t| (*b, view(t)))).collect();
    let attachments: Vec<Option<wgpu::RenderPassColorAttachment>> = views
        .iter()
        .map(|(b, v)| {
            let color = match (pack.clear_of(*b), b) {
                (BufferClear::Color([r, g, b, a]), _) => wgpu::Color { r, g, b, a },
                (BufferClear::Keep, _) => wgpu::Color::TRANSPARENT,
                (BufferClear::Default, 0) => wgpu::Color { r: fog[0], g: fog[1], b: fog[2], a: 1.0 },
                (BufferClear::Default, 1) => wgpu::Color::WHITE,
                (BufferClear::Default, _) => wgpu::Color::TRANSPARENT,
            };
            Some(wgpu::RenderPassColorAttachment {
                view: v,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations { load: wgpu::LoadOp::Clear(color), store: wgpu::StoreOp::Store },
            })
        })
        .collect();
    let depth_view = view(depth0);
    for chunk in attachments.chunks(8) {
        encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("clear"),
            color_attachments: chunk,
            depth_stencil_attachment: Some(depth_attachment(&depth_view, true)),
            ..Default::default()
        });
    }
}
