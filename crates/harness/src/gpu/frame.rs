//! A frame of any pack, ours included ([`crate::any_pack::FramePlan`]), through wgpu, step
//! by step: each step's pipeline is built against the textures current at its turn. The
//! screen is RGBA32F, so NaN and Inf survive. Frames can be repeated for timing, each followed
//! by a one-tap pass-through of colortex0, the floor a frame's cost is measured against;
//! after each step of the last frame the textures it wrote are read back and their NaN and Inf
//! counted.
//!
//! Buffers are stored in OpenGL orientation (row 0 at the bottom): the vertex shaders flip y.

use std::collections::{BTreeMap, BTreeSet};

use crate::HarnessError;
use crate::any_pack::{AnyPack, DepthSeed, FramePlan, PassValues, PlannedWork, ScreenOutput};
use crate::images::FloatImage;
use tidepack_scene::mesh::{PackVertex, SceneMesh, Sprites};
use crate::program::{LoadedProgram, PackResources};
use tidepack_loader::directives::Blend;
use tidepack_scene::scene::Scene;
use crate::uniforms::{Pass, Value};

use super::Gpu;
use super::bindings::{
    BindableTextures, DEPTH, DepthRead, DrawState, FullscreenQuad, HarnessTextures, NO_MIPMAPS, OUT, PassKind, ProgramPipeline, ShadowTextures,
    UniformBinding, view,
};
use super::geometry::{GeometryDraw, depth_attachment};
use super::own::{DepthWriter, MipmapPipelines, PassthroughPipeline};
use crate::samplers::SamplerNaming;
use tidepack_loader::buffers::mip_levels;
use super::readback::{read_pass_ms, read_texture, write_texture};
use crate::images::settled_median;

/// One pass of the frame as it ran.
#[derive(Clone, Debug, serde::Serialize)]
pub struct StepReport {
    /// `terrain (gbuffers_terrain)`, `composite1`, `depth copy`, …
    pub pass: String,
    /// Wall time of the last frame's step.
    pub wall_ms: f64,
    /// GPU time from timestamps, when the adapter has them (last frame).
    pub gpu_ms: Option<f64>,
    /// Median over the frames after the first: GPU time where timestamps exist, else wall.
    pub median_ms: f64,
    /// The time of every frame's step, the same kind of time as `median_ms`.
    pub samples_ms: Vec<f64>,
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
    /// The pass-through's time in every frame.
    pub passthrough_samples_ms: Vec<f64>,
}

/// A frame of any pack.
#[derive(Clone, Debug)]
pub struct Frame {
    /// The screen: what final wrote, bottom row first.
    pub image: FloatImage,
    /// Each colour buffer's current texture when final ran.
    pub buffers: BTreeMap<u8, FloatImage>,
    pub depth0: FloatImage,
    pub depth1: FloatImage,
    pub passes: Vec<StepReport>,
    pub timing: FrameTiming,
    /// What the pack uses that this frame did not imitate: the pack's own list, and the
    /// uniforms and vertex inputs left at zero.
    pub not_modelled: Vec<String>,
    /// The uniforms and vertex inputs the harness has no value for, left at zero.
    pub zeroed: Vec<String>,
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
    /// `lod`: Distant Horizons' draw, into its own depth buffer.
    Geometry { draw: GeometryDraw, current: &'p BTreeMap<u8, usize>, snapshots: &'p BTreeSet<u8>, lod: bool },
    DepthCopy,
    LodDepthCopy,
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
    /// A shadowcomp program, each shadow colour buffer copied to its copy as read first.
    ShadowComposite { program: &'p LoadedProgram, pipeline: ProgramPipeline },
    /// A step wgpu cannot draw, with why: [`render_from`] takes what it wrote from the
    /// reference.
    Cannot(String),
}

impl Work<'_> {
    /// A texture copy, not a render pass (no timestamps).
    fn is_copy(&self) -> bool {
        matches!(self, Work::DepthCopy | Work::LodDepthCopy | Work::ShadowDepthCopy)
    }
}

/// Renders `frames` frames of `scene` with the pack's programs, pipelines made once; returns
/// the last with the medians of the others' times. Every wgpu validation error becomes a
/// [`HarnessError::Wgpu`].
pub fn render(gpu: &Gpu, pack: &AnyPack, scene: &Scene, mesh: &SceneMesh, screen: ScreenOutput, frames: usize) -> Result<Frame, HarnessError> {
    gpu.check_resolution(scene.width(), scene.height())
        .map_err(|e| HarnessError::Scene(format!("scene {}: {e}", scene.name)))?;
    gpu.checked("frame", || render_checked(gpu, pack, scene, mesh, screen, frames))?
}

/// Every way a frame's textures are used: drawn into, sampled, copied from and to.
fn every_use() -> wgpu::TextureUsages {
    wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_SRC | wgpu::TextureUsages::COPY_DST
}

