//! One program as a wgpu pipeline: the bind groups that give its sampler names the textures
//! [`crate::samplers`] resolves them to and its uniform blocks (filled by reflection),
//! its vertex attributes, blend and depth state. The whole-frame renderer ([`super::frame`]) and
//! the composite-only runner ([`crate::composite_only`]) both build their programs here.

use std::borrow::Cow;
use std::collections::{BTreeMap, BTreeSet};

use wgpu::util::DeviceExt as _;

use tidepack_loader::directives::{Blend, BlendFactor, TextureTarget};
use tidepack_scene::mesh::{self, AttributeFormat, Sprites, offsets};

use crate::HarnessError;
use crate::program::{CustomTexture, LoadedProgram, LoadedStage, PackResources};
use crate::raw_texture::Texels;
use crate::samplers::{self, ProgramStage, SamplerNaming, Source};
use crate::uniforms::{self, Value};

use super::Gpu;

/// The format of a full-screen program's colortex0 output: RGBA32F, so NaN and Inf survive to
/// the readback.
pub(crate) const OUT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
/// The depth buffer gbuffers programs test and write.
pub(crate) const DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// `module` with every `uniform` global moved to read-only storage. Types, member offsets and
/// bindings are unchanged, so the bytes [`uniforms::fill_block`] lays out read the same.
///
/// Lavapipe may recompile a shader with the current values of the uniform-buffer members its
/// `if` conditions test (`isEyeInWater`) at every draw, and some versions never free the copies
/// (about 3 MB a frame); storage buffers are never inlined. The image is the same bit for bit
/// (crates/stress/tests/memory.rs).
fn uniforms_as_storage(module: &naga::Module) -> naga::Module {
    let mut module = module.clone();
    for (_, global) in module.global_variables.iter_mut() {
        if global.space == naga::AddressSpace::Uniform {
            global.space = naga::AddressSpace::Storage { access: naga::StorageAccess::LOAD };
        }
    }
    module
}

/// How the programs' uniform blocks are bound.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum UniformBinding {
    /// As the program declares them (`uniform` blocks), for comparison: lavapipe may recompile
    /// the shader with the blocks' values inlined at every draw (see [`uniforms_as_storage`]).
    Uniform,
    /// The same blocks as read-only storage buffers: no per-draw recompilation, no growth.
    #[default]
    ReadOnlyStorage,
}

/// A view of `t`'s first mip level: what is drawn into, and what a program that does not ask
/// for mipmaps reads.
pub(crate) fn view(t: &wgpu::Texture) -> wgpu::TextureView {
    t.create_view(&wgpu::TextureViewDescriptor { mip_level_count: Some(1), ..Default::default() })
}

/// A view of every mip level of `t`.
pub(crate) fn mipmapped_view(t: &wgpu::Texture) -> wgpu::TextureView {
    t.create_view(&wgpu::TextureViewDescriptor::default())
}

/// The harness's own textures (atlas, lightmap, noise), the pack's custom textures, and the
/// samplers OptiFine gives each kind.
pub(crate) struct HarnessTextures {
    atlas: wgpu::TextureView,
    sun: wgpu::TextureView,
    moon: wgpu::TextureView,
    lightmap: wgpu::TextureView,
    noise: wgpu::TextureView,
    nearest_repeat: wgpu::Sampler,
    linear_repeat: wgpu::Sampler,
    linear_clamp: wgpu::Sampler,
    /// Linear between mip levels too (`GL_LINEAR_MIPMAP_LINEAR`), for mipmapped buffers.
    linear_mipmap_clamp: wgpu::Sampler,
    nearest_clamp: wgpu::Sampler,
    comparison: wgpu::Sampler,
    flat_normals: wgpu::TextureView,
    no_specular: wgpu::TextureView,
    /// One white texel: what a shadow colour buffer the frame lacks reads (the white of its
    /// clear), and a shadow map nothing was drawn into as `sampler2D` reads it (depth 1).
    white: wgpu::Texture,
    /// A shadow map nothing was drawn into: depth 1 everywhere.
    pub(crate) empty_shadow_depth: wgpu::Texture,
    /// The sampler of shadow maps read through `sampler2D`: linear unless `shadowtexNearest`.
    shadow_depth_sampler: wgpu::Sampler,
    unbound: wgpu::TextureView,
    /// Per custom texture of the pack: its view, the sampler its properties ask for, and whether
    /// it filters.
    custom: Vec<(wgpu::TextureView, wgpu::Sampler, bool)>,
}

