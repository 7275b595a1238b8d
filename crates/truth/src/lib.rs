//! The truth: a physically based ray tracer, in f64, of the scenes the harness renders, against
//! which the pack's water model is scored (docs/truth.md). It traces the scene's own geometry
//! with the exact wave surface, Snell and Fresnel at every interface, Beer–Lambert absorption
//! with the pack's coefficients along the real paths, reflections of everything and of the sky
//! and sun, and photon-traced caustics; opaque surfaces are coloured exactly as the pack's
//! gbuffers programs colour them, so that the truth and the pack differ only in the water's
//! light transport.
//!
//! Data flow: `Scene` → [`geometry`] (the mesh's surfaces), [`surface`] (the water volume),
//! [`sky`], [`medium`] → [`caustics`] (photons onto a floor irradiance grid) → [`trace`] per
//! [`camera`] ray, rows on every core.

pub mod camera;
pub mod caustics;
pub mod fresnel;
pub mod geometry;
pub mod medium;
pub mod sky;
pub mod surface;
pub mod trace;

use std::io::Cursor;

use glam::DVec3;
use rayon::prelude::*;
use tidepack_reference::{Filter, ReferenceSettings, Texture, Wrap};
use tidepack_scene::Scene;

use camera::Camera;
use caustics::CausticGrid;
use geometry::Geometry;
use medium::Medium;
use sky::Sky;
use surface::WaterBody;
use trace::{Ray, Record, Tracer};

/// How the truth renders.
#[derive(Clone, Debug, PartialEq)]
pub struct TruthOptions {
    /// Samples per pixel along each axis: n × n stratified samples at the centres of the
    /// pixel's sub-cells (1: the pixel centre, where the composite shades).
    pub samples_per_axis: u32,
    /// Every `stride`-th pixel in x and y is traced (as the reference's `render`); the others
    /// stay zero.
    pub stride: usize,
    /// Most interfaces a path meets before it ends.
    pub max_depth: u32,
    /// False: the water's surface is flat at its level (checks against closed forms).
    pub waves: bool,
    /// Radiance changes by (n₁/n₂)² crossing into another medium (physics: L/n² is invariant;
    /// on by default). Off, refraction keeps radiance as most renderers do.
    pub radiance_scaling: bool,
}

impl Default for TruthOptions {
    fn default() -> Self {
        TruthOptions { samples_per_axis: 1, stride: 1, max_depth: 12, waves: true, radiance_scaling: true }
    }
}

/// A traced frame: linear colour, row 0 at the bottom, as `tidepack_reference::ReferenceImage`
/// and the composite's output (no tonemapping; fog as the pack applies it).
#[derive(Clone, Debug, PartialEq)]
pub struct TruthImage {
    pub width: usize,
    pub height: usize,
    /// Per pixel, the mean of its samples.
    pub pixels: Vec<DVec3>,
    /// Pixels where some ray of some sample met the water.
    pub water: Vec<bool>,
    /// Pixels where an overlay box (rain, clouds, particles, the hand) lies in front of what
    /// the eye sees: the truth leaves overlays out, so these pixels should be masked.
    pub overlay: Vec<bool>,
    /// Pixels traced (all at stride 1).
    pub evaluated: Vec<bool>,
}

/// The pack's water texture (colortex7) as the composite samples it: the generated PNG,
/// row 0 at v = 0, linear and repeating (its `.mcmeta`).
pub fn water_texture() -> Result<Texture, String> {
    let png = tidepack_pack::textures::water_texture().png;
    let image = image::ImageReader::with_format(Cursor::new(png), image::ImageFormat::Png)
        .decode()
        .map_err(|e| format!("the generated water texture does not decode: {e}"))?
        .to_rgba8();
    Ok(Texture::from_rgba8(image.width() as usize, image.height() as usize, image.as_raw(), Filter::Linear, Wrap::Repeat))
}

/// A scene prepared for tracing: geometry, water, sky and caustics built once.
pub struct Truth {
    pub camera: Camera,
    pub tracer: Tracer,
    options: TruthOptions,
}