/// The textures of one frame of the plan: each colour buffer's two and its snapshot, the depth
/// buffers, the screen and the shadow maps.
struct FrameTextures {
    size: wgpu::Extent3d,
    buffers: BTreeMap<u8, Buffer>,
    /// The snapshots, as gbuffers programs bind the colour buffers.
    snapshots: BTreeMap<u8, (wgpu::Texture, wgpu::TextureFormat)>,
    depth0: wgpu::Texture,
    depth1: wgpu::Texture,
    /// depth0 and depth1 as a lookup used past its first channel reads them (d, d, d, 1), kept
    /// current while `depth_read_bound` (see `BindableTextures::depth_read`).
    depth_read: [wgpu::Texture; 2],
    depth_read_bound: std::cell::Cell<bool>,
    /// Distant Horizons' depth buffers, dhDepthTex0 and dhDepthTex1.
    lod_depth: [wgpu::Texture; 2],
    screen: wgpu::Texture,
    shadow_size: wgpu::Extent3d,
    shadow_depth: [wgpu::Texture; 2],
    /// The shadow maps as `sampler2D` reads them (depth as luminance).
    shadow_depth_read: [wgpu::Texture; 2],
    shadow_colours: BTreeMap<u8, (wgpu::Texture, wgpu::TextureFormat)>,
    /// Each shadow colour buffer as a shadowcomp program reads it: copied just before the draw,
    /// as the loaders' flip leaves it to read. Empty without shadowcomp programs.
    shadow_colours_before: BTreeMap<u8, (wgpu::Texture, wgpu::TextureFormat)>,
}

/// Most bytes the textures of one frame may take (lavapipe keeps them in the machine's memory):
/// the pack's colour buffers at the scene's resolution, their snapshots, depth, the screen and
/// the shadow maps.
pub const MAX_FRAME_TEXTURE_BYTES: u64 = 384 << 20;

/// Bytes per texel of `format` (depth formats have no copy size of their own).
fn texel_bytes(format: wgpu::TextureFormat) -> u64 {
    u64::from(format.block_copy_size(None).unwrap_or(4))
}

impl FrameTextures {
    /// What the frame's textures will take, refused over [`MAX_FRAME_TEXTURE_BYTES`] before any
    /// is made.
    fn check_budget(gpu: &Gpu, pack: &AnyPack, plan: &FramePlan, scene: &Scene) -> Result<(), HarnessError> {
        let pixels = u64::from(scene.width()) * u64::from(scene.height());
        let mut per_pixel = 4 * texel_bytes(DEPTH) + 3 * texel_bytes(OUT);
        for &b in &plan.buffers {
            let bytes = texel_bytes(gpu.texture_format(pack.format_of(b))?);
            // Two to draw into and read from, one snapshot; a mip chain adds a third of a level.
            per_pixel += if plan.mipmapped.contains(&b) { bytes * 2 * 4 / 3 + bytes } else { 3 * bytes };
        }
        let shadow_side = if pack.shadow_pass { u64::from(pack.shadow_settings.drawn_resolution().0) } else { 1 };
        let mut per_shadow_texel = 2 * texel_bytes(DEPTH) + 2 * texel_bytes(OUT);
        let copies = if plan.has_shadow_composite() { 2 } else { 1 };
        for &b in &plan.shadow_buffers {
            per_shadow_texel += copies * texel_bytes(gpu.texture_format(pack.shadow_format_of(b))?);
        }
        let bytes = pixels.saturating_mul(per_pixel).saturating_add(shadow_side * shadow_side * per_shadow_texel);
        if bytes > MAX_FRAME_TEXTURE_BYTES {
            return Err(HarnessError::Scene(format!(
                "the frame's textures would take {} MiB ({} colour buffers at {}x{}, shadow maps of {shadow_side}^2), more than the budget of {} MiB",
                bytes >> 20,
                plan.buffers.len(),
                scene.width(),
                scene.height(),
                MAX_FRAME_TEXTURE_BYTES >> 20
            )));
        }
        Ok(())
    }

    fn new(gpu: &Gpu, pack: &AnyPack, plan: &FramePlan, scene: &Scene) -> Result<FrameTextures, HarnessError> {
        FrameTextures::check_budget(gpu, pack, plan, scene)?;
        let size = wgpu::Extent3d { width: scene.width(), height: scene.height(), depth_or_array_layers: 1 };
        let texture = |label: &str, format| gpu.texture(label, size, format, every_use());
        let mut buffers: BTreeMap<u8, Buffer> = BTreeMap::new();
        // Mipmapped buffers have full mip chains; programs draw into, and read, the first level.
        let levels = mip_levels(scene.width(), scene.height());
        for &b in &plan.buffers {
            let format = gpu.texture_format(pack.format_of(b))?;
            let label = |what: &str| format!("colortex{b} {what}");
            let levels = if plan.mipmapped.contains(&b) { levels } else { 1 };
            let flipped = |what: &str| gpu.texture_with_levels(&label(what), size, format, every_use(), levels);
            buffers.insert(b, Buffer { textures: [flipped("A"), flipped("B")], snapshot: texture(&label("as gbuffers read it"), format), format });
        }
        let snapshots = buffers.iter().map(|(b, buffer)| (*b, (buffer.snapshot.clone(), buffer.format))).collect();
        // The shadow maps: one texel each, cleared, when the frame has no shadow pass.
        let shadow_side = if pack.shadow_pass { pack.shadow_settings.drawn_resolution().0 } else { 1 };
        let shadow_size = wgpu::Extent3d { width: shadow_side, height: shadow_side, depth_or_array_layers: 1 };
        let shadow_texture = |label: &str, format| gpu.texture(label, shadow_size, format, every_use());
        let mut shadow_colours = BTreeMap::new();
        let mut shadow_colours_before = BTreeMap::new();
        for &b in &plan.shadow_buffers {
            let format = gpu.texture_format(pack.shadow_format_of(b))?;
            shadow_colours.insert(b, (shadow_texture(&format!("shadowcolor{b}"), format), format));
            if plan.has_shadow_composite() {
                shadow_colours_before.insert(b, (shadow_texture(&format!("shadowcolor{b} as shadowcomp reads it"), format), format));
            }
        }
        Ok(FrameTextures {
            size,
            buffers,
            snapshots,
            depth0: texture("depthtex0", DEPTH),
            depth1: texture("depthtex1", DEPTH),
            depth_read: [texture("depthtex0 as a colour lookup reads it", OUT), texture("depthtex1 as a colour lookup reads it", OUT)],
            depth_read_bound: std::cell::Cell::new(false),
            lod_depth: [texture("dhDepthTex0", DEPTH), texture("dhDepthTex1", DEPTH)],
            screen: texture("screen (RGBA32F)", OUT),
            shadow_size,
            shadow_depth: [shadow_texture("shadowtex0", DEPTH), shadow_texture("shadowtex1", DEPTH)],
            shadow_depth_read: [shadow_texture("shadowtex0 as sampler2D reads it", OUT), shadow_texture("shadowtex1 as sampler2D reads it", OUT)],
            shadow_colours,
            shadow_colours_before,
        })
    }

