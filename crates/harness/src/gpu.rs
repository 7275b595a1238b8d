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

use std::borrow::Cow;
use std::collections::{BTreeMap, BTreeSet};
use std::time::Instant;

use wgpu::util::DeviceExt as _;

use crate::HarnessError;
use crate::images::FloatImage;
use crate::mesh::{self, SceneMesh, offsets};
use crate::loader::{self, MissingProgramDraws, Phase};
use crate::program::{Blend, BlendFactor, BufferFormat, LoadedPack, LoadedProgram, LoadedStage};
use crate::scene::OverlayKind;
use crate::scene::Scene;
use crate::uniforms::{self, Pass};

/// The Debian package that provides the CPU Vulkan driver (lavapipe).
pub const VULKAN_PACKAGE: &str = "mesa-vulkan-drivers";

pub struct Gpu {
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub adapter: wgpu::AdapterInfo,
    pub timestamps: bool,
    float32_filterable: bool,
    norm16: bool,
}

impl Gpu {
    /// The first Vulkan adapter (lavapipe on a machine without a GPU).
    pub fn new() -> Result<Gpu, HarnessError> {
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
            backends: wgpu::Backends::VULKAN,
            ..wgpu::InstanceDescriptor::new_without_display_handle()
        });
        let adapters = pollster::block_on(instance.enumerate_adapters(wgpu::Backends::VULKAN));
        let adapter = adapters.into_iter().next().ok_or_else(|| {
            HarnessError::NoAdapter(format!(
                "no Vulkan adapter found: install the Debian package {VULKAN_PACKAGE} (lavapipe, Mesa's CPU Vulkan driver): \
                 `apt-get install --no-install-recommends {VULKAN_PACKAGE}`"
            ))
        })?;
        let info = adapter.get_info();
        let available = adapter.features();
        let wanted = wgpu::Features::TIMESTAMP_QUERY
            | wgpu::Features::FLOAT32_FILTERABLE
            | wgpu::Features::TEXTURE_FORMAT_16BIT_NORM
            // Rgba16Unorm is renderable only with the adapter's own format capabilities.
            | wgpu::Features::TEXTURE_ADAPTER_SPECIFIC_FORMAT_FEATURES;
        let features = available & wanted;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("tidepack-harness"),
            required_features: features,
            // A gbuffers program may write 8 colour buffers at once, as in OptiFine: the
            // adapter's own attachment limits, not wgpu's portable 32 bytes a sample.
            required_limits: wgpu::Limits {
                max_color_attachments: adapter.limits().max_color_attachments,
                max_color_attachment_bytes_per_sample: adapter.limits().max_color_attachment_bytes_per_sample,
                ..wgpu::Limits::default().using_resolution(adapter.limits())
            },
            ..Default::default()
        }))
        .map_err(|e| HarnessError::NoAdapter(format!("the Vulkan adapter {} refused a device: {e}", info.name)))?;
        Ok(Gpu {
            device,
            queue,
            adapter: info,
            timestamps: features.contains(wgpu::Features::TIMESTAMP_QUERY),
            float32_filterable: features.contains(wgpu::Features::FLOAT32_FILTERABLE),
            norm16: features.contains(wgpu::Features::TEXTURE_FORMAT_16BIT_NORM),
        })
    }

    /// Whether this device can render at `width` x `height`: every render target is that big,
    /// and the largest readback, the RGBA32F output (16 bytes a pixel, rows padded to 256
    /// bytes), is one buffer that must fit the device's `max_buffer_size`.
    pub fn check_resolution(&self, width: u32, height: u32) -> Result<(), HarnessError> {
        let limits = self.device.limits();
        let side = limits.max_texture_dimension_2d;
        if width > side || height > side {
            return Err(HarnessError::Scene(format!(
                "resolution {width}x{height} is too large: this device's textures are at most {side}x{side} pixels"
            )));
        }
        let bytes = readback_bytes(width, height);
        if bytes > limits.max_buffer_size {
            let mib = |b: u64| b as f64 / (1u64 << 20) as f64;
            // The largest square that fits, for the message.
            let mut fits = (limits.max_buffer_size as f64 / 16.0).sqrt() as u32;
            while fits > 1 && readback_bytes(fits, fits) > limits.max_buffer_size {
                fits -= 1;
            }
            return Err(HarnessError::Scene(format!(
                "resolution {width}x{height} is too large: reading the RGBA32F output back takes one {:.0} MiB buffer, \
                 over this device's limit of {:.0} MiB (max_buffer_size); the largest square resolution is {fits}x{fits}",
                mib(bytes),
                mib(limits.max_buffer_size)
            )));
        }
        Ok(())
    }

    /// `name (backend, device type, driver)`.
    pub fn describe(&self) -> String {
        let a = &self.adapter;
        format!("{} ({:?}, {:?}, {} {})", a.name, a.backend, a.device_type, a.driver, a.driver_info)
    }

    fn texture_format(&self, format: BufferFormat) -> Result<wgpu::TextureFormat, HarnessError> {
        Ok(match format {
            BufferFormat::Rgba8 => wgpu::TextureFormat::Rgba8Unorm,
            BufferFormat::Rgba16 if self.norm16 => wgpu::TextureFormat::Rgba16Unorm,
            BufferFormat::Rgba16 => {
                return Err(HarnessError::Unsupported(format!(
                    "the pack declares an RGBA16 buffer and the adapter {} lacks TEXTURE_FORMAT_16BIT_NORM",
                    self.adapter.name
                )));
            }
            BufferFormat::Rgba16F => wgpu::TextureFormat::Rgba16Float,
            BufferFormat::Rgba32F => wgpu::TextureFormat::Rgba32Float,
        })
    }

    fn filterable(&self, format: wgpu::TextureFormat) -> bool {
        format != wgpu::TextureFormat::Rgba32Float || self.float32_filterable
    }

    /// Runs `f` inside a validation error scope and turns a captured error into a HarnessError.
    pub(crate) fn checked<T>(&self, what: &str, f: impl FnOnce() -> T) -> Result<T, HarnessError> {
        let scope = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let value = f();
        match pollster::block_on(scope.pop()) {
            Some(e) => {
                let mut message = format!("{what}: {e}");
                let mut source = std::error::Error::source(&e);
                while let Some(inner) = source {
                    message.push_str(&format!(": {inner}"));
                    source = inner.source();
                }
                Err(HarnessError::Wgpu(message))
            }
            None => Ok(value),
        }
    }
}

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
    /// GPU time from timestamps, when the adapter has them.
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

