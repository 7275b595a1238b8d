//! A frame of any pack, ours included ([`crate::any_pack::FramePlan`]), through Mesa's OpenGL, the shipped text
//! as the driver compiles it, step by step as [`crate::gpu::frame`] runs it with wgpu, so
//! the two can be compared texture by texture after every step.
//!
//! Depth is mapped as the wgpu path maps it ([`DepthMapping::Harness`]) for every program
//! whose vertex outputs transform feedback can record (floats, perspective, at most 15, which
//! a pass-through vertex stage reads back as attributes); a program with other outputs (`flat`
//! integers, interface blocks, more of them) is linked as shipped and drawn with OpenGL's own depth
//! range, which equals the wgpu mapping up to the last bits. Those programs are named in
//! [`GlFrame::own_depth_mapping`].

use std::collections::{BTreeMap, BTreeSet};

use tidepack_gldriver::glow::{self, HasContext as _};
use tidepack_gldriver::{GlContext, legacy};

use crate::HarnessError;
use crate::any_pack::{AnyPack, DepthSeed, FramePlan, PassValues, PlannedWork, ScreenOutput};
use crate::gl::{
    Compiled, DepthMapping, GlHarnessTextures, Held, Textures, attach, clear_colour, compile, dispatch_compute, draw_own_colour, draw_program, internal_format, make_texture,
    pixel_transfer, read, add_mip_levels, mask_unwritten, read_as_shadow_map, set_blends,
};
use crate::samplers::{ProgramStage, SamplerNaming, Source};
use crate::images::FloatImage;
use tidepack_scene::mesh::{self, PackVertex, SceneMesh, Sprites};
use crate::program::{ComputeStage, LoadedProgram, PackResources};
use tidepack_loader::buffers::BufferFormat;
use tidepack_loader::directives::Blend;
use tidepack_scene::scene::Scene;
use crate::uniforms::{DrawUniforms, Pass};
use tidepack_loader::loader::MissingProgramDraws;

/// A frame from the OpenGL driver, every image bottom row first.
#[derive(Clone, Debug)]
pub struct GlFrame {
    /// The screen.
    pub image: FloatImage,
    /// Each colour buffer's current texture at the end of the frame.
    pub buffers: BTreeMap<u8, FloatImage>,
    pub depth0: FloatImage,
    pub depth1: FloatImage,
    /// Per step, in plan order: the textures it wrote, named as the wgpu path names them.
    pub steps: Vec<(String, Vec<(String, FloatImage)>)>,
    /// Per step, in plan order: the depth buffer a geometry step drew into (depthtex0,
    /// dhDepthTex0 or shadowtex0) as it left it, for a renderer that cannot draw that step.
    pub depth_written: Vec<Option<FloatImage>>,
    /// Programs drawn with OpenGL's depth range (see the module doc).
    pub own_depth_mapping: Vec<String>,
    /// Per step, in plan order: wall time of its draws and copies between two `glFinish`, in
    /// ms (compiling the programs and reading the textures back are left out).
    pub step_ms: Vec<f64>,
    /// Per step, in plan order: whether its program was drawn traced
    /// ([`Reference::trace_derivatives`]), so that its textures hold where its implicit
    /// derivatives are undefined.
    pub traced: Vec<bool>,
    /// Wall time of a one-tap pass-through of colortex0 into the screen, timed as the steps
    /// are (the median of five draws).
    pub passthrough_ms: f64,
    /// What of the stages' text was rewritten when the driver refused it over one of its own
    /// limits (`program: path: what`); the stages' [`crate::program::LoadedStage::gl_rewrites`] hold the
    /// rest.
    pub rewrites: Vec<String>,
}

impl GlFrame {
    /// This frame as the reference another renderer draws each step from, with its inputs
    /// moved by `nudge` ([`Reference::nudge`]).
    pub fn as_reference(&self, nudge: f64) -> Reference<'_> {
        Reference {
            steps: self.steps.iter().map(|(_, images)| images.as_slice()).collect(),
            depth0: &self.depth0,
            depth1: &self.depth1,
            depth_written: self.depth_written.iter().map(Option::as_ref).collect(),
            nudge,
            trace_derivatives: false,
        }
    }
}

/// Renders `scene` with the pack's shipped text through OpenGL.
pub fn render(ctx: &GlContext, pack: &AnyPack, scene: &Scene, mesh: &SceneMesh, screen: ScreenOutput) -> Result<GlFrame, HarnessError> {
    render_seeded(ctx, pack, scene, mesh, screen, None)
}

/// Another renderer's frame of the same plan, for [`render_from`]: per step, the textures it
/// wrote (as [`GlFrame::steps`] names them), and its depth buffers at the end of the frame.
pub struct Reference<'r> {
    pub steps: Vec<&'r [(String, FloatImage)]>,
    pub depth0: &'r FloatImage,
    pub depth1: &'r FloatImage,
    /// Per step, the depth buffer a geometry step left ([`GlFrame::depth_written`]), for a
    /// renderer that takes a step it cannot draw from the reference; empty for one that draws
    /// every step.
    pub depth_written: Vec<Option<&'r FloatImage>>,
    /// Every float uniform, float literal of the shaders and the full-screen quad's vertices
    /// moved by this much of themselves (0: as the loader gives them); the caller nudges the
    /// scene's mesh alike. Pixels a nudge of a few units in the last place moves are those whose
    /// result the last bit of some arithmetic decides (a hash, the edge of a `floor`), where two
    /// correct compilers differ.
    pub nudge: f64,
    /// Each full-screen program is drawn traced instead ([`LoadedProgram::with_derivative_trace`]):
    /// it writes 1 where its implicit derivatives are undefined, 0 elsewhere, unblended.
    pub trace_derivatives: bool,
}

