//! What drawing through a real OpenGL driver takes, for [`crate::gl_frame`]: the shipped GLSL
//! 120/330 text (includes expanded, as OptiFine hands it to the driver) compiled by Mesa's
//! compatibility context, legacy built-ins fed through the fixed-function API (matrix stacks,
//! client-state arrays), `mc_Entity` bound with glBindAttribLocation, `outColorN` with
//! glBindFragDataLocation; the harness's textures, blend state, read-back. Inputs are identical
//! to the wgpu path: the same mesh, textures, uniform values, blend modes and buffer formats.
//! Buffers are in OpenGL's own orientation (row 0 at the bottom).
//!
//! Depth is mapped as the wgpu path maps it ([`DepthMapping::Harness`], the default): every
//! program's vertex stage runs unchanged and its outputs are recorded bit for bit with transform
//! feedback; a pass-through vertex shader then hands them to the rasteriser with
//! `z' = 0.5 * (z + w)` under `glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)`, which is the
//! statement the wgpu wrapper `main` adds, with Vulkan's first-vertex provoking convention.
//! The fragment stage is the shipped one. With OpenGL's own conventions
//! ([`DepthMapping::OpenGl`]: `z / w * 0.5 + 0.5` in the viewport transform, last provoking
//! vertex) the window depth differs from wgpu's in the last bits in about half the pixels, and
//! composite amplifies that at a few pixels (up to 137/255; see docs/harness.md).

use std::collections::{BTreeMap, BTreeSet};

use tidepack_gldriver::glow::{self, HasContext as _};
use tidepack_gldriver::{GlContext, GlProgram, legacy};

use crate::HarnessError;
use tidepack_glsl::Location;
use crate::samplers::{self, ProgramStage, SamplerNaming, Source};
use crate::images::FloatImage;
use tidepack_loader::loader::MissingProgramDraws;
use tidepack_scene::mesh::{self, AttributeFormat, PackVertex, Sprites, offsets};
use crate::program::{ComputeStage, CustomTexture, LoadedProgram, LoadedStage, PackResources};
use crate::raw_texture::Texels;
use tidepack_loader::buffers::{BufferFormat, ImageOf, buffer_of_image};
use tidepack_loader::directives::ImageSize;
use tidepack_loader::directives::{Blend, BlendFactor, TextureTarget};
use tidepack_scene::scene::Scene;
use crate::uniforms::Value;

/// Opens the headless OpenGL context, or says which Debian packages are missing.
pub fn context() -> Result<GlContext, HarnessError> {
    GlContext::new().map_err(|e| HarnessError::NoGlDriver(e.to_string()))
}

/// How clip-space z becomes window depth.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum DepthMapping {
    /// As the wgpu path does it: `z' = 0.5 * (z + w)` after the vertex stage, then the depth
    /// range [0, 1] (`glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)`), Vulkan's provoking vertex
    /// (`glProvokingVertex(GL_FIRST_VERTEX_CONVENTION)`: llvmpipe sets up a triangle's plane
    /// equations from its provoking vertex, so the convention changes the last bit of the
    /// interpolated depth), and the harness's colour shader summing the matrix product in
    /// wgpu's order. Depth buffers then hold the same bits as wgpu's.
    #[default]
    Harness,
    /// OpenGL's own conventions: the vertex stage's output straight to the rasteriser,
    /// `z / w * 0.5 + 0.5`, last provoking vertex, the colour shader's `mvp * position`.
    OpenGl,
}

/// The harness's colour shader, for geometry the pack has no program for: position and vertex
/// colour.
const COLOUR_VS: &str = "#version 330 compatibility\nuniform mat4 mvp;\nin vec4 position;\nin vec4 color;\nout vec4 vColor;\n\
void main() { gl_Position = mvp * position; vColor = color; }\n";
/// The harness's colour shader with the wgpu path's arithmetic: the statements of
/// `COLOUR_VERTEX_WGSL` in gpu/own.rs less the y flip, and `mvp * position` summed in the order Mesa gives
/// the SPIR-V matrix product naga writes for it (last column first, `mvp * position` in GLSL
/// sums the first column first: the last bits of depth differ in ~4% of the pixels).
const COLOUR_VS_HARNESS: &str = "#version 330 compatibility\nuniform mat4 mvp;\nin vec4 position;\nin vec4 color;\nout vec4 vColor;\n\
void main() {\n\
    vec4 clip = mvp[0] * position.x + (mvp[1] * position.y + (mvp[2] * position.z + mvp[3] * position.w));\n\
    clip.z = 0.5 * (clip.z + clip.w);\n\
    gl_Position = clip;\n\
    vColor = color;\n\
}\n";
const COLOUR_FS: &str = "#version 330 compatibility\nin vec4 vColor;\nout vec4 outColor;\nvoid main() { outColor = vColor; }\n";
/// The colour shader for a loader that draws a pack's missing programs into every draw buffer:
/// `gl_FragColor` goes to every one, as fixed-function output does.
const COLOUR_FS_EVERY_BUFFER: &str = "#version 330 compatibility\nin vec4 vColor;\nvoid main() { gl_FragColor = vColor; }\n";

fn gl_err(what: &str) -> impl Fn(String) -> HarnessError + '_ {
    move |e| HarnessError::Gl(format!("{what}: {e}"))
}

pub(crate) fn internal_format(format: BufferFormat) -> u32 {
    match format {
        BufferFormat::Rgba8 => glow::RGBA8,
        BufferFormat::Rgba16 => glow::RGBA16,
        BufferFormat::Rgba16F => glow::RGBA16F,
        BufferFormat::Rgba32F => glow::RGBA32F,
        BufferFormat::Rgba32Ui => glow::RGBA32UI,
        BufferFormat::Rgba32I => glow::RGBA32I,
    }
}

/// The pixel format and type a buffer of `format` is uploaded and read back in: integer
/// buffers take integers.
pub(crate) fn pixel_transfer(format: BufferFormat) -> (u32, u32) {
    match format {
        BufferFormat::Rgba32Ui => (glow::RGBA_INTEGER, glow::UNSIGNED_INT),
        BufferFormat::Rgba32I => (glow::RGBA_INTEGER, glow::INT),
        _ => (glow::RGBA, glow::FLOAT),
    }
}

fn gl_factor(f: BlendFactor) -> u32 {
    match f {
        BlendFactor::Zero => glow::ZERO,
        BlendFactor::One => glow::ONE,
        BlendFactor::SrcColor => glow::SRC_COLOR,
        BlendFactor::OneMinusSrcColor => glow::ONE_MINUS_SRC_COLOR,
        BlendFactor::DstColor => glow::DST_COLOR,
        BlendFactor::OneMinusDstColor => glow::ONE_MINUS_DST_COLOR,
        BlendFactor::SrcAlpha => glow::SRC_ALPHA,
        BlendFactor::OneMinusSrcAlpha => glow::ONE_MINUS_SRC_ALPHA,
        BlendFactor::DstAlpha => glow::DST_ALPHA,
        BlendFactor::OneMinusDstAlpha => glow::ONE_MINUS_DST_ALPHA,
    }
}

/// The harness's own textures in OpenGL, as [`crate::gpu::bindings::HarnessTextures`] has them
/// for wgpu. A copy names the same textures.
#[derive(Clone)]
pub(crate) struct GlHarnessTextures {
    atlas: glow::Texture,
    sun: glow::Texture,
    moon: glow::Texture,
    lightmap: glow::Texture,
    noise: glow::Texture,
    /// Per custom texture of the pack: the texture and its target.
    custom: Vec<(glow::Texture, u32)>,
    flat_normals: glow::Texture,
    no_specular: glow::Texture,
    /// What a shadow colour buffer the frame lacks reads: the white of its clear.
    white: glow::Texture,
    /// A shadow map nothing was drawn into: depth 1.
    pub(crate) empty_shadow_depth: glow::Texture,
    /// The sampler of `sampler2DShadow` lookups: compared (`LEQUAL`), linear with
    /// `shadowHardwareFiltering`, clamped.
    comparison: glow::Sampler,
    unbound: glow::Texture,
    /// Zero textures of the other kinds a program may declare (3D, cube, array, integer) and of
    /// its images, made at their first use, by [`EmptyKind`].
    empties: std::cell::RefCell<BTreeMap<EmptyKind, glow::Texture>>,
    /// The pack's custom images ([`custom_images`]).
    pub(crate) images: Vec<GlCustomImage>,
}

/// An Iris custom image as OpenGL holds it: bound as the image `name` and read through the
/// sampler `sampler`.
#[derive(Clone)]
pub(crate) struct GlCustomImage {
    name: String,
    sampler: Option<String>,
    texture: glow::Texture,
    /// `TEXTURE_1D`, `TEXTURE_2D` or `TEXTURE_3D`.
    target: u32,
    internal: u32,
}

/// The OpenGL internal format an Iris custom image names (`RGBA16F`), and whether it holds
/// integers; None for a name the loaders do not know, or a format no image unit takes (three
/// channels, the mixed formats but two).
pub(crate) fn image_internal_format(name: &str) -> Option<(u32, bool)> {
    use tidepack_loader::texture_formats::{Component::*, TextureFormat};
    let format = TextureFormat::parse(name)?;
    let internal = match format {
        TextureFormat::R11fG11fB10f => glow::R11F_G11F_B10F,
        TextureFormat::Rgb10A2 => glow::RGB10_A2,
        TextureFormat::Uniform { channels, bits, component } => {
            // By channel count (1, 2, 4), as GL's tables list them.
            let of = |formats: [u32; 3]| match channels {
                1 => Some(formats[0]),
                2 => Some(formats[1]),
                4 => Some(formats[2]),
                _ => None,
            };
            match (bits, component) {
                (8, Unorm) => of([glow::R8, glow::RG8, glow::RGBA8]),
                (8, Snorm) => of([glow::R8_SNORM, glow::RG8_SNORM, glow::RGBA8_SNORM]),
                (8, Int) => of([glow::R8I, glow::RG8I, glow::RGBA8I]),
                (8, Uint) => of([glow::R8UI, glow::RG8UI, glow::RGBA8UI]),
                (16, Unorm) => of([glow::R16, glow::RG16, glow::RGBA16]),
                (16, Snorm) => of([glow::R16_SNORM, glow::RG16_SNORM, glow::RGBA16_SNORM]),
                (16, Float) => of([glow::R16F, glow::RG16F, glow::RGBA16F]),
                (16, Int) => of([glow::R16I, glow::RG16I, glow::RGBA16I]),
                (16, Uint) => of([glow::R16UI, glow::RG16UI, glow::RGBA16UI]),
                (32, Float) => of([glow::R32F, glow::RG32F, glow::RGBA32F]),
                (32, Int) => of([glow::R32I, glow::RG32I, glow::RGBA32I]),
                (32, Uint) => of([glow::R32UI, glow::RG32UI, glow::RGBA32UI]),
                _ => None,
            }?
        }
        TextureFormat::R3G3B2 | TextureFormat::Rgb5A1 | TextureFormat::Rgb9E5 => return None,
    };
    Some((internal, format.is_integer()))
}