/// What a sampler name in a program refers to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Source {
    Atlas,
    Lightmap,
    Noise,
    Color(u8),
    Depth0,
    Depth1,
    /// A custom texture of the pack (index into [`LoadedPack::custom_textures`]).
    Custom(usize),
}

/// Resolves a sampler name, custom textures of the pack first.
pub fn resolve_in_pack(pack: &LoadedPack, name: &str, gbuffers: bool) -> Result<Source, String> {
    let stage = if gbuffers { "gbuffers" } else { "composite" };
    match pack.custom_textures.iter().position(|t| t.stage == stage && t.unit == name) {
        Some(i) => Ok(Source::Custom(i)),
        None => resolve_sampler(name, gbuffers),
    }
}

/// Resolves a shipped sampler name for a program (`gbuffers` or full-screen).
pub fn resolve_sampler(name: &str, gbuffers: bool) -> Result<Source, String> {
    let aliases = [("gcolor", 0), ("gdepth", 1), ("gnormal", 2), ("composite", 3), ("gaux1", 4), ("gaux2", 5), ("gaux3", 6), ("gaux4", 7)];
    let color = name
        .strip_prefix("colortex")
        .and_then(|n| n.parse::<u8>().ok())
        .filter(|n| *n < 16)
        .or_else(|| aliases.iter().find(|(a, _)| *a == name).map(|(_, n)| *n));
    Ok(match (name, gbuffers) {
        ("noisetex", _) => Source::Noise,
        ("gtexture" | "texture" | "tex", true) => Source::Atlas,
        ("lightmap", true) => Source::Lightmap,
        ("depthtex1" | "depthtex2", _) => Source::Depth1,
        ("depthtex0" | "gdepthtex", false) => Source::Depth0,
        ("depthtex0" | "gdepthtex", true) => {
            return Err(format!("{name} is the depth buffer gbuffers_water draws into; read depthtex1 there"));
        }
        _ => match color {
            Some(n) if !gbuffers => Source::Color(n),
            Some(n) => {
                return Err(format!(
                    "{name} (colortex{n}) is not readable in gbuffers programs of this pipeline (nothing wrote it before translucents)"
                ));
            }
            None => return Err(format!("sampler {name} is not one the harness provides")),
        },
    })
}

struct Targets {
    colors: BTreeMap<u8, (wgpu::Texture, wgpu::TextureFormat)>,
    depth0: wgpu::Texture,
    depth1: wgpu::Texture,
    out: wgpu::Texture,
    passthrough: wgpu::Texture,
}

/// `module` with every `uniform` global moved to read-only storage. Types, member offsets and
/// bindings are unchanged, so the bytes [`uniforms::fill_block`] lays out read the same.
///
/// The harness binds uniform blocks this way because lavapipe (Mesa 22.3) recompiles a shader
/// with the current values of the uniform-buffer members its `if` conditions test
/// (`isEyeInWater`) at every draw, and never frees the copies (about 3 MB a frame); storage
/// buffers are never inlined. The image is the same bit for bit (crates/stress/tests/memory.rs).
pub(crate) fn uniforms_as_storage(module: &naga::Module) -> naga::Module {
    let mut module = module.clone();
    for (_, global) in module.global_variables.iter_mut() {
        if global.space == naga::AddressSpace::Uniform {
            global.space = naga::AddressSpace::Storage { access: naga::StorageAccess::LOAD };
        }
    }
    module
}

const DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
const OUT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

fn view(t: &wgpu::Texture) -> wgpu::TextureView {
    t.create_view(&wgpu::TextureViewDescriptor::default())
}