    /// depth_read with depth0 and depth1 as `[n0, n1]` of it.
    fn depth_read(&self, n: [usize; 2]) -> DepthRead<'_> {
        DepthRead { textures: n.map(|i| &self.depth_read[i]), bound: &self.depth_read_bound }
    }

    fn shadow(&self) -> ShadowTextures<'_> {
        ShadowTextures {
            depth: [&self.shadow_depth[0], &self.shadow_depth[1]],
            depth_read: [&self.shadow_depth_read[0], &self.shadow_depth_read[1]],
            colours: &self.shadow_colours,
        }
    }

    /// Every texture cleared as the pack's directives say, at the start of a frame.
    fn record_clears(&self, encoder: &mut wgpu::CommandEncoder, pack: &AnyPack, scene: &Scene) {
        let colours: Vec<(&wgpu::Texture, [f64; 4])> = self
            .buffers
            .iter()
            .flat_map(|(b, buffer)| buffer.textures.iter().map(move |t| (t, pack.clear_of(*b).colour(*b, scene.sky.fog_color))))
            .collect();
        // depth_read[0] is depth0 as luminance, cleared with it; depth1 and its copy are not.
        let mut colours = colours;
        colours.push((&self.depth_read[0], [1.0; 4]));
        record_clears(encoder, &colours, &self.depth0);
        record_clears(encoder, &[], &self.lod_depth[0]);
        let mut shadow_clears: Vec<(&wgpu::Texture, [f64; 4])> =
            self.shadow_colours.iter().map(|(b, (t, _))| (t, pack.shadow_clear_of(*b).shadow_colour())).collect();
        shadow_clears.extend(self.shadow_depth_read.iter().map(|t| (t, [1.0; 4])));
        record_clears(encoder, &shadow_clears, &self.shadow_depth[0]);
        record_clears(encoder, &[], &self.shadow_depth[1]);
    }

    /// The frame as these textures end it: the screen, each buffer's current texture and the
    /// depth buffers read back, with what the run gives.
    fn frame_as_ended(
        &self,
        gpu: &Gpu,
        plan: &FramePlan,
        passes: Vec<StepReport>,
        timing: FrameTiming,
        not_modelled: Vec<String>,
        zeroed: Vec<String>,
    ) -> Result<Frame, HarnessError> {
        let mut buffers = BTreeMap::new();
        for (b, buffer) in &self.buffers {
            buffers.insert(*b, read_texture(gpu, &buffer.textures[plan.current[b]], buffer.format)?);
        }
        Ok(Frame {
            image: read_texture(gpu, &self.screen, OUT)?,
            buffers,
            depth0: read_texture(gpu, &self.depth0, DEPTH)?,
            depth1: read_texture(gpu, &self.depth1, DEPTH)?,
            passes,
            timing,
            not_modelled,
            zeroed,
        })
    }

    /// The texture a step wrote, read back.
    fn read(&self, gpu: &Gpu, texture: &WrittenTexture) -> Result<FloatImage, HarnessError> {
        read_texture(gpu, self.texture(texture), self.format(texture))
    }

    fn texture(&self, texture: &WrittenTexture) -> &wgpu::Texture {
        match texture {
            WrittenTexture::Screen => &self.screen,
            WrittenTexture::Buffer(b, i) => &self.buffers[b].textures[*i],
            WrittenTexture::ShadowColour(b) => &self.shadow_colours[b].0,
        }
    }

    fn format(&self, texture: &WrittenTexture) -> wgpu::TextureFormat {
        match texture {
            WrittenTexture::Screen => OUT,
            WrittenTexture::Buffer(b, _) => self.buffers[b].format,
            WrittenTexture::ShadowColour(b) => self.shadow_colours[b].1,
        }
    }
}

/// The plan's steps with their pipelines, what each writes, and what the pipelines left at zero.
struct PreparedSteps<'p> {
    steps: Vec<(&'p str, Work<'p>, Vec<Written>)>,
    zeroed_inputs: Vec<String>,
    zeroed_uniforms: Vec<String>,
}