/// Renders `scene` as [`render`] does, but each step starts from what `reference` left: the
/// colour textures the step before wrote are replaced by the reference's, and so are the depth
/// buffers a full-screen step reads where the reference's final ones hold what they held then
/// (after the last geometry, or the opaque depth between the depth copy and the next geometry).
/// Each step is then drawn from the same inputs as the reference's, so a difference it shows is
/// its own, not one an earlier step made and a blur, a bloom or an occlusion pass spread.
pub fn render_from(ctx: &GlContext, pack: &AnyPack, scene: &Scene, mesh: &SceneMesh, screen: ScreenOutput, reference: &Reference) -> Result<GlFrame, HarnessError> {
    render_seeded(ctx, pack, scene, mesh, screen, Some(reference))
}

fn render_seeded(
    ctx: &GlContext,
    pack: &AnyPack,
    scene: &Scene,
    mesh: &SceneMesh,
    screen: ScreenOutput,
    reference: Option<&Reference>,
) -> Result<GlFrame, HarnessError> {
    let Some(clip_control) = ctx.legacy().clip_control else {
        return Err(HarnessError::Gl(format!("{} has no glClipControl (OpenGL 4.5 / ARB_clip_control)", ctx.info())));
    };
    // SAFETY: ctx is current on this thread; the calls take no pointers.
    unsafe {
        clip_control(legacy::LOWER_LEFT, legacy::ZERO_TO_ONE);
        (ctx.legacy().provoking_vertex)(legacy::FIRST_VERTEX_CONVENTION);
    }
    let frame = render_plan(ctx, pack, scene, mesh, screen, reference);
    // SAFETY: as above.
    unsafe {
        clip_control(legacy::LOWER_LEFT, legacy::NEGATIVE_ONE_TO_ONE);
        (ctx.legacy().provoking_vertex)(legacy::LAST_VERTEX_CONVENTION);
    }
    frame
}

/// A colour buffer in OpenGL: its two textures, the snapshot gbuffers programs read, its format.
type GlBuffer = ([glow::Texture; 2], glow::Texture, BufferFormat);

/// The format of the texture standing in for the screen (made RGBA32F).
const SCREEN_FORMAT: BufferFormat = BufferFormat::Rgba32F;

/// One frame of the plan in OpenGL: the textures and framebuffer it draws with, the uniform
/// values of each kind of pass, and the programs drawn with OpenGL's own depth range.
struct GlPlanFrame<'a> {
    ctx: &'a GlContext,
    pack: &'a AnyPack,
    scene: &'a Scene,
    w: i32,
    h: i32,
    buffers: BTreeMap<u8, GlBuffer>,
    depth0: glow::Texture,
    depth1: glow::Texture,
    /// Distant Horizons' depth buffers, dhDepthTex0 and dhDepthTex1.
    lod_depth: [glow::Texture; 2],
    shadow_side: i32,
    shadow_depth: [glow::Texture; 2],
    shadow_colours: BTreeMap<u8, (glow::Texture, BufferFormat)>,
    screen: glow::Texture,
    harness: GlHarnessTextures,
    /// The pack's `bufferObject`s, bound at their indices for the whole frame.
    storage: Vec<glow::Buffer>,
    fbo: glow::Framebuffer,
    values: PassValues,
    own_depth_mapping: Vec<String>,
    /// Wall time of the current step's draws and copies so far, in ms.
    step_ms: f64,
    /// [`Reference::nudge`]: the shaders' float literals are moved by it too.
    nudge: f64,
    /// [`Reference::trace_derivatives`].
    trace_derivatives: bool,
    /// Whether the current step's program was drawn traced.
    step_traced: bool,
    /// [`GlFrame::rewrites`].
    rewrites: Vec<String>,
}

/// The largest `bufferObject` the harness makes, in bytes (1 GiB): a larger one is refused
/// rather than taken from a machine other work shares.
const MAX_BUFFER_OBJECT_BYTES: u64 = 1 << 30;