/// The pack's custom images for a frame of `width` x `height`, each cleared to zero as Iris
/// makes them, but those of an internal format the harness does not make (the pack's report
/// says so).
pub(crate) unsafe fn custom_images(ctx: &GlContext, pack: &dyn PackResources, width: u32, height: u32) -> Result<Vec<GlCustomImage>, HarnessError> {
    let gl = ctx.gl();
    let mut made = Vec::new();
    for image in pack.custom_images() {
        let Some((internal, integer)) = image_internal_format(&image.internal_format) else { continue };
        let (target, [w, h, d]) = match image.size {
            ImageSize::Relative([x, y]) => (glow::TEXTURE_2D, [((width as f32 * x).round() as i32).max(1), ((height as f32 * y).round() as i32).max(1), 1]),
            ImageSize::Absolute { width, height: 0, .. } => (glow::TEXTURE_1D, [width.max(1) as i32, 1, 1]),
            ImageSize::Absolute { width, height, depth: 0 } => (glow::TEXTURE_2D, [width.max(1) as i32, height as i32, 1]),
            ImageSize::Absolute { width, height, depth } => (glow::TEXTURE_3D, [width.max(1) as i32, height as i32, depth as i32]),
        };
        // SAFETY: the caller holds the current context.
        let texture = unsafe {
            let texture = gl.create_texture().map_err(gl_err("texture"))?;
            gl.bind_texture(target, Some(texture));
            match target {
                glow::TEXTURE_1D => gl.tex_storage_1d(target, 1, internal, w),
                glow::TEXTURE_2D => gl.tex_storage_2d(target, 1, internal, w, h),
                _ => gl.tex_storage_3d(target, 1, internal, w, h, d),
            }
            let filter = if integer { glow::NEAREST } else { glow::LINEAR } as i32;
            gl.tex_parameter_i32(target, glow::TEXTURE_MIN_FILTER, filter);
            gl.tex_parameter_i32(target, glow::TEXTURE_MAG_FILTER, filter);
            for wrap in [glow::TEXTURE_WRAP_S, glow::TEXTURE_WRAP_T, glow::TEXTURE_WRAP_R] {
                gl.tex_parameter_i32(target, wrap, glow::CLAMP_TO_EDGE as i32);
            }
            gl.bind_texture(target, None);
            let Some(clear) = ctx.legacy().clear_tex_image else {
                gl.delete_texture(texture);
                return Err(HarnessError::Gl(format!("image {}: the driver has no glClearTexImage to clear it with", image.name)));
            };
            let (format, ty) = if integer { (glow::RED_INTEGER, glow::UNSIGNED_INT) } else { (glow::RED, glow::FLOAT) };
            clear(texture.0.get(), 0, format, ty, std::ptr::null());
            texture
        };
        made.push(GlCustomImage { name: image.name.clone(), sampler: image.sampler.clone(), texture, target, internal });
    }
    Ok(made)
}

/// A zero 1x1(x1) texture's target and the kind of value it holds. Samplers and images the
/// harness makes nothing for read it, as wgpu's empty texture of their kind: 0. A store to an
/// image lands outside it or on its one texel, which images alone share (never a sampler).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct EmptyKind {
    target: u32,
    /// glow::FLOAT, glow::INT or glow::UNSIGNED_INT.
    scalar: u32,
    image: bool,
}

impl EmptyKind {
    /// The empty texture a sampler or image uniform of GL type `utype` reads; `None` for a plain
    /// 2D sampler (bound by name) and for types with no such stand-in (buffer and multisampled
    /// textures, shadow cubes and arrays).
    fn of_uniform(utype: u32) -> Option<EmptyKind> {
        let (target, scalar, image) = match utype {
            glow::SAMPLER_1D => (glow::TEXTURE_1D, glow::FLOAT, false),
            glow::INT_SAMPLER_1D => (glow::TEXTURE_1D, glow::INT, false),
            glow::UNSIGNED_INT_SAMPLER_1D => (glow::TEXTURE_1D, glow::UNSIGNED_INT, false),
            glow::SAMPLER_3D => (glow::TEXTURE_3D, glow::FLOAT, false),
            glow::INT_SAMPLER_3D => (glow::TEXTURE_3D, glow::INT, false),
            glow::UNSIGNED_INT_SAMPLER_3D => (glow::TEXTURE_3D, glow::UNSIGNED_INT, false),
            glow::SAMPLER_CUBE => (glow::TEXTURE_CUBE_MAP, glow::FLOAT, false),
            glow::INT_SAMPLER_CUBE => (glow::TEXTURE_CUBE_MAP, glow::INT, false),
            glow::UNSIGNED_INT_SAMPLER_CUBE => (glow::TEXTURE_CUBE_MAP, glow::UNSIGNED_INT, false),
            glow::SAMPLER_2D_ARRAY => (glow::TEXTURE_2D_ARRAY, glow::FLOAT, false),
            glow::INT_SAMPLER_2D_ARRAY => (glow::TEXTURE_2D_ARRAY, glow::INT, false),
            glow::UNSIGNED_INT_SAMPLER_2D_ARRAY => (glow::TEXTURE_2D_ARRAY, glow::UNSIGNED_INT, false),
            glow::IMAGE_1D => (glow::TEXTURE_1D, glow::FLOAT, true),
            glow::INT_IMAGE_1D => (glow::TEXTURE_1D, glow::INT, true),
            glow::UNSIGNED_INT_IMAGE_1D => (glow::TEXTURE_1D, glow::UNSIGNED_INT, true),
            glow::IMAGE_2D => (glow::TEXTURE_2D, glow::FLOAT, true),
            glow::INT_IMAGE_2D => (glow::TEXTURE_2D, glow::INT, true),
            glow::UNSIGNED_INT_IMAGE_2D => (glow::TEXTURE_2D, glow::UNSIGNED_INT, true),
            glow::IMAGE_3D => (glow::TEXTURE_3D, glow::FLOAT, true),
            glow::INT_IMAGE_3D => (glow::TEXTURE_3D, glow::INT, true),
            glow::UNSIGNED_INT_IMAGE_3D => (glow::TEXTURE_3D, glow::UNSIGNED_INT, true),
            glow::IMAGE_2D_ARRAY => (glow::TEXTURE_2D_ARRAY, glow::FLOAT, true),
            glow::INT_IMAGE_2D_ARRAY => (glow::TEXTURE_2D_ARRAY, glow::INT, true),
            glow::UNSIGNED_INT_IMAGE_2D_ARRAY => (glow::TEXTURE_2D_ARRAY, glow::UNSIGNED_INT, true),
            _ => return None,
        };
        Some(EmptyKind { target, scalar, image })
    }

    /// Internal format, pixel format and type of its texel (an image is bound with the
    /// internal format).
    fn formats(self) -> (u32, u32, u32) {
        match self.scalar {
            glow::INT => (glow::RGBA32I, glow::RGBA_INTEGER, glow::INT),
            glow::UNSIGNED_INT => (glow::RGBA32UI, glow::RGBA_INTEGER, glow::UNSIGNED_INT),
            _ => (glow::RGBA32F, glow::RGBA, glow::FLOAT),
        }
    }
}

impl GlHarnessTextures {
    /// The harness's textures for a frame of `width` x `height` of `pack`.
    pub(crate) unsafe fn new(ctx: &GlContext, pack: &dyn PackResources, width: u32, height: u32) -> Result<GlHarnessTextures, HarnessError> {
        let gl = ctx.gl();
        let rgba8 = |(tw, th, data): (u32, u32, Vec<u8>), linear: bool, repeat: bool| {
            // SAFETY: the caller holds the current context.
            unsafe { make_texture(gl, glow::RGBA8, glow::RGBA, glow::UNSIGNED_BYTE, tw as i32, th as i32, Some(&data), linear, repeat) }
        };
        let one_texel = |rgba: [u8; 4]| rgba8((1, 1, rgba.to_vec()), true, false);
        // SAFETY: the caller holds the current context.
        let comparison = unsafe {
            let s = gl.create_sampler().map_err(gl_err("sampler"))?;
            let filter = if pack.shadow_settings().hardware_filtering { glow::LINEAR } else { glow::NEAREST } as i32;
            gl.sampler_parameter_i32(s, glow::TEXTURE_COMPARE_MODE, glow::COMPARE_REF_TO_TEXTURE as i32);
            gl.sampler_parameter_i32(s, glow::TEXTURE_COMPARE_FUNC, glow::LEQUAL as i32);
            gl.sampler_parameter_i32(s, glow::TEXTURE_MIN_FILTER, filter);
            gl.sampler_parameter_i32(s, glow::TEXTURE_MAG_FILTER, filter);
            gl.sampler_parameter_i32(s, glow::TEXTURE_WRAP_S, glow::CLAMP_TO_EDGE as i32);
            gl.sampler_parameter_i32(s, glow::TEXTURE_WRAP_T, glow::CLAMP_TO_EDGE as i32);
            s
        };
        Ok(GlHarnessTextures {
            atlas: rgba8(mesh::atlas(), false, true)?,
            sun: rgba8(mesh::sun(), false, true)?,
            moon: rgba8(mesh::moon(), false, true)?,
            lightmap: rgba8(mesh::lightmap(), true, false)?,
            noise: rgba8(mesh::noise(256), true, true)?,
            // SAFETY: the caller holds the current context.
            custom: pack.custom_textures().iter().map(|t| unsafe { custom_texture(gl, t) }).collect::<Result<_, _>>()?,
            flat_normals: one_texel([128, 128, 255, 255])?,
            no_specular: one_texel([0; 4])?,
            white: one_texel([255; 4])?,
            // SAFETY: the caller holds the current context.
            empty_shadow_depth: unsafe {
                let t = make_texture(gl, glow::DEPTH_COMPONENT32F, glow::DEPTH_COMPONENT, glow::FLOAT, 1, 1, Some(bytemuck::bytes_of(&1.0f32)), false, false)?;
                read_as_shadow_map(gl, t, true);
                t
            },
            comparison,
            unbound: one_texel([0; 4])?,
            empties: Default::default(),
            // SAFETY: the caller holds the current context.
            images: unsafe { custom_images(ctx, pack, width, height)? },
        })
    }