impl<'p> PreparedSteps<'p> {
    /// Every step's work. With `tolerate`, a step whose pipeline cannot be built (wgpu or naga
    /// refuses it, a binding the harness cannot make) becomes [`Work::Cannot`] and the others
    /// are still built; without, the first such error is the frame's.
    #[allow(clippy::too_many_arguments)]
    fn new(
        gpu: &Gpu,
        pack: &AnyPack,
        scene: &Scene,
        plan: &'p FramePlan,
        textures: &FrameTextures,
        harness: &HarnessTextures,
        values: &PassValues,
        tolerate: bool,
    ) -> Result<Self, HarnessError> {
        let mut prepared = PreparedSteps { steps: Vec::new(), zeroed_inputs: Vec::new(), zeroed_uniforms: Vec::new() };
        for step in &plan.steps {
            let built = if tolerate {
                gpu.checked(&step.label, || prepared.step(gpu, pack, scene, step, textures, harness, values)).and_then(|built| built)
            } else {
                prepared.step(gpu, pack, scene, step, textures, harness, values)
            };
            let (work, written) = match built {
                Ok(built) => built,
                Err(cannot) if tolerate => (Work::Cannot(cannot.to_string()), Vec::new()),
                Err(e) => return Err(e),
            };
            prepared.steps.push((step.label.as_str(), work, written));
        }
        Ok(prepared)
    }

    /// One step's work and the textures it writes.
    #[allow(clippy::too_many_arguments)]
    fn step(
        &mut self,
        gpu: &Gpu,
        pack: &AnyPack,
        scene: &Scene,
        step: &'p crate::any_pack::PlannedStep,
        textures: &FrameTextures,
        harness: &HarnessTextures,
        values: &PassValues,
    ) -> Result<(Work<'p>, Vec<Written>), HarnessError> {
        Ok(match &step.work {
            PlannedWork::Geometry { program, vertices, default_blend, depth_write, current, snapshots, sprites, pass, draw } => {
                let values = draw.applied(values.of_pass(*pass));
                let blend_of = |b: u8| pack.blend_of(*program, b, default_blend);
                let state = DrawState { blend_of: &blend_of, depth_write: *depth_write };
                // depthtex0 is the buffer being drawn into: gbuffers programs read depthtex1.
                let bindable = BindableTextures {
                    naming: SamplerNaming::Frame,
                    harness,
                    colors: &textures.snapshots,
                    depth0: &textures.depth1,
                    depth1: &textures.depth1,
                    depth_read: textures.depth_read([1, 1]),
                    // Likewise dhDepthTex0 while Distant Horizons draws into it.
                    lod_depth: [&textures.lod_depth[1]; 2],
                    shadow: textures.shadow(),
                    sprites: *sprites,
                    mipmapped: &NO_MIPMAPS,
                };
                let draw = self.geometry(gpu, pack, scene, &values, &bindable, *program, &state, vertices, &step.label)?;
                let written = draw.buffers().map(|b| (format!("colortex{b}"), WrittenTexture::Buffer(b, current[&b]))).collect();
                (Work::Geometry { draw, current, snapshots, lod: *pass == Pass::DistantHorizons }, written)
            }
            PlannedWork::DepthCopy => (Work::DepthCopy, Vec::new()),
            PlannedWork::LodDepthCopy => (Work::LodDepthCopy, Vec::new()),
            PlannedWork::ShadowGeometry { program, vertices, draw } => {
                let values = draw.applied(&values.shadow);
                let blend_of = |b: u8| pack.blend_of(Some(program), b, &Blend::Off);
                let state = DrawState { blend_of: &blend_of, depth_write: true };
                // The shadow maps being drawn read as nothing drawn; the frame's buffers are not bound.
                let bindable = BindableTextures {
                    naming: SamplerNaming::ShadowPass,
                    harness,
                    colors: &textures.shadow_colours,
                    depth0: &textures.depth1,
                    depth1: &textures.depth1,
                    depth_read: textures.depth_read([1, 1]),
                    lod_depth: [&textures.lod_depth[1]; 2],
                    shadow: ShadowTextures::empty(harness),
                    sprites: Sprites::Blocks,
                    mipmapped: &NO_MIPMAPS,
                };
                let draw = self.geometry(gpu, pack, scene, &values, &bindable, Some(program), &state, vertices, &step.label)?;
                let written = draw.buffers().map(|b| (format!("shadowcolor{b}"), WrittenTexture::ShadowColour(b))).collect();
                (Work::ShadowGeometry(draw), written)
            }
            PlannedWork::ShadowDepthCopy => (Work::ShadowDepthCopy, Vec::new()),
            PlannedWork::Fullscreen { program, current, into_screen, mipmaps } => {
                let mut formats: BTreeMap<u8, wgpu::TextureFormat> = textures.buffers.iter().map(|(b, buffer)| (*b, buffer.format)).collect();
                if *into_screen {
                    formats.insert(0, OUT);
                }
                let pipeline = self.fullscreen(gpu, pack, textures, harness, &values.fullscreen, program, current, &formats, textures.shadow(), mipmaps)?;
                let written = program
                    .drawn_buffers()
                    .map(|b| match (*into_screen, b) {
                        (true, 0) => ("screen".to_string(), WrittenTexture::Screen),
                        _ => (format!("colortex{b}"), WrittenTexture::Buffer(b, 1 - current[&b])),
                    })
                    .collect();
                (Work::Fullscreen { program, pipeline, current, into_screen: *into_screen, mipmaps }, written)
            }
            PlannedWork::Compute { stage, .. } => {
                return Err(HarnessError::Unsupported(stage.only_opengl()));
            }
            PlannedWork::ShadowComposite { program, current } => {
                let formats: BTreeMap<u8, wgpu::TextureFormat> = textures.shadow_colours.iter().map(|(b, (_, format))| (*b, *format)).collect();
                let shadow = ShadowTextures { colours: &textures.shadow_colours_before, ..textures.shadow() };
                let pipeline = self.fullscreen(gpu, pack, textures, harness, &values.fullscreen, program, current, &formats, shadow, &NO_MIPMAPS)?;
                let written = program.drawn_buffers().map(|b| (format!("shadowcolor{b}"), WrittenTexture::ShadowColour(b))).collect();
                (Work::ShadowComposite { program, pipeline }, written)
            }
            PlannedWork::ScreenCopy { current } => {
                let copy = PassthroughPipeline::new(gpu, &textures.buffers[&0].textures[*current])?;
                (Work::ScreenCopy(copy), vec![("screen".to_string(), WrittenTexture::Screen)])
            }
        })
    }

