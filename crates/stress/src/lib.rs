//! Stress sweep: adversarial and random uniform sets and G-buffer contents
//! through the real composite program on the harness, each compared with the f64 reference fed
//! the same inputs. Counts NaN/Inf pixels and the largest error per category, and tabulates the
//! error against |cameraPosition| with the reference fed the f32 uniforms the shader got and
//! the exact (f64) ones. See docs/stress.md.
//!
//! A "case" is one frame (small, 32x18 by default) with one uniform set and one G-buffer set.
//! G-buffers come from a few dozen base scenes rendered once through the whole harness
//! pipeline; per case only composite runs ([`tidepack_harness::composite_only`]), with its
//! uniforms rewritten and, for some categories, the G-buffers altered.

use rand_core::{Rng as _, SeedableRng};
use rand_xoshiro::SplitMix64;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use glam::DVec3;
use serde::Serialize;
use tidepack_harness::composite_only::{CompositeOnly, GBuffers};
use tidepack_harness::uniforms::{self, Pass, Value};
use tidepack_harness::{FloatImage, Gpu, LoadedPack, PackSelection, Scene, program, render_wgpu};
use tidepack_pack::Dialect;
use tidepack_reference::Inputs;
use tidepack_reference::model::{is_water_behind_translucent, is_water_nearest};
use tidepack_reference::harness::{self as reference, Precision, Textures};

/// The |cameraPosition| magnitudes of the distance table.
pub const MAGNITUDES: [f64; 6] = [0.0, 1e3, 1e4, 1e5, 1e6, 3e7];

#[derive(Clone, Debug)]
pub struct StressOptions {
    /// Folder with pack.toml and shaders/ (shaderpack).
    pub source_dir: PathBuf,
    /// Folder with the base scenes (tests/scenes).
    pub scenes_dir: PathBuf,
    pub dialect: Dialect,
    pub profile: Option<String>,
    /// Total number of cases, split over the categories by [`cases_of_category`].
    pub cases: usize,
    pub width: u32,
    pub height: u32,
    pub seed: u64,
    /// Where summary.json, categories.csv, distance.csv and cases.csv go.
    pub out_dir: Option<PathBuf>,
}

impl StressOptions {
    pub fn new(root: &Path) -> StressOptions {
        StressOptions {
            source_dir: root.join("shaderpack"),
            scenes_dir: root.join("tests/scenes"),
            dialect: Dialect::Glsl330,
            profile: None,
            cases: 10_000,
            width: 32,
            height: 18,
            seed: 0x5EED_0005,
            out_dir: None,
        }
    }
}

/// What a case stresses: each category draws its cases from its own base scenes and alterations
/// (see [`make_case`] and docs/stress.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Category {
    /// Camera exactly at the water surface.
    SurfaceExact,
    /// Camera 1e-6 above the surface.
    SurfaceAbove1e6,
    /// Camera 1e-6 below the surface.
    SurfaceBelow1e6,
    /// Camera far from the origin (the |cameraPosition| magnitudes of the distance table).
    CameraFar,
    /// `worldTime` at and around the day's and two days' wrap.
    WorldTime,
    /// `frameTimeCounter` at and around its wrap at 3600 s.
    FrameTime3600,
    /// Both depths 1.0 (sky) under a water mark, everywhere or on alternate pixels (depthtex1
    /// alone 1.0 on the others).
    SkyDepth,
    /// depthtex1 equal to depthtex0.
    D0EqD1,
    /// Extreme near and far planes.
    NearFar,
    /// No sky light and a black water tint.
    DarkWater,
    /// Rain, clouds or the hand over the water (colortex3) at any coverage up to 1, with the
    /// water's kept distance anywhere from 0 to the far plane.
    DrawnOver,
    /// Camera just above or below the surface looking along it.
    Grazing,
    /// Sun at or below the horizon.
    SunBelow,
    /// Random uniforms, half of them with fuzzed G-buffers.
    Random,
}

/// Every category, in report order (the order `--cases` fills them in).
pub const CATEGORIES: [Category; 14] = [
    Category::SurfaceExact,
    Category::SurfaceAbove1e6,
    Category::SurfaceBelow1e6,
    Category::CameraFar,
    Category::WorldTime,
    Category::FrameTime3600,
    Category::SkyDepth,
    Category::D0EqD1,
    Category::NearFar,
    Category::DarkWater,
    Category::DrawnOver,
    Category::Grazing,
    Category::SunBelow,
    Category::Random,
];