fn render_plan(
    ctx: &GlContext,
    pack: &AnyPack,
    scene: &Scene,
    mesh: &SceneMesh,
    screen: ScreenOutput,
    reference: Option<&Reference>,
) -> Result<GlFrame, HarnessError> {
    let plan = FramePlan::new(pack, scene, mesh, screen);
    if let Some(reference) = reference
        && reference.steps.len() != plan.steps.len()
    {
        return Err(HarnessError::Gl(format!("the reference frame ran {} steps, the OpenGL frame has {}", reference.steps.len(), plan.steps.len())));
    }
    // SAFETY: every call is on the context current on this thread, with objects it made.
    unsafe {
        let nudge = reference.map_or(0.0, |r| r.nudge);
        let mut frame = GlPlanFrame::new(ctx, pack, scene, &plan, nudge)?;
        frame.trace_derivatives = reference.is_some_and(|r| r.trace_derivatives);
        let mut traced = Vec::new();
        frame.clear()?;
        let quad: Vec<PackVertex> = mesh::fullscreen_quad().iter().map(|v| v.nudged(nudge as f32)).collect();
        let mut steps = Vec::new();
        let mut step_ms = Vec::new();
        let mut depth_written = Vec::new();
        // The textures the step before wrote, by name.
        let mut last_written: Vec<(String, glow::Texture)> = Vec::new();
        for (index, step) in plan.steps.iter().enumerate() {
            if let Some(reference) = reference {
                if index > 0 {
                    frame.seed(&last_written, reference.steps[index - 1])?;
                }
                match plan.depth_seed(index) {
                    Some(DepthSeed::AsEnded) => frame.seed_depth(reference.depth0, reference.depth1),
                    Some(DepthSeed::OpaqueOnly) => frame.seed_depth(reference.depth1, reference.depth1),
                    None => {}
                }
            }
            frame.step_ms = 0.0;
            frame.step_traced = false;
            let written = match &step.work {
                PlannedWork::Geometry { program, vertices, default_blend, depth_write, current, snapshots, sprites, pass, draw } => {
                    let draw = GeometryStep { program: *program, vertices, default_blend, depth_write: *depth_write, sprites: *sprites, pass: *pass, draw: *draw };
                    frame.geometry(&draw, current, snapshots)?
                }
                PlannedWork::DepthCopy => {
                    frame.copy(frame.depth0, frame.depth1, frame.w, frame.h);
                    Vec::new()
                }
                PlannedWork::LodDepthCopy => {
                    frame.copy(frame.lod_depth[0], frame.lod_depth[1], frame.w, frame.h);
                    Vec::new()
                }
                PlannedWork::ShadowGeometry { program, vertices, draw } => frame.shadow_geometry(program, vertices, *draw)?,
                PlannedWork::ShadowDepthCopy => {
                    frame.copy(frame.shadow_depth[0], frame.shadow_depth[1], frame.shadow_side, frame.shadow_side);
                    Vec::new()
                }
                PlannedWork::Fullscreen { program, current, into_screen, mipmaps } => frame.fullscreen(program, current, *into_screen, mipmaps, &quad)?,
                PlannedWork::ScreenCopy { current } => frame.screen_copy(*current)?,
                PlannedWork::Compute { stage, current } => frame.compute(stage, current)?,
                PlannedWork::ShadowComposite { program, current } => frame.shadow_composite(program, current, &quad)?,
            };
            last_written = written.iter().map(|w| (w.name.clone(), w.texture)).collect();
            steps.push((step.label.clone(), written.into_iter().map(|w| (w.name, w.image)).collect()));
            step_ms.push(frame.step_ms);
            traced.push(frame.step_traced);
            depth_written.push(frame.depth_written(&step.work)?);
        }
        frame.finish(steps, depth_written, step_ms, traced, &plan.current)
    }
}

/// A texture a step wrote, and what it holds after the step.
struct Written {
    name: String,
    texture: glow::Texture,
    image: FloatImage,
}

/// A geometry step of the plan, as drawn in OpenGL.
struct GeometryStep<'s> {
    program: Option<&'s LoadedProgram>,
    vertices: &'s [PackVertex],
    default_blend: &'s Blend,
    depth_write: bool,
    sprites: Sprites,
    pass: Pass,
    draw: DrawUniforms,
}

