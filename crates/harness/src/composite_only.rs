//! The composite program alone, over G-buffers the caller supplies, with its pipeline built
//! once: a stress sweep renders thousands of uniform sets and injected buffer contents
//! (`d0 == d1`, sky depth, zero normals) without recompiling anything per case.
//!
//! The program is built and bound exactly as in a whole frame ([`crate::gpu::bindings`]), with
//! two differences: the colour buffers are uploaded from the caller's floats (quantised to the
//! buffer's format, see [`CompositeOnly::quantize`]), and depthtex0/1 are R32Float textures
//! (bound unfilterable with a nearest sampler, as a frame binds Depth32Float), so any depth
//! value can be written. The output is RGBA32F, so NaN and Inf survive to the readback.
//!
//! The uniform blocks are bound as read-only storage buffers by default
//! ([`UniformBinding::ReadOnlyStorage`]): same bytes, same member offsets, same arithmetic, but
//! lavapipe cannot "inline" them. For uniform buffers, lavapipe may recompile a shader with the
//! current values of the members its `if` conditions test (here `isEyeInWater`) at every draw
//! after a pipeline or descriptor bind; some versions never free the copies, about 3.4 MB per
//! draw of composite (docs/stress.md, "Memory"). A storage buffer is read with `load_ssbo`,
//! which the inliner ignores, so the shader is compiled once and the resident memory stays
//! flat over any number of renders, whichever Mesa runs it.

use std::collections::BTreeMap;

use half::f16;

use crate::HarnessError;
use crate::gpu::bindings::{BindableTextures, DepthRead, FullscreenQuad, HarnessTextures, OUT, PassKind, ProgramPipeline, ShadowTextures};
use crate::samplers::{SamplerNaming, colour_buffers_read};
use crate::gpu::own::PassthroughPipeline;
use crate::gpu::readback::{read_pass_ms, read_texture, write_texture};
use crate::gpu::{Frame, Gpu};
use crate::images::FloatImage;
use crate::program::{LoadedPack, PackResources as _};
use tidepack_loader::buffers::BufferFormat;
use crate::uniforms::Value;

pub use crate::gpu::UniformBinding;

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

/// Depth textures as composite reads them here: writable from the caller's floats.
const DEPTH_AS: wgpu::TextureFormat = wgpu::TextureFormat::R32Float;