fn clear_color(buffer: u8, scene: &Scene) -> wgpu::Color {
    match buffer {
        0 => {
            let f = scene.sky.fog_color;
            wgpu::Color { r: f[0], g: f[1], b: f[2], a: 1.0 }
        }
        1 => wgpu::Color::WHITE,
        _ => wgpu::Color::TRANSPARENT,
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

fn render_frame(
    gpu: &Gpu,
    pack: &LoadedPack,
    scene: &Scene,
    mesh: &SceneMesh,
    passthrough: bool,
    frames: usize,
) -> Result<(Frame, Vec<Vec<PassTiming>>), HarnessError> {
    let device = &gpu.device;
    let (w, h) = (scene.width(), scene.height());
    let size = wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 };

    // Colour buffers: everything either program writes or reads.
    let mut buffers: BTreeSet<u8> = BTreeSet::from([0]);
    buffers.extend(pack.water.render_targets.iter().copied());
    buffers.extend(pack.gbuffers.values().flat_map(|p| p.render_targets.iter().copied()));
    for (name, _) in crate::program::texture_resources(&pack.composite.fragment.interface)
        .into_iter()
        .chain(crate::program::texture_resources(&pack.composite.vertex.interface))
    {
        if let Ok(Source::Color(n)) = resolve_in_pack(pack, &name, false) {
            buffers.insert(n);
        }
    }
    let mut colors = BTreeMap::new();
    for &b in &buffers {
        let format = gpu.texture_format(pack.format_of(b))?;
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some(&format!("colortex{b}")),
            size,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        colors.insert(b, (texture, format));
    }
    let depth_texture = |label: &str| {
        device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: DEPTH,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        })
    };
    let out_texture = |label: &str| {
        device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: OUT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        })
    };
    let targets = Targets {
        colors,
        depth0: depth_texture("depthtex0"),
        depth1: depth_texture("depthtex1"),
        out: out_texture("composite output (colortex0 alternate, RGBA32F)"),
        passthrough: out_texture("pass-through output"),
    };

    let textures = StaticTextures::new(gpu, pack);
    let water_state = DrawState { blend_of: &|b| pack.blend_of(b), depth_write: true };
    let water = GeometryDraw::new(
        gpu,
        pack,
        scene,
        &targets,
        &textures,
        Some(&pack.water),
        &water_state,
        &mesh.translucent,
        "gbuffers_water".into(),
    )?;
    let no_blend = |_| Blend::Off;
    let fullscreen = DrawState { blend_of: &no_blend, depth_write: false };
    let composite = ProgramPipeline::new(gpu, pack, &pack.composite, scene, Pass::Fullscreen, &fullscreen, &targets, &textures)?;
    // Opaque terrain is drawn with blending off.
    let opaque = DrawState { blend_of: &no_blend, depth_write: true };
    let terrain =
        GeometryDraw::new(gpu, pack, scene, &targets, &textures, pack.terrain_program(), &opaque, &mesh.terrain, "terrain".into())?;
    // Rain, clouds, particles and the hand, grouped by when the loader draws them.
    let mut overlays: BTreeMap<Phase, Vec<GeometryDraw>> = BTreeMap::new();
    for (kind, vertices) in &mesh.overlay {
        let program = pack.resolve(pack.loader.program_chain(*kind));
        let state = DrawState { blend_of: &|b| pack.gbuffers_blend_of(program, b), depth_write: loader::writes_depth(*kind) };
        let label = format!("{kind:?} ({})", program.map_or("the loader's own", |p| p.name.as_str()));
        let draw = GeometryDraw::new(gpu, pack, scene, &targets, &textures, program, &state, vertices, label)?;
        overlays.entry(overlay_phase(pack, scene, *kind)).or_default().push(draw);
    }
    let copy_pipeline = if passthrough { Some(PassthroughPipeline::new(gpu, &targets.colors[&0].0)?) } else { None };

    let quad = fullscreen_quad();
    let quad_vertices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("full-screen quad"),
        contents: mesh::as_bytes(&quad),
        usage: wgpu::BufferUsages::VERTEX,
    });

    let passes = if passthrough { 4 } else { 3 };
    let queries = gpu.timestamps.then(|| {
        device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("pass timestamps"),
            ty: wgpu::QueryType::Timestamp,
            count: passes * 2,
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
            let depth0_view = view(&targets.depth0);
            // 1. clear
            let mut encoder = new_encoder();
            {
                let views: Vec<(u8, wgpu::TextureView)> = targets.colors.iter().map(|(b, (t, _))| (*b, view(t))).collect();
                let attachments: Vec<Option<wgpu::RenderPassColorAttachment>> = views
                    .iter()
                    .map(|(b, v)| {
                        Some(wgpu::RenderPassColorAttachment {
                            view: v,
                            depth_slice: None,
                            resolve_target: None,
                            ops: wgpu::Operations { load: wgpu::LoadOp::Clear(clear_color(*b, scene)), store: wgpu::StoreOp::Store },
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
            submit(encoder)?;
            let draw_phase = |phase: Phase, wall: &mut Vec<(String, f64)>| -> Result<(), HarnessError> {
                for draw in overlays.get(&phase).into_iter().flatten() {
                    let mut encoder = new_encoder();
                    draw.record(&mut encoder, &targets, None);
                    wall.push((draw.label.clone(), submit(encoder)?));
                }
                Ok(())
            };
            draw_phase(Phase::BeforeTerrain, &mut wall)?;
            // 2. terrain
            let mut encoder = new_encoder();
            terrain.record(&mut encoder, &targets, stamps(0));
            wall.push(("terrain".into(), submit(encoder)?));
            draw_phase(Phase::BeforeWater, &mut wall)?;
            // 3. depth copy
            let mut encoder = new_encoder();
            encoder.copy_texture_to_texture(targets.depth0.as_image_copy(), targets.depth1.as_image_copy(), size);
            wall.push(("depth copy".into(), submit(encoder)?));
            // 4. gbuffers_water
            let mut encoder = new_encoder();
            water.record(&mut encoder, &targets, stamps(1));
            wall.push(("gbuffers_water".into(), submit(encoder)?));
            draw_phase(Phase::AfterWater, &mut wall)?;
            // 5. composite
            let mut encoder = new_encoder();
            {
                let alternates: Vec<wgpu::TextureView> = pack
                    .composite
                    .render_targets
                    .iter()
                    .map(|b| if *b == 0 { view(&targets.out) } else { view(&composite.alternates[b]) })
                    .collect();
                let attachments: Vec<_> = alternates.iter().map(|v| Some(clear_attachment(v))).collect();
                let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("composite"),
                    color_attachments: &attachments,
                    depth_stencil_attachment: None,
                    timestamp_writes: stamps(2),
                    ..Default::default()
                });
                pass.set_pipeline(&composite.pipeline);
                for (i, g) in composite.bind_groups.iter().enumerate() {
                    pass.set_bind_group(i as u32, g, &[]);
                }
                pass.set_vertex_buffer(0, quad_vertices.slice(..));
                pass.draw(0..quad.len() as u32, 0..1);
            }
            wall.push(("composite".into(), submit(encoder)?));
            // 6. pass-through
            if let Some(p) = &copy_pipeline {
                let mut encoder = new_encoder();
                {
                    let v = view(&targets.passthrough);
                    let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                        label: Some("pass-through composite"),
                        color_attachments: &[Some(clear_attachment(&v))],
                        depth_stencil_attachment: None,
                        timestamp_writes: stamps(3),
                        ..Default::default()
                    });
                    pass.set_pipeline(&p.pipeline);
                    pass.set_bind_group(0, &p.bind_group, &[]);
                    pass.draw(0..3, 0..1);
                }
                wall.push(("pass-through composite".into(), submit(encoder)?));
            }
            Ok(())
        })??;

        // Timestamps.
        let gpu_ms: Vec<Option<f64>> = match &queries {
            Some(q) => read_pass_ms(gpu, q, passes)?.into_iter().map(Some).collect(),
            None => vec![None; passes as usize],
        };
        let mut timings = Vec::new();
        let mut timed = 0;
        for (name, ms) in wall {
            // The four timed passes carry GPU timestamps; the depth copy and the overlay draws
            // are timed by the wall clock only.
            let gpu_time = if TIMED_PASSES.contains(&name.as_str()) {
                timed += 1;
                gpu_ms[timed - 1]
            } else {
                None
            };
            timings.push(PassTiming { pass: name, gpu_ms: gpu_time, wall_ms: ms });
        }
        runs.push(timings);
    }
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

/// The passes with GPU timestamps, in frame order.
const TIMED_PASSES: [&str; 4] = ["terrain", "gbuffers_water", "composite", "pass-through composite"];

/// When the loader draws a scene's boxes of `kind`.
pub(crate) fn overlay_phase(pack: &LoadedPack, scene: &Scene, kind: OverlayKind) -> Phase {
    let boxes = scene.overlay.iter().filter(|o| o.kind == kind);
    let camera_below = boxes.clone().all(|o| o.min[1] > scene.camera.position[1]);
    let opaque = boxes.clone().all(|o| o.color[3] >= 1.0);
    pack.loader.phase(kind, camera_below, opaque)
}

fn load_attachment(v: &wgpu::TextureView) -> wgpu::RenderPassColorAttachment<'_> {
    wgpu::RenderPassColorAttachment {
        view: v,
        depth_slice: None,
        resolve_target: None,
        ops: wgpu::Operations { load: wgpu::LoadOp::Load, store: wgpu::StoreOp::Store },
    }
}