    /// A geometry step's draw, its zeroed inputs and uniforms noted.
    #[allow(clippy::too_many_arguments)]
    fn geometry(
        &mut self,
        gpu: &Gpu,
        pack: &AnyPack,
        scene: &Scene,
        values: &BTreeMap<String, Value>,
        bindable: &BindableTextures,
        program: Option<&LoadedProgram>,
        state: &DrawState,
        vertices: &[PackVertex],
        label: &str,
    ) -> Result<GeometryDraw, HarnessError> {
        let missing = pack.loader.missing_program_draws();
        let draw = GeometryDraw::new(gpu, pack, missing, scene, values, bindable, program, state, vertices, label.to_string())?;
        if let Some(pipeline) = draw.pipeline() {
            self.zeroed_inputs.extend(pipeline.zeroed_inputs.iter().cloned());
            self.zeroed_uniforms.extend(pipeline.zeroed_uniforms.iter().cloned());
        }
        Ok(draw)
    }

    /// A full-screen step's pipeline into targets of `formats`, reading the buffers' current
    /// textures and `shadow`.
    #[allow(clippy::too_many_arguments)]
    fn fullscreen(
        &mut self,
        gpu: &Gpu,
        pack: &AnyPack,
        textures: &FrameTextures,
        harness: &HarnessTextures,
        values: &BTreeMap<String, Value>,
        program: &LoadedProgram,
        current: &BTreeMap<u8, usize>,
        formats: &BTreeMap<u8, wgpu::TextureFormat>,
        shadow: ShadowTextures,
        mipmaps: &BTreeSet<u8>,
    ) -> Result<ProgramPipeline, HarnessError> {
        let reading: BTreeMap<u8, (wgpu::Texture, wgpu::TextureFormat)> =
            textures.buffers.iter().map(|(b, buffer)| (*b, (buffer.textures[current[b]].clone(), buffer.format))).collect();
        let blend_of = |b: u8| pack.blend_of(Some(program), b, &Blend::Off);
        let bindable = BindableTextures {
            naming: SamplerNaming::Frame,
            harness,
            colors: &reading,
            depth0: &textures.depth0,
            depth1: &textures.depth1,
            depth_read: textures.depth_read([0, 1]),
            lod_depth: [&textures.lod_depth[0], &textures.lod_depth[1]],
            shadow,
            sprites: Sprites::Blocks,
            mipmapped: mipmaps,
        };
        let kind = PassKind::FullscreenInto { formats, blend_of: &blend_of };
        let pipeline = ProgramPipeline::new(gpu, pack, program, values, kind, &bindable, UniformBinding::ReadOnlyStorage)?;
        self.zeroed_uniforms.extend(pipeline.zeroed_uniforms.iter().cloned());
        Ok(pipeline)
    }
}

/// What recording a step needs besides its work: the frame's textures and the harness's own
/// pipelines.
struct Recorder<'r> {
    gpu: &'r Gpu,
    textures: &'r FrameTextures,
    mipmaps: MipmapPipelines,
    /// shadowtex0 as sampler2D reads it after each shadow draw; shadowtex1's is copied with it.
    depth_as_luminance: PassthroughPipeline,
    /// depth0 into `FrameTextures::depth_read[0]`, where a program reads it so.
    depth0_as_luminance: PassthroughPipeline,
    quad: FullscreenQuad,
}

impl<'r> Recorder<'r> {
    fn new(gpu: &'r Gpu, plan: &FramePlan, textures: &'r FrameTextures) -> Result<Recorder<'r>, HarnessError> {
        Ok(Recorder {
            gpu,
            textures,
            mipmaps: MipmapPipelines::new(gpu, plan.mipmapped.iter().map(|b| textures.buffers[b].format))?,
            depth_as_luminance: PassthroughPipeline::depth_as_luminance(gpu, &textures.shadow_depth[0])?,
            depth0_as_luminance: PassthroughPipeline::depth_as_luminance(gpu, &textures.depth0)?,
            quad: FullscreenQuad::new(gpu),
        })
    }
}