impl Category {
    /// The category's name in the tables, the JSON and CSV files, and the labels of its base
    /// scenes (`surface_exact:yaw180:pitch30`).
    pub fn name(self) -> &'static str {
        match self {
            Category::SurfaceExact => "surface_exact",
            Category::SurfaceAbove1e6 => "surface_above_1e-6",
            Category::SurfaceBelow1e6 => "surface_below_1e-6",
            Category::CameraFar => "camera_far",
            Category::WorldTime => "world_time",
            Category::FrameTime3600 => "frame_time_3600",
            Category::SkyDepth => "sky_depth",
            Category::D0EqD1 => "d0_eq_d1",
            Category::NearFar => "near_far",
            Category::DarkWater => "dark_water",
            Category::DrawnOver => "drawn_over",
            Category::Grazing => "grazing",
            Category::SunBelow => "sun_below",
            Category::Random => "random",
        }
    }
}

impl std::fmt::Display for Category {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl Serialize for Category {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

#[derive(Clone, Debug, Serialize)]
pub struct CategoryResult {
    pub category: Category,
    pub cases: usize,
    pub pixels: usize,
    /// GPU output pixels with a NaN or Inf in any channel.
    pub non_finite_pixels: usize,
    /// Reference pixels that are not finite (the reference has the same guards).
    pub reference_non_finite_pixels: usize,
    /// Largest |GPU − reference| over rgb, all cases.
    pub max_error: f64,
    pub worst_case: String,
    /// RMSE over every rgb channel of every case.
    pub rmse: f64,
    /// Pixels with a channel off by more than 1/255.
    pub visible_pixels: usize,
    #[serde(skip)]
    squares: f64,
}

impl CategoryResult {
    fn new(category: Category) -> CategoryResult {
        CategoryResult {
            category,
            cases: 0,
            pixels: 0,
            non_finite_pixels: 0,
            reference_non_finite_pixels: 0,
            max_error: 0.0,
            worst_case: String::new(),
            rmse: 0.0,
            visible_pixels: 0,
            squares: 0.0,
        }
    }
}

#[derive(Clone, Debug, Default, Serialize)]
pub struct DistanceRow {
    pub magnitude: f64,
    pub cases: usize,
    /// GPU against the reference fed the f32 uniforms the shader got: shader arithmetic.
    pub max_error_f32_inputs: f64,
    pub rmse_f32_inputs: f64,
    /// GPU against the reference fed exact (f64) uniforms: arithmetic and input rounding.
    pub max_error_exact_inputs: f64,
    pub rmse_exact_inputs: f64,
    /// Reference(f32 uniforms) against reference(exact): input rounding alone.
    pub max_input_rounding: f64,
    #[serde(skip)]
    sq: [f64; 2],
    #[serde(skip)]
    n: usize,
}

#[derive(Clone, Debug, Serialize)]
pub struct CaseRecord {
    pub index: usize,
    pub category: Category,
    pub description: String,
    pub non_finite_pixels: usize,
    pub max_error: f64,
}

#[derive(Clone, Debug, Serialize)]
pub struct StressReport {
    pub adapter: String,
    pub dialect: String,
    pub profile: String,
    pub resolution: [u32; 2],
    pub seed: u64,
    pub cases: usize,
    pub base_scenes: usize,
    pub non_finite_pixels: usize,
    pub categories: Vec<CategoryResult>,
    pub distance: Vec<DistanceRow>,
    pub seconds: f64,
    #[serde(skip)]
    pub records: Vec<CaseRecord>,
}

/// The draws the categories make, on the workspace's splitmix64 (value-stable for a seed, so a
/// seed names the same cases on every build).
pub struct Rng(SplitMix64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(SplitMix64::seed_from_u64(seed))
    }
    pub fn next_u64(&mut self) -> u64 {
        self.0.next_u64()
    }
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    pub fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[(self.next_u64() % items.len() as u64) as usize]
    }
    pub fn sign(&mut self) -> f64 {
        if self.next_u64() & 1 == 0 { 1.0 } else { -1.0 }
    }
}

/// A G-buffer frame rendered once through the whole harness pipeline.
struct Base {
    name: String,
    scene: Scene,
    gbuffers: GBuffers,
}