    /// The zero texture of `kind`, made at its first use.
    unsafe fn empty(&self, gl: &glow::Context, kind: EmptyKind) -> Result<glow::Texture, HarnessError> {
        if let Some(&t) = self.empties.borrow().get(&kind) {
            return Ok(t);
        }
        let (internal, format, ty) = kind.formats();
        let zero = [0u8; 16];
        let data = || glow::PixelUnpackData::Slice(Some(&zero[..]));
        // SAFETY: the caller holds the current context.
        let t = unsafe {
            let t = gl.create_texture().map_err(gl_err("texture"))?;
            gl.bind_texture(kind.target, Some(t));
            match kind.target {
                glow::TEXTURE_1D => gl.tex_image_1d(kind.target, 0, internal as i32, 1, 0, format, ty, data()),
                glow::TEXTURE_3D | glow::TEXTURE_2D_ARRAY => gl.tex_image_3d(kind.target, 0, internal as i32, 1, 1, 1, 0, format, ty, data()),
                glow::TEXTURE_CUBE_MAP => {
                    for face in 0..6 {
                        gl.tex_image_2d(glow::TEXTURE_CUBE_MAP_POSITIVE_X + face, 0, internal as i32, 1, 1, 0, format, ty, data());
                    }
                }
                _ => gl.tex_image_2d(kind.target, 0, internal as i32, 1, 1, 0, format, ty, data()),
            }
            gl.tex_parameter_i32(kind.target, glow::TEXTURE_MIN_FILTER, glow::NEAREST as i32);
            gl.tex_parameter_i32(kind.target, glow::TEXTURE_MAG_FILTER, glow::NEAREST as i32);
            gl.tex_parameter_i32(kind.target, glow::TEXTURE_MAX_LEVEL, 0);
            gl.bind_texture(kind.target, None);
            t
        };
        self.empties.borrow_mut().insert(kind, t);
        Ok(t)
    }

    pub(crate) unsafe fn delete(&self, gl: &glow::Context) {
        let own = [
            self.atlas,
            self.sun,
            self.moon,
            self.lightmap,
            self.noise,
            self.flat_normals,
            self.no_specular,
            self.white,
            self.empty_shadow_depth,
            self.unbound,
        ];
        let images = self.images.iter().map(|i| i.texture);
        for t in own.into_iter().chain(self.custom.iter().map(|(t, _)| *t)).chain(self.empties.borrow().values().copied()).chain(images) {
            // SAFETY: the caller holds the current context that made the texture.
            unsafe { gl.delete_texture(t) };
        }
        // SAFETY: as above.
        unsafe { gl.delete_sampler(self.comparison) };
    }
}

/// What a program's samplers can be bound to, as [`crate::gpu::bindings::BindableTextures`].
pub(crate) struct Textures<'a> {
    pub naming: SamplerNaming,
    pub harness: &'a GlHarnessTextures,
    pub colors: BTreeMap<u8, (glow::Texture, BufferFormat)>,
    pub depth0: glow::Texture,
    pub depth1: glow::Texture,
    /// dhDepthTex0 and dhDepthTex1.
    pub lod_depth: [glow::Texture; 2],
    /// shadowtex0 and shadowtex1.
    pub shadow_depth: [glow::Texture; 2],
    /// The shadow colour buffers by number, with their formats (one not here reads white).
    pub shadow_colours: BTreeMap<u8, (glow::Texture, BufferFormat)>,
    /// What `gtexture` holds.
    pub sprites: Sprites,
    /// Colour buffers read with their mipmaps.
    pub mipmapped: BTreeSet<u8>,
}

/// Draws `vertices` in their vertex colour with the harness's colour shader: what a loader
/// draws where the pack has no program of the chain, into the bound draw buffers.
pub(crate) unsafe fn draw_own_colour(
    ctx: &GlContext,
    missing: MissingProgramDraws,
    depth: DepthMapping,
    scene: &Scene,
    vertices: &[PackVertex],
) -> Result<(), HarnessError> {
    let gl = ctx.gl();
    let vertex = if depth == DepthMapping::Harness { COLOUR_VS_HARNESS } else { COLOUR_VS };
    let attributes = [("position", 0), ("color", 1)];
    let own = match missing {
        MissingProgramDraws::FirstBufferOnly => ctx.compile_program(vertex, None, COLOUR_FS, &attributes, &[("outColor", 0)]),
        MissingProgramDraws::EveryBuffer => ctx.compile_program(vertex, None, COLOUR_FS_EVERY_BUFFER, &attributes, &[]),
    };
    let own = own.map_err(|e| HarnessError::Gl(format!("the harness's colour shader: {e}")))?;
    // SAFETY: the caller holds the current context; the vertex data outlives the draw.
    unsafe {
        gl.use_program(Some(own.raw));
        gl.uniform_matrix_4_f32_slice(gl.get_uniform_location(own.raw, "mvp").as_ref(), false, &scene.terrain_mvp());
        let vbo = gl.create_buffer().map_err(gl_err("buffer"))?;
        gl.bind_buffer(glow::ARRAY_BUFFER, Some(vbo));
        gl.buffer_data_u8_slice(glow::ARRAY_BUFFER, bytemuck::cast_slice(vertices), glow::STATIC_DRAW);
        let stride = offsets::STRIDE as i32;
        gl.enable_vertex_attrib_array(0);
        gl.vertex_attrib_pointer_f32(0, 4, glow::FLOAT, false, stride, offsets::POSITION as i32);
        gl.enable_vertex_attrib_array(1);
        gl.vertex_attrib_pointer_f32(1, 4, glow::FLOAT, false, stride, offsets::COLOR as i32);
        gl.draw_arrays(glow::TRIANGLES, 0, vertices.len() as i32);
        gl.disable_vertex_attrib_array(0);
        gl.disable_vertex_attrib_array(1);
        gl.delete_buffer(vbo);
    }
    ctx.delete_program(own);
    Ok(())
}

/// Sets the blend of each draw buffer (draw buffer i draws into `buffers[i]`, or nothing).
pub(crate) unsafe fn set_blends(gl: &glow::Context, buffers: &[Option<u8>], blend_of: &dyn Fn(u8) -> Blend) {
    for (i, b) in buffers.iter().enumerate().filter_map(|(i, b)| Some((i, b.as_ref()?))) {
        // SAFETY: the caller holds the current context.
        unsafe {
            match blend_of(*b) {
                Blend::Off => gl.disable_draw_buffer(glow::BLEND, i as u32),
                Blend::Factors([s, d, sa, da]) => {
                    gl.enable_draw_buffer(glow::BLEND, i as u32);
                    gl.blend_func_separate_draw_buffer(i as u32, gl_factor(s), gl_factor(d), gl_factor(sa), gl_factor(da));
                }
            }
        }
    }
}

/// With `masked`, writes to the draw buffers `program` never writes turned off, so that they
/// keep what they held, as wgpu keeps them; without, turned on again.
pub(crate) unsafe fn mask_unwritten(gl: &glow::Context, program: &LoadedProgram, masked: bool) {
    for i in program.draw_buffers_never_written() {
        // SAFETY: the caller holds the current context.
        unsafe { gl.color_mask_draw_buffer(i as u32, !masked, !masked, !masked, !masked) };
    }
}

/// A 2D texture with one level, filtered and wrapped as asked.
#[allow(clippy::too_many_arguments)]
pub(crate) unsafe fn make_texture(
    gl: &glow::Context,
    internal: u32,
    format: u32,
    ty: u32,
    width: i32,
    height: i32,
    data: Option<&[u8]>,
    linear: bool,
    repeat: bool,
) -> Result<glow::Texture, HarnessError> {
    // SAFETY: the caller holds the current context.
    unsafe {
        let t = gl.create_texture().map_err(gl_err("texture"))?;
        gl.bind_texture(glow::TEXTURE_2D, Some(t));
        gl.tex_image_2d(glow::TEXTURE_2D, 0, internal as i32, width, height, 0, format, ty, glow::PixelUnpackData::Slice(data));
        let filter = if linear { glow::LINEAR } else { glow::NEAREST } as i32;
        let wrap = if repeat { glow::REPEAT } else { glow::CLAMP_TO_EDGE } as i32;
        gl.tex_parameter_i32(glow::TEXTURE_2D, glow::TEXTURE_MIN_FILTER, filter);
        gl.tex_parameter_i32(glow::TEXTURE_2D, glow::TEXTURE_MAG_FILTER, filter);
        gl.tex_parameter_i32(glow::TEXTURE_2D, glow::TEXTURE_WRAP_S, wrap);
        gl.tex_parameter_i32(glow::TEXTURE_2D, glow::TEXTURE_WRAP_T, wrap);
        gl.tex_parameter_i32(glow::TEXTURE_2D, glow::TEXTURE_MAX_LEVEL, 0);
        Ok(t)
    }
}

