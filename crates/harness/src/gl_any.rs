//! Any pack's frame ([`crate::any_pack::FramePlan`]) through Mesa's OpenGL, the shipped text
//! as the driver compiles it, step by step as [`crate::gpu::any_frame`] runs it with wgpu, so
//! the two can be compared texture by texture after every step.
//!
//! Depth is mapped as the wgpu path maps it ([`DepthMapping::Harness`]) for every program
//! whose vertex outputs transform feedback can record (floats, perspective); a program with
//! other outputs (`flat` integers) is linked as shipped and drawn with OpenGL's own depth
//! range, which equals the wgpu mapping up to the last bits. Those programs are named in
//! [`GlAnyFrame::own_depth_mapping`].

use std::collections::{BTreeMap, BTreeSet};

use tidepack_gldriver::glow::{self, HasContext as _};
use tidepack_gldriver::{GlContext, legacy};

use crate::HarnessError;
use crate::any_pack::{AnyPack, FramePlan, PlannedWork};
use crate::gl::{
    Compiled, DepthMapping, GlHarnessTextures, Textures, attach, compile, draw_own_colour, draw_program, internal_format, make_texture, read,
    add_mip_levels, read_as_shadow_map, set_blends,
};
use crate::gpu::bindings::SamplerNaming;
use crate::gpu::fullscreen_quad;
use crate::images::FloatImage;
use crate::mesh::{PackVertex, SceneMesh, Sprites};
use crate::program::{LoadedProgram, PackResources};
use tidepack_loader::buffers::BufferFormat;
use tidepack_loader::directives::Blend;
use crate::scene::Scene;
use crate::uniforms::{self, Pass};

/// A frame of any pack from the OpenGL driver.
#[derive(Clone, Debug)]
pub struct GlAnyFrame {
    pub image: FloatImage,
    /// Per step, in plan order: the textures it wrote, named as the wgpu path names them.
    pub steps: Vec<(String, Vec<(String, FloatImage)>)>,
    /// Programs drawn with OpenGL's depth range (see the module doc).
    pub own_depth_mapping: Vec<String>,
}

/// Renders `scene` with any pack's shipped text through OpenGL.
pub fn render_any(ctx: &GlContext, pack: &AnyPack, scene: &Scene, mesh: &SceneMesh) -> Result<GlAnyFrame, HarnessError> {
    let Some(clip_control) = ctx.legacy().clip_control else {
        return Err(HarnessError::Gl(format!("{} has no glClipControl (OpenGL 4.5 / ARB_clip_control)", ctx.info())));
    };
    // SAFETY: ctx is current on this thread; the calls take no pointers.
    unsafe {
        clip_control(legacy::LOWER_LEFT, legacy::ZERO_TO_ONE);
        (ctx.legacy().provoking_vertex)(legacy::FIRST_VERTEX_CONVENTION);
    }
    let frame = render_plan(ctx, pack, scene, mesh);
    // SAFETY: as above.
    unsafe {
        clip_control(legacy::LOWER_LEFT, legacy::NEGATIVE_ONE_TO_ONE);
        (ctx.legacy().provoking_vertex)(legacy::LAST_VERTEX_CONVENTION);
    }
    frame
}

