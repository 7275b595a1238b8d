//! The harness's own shaders, for what is not the pack's: the fixed-function colour a loader
//! draws geometry with when the pack has no program for it, and the one-tap pass-through
//! composite that composite's cost is measured against, and the mip levels of mipmapped
//! buffers.

use wgpu::util::DeviceExt as _;

use crate::HarnessError;
use tidepack_scene::mesh::offsets;
use tidepack_scene::scene::Scene;

use super::Gpu;
use super::bindings::{DEPTH, OUT, clear_attachment, view};

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

/// A depth texture copied as OpenGL's compatibility profile reads it through `sampler2D`
/// (`GL_DEPTH_TEXTURE_MODE` `GL_LUMINANCE`) and as Iris swizzles its shadow maps: (d, d, d, 1).
const DEPTH_AS_LUMINANCE_WGSL: &str = r#"
@group(0) @binding(0) var depth: texture_depth_2d;
@vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let p = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(p * 2.0 - 1.0, 0.0, 1.0);
}
@fragment fn fs(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    let d = textureLoad(depth, vec2<i32>(p.xy), 0);
    return vec4<f32>(d, d, d, 1.0);
}
"#;

/// The harness's own shader for geometry the pack has no program for: the vertex colour into
/// every colour target given.
pub(crate) struct ColourPipeline {
    pipeline: wgpu::RenderPipeline,
    bind_group: wgpu::BindGroup,
}

impl ColourPipeline {
    pub(crate) fn new(
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
        let mvp: Vec<u8> = scene.terrain_mvp().iter().flat_map(|v| v.to_le_bytes()).collect();
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

    /// Sets the pipeline and its bind group on `pass`.
    pub(crate) fn bind(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.bind_group, &[]);
    }
}

/// A one-tap copy of a texture into an [`OUT`] texture of the same size: the pass-through
/// composite over `colortex0` the floor composite is timed against, or a depth texture read
/// as (d, d, d, 1).
pub(crate) struct PassthroughPipeline {
    pipeline: wgpu::RenderPipeline,
    bind_group: wgpu::BindGroup,
}

impl PassthroughPipeline {
    pub(crate) fn new(gpu: &Gpu, colortex0: &wgpu::Texture) -> Result<PassthroughPipeline, HarnessError> {
        PassthroughPipeline::with_shader(gpu, "pass-through", PASSTHROUGH_WGSL, colortex0)
    }

    /// Copies `depth` as OpenGL's compatibility profile reads a depth texture: (d, d, d, 1).
    pub(crate) fn depth_as_luminance(gpu: &Gpu, depth: &wgpu::Texture) -> Result<PassthroughPipeline, HarnessError> {
        PassthroughPipeline::with_shader(gpu, "depth as (d, d, d, 1)", DEPTH_AS_LUMINANCE_WGSL, depth)
    }

    fn with_shader(gpu: &Gpu, label: &str, wgsl: &str, input: &wgpu::Texture) -> Result<PassthroughPipeline, HarnessError> {
        let device = &gpu.device;
        let module = gpu.checked(&format!("{label} shader"), || {
            device.create_shader_module(wgpu::ShaderModuleDescriptor { label: Some(label), source: wgpu::ShaderSource::Wgsl(wgsl.into()) })
        })?;
        let pipeline = full_screen_triangle(gpu, label, &module, OUT)?;
        let bind_group = gpu.checked(&format!("{label} bind group"), || {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(label),
                layout: &pipeline.get_bind_group_layout(0),
                entries: &[wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(&view(input)) }],
            })
        })?;
        Ok(PassthroughPipeline { pipeline, bind_group })
    }

    /// Records the pass-through into `out`, an [`OUT`] texture, cleared first.
    pub(crate) fn record(&self, encoder: &mut wgpu::CommandEncoder, out: &wgpu::Texture, timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>) {
        let v = view(out);
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("one-tap copy"),
            color_attachments: &[Some(clear_attachment(&v))],
            timestamp_writes,
            ..Default::default()
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.bind_group, &[]);
        pass.draw(0..3, 0..1);
    }
}

/// Depth from an R32Float texture into the depth buffer drawn into, texel for texel: a depth
/// buffer cannot be a copy's destination.
const DEPTH_FROM_FLOATS_WGSL: &str = r#"
@group(0) @binding(0) var depths: texture_2d<f32>;
@vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let p = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(p * 2.0 - 1.0, 0.0, 1.0);
}
@fragment fn fs(@builtin(position) p: vec4<f32>) -> @builtin(frag_depth) f32 {
    return textureLoad(depths, vec2<i32>(p.xy), 0).r;
}
"#;

/// Writes depth buffers from images: a step another renderer drew leaves its depth so.
pub(crate) struct DepthWriter {
    pipeline: wgpu::RenderPipeline,
}