/// Base scenes: the shipped ones plus camera variants the categories need.
fn base_scenes(opts: &StressOptions) -> Result<Vec<(String, Scene)>, String> {
    let load = |name: &str| -> Result<Scene, String> {
        Scene::load(&opts.scenes_dir.join(format!("{name}.toml"))).map(|s| s.with_resolution(opts.width, opts.height)).map_err(|e| e.to_string())
    };
    let mut out = Vec::new();
    let mut names: Vec<String> = std::fs::read_dir(&opts.scenes_dir)
        .map_err(|e| format!("{}: {e}", opts.scenes_dir.display()))?
        .filter_map(|e| {
            let p = e.ok()?.path();
            (p.extension()? == "toml").then(|| p.file_stem().map(|s| s.to_string_lossy().into_owned()))?
        })
        .collect();
    names.sort();
    for n in &names {
        out.push((format!("shipped:{n}"), load(n)?));
    }
    let template = load("case4_above_near")?;
    let level = template.water.as_ref().map(|w| w.level).ok_or("case4_above_near has no water")?;
    let at = |label: &str, y: f64, yaw: f64, pitch: f64, near: f64, far: f64| {
        let mut s = template.clone();
        s.camera.position[1] = y;
        s.camera.yaw = yaw;
        s.camera.pitch = pitch;
        s.camera.near = near;
        s.camera.far = far;
        s.name = label.to_string();
        (label.to_string(), s)
    };
    // Labelled `<category>:...`: the categories that carry their hazard in the base scene pick
    // their bases by that prefix.
    for (tag, dy) in [(Category::SurfaceExact, 0.0), (Category::SurfaceAbove1e6, 1e-6), (Category::SurfaceBelow1e6, -1e-6)] {
        for (yaw, pitch) in [(180.0, 30.0), (180.0, 0.0), (180.0, -30.0), (90.0, 89.0), (0.0, -89.0)] {
            out.push(at(&format!("{tag}:yaw{yaw}:pitch{pitch}"), level + dy, yaw, pitch, 0.05, 96.0));
        }
    }
    let near_far = Category::NearFar;
    for (near, far) in [(1e-4, 96.0), (0.05, 2.0), (1.0, 4.0), (0.05, 4096.0), (1e-4, 32768.0)] {
        out.push(at(&format!("{near_far}:near{near}:far{far}"), level + 4.0, 180.0, 38.0, near, far));
        out.push(at(&format!("{near_far}:below:near{near}:far{far}"), level - 3.0, 180.0, -38.0, near, far));
    }
    let grazing = Category::Grazing;
    for (dy, pitch) in [(0.01, 0.5), (0.1, 0.05), (1.0, 1.0), (0.001, 0.0), (-0.01, -0.5), (-0.1, -0.05)] {
        out.push(at(&format!("{grazing}:dy{dy}:pitch{pitch}"), level + dy, 180.0, pitch, 0.05, 96.0));
    }
    Ok(out)
}

/// The reference's inputs for a case: its G-buffers with the uniforms the shader got (`f32_inputs`)
/// or the exact ones. An RGBA32F colour buffer would be taken as not filtering (nearest) without
/// asking the adapter: the pack's colour buffers are RGBA8/RGBA16, which filter on every adapter.
fn reference_inputs(pack: &LoadedPack, textures: &Textures, g: &GBuffers, values: &BTreeMap<String, Value>, f32_inputs: bool) -> Result<Inputs, String> {
    let uniforms = reference::uniforms_of(values, if f32_inputs { Precision::F32 } else { Precision::Exact })?;
    reference::from_gbuffers(pack, &g.colors, &g.depth0, &g.depth1, Some(false), textures, uniforms)
}

/// One case: the uniforms (from a scene variant) and the G-buffers.
struct Case {
    description: String,
    scene: Scene,
    gbuffers: GBuffers,
    /// |cameraPosition| bucket for the distance table.
    magnitude: Option<f64>,
}

fn with_origin(scene: &mut Scene, rng: &mut Rng, magnitude: f64) {
    // x and z at the magnitude (random signs), plus a fractional part f32 cannot hold there.
    scene.origin = [rng.sign() * magnitude + rng.unit(), 0.0, rng.sign() * magnitude + rng.unit()];
    if magnitude == 0.0 {
        scene.origin = [0.0; 3];
    }
}

fn random_sun(rng: &mut Rng, below: bool) -> [f64; 3] {
    let y = if below { -rng.range(0.0, 1.0) } else { rng.range(-1.0, 1.0) };
    let a = rng.range(0.0, std::f64::consts::TAU);
    let r = (1.0 - y * y).max(0.0).sqrt();
    let v = [r * a.cos(), y, r * a.sin()];
    if DVec3::from(v).length() < 1e-6 { [0.0, -1.0, 0.0] } else { v }
}