impl<'a> GlPlanFrame<'a> {
    /// The frame's textures, as the wgpu path makes them.
    unsafe fn new(ctx: &'a GlContext, pack: &'a AnyPack, scene: &'a Scene, plan: &FramePlan, nudge: f64) -> Result<GlPlanFrame<'a>, HarnessError> {
        let gl = ctx.gl();
        let (w, h) = (scene.width() as i32, scene.height() as i32);
        unsafe {
            // Integer buffers are never filtered: a linear filter leaves them incomplete.
            let colour = |format: BufferFormat| {
                let (pixels, ty) = pixel_transfer(format);
                make_texture(gl, internal_format(format), pixels, ty, w, h, None, !format.is_integer(), false)
            };
            let mut buffers = BTreeMap::new();
            for &b in &plan.buffers {
                let format = pack.format_of(b);
                let flipped = [colour(format)?, colour(format)?];
                if plan.mipmapped.contains(&b) && !format.is_integer() {
                    for t in flipped {
                        add_mip_levels(gl, t, internal_format(format), w, h);
                    }
                }
                buffers.insert(b, (flipped, colour(format)?, format));
            }
            let depth_of =
                |width: i32, height: i32| make_texture(gl, glow::DEPTH_COMPONENT32F, glow::DEPTH_COMPONENT, glow::FLOAT, width, height, None, false, false);
            // The shadow maps, as the wgpu path makes them: one texel each without a shadow pass.
            let shadow_side = if pack.shadow_pass { pack.shadow_settings.drawn_resolution().0 as i32 } else { 1 };
            let shadow_depth = [depth_of(shadow_side, shadow_side)?, depth_of(shadow_side, shadow_side)?];
            for t in shadow_depth {
                read_as_shadow_map(gl, t, pack.shadow_settings.nearest);
            }
            let mut shadow_colours = BTreeMap::new();
            for &b in &plan.shadow_buffers {
                let format = pack.shadow_format_of(b);
                let (pixels, ty) = pixel_transfer(format);
                let texture = make_texture(gl, internal_format(format), pixels, ty, shadow_side, shadow_side, None, !format.is_integer(), false)?;
                shadow_colours.insert(b, (texture, format));
            }
            let fbo = gl.create_framebuffer().map_err(|e| HarnessError::Gl(format!("framebuffer: {e}")))?;
            let values = PassValues::of(pack, scene).0.nudged(nudge);
            let mut storage = Vec::new();
            for buffer in &pack.buffer_objects {
                let bytes = buffer.bytes(w as u32, h as u32);
                if bytes > MAX_BUFFER_OBJECT_BYTES {
                    return Err(HarnessError::Unsupported(format!(
                        "shaders.properties:{}: bufferObject.{}: {bytes} bytes, more than the {MAX_BUFFER_OBJECT_BYTES} the harness gives a buffer",
                        buffer.line, buffer.index
                    )));
                }
                let made = gl.create_buffer().map_err(|e| HarnessError::Gl(format!("buffer: {e}")))?;
                gl.bind_buffer(glow::SHADER_STORAGE_BUFFER, Some(made));
                gl.buffer_data_u8_slice(glow::SHADER_STORAGE_BUFFER, &vec![0u8; bytes.max(4) as usize], glow::DYNAMIC_COPY);
                gl.bind_buffer_base(glow::SHADER_STORAGE_BUFFER, buffer.index, Some(made));
                storage.push(made);
            }
            gl.bind_buffer(glow::SHADER_STORAGE_BUFFER, None);
            Ok(GlPlanFrame {
                ctx,
                pack,
                scene,
                w,
                h,
                buffers,
                depth0: depth_of(w, h)?,
                depth1: depth_of(w, h)?,
                lod_depth: [depth_of(w, h)?, depth_of(w, h)?],
                shadow_side,
                shadow_depth,
                shadow_colours,
                screen: make_texture(gl, internal_format(SCREEN_FORMAT), glow::RGBA, glow::FLOAT, w, h, None, false, false)?,
                harness: GlHarnessTextures::new(ctx, pack, w as u32, h as u32)?,
                storage,
                fbo,
                values,
                own_depth_mapping: Vec::new(),
                step_ms: 0.0,
                nudge,
                trace_derivatives: false,
                step_traced: false,
                rewrites: Vec::new(),
            })
        }
    }

    /// Clears as the wgpu path does: both textures of each buffer, depth to 1, the shadow maps.
    unsafe fn clear(&self) -> Result<(), HarnessError> {
        let gl = self.ctx.gl();
        unsafe {
            gl.bind_framebuffer(glow::FRAMEBUFFER, Some(self.fbo));
            gl.viewport(0, 0, self.w, self.h);
            for (b, (textures, _, format)) in &self.buffers {
                let c = self.pack.clear_of(*b).colour(*b, self.scene.sky.fog_color);
                for t in textures {
                    attach(gl, &[Some(*t)], Some(self.depth0))?;
                    clear_colour(gl, *format, c);
                }
            }
            gl.depth_mask(true);
            gl.clear_buffer_f32_slice(glow::DEPTH, 0, &[1.0]);
            attach(gl, &[], Some(self.lod_depth[0]))?;
            gl.clear_buffer_f32_slice(glow::DEPTH, 0, &[1.0]);
            for (b, (t, format)) in &self.shadow_colours {
                attach(gl, &[Some(*t)], Some(self.shadow_depth[0]))?;
                clear_colour(gl, *format, self.pack.shadow_clear_of(*b).shadow_colour());
            }
            for depth in self.shadow_depth {
                attach(gl, &[], Some(depth))?;
                gl.clear_buffer_f32_slice(glow::DEPTH, 0, &[1.0]);
            }
            gl.disable(glow::CULL_FACE);
            gl.depth_func(glow::LEQUAL);
        }
        Ok(())
    }

    /// Each texture in `written` overwritten with the reference's image of the same name
    /// (see [`render_from`]); its mipmaps are made again by the step that reads them.
    unsafe fn seed(&self, written: &[(String, glow::Texture)], reference: &[(String, FloatImage)]) -> Result<(), HarnessError> {
        for (name, texture) in written {
            let Some((_, image)) = reference.iter().find(|(n, _)| n == name) else {
                return Err(HarnessError::Gl(format!("the reference frame has no {name} where the OpenGL frame wrote it")));
            };
            // SAFETY: the texture is this frame's, of the image's size (both frames follow one plan).
            unsafe { self.upload(*texture, image, glow::RGBA, bytemuck::cast_slice(&image.pixels)) };
        }
        Ok(())
    }

    /// depthtex0 and depthtex1 overwritten with the reference's images (see [`render_from`]).
    unsafe fn seed_depth(&self, depth0: &FloatImage, depth1: &FloatImage) {
        for (texture, image) in [(self.depth0, depth0), (self.depth1, depth1)] {
            let depths: Vec<f32> = image.pixels.iter().map(|p| p[0]).collect();
            // SAFETY: the texture is this frame's, of the frame's size, as the image is.
            unsafe { self.upload(texture, image, glow::DEPTH_COMPONENT, bytemuck::cast_slice(&depths)) };
        }
    }

    /// Level 0 of `texture` replaced by `floats` (`format`, one float a channel), of `image`'s size.
    unsafe fn upload(&self, texture: glow::Texture, image: &FloatImage, format: u32, floats: &[u8]) {
        let gl = self.ctx.gl();
        // SAFETY: the caller holds the current context, and `texture` has `image`'s size.
        unsafe {
            gl.bind_texture(glow::TEXTURE_2D, Some(texture));
            gl.tex_sub_image_2d(
                glow::TEXTURE_2D,
                0,
                0,
                0,
                image.width as i32,
                image.height as i32,
                format,
                glow::FLOAT,
                glow::PixelUnpackData::Slice(Some(floats)),
            );
        }
    }

    /// `from` copied into `to` (depth copies).
    unsafe fn copy(&mut self, from: glow::Texture, to: glow::Texture, w: i32, h: i32) {
        let gl = self.ctx.gl();
        // SAFETY: both textures are this frame's.
        self.step_ms += timed(gl, || unsafe { gl.copy_image_sub_data(from, glow::TEXTURE_2D, 0, 0, 0, 0, to, glow::TEXTURE_2D, 0, 0, 0, 0, w, h, 1) });
    }

    /// The depth buffer `work` drew into, read back, when it is a geometry step.
    unsafe fn depth_written(&self, work: &PlannedWork) -> Result<Option<FloatImage>, HarnessError> {
        let (texture, side) = match work {
            PlannedWork::Geometry { pass: Pass::DistantHorizons, .. } => (self.lod_depth[0], None),
            PlannedWork::Geometry { .. } => (self.depth0, None),
            PlannedWork::ShadowGeometry { .. } => (self.shadow_depth[0], Some(self.shadow_side)),
            _ => return Ok(None),
        };
        let gl = self.ctx.gl();
        // SAFETY: the textures are this frame's. The shadow map, of its own size, is attached
        // alone: a framebuffer reads only where all its attachments overlap.
        unsafe {
            match side {
                None => read(gl, texture, Held::Depth, self.screen, self.w, self.h).map(Some),
                Some(side) => {
                    attach(gl, &[], Some(texture))?;
                    let mut depths = vec![0f32; (side * side) as usize];
                    gl.read_pixels(0, 0, side, side, glow::DEPTH_COMPONENT, glow::FLOAT, glow::PixelPackData::Slice(Some(bytemuck::cast_slice_mut(&mut depths))));
                    let mut image = FloatImage::new(side as u32, side as u32);
                    for (px, d) in image.pixels.iter_mut().zip(depths) {
                        *px = [d, d, d, 1.0];
                    }
                    Ok(Some(image))
                }
            }
        }
    }

    unsafe fn read_colour(&self, t: glow::Texture, format: BufferFormat) -> Result<FloatImage, HarnessError> {
        // SAFETY: `t` and the scratch screen are this frame's, of the frame's size.
        unsafe { read(self.ctx.gl(), t, Held::Colour(format), self.screen, self.w, self.h) }
    }


    /// Compiles `program` with the harness's depth mapping where the outputs allow it: the
    /// vertex stage recorded by transform feedback, then a stand-in vertex stage passing its
    /// outputs on, which cannot stand in for interface blocks (the link fails).
    fn build(&mut self, program: &LoadedProgram) -> Result<(Compiled, bool), HarnessError> {
        let nudged;
        let program = if self.nudge == 0.0 {
            program
        } else {
            nudged = program.with_float_literals_nudged(self.nudge);
            &nudged
        };
        match compile(self.ctx, program, DepthMapping::Harness) {
            Ok(c) => Ok((c, false)),
            Err(HarnessError::Unsupported(_)) | Err(HarnessError::Gl(_)) => {
                self.own_depth_mapping.push(program.name.clone());
                Ok((compile(self.ctx, program, DepthMapping::OpenGl)?, true))
            }
            Err(e) => Err(e),
        }
    }

    /// Compiles, draws and deletes `program` with the uniform values of `pass` and the draw's.
    unsafe fn draw(&mut self, program: &LoadedProgram, pass: Pass, draw: DrawUniforms, textures: &Textures, vertices: &[PackVertex]) -> Result<(), HarnessError> {
        let (compiled, own_range) = self.build(program)?;
        let clip_control = self.ctx.legacy().clip_control.filter(|_| own_range);
        let values = draw.applied(self.values.of_pass(pass));
        // SAFETY: the program was compiled on this context; the textures are this frame's.
        let drawn = unsafe {
            if let Some(clip_control) = clip_control {
                clip_control(legacy::LOWER_LEFT, legacy::NEGATIVE_ONE_TO_ONE);
            }
            mask_unwritten(self.ctx.gl(), program, true);
            let mut drawn = Ok(());
            self.step_ms += timed(self.ctx.gl(), || drawn = draw_program(self.ctx, self.pack, program, &compiled, &values, textures, vertices));
            mask_unwritten(self.ctx.gl(), program, false);
            if let Some(clip_control) = clip_control {
                clip_control(legacy::LOWER_LEFT, legacy::ZERO_TO_ONE);
            }
            drawn
        };
        compiled.delete(self.ctx);
        drawn
    }

    /// A gbuffers draw (or the loader's own colour where the chain has no program), after the
    /// buffers it samples are copied to their snapshots.
    unsafe fn geometry(&mut self, step: &GeometryStep, current: &BTreeMap<u8, usize>, snapshots: &BTreeSet<u8>) -> Result<Vec<Written>, HarnessError> {
        let gl = self.ctx.gl();
        let (w, h) = (self.w, self.h);
        unsafe {
            for b in snapshots {
                let (textures, snapshot, _) = &self.buffers[b];
                gl.copy_image_sub_data(textures[current[b]], glow::TEXTURE_2D, 0, 0, 0, 0, *snapshot, glow::TEXTURE_2D, 0, 0, 0, 0, w, h, 1);
            }
            let drawn: Vec<Option<u8>> = match step.program {
                Some(p) => p.render_targets.clone(),
                None => match self.pack.loader.missing_program_draws() {
                    MissingProgramDraws::FirstBufferOnly => vec![Some(0)],
                    MissingProgramDraws::EveryBuffer => self.buffers.keys().copied().map(Some).collect(),
                },
            };
            let targets: Vec<Option<glow::Texture>> = drawn.iter().map(|b| b.map(|b| self.buffers[&b].0[current[&b]])).collect();
            // Distant Horizons draws into its own depth buffer.
            let depth = if step.pass == Pass::DistantHorizons { self.lod_depth[0] } else { self.depth0 };
            attach(gl, &targets, Some(depth))?;
            set_blends(gl, &drawn, &|b| self.pack.blend_of(step.program, b, step.default_blend));
            gl.enable(glow::DEPTH_TEST);
            gl.depth_mask(step.depth_write);
            match step.program {
                Some(program) => {
                    // depthtex0 is the buffer being drawn into: gbuffers programs read depthtex1.
                    let harness = self.harness.clone();
                    let textures = Textures {
                        naming: SamplerNaming::Frame,
                        harness: &harness,
                        colors: self.buffers.iter().map(|(b, (_, snapshot, format))| (*b, (*snapshot, *format))).collect(),
                        depth0: self.depth1,
                        depth1: self.depth1,
                        // Likewise dhDepthTex0 while Distant Horizons draws into it.
                        lod_depth: [self.lod_depth[1]; 2],
                        shadow_depth: self.shadow_depth,
                        shadow_colours: self.shadow_colours.clone(),
                        sprites: step.sprites,
                        mipmapped: BTreeSet::new(),
                    };
                    self.draw(program, step.pass, step.draw, &textures, step.vertices)?;
                }
                None => {
                    let mut drawn = Ok(());
                    let missing = self.pack.loader.missing_program_draws();
                    self.step_ms += timed(gl, || drawn = draw_own_colour(self.ctx, missing, DepthMapping::Harness, self.scene, step.vertices));
                    drawn?
                }
            }
            set_blends(gl, &drawn, &|_| Blend::Off);
            gl.depth_mask(true);
            drawn
                .iter()
                .zip(&targets)
                .filter_map(|(b, t)| Some((b.as_ref()?, t.as_ref()?)))
                .map(|(b, t)| Ok(Written { name: format!("colortex{b}"), texture: *t, image: self.read_colour(*t, self.buffers[b].2)? }))
                .collect()
        }
    }

    /// A shadow program's draw into the shadow map, at the shadow map's size.
    unsafe fn shadow_geometry(&mut self, program: &LoadedProgram, vertices: &[PackVertex], draw: DrawUniforms) -> Result<Vec<Written>, HarnessError> {
        let gl = self.ctx.gl();
        let side = self.shadow_side;
        unsafe {
            let targets: Vec<Option<glow::Texture>> = program.render_targets.iter().map(|b| b.map(|b| self.shadow_colours[&b].0)).collect();
            attach(gl, &targets, Some(self.shadow_depth[0]))?;
            set_blends(gl, &program.render_targets, &|b| self.pack.blend_of(Some(program), b, &Blend::Off));
            gl.enable(glow::DEPTH_TEST);
            gl.depth_mask(true);
            gl.viewport(0, 0, side, side);
            // The shadow maps being drawn read as nothing drawn; the frame's buffers are not bound.
            let harness = self.harness.clone();
            let textures = Textures {
                naming: SamplerNaming::ShadowPass,
                harness: &harness,
                colors: BTreeMap::new(),
                depth0: self.depth1,
                depth1: self.depth1,
                lod_depth: [self.lod_depth[1]; 2],
                shadow_depth: [harness.empty_shadow_depth; 2],
                shadow_colours: BTreeMap::new(),
                sprites: Sprites::Blocks,
                mipmapped: BTreeSet::new(),
            };
            self.draw(program, Pass::Shadow, draw, &textures, vertices)?;
            gl.viewport(0, 0, self.w, self.h);
            set_blends(gl, &program.render_targets, &|_| Blend::Off);
            self.shadow_colours_read(program.drawn_buffers())
        }
    }

    /// The shadow colour buffers `buffers` of the frame, read back.
    unsafe fn shadow_colours_read(&self, buffers: impl Iterator<Item = u8>) -> Result<Vec<Written>, HarnessError> {
        let side = self.shadow_side;
        buffers
            .filter_map(|b| Some((b, *self.shadow_colours.get(&b)?)))
            // SAFETY: the textures are this frame's, on the current context.
            .map(|(b, (texture, format))| Ok(Written { name: format!("shadowcolor{b}"), texture, image: unsafe { read(self.ctx.gl(), texture, Held::Colour(format), self.screen, side, side)? } }))
            .collect()
    }

    /// A shadowcomp program: the full-screen quad at the shadow map's size into the shadow
    /// colour buffers it writes, every shadow colour buffer read from a copy made just before
    /// (what the loaders' flip leaves it to read).
    unsafe fn shadow_composite(&mut self, program: &LoadedProgram, current: &BTreeMap<u8, usize>, quad: &[PackVertex]) -> Result<Vec<Written>, HarnessError> {
        let gl = self.ctx.gl();
        let side = self.shadow_side;
        unsafe {
            let mut before = BTreeMap::new();
            let shadow_colours: Vec<(u8, (glow::Texture, BufferFormat))> = self.shadow_colours.iter().map(|(b, t)| (*b, *t)).collect();
            for (b, (texture, format)) in shadow_colours {
                let (pixels, ty) = pixel_transfer(format);
                let copy = make_texture(gl, internal_format(format), pixels, ty, side, side, None, !format.is_integer(), false)?;
                self.copy(texture, copy, side, side);
                before.insert(b, (copy, format));
            }
            let targets: Vec<Option<glow::Texture>> = program.render_targets.iter().map(|b| b.and_then(|b| self.shadow_colours.get(&b)).map(|t| t.0)).collect();
            attach(gl, &targets, None)?;
            set_blends(gl, &program.render_targets, &|b| self.pack.blend_of(Some(program), b, &Blend::Off));
            gl.disable(glow::DEPTH_TEST);
            gl.viewport(0, 0, side, side);
            let harness = self.harness.clone();
            let textures = Textures { shadow_colours: before.clone(), ..self.frame_textures(&harness, current, BTreeSet::new()) };
            let drawn = self.draw(program, Pass::Fullscreen, DrawUniforms::stage("NONE"), &textures, quad);
            gl.viewport(0, 0, self.w, self.h);
            set_blends(gl, &program.render_targets, &|_| Blend::Off);
            for (copy, _) in before.values() {
                gl.delete_texture(*copy);
            }
            drawn?;
            self.shadow_colours_read(program.drawn_buffers())
        }
    }

    /// A full-screen program drawing into the other texture of each of its targets (or the
    /// screen), its mipmapped buffers' chains made first.
    unsafe fn fullscreen(
        &mut self,
        program: &LoadedProgram,
        current: &BTreeMap<u8, usize>,
        into_screen: bool,
        mipmaps: &BTreeSet<u8>,
        quad: &[PackVertex],
    ) -> Result<Vec<Written>, HarnessError> {
        let gl = self.ctx.gl();
        // Only the colour buffers read with their mipmaps have levels to pick: every other
        // texture the harness binds has one level and one filter for both ways, so lookups in
        // it read alike whatever the derivatives.
        let stage = ProgramStage::of(&program.name);
        let level_free = |name: &str| !matches!(crate::samplers::resolve_any(self.pack, name, stage), Ok(Source::Color(n)) if mipmaps.contains(&n));
        let traced = if self.trace_derivatives { program.with_derivative_trace(level_free) } else { None };
        self.step_traced = traced.is_some();
        let program = traced.as_ref().unwrap_or(program);
        unsafe {
            // Integer buffers have no mip chain (OpenGL makes none for them).
            for b in mipmaps.iter().filter(|b| !self.buffers[b].2.is_integer()) {
                gl.bind_texture(glow::TEXTURE_2D, Some(self.buffers[b].0[current[b]]));
                gl.generate_mipmap(glow::TEXTURE_2D);
            }
            let targets: Vec<Option<(String, glow::Texture, BufferFormat)>> = program
                .render_targets
                .iter()
                .map(|b| match (into_screen, (*b)?) {
                    (true, 0) => Some(("screen".to_string(), self.screen, SCREEN_FORMAT)),
                    (_, b) => Some((format!("colortex{b}"), self.buffers[&b].0[1 - current[&b]], self.buffers[&b].2)),
                })
                .collect();
            let attachments: Vec<Option<glow::Texture>> = targets.iter().map(|t| t.as_ref().map(|(_, t, _)| *t)).collect();
            attach(gl, &attachments, None)?;
            set_blends(gl, &program.render_targets, &|b| if self.step_traced { Blend::Off } else { self.pack.blend_of(Some(program), b, &Blend::Off) });
            gl.disable(glow::DEPTH_TEST);
            let harness = self.harness.clone();
            let textures = self.frame_textures(&harness, current, mipmaps.clone());
            self.draw(program, Pass::Fullscreen, DrawUniforms::stage("NONE"), &textures, quad)?;
            set_blends(gl, &program.render_targets, &|_| Blend::Off);
            targets.into_iter().flatten().map(|(name, texture, format)| Ok(Written { name, texture, image: self.read_colour(texture, format)? })).collect()
        }
    }

    /// What a full-screen program or compute stage reads: the current texture of each buffer
    /// (`mipmapped`: those read through their mip chains), both depth buffers, the shadow maps.
    fn frame_textures<'h>(&self, harness: &'h GlHarnessTextures, current: &BTreeMap<u8, usize>, mipmapped: BTreeSet<u8>) -> Textures<'h> {
        Textures {
            naming: SamplerNaming::Frame,
            harness,
            colors: self.buffers.iter().map(|(b, (textures, _, format))| (*b, (textures[current[b]], *format))).collect(),
            depth0: self.depth0,
            depth1: self.depth1,
            lod_depth: self.lod_depth,
            shadow_depth: self.shadow_depth,
            shadow_colours: self.shadow_colours.clone(),
            sprites: Sprites::Blocks,
            mipmapped,
        }
    }

    /// A compute stage dispatched over the frame: what it writes through its images is the
    /// current texture of each buffer it names, and each shadow colour buffer it names.
    unsafe fn compute(&mut self, stage: &ComputeStage, current: &BTreeMap<u8, usize>) -> Result<Vec<Written>, HarnessError> {
        let harness = self.harness.clone();
        let textures = self.frame_textures(&harness, current, BTreeSet::new());
        // SAFETY: the textures are this frame's, on the current context.
        unsafe {
            let reserved: Vec<u32> = self.pack.buffer_objects.iter().map(|b| b.index).collect();
            let dispatched = dispatch_compute(self.ctx, self.pack, stage, self.values.of_pass(Pass::Fullscreen), &textures, &reserved, self.w as u32, self.h as u32)?;
            self.step_ms += dispatched.ms;
            self.rewrites.extend(dispatched.rewrite.filter(|r| !self.rewrites.contains(r)));
            let mut written: Vec<Written> = stage
                .images
                .iter()
                .filter_map(|b| self.buffers.get(b).map(|(textures, _, format)| (*b, textures[current[b]], *format)))
                .map(|(b, texture, format)| Ok(Written { name: format!("colortex{b}"), texture, image: self.read_colour(texture, format)? }))
                .collect::<Result<_, HarnessError>>()?;
            written.extend(self.shadow_colours_read(stage.shadow_images.iter().copied())?);
            Ok(written)
        }
    }

    /// colortex0's current texture blitted to the screen, for a pack without final.
    unsafe fn screen_copy(&self, current: usize) -> Result<Vec<Written>, HarnessError> {
        let gl = self.ctx.gl();
        let (w, h) = (self.w, self.h);
        unsafe {
            let read_fbo = gl.create_framebuffer().map_err(|e| HarnessError::Gl(format!("framebuffer: {e}")))?;
            gl.bind_framebuffer(glow::READ_FRAMEBUFFER, Some(read_fbo));
            gl.framebuffer_texture_2d(glow::READ_FRAMEBUFFER, glow::COLOR_ATTACHMENT0, glow::TEXTURE_2D, Some(self.buffers[&0].0[current]), 0);
            gl.bind_framebuffer(glow::DRAW_FRAMEBUFFER, Some(self.fbo));
            attach(gl, &[Some(self.screen)], None)?;
            gl.blit_framebuffer(0, 0, w, h, 0, 0, w, h, glow::COLOR_BUFFER_BIT, glow::NEAREST);
            gl.bind_framebuffer(glow::FRAMEBUFFER, Some(self.fbo));
            gl.delete_framebuffer(read_fbo);
            Ok(vec![Written { name: "screen".to_string(), texture: self.screen, image: self.read_colour(self.screen, SCREEN_FORMAT)? }])
        }
    }

    /// The screen read back, every object deleted, and the driver's error state checked.
    unsafe fn finish(
        self,
        steps: Vec<(String, Vec<(String, FloatImage)>)>,
        depth_written: Vec<Option<FloatImage>>,
        step_ms: Vec<f64>,
        traced: Vec<bool>,
        current: &BTreeMap<u8, usize>,
    ) -> Result<GlFrame, HarnessError> {
        let gl = self.ctx.gl();
        unsafe {
            gl.finish();
            let image = self.read_colour(self.screen, SCREEN_FORMAT)?;
            let passthrough_ms = match self.buffers.get(&0) {
                Some((textures, _, _)) => self.time_passthrough(textures[current[&0]])?,
                None => f64::NAN,
            };
            let mut buffers = BTreeMap::new();
            for (b, (textures, _, format)) in &self.buffers {
                buffers.insert(*b, self.read_colour(textures[current[b]], *format)?);
            }
            let depth0 = read(gl, self.depth0, Held::Depth, self.screen, self.w, self.h)?;
            let depth1 = read(gl, self.depth1, Held::Depth, self.screen, self.w, self.h)?;
            let error = gl.get_error();
            gl.bind_framebuffer(glow::FRAMEBUFFER, None);
            gl.delete_framebuffer(self.fbo);
            self.harness.delete(gl);
            for buffer in self.storage {
                gl.delete_buffer(buffer);
            }
            let shadow_textures = self.shadow_depth.into_iter().chain(self.shadow_colours.values().map(|(t, _)| *t));
            let buffer_textures = self.buffers.values().flat_map(|(t, s, _)| [t[0], t[1], *s]);
            for t in [self.depth0, self.depth1, self.lod_depth[0], self.lod_depth[1], self.screen].into_iter().chain(buffer_textures).chain(shadow_textures) {
                gl.delete_texture(t);
            }
            if error != glow::NO_ERROR {
                return Err(HarnessError::Gl(format!("the driver reported error 0x{error:x} during the frame")));
            }
            Ok(GlFrame { image, buffers, depth0, depth1, steps, depth_written, own_depth_mapping: self.own_depth_mapping, step_ms, traced, passthrough_ms, rewrites: self.rewrites })
        }
    }

    /// The one-tap pass-through of `colour` into the scratch screen, timed as a step's draws
    /// are: the median of five draws after one that lets llvmpipe compile it.
    unsafe fn time_passthrough(&self, colour: glow::Texture) -> Result<f64, HarnessError> {
        const VERTEX: &str = "#version 330 core\nvoid main() {\n    vec2 corner = vec2(gl_VertexID & 1, gl_VertexID >> 1) * 4.0 - 1.0;\n    gl_Position = vec4(corner, 0.0, 1.0);\n}\n";
        const FRAGMENT: &str = "#version 330 core\nuniform sampler2D colortex0;\nout vec4 color;\nvoid main() {\n    color = texelFetch(colortex0, ivec2(gl_FragCoord.xy), 0);\n}\n";
        let program = self.ctx.compile_program(VERTEX, None, FRAGMENT, &[], &[("color", 0)]).map_err(|e| HarnessError::Gl(format!("the pass-through: {e}")))?;
        let gl = self.ctx.gl();
        // SAFETY: the program, the textures and the framebuffer are this context's.
        let samples = unsafe {
            let vertex_array = gl.create_vertex_array().map_err(|e| HarnessError::Gl(format!("vertex array: {e}")))?;
            gl.bind_vertex_array(Some(vertex_array));
            gl.bind_framebuffer(glow::FRAMEBUFFER, Some(self.fbo));
            attach(gl, &[Some(self.screen)], None)?;
            gl.disable(glow::DEPTH_TEST);
            gl.disable(glow::BLEND);
            gl.use_program(Some(program.raw));
            gl.active_texture(glow::TEXTURE0);
            gl.bind_texture(glow::TEXTURE_2D, Some(colour));
            let location = gl.get_uniform_location(program.raw, "colortex0");
            gl.uniform_1_i32(location.as_ref(), 0);
            let samples: Vec<f64> = (0..6).map(|_| timed(gl, || gl.draw_arrays(glow::TRIANGLES, 0, 3))).skip(1).collect();
            gl.use_program(None);
            gl.bind_vertex_array(None);
            gl.delete_vertex_array(vertex_array);
            samples
        };
        self.ctx.delete_program(program);
        Ok(crate::images::median(&samples))
    }
}

/// Wall time of `work` between two `glFinish`, in ms.
pub(crate) fn timed(gl: &glow::Context, work: impl FnOnce()) -> f64 {
    // SAFETY: glFinish takes no arguments; the caller holds the current context.
    unsafe { gl.finish() };
    let start = std::time::Instant::now();
    work();
    // SAFETY: as above.
    unsafe { gl.finish() };
    start.elapsed().as_secs_f64() * 1000.0
}