impl DepthWriter {
    pub(crate) fn new(gpu: &Gpu) -> Result<DepthWriter, HarnessError> {
        let device = &gpu.device;
        let module = gpu.checked("depth writer shader", || {
            device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("depth from floats"),
                source: wgpu::ShaderSource::Wgsl(DEPTH_FROM_FLOATS_WGSL.into()),
            })
        })?;
        let pipeline = gpu.checked("depth writer pipeline", || {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some("depth from floats"),
                layout: None,
                vertex: wgpu::VertexState { module: &module, entry_point: Some("vs"), compilation_options: Default::default(), buffers: &[] },
                primitive: Default::default(),
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: DEPTH,
                    depth_write_enabled: Some(true),
                    depth_compare: Some(wgpu::CompareFunction::Always),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
                multisample: Default::default(),
                fragment: Some(wgpu::FragmentState { module: &module, entry_point: Some("fs"), compilation_options: Default::default(), targets: &[] }),
                multiview_mask: None,
                cache: None,
            })
        })?;
        Ok(DepthWriter { pipeline })
    }

    /// Replaces `depth` (a [`DEPTH`] texture) with `image`'s first channel.
    pub(crate) fn write(&self, gpu: &Gpu, depth: &wgpu::Texture, image: &crate::images::FloatImage) -> Result<(), HarnessError> {
        let floats = gpu.texture("depth to write (R32Float)", depth.size(), wgpu::TextureFormat::R32Float, wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST);
        super::readback::write_texture(gpu, &floats, wgpu::TextureFormat::R32Float, image)?;
        let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("depth from floats"),
            layout: &self.pipeline.get_bind_group_layout(0),
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(&view(&floats)) }],
        });
        let mut encoder = gpu.encoder();
        {
            let target = view(depth);
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("depth from floats"),
                color_attachments: &[],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &target,
                    depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Load, store: wgpu::StoreOp::Store }),
                    stencil_ops: None,
                }),
                ..Default::default()
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.draw(0..3, 0..1);
        }
        gpu.queue.submit([encoder.finish()]);
        Ok(())
    }
}

/// Each mip level from the one above it by linear filtering at the level's texel centres: what
/// Mesa's `glGenerateMipmap` does (a linear blit per level), so both renderers agree.
const MIPMAP_WGSL: &str = r#"
@group(0) @binding(0) var above: texture_2d<f32>;
@group(0) @binding(1) var linear: sampler;
@vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let p = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(p * 2.0 - 1.0, 0.0, 1.0);
}
@fragment fn fs(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    let size = max(textureDimensions(above) / 2u, vec2<u32>(1u));
    return textureSampleLevel(above, linear, p.xy / vec2<f32>(size), 0.0);
}
"#;

/// Makes the mip levels of textures of the given formats (`glGenerateMipmap`).
pub(crate) struct MipmapPipelines {
    pipelines: std::collections::HashMap<wgpu::TextureFormat, wgpu::RenderPipeline>,
    linear: wgpu::Sampler,
}

impl MipmapPipelines {
    pub(crate) fn new(gpu: &Gpu, formats: impl IntoIterator<Item = wgpu::TextureFormat>) -> Result<MipmapPipelines, HarnessError> {
        let device = &gpu.device;
        let module = gpu.checked("mipmap shader", || {
            device.create_shader_module(wgpu::ShaderModuleDescriptor { label: Some("mipmaps"), source: wgpu::ShaderSource::Wgsl(MIPMAP_WGSL.into()) })
        })?;
        let mut pipelines = std::collections::HashMap::new();
        for format in formats {
            let pipeline = full_screen_triangle(gpu, "mipmaps", &module, format)?;
            pipelines.insert(format, pipeline);
        }
        let linear = device.create_sampler(&wgpu::SamplerDescriptor {
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        Ok(MipmapPipelines { pipelines, linear })
    }

    /// Records the making of every level of `texture` below the first.
    pub(crate) fn record(&self, gpu: &Gpu, encoder: &mut wgpu::CommandEncoder, texture: &wgpu::Texture) {
        let Some(pipeline) = self.pipelines.get(&texture.format()) else { return };
        let level = |l: u32| {
            texture.create_view(&wgpu::TextureViewDescriptor { base_mip_level: l, mip_level_count: Some(1), ..Default::default() })
        };
        for l in 1..texture.mip_level_count() {
            let (above, target) = (level(l - 1), level(l));
            let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("mipmap level"),
                layout: &pipeline.get_bind_group_layout(0),
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(&above) },
                    wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::Sampler(&self.linear) },
                ],
            });
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("mipmap level"),
                color_attachments: &[Some(clear_attachment(&target))],
                ..Default::default()
            });
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.draw(0..3, 0..1);
        }
    }
}

/// A pipeline of `module`'s `vs` (a triangle over the target, no vertex buffers) and `fs` into
/// one target of `format`, its layout from the shader.
fn full_screen_triangle(gpu: &Gpu, label: &str, module: &wgpu::ShaderModule, format: wgpu::TextureFormat) -> Result<wgpu::RenderPipeline, HarnessError> {
    gpu.checked(&format!("{label} pipeline"), || {
        gpu.device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(label),
            layout: None,
            vertex: wgpu::VertexState { module, entry_point: Some("vs"), compilation_options: Default::default(), buffers: &[] },
            primitive: Default::default(),
            depth_stencil: None,
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module,
                entry_point: Some("fs"),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState { format, blend: None, write_mask: wgpu::ColorWrites::ALL })],
            }),
            multiview_mask: None,
            cache: None,
        })
    })
}