/// Alters G-buffers in place, quantised to what the buffers can hold.
fn map_gbuffers(runner: &CompositeOnly, g: &mut GBuffers, mut f: impl FnMut(usize, &mut BTreeMap<u8, [f32; 4]>, &mut f32, &mut f32)) {
    let n = g.depth0.pixels.len();
    for i in 0..n {
        let mut px: BTreeMap<u8, [f32; 4]> = g.colors.iter().map(|(b, img)| (*b, img.pixels[i])).collect();
        let (mut d0, mut d1) = (g.depth0.pixels[i][0], g.depth1.pixels[i][0]);
        f(i, &mut px, &mut d0, &mut d1);
        // gbuffers_water's blending leaves colortex0's alpha at 0 wherever it drew a translucent
        // (shaders.properties), and rain, clouds and the hand drawn after it add their coverage
        // (colortex3's alpha) to it. Composite reads the water mark only where that alpha is
        // below 1, and colortex3 only where it is above 0: a mark put into colortex4 here must
        // come with that alpha to be shaded.
        let coverage = px.get(&3).map_or(0.0, |p| p[3]);
        if px.get(&4).is_some_and(|p| is_water_nearest(p[0] as f64) || is_water_behind_translucent(p[0] as f64))
            && let Some(scene) = px.get_mut(&0)
        {
            scene[3] = coverage;
        }
        for (b, p) in px {
            let img = g.colors.get_mut(&b).expect("same buffers");
            img.pixels[i] = p.map(|c| runner.quantize(b, c));
        }
        g.depth0.pixels[i] = [d0, d0, d0, 1.0];
        g.depth1.pixels[i] = [d1, d1, d1, 1.0];
    }
}