impl Recorder<'_> {
    fn record(&self, encoder: &mut wgpu::CommandEncoder, work: &Work, stamps: Option<wgpu::RenderPassTimestampWrites<'_>>) {
        let t = self.textures;
        match work {
            Work::Geometry { draw, current, snapshots, lod } => {
                for b in *snapshots {
                    let buffer = &t.buffers[b];
                    encoder.copy_texture_to_texture(buffer.textures[current[b]].as_image_copy(), buffer.snapshot.as_image_copy(), t.size);
                }
                let depth = if *lod { &t.lod_depth[0] } else { &t.depth0 };
                draw.record(encoder, &|b| &t.buffers[&b].textures[current[&b]], depth, stamps);
                if !*lod && t.depth_read_bound.get() {
                    self.depth0_as_luminance.record(encoder, &t.depth_read[0], None);
                }
            }
            Work::DepthCopy => {
                encoder.copy_texture_to_texture(t.depth0.as_image_copy(), t.depth1.as_image_copy(), t.size);
                if t.depth_read_bound.get() {
                    encoder.copy_texture_to_texture(t.depth_read[0].as_image_copy(), t.depth_read[1].as_image_copy(), t.size);
                }
            }
            Work::LodDepthCopy => encoder.copy_texture_to_texture(t.lod_depth[0].as_image_copy(), t.lod_depth[1].as_image_copy(), t.size),
            Work::ShadowGeometry(draw) => {
                draw.record(encoder, &|b| &t.shadow_colours[&b].0, &t.shadow_depth[0], stamps);
                self.depth_as_luminance.record(encoder, &t.shadow_depth_read[0], None);
            }
            Work::ShadowDepthCopy => {
                encoder.copy_texture_to_texture(t.shadow_depth[0].as_image_copy(), t.shadow_depth[1].as_image_copy(), t.shadow_size);
                encoder.copy_texture_to_texture(t.shadow_depth_read[0].as_image_copy(), t.shadow_depth_read[1].as_image_copy(), t.shadow_size);
            }
            Work::Fullscreen { program, pipeline, current, into_screen, mipmaps } => {
                for b in *mipmaps {
                    self.mipmaps.record(self.gpu, encoder, &t.buffers[b].textures[current[b]]);
                }
                let target = |b: u8| if *into_screen && b == 0 { &t.screen } else { &t.buffers[&b].textures[1 - current[&b]] };
                pipeline.record_fullscreen_into(encoder, program, &target, wgpu::LoadOp::Load, &self.quad, stamps);
            }
            Work::ScreenCopy(copy) => copy.record(encoder, &t.screen, stamps),
            Work::ShadowComposite { program, pipeline } => {
                for (b, (texture, _)) in &t.shadow_colours {
                    encoder.copy_texture_to_texture(texture.as_image_copy(), t.shadow_colours_before[b].0.as_image_copy(), t.shadow_size);
                }
                pipeline.record_fullscreen_into(encoder, program, &|b| &t.shadow_colours[&b].0, wgpu::LoadOp::Load, &self.quad, stamps);
            }
            Work::Cannot(_) => {}
        }
    }
}

fn render_checked(gpu: &Gpu, pack: &AnyPack, scene: &Scene, mesh: &SceneMesh, screen: ScreenOutput, frames: usize) -> Result<Frame, HarnessError> {
    let plan = FramePlan::new(pack, scene, mesh, screen);
    let textures = FrameTextures::new(gpu, pack, &plan, scene)?;
    let harness_textures = HarnessTextures::new(gpu, pack);
    let recorder = Recorder::new(gpu, &plan, &textures)?;

    let mut not_modelled = pack.not_modelled.clone();
    let (values, problems) = PassValues::of(pack, scene);
    not_modelled.extend(pack.sun_path_note(scene));
    not_modelled.extend(problems.iter().map(|problem| format!("{problem} (the uniform stays zero)")));
    let prepared = PreparedSteps::new(gpu, pack, scene, &plan, &textures, &harness_textures, &values, false)?;
    let mut zeroed: Vec<String> = prepared.zeroed_uniforms.iter().map(|name| format!("uniform {name}")).collect();
    zeroed.extend(prepared.zeroed_inputs.iter().map(|input| format!("vertex input {input}")));
    zeroed.sort();
    zeroed.dedup();
    not_modelled.extend(prepared.zeroed_uniforms.iter().map(|name| format!("uniform {name}: zero (the harness has no value for it)")));
    not_modelled.extend(prepared.zeroed_inputs.iter().map(|input| format!("vertex input {input}: zero (the harness's vertices do not carry it)")));

    let (passes, timing) = run_frames(&recorder, pack, scene, &plan, &prepared.steps, frames)?;
    not_modelled.sort();
    not_modelled.dedup();
    textures.frame_as_ended(gpu, &plan, passes, timing, not_modelled, zeroed)
}

/// A frame drawn by [`render_from`]: each step from the reference's inputs.
pub struct SteppedFrame {
    pub frame: Frame,
    /// Per step, in plan order: why wgpu cannot draw it, where it cannot; the step's textures
    /// are then the reference's.
    pub cannot_draw: Vec<Option<String>>,
}

