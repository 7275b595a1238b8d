//! The composite program alone, over G-buffers the caller supplies, with its pipeline built
//! once: a stress sweep renders thousands of uniform sets and injected buffer contents
//! (`d0 == d1`, sky depth, zero normals) without recompiling anything per case.
//!
//! Bindings follow `gpu.rs` for full-screen programs (same samplers, same resolution of
//! sampler names), with two differences: the colour buffers are uploaded from the caller's
//! floats (quantised to the buffer's format, see [`CompositeOnly::quantize`]), and depthtex0/1
//! are R32Float textures (bound unfilterable with a nearest sampler, as gpu.rs binds
//! Depth32Float), so any depth value can be written. The output is RGBA32F, so NaN and Inf
//! survive to the readback.
//!
//! The uniform blocks are bound as read-only storage buffers by default
//! ([`UniformBinding::ReadOnlyStorage`]): same bytes, same member offsets, same arithmetic, but
//! lavapipe cannot "inline" them. For uniform buffers, lavapipe may recompile a shader with the
//! current values of the members its `if` conditions test (here `isEyeInWater`) at every draw
//! after a pipeline or descriptor bind; the lavapipe of Mesa 22.3 (Debian 12's own) does and
//! never frees the copies, about 3.4 MB per draw of composite (docs/stress.md, "Memory"). A
//! storage buffer is read with `load_ssbo`, which the inliner ignores, so the shader is compiled
//! once and the resident memory stays flat over any number of renders, whichever Mesa runs it.

use std::borrow::Cow;
use std::collections::BTreeMap;

use wgpu::util::DeviceExt as _;

use crate::gpu::{self, Frame, Gpu, Source};
use crate::images::FloatImage;
use crate::mesh::{self, offsets};
use crate::program::{BufferFormat, LoadedPack};
use crate::uniforms::{self, Value};
use crate::HarnessError;

/// What composite reads: colour buffers by number, and the two depth buffers (r), bottom row
/// first.
#[derive(Clone, Debug)]
pub struct GBuffers {
    pub colors: BTreeMap<u8, FloatImage>,
    pub depth0: FloatImage,
    pub depth1: FloatImage,
}

impl GBuffers {
    /// The buffers a harness frame left for composite.
    pub fn from_frame(frame: &Frame) -> GBuffers {
        GBuffers { colors: frame.buffers.clone(), depth0: frame.depth0.clone(), depth1: frame.depth1.clone() }
    }
}

const OUT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
const DEPTH_AS: wgpu::TextureFormat = wgpu::TextureFormat::R32Float;

/// How the programs' uniform blocks are bound.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum UniformBinding {
    /// As the program declares them (`uniform` blocks), for comparison: lavapipe may recompile
    /// the shader with the blocks' values inlined at every draw (see the module doc).
    Uniform,
    /// The same blocks as read-only storage buffers: no per-draw recompilation, no growth.
    #[default]
    ReadOnlyStorage,
}

pub struct CompositeOnly {
    width: u32,
    height: u32,
    colors: BTreeMap<u8, (wgpu::Texture, BufferFormat)>,
    depth0: wgpu::Texture,
    depth1: wgpu::Texture,
    out: wgpu::Texture,
    /// Other render targets of composite (written, never read back).
    alternates: Vec<wgpu::Texture>,
    pipeline: wgpu::RenderPipeline,
    bind_groups: Vec<wgpu::BindGroup>,
    /// Per stage with a uniform block: (stage index 0 = vertex, 1 = fragment, buffer).
    uniform_buffers: Vec<(usize, wgpu::Buffer)>,
    quad: wgpu::Buffer,
    quad_len: u32,
    /// The one-tap pass-through composite (colortex0 to an RGBA32F target), the floor
    /// [`CompositeOnly::time`] measures composite against.
    passthrough: Passthrough,
}

struct Passthrough {
    pipeline: gpu::PassthroughPipeline,
    out: wgpu::Texture,
}

/// Per-frame pass times of [`CompositeOnly::time`] and the composite output of the last frame.
#[derive(Clone, Debug)]
pub struct CompositeTimes {
    pub image: FloatImage,
    /// Composite pass per frame, ms.
    pub composite_ms: Vec<f64>,
    /// One-tap pass-through composite of the same G-buffers per frame, ms.
    pub passthrough_ms: Vec<f64>,
    /// True: GPU timestamps around each pass; false: wall clock of each pass's submit and wait.
    pub gpu_timestamps: bool,
}