fn make_case(category: Category, k: usize, bases: &[Base], runner: &CompositeOnly, rng: &mut Rng) -> Case {
    let pick_prefix = |rng: &mut Rng, prefix: &str| -> usize {
        let matching: Vec<usize> = bases.iter().enumerate().filter(|(_, b)| b.name.starts_with(prefix)).map(|(i, _)| i).collect();
        *rng.pick(&matching)
    };
    let any_water = |rng: &mut Rng| -> usize {
        let matching: Vec<usize> = bases.iter().enumerate().filter(|(_, b)| b.scene.water.is_some()).map(|(i, _)| i).collect();
        *rng.pick(&matching)
    };
    let mut magnitude = None;
    use Category::*;
    let base_index = match category {
        SurfaceExact | SurfaceAbove1e6 | SurfaceBelow1e6 | NearFar | Grazing => pick_prefix(rng, &format!("{category}:")),
        Random => rng.next_u64() as usize % bases.len(),
        CameraFar | WorldTime | FrameTime3600 | SkyDepth | D0EqD1 | DarkWater | DrawnOver | SunBelow => any_water(rng),
    };
    let base = &bases[base_index];
    let mut scene = base.scene.clone();
    let mut g = base.gbuffers.clone();
    let mut description = base.name.clone();
    scene.time.frame_time_counter = rng.range(0.0, 3600.0);
    match category {
        CameraFar => {
            let m = MAGNITUDES[k % MAGNITUDES.len()];
            with_origin(&mut scene, rng, m);
            magnitude = Some(m);
        }
        WorldTime => scene.time.world_time = *rng.pick(&[0, 23999, 24000, 1, 12000, 47999, 48000]),
        FrameTime3600 => {
            let ulp = 3600f32.next_down() as f64;
            let (a, b) = (3600.0 - rng.range(0.0, 1.0), rng.range(0.0, 0.1));
            scene.time.frame_time_counter = *rng.pick(&[0.0, 1e-6, 3599.9, 3599.999, ulp, 3600.0, a, b]);
        }
        SkyDepth => {
            let all = rng.unit() < 0.5;
            map_gbuffers(runner, &mut g, |i, px, d0, d1| {
                if all || i % 2 == 0 {
                    *d0 = 1.0;
                    *d1 = 1.0;
                    if let Some(p) = px.get_mut(&4) {
                        p[0] = 1.0; // water mark at sky depth
                    }
                } else {
                    *d1 = 1.0;
                }
            });
            description.push_str(if all { " +depth0=depth1=1 everywhere, water mark" } else { " +sky depth on alternate pixels" });
        }
        D0EqD1 => {
            map_gbuffers(runner, &mut g, |_, _, d0, d1| *d1 = *d0);
            description.push_str(" +depthtex1=depthtex0");
        }
        DarkWater => {
            // Black tint and no sky light: the scattered colour and every sky term vanish.
            map_gbuffers(runner, &mut g, |_, px, _, _| {
                if let Some(p) = px.get_mut(&4) {
                    p[1] = 0.0;
                }
                if let Some(p) = px.get_mut(&5) {
                    *p = [0.0, 0.0, 0.0, p[3]];
                }
            });
            description.push_str(" +colortex4.g=0 (no sky light), colortex5=black tint");
        }
        DrawnOver => {
            let any = rng.unit() as f32;
            let coverage = *rng.pick(&[0.5f32, 1.0 - 1.0 / 255.0, 1.0, any]);
            // The water's kept distance: at the eye, as rendered, or anywhere to the far plane.
            let anywhere = rng.unit() as f32;
            let distance = *rng.pick(&[Some(0.0f32), None, Some(anywhere)]);
            let color = [rng.unit() as f32, rng.unit() as f32, rng.unit() as f32];
            map_gbuffers(runner, &mut g, |_, px, _, _| {
                if let Some(p) = px.get_mut(&3) {
                    *p = [color[0] * coverage, color[1] * coverage, color[2] * coverage, coverage];
                }
                if let (Some(p), Some(d)) = (px.get_mut(&4), distance) {
                    p[2] = d;
                }
            });
            let kept = distance.map_or("as rendered".to_string(), |d| d.to_string());
            description.push_str(&format!(" +colortex3 coverage {coverage}, colortex4.b {kept}"));
        }
        SunBelow => {
            let y = *rng.pick(&[-1.0, -0.5, -0.05, -1e-6, 0.0]);
            let a = rng.range(0.0, std::f64::consts::TAU);
            let r = (1.0f64 - y * y).sqrt();
            scene.sky.sun_direction = if r == 0.0 { [0.0, -1.0, 0.0] } else { [r * a.cos(), y, r * a.sin()] };
        }
        Random => {
            let m = *rng.pick(&MAGNITUDES);
            with_origin(&mut scene, rng, m);
            scene.time.world_time = (rng.next_u64() % 48000) as i32;
            scene.sky.sun_direction = random_sun(rng, false);
            scene.sky.sky_color = [rng.unit(), rng.unit(), rng.unit()];
            scene.sky.fog_color = [rng.unit(), rng.unit(), rng.unit()];
            if rng.unit() < 0.5 {
                // Fuzz the G-buffers: random depths (either order), materials and normals.
                let mut r2 = Rng::new(rng.next_u64());
                map_gbuffers(runner, &mut g, |_, px, d0, d1| {
                    if r2.unit() < 0.3 {
                        let u = r2.unit() as f32;
                        let a = *r2.pick(&[0.0f32, 1.0, 0.5, u, 1.0 - 1e-7, 0.9999]);
                        let b = if r2.unit() < 0.5 { a } else { r2.unit() as f32 };
                        *d0 = a;
                        *d1 = b;
                    }
                    if let Some(p) = px.get_mut(&4)
                        && r2.unit() < 0.3
                    {
                        let u = r2.unit() as f32;
                        let mark = *r2.pick(&[0.0f32, 0.0627, 0.75, 1.0, u]);
                        *p = [mark, r2.unit() as f32, r2.unit() as f32, r2.unit() as f32];
                    }
                    if let Some(p) = px.get_mut(&5)
                        && r2.unit() < 0.3
                    {
                        *p = [r2.unit() as f32, r2.unit() as f32, r2.unit() as f32, r2.unit() as f32];
                    }
                });
                description.push_str(" +fuzzed g-buffers");
            }
        }
        SurfaceExact | SurfaceAbove1e6 | SurfaceBelow1e6 | NearFar | Grazing => {
            // The base carries the hazard; vary time, sun, origin.
            scene.sky.sun_direction = random_sun(rng, false);
            let m = *rng.pick(&[0.0, 0.0, 1e3, 1e5]);
            with_origin(&mut scene, rng, m);
        }
    }
    write!(
        description,
        " origin=({:.3},{:.3},{:.3}) worldTime={} ftc={} sun=({:.3},{:.3},{:.3})",
        scene.origin[0],
        scene.origin[1],
        scene.origin[2],
        scene.time.world_time,
        scene.time.frame_time_counter,
        scene.sky.sun_direction[0],
        scene.sky.sun_direction[1],
        scene.sky.sun_direction[2]
    )
    .ok();
    Case { description, scene, gbuffers: g, magnitude }
}

fn non_finite(image: &FloatImage) -> usize {
    image.pixels.iter().filter(|p| p.iter().any(|c| !c.is_finite())).count()
}

/// Max abs and sum of squares over rgb where both are finite.
fn compare(gpu: impl Fn(usize) -> DVec3, reference: &[DVec3]) -> (f64, f64, usize) {
    let (mut max, mut sq, mut visible) = (0.0f64, 0.0f64, 0);
    for (i, r) in reference.iter().enumerate() {
        let d = (gpu(i) - *r).abs();
        if !d.is_finite() {
            continue;
        }
        max = max.max(d.max_element());
        sq += d.length_squared();
        if d.max_element() > 1.0 / 255.0 {
            visible += 1;
        }
    }
    (max, sq, visible)
}

