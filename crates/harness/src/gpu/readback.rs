//! Reading results back from the device: textures as floats, pass timestamps as milliseconds.

use half::f16;

use crate::HarnessError;
use crate::images::FloatImage;

use super::Gpu;

/// The GPU time in ms of each of `passes` timed passes, from their begin and end timestamps in
/// query order.
pub(crate) fn read_pass_ms(gpu: &Gpu, queries: &wgpu::QuerySet, passes: u32) -> Result<Vec<f64>, HarnessError> {
    let bytes = (passes * 2) as u64 * 8;
    let resolve = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("timestamp resolve"),
        size: bytes,
        usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let read = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("timestamp readback"),
        size: bytes,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    encoder.resolve_query_set(queries, 0..passes * 2, &resolve, 0);
    encoder.copy_buffer_to_buffer(&resolve, 0, &read, 0, bytes);
    gpu.queue.submit([encoder.finish()]);
    let data = map_read(gpu, &read)?;
    let ticks: Vec<u64> = data.chunks_exact(8).map(|c| u64::from_le_bytes(c.try_into().expect("8 bytes"))).collect();
    let period = gpu.queue.get_timestamp_period() as f64;
    Ok(ticks.chunks_exact(2).map(|t| t[1].saturating_sub(t[0]) as f64 * period / 1e6).collect())
}

fn map_read(gpu: &Gpu, buffer: &wgpu::Buffer) -> Result<Vec<u8>, HarnessError> {
    let (sender, receiver) = std::sync::mpsc::channel();
    buffer.map_async(wgpu::MapMode::Read, .., move |r| {
        let _ = sender.send(r);
    });
    gpu.device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| HarnessError::Wgpu(format!("waiting for a readback: {e}")))?;
    receiver
        .recv()
        .map_err(|_| HarnessError::Wgpu("readback callback dropped".into()))?
        .map_err(|e| HarnessError::Wgpu(format!("mapping a readback buffer: {e}")))?;
    let data = buffer
        .get_mapped_range(..)
        .map_err(|e| HarnessError::Wgpu(format!("reading a mapped buffer: {e:?}")))?
        .to_vec();
    buffer.unmap();
    Ok(data)
}

/// Bytes of the buffer [`read_texture`] needs for an RGBA32F texture of this size.
pub(crate) fn readback_bytes(width: u32, height: u32) -> u64 {
    (width as u64 * 16).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT as u64) * height as u64
}

/// Reads a texture back as floats, bottom row first (memory row 0 is OpenGL's bottom row).
pub fn read_texture(gpu: &Gpu, texture: &wgpu::Texture, format: wgpu::TextureFormat) -> Result<FloatImage, HarnessError> {
    let (w, h) = (texture.width(), texture.height());
    let texel = match format {
        wgpu::TextureFormat::Rgba8Unorm | wgpu::TextureFormat::Depth32Float => 4,
        wgpu::TextureFormat::Rgba16Unorm | wgpu::TextureFormat::Rgba16Float => 8,
        wgpu::TextureFormat::Rgba32Float => 16,
        other => return Err(HarnessError::Unsupported(format!("reading back {other:?}"))),
    };
    let row = (w * texel).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
    let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("texture readback"),
        size: (row * h) as u64,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(row), rows_per_image: Some(h) },
        },
        texture.size(),
    );
    gpu.queue.submit([encoder.finish()]);
    let data = map_read(gpu, &buffer)?;
    let mut image = FloatImage::new(w, h);
    for y in 0..h {
        for x in 0..w {
            let at = (y * row + x * texel) as usize;
            let p = &data[at..at + texel as usize];
            let px = match format {
                wgpu::TextureFormat::Rgba8Unorm => [0, 1, 2, 3].map(|c| p[c] as f32 / 255.0),
                wgpu::TextureFormat::Rgba16Unorm => [0, 1, 2, 3].map(|c| u16::from_le_bytes([p[2 * c], p[2 * c + 1]]) as f32 / 65535.0),
                wgpu::TextureFormat::Rgba16Float => [0, 1, 2, 3].map(|c| f16::from_le_bytes([p[2 * c], p[2 * c + 1]]).to_f32()),
                wgpu::TextureFormat::Rgba32Float => [0, 1, 2, 3].map(|c| f32::from_le_bytes(p[4 * c..4 * c + 4].try_into().expect("4 bytes"))),
                _ => {
                    let d = f32::from_le_bytes(p[0..4].try_into().expect("4 bytes"));
                    [d, d, d, 1.0]
                }
            };
            image.pixels[(y * w + x) as usize] = px;
        }
    }
    Ok(image)
}

/// Replaces level 0 of `texture` (of `format`, the image's size) with `image`, bottom row first
/// as [`read_texture`] gives it: unorm channels clamped and rounded, floats as they are.
pub(crate) fn write_texture(gpu: &Gpu, texture: &wgpu::Texture, format: wgpu::TextureFormat, image: &FloatImage) -> Result<(), HarnessError> {
    let (w, h) = (texture.width(), texture.height());
    if (image.width, image.height) != (w, h) {
        return Err(HarnessError::Wgpu(format!("a {}x{} image for a {w}x{h} texture", image.width, image.height)));
    }
    let channels = image.pixels.iter().flatten().copied();
    let unorm = |c: f32, max: f32| (c.clamp(0.0, 1.0) * max).round();
    let (bytes, texel): (Vec<u8>, u32) = match format {
        wgpu::TextureFormat::Rgba8Unorm => (channels.map(|c| unorm(c, 255.0) as u8).collect(), 4),
        wgpu::TextureFormat::Rgba16Unorm => (channels.flat_map(|c| (unorm(c, 65535.0) as u16).to_le_bytes()).collect(), 8),
        wgpu::TextureFormat::Rgba16Float => (channels.flat_map(|c| f16::from_f32(c).to_le_bytes()).collect(), 8),
        wgpu::TextureFormat::Rgba32Float => (channels.flat_map(f32::to_le_bytes).collect(), 16),
        wgpu::TextureFormat::R32Float => (image.pixels.iter().flat_map(|p| p[0].to_le_bytes()).collect(), 4),
        other => return Err(HarnessError::Unsupported(format!("writing {other:?}"))),
    };
    gpu.queue.write_texture(
        texture.as_image_copy(),
        &bytes,
        wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(w * texel), rows_per_image: Some(h) },
        texture.size(),
    );
    Ok(())
}