fn render_plan(ctx: &GlContext, pack: &AnyPack, scene: &Scene, mesh: &SceneMesh) -> Result<GlAnyFrame, HarnessError> {
    let gl = ctx.gl();
    let lg = ctx.legacy();
    let plan = FramePlan::new(pack, scene, mesh);
    let (w, h) = (scene.width() as i32, scene.height() as i32);
    // SAFETY: every call below is on the context current on this thread, with objects it made.
    unsafe {
        let colour = |format| make_texture(gl, internal_format(format), glow::RGBA, glow::FLOAT, w, h, None, true, false);
        let mut buffers = BTreeMap::new();
        for &b in &plan.buffers {
            let format = pack.format_of(b);
            let flipped = [colour(format)?, colour(format)?];
            if plan.mipmapped.contains(&b) {
                for t in flipped {
                    add_mip_levels(gl, t, internal_format(format), w, h);
                }
            }
            buffers.insert(b, (flipped, colour(format)?, format));
        }
        let depth_of =
            |width: i32, height: i32| make_texture(gl, glow::DEPTH_COMPONENT32F, glow::DEPTH_COMPONENT, glow::FLOAT, width, height, None, false, false);
        let (depth0, depth1) = (depth_of(w, h)?, depth_of(w, h)?);
        // The shadow maps, as the wgpu path makes them: one texel each without a shadow pass.
        let shadow_side = if pack.shadow_pass { pack.shadow_settings.drawn_resolution().0 as i32 } else { 1 };
        let shadow_depth = [depth_of(shadow_side, shadow_side)?, depth_of(shadow_side, shadow_side)?];
        for t in shadow_depth {
            read_as_shadow_map(gl, t, pack.shadow_settings.nearest);
        }
        let mut shadow_colours = BTreeMap::new();
        for &b in &plan.shadow_buffers {
            let format = internal_format(pack.shadow_format_of(b));
            shadow_colours.insert(b, make_texture(gl, format, glow::RGBA, glow::FLOAT, shadow_side, shadow_side, None, true, false)?);
        }
        let screen = make_texture(gl, glow::RGBA32F, glow::RGBA, glow::FLOAT, w, h, None, false, false)?;
        let harness = GlHarnessTextures::new(gl, pack)?;
        let fbo = gl.create_framebuffer().map_err(|e| HarnessError::Gl(format!("framebuffer: {e}")))?;
        gl.bind_framebuffer(glow::FRAMEBUFFER, Some(fbo));
        gl.viewport(0, 0, w, h);

        // Clear, as the wgpu path does: both textures of each buffer, depth to 1.
        for (b, (textures, _, _)) in &buffers {
            let c = pack.clear_of(*b).colour(*b, scene.sky.fog_color).map(|v| v as f32);
            for t in textures {
                attach(gl, &[*t], Some(depth0))?;
                gl.clear_buffer_f32_slice(glow::COLOR, 0, &c);
            }
        }
        gl.depth_mask(true);
        gl.clear_buffer_f32_slice(glow::DEPTH, 0, &[1.0]);
        for (b, t) in &shadow_colours {
            attach(gl, &[*t], Some(shadow_depth[0]))?;
            gl.clear_buffer_f32_slice(glow::COLOR, 0, &pack.shadow_clear_of(*b).shadow_colour().map(|v| v as f32));
        }
        for depth in shadow_depth {
            attach(gl, &[], Some(depth))?;
            gl.clear_buffer_f32_slice(glow::DEPTH, 0, &[1.0]);
        }
        gl.disable(glow::CULL_FACE);
        gl.depth_func(glow::LEQUAL);

        let read_colour = |t: glow::Texture| read(gl, t, false, screen, w, h);
        let mut steps = Vec::new();
        let mut own_depth_mapping = Vec::new();
        // Compiles with the harness's depth mapping where the outputs allow it.
        let mut build = |program: &LoadedProgram| -> Result<(Compiled, bool), HarnessError> {
            match compile(ctx, program, DepthMapping::Harness) {
                Ok(c) => Ok((c, false)),
                Err(HarnessError::Unsupported(_)) => {
                    own_depth_mapping.push(program.name.clone());
                    Ok((compile(ctx, program, DepthMapping::OpenGl)?, true))
                }
                Err(e) => Err(e),
            }
        };
        let (gbuffers_values, _) = pack.uniform_values(scene, Pass::Gbuffers);
        let (fullscreen_values, _) = pack.uniform_values(scene, Pass::Fullscreen);
        let (shadow_values, _) = pack.uniform_values(scene, Pass::Shadow);
        let (celestial_values, _) = pack.uniform_values(scene, Pass::Celestial);
        // `render_stage`: the `MC_RENDER_STAGE_*` of the draw.
        let draw = |program: &LoadedProgram, compiled: &Compiled, own_range: bool, pass: Pass, render_stage: &str, textures: &Textures, vertices: &[PackVertex]| {
            if own_range && let Some(clip_control) = lg.clip_control {
                clip_control(legacy::LOWER_LEFT, legacy::NEGATIVE_ONE_TO_ONE);
            }
            let values = match pass {
                Pass::Gbuffers => &gbuffers_values,
                Pass::Fullscreen => &fullscreen_values,
                Pass::Shadow => &shadow_values,
                Pass::Celestial => &celestial_values,
            };
            let values = uniforms::with_render_stage(values, render_stage);
            let drawn = draw_program(ctx, pack, program, compiled, pass, &values, textures, vertices);
            if own_range && let Some(clip_control) = lg.clip_control {
                clip_control(legacy::LOWER_LEFT, legacy::ZERO_TO_ONE);
            }
            drawn
        };
        let colors_at = |current: &BTreeMap<u8, usize>| -> BTreeMap<u8, (glow::Texture, BufferFormat)> {
            buffers.iter().map(|(b, (textures, _, format))| (*b, (textures[current[b]], *format))).collect()
        };
        let snapshots: BTreeMap<u8, (glow::Texture, BufferFormat)> =
            buffers.iter().map(|(b, (_, snapshot, format))| (*b, (*snapshot, *format))).collect();

        let quad = fullscreen_quad();
        for step in &plan.steps {
            let mut written = Vec::new();
            match &step.work {
                PlannedWork::Geometry { program, vertices, default_blend, depth_write, current, snapshots: read_buffers, sprites, pass, render_stage } => {
                    for b in read_buffers {
                        let (textures, snapshot, _) = &buffers[b];
                        gl.copy_image_sub_data(textures[current[b]], glow::TEXTURE_2D, 0, 0, 0, 0, *snapshot, glow::TEXTURE_2D, 0, 0, 0, 0, w, h, 1);
                    }
                    let drawn: Vec<u8> = match program {
                        Some(p) => p.render_targets.clone(),
                        None => match pack.loader.missing_program_draws() {
                            tidepack_loader::loader::MissingProgramDraws::FirstBufferOnly => vec![0],
                            tidepack_loader::loader::MissingProgramDraws::EveryBuffer => buffers.keys().copied().collect(),
                        },
                    };
                    let targets: Vec<glow::Texture> = drawn.iter().map(|b| buffers[b].0[current[b]]).collect();
                    attach(gl, &targets, Some(depth0))?;
                    set_blends(gl, &drawn, &|b| pack.blend_of(*program, b, default_blend));
                    gl.enable(glow::DEPTH_TEST);
                    gl.depth_mask(*depth_write);
                    match program {
                        Some(program) => {
                            // depthtex0 is the buffer being drawn into: gbuffers programs read depthtex1.
                            let textures = Textures {
                                naming: SamplerNaming::AnyPack,
                                harness: &harness,
                                colors: snapshots.clone(),
                                depth0: depth1,
                                depth1,
                                shadow_depth,
                                shadow_colours: shadow_colours.clone(),
                                sprites: *sprites,
                                mipmapped: BTreeSet::new(),
                            };
                            let (compiled, own_range) = build(program)?;
                            draw(program, &compiled, own_range, *pass, render_stage, &textures, vertices)?;
                            compiled.delete(ctx);
                        }
                        None => draw_own_colour(ctx, pack.loader.missing_program_draws(), DepthMapping::Harness, scene, vertices)?,
                    }
                    set_blends(gl, &drawn, &|_| Blend::Off);
                    gl.depth_mask(true);
                    for (b, t) in drawn.iter().zip(&targets) {
                        written.push((format!("colortex{b}"), read_colour(*t)?));
                    }
                }
                PlannedWork::DepthCopy => {
                    gl.copy_image_sub_data(depth0, glow::TEXTURE_2D, 0, 0, 0, 0, depth1, glow::TEXTURE_2D, 0, 0, 0, 0, w, h, 1);
                }
                PlannedWork::ShadowGeometry { program, vertices, render_stage } => {
                    let targets: Vec<glow::Texture> = program.render_targets.iter().map(|b| shadow_colours[b]).collect();
                    attach(gl, &targets, Some(shadow_depth[0]))?;
                    set_blends(gl, &program.render_targets, &|b| pack.blend_of(Some(program), b, &Blend::Off));
                    gl.enable(glow::DEPTH_TEST);
                    gl.depth_mask(true);
                    gl.viewport(0, 0, shadow_side, shadow_side);
                    // The shadow maps being drawn read as nothing drawn; the frame's buffers are not bound.
                    let textures = Textures {
                        naming: SamplerNaming::ShadowPass,
                        harness: &harness,
                        colors: BTreeMap::new(),
                        depth0: depth1,
                        depth1,
                        shadow_depth: [harness.empty_shadow_depth; 2],
                        shadow_colours: BTreeMap::new(),
                        sprites: Sprites::Blocks,
                        mipmapped: BTreeSet::new(),
                    };
                    let (compiled, own_range) = build(program)?;
                    draw(program, &compiled, own_range, Pass::Shadow, render_stage, &textures, vertices)?;
                    compiled.delete(ctx);
                    gl.viewport(0, 0, w, h);
                    set_blends(gl, &program.render_targets, &|_| Blend::Off);
                    for (b, t) in program.render_targets.iter().zip(&targets) {
                        written.push((format!("shadowcolor{b}"), read(gl, *t, false, screen, shadow_side, shadow_side)?));
                    }
                }
                PlannedWork::ShadowDepthCopy => {
                    let [from, to] = shadow_depth;
                    gl.copy_image_sub_data(from, glow::TEXTURE_2D, 0, 0, 0, 0, to, glow::TEXTURE_2D, 0, 0, 0, 0, shadow_side, shadow_side, 1);
                }
                PlannedWork::Fullscreen { program, current, into_screen, mipmaps } => {
                    for b in mipmaps {
                        gl.bind_texture(glow::TEXTURE_2D, Some(buffers[b].0[current[b]]));
                        gl.generate_mipmap(glow::TEXTURE_2D);
                    }
                    let targets: Vec<(String, glow::Texture)> = if *into_screen {
                        vec![("screen".to_string(), screen)]
                    } else {
                        program.render_targets.iter().map(|b| (format!("colortex{b}"), buffers[b].0[1 - current[b]])).collect()
                    };
                    let attachments: Vec<glow::Texture> = targets.iter().map(|(_, t)| *t).collect();
                    attach(gl, &attachments, None)?;
                    set_blends(gl, &program.render_targets, &|b| pack.blend_of(Some(program), b, &Blend::Off));
                    gl.disable(glow::DEPTH_TEST);
                    let textures = Textures {
                        naming: SamplerNaming::AnyPack,
                        harness: &harness,
                        colors: colors_at(current),
                        depth0,
                        depth1,
                        shadow_depth,
                        shadow_colours: shadow_colours.clone(),
                        sprites: Sprites::Blocks,
                        mipmapped: mipmaps.clone(),
                    };
                    let (compiled, own_range) = build(program)?;
                    draw(program, &compiled, own_range, Pass::Fullscreen, "NONE", &textures, &quad)?;
                    compiled.delete(ctx);
                    set_blends(gl, &program.render_targets, &|_| Blend::Off);
                    for (name, t) in targets {
                        written.push((name, read_colour(t)?));
                    }
                }
                PlannedWork::ScreenCopy { current } => {
                    let read_fbo = gl.create_framebuffer().map_err(|e| HarnessError::Gl(format!("framebuffer: {e}")))?;
                    gl.bind_framebuffer(glow::READ_FRAMEBUFFER, Some(read_fbo));
                    gl.framebuffer_texture_2d(glow::READ_FRAMEBUFFER, glow::COLOR_ATTACHMENT0, glow::TEXTURE_2D, Some(buffers[&0].0[*current]), 0);
                    gl.bind_framebuffer(glow::DRAW_FRAMEBUFFER, Some(fbo));
                    attach(gl, &[screen], None)?;
                    gl.blit_framebuffer(0, 0, w, h, 0, 0, w, h, glow::COLOR_BUFFER_BIT, glow::NEAREST);
                    gl.bind_framebuffer(glow::FRAMEBUFFER, Some(fbo));
                    gl.delete_framebuffer(read_fbo);
                    written.push(("screen".to_string(), read_colour(screen)?));
                }
            }
            steps.push((step.label.clone(), written));
        }
        gl.finish();
        let image = read_colour(screen)?;
        let error = gl.get_error();
        gl.bind_framebuffer(glow::FRAMEBUFFER, None);
        gl.delete_framebuffer(fbo);
        harness.delete(gl);
        let shadow_textures = shadow_depth.into_iter().chain(shadow_colours.values().copied());
        for t in [depth0, depth1, screen].into_iter().chain(buffers.values().flat_map(|(t, s, _)| [t[0], t[1], *s])).chain(shadow_textures) {
            gl.delete_texture(t);
        }
        if error != glow::NO_ERROR {
            return Err(HarnessError::Gl(format!("the driver reported error 0x{error:x} during the frame")));
        }
        Ok(GlAnyFrame { image, steps, own_depth_mapping })
    }
}
