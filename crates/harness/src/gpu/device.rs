//! The wgpu device the harness renders with, and what it can do: buffer formats, filtering,
//! the largest resolution, and the validation-error scope every call runs in.

use crate::HarnessError;
use tidepack_loader::buffers::BufferFormat;

use super::readback::readback_bytes;

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
            | wgpu::Features::TEXTURE_ADAPTER_SPECIFIC_FORMAT_FEATURES
            // A pack's buffer blocks may be written from a vertex stage, as OpenGL allows.
            | wgpu::Features::VERTEX_WRITABLE_STORAGE;
        let features = available & wanted;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("tidepack-harness"),
            required_features: features,
            // A gbuffers program may write 8 colour buffers at once, as in OptiFine: the
            // adapter's own attachment limits, not wgpu's portable 32 bytes a sample.
            required_limits: wgpu::Limits {
                max_color_attachments: adapter.limits().max_color_attachments,
                max_color_attachment_bytes_per_sample: adapter.limits().max_color_attachment_bytes_per_sample,
                // Packs pass more varyings than wgpu's portable 16 locations; GL drivers allow
                // 32 and more.
                max_inter_stage_shader_variables: adapter.limits().max_inter_stage_shader_variables,
                // The lowering numbers vertex inputs by their legacy slots (up to 24 and more).
                max_vertex_attributes: adapter.limits().max_vertex_attributes,
                // Packs sample more textures per stage than wgpu's portable 16.
                max_sampled_textures_per_shader_stage: adapter.limits().max_sampled_textures_per_shader_stage,
                max_samplers_per_shader_stage: adapter.limits().max_samplers_per_shader_stage,
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

    pub(crate) fn texture_format(&self, format: BufferFormat) -> Result<wgpu::TextureFormat, HarnessError> {
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
            BufferFormat::Rgba32Ui | BufferFormat::Rgba32I => {
                return Err(HarnessError::Unsupported(format!(
                    "the pack declares an integer buffer ({format:?}), which the harness's wgpu frames do not hold; OpenGL draws it"
                )));
            }
        })
    }

    pub(crate) fn filterable(&self, format: wgpu::TextureFormat) -> bool {
        format != wgpu::TextureFormat::Rgba32Float || self.float32_filterable
    }

    /// A single-level 2D texture of `size`.
    pub(crate) fn texture(&self, label: &str, size: wgpu::Extent3d, format: wgpu::TextureFormat, usage: wgpu::TextureUsages) -> wgpu::Texture {
        self.texture_with_levels(label, size, format, usage, 1)
    }

    /// A 2D texture of `size` with `levels` mip levels.
    pub(crate) fn texture_with_levels(
        &self,
        label: &str,
        size: wgpu::Extent3d,
        format: wgpu::TextureFormat,
        usage: wgpu::TextureUsages,
        levels: u32,
    ) -> wgpu::Texture {
        self.device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size,
            mip_level_count: levels,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage,
            view_formats: &[],
        })
    }

    /// Submits `encoder`'s commands and waits until the device has run them; the wall time
    /// that took, in ms.
    pub(crate) fn submit_and_wait(&self, encoder: wgpu::CommandEncoder) -> Result<f64, HarnessError> {
        let started = std::time::Instant::now();
        self.queue.submit([encoder.finish()]);
        self.device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| HarnessError::Wgpu(format!("waiting for the GPU: {e}")))?;
        Ok(started.elapsed().as_secs_f64() * 1000.0)
    }

    /// A command encoder of this device.
    pub(crate) fn encoder(&self) -> wgpu::CommandEncoder {
        self.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: None })
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
                if let Some(said) = varyings_past_the_limit(&message) {
                    message.push_str(&format!(": {said}"));
                }
                // wgpu quotes the lowered text's names; the pack author wrote the GLSL ones.
                Err(HarnessError::Wgpu(tidepack_glsl::lower::unlower_names(&message)))
            }
            None => Ok(value),
        }
    }
}

/// wgpu's refusal of a pipeline whose stages pass varyings at more locations than the adapter
/// has, said in GLSL's terms, or `None` for another error.
fn varyings_past_the_limit(message: &str) -> Option<String> {
    let rest = &message[message.find("output location Location[")? + "output location Location[".len()..];
    let location: u32 = rest[..rest.find(']')?].parse().ok()?;
    let limit_at = message.find("`max_inter_stage_shader_variables` limit (")? + "`max_inter_stage_shader_variables` limit (".len();
    let limit: u32 = message[limit_at..].split(|c: char| !c.is_ascii_digit()).next()?.parse().ok()?;
    Some(format!(
        "in GLSL terms, the vertex stage's varyings (one location per vec4, a matrix one per column) reach location {location}, and this \
         adapter passes {} (locations 0-{limit})",
        limit + 1
    ))
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_refusal_for_too_many_varyings_is_said_in_glsl_terms() {
        let wgpu = "gbuffers_terrain (wgpu pipeline): Validation Error: vertex shader output location Location[35] (Float32x4 interpolated as \
                    Some(Perspective) with sampling Some(Center)) exceeds the `max_inter_stage_shader_variables` limit (30, 0-based)";
        let said = super::varyings_past_the_limit(wgpu).expect("recognised");
        assert!(said.contains("reach location 35") && said.contains("passes 31 (locations 0-30)"), "{said}");
        assert_eq!(super::varyings_past_the_limit("Validation Error: Color state [2] is invalid"), None);
    }
}