/// Draws `scene` once as [`render`] does, but each step starts from what `reference` (another
/// renderer's frame of the same plan) left: the textures the step before wrote are replaced by
/// the reference's, and so are the depth buffers a full-screen step reads, as
/// [`crate::gl_frame::render_from`] does for OpenGL. A step wgpu or naga cannot draw is left to
/// the reference: its textures, and the depth buffer a geometry step drew into, are the
/// reference's. Each step wgpu draws is then drawn from the inputs the reference's was.
pub fn render_from(gpu: &Gpu, pack: &AnyPack, scene: &Scene, mesh: &SceneMesh, screen: ScreenOutput, reference: &crate::gl_frame::Reference) -> Result<SteppedFrame, HarnessError> {
    gpu.check_resolution(scene.width(), scene.height())
        .map_err(|e| HarnessError::Scene(format!("scene {}: {e}", scene.name)))?;
    gpu.checked("frame", || render_from_checked(gpu, pack, scene, mesh, screen, reference))?
}

fn render_from_checked(gpu: &Gpu, pack: &AnyPack, scene: &Scene, mesh: &SceneMesh, screen: ScreenOutput, reference: &crate::gl_frame::Reference) -> Result<SteppedFrame, HarnessError> {
    let plan = FramePlan::new(pack, scene, mesh, screen);
    if reference.steps.len() != plan.steps.len() || reference.depth_written.len() != plan.steps.len() {
        return Err(HarnessError::Wgpu(format!("the reference frame ran {} steps, the wgpu frame has {}", reference.steps.len(), plan.steps.len())));
    }
    let textures = FrameTextures::new(gpu, pack, &plan, scene)?;
    let harness_textures = HarnessTextures::new(gpu, pack);
    let recorder = Recorder::new(gpu, &plan, &textures)?;
    let (depth_as_luminance, depth0_as_luminance) = (&recorder.depth_as_luminance, &recorder.depth0_as_luminance);
    let depth1_as_luminance = PassthroughPipeline::depth_as_luminance(gpu, &textures.depth1)?;
    let depth_writer = DepthWriter::new(gpu)?;
    let (values, _) = PassValues::of(pack, scene);
    let prepared = PreparedSteps::new(gpu, pack, scene, &plan, &textures, &harness_textures, &values, true)?;

    let mut encoder = gpu.encoder();
    textures.record_clears(&mut encoder, pack, scene);
    gpu.submit_and_wait(encoder)?;
    let mut passes = Vec::new();
    let mut cannot_draw = Vec::new();
    for (index, (label, work, written)) in prepared.steps.iter().enumerate() {
        if index > 0 {
            // What the step before wrote, as the reference has it.
            for (name, image) in reference.steps[index - 1] {
                if let Some(texture) = texture_written(&plan.steps[index - 1].work, name) {
                    write_texture(gpu, textures.texture(&texture), textures.format(&texture), image)?;
                }
            }
            if let (Work::Cannot(_), Some(depth)) = (&prepared.steps[index - 1].1, reference.depth_written[index - 1]) {
                let mut encoder = gpu.encoder();
                match &plan.steps[index - 1].work {
                    PlannedWork::Geometry { pass: Pass::DistantHorizons, .. } => depth_writer.write(gpu, &textures.lod_depth[0], depth)?,
                    PlannedWork::Geometry { .. } => {
                        depth_writer.write(gpu, &textures.depth0, depth)?;
                        if textures.depth_read_bound.get() {
                            depth0_as_luminance.record(&mut encoder, &textures.depth_read[0], None);
                        }
                    }
                    _ => {
                        depth_writer.write(gpu, &textures.shadow_depth[0], depth)?;
                        depth_as_luminance.record(&mut encoder, &textures.shadow_depth_read[0], None);
                    }
                }
                gpu.submit_and_wait(encoder)?;
            }
        }
        let seeds = match plan.depth_seed(index) {
            Some(DepthSeed::AsEnded) => Some([reference.depth0, reference.depth1]),
            Some(DepthSeed::OpaqueOnly) => Some([reference.depth1; 2]),
            None => None,
        };
        if let Some([depth0, depth1]) = seeds {
            depth_writer.write(gpu, &textures.depth0, depth0)?;
            depth_writer.write(gpu, &textures.depth1, depth1)?;
            let mut encoder = gpu.encoder();
            depth0_as_luminance.record(&mut encoder, &textures.depth_read[0], None);
            depth1_as_luminance.record(&mut encoder, &textures.depth_read[1], None);
            gpu.submit_and_wait(encoder)?;
        }
        let (images, wall_ms) = match work {
            Work::Cannot(why) => {
                cannot_draw.push(Some(why.clone()));
                (reference.steps[index].to_vec(), 0.0)
            }
            _ => {
                cannot_draw.push(None);
                let mut encoder = gpu.encoder();
                recorder.record(&mut encoder, work, None);
                let wall_ms = gpu.submit_and_wait(encoder)?;
                let mut images = Vec::new();
                for (name, texture) in written {
                    images.push((name.clone(), textures.read(gpu, texture)?));
                }
                (images, wall_ms)
            }
        };
        let non_finite = images.iter().map(|(name, image)| (name.clone(), image.non_finite())).collect();
        passes.push(StepReport { pass: label.to_string(), wall_ms, gpu_ms: None, median_ms: wall_ms, samples_ms: vec![wall_ms], non_finite, images });
    }
    let untimed = FrameTiming { frames: 1, frame_ms: f64::NAN, passthrough_ms: f64::NAN, passthrough_samples_ms: Vec::new() };
    let frame = textures.frame_as_ended(gpu, &plan, passes, untimed, pack.not_modelled.clone(), Vec::new())?;
    Ok(SteppedFrame { frame, cannot_draw })
}