fn clear_attachment(v: &wgpu::TextureView) -> wgpu::RenderPassColorAttachment<'_> {
    wgpu::RenderPassColorAttachment {
        view: v,
        depth_slice: None,
        resolve_target: None,
        ops: wgpu::Operations { load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT), store: wgpu::StoreOp::Store },
    }
}

fn depth_attachment(v: &wgpu::TextureView, clear: bool) -> wgpu::RenderPassDepthStencilAttachment<'_> {
    wgpu::RenderPassDepthStencilAttachment {
        view: v,
        depth_ops: Some(wgpu::Operations {
            load: if clear { wgpu::LoadOp::Clear(1.0) } else { wgpu::LoadOp::Load },
            store: wgpu::StoreOp::Store,
        }),
        stencil_ops: None,
    }
}

/// The full-screen quad OptiFine draws: x, y in 0..1 under an orthographic projection,
/// texture coordinates 0..1, as two triangles.
pub fn fullscreen_quad() -> Vec<mesh::PackVertex> {
    let corner = |x: f32, y: f32| mesh::PackVertex {
        position: [x, y, 0.0, 1.0],
        color: [1.0; 4],
        normal: [0.0, 0.0, 1.0],
        uv0: [x, y, 0.0, 1.0],
        uv1: [0.0, 0.0, 0.0, 1.0],
        entity: [-1.0, -1.0, 0.0, 0.0],
    };
    [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 0.0), (1.0, 1.0), (0.0, 1.0)].iter().map(|&(x, y)| corner(x, y)).collect()
}

/// The harness's own textures: atlas, lightmap, noise, and their samplers.
struct StaticTextures {
    atlas: wgpu::TextureView,
    lightmap: wgpu::TextureView,
    noise: wgpu::TextureView,
    nearest_repeat: wgpu::Sampler,
    linear_repeat: wgpu::Sampler,
    linear_clamp: wgpu::Sampler,
    nearest_clamp: wgpu::Sampler,
    linear_repeat_custom: Vec<(wgpu::TextureView, wgpu::Sampler)>,
}

impl StaticTextures {
    fn new(gpu: &Gpu, pack: &LoadedPack) -> StaticTextures {
        let upload = |label: &str, (w, h, data): (u32, u32, Vec<u8>)| {
            let t = gpu.device.create_texture_with_data(
                &gpu.queue,
                &wgpu::TextureDescriptor {
                    label: Some(label),
                    size: wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format: wgpu::TextureFormat::Rgba8Unorm,
                    usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
                    view_formats: &[],
                },
                wgpu::util::TextureDataOrder::LayerMajor,
                &data,
            );
            view(&t)
        };
        let sampler = |filter: wgpu::FilterMode, address: wgpu::AddressMode| {
            gpu.device.create_sampler(&wgpu::SamplerDescriptor {
                address_mode_u: address,
                address_mode_v: address,
                address_mode_w: address,
                mag_filter: filter,
                min_filter: filter,
                ..Default::default()
            })
        };
        let custom = pack
            .custom_textures
            .iter()
            .map(|t| {
                let filter = if t.blur { wgpu::FilterMode::Linear } else { wgpu::FilterMode::Nearest };
                let address = if t.clamp { wgpu::AddressMode::ClampToEdge } else { wgpu::AddressMode::Repeat };
                (upload(&t.path, (t.width, t.height, t.rgba.clone())), sampler(filter, address))
            })
            .collect();
        StaticTextures {
            linear_repeat_custom: custom,
            atlas: upload("gtexture (mock atlas)", mesh::atlas()),
            lightmap: upload("lightmap", mesh::lightmap()),
            noise: upload("noisetex", mesh::noise(256)),
            nearest_repeat: sampler(wgpu::FilterMode::Nearest, wgpu::AddressMode::Repeat),
            linear_repeat: sampler(wgpu::FilterMode::Linear, wgpu::AddressMode::Repeat),
            linear_clamp: sampler(wgpu::FilterMode::Linear, wgpu::AddressMode::ClampToEdge),
            nearest_clamp: sampler(wgpu::FilterMode::Nearest, wgpu::AddressMode::ClampToEdge),
        }
    }
}

/// How a gbuffers draw blends into each colour buffer, and whether it writes depth.
struct DrawState<'a> {
    blend_of: &'a dyn Fn(u8) -> Blend,
    depth_write: bool,
}

/// Geometry drawn before composite by one program: the pack's, or the harness's own colour
/// shader where the pack has no program of the chain (drawing into the buffers the loader
/// would).
struct GeometryDraw {
    label: String,
    drawer: Drawer,
    buffers: Vec<u8>,
    vertices: wgpu::Buffer,
    count: u32,
}

enum Drawer {
    Pack(ProgramPipeline),
    Harness(ColourPipeline),
}

impl GeometryDraw {
    #[allow(clippy::too_many_arguments)]
    fn new(
        gpu: &Gpu,
        pack: &LoadedPack,
        scene: &Scene,
        targets: &Targets,
        statics: &StaticTextures,
        program: Option<&LoadedProgram>,
        state: &DrawState,
        vertices: &[mesh::PackVertex],
        label: String,
    ) -> Result<GeometryDraw, HarnessError> {
        let (drawer, buffers) = match program {
            Some(program) => {
                let pipeline = ProgramPipeline::new(gpu, pack, program, scene, Pass::Gbuffers, state, targets, statics)?;
                (Drawer::Pack(pipeline), program.render_targets.clone())
            }
            None => {
                let buffers: Vec<u8> = match pack.loader.missing_program_draws() {
                    MissingProgramDraws::FirstBufferOnly => vec![0],
                    MissingProgramDraws::EveryBuffer => targets.colors.keys().copied().collect(),
                };
                let formats: Vec<(wgpu::TextureFormat, Option<wgpu::BlendState>)> =
                    buffers.iter().map(|b| (targets.colors[b].1, wgpu_blend(&(state.blend_of)(*b)))).collect();
                (Drawer::Harness(ColourPipeline::new(gpu, scene, &formats, state.depth_write)?), buffers)
            }
        };
        // wgpu refuses empty buffers: an empty mesh uploads one unused vertex and draws nothing.
        let one = [mesh::PackVertex::default()];
        let vertices_buffer = gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(&label),
            contents: mesh::as_bytes(if vertices.is_empty() { &one } else { vertices }),
            usage: wgpu::BufferUsages::VERTEX,
        });
        Ok(GeometryDraw { label, drawer, buffers, vertices: vertices_buffer, count: vertices.len() as u32 })
    }

    fn record(&self, encoder: &mut wgpu::CommandEncoder, targets: &Targets, timestamps: Option<wgpu::RenderPassTimestampWrites>) {
        let depth0_view = view(&targets.depth0);
        let views: Vec<wgpu::TextureView> = self.buffers.iter().map(|b| view(&targets.colors[b].0)).collect();
        let attachments: Vec<_> = views.iter().map(|v| Some(load_attachment(v))).collect();
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(&self.label),
            color_attachments: &attachments,
            depth_stencil_attachment: Some(depth_attachment(&depth0_view, false)),
            timestamp_writes: timestamps,
            ..Default::default()
        });
        match &self.drawer {
            Drawer::Pack(program) => {
                pass.set_pipeline(&program.pipeline);
                for (i, g) in program.bind_groups.iter().enumerate() {
                    pass.set_bind_group(i as u32, g, &[]);
                }
            }
            Drawer::Harness(own) => {
                pass.set_pipeline(&own.pipeline);
                pass.set_bind_group(0, &own.bind_group, &[]);
            }
        }
        pass.set_vertex_buffer(0, self.vertices.slice(..));
        if self.count > 0 {
            pass.draw(0..self.count, 0..1);
        }
    }
}