/// How many of `cases` category `index` runs: as even a split as there is, earlier
/// categories taking the remainder (below one per category, the later ones run none).
pub fn cases_of_category(cases: usize, index: usize) -> usize {
    cases / CATEGORIES.len() + usize::from(index < cases % CATEGORIES.len())
}

/// Runs exactly `opts.cases` cases; `progress` is called every few hundred cases.
pub fn run(opts: &StressOptions, progress: &mut dyn FnMut(&str)) -> Result<StressReport, String> {
    if opts.cases == 0 {
        return Err("the sweep needs at least one case (--cases 1 or more)".into());
    }
    let started = Instant::now();
    let pack = program::load(&PackSelection {
        source_dir: opts.source_dir.clone(),
        dialect: opts.dialect,
        profile: opts.profile.clone(),
        options: vec![],
    })
    .map_err(|e| e.to_string())?;
    let gpu = Gpu::new().map_err(|e| e.to_string())?;
    let settings = reference::settings_of(&pack)?;
    let textures = Textures::of(&pack)?;

    let mut bases = Vec::new();
    for (name, scene) in base_scenes(opts)? {
        let frame = render_wgpu(&gpu, &pack, &scene).map_err(|e| format!("{name}: {e}"))?;
        bases.push(Base { name, scene, gbuffers: GBuffers::from_frame(&frame) });
    }
    progress(&format!("{} base scenes rendered in {:.1} s", bases.len(), started.elapsed().as_secs_f64()));
    let values0 = uniforms::values(&bases[0].scene, Pass::Fullscreen);
    let runner = CompositeOnly::new(&gpu, &pack, opts.width, opts.height, &values0).map_err(|e| e.to_string())?;

    let mut rng = Rng::new(opts.seed);
    let mut categories: Vec<CategoryResult> = CATEGORIES.map(CategoryResult::new).to_vec();
    let mut distance: Vec<DistanceRow> = MAGNITUDES.iter().map(|&m| DistanceRow { magnitude: m, ..Default::default() }).collect();
    let mut records = Vec::new();
    let mut index = 0;
    for (ci, category) in CATEGORIES.into_iter().enumerate() {
        for k in 0..cases_of_category(opts.cases, ci) {
            let case = make_case(category, k, &bases, &runner, &mut rng);
            let values = uniforms::values(&case.scene, Pass::Fullscreen);
            let image = runner.render(&gpu, &pack, &case.gbuffers, &values).map_err(|e| format!("{}: {e}", case.description))?;
            let bad = non_finite(&image);
            // The reference at the f32 uniforms the shader got (for every case) and, far from
            // the origin, also at the exact ones.
            let inputs = reference_inputs(&pack, &textures, &case.gbuffers, &values, true)?;
            let reference = tidepack_reference::render(&inputs, &settings, 1)?;
            let gpu_rgb = |i: usize| {
                let p = image.pixels[i];
                DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64)
            };
            let (max, sq, visible) = compare(gpu_rgb, &reference.pixels);
            let c = &mut categories[ci];
            c.cases += 1;
            c.pixels += image.pixels.len();
            c.non_finite_pixels += bad;
            c.reference_non_finite_pixels += reference.pixels.iter().filter(|p| !p.is_finite()).count();
            c.squares += sq;
            c.visible_pixels += visible;
            if max > c.max_error || c.worst_case.is_empty() {
                c.max_error = max.max(c.max_error);
                c.worst_case = format!("#{index} {}", case.description);
            }
            if let Some(m) = case.magnitude {
                let exact = tidepack_reference::render(&reference_inputs(&pack, &textures, &case.gbuffers, &values, false)?, &settings, 1)?;
                let (max_exact, sq_exact, _) = compare(gpu_rgb, &exact.pixels);
                let (rounding, _, _) = compare(|i| reference.pixels[i], &exact.pixels);
                let row = distance.iter_mut().find(|r| r.magnitude == m).expect("a row per magnitude");
                row.cases += 1;
                row.n += image.pixels.len();
                row.max_error_f32_inputs = row.max_error_f32_inputs.max(max);
                row.max_error_exact_inputs = row.max_error_exact_inputs.max(max_exact);
                row.max_input_rounding = row.max_input_rounding.max(rounding);
                row.sq[0] += sq;
                row.sq[1] += sq_exact;
            }
            records.push(CaseRecord { index, category, description: case.description, non_finite_pixels: bad, max_error: max });
            index += 1;
            if index % 100 == 0 {
                progress(&format!("{index} cases, {:.0} s, RSS {}", started.elapsed().as_secs_f64(), rss_text()));
            }
        }
    }
    if opts.cases < CATEGORIES.len() {
        progress(&format!(
            "note: {} cases cover only the first {} of the {} categories; --cases {} runs one of each",
            opts.cases,
            opts.cases,
            CATEGORIES.len(),
            CATEGORIES.len()
        ));
    }
    for c in &mut categories {
        c.rmse = if c.pixels > 0 { (c.squares / (3 * c.pixels) as f64).sqrt() } else { 0.0 };
    }
    for r in &mut distance {
        if r.n > 0 {
            r.rmse_f32_inputs = (r.sq[0] / (3 * r.n) as f64).sqrt();
            r.rmse_exact_inputs = (r.sq[1] / (3 * r.n) as f64).sqrt();
        }
    }
    let report = StressReport {
        adapter: gpu.describe(),
        dialect: match opts.dialect {
            Dialect::Glsl120 => "120".into(),
            _ => "330".into(),
        },
        profile: pack.profile.clone(),
        resolution: [opts.width, opts.height],
        seed: opts.seed,
        cases: records.len(),
        base_scenes: bases.len(),
        non_finite_pixels: categories.iter().map(|c| c.non_finite_pixels).sum(),
        categories,
        distance,
        seconds: started.elapsed().as_secs_f64(),
        records,
    };
    if let Some(dir) = &opts.out_dir {
        write_files(&report, dir)?;
    }
    Ok(report)
}