impl HarnessTextures {
    pub(crate) fn new(gpu: &Gpu, pack: &dyn PackResources) -> HarnessTextures {
        let upload_texture = |label: &str, (w, h, data): (u32, u32, Vec<u8>)| {
            let size = wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 };
            texture_with_data(gpu, label, size, wgpu::TextureDimension::D2, wgpu::TextureFormat::Rgba8Unorm, &data)
        };
        let upload = |label: &str, image: (u32, u32, Vec<u8>)| view(&upload_texture(label, image));
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
            .custom_textures()
            .iter()
            .map(|t| {
                let filter = if t.blur { wgpu::FilterMode::Linear } else { wgpu::FilterMode::Nearest };
                let address = if t.clamp { wgpu::AddressMode::ClampToEdge } else { wgpu::AddressMode::Repeat };
                let (view, filters) = custom_texture(gpu, t);
                (view, sampler(filter, address), filters)
            })
            .collect();
        let one_texel = |label: &str, rgba: [u8; 4]| upload(label, (1, 1, rgba.to_vec()));
        HarnessTextures {
            custom,
            // `shadowHardwareFiltering` filters the comparison's results.
            comparison: {
                let filter = if pack.shadow_settings().hardware_filtering { wgpu::FilterMode::Linear } else { wgpu::FilterMode::Nearest };
                gpu.device.create_sampler(&wgpu::SamplerDescriptor {
                    compare: Some(wgpu::CompareFunction::LessEqual),
                    mag_filter: filter,
                    min_filter: filter,
                    ..Default::default()
                })
            },
            flat_normals: one_texel("normals (flat)", [128, 128, 255, 255]),
            no_specular: one_texel("specular (none)", [0, 0, 0, 0]),
            white: upload_texture("white: shadowcolor and shadowtex, nothing drawn", (1, 1, vec![255; 4])),
            unbound: one_texel("a sampler OptiFine binds nothing to", [0; 4]),
            empty_shadow_depth: empty_depth(gpu),
            shadow_depth_sampler: if pack.shadow_settings().nearest {
                sampler(wgpu::FilterMode::Nearest, wgpu::AddressMode::ClampToEdge)
            } else {
                sampler(wgpu::FilterMode::Linear, wgpu::AddressMode::ClampToEdge)
            },
            atlas: upload("gtexture (block atlas)", mesh::atlas()),
            sun: upload("gtexture (sun)", mesh::sun()),
            moon: upload("gtexture (moon)", mesh::moon()),
            lightmap: upload("lightmap", mesh::lightmap()),
            noise: upload("noisetex", mesh::noise(256)),
            nearest_repeat: sampler(wgpu::FilterMode::Nearest, wgpu::AddressMode::Repeat),
            linear_repeat: sampler(wgpu::FilterMode::Linear, wgpu::AddressMode::Repeat),
            linear_clamp: sampler(wgpu::FilterMode::Linear, wgpu::AddressMode::ClampToEdge),
            nearest_clamp: sampler(wgpu::FilterMode::Nearest, wgpu::AddressMode::ClampToEdge),
            linear_mipmap_clamp: gpu.device.create_sampler(&wgpu::SamplerDescriptor {
                mag_filter: wgpu::FilterMode::Linear,
                min_filter: wgpu::FilterMode::Linear,
                mipmap_filter: wgpu::MipmapFilterMode::Linear,
                ..Default::default()
            }),
        }
    }
}

/// Runs `f`, turning a panic into an error about `what`. naga's SPIR-V writer, run by wgpu
/// when it makes a shader module or pipeline, panics on some modules naga's validator passed:
/// that is a program the harness cannot run, not a crash of the tool.
fn without_panics<T>(what: &str, f: impl FnOnce() -> Result<T, HarnessError>) -> Result<T, HarnessError> {
    // The panic becomes the error below: the default hook's report on stderr would read as a
    // crash.
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(f));
    std::panic::set_hook(hook);
    outcome.unwrap_or_else(|panic| {
        let why = panic.downcast_ref::<String>().cloned().or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()));
        Err(HarnessError::Unsupported(format!(
            "{what}: naga cannot translate the lowered program for wgpu ({})",
            why.unwrap_or_else(|| "no message".into())
        )))
    })
}

/// A custom texture of the pack as wgpu holds it, RGBA8 or RGBA32F: its view and whether it
/// filters.
fn custom_texture(gpu: &Gpu, t: &CustomTexture) -> (wgpu::TextureView, bool) {
    let format = match t.texels {
        Texels::Rgba8(_) => wgpu::TextureFormat::Rgba8Unorm,
        Texels::Float(_) => wgpu::TextureFormat::Rgba32Float,
    };
    let (dimension, view_dimension) = match t.target {
        TextureTarget::D1 => (wgpu::TextureDimension::D1, wgpu::TextureViewDimension::D1),
        TextureTarget::D3 => (wgpu::TextureDimension::D3, wgpu::TextureViewDimension::D3),
        TextureTarget::D2 | TextureTarget::Rectangle => (wgpu::TextureDimension::D2, wgpu::TextureViewDimension::D2),
    };
    let size = wgpu::Extent3d { width: t.width, height: t.height, depth_or_array_layers: t.depth };
    let texture = texture_with_data(gpu, &t.path, size, dimension, format, t.texels.bytes());
    let view = texture.create_view(&wgpu::TextureViewDescriptor { dimension: Some(view_dimension), ..Default::default() });
    (view, gpu.filterable(format))
}

/// A single-level texture the harness samples, filled with `data` (layer after layer).
fn texture_with_data(gpu: &Gpu, label: &str, size: wgpu::Extent3d, dimension: wgpu::TextureDimension, format: wgpu::TextureFormat, data: &[u8]) -> wgpu::Texture {
    gpu.device.create_texture_with_data(
        &gpu.queue,
        &wgpu::TextureDescriptor {
            label: Some(label),
            size,
            mip_level_count: 1,
            sample_count: 1,
            dimension,
            format,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        data,
    )
}

/// An empty (zero) texture of a shader's texture type other than a plain 2D float texture:
/// its view, sample type and dimension; `None` for storage images and multisampled textures.
fn empty_texture_of(
    gpu: &Gpu,
    dim: naga::ImageDimension,
    arrayed: bool,
    class: &naga::ImageClass,
) -> Option<(wgpu::TextureView, wgpu::TextureSampleType, wgpu::TextureViewDimension)> {
    let (format, sample_type) = match class {
        naga::ImageClass::Sampled { kind: naga::ScalarKind::Float, multi: false } => {
            (wgpu::TextureFormat::Rgba8Unorm, wgpu::TextureSampleType::Float { filterable: true })
        }
        naga::ImageClass::Sampled { kind: naga::ScalarKind::Sint, multi: false } => (wgpu::TextureFormat::Rgba32Sint, wgpu::TextureSampleType::Sint),
        naga::ImageClass::Sampled { kind: naga::ScalarKind::Uint, multi: false } => (wgpu::TextureFormat::Rgba32Uint, wgpu::TextureSampleType::Uint),
        naga::ImageClass::Depth { multi: false } => (DEPTH, wgpu::TextureSampleType::Depth),
        _ => return None,
    };
    let (dimension, view_dimension, layers) = match (dim, arrayed) {
        (naga::ImageDimension::D1, false) => (wgpu::TextureDimension::D1, wgpu::TextureViewDimension::D1, 1),
        (naga::ImageDimension::D2, false) => (wgpu::TextureDimension::D2, wgpu::TextureViewDimension::D2, 1),
        (naga::ImageDimension::D2, true) => (wgpu::TextureDimension::D2, wgpu::TextureViewDimension::D2Array, 1),
        (naga::ImageDimension::D3, false) => (wgpu::TextureDimension::D3, wgpu::TextureViewDimension::D3, 1),
        (naga::ImageDimension::Cube, false) => (wgpu::TextureDimension::D2, wgpu::TextureViewDimension::Cube, 6),
        (naga::ImageDimension::Cube, true) => (wgpu::TextureDimension::D2, wgpu::TextureViewDimension::CubeArray, 6),
        _ => return None,
    };
    if format == DEPTH && dimension != wgpu::TextureDimension::D2 {
        return None;
    }
    let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("a texture the harness does not make (empty)"),
        size: wgpu::Extent3d { width: 1, height: 1, depth_or_array_layers: layers },
        mip_level_count: 1,
        sample_count: 1,
        dimension,
        format,
        usage: wgpu::TextureUsages::TEXTURE_BINDING,
        view_formats: &[],
    });
    let view = texture.create_view(&wgpu::TextureViewDescriptor { dimension: Some(view_dimension), ..Default::default() });
    Some((view, sample_type, view_dimension))
}