struct ProgramPipeline {
    pipeline: wgpu::RenderPipeline,
    bind_groups: Vec<wgpu::BindGroup>,
    /// Alternate buffers a full-screen program writes (other than colortex0).
    alternates: BTreeMap<u8, wgpu::Texture>,
}

enum Entry {
    Uniform(wgpu::Buffer),
    Texture(wgpu::TextureView, wgpu::TextureSampleType),
    Sampler(wgpu::Sampler, wgpu::SamplerBindingType),
}

impl ProgramPipeline {
    /// `state` is a gbuffers program's blending and depth writes (unused for full-screen passes).
    #[allow(clippy::too_many_arguments)]
    fn new(
        gpu: &Gpu,
        pack: &LoadedPack,
        program: &LoadedProgram,
        scene: &Scene,
        pass: Pass,
        state: &DrawState,
        targets: &Targets,
        statics: &StaticTextures,
    ) -> Result<ProgramPipeline, HarnessError> {
        let device = &gpu.device;
        let values = uniforms::values(scene, pass);
        let gbuffers = pass == Pass::Gbuffers;
        // group → binding → (visibility, entry)
        let mut groups: BTreeMap<u32, BTreeMap<u32, (wgpu::ShaderStages, Entry)>> = BTreeMap::new();
        for stage in [&program.vertex, &program.fragment] {
            let visibility = match stage.stage {
                tidepack_glsl::Stage::Vertex => wgpu::ShaderStages::VERTEX,
                tidepack_glsl::Stage::Fragment => wgpu::ShaderStages::FRAGMENT,
            };
            let mut entries = stage_entries(gpu, pack, stage, &values, gbuffers, targets, statics)?;
            for (group, binding, entry) in entries.drain(..) {
                if groups.entry(group).or_default().insert(binding, (visibility, entry)).is_some() {
                    return Err(HarnessError::Pack(format!("{}: binding {group}.{binding} used twice", stage.path)));
                }
            }
        }
        let max_group = groups.keys().copied().max().map_or(0, |g| g + 1);
        let mut layouts = Vec::new();
        let mut bind_groups = Vec::new();
        for g in 0..max_group {
            let entries = groups.remove(&g).unwrap_or_default();
            let layout_entries: Vec<wgpu::BindGroupLayoutEntry> = entries
                .iter()
                .map(|(binding, (visibility, entry))| wgpu::BindGroupLayoutEntry {
                    binding: *binding,
                    visibility: *visibility,
                    ty: match entry {
                        Entry::Uniform(_) => wgpu::BindingType::Buffer {
                            ty: wgpu::BufferBindingType::Storage { read_only: true },
                            has_dynamic_offset: false,
                            min_binding_size: None,
                        },
                        Entry::Texture(_, sample_type) => wgpu::BindingType::Texture {
                            sample_type: *sample_type,
                            view_dimension: wgpu::TextureViewDimension::D2,
                            multisampled: false,
                        },
                        Entry::Sampler(_, ty) => wgpu::BindingType::Sampler(*ty),
                    },
                    count: None,
                })
                .collect();
            let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(&format!("{} set {g}", program.name)),
                entries: &layout_entries,
            });
            let group_entries: Vec<wgpu::BindGroupEntry> = entries
                .iter()
                .map(|(binding, (_, entry))| wgpu::BindGroupEntry {
                    binding: *binding,
                    resource: match entry {
                        Entry::Uniform(b) => b.as_entire_binding(),
                        Entry::Texture(v, _) => wgpu::BindingResource::TextureView(v),
                        Entry::Sampler(s, _) => wgpu::BindingResource::Sampler(s),
                    },
                })
                .collect();
            let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(&format!("{} set {g}", program.name)),
                layout: &layout,
                entries: &group_entries,
            });
            layouts.push(layout);
            bind_groups.push(group);
        }
        let layout_refs: Vec<Option<&wgpu::BindGroupLayout>> = layouts.iter().map(Some).collect();
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(&program.name),
            bind_group_layouts: &layout_refs,
            immediate_size: 0,
        });

        let attributes = vertex_attributes(&program.vertex)?;
        let mut alternates = BTreeMap::new();
        let mut color_targets = Vec::new();
        for &b in &program.render_targets {
            let format = if gbuffers {
                targets.colors[&b].1
            } else if b == 0 {
                OUT
            } else {
                let format = targets.colors.get(&b).map_or(Ok(wgpu::TextureFormat::Rgba8Unorm), |(_, f)| Ok::<_, HarnessError>(*f))?;
                let t = device.create_texture(&wgpu::TextureDescriptor {
                    label: Some(&format!("colortex{b} alternate")),
                    size: wgpu::Extent3d { width: scene.width(), height: scene.height(), depth_or_array_layers: 1 },
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format,
                    usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
                    view_formats: &[],
                });
                alternates.insert(b, t);
                format
            };
            let blend = if gbuffers { wgpu_blend(&(state.blend_of)(b)) } else { None };
            color_targets.push(Some(wgpu::ColorTargetState { format, blend, write_mask: wgpu::ColorWrites::ALL }));
        }
        let vertex_module = gpu.checked(&format!("{} (wgpu shader module)", program.vertex.path), || {
            device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(&program.vertex.path),
                source: wgpu::ShaderSource::Naga(Cow::Owned(uniforms_as_storage(&program.vertex.module))),
            })
        })?;
        let fragment_module = gpu.checked(&format!("{} (wgpu shader module)", program.fragment.path), || {
            device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(&program.fragment.path),
                source: wgpu::ShaderSource::Naga(Cow::Owned(uniforms_as_storage(&program.fragment.module))),
            })
        })?;
        let pipeline = gpu.checked(&format!("{} (wgpu pipeline)", program.name), || {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(&program.name),
                layout: Some(&pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &vertex_module,
                    entry_point: Some("main"),
                    compilation_options: Default::default(),
                    buffers: &[Some(wgpu::VertexBufferLayout {
                        array_stride: offsets::STRIDE,
                        step_mode: wgpu::VertexStepMode::Vertex,
                        attributes: &attributes,
                    })],
                },
                primitive: wgpu::PrimitiveState { cull_mode: None, ..Default::default() },
                depth_stencil: gbuffers.then_some(wgpu::DepthStencilState {
                    format: DEPTH,
                    depth_write_enabled: Some(state.depth_write),
                    depth_compare: Some(wgpu::CompareFunction::LessEqual),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
                multisample: Default::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &fragment_module,
                    entry_point: Some("main"),
                    compilation_options: Default::default(),
                    targets: &color_targets,
                }),
                multiview_mask: None,
                cache: None,
            })
        })?;
        Ok(ProgramPipeline { pipeline, bind_groups, alternates })
    }
}