/// A custom texture of the pack as OpenGL holds it, RGBA8 or RGBA32F, with the filter and wrap
/// its properties ask for: the texture and its target.
unsafe fn custom_texture(gl: &glow::Context, t: &CustomTexture) -> Result<(glow::Texture, u32), HarnessError> {
    let (internal, ty) = match t.texels {
        Texels::Rgba8(_) => (glow::RGBA8, glow::UNSIGNED_BYTE),
        Texels::Float(_) => (glow::RGBA32F, glow::FLOAT),
    };
    let data = || glow::PixelUnpackData::Slice(Some(t.texels.bytes()));
    let (width, height, depth) = (t.width as i32, t.height as i32, t.depth as i32);
    // SAFETY: the caller holds the current context.
    unsafe {
        let target = match t.target {
            TextureTarget::D2 | TextureTarget::Rectangle => return Ok((make_texture(gl, internal, glow::RGBA, ty, width, height, Some(t.texels.bytes()), t.blur, !t.clamp)?, glow::TEXTURE_2D)),
            TextureTarget::D1 => glow::TEXTURE_1D,
            TextureTarget::D3 => glow::TEXTURE_3D,
        };
        let texture = gl.create_texture().map_err(gl_err("texture"))?;
        gl.bind_texture(target, Some(texture));
        // Rows of RGBA8 and RGBA32F texels are whole 4-byte words, as OpenGL unpacks them.
        if target == glow::TEXTURE_1D {
            gl.tex_image_1d(target, 0, internal as i32, width, 0, glow::RGBA, ty, data());
        } else {
            gl.tex_image_3d(target, 0, internal as i32, width, height, depth, 0, glow::RGBA, ty, data());
        }
        let filter = if t.blur { glow::LINEAR } else { glow::NEAREST } as i32;
        let wrap = if t.clamp { glow::CLAMP_TO_EDGE } else { glow::REPEAT } as i32;
        for (parameter, value) in [
            (glow::TEXTURE_MIN_FILTER, filter),
            (glow::TEXTURE_MAG_FILTER, filter),
            (glow::TEXTURE_WRAP_S, wrap),
            (glow::TEXTURE_WRAP_T, wrap),
            (glow::TEXTURE_WRAP_R, wrap),
            (glow::TEXTURE_MAX_LEVEL, 0),
        ] {
            gl.tex_parameter_i32(target, parameter, value);
        }
        Ok((texture, target))
    }
}

/// Gives colour texture `t` (`width` x `height`, level 0 made) every further mip level.
pub(crate) unsafe fn add_mip_levels(gl: &glow::Context, t: glow::Texture, internal: u32, width: i32, height: i32) {
    let levels = tidepack_loader::buffers::mip_levels(width as u32, height as u32);
    // SAFETY: the caller holds the current context.
    unsafe {
        gl.bind_texture(glow::TEXTURE_2D, Some(t));
        for level in 1..levels {
            let (w, h) = ((width >> level).max(1), (height >> level).max(1));
            gl.tex_image_2d(glow::TEXTURE_2D, level as i32, internal as i32, w, h, 0, glow::RGBA, glow::FLOAT, glow::PixelUnpackData::Slice(None));
        }
        gl.tex_parameter_i32(glow::TEXTURE_2D, glow::TEXTURE_MAX_LEVEL, levels as i32 - 1);
    }
}

/// Sets up depth texture `t` as the loaders read a shadow map through `sampler2D`: (d, d, d, 1)
/// (Iris swizzles its shadow maps so; OptiFine's compatibility profile reads depth as
/// luminance), filtered linearly unless `nearest` (`shadowtexNearest`).
pub(crate) unsafe fn read_as_shadow_map(gl: &glow::Context, t: glow::Texture, nearest: bool) {
    // SAFETY: the caller holds the current context.
    unsafe {
        gl.bind_texture(glow::TEXTURE_2D, Some(t));
        let swizzle = [glow::RED, glow::RED, glow::RED, glow::ONE].map(|c| c as i32);
        gl.tex_parameter_i32_slice(glow::TEXTURE_2D, glow::TEXTURE_SWIZZLE_RGBA, &swizzle);
        let filter = if nearest { glow::NEAREST } else { glow::LINEAR } as i32;
        gl.tex_parameter_i32(glow::TEXTURE_2D, glow::TEXTURE_MIN_FILTER, filter);
        gl.tex_parameter_i32(glow::TEXTURE_2D, glow::TEXTURE_MAG_FILTER, filter);
    }
}

/// Attaches `attachments` as colour attachments 0.. (draw buffers in that order) and `depth`
/// to the bound framebuffer.
pub(crate) unsafe fn attach(gl: &glow::Context, attachments: &[Option<glow::Texture>], depth: Option<glow::Texture>) -> Result<(), HarnessError> {
    // SAFETY: the caller holds the current context with a framebuffer bound.
    unsafe {
        for i in 0..8 {
            gl.framebuffer_texture_2d(glow::FRAMEBUFFER, glow::COLOR_ATTACHMENT0 + i, glow::TEXTURE_2D, None, 0);
        }
        for (i, t) in attachments.iter().enumerate() {
            gl.framebuffer_texture_2d(glow::FRAMEBUFFER, glow::COLOR_ATTACHMENT0 + i as u32, glow::TEXTURE_2D, *t, 0);
        }
        gl.framebuffer_texture_2d(glow::FRAMEBUFFER, glow::DEPTH_ATTACHMENT, glow::TEXTURE_2D, depth, 0);
        // An output drawn into no buffer (`N`) has GL_NONE as its draw buffer.
        let draw: Vec<u32> = attachments.iter().enumerate().map(|(i, t)| if t.is_some() { glow::COLOR_ATTACHMENT0 + i as u32 } else { glow::NONE }).collect();
        gl.draw_buffers(&draw);
        let status = gl.check_framebuffer_status(glow::FRAMEBUFFER);
        if status != glow::FRAMEBUFFER_COMPLETE {
            return Err(HarnessError::Gl(format!("framebuffer incomplete (0x{status:x})")));
        }
        Ok(())
    }
}

/// Clears colour attachment 0 of the bound framebuffer, of `format`, to `colour`: an integer
/// buffer takes integers (a float clear leaves it undefined).
pub(crate) unsafe fn clear_colour(gl: &glow::Context, format: BufferFormat, colour: [f64; 4]) {
    // SAFETY: the caller holds the current context with a framebuffer bound.
    unsafe {
        match format {
            BufferFormat::Rgba32Ui => gl.clear_buffer_u32_slice(glow::COLOR, 0, &colour.map(|v| v.max(0.0) as u32)),
            BufferFormat::Rgba32I => gl.clear_buffer_i32_slice(glow::COLOR, 0, &colour.map(|v| v as i32)),
            _ => gl.clear_buffer_f32_slice(glow::COLOR, 0, &colour.map(|v| v as f32)),
        }
    }
}

/// What a texture read back holds.
#[derive(Clone, Copy)]
pub(crate) enum Held {
    Depth,
    Colour(BufferFormat),
}

/// Reads a colour texture, or a depth texture (attached beside the colour texture `scratch`),
/// as floats, bottom row first; an integer texture's values become floats.
pub(crate) unsafe fn read(gl: &glow::Context, t: glow::Texture, held: Held, scratch: glow::Texture, w: i32, h: i32) -> Result<FloatImage, HarnessError> {
    let is_depth = matches!(held, Held::Depth);
    // SAFETY: the caller holds the current context with a framebuffer bound.
    unsafe {
        if is_depth {
            attach(gl, &[Some(scratch)], Some(t))?;
        } else {
            attach(gl, &[Some(t)], None)?;
            gl.read_buffer(glow::COLOR_ATTACHMENT0);
        }
        let mut image = FloatImage::new(w as u32, h as u32);
        let channels = if is_depth { 1 } else { 4 };
        let mut floats = vec![0f32; (w * h) as usize * channels];
        if let Held::Colour(format @ (BufferFormat::Rgba32Ui | BufferFormat::Rgba32I)) = held {
            let mut words = vec![0u32; floats.len()];
            let (pixels, ty) = pixel_transfer(format);
            gl.read_pixels(0, 0, w, h, pixels, ty, glow::PixelPackData::Slice(Some(bytemuck::cast_slice_mut(&mut words))));
            for (f, word) in floats.iter_mut().zip(words) {
                *f = if format == BufferFormat::Rgba32Ui { word as f32 } else { word as i32 as f32 };
            }
        } else {
            let format = if is_depth { glow::DEPTH_COMPONENT } else { glow::RGBA };
            gl.read_pixels(0, 0, w, h, format, glow::FLOAT, glow::PixelPackData::Slice(Some(bytemuck::cast_slice_mut(&mut floats))));
        }
        for (i, px) in image.pixels.iter_mut().enumerate() {
            let f = |c: usize| floats[i * channels + c];
            *px = if is_depth { [f(0), f(0), f(0), 1.0] } else { [f(0), f(1), f(2), f(3)] };
        }
        Ok(image)
    }
}

/// A program's shipped text as the driver built it.
pub(crate) enum Compiled {
    /// Vertex and fragment stage linked together ([`DepthMapping::OpenGl`]).
    Direct(GlProgram),
    /// [`DepthMapping::Harness`]: the shipped vertex stage alone, recording `gl_Position` and
    /// its outputs by transform feedback, and the shipped fragment stage behind a pass-through
    /// vertex shader that maps depth as the wgpu wrapper does.
    Captured { capture: GlProgram, draw: GlProgram, components: Vec<i32> },
}

impl Compiled {
    pub(crate) fn delete(self, ctx: &GlContext) {
        match self {
            Compiled::Direct(p) => ctx.delete_program(p),
            Compiled::Captured { capture, draw, .. } => {
                ctx.delete_program(capture);
                ctx.delete_program(draw);
            }
        }
    }
}

