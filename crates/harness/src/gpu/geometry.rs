//! Geometry drawn by a gbuffers program, or by the loader's own fixed-function colour where
//! the pack has no program for it.

use std::collections::BTreeMap;

use wgpu::util::DeviceExt as _;

use crate::HarnessError;
use tidepack_loader::loader::MissingProgramDraws;
use tidepack_scene::mesh;
use crate::program::{LoadedProgram, PackResources};
use tidepack_scene::scene::Scene;
use crate::uniforms::Value;

use super::Gpu;
use super::bindings::{BindableTextures, DrawState, PassKind, ProgramPipeline, UniformBinding, view, wgpu_blend};
use super::own::ColourPipeline;

/// Geometry drawn before composite by one program: the pack's, or the harness's own colour
/// shader where the pack has no program of the chain (drawing into the buffers the loader
/// would).
pub(crate) struct GeometryDraw {
    pub label: String,
    drawer: Drawer,
    buffers: Vec<Option<u8>>,
    vertices: wgpu::Buffer,
    count: u32,
}

enum Drawer {
    Pack(ProgramPipeline),
    Harness(ColourPipeline),
}

impl GeometryDraw {
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn new(
        gpu: &Gpu,
        pack: &dyn PackResources,
        missing: MissingProgramDraws,
        scene: &Scene,
        values: &BTreeMap<String, Value>,
        textures: &BindableTextures,
        program: Option<&LoadedProgram>,
        state: &DrawState,
        vertices: &[mesh::PackVertex],
        label: String,
    ) -> Result<GeometryDraw, HarnessError> {
        let (drawer, buffers) = match program {
            Some(program) => {
                let pipeline =
                    ProgramPipeline::new(gpu, pack, program, values, PassKind::Gbuffers(state), textures, UniformBinding::ReadOnlyStorage)?;
                (Drawer::Pack(pipeline), program.render_targets.clone())
            }
            None => {
                let buffers: Vec<u8> = match missing {
                    MissingProgramDraws::FirstBufferOnly => vec![0],
                    MissingProgramDraws::EveryBuffer => textures.colors.keys().copied().collect(),
                };
                let formats: Vec<(wgpu::TextureFormat, Option<wgpu::BlendState>)> =
                    buffers.iter().map(|b| (textures.colors[b].1, wgpu_blend(&(state.blend_of)(*b)))).collect();
                (Drawer::Harness(ColourPipeline::new(gpu, scene, &formats, state.depth_write)?), buffers.into_iter().map(Some).collect())
            }
        };
        // wgpu refuses empty buffers: an empty mesh uploads one unused vertex and draws nothing.
        let one = [mesh::PackVertex::default()];
        let vertices_buffer = gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(&label),
            contents: bytemuck::cast_slice(if vertices.is_empty() { &one } else { vertices }),
            usage: wgpu::BufferUsages::VERTEX,
        });
        Ok(GeometryDraw { label, drawer, buffers, vertices: vertices_buffer, count: vertices.len() as u32 })
    }

    /// The pack's pipeline, when the pack has a program for this draw.
    pub(crate) fn pipeline(&self) -> Option<&ProgramPipeline> {
        match &self.drawer {
            Drawer::Pack(pipeline) => Some(pipeline),
            Drawer::Harness(_) => None,
        }
    }

    /// The colour buffers the draw writes.
    pub(crate) fn buffers(&self) -> impl Iterator<Item = u8> + '_ {
        self.buffers.iter().flatten().copied()
    }

    /// Records the draw into the colour buffers `buffer` gives for each number and `depth0`.
    pub(crate) fn record<'t>(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        buffer: &dyn Fn(u8) -> &'t wgpu::Texture,
        depth0: &wgpu::Texture,
        timestamps: Option<wgpu::RenderPassTimestampWrites>,
    ) {
        let depth0_view = view(depth0);
        let views: Vec<Option<wgpu::TextureView>> = self.buffers.iter().map(|b| b.map(|b| view(buffer(b)))).collect();
        let attachments: Vec<_> = views.iter().map(|v| v.as_ref().map(load_attachment)).collect();
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(&self.label),
            color_attachments: &attachments,
            depth_stencil_attachment: Some(depth_attachment(&depth0_view, false)),
            timestamp_writes: timestamps,
            ..Default::default()
        });
        match &self.drawer {
            Drawer::Pack(program) => program.bind(&mut pass),
            Drawer::Harness(own) => own.bind(&mut pass),
        }
        pass.set_vertex_buffer(0, self.vertices.slice(..));
        if self.count > 0 {
            pass.draw(0..self.count, 0..1);
        }
    }
}

fn load_attachment(v: &wgpu::TextureView) -> wgpu::RenderPassColorAttachment<'_> {
    wgpu::RenderPassColorAttachment {
        view: v,
        depth_slice: None,
        resolve_target: None,
        ops: wgpu::Operations { load: wgpu::LoadOp::Load, store: wgpu::StoreOp::Store },
    }
}

pub(crate) fn depth_attachment(v: &wgpu::TextureView, clear: bool) -> wgpu::RenderPassDepthStencilAttachment<'_> {
    wgpu::RenderPassDepthStencilAttachment {
        view: v,
        depth_ops: Some(wgpu::Operations {
            load: if clear { wgpu::LoadOp::Clear(1.0) } else { wgpu::LoadOp::Load },
            store: wgpu::StoreOp::Store,
        }),
        stencil_ops: None,
    }
}