fn wgpu_format(gpu: &Gpu, format: BufferFormat) -> Result<wgpu::TextureFormat, HarnessError> {
    Ok(match format {
        BufferFormat::Rgba8 => wgpu::TextureFormat::Rgba8Unorm,
        BufferFormat::Rgba16 if gpu.device.features().contains(wgpu::Features::TEXTURE_FORMAT_16BIT_NORM) => {
            wgpu::TextureFormat::Rgba16Unorm
        }
        BufferFormat::Rgba32F => wgpu::TextureFormat::Rgba32Float,
        other => return Err(HarnessError::Unsupported(format!("composite_only: uploading a {other:?} buffer"))),
    })
}

impl CompositeOnly {
    /// Builds the composite pipeline for frames of `width` x `height`. `values` only sizes the
    /// uniform blocks (every member must have a value); each render writes its own. The blocks
    /// are bound as read-only storage ([`UniformBinding::ReadOnlyStorage`]).
    pub fn new(gpu: &Gpu, pack: &LoadedPack, width: u32, height: u32, values: &BTreeMap<String, Value>) -> Result<CompositeOnly, HarnessError> {
        CompositeOnly::with_binding(gpu, pack, width, height, values, UniformBinding::default())
    }

    /// [`CompositeOnly::new`] with a choice of how the uniform blocks are bound.
    pub fn with_binding(
        gpu: &Gpu,
        pack: &LoadedPack,
        width: u32,
        height: u32,
        values: &BTreeMap<String, Value>,
        binding: UniformBinding,
    ) -> Result<CompositeOnly, HarnessError> {
        gpu.check_resolution(width, height)?;
        let storage = binding == UniformBinding::ReadOnlyStorage;
        let device = &gpu.device;
        let program = &pack.composite;
        let size = wgpu::Extent3d { width, height, depth_or_array_layers: 1 };
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
        let input = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST;
        let float32_filterable = device.features().contains(wgpu::Features::FLOAT32_FILTERABLE);
        let filterable = |f: BufferFormat| f != BufferFormat::Rgba32F || float32_filterable;

        let mut colors = BTreeMap::new();
        let nearest = |address| sampler(gpu, wgpu::FilterMode::Nearest, address);
        let linear = |address| sampler(gpu, wgpu::FilterMode::Linear, address);
        let upload_rgba8 = |label: &str, (w, h, data): (u32, u32, Vec<u8>)| {
            let t = device.create_texture_with_data(
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
            t.create_view(&Default::default())
        };
        let depth0 = texture("depthtex0 (R32Float)", DEPTH_AS, input);
        let depth1 = texture("depthtex1 (R32Float)", DEPTH_AS, input);

        enum Entry {
            Uniform(wgpu::Buffer),
            Texture(wgpu::TextureView, wgpu::TextureSampleType),
            Sampler(wgpu::Sampler, wgpu::SamplerBindingType),
        }
        let mut groups: BTreeMap<u32, BTreeMap<u32, (wgpu::ShaderStages, Entry)>> = BTreeMap::new();
        let mut uniform_buffers = Vec::new();
        for (index, stage) in [&program.vertex, &program.fragment].into_iter().enumerate() {
            let visibility = if index == 0 { wgpu::ShaderStages::VERTEX } else { wgpu::ShaderStages::FRAGMENT };
            let module = &stage.module;
            let mut entries: Vec<(u32, u32, Entry)> = Vec::new();
            if let Some(block) = uniforms::fill_block(module, values, &stage.path)? {
                let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(&format!("{} uniforms", stage.path)),
                    contents: &block.bytes,
                    usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                });
                uniform_buffers.push((index, buffer.clone()));
                entries.push((block.group, block.binding, Entry::Uniform(buffer)));
            }
            let mut filters_of: BTreeMap<String, (Source, bool)> = BTreeMap::new();
            for (_, global) in module.global_variables.iter() {
                let (Some(binding), Some(name)) = (&global.binding, &global.name) else { continue };
                if let naga::TypeInner::Image { .. } = &module.types[global.ty].inner {
                    let source = gpu::resolve_in_pack(pack, name, false).map_err(HarnessError::Uniform)?;
                    let (view, filters) = match source {
                        Source::Noise => (upload_rgba8("noisetex", mesh::noise(256)), true),
                        Source::Custom(i) => {
                            let t = &pack.custom_textures[i];
                            (upload_rgba8(&t.path, (t.width, t.height, t.rgba.clone())), true)
                        }
                        Source::Depth0 => (depth0.create_view(&Default::default()), false),
                        Source::Depth1 => (depth1.create_view(&Default::default()), false),
                        Source::Color(n) => {
                            let format = pack.format_of(n);
                            let t = colors
                                .entry(n)
                                .or_insert_with(|| (texture(&format!("colortex{n}"), wgpu_format(gpu, format).unwrap_or(wgpu::TextureFormat::Rgba8Unorm), input), format));
                            wgpu_format(gpu, format)?;
                            (t.0.create_view(&Default::default()), filterable(format))
                        }
                        Source::Atlas | Source::Lightmap => {
                            return Err(HarnessError::Unsupported(format!("composite reads {name}, a gbuffers texture")));
                        }
                    };
                    filters_of.insert(name.clone(), (source, filters));
                    entries.push((binding.group, binding.binding, Entry::Texture(view, wgpu::TextureSampleType::Float { filterable: filters })));
                }
            }
            for (_, global) in module.global_variables.iter() {
                let (Some(binding), Some(name)) = (&global.binding, &global.name) else { continue };
                if let naga::TypeInner::Sampler { .. } = &module.types[global.ty].inner {
                    let texture_name = name.strip_prefix("tp_sampler_").unwrap_or(name);
                    let &(source, filters) = filters_of
                        .get(texture_name)
                        .ok_or_else(|| HarnessError::Uniform(format!("sampler {name} has no texture {texture_name}")))?;
                    let s = match source {
                        Source::Custom(i) => {
                            let t = &pack.custom_textures[i];
                            let address = if t.clamp { wgpu::AddressMode::ClampToEdge } else { wgpu::AddressMode::Repeat };
                            if t.blur { linear(address) } else { nearest(address) }
                        }
                        Source::Noise => linear(wgpu::AddressMode::Repeat),
                        Source::Color(_) if filters => linear(wgpu::AddressMode::ClampToEdge),
                        _ => nearest(wgpu::AddressMode::ClampToEdge),
                    };
                    let ty = if filters { wgpu::SamplerBindingType::Filtering } else { wgpu::SamplerBindingType::NonFiltering };
                    entries.push((binding.group, binding.binding, Entry::Sampler(s, ty)));
                }
            }
            for (group, binding, entry) in entries {
                if groups.entry(group).or_default().insert(binding, (visibility, entry)).is_some() {
                    return Err(HarnessError::Pack(format!("{}: binding {group}.{binding} used twice", stage.path)));
                }
            }
        }
        // colortex0 is always uploaded (the output replaces it).
        if let std::collections::btree_map::Entry::Vacant(slot) = colors.entry(0) {
            let format = pack.format_of(0);
            slot.insert((texture("colortex0", wgpu_format(gpu, format)?, input), format));
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
                            ty: if storage {
                                wgpu::BufferBindingType::Storage { read_only: true }
                            } else {
                                wgpu::BufferBindingType::Uniform
                            },
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
            let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some("composite_only"), entries: &layout_entries });
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
            let group = device.create_bind_group(&wgpu::BindGroupDescriptor { label: Some("composite_only"), layout: &layout, entries: &group_entries });
            layouts.push(layout);
            bind_groups.push(group);
        }
        let layout_refs: Vec<Option<&wgpu::BindGroupLayout>> = layouts.iter().map(Some).collect();
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("composite_only"),
            bind_group_layouts: &layout_refs,
            immediate_size: 0,
        });

        let mut attributes = Vec::new();
        for (name, location) in &program.vertex.interface.inputs {
            let (format, offset) = gpu::vertex_attribute_source(name)
                .ok_or_else(|| HarnessError::Unsupported(format!("{} reads vertex input {name}", program.vertex.path)))?;
            attributes.push(wgpu::VertexAttribute { format, offset, shader_location: *location });
        }
        let out = texture("composite output (RGBA32F)", OUT, wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC);
        let mut alternates = Vec::new();
        let mut color_targets = Vec::new();
        for &b in &program.render_targets {
            let format = if b == 0 { OUT } else { wgpu_format(gpu, pack.format_of(b))? };
            if b != 0 {
                alternates.push(texture(&format!("colortex{b} alternate"), format, wgpu::TextureUsages::RENDER_ATTACHMENT));
            }
            color_targets.push(Some(wgpu::ColorTargetState { format, blend: None, write_mask: wgpu::ColorWrites::ALL }));
        }
        let module = |stage: &crate::program::LoadedStage| {
            gpu.checked(&stage.path, || {
                device.create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some(&stage.path),
                    source: wgpu::ShaderSource::Naga(Cow::Owned(if storage { gpu::uniforms_as_storage(&stage.module) } else { stage.module.clone() })),
                })
            })
        };
        let vertex_module = module(&program.vertex)?;
        let fragment_module = module(&program.fragment)?;
        let pipeline = gpu.checked("composite_only pipeline", || {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some("composite_only"),
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
                depth_stencil: None,
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
        let passthrough = {
            let pipeline = gpu::PassthroughPipeline::new(gpu, &colors[&0].0)?;
            let out = texture("pass-through output (RGBA32F)", OUT, wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC);
            Passthrough { pipeline, out }
        };
        let quad = gpu::fullscreen_quad();
        let quad_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("full-screen quad"),
            contents: mesh::as_bytes(&quad),
            usage: wgpu::BufferUsages::VERTEX,
        });
        Ok(CompositeOnly {
            width,
            height,
            colors,
            depth0,
            depth1,
            out,
            alternates,
            pipeline,
            bind_groups,
            uniform_buffers,
            quad: quad_buffer,
            quad_len: quad.len() as u32,
            passthrough,
        })
    }

    /// Colour buffers composite reads (colortex0 included).
    pub fn color_buffers(&self) -> Vec<u8> {
        self.colors.keys().copied().collect()
    }

    /// The value a colour buffer holds after uploading `v` (clamped and rounded for unorm
    /// formats), so a reference can be fed exactly what composite read.
    pub fn quantize(&self, buffer: u8, v: f32) -> f32 {
        match self.colors.get(&buffer).map(|c| c.1) {
            Some(BufferFormat::Rgba8) => (v.clamp(0.0, 1.0) * 255.0).round() / 255.0,
            Some(BufferFormat::Rgba16) => (v.clamp(0.0, 1.0) * 65535.0).round() / 65535.0,
            _ => v,
        }
    }

    /// Runs composite over `g` with the uniform values `values` (by OptiFine name, as
    /// [`uniforms::values`] gives them); returns the RGBA32F output, bottom row first.
    pub fn render(&self, gpu: &Gpu, pack: &LoadedPack, g: &GBuffers, values: &BTreeMap<String, Value>) -> Result<FloatImage, HarnessError> {
        self.upload(gpu, pack, g, values)?;
        gpu.checked("composite_only", || {
            let mut encoder = gpu.device.create_command_encoder(&Default::default());
            self.encode_composite(&mut encoder, pack, None);
            gpu.queue.submit([encoder.finish()]);
        })?;
        gpu::read_texture(gpu, &self.out, OUT)
    }

    /// Times `frames` frames of composite over `g` and `values` (uploaded once), each followed by
    /// the one-tap pass-through composite of the same colortex0. Every frame is returned; the
    /// first includes llvmpipe's lazy compilation of the shader variant at the first draw, so
    /// callers drop it. Both passes are separate submissions, waited for one by one.
    pub fn time(&self, gpu: &Gpu, pack: &LoadedPack, g: &GBuffers, values: &BTreeMap<String, Value>, frames: usize) -> Result<CompositeTimes, HarnessError> {
        self.upload(gpu, pack, g, values)?;
        let queries = gpu.timestamps.then(|| {
            gpu.device.create_query_set(&wgpu::QuerySetDescriptor { label: Some("composite_only timestamps"), ty: wgpu::QueryType::Timestamp, count: 4 })
        });
        let wait = || {
            gpu.device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| HarnessError::Wgpu(format!("waiting for the GPU: {e}")))
        };
        let (mut composite_ms, mut passthrough_ms) = (Vec::new(), Vec::new());
        for _ in 0..frames.max(1) {
            let mut walls = [0.0; 2];
            for (pass, wall) in walls.iter_mut().enumerate() {
                let stamps = queries.as_ref().map(|q| wgpu::RenderPassTimestampWrites {
                    query_set: q,
                    beginning_of_pass_write_index: Some(2 * pass as u32),
                    end_of_pass_write_index: Some(2 * pass as u32 + 1),
                });
                let started = std::time::Instant::now();
                gpu.checked("composite_only timing", || {
                    let mut encoder = gpu.device.create_command_encoder(&Default::default());
                    if pass == 0 {
                        self.encode_composite(&mut encoder, pack, stamps);
                    } else {
                        self.encode_passthrough(&mut encoder, stamps);
                    }
                    gpu.queue.submit([encoder.finish()]);
                })?;
                wait()?;
                *wall = started.elapsed().as_secs_f64() * 1000.0;
            }
            match &queries {
                Some(q) => {
                    // Two timed passes: composite, then the pass-through.
                    let ms = gpu::read_pass_ms(gpu, q, 2)?;
                    composite_ms.push(ms[0]);
                    passthrough_ms.push(ms[1]);
                }
                None => {
                    composite_ms.push(walls[0]);
                    passthrough_ms.push(walls[1]);
                }
            }
        }
        Ok(CompositeTimes { image: gpu::read_texture(gpu, &self.out, OUT)?, composite_ms, passthrough_ms, gpu_timestamps: queries.is_some() })
    }

    /// Writes the G-buffers and the uniform blocks.
    fn upload(&self, gpu: &Gpu, pack: &LoadedPack, g: &GBuffers, values: &BTreeMap<String, Value>) -> Result<(), HarnessError> {
        let (w, h) = (self.width, self.height);
        let check = |name: &str, image: &FloatImage| {
            if (image.width, image.height) != (w, h) {
                return Err(HarnessError::Scene(format!("{name} is {}x{}, composite_only was built for {w}x{h}", image.width, image.height)));
            }
            Ok(())
        };
        let write = |texture: &wgpu::Texture, bytes: &[u8], texel: u32| {
            gpu.queue.write_texture(
                texture.as_image_copy(),
                bytes,
                wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(w * texel), rows_per_image: Some(h) },
                wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
            );
        };
        for (b, (texture, format)) in &self.colors {
            let image = g.colors.get(b).ok_or_else(|| HarnessError::Scene(format!("no colortex{b} supplied")))?;
            check(&format!("colortex{b}"), image)?;
            let flat = image.pixels.iter().flatten();
            match format {
                BufferFormat::Rgba8 => write(texture, &flat.map(|&c| (c.clamp(0.0, 1.0) * 255.0).round() as u8).collect::<Vec<u8>>(), 4),
                BufferFormat::Rgba16 => write(
                    texture,
                    &flat.flat_map(|&c| ((c.clamp(0.0, 1.0) * 65535.0).round() as u16).to_le_bytes()).collect::<Vec<u8>>(),
                    8,
                ),
                _ => write(texture, &flat.flat_map(|c| c.to_le_bytes()).collect::<Vec<u8>>(), 16),
            }
        }
        for (name, texture, image) in [("depthtex0", &self.depth0, &g.depth0), ("depthtex1", &self.depth1, &g.depth1)] {
            check(name, image)?;
            write(texture, &image.pixels.iter().flat_map(|p| p[0].to_le_bytes()).collect::<Vec<u8>>(), 4);
        }
        for (index, buffer) in &self.uniform_buffers {
            let stage = if *index == 0 { &pack.composite.vertex } else { &pack.composite.fragment };
            let block = uniforms::fill_block(&stage.module, values, &stage.path)?.expect("the block was found when building");
            gpu.queue.write_buffer(buffer, 0, &block.bytes);
        }
        Ok(())
    }

    fn encode_composite(&self, encoder: &mut wgpu::CommandEncoder, pack: &LoadedPack, timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>) {
        let out_view = self.out.create_view(&Default::default());
        let alt_views: Vec<wgpu::TextureView> = self.alternates.iter().map(|t| t.create_view(&Default::default())).collect();
        let mut alt = alt_views.iter();
        let attachments: Vec<_> = pack
            .composite
            .render_targets
            .iter()
            .map(|b| {
                let v = if *b == 0 { &out_view } else { alt.next().expect("one alternate per target") };
                Some(wgpu::RenderPassColorAttachment {
                    view: v,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations { load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT), store: wgpu::StoreOp::Store },
                })
            })
            .collect();
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("composite_only"),
            color_attachments: &attachments,
            timestamp_writes,
            ..Default::default()
        });
        pass.set_pipeline(&self.pipeline);
        for (i, group) in self.bind_groups.iter().enumerate() {
            pass.set_bind_group(i as u32, group, &[]);
        }
        pass.set_vertex_buffer(0, self.quad.slice(..));
        pass.draw(0..self.quad_len, 0..1);
    }

    fn encode_passthrough(&self, encoder: &mut wgpu::CommandEncoder, timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>) {
        let view = self.passthrough.out.create_view(&Default::default());
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("pass-through composite"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations { load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT), store: wgpu::StoreOp::Store },
            })],
            timestamp_writes,
            ..Default::default()
        });
        pass.set_pipeline(&self.passthrough.pipeline.pipeline);
        pass.set_bind_group(0, &self.passthrough.pipeline.bind_group, &[]);
        pass.draw(0..3, 0..1);
    }
}

fn sampler(gpu: &Gpu, filter: wgpu::FilterMode, address: wgpu::AddressMode) -> wgpu::Sampler {
    gpu.device.create_sampler(&wgpu::SamplerDescriptor {
        address_mode_u: address,
        address_mode_v: address,
        address_mode_w: address,
        mag_filter: filter,
        min_filter: filter,
        ..Default::default()
    })
}