impl Truth {
    pub fn new(scene: &Scene, settings: &ReferenceSettings, options: &TruthOptions) -> Result<Truth, String> {
        let texture = water_texture()?;
        let geometry = Geometry::of(scene);
        let mut water = WaterBody::of(scene, &texture);
        if let Some(w) = &mut water {
            w.waves = options.waves;
        }
        let tint = water.as_ref().map_or(DVec3::from(default_water_tint()), |w| w.tint);
        let medium = Medium::new(settings, tint, DVec3::from(scene.sky.sky_color));
        let sun = scene.sun_direction();
        let caustics = water.as_ref().and_then(|w| CausticGrid::trace(w, &geometry, &medium, sun));
        let tracer = Tracer {
            geometry,
            water,
            medium,
            sky: Sky::of(scene),
            caustics,
            sun,
            fog: !scene.eye_in_water(),
            far: scene.camera.far,
            fog_color: DVec3::from(scene.sky.fog_color),
            max_depth: options.max_depth,
            radiance_scaling: options.radiance_scaling,
        };
        Ok(Truth { camera: Camera::of(scene), tracer, options: options.clone() })
    }

    /// The radiance the eye receives along unit direction `dir`, with what its rays did.
    pub fn trace(&self, dir: DVec3) -> (DVec3, Record) {
        let in_water = self.tracer.water.as_ref().is_some_and(|w| w.contains(DVec3::ZERO));
        let ray = Ray { origin: DVec3::ZERO, dir, in_water, straight: true, path: 0.0, weight: 1.0, depth: 0 };
        let mut record = Record::default();
        let colour = self.tracer.radiance(ray, &mut record);
        (colour, record)
    }

    /// Whether an overlay box is in front of the first thing along `dir`.
    fn overlay_in_front(&self, dir: DVec3) -> bool {
        let t = &self.tracer;
        let in_water = t.water.as_ref().is_some_and(|w| w.contains(DVec3::ZERO));
        let hit = t.geometry.hit(DVec3::ZERO, dir, 0.0, f64::INFINITY).map_or(f64::INFINITY, |h| h.t());
        let first = t.water.as_ref().and_then(|w| w.crossing(DVec3::ZERO, dir, in_water, hit)).map_or(hit, |c| c.t);
        t.geometry.overlay_before(DVec3::ZERO, dir, first)
    }

    /// Pixel (x, y), y from the bottom: the mean over its samples, whether water was met, and
    /// whether an overlay covers it.
    pub fn pixel(&self, x: usize, y: usize) -> (DVec3, bool, bool) {
        let n = self.options.samples_per_axis.max(1);
        let (mut sum, mut water, mut overlay) = (DVec3::ZERO, false, false);
        for j in 0..n {
            for i in 0..n {
                let dir = self.camera.direction(self.camera.sample(x, y, i, j, n));
                let (colour, record) = self.trace(dir);
                sum += colour;
                water |= record.touched_water;
                overlay |= self.overlay_in_front(dir);
            }
        }
        (sum / (n * n) as f64, water, overlay)
    }

    /// Every `stride`-th pixel, rows on every core; the image does not depend on the
    /// scheduling (each pixel depends only on the prepared scene).
    pub fn render(&self) -> TruthImage {
        let (w, h) = (self.camera.width, self.camera.height);
        let stride = self.options.stride.max(1);
        let rows: Vec<Row> = (0..h)
            .into_par_iter()
            .step_by(stride)
            .map(|y| (y, (0..w).step_by(stride).map(|x| { let (c, water, overlay) = self.pixel(x, y); (x, c, water, overlay) }).collect()))
            .collect();
        let mut image = TruthImage {
            width: w,
            height: h,
            pixels: vec![DVec3::ZERO; w * h],
            water: vec![false; w * h],
            overlay: vec![false; w * h],
            evaluated: vec![false; w * h],
        };
        for (y, row) in rows {
            for (x, colour, water, overlay) in row {
                let i = y * w + x;
                image.pixels[i] = colour;
                image.water[i] = water;
                image.overlay[i] = overlay;
                image.evaluated[i] = true;
            }
        }
        image
    }
}

/// A traced row: its index, and per traced pixel its x, colour, water and overlay flags.
type Row = (usize, Vec<(usize, DVec3, bool, bool)>);

/// Minecraft's default water colour, the pack's `DEFAULT_WATER_TINT`, for scenes without
/// water (whose medium is then never entered).
fn default_water_tint() -> [f64; 3] {
    [63.0 / 255.0, 118.0 / 255.0, 228.0 / 255.0]
}

/// Traces `scene` (its resolution) with the pack's absorption density (`settings`) and
/// `options`: linear colour per pixel, row 0 at the bottom, with the water and overlay masks.
pub fn render(scene: &Scene, settings: &ReferenceSettings, options: &TruthOptions) -> Result<TruthImage, String> {
    Ok(Truth::new(scene, settings, options)?.render())
}