/// A 1x1 depth texture cleared to 1: a shadow map nothing was drawn into.
fn empty_depth(gpu: &Gpu) -> wgpu::Texture {
    let texture = gpu.texture(
        "shadowtex (nothing drawn)",
        wgpu::Extent3d { width: 1, height: 1, depth_or_array_layers: 1 },
        DEPTH,
        wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
    );
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("shadowtex clear"),
        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
            view: &view(&texture),
            depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(1.0), store: wgpu::StoreOp::Store }),
            stencil_ops: None,
        }),
        ..Default::default()
    });
    gpu.queue.submit([encoder.finish()]);
    texture
}

/// Everything a program's samplers can be bound to: the harness's textures and the frame's
/// buffers. Depth textures may be any single-channel float format (Depth32Float when drawn
/// into, R32Float when the caller uploads depth values); both bind unfilterable.
pub(crate) struct BindableTextures<'a> {
    pub naming: SamplerNaming,
    pub harness: &'a HarnessTextures,
    pub colors: &'a BTreeMap<u8, (wgpu::Texture, wgpu::TextureFormat)>,
    pub depth0: &'a wgpu::Texture,
    pub depth1: &'a wgpu::Texture,
    /// depth0 and depth1 as a colour lookup reads them where a program uses more than its first
    /// channel: RGBA32F (d, d, d, 1), as OptiFine's compatibility profile reads depth
    /// (`GL_DEPTH_TEXTURE_MODE` `GL_LUMINANCE`); wgpu has no swizzle. Set when such a program
    /// binds them: the caller keeps them current then.
    pub depth_read: DepthRead<'a>,
    /// dhDepthTex0 and dhDepthTex1.
    pub lod_depth: [&'a wgpu::Texture; 2],
    pub shadow: ShadowTextures<'a>,
    /// What `gtexture` holds.
    pub sprites: Sprites,
    /// Colour buffers read with their mipmaps.
    pub mipmapped: &'a BTreeSet<u8>,
}

/// The copies of [`BindableTextures::depth_read`], and whether a program bound them.
#[derive(Clone, Copy)]
pub(crate) struct DepthRead<'a> {
    pub textures: [&'a wgpu::Texture; 2],
    pub bound: &'a std::cell::Cell<bool>,
}

/// No buffers read with mipmaps.
pub(crate) static NO_MIPMAPS: BTreeSet<u8> = BTreeSet::new();