/// The texture of `work`'s that the reference names `name` (`colortex2`, `shadowcolor0`,
/// `screen`), as the step writes it.
fn texture_written(work: &PlannedWork, name: &str) -> Option<WrittenTexture> {
    let buffer = |prefix: &str| name.strip_prefix(prefix).and_then(|n| n.parse::<u8>().ok());
    match work {
        PlannedWork::Geometry { current, .. } => buffer("colortex").map(|b| WrittenTexture::Buffer(b, current[&b])),
        PlannedWork::ShadowGeometry { .. } | PlannedWork::ShadowComposite { .. } => buffer("shadowcolor").map(WrittenTexture::ShadowColour),
        PlannedWork::Fullscreen { .. } if name == "screen" => Some(WrittenTexture::Screen),
        PlannedWork::Fullscreen { current, .. } => buffer("colortex").map(|b| WrittenTexture::Buffer(b, 1 - current[&b])),
        PlannedWork::ScreenCopy { .. } if name == "screen" => Some(WrittenTexture::Screen),
        PlannedWork::Compute { current, .. } => {
            buffer("colortex").map(|b| WrittenTexture::Buffer(b, current[&b])).or_else(|| buffer("shadowcolor").map(WrittenTexture::ShadowColour))
        }
        _ => None,
    }
}

/// Runs `frames` frames of the prepared steps, each followed by a one-tap pass-through of
/// colortex0 to a texture of its own (the floor the frame's cost is measured against); the
/// textures are read back, and their NaN and Inf counted, after every step of the last frame
/// only.
fn run_frames(
    recorder: &Recorder,
    pack: &AnyPack,
    scene: &Scene,
    plan: &FramePlan,
    steps: &[(&str, Work, Vec<Written>)],
    frames: usize,
) -> Result<(Vec<StepReport>, FrameTiming), HarnessError> {
    let (gpu, textures) = (recorder.gpu, recorder.textures);
    let device = &gpu.device;
    let floor_target = gpu.texture("pass-through output (RGBA32F)", textures.size, OUT, every_use());
    let floor = PassthroughPipeline::new(gpu, &textures.buffers[&0].textures[plan.current[&0]])?;
    let render_passes = steps.iter().filter(|(_, work, _)| !work.is_copy()).count() as u32 + 1;
    let queries = gpu.timestamps.then(|| {
        device.create_query_set(&wgpu::QuerySetDescriptor { label: Some("pass timestamps"), ty: wgpu::QueryType::Timestamp, count: render_passes * 2 })
    });
    let frames = frames.max(1);
    let mut reports: Vec<StepReport> = Vec::new();
    // Per frame: each step's time (GPU where timestamps exist, else wall) and the floor's.
    let mut step_ms: Vec<Vec<f64>> = vec![Vec::new(); steps.len()];
    let mut floor_ms = Vec::new();
    for frame in 0..frames {
        let last = frame + 1 == frames;
        let mut encoder = gpu.encoder();
        textures.record_clears(&mut encoder, pack, scene);
        gpu.submit_and_wait(encoder)?;
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
        for (label, work, written) in steps {
            let mut encoder = gpu.encoder();
            recorder.record(&mut encoder, work, stamp(!work.is_copy()));
            let wall_ms = gpu.submit_and_wait(encoder)?;
            walls.push(wall_ms);
            if last {
                let mut non_finite = BTreeMap::new();
                let mut images = Vec::new();
                for (name, texture) in written {
                    let image = textures.read(gpu, texture)?;
                    non_finite.insert(name.clone(), image.non_finite());
                    images.push((name.clone(), image));
                }
                reports.push(StepReport { pass: label.to_string(), wall_ms, gpu_ms: None, median_ms: 0.0, samples_ms: Vec::new(), non_finite, images });
            }
        }
        let mut encoder = gpu.encoder();
        floor.record(&mut encoder, &floor_target, stamp(true));
        walls.push(gpu.submit_and_wait(encoder)?);
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
    for (report, samples) in reports.iter_mut().zip(&step_ms) {
        report.median_ms = settled_median(samples);
        report.samples_ms = samples.clone();
    }
    let frame_ms: Vec<f64> = (0..frames).map(|f| step_ms.iter().map(|s| s[f]).sum()).collect();
    let timing = FrameTiming { frames, frame_ms: settled_median(&frame_ms), passthrough_ms: settled_median(&floor_ms), passthrough_samples_ms: floor_ms };
    Ok((reports, timing))
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
    // Without colours, one pass clears the depth alone.
    let chunks: Vec<&[Option<wgpu::RenderPassColorAttachment>]> = if attachments.is_empty() { vec![&[]] } else { attachments.chunks(8).collect() };
    for chunk in chunks {
        encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("clear"),
            color_attachments: chunk,
            depth_stencil_attachment: Some(depth_attachment(&depth0_view, true)),
            ..Default::default()
        });
    }
}