fn rss_text() -> String {
    tidepack_harness::resident_mib().map_or_else(|| "unknown".to_string(), |m| format!("{m:.1} MiB"))
}

/// summary.json, categories.csv, distance.csv, cases.csv. Fields with commas, quotes or line
/// breaks (the case descriptions) are quoted by the `csv` crate.
pub fn write_files(report: &StressReport, dir: &Path) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let summary = dir.join("summary.json");
    std::fs::write(&summary, serde_json::to_string_pretty(report).map_err(|e| e.to_string())? + "\n")
        .map_err(|e| format!("{}: {e}", summary.display()))?;
    write_csv(
        &dir.join("categories.csv"),
        &["category", "cases", "pixels", "non_finite_pixels", "reference_non_finite_pixels", "max_error", "rmse", "visible_pixels", "worst_case"],
        report.categories.iter().map(|c| {
            [
                c.category.to_string(),
                c.cases.to_string(),
                c.pixels.to_string(),
                c.non_finite_pixels.to_string(),
                c.reference_non_finite_pixels.to_string(),
                format!("{:e}", c.max_error),
                format!("{:e}", c.rmse),
                c.visible_pixels.to_string(),
                c.worst_case.clone(),
            ]
        }),
    )?;
    write_csv(
        &dir.join("distance.csv"),
        &["magnitude", "cases", "max_error_f32_inputs", "rmse_f32_inputs", "max_error_exact_inputs", "rmse_exact_inputs", "max_input_rounding"],
        report.distance.iter().map(|r| {
            [
                r.magnitude.to_string(),
                r.cases.to_string(),
                format!("{:e}", r.max_error_f32_inputs),
                format!("{:e}", r.rmse_f32_inputs),
                format!("{:e}", r.max_error_exact_inputs),
                format!("{:e}", r.rmse_exact_inputs),
                format!("{:e}", r.max_input_rounding),
            ]
        }),
    )?;
    write_csv(
        &dir.join("cases.csv"),
        &["index", "category", "non_finite_pixels", "max_error", "description"],
        report.records.iter().map(|r| {
            [r.index.to_string(), r.category.to_string(), r.non_finite_pixels.to_string(), format!("{:e}", r.max_error), r.description.clone()]
        }),
    )
}

/// Writes a header and rows to a CSV file.
fn write_csv<const N: usize>(path: &Path, header: &[&str; N], rows: impl Iterator<Item = [String; N]>) -> Result<(), String> {
    let error = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
    let mut w = csv::Writer::from_path(path).map_err(|e| error(&e))?;
    w.write_record(header).map_err(|e| error(&e))?;
    for row in rows {
        w.write_record(&row).map_err(|e| error(&e))?;
    }
    w.flush().map_err(|e| error(&e))
}