/// The shadow maps a program reads: shadowtex0 and shadowtex1, as depth (for `sampler2DShadow`)
/// and as `sampler2D` reads them (RGBA32F (d, d, d, 1): wgpu has no depth swizzle), and the
/// shadow colour buffers by number (one the frame lacks reads white).
#[derive(Clone, Copy)]
pub(crate) struct ShadowTextures<'a> {
    pub depth: [&'a wgpu::Texture; 2],
    pub depth_read: [&'a wgpu::Texture; 2],
    pub colours: &'a BTreeMap<u8, (wgpu::Texture, wgpu::TextureFormat)>,
}

/// No shadow colour buffers.
pub(crate) static NO_SHADOW_COLOURS: BTreeMap<u8, (wgpu::Texture, wgpu::TextureFormat)> = BTreeMap::new();

impl<'a> ShadowTextures<'a> {
    /// Shadow maps nothing was drawn into.
    pub(crate) fn empty(harness: &'a HarnessTextures) -> ShadowTextures<'a> {
        ShadowTextures { depth: [&harness.empty_shadow_depth; 2], depth_read: [&harness.white; 2], colours: &NO_SHADOW_COLOURS }
    }
}

impl BindableTextures<'_> {
    fn resolve(&self, pack: &dyn PackResources, name: &str, stage: ProgramStage) -> Result<Source, String> {
        self.naming.resolve(pack, name, stage)
    }

    /// The view of `source` and whether it filters; `compared`: for a `sampler2DShadow`.
    fn texture(&self, gpu: &Gpu, source: Source, compared: bool) -> Result<(wgpu::TextureView, bool), String> {
        let harness = self.harness;
        Ok(match source {
            Source::FlatNormals => (harness.flat_normals.clone(), true),
            Source::NoSpecular => (harness.no_specular.clone(), true),
            Source::ShadowColour(n) => match self.shadow.colours.get(&n) {
                Some((t, format)) => (view(t), gpu.filterable(*format)),
                None => (view(&harness.white), true),
            },
            Source::Unbound => (harness.unbound.clone(), true),
            Source::ShadowDepth(n) if compared => (view(self.shadow.depth[n as usize]), false),
            Source::ShadowDepth(n) => {
                let texture = self.shadow.depth_read[n as usize];
                (view(texture), gpu.filterable(texture.format()))
            }
            Source::Atlas => match self.sprites {
                Sprites::Blocks => (harness.atlas.clone(), true),
                Sprites::Sun => (harness.sun.clone(), true),
                Sprites::Moon => (harness.moon.clone(), true),
            },
            Source::BlockAtlas => (harness.atlas.clone(), true),
            Source::Lightmap => (harness.lightmap.clone(), true),
            Source::Noise => (harness.noise.clone(), true),
            Source::Custom(i) => (harness.custom[i].0.clone(), harness.custom[i].2),
            Source::Depth0 => (view(self.depth0), false),
            Source::Depth1 => (view(self.depth1), false),
            Source::LodDepth(n) => (view(self.lod_depth[n as usize]), false),
            Source::Color(n) => {
                let (t, format) = self.colors.get(&n).ok_or_else(|| format!("colortex{n} is not a buffer of this frame"))?;
                let filters = gpu.filterable(*format);
                (if filters && self.mipmapped.contains(&n) { mipmapped_view(t) } else { view(t) }, filters)
            }
        })
    }

    /// The sampler OptiFine gives `source`: the atlas nearest and repeating, noise linear and
    /// repeating, the lightmap linear and clamped, buffers linear where they filter, nearest
    /// otherwise; shadow maps as `shadowtexNearest` says; custom textures as their properties
    /// say.
    fn sampler(&self, source: Source, filters: bool) -> wgpu::Sampler {
        let harness = self.harness;
        match source {
            _ if !filters => harness.nearest_clamp.clone(),
            Source::Custom(i) => harness.custom[i].1.clone(),
            Source::Atlas | Source::BlockAtlas => harness.nearest_repeat.clone(),
            Source::Noise => harness.linear_repeat.clone(),
            Source::Lightmap | Source::FlatNormals | Source::NoSpecular | Source::Unbound => harness.linear_clamp.clone(),
            Source::Color(n) if self.mipmapped.contains(&n) => harness.linear_mipmap_clamp.clone(),
            Source::Color(_) | Source::ShadowColour(_) if filters => harness.linear_clamp.clone(),
            Source::ShadowDepth(_) => harness.shadow_depth_sampler.clone(),
            _ => harness.nearest_clamp.clone(),
        }
    }
}

/// How a gbuffers draw blends into each colour buffer, and whether it writes depth.
pub(crate) struct DrawState<'a> {
    pub blend_of: &'a dyn Fn(u8) -> Blend,
    pub depth_write: bool,
}

/// What kind of pass a program runs in.
pub(crate) enum PassKind<'a> {
    /// Geometry into the frame's colour buffers (which must hold every render target) and
    /// depthtex0.
    Gbuffers(&'a DrawState<'a>),
    /// A full-screen quad into buffers of the given formats, blended as `blend_of` says; no
    /// depth.
    FullscreenInto { formats: &'a BTreeMap<u8, wgpu::TextureFormat>, blend_of: &'a dyn Fn(u8) -> Blend },
    /// A full-screen quad: colortex0 goes to an [`OUT`] target, other render targets to
    /// alternate buffers of their declared formats; no depth.
    Fullscreen { width: u32, height: u32 },
}

enum Entry {
    Uniform(wgpu::Buffer),
    /// A pack's own buffer block (Iris's `bufferObject`), zero-filled; read-only or not.
    Storage(wgpu::Buffer, bool),
    Texture(wgpu::TextureView, wgpu::TextureSampleType, wgpu::TextureViewDimension),
    Sampler(wgpu::Sampler, wgpu::SamplerBindingType),
}

/// Every binding of `program`'s stages, by group and binding: its textures and samplers
/// ([`stage_entries`]) and each stage's uniform block filled from `values`; with the uniform
/// buffers by stage and, for any pack, the uniforms left zero.
#[allow(clippy::type_complexity)]
fn binding_entries(
    gpu: &Gpu,
    pack: &dyn PackResources,
    program: &LoadedProgram,
    values: &BTreeMap<String, Value>,
    textures: &BindableTextures,
) -> Result<(BindingGroups, Vec<(tidepack_glsl::Stage, wgpu::Buffer)>, Vec<String>), HarnessError> {
    let device = &gpu.device;
    let mut groups: BindingGroups = BTreeMap::new();
    let mut uniform_buffers = Vec::new();
    let mut zeroed_uniforms = Vec::new();
    let mut fill = |module: &naga::Module, values: &BTreeMap<String, Value>, path: &str| {
        uniforms::fill_block_leaving_zero(module, values, path).map(|(block, zeroed)| {
            zeroed_uniforms.extend(zeroed);
            block
        })
    };
    for stage in [&program.vertex, &program.fragment] {
        let visibility = match stage.stage {
            tidepack_glsl::Stage::Vertex => wgpu::ShaderStages::VERTEX,
            tidepack_glsl::Stage::Fragment => wgpu::ShaderStages::FRAGMENT,
        };
        let mut entries = stage_entries(gpu, pack, stage, ProgramStage::of(&program.name), textures)?;
        if let Some(block) = fill(stage.module()?, &uniforms::with_initializers(values, &stage.interface), &stage.path)? {
            let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(&format!("{} uniforms", stage.path)),
                contents: &block.bytes,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            });
            uniform_buffers.push((stage.stage, buffer.clone()));
            entries.push((block.group, block.binding, Entry::Uniform(buffer)));
        }
        for (group, binding, entry) in entries {
            let slots = groups.entry(group).or_default();
            match (slots.get_mut(&binding), entry) {
                // A buffer block both stages declare at one binding is one buffer that both
                // see, as in OpenGL: the larger of the two, read-only where both only read.
                (Some((seen_by, Entry::Storage(kept, kept_read_only))), Entry::Storage(buffer, read_only)) => {
                    *seen_by |= visibility;
                    if buffer.size() > kept.size() {
                        *kept = buffer;
                    }
                    *kept_read_only &= read_only;
                }
                (Some(_), _) => return Err(HarnessError::Pack(format!("{}: binding {group}.{binding} used twice", stage.path))),
                (None, entry) => {
                    slots.insert(binding, (visibility, entry));
                }
            }
        }
    }
    Ok((groups, uniform_buffers, zeroed_uniforms))
}