/// The vertex stage's outputs (name, components), read from the lowered module's entry point:
/// the shipped names, all `float`/`vecN` with the default (perspective, centre) interpolation.
fn vertex_outputs(stage: &LoadedStage) -> Result<Vec<(String, u32)>, HarnessError> {
    let unsupported = |what: String| HarnessError::Unsupported(format!("{}: {what} (OpenGL depth mapping)", stage.path));
    let module = stage.module()?;
    let entry = module.entry_points.iter().find(|e| e.stage == naga::ShaderStage::Vertex).ok_or_else(|| unsupported("no vertex entry point".into()))?;
    let Some(result) = &entry.function.result else { return Ok(Vec::new()) };
    // Outputs the harness declared for fragment inputs the shipped vertex stage lacks are not
    // in the shipped text: nothing to record.
    let outputs_declared: Vec<_> =
        crate::program::interface_declarations(&stage.lowered_text).into_iter().filter(|d| d.direction() == Some("out")).collect();
    // naga spreads a struct output over its members, named as the struct's fields: transform
    // feedback would need them as `name.field`.
    for declaration in &outputs_declared {
        if let [.., ty, name] = declaration.words.as_slice()
            && !tidepack_glsl::lower::is_builtin_type(ty)
        {
            return Err(unsupported(format!("output {name} of the struct type {ty}")));
        }
    }
    let declared: Vec<&str> = outputs_declared.iter().filter_map(|d| d.words.last().copied()).collect();
    let naga::TypeInner::Struct { members, .. } = &module.types[result.ty].inner else {
        return Err(unsupported("the entry point does not return a struct".into()));
    };
    let mut outputs = Vec::new();
    for member in members {
        let name = member.name.clone().unwrap_or_default();
        match &member.binding {
            Some(naga::Binding::BuiltIn(naga::BuiltIn::Position { .. })) => continue,
            Some(naga::Binding::Location { .. }) if !declared.iter().any(|d| d.split('[').next() == Some(name.as_str())) => continue,
            Some(naga::Binding::Location { interpolation, sampling, .. }) => {
                if !matches!(interpolation, None | Some(naga::Interpolation::Perspective))
                    || !matches!(sampling, None | Some(naga::Sampling::Center))
                {
                    return Err(unsupported(format!("output {name} is not perspective-interpolated at the centre")));
                }
            }
            other => return Err(unsupported(format!("output {name} ({other:?})"))),
        }
        let components = match &module.types[member.ty].inner {
            naga::TypeInner::Scalar(naga::Scalar::F32) => 1,
            naga::TypeInner::Vector { size, scalar: naga::Scalar::F32 } => *size as u32,
            other => return Err(unsupported(format!("output {name} of type {other:?}"))),
        };
        // Names the lowering made (a matrix varying split into columns) are not in the shipped
        // text transform feedback records.
        if name.is_empty() || name.starts_with("gl_") || name.starts_with("tp_") || outputs.iter().any(|(n, _)| *n == name) {
            return Err(unsupported(format!("output {name:?}")));
        }
        outputs.push((name, components));
    }
    Ok(outputs)
}

/// The pass-through vertex shader of [`Compiled::Captured`]: attribute 0 is the captured
/// `gl_Position`, attribute i + 1 the i-th output; the only arithmetic is the wgpu wrapper's
/// `z = 0.5 * (z + w)`. Written in the fragment stage's dialect (`varying` for GLSL 120).
fn pass_through_vertex(fragment_text: &str, outputs: &[(String, u32)]) -> String {
    let legacy = fragment_text.trim_start().starts_with("#version 120") || fragment_text.trim_start().starts_with("#version 110");
    let ty = |n: u32| if n == 1 { "float".to_string() } else { format!("vec{n}") };
    let (input, output) = if legacy { ("attribute", "varying") } else { ("in", "out") };
    let mut text = String::from(if legacy { "#version 120\n" } else { "#version 330 compatibility\n" });
    text.push_str(&format!("{input} vec4 tp_position;\n"));
    for (i, (name, n)) in outputs.iter().enumerate() {
        text.push_str(&format!("{input} {} tp_output{i};\n{output} {} {name};\n", ty(*n), ty(*n)));
    }
    text.push_str("void main() {\n    vec4 clip = tp_position;\n    clip.z = 0.5 * (clip.z + clip.w);\n    gl_Position = clip;\n");
    for (i, (name, _)) in outputs.iter().enumerate() {
        text.push_str(&format!("    {name} = tp_output{i};\n"));
    }
    text.push_str("}\n");
    text
}

/// Vertex attributes OpenGL guarantees (GL_MAX_VERTEX_ATTRIBS).
const MAX_VERTEX_ATTRIBUTES: usize = 16;

/// Where each user vertex input of `stage` is for OpenGL: at the location the shipped text gives
/// it (`layout(location = N)`), the others at the lowering's location, or where that is taken by
/// a placed one or past the [`MAX_VERTEX_ATTRIBUTES`] OpenGL has (a stage with more than eight
/// inputs of its own), at the first location from 1 neither takes (0 is `gl_Vertex`'s in a
/// compatibility profile).
fn attribute_locations(stage: &LoadedStage) -> Vec<(&str, u32)> {
    let interface = &stage.interface;
    let mut taken: Vec<u32> = interface.declared_input_locations.values().copied().collect();
    let mut locations = Vec::new();
    for (name, &lowered) in interface.inputs.iter().filter(|(name, _)| !name.starts_with("gl_")) {
        let location = match interface.declared_input_locations.get(name) {
            Some(&declared) => declared,
            None if !taken.contains(&lowered) && (lowered as usize) < MAX_VERTEX_ATTRIBUTES => lowered,
            None => (1..MAX_VERTEX_ATTRIBUTES as u32).find(|l| !taken.contains(l)).unwrap_or(lowered),
        };
        taken.push(location);
        locations.push((name.as_str(), location));
    }
    locations
}

/// A driver's log with each `0:LINE(COLUMN)` it names said as the pack file and line the
/// compiled line came from.
fn located_log(log: &tidepack_gldriver::DriverLog, program: &LoadedProgram) -> String {
    use tidepack_gldriver::ProgramStep;
    let origins = match log.step {
        ProgramStep::CompileVertex => Some(&program.vertex.gl_origins),
        ProgramStep::CompileGeometry => program.geometry.as_ref().map(|g| &g.gl_origins),
        ProgramStep::CompileFragment => Some(&program.fragment.gl_origins),
        ProgramStep::CompileCompute | ProgramStep::Link | ProgramStep::CreateObject => None,
    };
    located_at(log, origins)
}

/// A driver's log with each line it names said as the pack file and line in `origins` (the
/// pack location of each line of the compiled text).
fn located_at(log: &tidepack_gldriver::DriverLog, origins: Option<&Vec<Option<Location>>>) -> String {
    let lines: Vec<String> = log
        .log
        .trim_end()
        .lines()
        .map(|line| {
            let message = tidepack_gldriver::parse_log(line).into_iter().next();
            let origin = message.as_ref().zip(origins).and_then(|(m, o)| o.get(m.line.checked_sub(1)? as usize).cloned().flatten());
            match (message, origin) {
                (Some(m), Some(at)) => format!("{at}: {}: {}", m.severity, m.message.trim()),
                _ => line.to_string(),
            }
        })
        .collect();
    format!("{} failed:\n{}", log.step, lines.join("\n"))
}

/// Compiles a program's shipped text, binding user attributes ([`attribute_locations`]) and
/// `outColorN` outputs to the locations the lowering gave them (so both renderers feed and read
/// the same slots).
pub(crate) fn compile(ctx: &GlContext, program: &LoadedProgram, depth: DepthMapping) -> Result<Compiled, HarnessError> {
    let attributes = attribute_locations(&program.vertex);
    // An output past the draw buffers has no buffer to bind (`preprocess::MAX_DRAW_BUFFERS`).
    let frag_data: Vec<(&str, u32)> = program
        .fragment
        .interface
        .outputs
        .iter()
        .filter(|(location, name)| !name.starts_with("gl_") && (**location as usize) < tidepack_glsl::preprocess::MAX_DRAW_BUFFERS)
        .map(|(location, name)| (name.as_str(), *location))
        .collect();
    let failed = |e: tidepack_gldriver::DriverLog| HarnessError::Gl(format!("{} through {}: {}", program.name, ctx.info(), located_log(&e, program)));
    match depth {
        DepthMapping::OpenGl => {
            let geometry = program.geometry.as_ref().map(|g| g.gl_text.as_str());
            ctx.compile_program(&program.vertex.gl_text, geometry, &program.fragment.gl_text, &attributes, &frag_data)
                .map(Compiled::Direct)
                .map_err(failed)
        }
        DepthMapping::Harness => {
            // What the fragment stage reads comes from the geometry stage, which the recorded
            // vertex stage does not run.
            if let Some(geometry) = &program.geometry {
                return Err(HarnessError::Unsupported(format!("{}: a geometry stage ({}) between the recorded vertex stage and the fragment stage", program.name, geometry.path)));
            }
            let outputs = vertex_outputs(&program.vertex)?;
            // The pass-through vertex stage reads each output as an attribute, after the
            // position: OpenGL guarantees 16 (Mesa's llvmpipe has no more).
            if outputs.len() + 1 > MAX_VERTEX_ATTRIBUTES {
                return Err(HarnessError::Unsupported(format!(
                    "{}: {} vertex outputs, more than the {} attributes a pass-through vertex stage can read",
                    program.name,
                    outputs.len(),
                    MAX_VERTEX_ATTRIBUTES - 1
                )));
            }
            let mut captured = vec!["gl_Position"];
            captured.extend(outputs.iter().map(|(name, _)| name.as_str()));
            // The driver drops outputs the vertex stage never writes, and then refuses to record
            // them: that program cannot be captured (the caller may draw it as shipped).
            let capture = ctx.compile_capture_program(&program.vertex.gl_text, &attributes, &captured).map_err(|e| {
                if e.to_string().contains("Transform feedback varying") {
                    HarnessError::Unsupported(format!("{}: {e}", program.name))
                } else {
                    failed(e)
                }
            })?;
            let vertex = pass_through_vertex(&program.fragment.gl_text, &outputs);
            let mut locations = vec![("tp_position".to_string(), 0u32)];
            locations.extend((0..outputs.len()).map(|i| (format!("tp_output{i}"), i as u32 + 1)));
            let locations: Vec<(&str, u32)> = locations.iter().map(|(n, l)| (n.as_str(), *l)).collect();
            let draw = match ctx.compile_program(&vertex, None, &program.fragment.gl_text, &locations, &frag_data) {
                Ok(d) => d,
                Err(e) => {
                    ctx.delete_program(capture);
                    return Err(failed(e));
                }
            };
            let mut components = vec![4];
            components.extend(outputs.iter().map(|(_, n)| *n as i32));
            Ok(Compiled::Captured { capture, draw, components })
        }
    }
}