fn wgpu_blend(blend: &Blend) -> Option<wgpu::BlendState> {
    let factor = |f: BlendFactor| match f {
        BlendFactor::Zero => wgpu::BlendFactor::Zero,
        BlendFactor::One => wgpu::BlendFactor::One,
        BlendFactor::SrcColor => wgpu::BlendFactor::Src,
        BlendFactor::OneMinusSrcColor => wgpu::BlendFactor::OneMinusSrc,
        BlendFactor::DstColor => wgpu::BlendFactor::Dst,
        BlendFactor::OneMinusDstColor => wgpu::BlendFactor::OneMinusDst,
        BlendFactor::SrcAlpha => wgpu::BlendFactor::SrcAlpha,
        BlendFactor::OneMinusSrcAlpha => wgpu::BlendFactor::OneMinusSrcAlpha,
        BlendFactor::DstAlpha => wgpu::BlendFactor::DstAlpha,
        BlendFactor::OneMinusDstAlpha => wgpu::BlendFactor::OneMinusDstAlpha,
    };
    match blend {
        Blend::Off => None,
        Blend::Factors([s, d, sa, da]) => Some(wgpu::BlendState {
            color: wgpu::BlendComponent { src_factor: factor(*s), dst_factor: factor(*d), operation: wgpu::BlendOperation::Add },
            alpha: wgpu::BlendComponent { src_factor: factor(*sa), dst_factor: factor(*da), operation: wgpu::BlendOperation::Add },
        }),
    }
}

/// The vertex attributes of [`mesh::PackVertex`] a stage declares, by its shipped input names.
pub fn vertex_attribute_source(name: &str) -> Option<(wgpu::VertexFormat, u64)> {
    Some(match name {
        "gl_Vertex" => (wgpu::VertexFormat::Float32x4, offsets::POSITION),
        "gl_Color" => (wgpu::VertexFormat::Float32x4, offsets::COLOR),
        "gl_Normal" => (wgpu::VertexFormat::Float32x3, offsets::NORMAL),
        "gl_MultiTexCoord0" => (wgpu::VertexFormat::Float32x4, offsets::UV0),
        "gl_MultiTexCoord1" => (wgpu::VertexFormat::Float32x4, offsets::UV1),
        "mc_Entity" => (wgpu::VertexFormat::Float32x4, offsets::ENTITY),
        _ => return None,
    })
}

fn vertex_attributes(stage: &LoadedStage) -> Result<Vec<wgpu::VertexAttribute>, HarnessError> {
    let mut attributes = Vec::new();
    for (name, location) in &stage.interface.inputs {
        let (format, offset) = vertex_attribute_source(name).ok_or_else(|| {
            HarnessError::Unsupported(format!(
                "{} reads vertex input {name}, which the harness does not provide (it has gl_Vertex, gl_Color, gl_Normal, \
                 gl_MultiTexCoord0, gl_MultiTexCoord1, mc_Entity)",
                stage.path
            ))
        })?;
        attributes.push(wgpu::VertexAttribute { format, offset, shader_location: *location });
    }
    Ok(attributes)
}