/// Bindings by group, then binding: the stages that see each and what is bound.
type BindingGroups = BTreeMap<u32, BTreeMap<u32, (wgpu::ShaderStages, Entry)>>;

/// The bind group layouts and bind groups of `groups`, every group number up to the highest
/// (an unused one empty); uniform blocks bound as read-only storage where `storage`.
fn bind_groups(device: &wgpu::Device, name: &str, mut groups: BindingGroups, storage: bool) -> (Vec<wgpu::BindGroupLayout>, Vec<wgpu::BindGroup>) {
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
                        ty: if storage { wgpu::BufferBindingType::Storage { read_only: true } } else { wgpu::BufferBindingType::Uniform },
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    Entry::Storage(_, read_only) => wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Storage { read_only: *read_only },
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    Entry::Texture(_, sample_type, view_dimension) => wgpu::BindingType::Texture {
                        sample_type: *sample_type,
                        view_dimension: *view_dimension,
                        multisampled: false,
                    },
                    Entry::Sampler(_, ty) => wgpu::BindingType::Sampler(*ty),
                },
                count: None,
            })
            .collect();
        let label = format!("{name} set {g}");
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some(&label), entries: &layout_entries });
        let group_entries: Vec<wgpu::BindGroupEntry> = entries
            .iter()
            .map(|(binding, (_, entry))| wgpu::BindGroupEntry {
                binding: *binding,
                resource: match entry {
                    Entry::Uniform(b) | Entry::Storage(b, _) => b.as_entire_binding(),
                    Entry::Texture(v, ..) => wgpu::BindingResource::TextureView(v),
                    Entry::Sampler(s, _) => wgpu::BindingResource::Sampler(s),
                },
            })
            .collect();
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor { label: Some(&label), layout: &layout, entries: &group_entries });
        layouts.push(layout);
        bind_groups.push(group);
    }
    (layouts, bind_groups)
}

/// The colour targets of `program`'s render targets in `kind`, and the alternate textures a
/// [`PassKind::Fullscreen`] program writes besides colortex0.
#[allow(clippy::type_complexity)]
fn color_targets(
    gpu: &Gpu,
    pack: &dyn PackResources,
    program: &LoadedProgram,
    kind: &PassKind,
    textures: &BindableTextures,
) -> Result<(Vec<Option<wgpu::ColorTargetState>>, BTreeMap<u8, wgpu::Texture>), HarnessError> {
    let mut alternates = BTreeMap::new();
    let mut color_targets = Vec::new();
    for (location, &b) in program.render_targets.iter().enumerate() {
        // An output drawn into no buffer (`N`) has no target.
        let Some(b) = b else {
            color_targets.push(None);
            continue;
        };
        // A target the fragment stage has no output for is left as it is.
        let location = location as u32;
        let write_mask = match program.fragment.narrow_outputs.get(&location) {
            _ if !program.fragment.interface.outputs.contains_key(&location) => wgpu::ColorWrites::empty(),
            Some(1) => wgpu::ColorWrites::RED,
            Some(2) => wgpu::ColorWrites::RED | wgpu::ColorWrites::GREEN,
            Some(3) => wgpu::ColorWrites::COLOR,
            _ => wgpu::ColorWrites::ALL,
        };
        let (format, blend) = match kind {
            PassKind::Gbuffers(state) => {
                let (_, format) = textures.colors.get(&b).ok_or_else(|| {
                    HarnessError::Unsupported(format!("{} writes colortex{b}, which is not a buffer of this frame", program.name))
                })?;
                (*format, wgpu_blend(&(state.blend_of)(b)))
            }
            PassKind::FullscreenInto { formats, blend_of } => {
                let format = formats.get(&b).ok_or_else(|| {
                    HarnessError::Unsupported(format!("{} writes colortex{b}, which is not a buffer of this frame", program.name))
                })?;
                (*format, wgpu_blend(&blend_of(b)))
            }
            PassKind::Fullscreen { .. } if b == 0 => (OUT, None),
            PassKind::Fullscreen { width, height } => {
                let format = gpu.texture_format(pack.format_of(b))?;
                let size = wgpu::Extent3d { width: *width, height: *height, depth_or_array_layers: 1 };
                let t = gpu.texture(&format!("colortex{b} alternate"), size, format, wgpu::TextureUsages::RENDER_ATTACHMENT);
                alternates.insert(b, t);
                (format, None)
            }
        };
        color_targets.push(Some(wgpu::ColorTargetState { format, blend, write_mask }));
    }
    Ok((color_targets, alternates))
}

/// One program of the pack as a wgpu pipeline with its bind groups.
pub(crate) struct ProgramPipeline {
    pub pipeline: wgpu::RenderPipeline,
    pub bind_groups: Vec<wgpu::BindGroup>,
    /// Alternate buffers a full-screen program writes (other than colortex0).
    pub alternates: BTreeMap<u8, wgpu::Texture>,
    /// The uniform block of each stage that has one, for [`ProgramPipeline::write_uniforms`].
    uniform_buffers: Vec<(tidepack_glsl::Stage, wgpu::Buffer)>,
    /// The zero element the vertex inputs the harness does not provide read.
    zero_vertex: Option<wgpu::Buffer>,
    /// Those inputs, by name.
    pub zeroed_inputs: Vec<String>,
    /// Any pack's uniforms left zero (no value, or another type than the loader sets), by
    /// shipped name with the reason where there is one.
    pub zeroed_uniforms: Vec<String>,
}