/// Sets `raw`'s active uniforms by name and binds its samplers to texture units from 0.
#[allow(clippy::too_many_arguments)]
unsafe fn set_uniforms(
    gl: &glow::Context,
    pack: &dyn PackResources,
    program: &str,
    raw: glow::Program,
    values: &BTreeMap<String, Value>,
    stage: ProgramStage,
    textures: &Textures,
) -> Result<(), HarnessError> {
    // SAFETY: the caller holds the current context and `raw` is in use.
    unsafe {
        let (mut unit, mut image_unit) = (0u32, 0u32);
        let mut missing = Vec::new();
        for index in 0..gl.get_active_uniforms(raw) {
            let Some(active) = gl.get_active_uniform(raw, index) else { continue };
            if active.name.starts_with("gl_") {
                continue;
            }
            let name = active.name.trim_end_matches("[0]").to_string();
            let location = gl.get_uniform_location(raw, &active.name);
            // A custom image through its image uniform or its sampler, as Iris binds it.
            let kind = EmptyKind::of_uniform(active.utype);
            if let Some(image) = textures.harness.images.iter().find(|i| i.name == name)
                && kind.is_some_and(|k| k.image)
            {
                bind_image(gl, &mut image_unit, location.as_ref(), image.texture, image.target == glow::TEXTURE_3D, image.internal);
                continue;
            }
            if let Some(image) = textures.harness.images.iter().find(|i| i.sampler.as_deref() == Some(name.as_str()))
                && !kind.is_some_and(|k| k.image)
            {
                bind_texture(gl, &mut unit, location.as_ref(), image.target, image.texture);
                continue;
            }
            if matches!(active.utype, glow::SAMPLER_2D | glow::SAMPLER_2D_SHADOW | glow::UNSIGNED_INT_SAMPLER_2D | glow::INT_SAMPLER_2D) {
                let shadow = active.utype == glow::SAMPLER_2D_SHADOW;
                let resolved = textures.naming.resolve(pack, &name, stage);
                let harness = textures.harness;
                let texture = match resolved {
                    Ok(Source::Atlas) => match textures.sprites {
                        Sprites::Blocks => harness.atlas,
                        Sprites::Sun => harness.sun,
                        Sprites::Moon => harness.moon,
                    },
                    Ok(Source::BlockAtlas) => harness.atlas,
                    Ok(Source::Lightmap) => harness.lightmap,
                    Ok(Source::Noise) => harness.noise,
                    Ok(Source::Custom(i)) => harness.custom[i].0,
                    Ok(Source::FlatNormals) => harness.flat_normals,
                    Ok(Source::NoSpecular) => harness.no_specular,
                    Ok(Source::ShadowColour(n)) => textures.shadow_colours.get(&n).map_or(harness.white, |(t, _)| *t),
                    Ok(Source::ShadowDepth(n)) => textures.shadow_depth[n as usize],
                    Ok(Source::Unbound) => harness.unbound,
                    Ok(Source::Depth0) => textures.depth0,
                    Ok(Source::Depth1) => textures.depth1,
                    Ok(Source::LodDepth(n)) => textures.lod_depth[n as usize],
                    Ok(Source::Color(n)) => match textures.colors.get(&n) {
                        Some(c) => c.0,
                        None => {
                            missing.push(format!("{name} (colortex{n} was never allocated)"));
                            continue;
                        }
                    },
                    Err(m) => {
                        missing.push(m);
                        continue;
                    }
                };
                // A shadow sampler over a colour buffer reads undefined values in OpenGL. The
                // loaders bind the buffer as it is, without a comparison, and so does this; wgpu
                // cannot bind it at all, so OpenGL draws such a step alone.
                let compares = shadow && matches!(resolved, Ok(Source::Depth0 | Source::Depth1 | Source::LodDepth(_) | Source::ShadowDepth(_)));
                gl.active_texture(glow::TEXTURE0 + unit);
                gl.bind_texture(glow::TEXTURE_2D, Some(texture));
                gl.bind_sampler(unit, compares.then_some(harness.comparison));
                // A colour buffer reads its mipmaps only in the programs that asked for them.
                // Integer buffers are never filtered.
                if let Ok(Source::Color(n)) = resolved
                    && !textures.colors.get(&n).is_some_and(|(_, format)| format.is_integer())
                {
                    let filter = if textures.mipmapped.contains(&n) { glow::LINEAR_MIPMAP_LINEAR } else { glow::LINEAR };
                    gl.tex_parameter_i32(glow::TEXTURE_2D, glow::TEXTURE_MIN_FILTER, filter as i32);
                }
                gl.uniform_1_i32(location.as_ref(), unit as i32);
                unit += 1;
                continue;
            }
            // colorimgN is colortexN's current texture and shadowcolorimgN shadowcolorN, read and
            // written in place, in the buffer's own format (OptiFine's shaders.txt, "Image
            // access").
            let buffer = buffer_of_image(&name).and_then(|image| match image {
                ImageOf::Colour(n) => textures.colors.get(&n).copied(),
                ImageOf::ShadowColour(n) => textures.shadow_colours.get(&n).copied(),
            });
            if active.utype == glow::IMAGE_2D
                && let Some((texture, format)) = buffer
                && !format.is_integer()
            {
                bind_image(gl, &mut image_unit, location.as_ref(), texture, false, internal_format(format));
                continue;
            }
            // A 1D or 3D float sampler reads the unit's custom texture of its type.
            let custom_target = match active.utype {
                glow::SAMPLER_1D => Some(TextureTarget::D1),
                glow::SAMPLER_3D => Some(TextureTarget::D3),
                _ => None,
            };
            if let Some(i) = custom_target.and_then(|target| samplers::custom_texture_of(pack, &name, stage, target)) {
                let (texture, target) = textures.harness.custom[i];
                bind_texture(gl, &mut unit, location.as_ref(), target, texture);
                continue;
            }
            // Samplers of the other kinds and images read zero from a texture of their own
            // kind, each on a unit of its own (samplers of two types on one unit are an error).
            if let Some(kind) = EmptyKind::of_uniform(active.utype) {
                let texture = textures.harness.empty(gl, kind)?;
                if kind.image {
                    bind_image(gl, &mut image_unit, location.as_ref(), texture, true, kind.formats().0);
                } else {
                    bind_texture(gl, &mut unit, location.as_ref(), kind.target, texture);
                }
                continue;
            }
            // Uniforms the harness has no value for, or one of another type, keep OpenGL's
            // initial value, as the wgpu path leaves them zero or their initializer's.
            let Some(value) = values.get(&name) else { continue };
            set_uniform(gl, location.as_ref(), active.utype, value)
                .map_err(|m| HarnessError::Uniform(format!("{program} (OpenGL): uniform {name}: {m}")))?;
        }
        gl.active_texture(glow::TEXTURE0);
        if !missing.is_empty() {
            return Err(HarnessError::Uniform(format!("{program} (OpenGL) declares what the harness cannot fill: {}", missing.join(", "))));
        }
    }
    Ok(())
}

/// Binds `texture` to the image unit `*unit` for the image uniform at `location`, read and
/// written as `format` (all its layers where `layered`), and moves `*unit` on.
unsafe fn bind_image(gl: &glow::Context, unit: &mut u32, location: Option<&glow::UniformLocation>, texture: glow::Texture, layered: bool, format: u32) {
    // SAFETY: the caller holds the current context, with the program using `location` in use.
    unsafe {
        gl.bind_image_texture(*unit, Some(texture), 0, layered, 0, glow::READ_WRITE, format);
        gl.uniform_1_i32(location, *unit as i32);
    }
    *unit += 1;
}

/// Binds `texture` (a `target` texture) to the texture unit `*unit`, with its own filtering,
/// for the sampler at `location`, and moves `*unit` on.
unsafe fn bind_texture(gl: &glow::Context, unit: &mut u32, location: Option<&glow::UniformLocation>, target: u32, texture: glow::Texture) {
    // SAFETY: the caller holds the current context, with the program using `location` in use.
    unsafe {
        gl.active_texture(glow::TEXTURE0 + *unit);
        gl.bind_texture(target, Some(texture));
        gl.bind_sampler(*unit, None);
        gl.uniform_1_i32(location, *unit as i32);
    }
    *unit += 1;
}

/// A compute stage dispatched: how long it took, and what of its text was rewritten to run on
/// this driver (`program: path: what`), if anything was.
pub(crate) struct Dispatched {
    pub ms: f64,
    pub rewrite: Option<String>,
}

/// The most bytes the `shared` variables of one dispatch are given in storage buffers, all work
/// groups together; a dispatch needing more runs in parts that reuse them.
const MAX_MOVED_SHARED_BYTES: u64 = 1 << 28;