/// Bindings of a stage: its uniform block filled by reflection, and its textures/samplers.
fn stage_entries(
    gpu: &Gpu,
    pack: &LoadedPack,
    stage: &LoadedStage,
    values: &BTreeMap<String, uniforms::Value>,
    gbuffers: bool,
    targets: &Targets,
    statics: &StaticTextures,
) -> Result<Vec<(u32, u32, Entry)>, HarnessError> {
    let module = &stage.module;
    let mut entries = Vec::new();
    if let Some(block) = uniforms::fill_block(module, values, &stage.path)? {
        let buffer = gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(&format!("{} uniforms", stage.path)),
            contents: &block.bytes,
            usage: wgpu::BufferUsages::STORAGE,
        });
        entries.push((block.group, block.binding, Entry::Uniform(buffer)));
    }
    // Textures first, so each sampler knows whether its texture filters.
    let mut filterable: BTreeMap<String, bool> = BTreeMap::new();
    let mut problems = Vec::new();
    for (_, global) in module.global_variables.iter() {
        let (Some(binding), Some(name)) = (&global.binding, &global.name) else { continue };
        if let naga::TypeInner::Image { class, dim, arrayed, .. } = &module.types[global.ty].inner {
            if *dim != naga::ImageDimension::D2 || *arrayed || !matches!(class, naga::ImageClass::Sampled { kind: naga::ScalarKind::Float, multi: false }) {
                problems.push(format!("texture {name} is not a plain sampler2D"));
                continue;
            }
            let source = match resolve_in_pack(pack, name, gbuffers) {
                Ok(s) => s,
                Err(m) => {
                    problems.push(m);
                    continue;
                }
            };
            let (view_, sample_type, filters) = match source {
                Source::Atlas => (statics.atlas.clone(), wgpu::TextureSampleType::Float { filterable: true }, true),
                Source::Lightmap => (statics.lightmap.clone(), wgpu::TextureSampleType::Float { filterable: true }, true),
                Source::Noise => (statics.noise.clone(), wgpu::TextureSampleType::Float { filterable: true }, true),
                Source::Custom(i) => (statics.linear_repeat_custom[i].0.clone(), wgpu::TextureSampleType::Float { filterable: true }, true),
                Source::Depth0 => (view(&targets.depth0), wgpu::TextureSampleType::Float { filterable: false }, false),
                Source::Depth1 => (view(&targets.depth1), wgpu::TextureSampleType::Float { filterable: false }, false),
                Source::Color(n) => {
                    let (t, format) = &targets.colors[&n];
                    let f = gpu.filterable(*format);
                    (view(t), wgpu::TextureSampleType::Float { filterable: f }, f)
                }
            };
            filterable.insert(name.clone(), filters);
            entries.push((binding.group, binding.binding, Entry::Texture(view_, sample_type)));
        }
    }
    for (_, global) in module.global_variables.iter() {
        let (Some(binding), Some(name)) = (&global.binding, &global.name) else { continue };
        if let naga::TypeInner::Sampler { comparison } = &module.types[global.ty].inner {
            let texture = name.strip_prefix("tp_sampler_").unwrap_or(name);
            if *comparison {
                problems.push(format!("{texture} is a shadow sampler; the harness has no shadow maps"));
                continue;
            }
            let Some(&filters) = filterable.get(texture) else {
                if !problems.iter().any(|p| p.contains(texture)) {
                    problems.push(format!("sampler {name} has no texture {texture}"));
                }
                continue;
            };
            let source = resolve_in_pack(pack, texture, gbuffers).expect("resolved with its texture");
            let sampler = match source {
                Source::Custom(i) => statics.linear_repeat_custom[i].1.clone(),
                Source::Atlas => statics.nearest_repeat.clone(),
                Source::Noise => statics.linear_repeat.clone(),
                Source::Lightmap => statics.linear_clamp.clone(),
                Source::Color(_) if filters => statics.linear_clamp.clone(),
                _ => statics.nearest_clamp.clone(),
            };
            let ty = if filters { wgpu::SamplerBindingType::Filtering } else { wgpu::SamplerBindingType::NonFiltering };
            entries.push((binding.group, binding.binding, Entry::Sampler(sampler, ty)));
        }
    }
    if !problems.is_empty() {
        return Err(HarnessError::Uniform(format!("{}: {}", stage.path, problems.join("; "))));
    }
    Ok(entries)
}

/// The harness's colour shader: position and vertex colour, OpenGL clip space mapped as in
/// [`crate::program::adapt_vertex`]; the fragment entry point comes from [`colour_wgsl`].
const COLOUR_VERTEX_WGSL: &str = r#"
struct Uniforms { mvp: mat4x4<f32> }
@group(0) @binding(0) var<uniform> u: Uniforms;
struct Out { @builtin(position) position: vec4<f32>, @location(0) color: vec4<f32> }
@vertex fn vs(@location(0) position: vec4<f32>, @location(1) color: vec4<f32>) -> Out {
    var clip = u.mvp * position;
    clip.y = -clip.y;
    clip.z = 0.5 * (clip.z + clip.w);
    return Out(clip, color);
}
"#;

/// The colour shader writing the same colour to `targets` colour attachments, as
/// fixed-function drawing does to every draw buffer.
fn colour_wgsl(targets: usize) -> String {
    let fields: String = (0..targets).map(|i| format!("@location({i}) c{i}: vec4<f32>, ")).collect();
    let values: Vec<&str> = vec!["i.color"; targets];
    format!(
        "{COLOUR_VERTEX_WGSL}struct Targets {{ {fields}}}\n@fragment fn fs(i: Out) -> Targets {{ return Targets({}); }}\n",
        values.join(", ")
    )
}

/// The one-tap pass-through composite: colortex0 to the output, nothing else.
const PASSTHROUGH_WGSL: &str = r#"
@group(0) @binding(0) var colortex0: texture_2d<f32>;
@vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let p = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(p * 2.0 - 1.0, 0.0, 1.0);
}
@fragment fn fs(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    return textureLoad(colortex0, vec2<i32>(p.xy), 0);
}
"#;

/// The harness's own shader for geometry the pack has no program for: the vertex colour into
/// every colour target given.
struct ColourPipeline {
    pipeline: wgpu::RenderPipeline,
    bind_group: wgpu::BindGroup,
}

/// The model-view-projection the terrain shader uses (f64, then f32), shared with the GL path.
pub fn terrain_mvp(scene: &Scene) -> [f32; 16] {
    (scene.projection() * scene.model_view()).to_cols_array().map(|v| v as f32)
}

impl ColourPipeline {
    fn new(
        gpu: &Gpu,
        scene: &Scene,
        targets: &[(wgpu::TextureFormat, Option<wgpu::BlendState>)],
        depth_write: bool,
    ) -> Result<ColourPipeline, HarnessError> {
        let device = &gpu.device;
        let module = gpu.checked("terrain shader", || {
            device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("terrain"),
                source: wgpu::ShaderSource::Wgsl(colour_wgsl(targets.len()).into()),
            })
        })?;
        let targets: Vec<Option<wgpu::ColorTargetState>> = targets
            .iter()
            .map(|&(format, blend)| Some(wgpu::ColorTargetState { format, blend, write_mask: wgpu::ColorWrites::ALL }))
            .collect();
        let mvp: Vec<u8> = terrain_mvp(scene).iter().flat_map(|v| v.to_le_bytes()).collect();
        let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("terrain uniforms"),
            contents: &mvp,
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let pipeline = gpu.checked("terrain pipeline", || {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some("terrain"),
                layout: None,
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some("vs"),
                    compilation_options: Default::default(),
                    buffers: &[Some(wgpu::VertexBufferLayout {
                        array_stride: offsets::STRIDE,
                        step_mode: wgpu::VertexStepMode::Vertex,
                        attributes: &[
                            wgpu::VertexAttribute { format: wgpu::VertexFormat::Float32x4, offset: offsets::POSITION, shader_location: 0 },
                            wgpu::VertexAttribute { format: wgpu::VertexFormat::Float32x4, offset: offsets::COLOR, shader_location: 1 },
                        ],
                    })],
                },
                primitive: wgpu::PrimitiveState { cull_mode: None, ..Default::default() },
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: DEPTH,
                    depth_write_enabled: Some(depth_write),
                    depth_compare: Some(wgpu::CompareFunction::LessEqual),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
                multisample: Default::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some("fs"),
                    compilation_options: Default::default(),
                    targets: &targets,
                }),
                multiview_mask: None,
                cache: None,
            })
        })?;
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("terrain"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: buffer.as_entire_binding() }],
        });
        Ok(ColourPipeline { pipeline, bind_group })
    }
}