impl ProgramPipeline {
    /// Builds `program` with its uniform blocks filled from `values` (every member must have
    /// one) and its samplers bound to `textures`.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn new(
        gpu: &Gpu,
        pack: &dyn PackResources,
        program: &LoadedProgram,
        values: &BTreeMap<String, Value>,
        kind: PassKind,
        textures: &BindableTextures,
        uniform_binding: UniformBinding,
    ) -> Result<ProgramPipeline, HarnessError> {
        if let Some(cannot) = program.wgpu_cannot_draw() {
            return Err(cannot);
        }
        let device = &gpu.device;
        let storage = uniform_binding == UniformBinding::ReadOnlyStorage;
        let (groups, uniform_buffers, zeroed_uniforms) = binding_entries(gpu, pack, program, values, textures)?;
        let (layouts, bind_groups) = bind_groups(device, &program.name, groups, storage);
        let layout_refs: Vec<Option<&wgpu::BindGroupLayout>> = layouts.iter().map(Some).collect();
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(&program.name),
            bind_group_layouts: &layout_refs,
            immediate_size: 0,
        });

        let VertexInputs { known: attributes, zeroed: zeroed_attributes, zeroed_names: zeroed } =
            vertex_attributes(&program.vertex);
        let zero_vertex = (!zeroed_attributes.is_empty()).then(|| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(&format!("{} inputs the harness does not provide (zero)", program.name)),
                contents: &[0u8; 16],
                usage: wgpu::BufferUsages::VERTEX,
            })
        });
        let (color_targets, alternates) = color_targets(gpu, pack, program, &kind, textures)?;
        let shader_module = |stage: &LoadedStage| {
            let module = if storage { uniforms_as_storage(stage.module()?) } else { stage.module()?.clone() };
            without_panics(&stage.path, || {
                gpu.checked(&format!("{} (wgpu shader module)", stage.path), || {
                    device.create_shader_module(wgpu::ShaderModuleDescriptor {
                        label: Some(&stage.path),
                        source: wgpu::ShaderSource::Naga(Cow::Owned(module)),
                    })
                })
            })
        };
        let vertex_module = shader_module(&program.vertex)?;
        let fragment_module = shader_module(&program.fragment)?;
        let depth_stencil = match &kind {
            PassKind::Gbuffers(state) => Some(wgpu::DepthStencilState {
                format: DEPTH,
                depth_write_enabled: Some(state.depth_write),
                depth_compare: Some(wgpu::CompareFunction::LessEqual),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            PassKind::Fullscreen { .. } | PassKind::FullscreenInto { .. } => None,
        };
        let pipeline = without_panics(&program.name, || gpu.checked(&format!("{} (wgpu pipeline)", program.name), || {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(&program.name),
                layout: Some(&pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &vertex_module,
                    entry_point: Some("main"),
                    compilation_options: Default::default(),
                    buffers: &[
                        Some(wgpu::VertexBufferLayout {
                            array_stride: offsets::STRIDE,
                            step_mode: wgpu::VertexStepMode::Vertex,
                            attributes: &attributes,
                        }),
                        // One zero element for every instance: the inputs read zero at every vertex.
                        (!zeroed_attributes.is_empty()).then_some(wgpu::VertexBufferLayout {
                            array_stride: 16,
                            step_mode: wgpu::VertexStepMode::Instance,
                            attributes: &zeroed_attributes,
                        }),
                    ],
                },
                // `adapt_vertex` flips y, which turns OpenGL's counter-clockwise front faces
                // clockwise: gl_FrontFacing keeps OpenGL's meaning.
                primitive: wgpu::PrimitiveState { cull_mode: None, front_face: wgpu::FrontFace::Cw, ..Default::default() },
                depth_stencil,
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
        }))?;
        Ok(ProgramPipeline { pipeline, bind_groups, alternates, uniform_buffers, zero_vertex, zeroed_inputs: zeroed, zeroed_uniforms })
    }

    /// Rewrites the uniform blocks with `values`, for the next submission.
    pub(crate) fn write_uniforms(&self, gpu: &Gpu, program: &LoadedProgram, values: &BTreeMap<String, Value>) -> Result<(), HarnessError> {
        for (stage, buffer) in &self.uniform_buffers {
            let stage = if *stage == tidepack_glsl::Stage::Vertex { &program.vertex } else { &program.fragment };
            let block = uniforms::fill_block(stage.module()?, values, &stage.path)?
                .ok_or_else(|| HarnessError::Uniform(format!("{}: the uniform block is gone", stage.path)))?;
            gpu.queue.write_buffer(buffer, 0, &block.bytes);
        }
        Ok(())
    }

    /// Sets the pipeline and its bind groups on `pass`.
    pub(crate) fn bind(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_pipeline(&self.pipeline);
        for (i, group) in self.bind_groups.iter().enumerate() {
            pass.set_bind_group(i as u32, group, &[]);
        }
        if let Some(zero) = &self.zero_vertex {
            pass.set_vertex_buffer(1, zero.slice(..));
        }
    }

    /// Records `program`, a full-screen program built with [`PassKind::Fullscreen`], over the
    /// quad: colortex0 into `out`, other render targets into the alternates, all cleared first.
    pub(crate) fn record_fullscreen(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        program: &LoadedProgram,
        out: &wgpu::Texture,
        quad: &FullscreenQuad,
        timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) {
        let target = |b: u8| if b == 0 { out } else { &self.alternates[&b] };
        self.record_fullscreen_into(encoder, program, &target, wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT), quad, timestamp_writes);
    }

    /// Records a full-screen `program` over the quad into the texture `target` gives for each
    /// of its render targets, loaded as `load` says.
    pub(crate) fn record_fullscreen_into<'t>(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        program: &LoadedProgram,
        target: &dyn Fn(u8) -> &'t wgpu::Texture,
        load: wgpu::LoadOp<wgpu::Color>,
        quad: &FullscreenQuad,
        timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) {
        let views: Vec<Option<wgpu::TextureView>> = program.render_targets.iter().map(|b| b.map(|b| view(target(b)))).collect();
        let attachments: Vec<_> = views
            .iter()
            .map(|v| {
                Some(wgpu::RenderPassColorAttachment {
                    view: v.as_ref()?,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations { load, store: wgpu::StoreOp::Store },
                })
            })
            .collect();
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(&program.name),
            color_attachments: &attachments,
            timestamp_writes,
            ..Default::default()
        });
        self.bind(&mut pass);
        pass.set_vertex_buffer(0, quad.vertices.slice(..));
        pass.draw(0..quad.count, 0..1);
    }
}