/// Dispatches a compute stage over a frame of `width` x `height` with the values and textures
/// of a full-screen program, and waits for its image writes. The storage buffers at
/// `reserved_bindings` (the pack's) are left bound as they are.
#[allow(clippy::too_many_arguments)]
pub(crate) unsafe fn dispatch_compute(
    ctx: &GlContext,
    pack: &dyn PackResources,
    stage: &ComputeStage,
    values: &BTreeMap<String, Value>,
    textures: &Textures,
    reserved_bindings: &[u32],
    width: u32,
    height: u32,
) -> Result<Dispatched, HarnessError> {
    let gl = ctx.gl();
    let count = stage.work_groups.count(width, height, stage.local_size);
    // SAFETY: the caller holds the current context.
    let mut most = [0, 1, 2].map(|axis| unsafe { gl.get_parameter_indexed_i32(glow::MAX_COMPUTE_WORK_GROUP_COUNT, axis) }.max(1) as u32);
    // llvmpipe dispatches at most 65,535 groups along an axis, the least OpenGL allows; NVIDIA's
    // and AMD's drivers take 2^31 - 1 along x. A larger count is dispatched in parts.
    let in_parts = count.iter().zip(&most).any(|(n, most)| n > most);
    let text = if in_parts { dispatched_in_parts(&stage.stage.gl_text) } else { stage.stage.gl_text.clone() };
    let said = |e: &tidepack_gldriver::DriverLog| format!("{} ({}) through {}: {}", stage.program, stage.stage.path, ctx.info(), located_at(e, Some(&stage.stage.gl_origins)));
    let refused = |e: &tidepack_gldriver::DriverLog| HarnessError::Gl(said(e));
    let (compiled, moved) = match ctx.compile_compute_program(&text) {
        Ok(compiled) => (compiled, None),
        Err(e) => {
            // A stage over llvmpipe's `shared` memory has its variables kept in storage buffers,
            // always in parts, so that the parts can reuse one buffer's slices.
            let over = crate::shared_memory::over_limit(&e.log);
            let Some((moved, (used, given))) = over.and_then(|over| Some((crate::shared_memory::moved_to_buffers(&dispatched_in_parts(&stage.stage.gl_text))?, over))) else {
                return Err(refused(&e));
            };
            let compiled = ctx.compile_compute_program(&moved.text).map_err(|moved_refused| {
                let why = crate::shared_memory::in_the_packs_names(&located_at(&moved_refused, Some(&stage.stage.gl_origins)));
                HarnessError::Gl(format!("{}; with its `shared` variables kept in storage buffers instead, the driver refuses it too: {why}", said(&e)))
            })?;
            let rewrite = format!(
                "{}: {}: `shared` variables of {used} bytes a work group, more than the {given} llvmpipe gives, kept in storage buffers with one slice per work group",
                stage.program, stage.stage.path
            );
            (compiled, Some((moved, rewrite)))
        }
    };
    // SAFETY: the caller holds the current context; the program and buffers are made on it.
    let slices = match &moved {
        Some((moved, _)) => match unsafe { shared_slices(ctx, compiled.raw, &moved.blocks, reserved_bindings, count) } {
            Ok((buffers, groups)) => {
                most = part_of_at_most(count, groups);
                Some(buffers)
            }
            Err(why) => {
                ctx.delete_program(compiled);
                return Err(HarnessError::Unsupported(format!("{} ({}): {why}", stage.program, stage.stage.path)));
            }
        },
        None => None,
    };
    // SAFETY: as above.
    let dispatched = unsafe {
        gl.use_program(Some(compiled.raw));
        let set = set_uniforms(gl, pack, &stage.program, compiled.raw, values, ProgramStage::of(&stage.program), textures);
        let mut ms = 0.0;
        if set.is_ok() && count.iter().all(|n| *n > 0) {
            let offset_at = gl.get_uniform_location(compiled.raw, "tp_WorkGroupOffset");
            let total_at = gl.get_uniform_location(compiled.raw, "tp_NumWorkGroups");
            gl.uniform_3_u32(total_at.as_ref(), count[0], count[1], count[2]);
            let starts = |axis: usize| (0..count[axis]).step_by(most[axis] as usize);
            ms = crate::gl_frame::timed(gl, || {
                for oz in starts(2) {
                    for oy in starts(1) {
                        for ox in starts(0) {
                            gl.uniform_3_u32(offset_at.as_ref(), ox, oy, oz);
                            let part = |axis: usize, start: u32| (count[axis] - start).min(most[axis]);
                            gl.dispatch_compute(part(0, ox), part(1, oy), part(2, oz));
                            if slices.is_some() {
                                gl.memory_barrier(glow::SHADER_STORAGE_BARRIER_BIT);
                            }
                        }
                    }
                }
                gl.memory_barrier(glow::ALL_BARRIER_BITS);
            });
        }
        gl.use_program(None);
        for (binding, buffer) in slices.unwrap_or_default() {
            gl.bind_buffer_base(glow::SHADER_STORAGE_BUFFER, binding, None);
            gl.delete_buffer(buffer);
        }
        set.map(|()| ms)
    };
    ctx.delete_program(compiled);
    Ok(Dispatched { ms: dispatched?, rewrite: moved.map(|(_, rewrite)| rewrite) })
}

/// Storage buffers for the `blocks` holding a stage's `shared` variables, each bound at a
/// binding outside `reserved`, from the last down, with as many slices as the work groups of
/// a part: the whole `count`, or fewer where the slices would pass the driver's block size or
/// [`MAX_MOVED_SHARED_BYTES`]. Returns the bindings and buffers, and the groups of a part.
unsafe fn shared_slices(
    ctx: &GlContext,
    program: glow::Program,
    blocks: &[String],
    reserved: &[u32],
    count: [u32; 3],
) -> Result<(Vec<(u32, glow::Buffer)>, u64), String> {
    let gl = ctx.gl();
    // SAFETY: the caller holds the current context, on which `program` was made.
    unsafe {
        let bindings = gl.get_parameter_i32(glow::MAX_SHADER_STORAGE_BUFFER_BINDINGS).max(0) as u32;
        let largest_block = gl.get_parameter_i64(glow::MAX_SHADER_STORAGE_BLOCK_SIZE).max(0) as u64;
        // The pack's own blocks read the pack's buffers, bound at their bindings for the frame.
        let mut free = (0..bindings).rev().filter(|b| !reserved.contains(b));
        // Each block's slice: its size with a one-slice array, rounded up past any alignment.
        let mut sliced = Vec::new();
        for name in blocks {
            // A variable the stage never uses has no block left after linking.
            let Some(index) = gl.get_shader_storage_block_index(program, name) else { continue };
            let size = ctx.program_resource_i32(program, glow::SHADER_STORAGE_BLOCK, index, glow::BUFFER_DATA_SIZE).ok_or("the driver does not say how large a storage block is")?.max(4) as u64;
            let binding = free.next().ok_or_else(|| format!("no storage buffer binding is free for its `shared` variables ({bindings} in all)"))?;
            sliced.push((index, binding, size.next_multiple_of(256)));
        }
        let groups = count.iter().map(|&n| u64::from(n)).product::<u64>().max(1);
        let slice_bytes: u64 = sliced.iter().map(|(_, _, size)| size).sum::<u64>().max(1);
        let largest_slice = sliced.iter().map(|(_, _, size)| *size).max().unwrap_or(1);
        let part_groups = groups.min(MAX_MOVED_SHARED_BYTES / slice_bytes).min(largest_block / largest_slice);
        if part_groups == 0 {
            return Err(format!("its `shared` variables need {slice_bytes} bytes a work group, more than the {} a storage buffer holds here", largest_block.min(MAX_MOVED_SHARED_BYTES)));
        }
        let mut made = Vec::new();
        for (index, binding, size) in sliced {
            gl.shader_storage_block_binding(program, index, binding);
            let buffer = gl.create_buffer()?;
            gl.bind_buffer(glow::SHADER_STORAGE_BUFFER, Some(buffer));
            gl.buffer_data_size(glow::SHADER_STORAGE_BUFFER, (size * part_groups) as i32, glow::DYNAMIC_COPY);
            gl.bind_buffer_base(glow::SHADER_STORAGE_BUFFER, binding, Some(buffer));
            made.push((binding, buffer));
        }
        gl.bind_buffer(glow::SHADER_STORAGE_BUFFER, None);
        Ok((made, part_groups))
    }
}

/// The most groups a part takes along each axis so that a part holds at most `groups` of
/// `count`: whole rows along x first, then whole layers.
fn part_of_at_most(count: [u32; 3], groups: u64) -> [u32; 3] {
    let x = groups.min(u64::from(count[0])).max(1);
    let y = (groups / x).min(u64::from(count[1])).max(1);
    let z = (groups / (x * y)).min(u64::from(count[2])).max(1);
    [x as u32, y as u32, z as u32]
}

/// A compute stage's `text` for a dispatch in parts: `gl_WorkGroupID`, `gl_GlobalInvocationID`
/// and `gl_NumWorkGroups` read as in one dispatch of the whole count, through the part's
/// `tp_WorkGroupOffset` and the whole `tp_NumWorkGroups`. Their declarations follow the last
/// `#version` or `#extension` line, and a `#line` keeps the numbers of the lines after them.
fn dispatched_in_parts(text: &str) -> String {
    let Ok(tokens) = tidepack_glsl::token::tokenize(text) else { return text.to_string() };
    let rewritten: String = tokens
        .iter()
        .map(|t| match t.text {
            "gl_WorkGroupID" if t.kind == tidepack_glsl::token::TokenKind::Ident => "(gl_WorkGroupID + tp_WorkGroupOffset)",
            "gl_GlobalInvocationID" if t.kind == tidepack_glsl::token::TokenKind::Ident => {
                "(gl_GlobalInvocationID + tp_WorkGroupOffset * gl_WorkGroupSize)"
            }
            "gl_NumWorkGroups" if t.kind == tidepack_glsl::token::TokenKind::Ident => "tp_NumWorkGroups",
            other => other,
        })
        .collect();
    let lines: Vec<&str> = rewritten.split_inclusive('\n').collect();
    let directive = |line: &str| {
        let line = line.trim_start();
        line.strip_prefix('#').is_some_and(|rest| rest.trim_start().starts_with("version") || rest.trim_start().starts_with("extension"))
    };
    let at = lines.iter().rposition(|l| directive(l)).map_or(0, |i| i + 1);
    let mut out = lines[..at].concat();
    if !out.is_empty() && !out.ends_with('\n') {
        out.push('\n');
    }
    out.push_str(&format!("uniform uvec3 tp_WorkGroupOffset;\nuniform uvec3 tp_NumWorkGroups;\n#line {}\n", at + 1));
    out.push_str(&lines[at..].concat());
    out
}