/// The one-tap pass-through composite over `colortex0`, the floor composite is timed against.
pub(crate) struct PassthroughPipeline {
    pub(crate) pipeline: wgpu::RenderPipeline,
    pub(crate) bind_group: wgpu::BindGroup,
}

impl PassthroughPipeline {
    pub(crate) fn new(gpu: &Gpu, colortex0: &wgpu::Texture) -> Result<PassthroughPipeline, HarnessError> {
        let device = &gpu.device;
        let module = gpu.checked("pass-through shader", || {
            device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("pass-through"),
                source: wgpu::ShaderSource::Wgsl(PASSTHROUGH_WGSL.into()),
            })
        })?;
        let pipeline = gpu.checked("pass-through pipeline", || {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some("pass-through"),
                layout: None,
                vertex: wgpu::VertexState { module: &module, entry_point: Some("vs"), compilation_options: Default::default(), buffers: &[] },
                primitive: Default::default(),
                depth_stencil: None,
                multisample: Default::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some("fs"),
                    compilation_options: Default::default(),
                    targets: &[Some(wgpu::ColorTargetState { format: OUT, blend: None, write_mask: wgpu::ColorWrites::ALL })],
                }),
                multiview_mask: None,
                cache: None,
            })
        })?;
        let bind_group = gpu.checked("pass-through bind group", || {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("pass-through"),
                layout: &pipeline.get_bind_group_layout(0),
                entries: &[wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(&view(colortex0)) }],
            })
        })?;
        Ok(PassthroughPipeline { pipeline, bind_group })
    }
}

/// The GPU time in ms of each of `passes` timed passes, from their begin and end timestamps in
/// query order.
pub(crate) fn read_pass_ms(gpu: &Gpu, queries: &wgpu::QuerySet, passes: u32) -> Result<Vec<f64>, HarnessError> {
    let bytes = (passes * 2) as u64 * 8;
    let resolve = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("timestamp resolve"),
        size: bytes,
        usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let read = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("timestamp readback"),
        size: bytes,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    encoder.resolve_query_set(queries, 0..passes * 2, &resolve, 0);
    encoder.copy_buffer_to_buffer(&resolve, 0, &read, 0, bytes);
    gpu.queue.submit([encoder.finish()]);
    let data = map_read(gpu, &read)?;
    let ticks: Vec<u64> = data.chunks_exact(8).map(|c| u64::from_le_bytes(c.try_into().expect("8 bytes"))).collect();
    let period = gpu.queue.get_timestamp_period() as f64;
    Ok(ticks.chunks_exact(2).map(|t| t[1].saturating_sub(t[0]) as f64 * period / 1e6).collect())
}

fn map_read(gpu: &Gpu, buffer: &wgpu::Buffer) -> Result<Vec<u8>, HarnessError> {
    let (sender, receiver) = std::sync::mpsc::channel();
    buffer.map_async(wgpu::MapMode::Read, .., move |r| {
        let _ = sender.send(r);
    });
    gpu.device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| HarnessError::Wgpu(format!("waiting for a readback: {e}")))?;
    receiver
        .recv()
        .map_err(|_| HarnessError::Wgpu("readback callback dropped".into()))?
        .map_err(|e| HarnessError::Wgpu(format!("mapping a readback buffer: {e}")))?;
    let data = buffer
        .get_mapped_range(..)
        .map_err(|e| HarnessError::Wgpu(format!("reading a mapped buffer: {e:?}")))?
        .to_vec();
    buffer.unmap();
    Ok(data)
}

/// Bytes of the buffer [`read_texture`] needs for an RGBA32F texture of this size.
fn readback_bytes(width: u32, height: u32) -> u64 {
    (width as u64 * 16).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT as u64) * height as u64
}

/// Reads a texture back as floats, bottom row first (memory row 0 is OpenGL's bottom row).
pub fn read_texture(gpu: &Gpu, texture: &wgpu::Texture, format: wgpu::TextureFormat) -> Result<FloatImage, HarnessError> {
    let (w, h) = (texture.width(), texture.height());
    let texel = match format {
        wgpu::TextureFormat::Rgba8Unorm | wgpu::TextureFormat::Depth32Float => 4,
        wgpu::TextureFormat::Rgba16Unorm | wgpu::TextureFormat::Rgba16Float => 8,
        wgpu::TextureFormat::Rgba32Float => 16,
        other => return Err(HarnessError::Unsupported(format!("reading back {other:?}"))),
    };
    let row = (w * texel).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
    let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("texture readback"),
        size: (row * h) as u64,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(row), rows_per_image: Some(h) },
        },
        texture.size(),
    );
    gpu.queue.submit([encoder.finish()]);
    let data = map_read(gpu, &buffer)?;
    let mut image = FloatImage::new(w, h);
    for y in 0..h {
        for x in 0..w {
            let at = (y * row + x * texel) as usize;
            let p = &data[at..at + texel as usize];
            let px = match format {
                wgpu::TextureFormat::Rgba8Unorm => [0, 1, 2, 3].map(|c| p[c] as f32 / 255.0),
                wgpu::TextureFormat::Rgba16Unorm => [0, 1, 2, 3].map(|c| u16::from_le_bytes([p[2 * c], p[2 * c + 1]]) as f32 / 65535.0),
                wgpu::TextureFormat::Rgba16Float => [0, 1, 2, 3].map(|c| f16_to_f32(u16::from_le_bytes([p[2 * c], p[2 * c + 1]]))),
                wgpu::TextureFormat::Rgba32Float => [0, 1, 2, 3].map(|c| f32::from_le_bytes(p[4 * c..4 * c + 4].try_into().expect("4 bytes"))),
                _ => {
                    let d = f32::from_le_bytes(p[0..4].try_into().expect("4 bytes"));
                    [d, d, d, 1.0]
                }
            };
            image.pixels[(y * w + x) as usize] = px;
        }
    }
    Ok(image)
}

/// IEEE half to f32.
pub fn f16_to_f32(h: u16) -> f32 {
    let sign = if h & 0x8000 != 0 { -1.0 } else { 1.0 };
    let exp = ((h >> 10) & 0x1f) as i32;
    let mant = (h & 0x3ff) as f32;
    match exp {
        0 => sign * mant * 2f32.powi(-24),
        31 if mant == 0.0 => sign * f32::INFINITY,
        31 => f32::NAN,
        _ => sign * (1.0 + mant / 1024.0) * 2f32.powi(exp - 15),
    }
}