/// A colour attachment cleared to transparent black.
pub(crate) fn clear_attachment(v: &wgpu::TextureView) -> wgpu::RenderPassColorAttachment<'_> {
    wgpu::RenderPassColorAttachment {
        view: v,
        depth_slice: None,
        resolve_target: None,
        ops: wgpu::Operations { load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT), store: wgpu::StoreOp::Store },
    }
}

/// The full-screen quad OptiFine draws for composite programs, uploaded.
pub(crate) struct FullscreenQuad {
    vertices: wgpu::Buffer,
    count: u32,
}

impl FullscreenQuad {
    pub(crate) fn new(gpu: &Gpu) -> FullscreenQuad {
        let quad = mesh::fullscreen_quad();
        let vertices = gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("full-screen quad"),
            contents: bytemuck::cast_slice(&quad),
            usage: wgpu::BufferUsages::VERTEX,
        });
        FullscreenQuad { vertices, count: quad.len() as u32 }
    }
}

pub(crate) fn wgpu_blend(blend: &Blend) -> Option<wgpu::BlendState> {
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

/// The wgpu format of a vertex attribute.
fn vertex_format(format: AttributeFormat) -> wgpu::VertexFormat {
    match format {
        AttributeFormat::Float32x2 => wgpu::VertexFormat::Float32x2,
        AttributeFormat::Float32x3 => wgpu::VertexFormat::Float32x3,
        AttributeFormat::Float32x4 => wgpu::VertexFormat::Float32x4,
        AttributeFormat::Sint32x2 => wgpu::VertexFormat::Sint32x2,
    }
}

/// A vertex stage's inputs bound to vertex buffers.
#[derive(Default)]
struct VertexInputs {
    /// Those of [`mesh::PackVertex`], buffer slot 0.
    known: Vec<wgpu::VertexAttribute>,
    /// The others, all reading a one-element zero buffer in slot 1.
    zeroed: Vec<wgpu::VertexAttribute>,
    zeroed_names: Vec<String>,
}

/// The vertex inputs a stage declares; those the harness's vertices lack are an error unless
/// `zero_unknown`.
fn vertex_attributes(stage: &LoadedStage) -> VertexInputs {
    let VertexInputs { mut known, mut zeroed, mut zeroed_names } = VertexInputs::default();
    for (name, location) in &stage.interface.inputs {
        if let Some((format, offset)) = mesh::input_source(name, stage.interface.declared_input_locations.get(name).copied()) {
            known.push(wgpu::VertexAttribute { format: vertex_format(format), offset, shader_location: *location });
        } else {
            let format = match stage.module().ok().and_then(|module| input_scalar_kind(module, *location)) {
                Some(naga::ScalarKind::Sint) => wgpu::VertexFormat::Sint32x4,
                Some(naga::ScalarKind::Uint) => wgpu::VertexFormat::Uint32x4,
                _ => wgpu::VertexFormat::Float32x4,
            };
            zeroed.push(wgpu::VertexAttribute { format, offset: 0, shader_location: *location });
            zeroed_names.push(name.clone());
        }
    }
    VertexInputs { known, zeroed, zeroed_names }
}

/// The scalar kind of the vertex entry point's input at `location`.
fn input_scalar_kind(module: &naga::Module, location: u32) -> Option<naga::ScalarKind> {
    let entry = module.entry_points.iter().find(|e| e.stage == naga::ShaderStage::Vertex)?;
    let argument = entry.function.arguments.iter().find(|a| matches!(a.binding, Some(naga::Binding::Location { location: l, .. }) if l == location))?;
    match module.types[argument.ty].inner {
        naga::TypeInner::Scalar(s) | naga::TypeInner::Vector { scalar: s, .. } => Some(s.kind),
        _ => None,
    }
}

/// The textures and samplers of a stage, each bound to what its name resolves to. Every name
/// the harness cannot bind is reported, all in one error.
fn stage_entries(
    gpu: &Gpu,
    pack: &dyn PackResources,
    stage: &LoadedStage,
    program_stage: ProgramStage,
    textures: &BindableTextures,
) -> Result<Vec<(u32, u32, Entry)>, HarnessError> {
    let module = stage.module()?;
    let mut entries = Vec::new();
    // A pack's own buffer blocks read zero, each program's its own, where no other program
    // shares them.
    {
        let mut layouter = naga::proc::Layouter::default();
        if layouter.update(module.to_ctx()).is_ok() {
            for (_, global) in module.global_variables.iter() {
                let (Some(binding), naga::AddressSpace::Storage { access }) = (&global.binding, global.space) else { continue };
                if pack.buffers_shared_across_programs() {
                    return Err(HarnessError::Unsupported(format!(
                        "{}: a buffer block of the pack's bufferObjects, which other programs share and the harness's wgpu frames give each program apart",
                        stage.path
                    )));
                }
                // A runtime-sized array at the end gets 1024 elements.
                let tail = match &module.types[global.ty].inner {
                    naga::TypeInner::Struct { members, .. } => members.last().map(|m| &module.types[m.ty].inner),
                    other => Some(other),
                };
                let extra = match tail {
                    Some(naga::TypeInner::Array { size: naga::ArraySize::Dynamic, stride, .. }) => *stride as u64 * 1024,
                    _ => 0,
                };
                let size = (layouter[global.ty].size as u64 + extra).max(16).next_multiple_of(16);
                let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some(&format!("{} buffer block (zero)", stage.path)),
                    size,
                    usage: wgpu::BufferUsages::STORAGE,
                    mapped_at_creation: false,
                });
                let read_only = !access.contains(naga::StorageAccess::STORE);
                entries.push((binding.group, binding.binding, Entry::Storage(buffer, read_only)));
            }
        }
    }
    // Textures first, so each sampler knows whether its texture filters.
    let mut resolved: BTreeMap<String, (Source, bool)> = BTreeMap::new();
    let mut problems = Vec::new();
    let mut beyond_wgpu = Vec::new();
    for (handle, global) in module.global_variables.iter() {
        let (Some(binding), Some(name)) = (&global.binding, &global.name) else { continue };
        if let Some(image) = pack.custom_images().iter().find(|i| i.sampler.as_deref() == Some(name.as_str())) {
            beyond_wgpu.push(format!("{name} reads the custom image {}, which the harness's wgpu frames do not hold", image.name));
            continue;
        }
        if let naga::TypeInner::Image { class, dim, arrayed, .. } = &module.types[global.ty].inner {
            // A shadow sampler's texture is a depth texture, sampled by comparison.
            let depth_class = matches!(class, naga::ImageClass::Depth { multi: false });
            if *dim != naga::ImageDimension::D2
                || *arrayed
                || !(depth_class || matches!(class, naga::ImageClass::Sampled { kind: naga::ScalarKind::Float, multi: false }))
            {
                // A 1D or 3D float sampler reads the unit's custom texture of its type.
                let target = match (dim, arrayed, class) {
                    (naga::ImageDimension::D1, false, naga::ImageClass::Sampled { kind: naga::ScalarKind::Float, multi: false }) => Some(TextureTarget::D1),
                    (naga::ImageDimension::D3, false, naga::ImageClass::Sampled { kind: naga::ScalarKind::Float, multi: false }) => Some(TextureTarget::D3),
                    _ => None,
                };
                if let Some(i) = target.and_then(|target| samplers::custom_texture_of(pack, name, program_stage, target)) {
                    let (view, _, filters) = &textures.harness.custom[i];
                    let view_dimension = if target == Some(TextureTarget::D1) { wgpu::TextureViewDimension::D1 } else { wgpu::TextureViewDimension::D3 };
                    resolved.insert(name.clone(), (Source::Custom(i), *filters));
                    entries.push((binding.group, binding.binding, Entry::Texture(view.clone(), wgpu::TextureSampleType::Float { filterable: *filters }, view_dimension)));
                    continue;
                }
                // Any pack's other 3D, array, cube and integer textures are images the harness
                // does not make: they read an empty texture of their kind.
                match empty_texture_of(gpu, *dim, *arrayed, class) {
                    Some((view, sample_type, dimension)) => {
                        let filters = matches!(sample_type, wgpu::TextureSampleType::Float { filterable: true });
                        resolved.insert(name.clone(), (Source::Unbound, filters));
                        entries.push((binding.group, binding.binding, Entry::Texture(view, sample_type, dimension)));
                    }
                    None if matches!(class, naga::ImageClass::Storage { .. }) => {
                        beyond_wgpu.push(format!("{name} is a storage image, which the harness's wgpu frames do not hold"))
                    }
                    None => problems.push(format!("texture {name} is not a plain sampler2D")),
                }
                continue;
            }
            let bound = textures.resolve(pack, name, program_stage).and_then(|source| {
                // A depth buffer whose lookups are used past their first channel reads as
                // luminance (see `BindableTextures::depth_read`).
                let read = match source {
                    Source::Depth0 | Source::Depth1 if !depth_class && tidepack_glsl::liveness::reads_beyond_first_channel(module, handle) => {
                        textures.depth_read.bound.set(true);
                        let texture = textures.depth_read.textures[usize::from(source == Source::Depth1)];
                        (view(texture), false)
                    }
                    _ => textures.texture(gpu, source, depth_class)?,
                };
                Ok((source, read))
            });
            match bound {
                Ok((source, _)) if depth_class && !matches!(source, Source::Depth0 | Source::Depth1 | Source::LodDepth(_) | Source::ShadowDepth(_)) => {
                    // OpenGL binds it (its results are undefined there) and draws the step.
                    beyond_wgpu.push(format!("{name} is read as a shadow sampler but is not a depth buffer, which wgpu cannot bind"));
                }
                Ok((source, (view, filters))) => {
                    resolved.insert(name.clone(), (source, filters));
                    let sample_type = if depth_class { wgpu::TextureSampleType::Depth } else { wgpu::TextureSampleType::Float { filterable: filters } };
                    entries.push((binding.group, binding.binding, Entry::Texture(view, sample_type, wgpu::TextureViewDimension::D2)));
                }
                Err(m) => problems.push(m),
            }
        }
    }
    for (_, global) in module.global_variables.iter() {
        let (Some(binding), Some(name)) = (&global.binding, &global.name) else { continue };
        if let naga::TypeInner::Sampler { comparison } = &module.types[global.ty].inner {
            let texture = name.strip_prefix("tp_sampler_").unwrap_or(name);
            let Some(&(source, filters)) = resolved.get(texture) else {
                // The lowering splits each GLSL sampler into a texture and this sampler: a
                // texture that could not be bound has said so already.
                if !problems.iter().chain(&beyond_wgpu).any(|p| p.contains(texture)) {
                    problems.push(format!("no texture is bound to the sampler {texture}"));
                }
                continue;
            };
            let (sampler, ty) = if *comparison {
                (textures.harness.comparison.clone(), wgpu::SamplerBindingType::Comparison)
            } else if filters {
                (textures.sampler(source, true), wgpu::SamplerBindingType::Filtering)
            } else {
                (textures.sampler(source, false), wgpu::SamplerBindingType::NonFiltering)
            };
            entries.push((binding.group, binding.binding, Entry::Sampler(sampler, ty)));
        }
    }
    if !problems.is_empty() {
        return Err(HarnessError::Uniform(format!("{}: {}", stage.path, problems.join("; "))));
    }
    if !beyond_wgpu.is_empty() {
        return Err(HarnessError::Unsupported(format!("{}: {}", stage.path, beyond_wgpu.join("; "))));
    }
    Ok(entries)
}