/// The terminal tables (Markdown).
pub fn tables(report: &StressReport) -> String {
    let mut s = String::new();
    writeln!(
        s,
        "{} cases at {}x{} ({} base scenes), GLSL {}, {} profile, seed {:#x}, {}; {:.0} s",
        report.cases, report.resolution[0], report.resolution[1], report.base_scenes, report.dialect, report.profile, report.seed, report.adapter, report.seconds
    )
    .ok();
    writeln!(s, "NaN/Inf pixels in the GPU output: {}\n", report.non_finite_pixels).ok();
    writeln!(s, "| category | cases | NaN/Inf pixels | reference non-finite | max error | RMSE | pixels > 1/255 |").ok();
    writeln!(s, "|---|---|---|---|---|---|---|").ok();
    for c in &report.categories {
        writeln!(
            s,
            "| {} | {} | {} | {} | {:.3e} | {:.2e} | {} ({:.3}%) |",
            c.category,
            c.cases,
            c.non_finite_pixels,
            c.reference_non_finite_pixels,
            c.max_error,
            c.rmse,
            c.visible_pixels,
            100.0 * c.visible_pixels as f64 / c.pixels.max(1) as f64
        )
        .ok();
    }
    writeln!(s, "\nError against |cameraPosition| (camera_far cases; x and z at ± the magnitude plus a random fraction):\n").ok();
    writeln!(s, "| \\|cameraPosition\\| | cases | max err (ref at f32 uniforms) | RMSE | max err (ref at exact uniforms) | RMSE | ref f32 vs exact (input rounding) |").ok();
    writeln!(s, "|---|---|---|---|---|---|---|").ok();
    for r in &report.distance {
        writeln!(
            s,
            "| {:e} | {} | {:.3e} | {:.2e} | {:.3e} | {:.2e} | {:.3e} |",
            r.magnitude, r.cases, r.max_error_f32_inputs, r.rmse_f32_inputs, r.max_error_exact_inputs, r.rmse_exact_inputs, r.max_input_rounding
        )
        .ok();
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The CSV files quote a field holding a quote and a comma and read back to the same fields.
    #[test]
    fn csv_fields_with_quotes_and_commas_read_back_intact() {
        let description = "shipped:glass \"a, b\" origin=(1.000,0.000,2.000)".to_string();
        let report = StressReport {
            adapter: "synthetic".into(),
            dialect: "330".into(),
            profile: "HIGH".into(),
            resolution: [16, 9],
            seed: 1,
            cases: 1,
            base_scenes: 1,
            non_finite_pixels: 0,
            categories: vec![CategoryResult { cases: 1, max_error: 0.5, worst_case: format!("#0 {description}"), ..CategoryResult::new(Category::Random) }],
            distance: vec![DistanceRow { magnitude: 1e3, ..Default::default() }],
            seconds: 0.0,
            records: vec![CaseRecord { index: 0, category: Category::Random, description: description.clone(), non_finite_pixels: 0, max_error: 0.5 }],
        };
        let dir = tempfile::tempdir().unwrap();
        write_files(&report, dir.path()).unwrap();
        let read = |name: &str| -> (usize, Vec<csv::StringRecord>) {
            let mut reader = csv::Reader::from_path(dir.path().join(name)).unwrap();
            let columns = reader.headers().unwrap().len();
            (columns, reader.records().map(Result::unwrap).collect())
        };
        let (columns, cases) = read("cases.csv");
        assert_eq!((columns, cases.len(), cases[0].len()), (5, 1, 5));
        assert_eq!(&cases[0][4], description);
        let (columns, categories) = read("categories.csv");
        assert_eq!((columns, categories.len(), categories[0].len()), (9, 1, 9));
        assert_eq!(&categories[0][8], format!("#0 {description}"));
        let (_, distance) = read("distance.csv");
        assert_eq!(&distance[0][0], "1000");
    }

    /// The names the tables, the files and `--cases` reports use.
    #[test]
    fn category_names_are_the_reports() {
        let names = CATEGORIES.map(Category::name);
        assert_eq!(names, [
            "surface_exact",
            "surface_above_1e-6",
            "surface_below_1e-6",
            "camera_far",
            "world_time",
            "frame_time_3600",
            "sky_depth",
            "d0_eq_d1",
            "near_far",
            "dark_water",
            "drawn_over",
            "grazing",
            "sun_below",
            "random",
        ]);
        assert_eq!(serde_json::to_string(&Category::SurfaceAbove1e6).unwrap(), "\"surface_above_1e-6\"");
        assert_eq!(Category::D0EqD1.to_string(), "d0_eq_d1");
    }

    #[test]
    fn cases_are_split_exactly() {
        for cases in [1, 5, 13, 20, 260, 10_000] {
            let split: Vec<usize> = (0..CATEGORIES.len()).map(|i| cases_of_category(cases, i)).collect();
            assert_eq!(split.iter().sum::<usize>(), cases, "{cases}: {split:?}");
            assert!(split.iter().max().unwrap() - split.iter().min().unwrap() <= 1, "{cases}: {split:?}");
        }
    }
}