pub struct CompositeOnly {
    width: u32,
    height: u32,
    /// Colour buffers composite reads, and colortex0.
    colors: BTreeMap<u8, (wgpu::Texture, wgpu::TextureFormat)>,
    formats: BTreeMap<u8, BufferFormat>,
    depth0: wgpu::Texture,
    depth1: wgpu::Texture,
    /// The depth buffers as luminance (d, d, d, 1), written when composite binds them
    /// (`BindableTextures::depth_read`).
    depth_read: Option<[wgpu::Texture; 2]>,
    out: wgpu::Texture,
    composite: ProgramPipeline,
    quad: FullscreenQuad,
    /// The one-tap pass-through composite (colortex0 to an RGBA32F target), the floor
    /// [`CompositeOnly::time`] measures composite against.
    passthrough: PassthroughPipeline,
    passthrough_out: wgpu::Texture,
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
        let texture = |label: &str, format, usage| gpu.texture(label, wgpu::Extent3d { width, height, depth_or_array_layers: 1 }, format, usage);
        let input = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST;
        let output = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC;
        let mut buffers = colour_buffers_read(&pack.pack, pack.composite(), SamplerNaming::Frame);
        buffers.insert(0);
        let mut colors = BTreeMap::new();
        let mut formats = BTreeMap::new();
        for b in buffers {
            let format = pack.pack.format_of(b);
            let wgpu_format = gpu.texture_format(format)?;
            colors.insert(b, (texture(&format!("colortex{b}"), wgpu_format, input), wgpu_format));
            formats.insert(b, format);
        }
        let depth0 = texture("depthtex0 (R32Float)", DEPTH_AS, input);
        let depth1 = texture("depthtex1 (R32Float)", DEPTH_AS, input);
        // Distant Horizons' depth with no LODs drawn: 1 everywhere.
        let no_lods = texture("dhDepthTex0 and 1 (no LODs, R32Float)", DEPTH_AS, input);
        gpu.queue.write_texture(
            no_lods.as_image_copy(),
            bytemuck::cast_slice(&vec![1.0f32; (width * height) as usize]),
            wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(width * 4), rows_per_image: Some(height) },
            wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
        );
        let harness_textures = HarnessTextures::new(gpu, &pack.pack);
        let depth_read = [texture("depthtex0 as luminance (RGBA32F)", OUT, input), texture("depthtex1 as luminance (RGBA32F)", OUT, input)];
        let depth_read_bound = std::cell::Cell::new(false);
        let bindable = BindableTextures {
            naming: SamplerNaming::Frame,
            harness: &harness_textures,
            colors: &colors,
            depth0: &depth0,
            depth1: &depth1,
            depth_read: DepthRead { textures: [&depth_read[0], &depth_read[1]], bound: &depth_read_bound },
            lod_depth: [&no_lods; 2],
            shadow: ShadowTextures::empty(&harness_textures),
            sprites: tidepack_scene::mesh::Sprites::Blocks,
            mipmapped: &crate::gpu::bindings::NO_MIPMAPS,
        };
        let composite = gpu.checked("composite_only", || {
            ProgramPipeline::new(gpu, &pack.pack, pack.composite(), values, PassKind::Fullscreen { width, height }, &bindable, binding)
        })??;
        crate::complete(&composite.zeroed_uniforms)?;
        let passthrough = PassthroughPipeline::new(gpu, &colors[&0].0)?;
        Ok(CompositeOnly {
            width,
            height,
            formats,
            depth0,
            depth1,
            depth_read: depth_read_bound.get().then_some(depth_read),
            out: texture("composite output (RGBA32F)", OUT, output),
            composite,
            quad: FullscreenQuad::new(gpu),
            passthrough,
            passthrough_out: texture("pass-through output (RGBA32F)", OUT, output),
            colors,
        })
    }

    /// Colour buffers composite reads (colortex0 included).
    pub fn color_buffers(&self) -> Vec<u8> {
        self.colors.keys().copied().collect()
    }

    /// The value a colour buffer holds after uploading `v` (clamped and rounded for unorm
    /// formats, rounded to half precision for RGBA16F), so a reference can be fed exactly what
    /// composite read.
    pub fn quantize(&self, buffer: u8, v: f32) -> f32 {
        match self.formats.get(&buffer) {
            Some(BufferFormat::Rgba8) => (v.clamp(0.0, 1.0) * 255.0).round() / 255.0,
            Some(BufferFormat::Rgba16) => (v.clamp(0.0, 1.0) * 65535.0).round() / 65535.0,
            Some(BufferFormat::Rgba16F) => f16::from_f32(v).to_f32(),
            Some(BufferFormat::Rgba32F) | None => v,
            Some(BufferFormat::Rgba32Ui | BufferFormat::Rgba32I) => v.round(),
        }
    }

    /// Runs composite over `g` with the uniform values `values` (by OptiFine name, as
    /// [`crate::uniforms::values`] gives them); returns the RGBA32F output, bottom row first.
    pub fn render(&self, gpu: &Gpu, pack: &LoadedPack, g: &GBuffers, values: &BTreeMap<String, Value>) -> Result<FloatImage, HarnessError> {
        self.upload(gpu, pack, g, values)?;
        gpu.checked("composite_only", || {
            let mut encoder = gpu.device.create_command_encoder(&Default::default());
            self.composite.record_fullscreen(&mut encoder, pack.composite(), &self.out, &self.quad, None);
            gpu.queue.submit([encoder.finish()]);
        })?;
        read_texture(gpu, &self.out, OUT)
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
                        self.composite.record_fullscreen(&mut encoder, pack.composite(), &self.out, &self.quad, stamps);
                    } else {
                        self.passthrough.record(&mut encoder, &self.passthrough_out, stamps);
                    }
                    gpu.queue.submit([encoder.finish()]);
                })?;
                wait()?;
                *wall = started.elapsed().as_secs_f64() * 1000.0;
            }
            match &queries {
                Some(q) => {
                    // Two timed passes: composite, then the pass-through.
                    let ms = read_pass_ms(gpu, q, 2)?;
                    composite_ms.push(ms[0]);
                    passthrough_ms.push(ms[1]);
                }
                None => {
                    composite_ms.push(walls[0]);
                    passthrough_ms.push(walls[1]);
                }
            }
        }
        Ok(CompositeTimes { image: read_texture(gpu, &self.out, OUT)?, composite_ms, passthrough_ms, gpu_timestamps: queries.is_some() })
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
        for (b, (texture, format)) in &self.colors {
            let image = g.colors.get(b).ok_or_else(|| HarnessError::Scene(format!("no colortex{b} supplied")))?;
            check(&format!("colortex{b}"), image)?;
            write_texture(gpu, texture, *format, image)?;
        }
        for (n, (name, texture, image)) in [("depthtex0", &self.depth0, &g.depth0), ("depthtex1", &self.depth1, &g.depth1)].into_iter().enumerate() {
            check(name, image)?;
            write_texture(gpu, texture, DEPTH_AS, image)?;
            if let Some(read) = &self.depth_read {
                write_texture(gpu, &read[n], OUT, &FloatImage { pixels: image.pixels.iter().map(|p| [p[0], p[0], p[0], 1.0]).collect(), ..*image })?;
            }
        }
        self.composite.write_uniforms(gpu, pack.composite(), values)
    }
}