#[allow(clippy::too_many_arguments)]
pub(crate) unsafe fn draw_program(
    ctx: &GlContext,
    pack: &dyn PackResources,
    program: &LoadedProgram,
    compiled: &Compiled,
    values: &BTreeMap<String, Value>,
    textures: &Textures,
    vertices: &[PackVertex],
) -> Result<(), HarnessError> {
    let gl = ctx.gl();
    let lg = ctx.legacy();
    let stage = ProgramStage::of(&program.name);
    let first = match compiled {
        Compiled::Direct(p) => p.raw,
        Compiled::Captured { capture, .. } => capture.raw,
    };
    // SAFETY: the caller holds the current context.
    unsafe {
        gl.use_program(Some(first));
        set_uniforms(gl, pack, &program.name, first, values, stage, textures)?;
        // Legacy matrices through the fixed-function stacks, as the wgpu path fills them.
        let matrix = |name: &str| {
            values.get(name).map(Value::as_f32).ok_or_else(|| HarnessError::Uniform(format!("the harness has no {name} for {}", program.name)))
        };
        let load = |mode: u32, columns: &[f32]| {
            (lg.matrix_mode)(mode);
            (lg.load_matrix_f)(columns.as_ptr());
        };
        load(legacy::MODELVIEW, &matrix("tp_ModelViewMatrix")?);
        load(legacy::PROJECTION, &matrix("tp_ProjectionMatrix")?);
        for (i, columns) in matrix("tp_TextureMatrix")?.chunks_exact(16).take(2).enumerate() {
            gl.active_texture(glow::TEXTURE0 + i as u32);
            load(legacy::TEXTURE, columns);
        }
        (lg.matrix_mode)(legacy::MODELVIEW);
        gl.active_texture(glow::TEXTURE0);
        // The fog state `gl_Fog` reads, as the wgpu path fills it.
        let fog = |key: &str| values.get(&format!("tp_Fog.{key}")).map(Value::as_f32);
        if let (Some(color), Some(density), Some(start), Some(end)) = (fog("color"), fog("density"), fog("start"), fog("end")) {
            (lg.fog_fv)(legacy::FOG_COLOR, color.as_ptr());
            (lg.fog_f)(legacy::FOG_DENSITY, density[0]);
            (lg.fog_f)(legacy::FOG_START, start[0]);
            (lg.fog_f)(legacy::FOG_END, end[0]);
        }

        // Vertex arrays: legacy inputs through client state, user attributes generic.
        let vbo = gl.create_buffer().map_err(gl_err("buffer"))?;
        gl.bind_buffer(glow::ARRAY_BUFFER, Some(vbo));
        gl.buffer_data_u8_slice(glow::ARRAY_BUFFER, bytemuck::cast_slice(vertices), glow::STATIC_DRAW);
        let stride = offsets::STRIDE as i32;
        let at = |offset: u64| offset as usize as *const std::ffi::c_void;
        (lg.enable_client_state)(legacy::VERTEX_ARRAY);
        (lg.vertex_pointer)(4, glow::FLOAT, stride, at(offsets::POSITION));
        (lg.enable_client_state)(legacy::COLOR_ARRAY);
        (lg.color_pointer)(4, glow::FLOAT, stride, at(offsets::COLOR));
        (lg.enable_client_state)(legacy::NORMAL_ARRAY);
        (lg.normal_pointer)(glow::FLOAT, stride, at(offsets::NORMAL));
        for (i, offset) in [offsets::UV0, offsets::UV1].into_iter().enumerate() {
            (lg.client_active_texture)(glow::TEXTURE0 + i as u32);
            (lg.enable_client_state)(legacy::TEXTURE_COORD_ARRAY);
            (lg.tex_coord_pointer)(4, glow::FLOAT, stride, at(offset));
        }
        let mut generic = Vec::new();
        for (name, location) in attribute_locations(&program.vertex) {
            match mesh::input_source(name, program.vertex.interface.declared_input_locations.get(name).copied()) {
                Some((format, offset)) => {
                    gl.enable_vertex_attrib_array(location);
                    match format {
                        AttributeFormat::Sint32x2 => gl.vertex_attrib_pointer_i32(location, 2, glow::INT, stride, offset as i32),
                        _ => gl.vertex_attrib_pointer_f32(location, format.components(), glow::FLOAT, false, stride, offset as i32),
                    }
                    generic.push(location);
                }
                // As in the wgpu path: inputs the harness's vertices lack read zero.
                None => {
                    gl.disable_vertex_attrib_array(location);
                    gl.vertex_attrib_4_f32(location, 0.0, 0.0, 0.0, 0.0);
                }
            }
        }
        // Captured: the vertex stage alone, its outputs recorded, nothing rasterised. With no
        // fragment stage no draw buffer may be on: Mesa refuses such a draw into an integer
        // buffer even with rasterisation off. The draw buffers come back for the draw after it.
        let mut draw_buffers = Vec::new();
        let feedback = match compiled {
            Compiled::Captured { components, .. } if !vertices.is_empty() => {
                for i in 0..tidepack_glsl::preprocess::MAX_DRAW_BUFFERS as u32 {
                    draw_buffers.push(gl.get_parameter_i32(glow::DRAW_BUFFER0 + i) as u32);
                }
                gl.draw_buffers(&[glow::NONE]);
                let size = components.iter().sum::<i32>() as usize * 4 * vertices.len();
                let buffer = gl.create_buffer().map_err(gl_err("buffer"))?;
                gl.bind_buffer(glow::TRANSFORM_FEEDBACK_BUFFER, Some(buffer));
                gl.buffer_data_size(glow::TRANSFORM_FEEDBACK_BUFFER, size as i32, glow::STATIC_COPY);
                gl.bind_buffer_base(glow::TRANSFORM_FEEDBACK_BUFFER, 0, Some(buffer));
                gl.enable(glow::RASTERIZER_DISCARD);
                gl.begin_transform_feedback(glow::TRIANGLES);
                Some(buffer)
            }
            _ => None,
        };
        if !vertices.is_empty() {
            gl.draw_arrays(glow::TRIANGLES, 0, vertices.len() as i32);
        }
        for location in generic {
            gl.disable_vertex_attrib_array(location);
        }
        for i in 0..2 {
            (lg.client_active_texture)(glow::TEXTURE0 + i);
            (lg.disable_client_state)(legacy::TEXTURE_COORD_ARRAY);
        }
        (lg.client_active_texture)(glow::TEXTURE0);
        for state in [legacy::VERTEX_ARRAY, legacy::COLOR_ARRAY, legacy::NORMAL_ARRAY] {
            (lg.disable_client_state)(state);
        }
        gl.delete_buffer(vbo);
        if let (Some(buffer), Compiled::Captured { draw, components, .. }) = (feedback, compiled) {
            gl.end_transform_feedback();
            gl.disable(glow::RASTERIZER_DISCARD);
            gl.draw_buffers(&draw_buffers);
            gl.bind_buffer_base(glow::TRANSFORM_FEEDBACK_BUFFER, 0, None);
            // The shipped fragment stage behind the pass-through vertex shader.
            gl.use_program(Some(draw.raw));
            set_uniforms(gl, pack, &program.name, draw.raw, values, stage, textures)?;
            gl.bind_buffer(glow::ARRAY_BUFFER, Some(buffer));
            let stride = components.iter().sum::<i32>() * 4;
            let mut offset = 0;
            for (location, n) in components.iter().enumerate() {
                gl.enable_vertex_attrib_array(location as u32);
                gl.vertex_attrib_pointer_f32(location as u32, *n, glow::FLOAT, false, stride, offset);
                offset += n * 4;
            }
            gl.draw_arrays(glow::TRIANGLES, 0, vertices.len() as i32);
            for location in 0..components.len() {
                gl.disable_vertex_attrib_array(location as u32);
            }
            gl.delete_buffer(buffer);
        }
        gl.use_program(None);
    }
    Ok(())
}

/// Sets one uniform of GL type `ty` from `value`; a value of another type sets nothing (a
/// loader's `glUniform` of the wrong type fails and leaves the uniform as it was, as the wgpu
/// path leaves it zero).
unsafe fn set_uniform(gl: &glow::Context, location: Option<&glow::UniformLocation>, ty: u32, value: &Value) -> Result<(), String> {
    let declared = match ty {
        glow::FLOAT => "float",
        glow::FLOAT_VEC2 => "vec2",
        glow::FLOAT_VEC3 => "vec3",
        glow::FLOAT_VEC4 => "vec4",
        glow::INT => "int",
        glow::INT_VEC2 => "ivec2",
        glow::INT_VEC3 => "ivec3",
        glow::INT_VEC4 => "ivec4",
        glow::BOOL => "bool",
        glow::FLOAT_MAT3 => "mat3",
        glow::FLOAT_MAT4 => "mat4",
        other => return Err(format!("GL type 0x{other:x} is not supported by the harness")),
    };
    let provided = value.glsl_type();
    let provided = provided.split('[').next().unwrap_or_default();
    // OpenGL sets a `bool` from an int (0 is false), as OptiFine sets a pack's `uniform bool
    // isEyeInWater;` from the int it has.
    if provided != declared && !(ty == glow::BOOL && provided == "int") {
        return Ok(());
    }
    let f = value.as_f32();
    let i = value.as_i32();
    // SAFETY: the caller holds the current context and the program is in use.
    unsafe {
        match ty {
            glow::FLOAT => gl.uniform_1_f32_slice(location, &f),
            glow::FLOAT_VEC2 => gl.uniform_2_f32_slice(location, &f),
            glow::FLOAT_VEC3 => gl.uniform_3_f32_slice(location, &f),
            glow::FLOAT_VEC4 => gl.uniform_4_f32_slice(location, &f),
            glow::INT | glow::BOOL => gl.uniform_1_i32_slice(location, &i),
            glow::INT_VEC2 => gl.uniform_2_i32_slice(location, &i),
            glow::INT_VEC3 => gl.uniform_3_i32_slice(location, &i),
            glow::INT_VEC4 => gl.uniform_4_i32_slice(location, &i),
            glow::FLOAT_MAT3 => gl.uniform_matrix_3_f32_slice(location, false, &f),
            _ => gl.uniform_matrix_4_f32_slice(location, false, &f),
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::part_of_at_most;

    #[test]
    fn a_part_takes_whole_rows_then_whole_layers_up_to_its_groups() {
        assert_eq!(part_of_at_most([10, 360, 1], 10_000), [10, 360, 1]);
        assert_eq!(part_of_at_most([10, 360, 1], 3_599), [10, 359, 1]);
        assert_eq!(part_of_at_most([10, 360, 1], 7), [7, 1, 1]);
        assert_eq!(part_of_at_most([4, 4, 4], 40), [4, 4, 2]);
    }
}
