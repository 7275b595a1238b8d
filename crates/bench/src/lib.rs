//! `tidepack bench`: for every scene and every option set (the profiles, and single-knob sweeps
//! around the default profile), the composite's GPU time on the harness
//! (median of N frames, with the one-tap pass-through composite of the same frames as the
//! floor) and its error against the f64 reference at converged settings (max abs, RMSE, PSNR,
//! mean FLIP), and its error against the truth (`tidepack-truth`, a physically based ray tracer
//! of the same scenes) over the pixels where the truth met water: the converged reference
//! measures discretisation error, the truth the model's own. Writes a table, CSV, JSON, a
//! Pareto plot of time against error, FLIP heat-maps, pictures of the truth beside the base
//! profile and a Markdown report. See docs/accuracy.md.
//!
//! Each scene is rendered once per option set through the whole harness pipeline
//! (`render_wgpu`: the image whose error is measured, and the G-buffers). The composite is then
//! timed alone over those G-buffers with [`tidepack_harness::composite_only`] (all option sets
//! taking turns, one frame each per round, so load changes hit them alike). `composite_only`
//! binds the uniform blocks as read-only storage, so the driver compiles the shader once
//! instead of specialising it on the blocks' values at every draw, which would add its
//! compile time to the timed pass (see that module and docs/stress.md, "Memory"). The timed
//! image is checked against the harness frame's (`timed_image_difference`).

pub mod compare;
pub mod labels;
pub mod metrics;
pub mod output;
pub mod pareto;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::Serialize;
use tidepack_loader::option_lines::{OptionKind, OptionValue};
use tidepack_harness::composite_only::{CompositeOnly, GBuffers};
use tidepack_harness::uniforms::{self, Pass};
use tidepack_harness::{Gpu, LoadedPack, PackSelection, Scene, program, render_wgpu};
use tidepack_pack::Dialect;
use tidepack_pack::source::PackSource;
use tidepack_pack::specialise::Specialisation;
use tidepack_reference::ReferenceImage;
use tidepack_truth::TruthOptions;

pub use metrics::ErrorMetrics;

/// The knobs swept one at a time around the base profile, with every value settings.glsl lists.
pub const SWEPT_KNOBS: [&str; 8] = [
    "WAVE_REFINE_STEPS",
    "SSR_STEPS",
    "SSR_REFINE_STEPS",
    "NORMAL_OCTAVES",
    "CAUSTIC_SAMPLES",
    "FRESNEL_EXACT",
    "ABSORPTION_MODEL",
    "EARLY_OUTS",
];

#[derive(Clone, Debug)]
pub struct BenchConfig {
    /// Folder with pack.toml and shaders/.
    pub source_dir: PathBuf,
    /// Folder of scene files (*.toml).
    pub scenes_dir: PathBuf,
    /// Only these scenes (file stems); all when empty.
    pub scene_filter: Vec<String>,
    /// Timed frames per option set and scene (after one warm-up frame); the median is reported.
    pub frames: usize,
    /// Render every scene at this resolution instead of its own.
    pub resolution: Option<[u32; 2]>,
    /// Reference pixel stride (1: every pixel).
    pub reference_stride: usize,
    pub out_dir: PathBuf,
    /// Only these runs; the profiles and sweeps when None.
    pub runs: Option<Vec<RunSpec>>,
    /// Also write the Markdown report here, with the plot beside it as `<stem>-pareto.png`.
    pub report: Option<PathBuf>,
    /// The command line that produced this run, quoted in the report.
    pub command: String,
    pub progress: bool,
    /// Time each option set specialised for each scene (`build --scene`: the uniforms the
    /// scene fixes folded into constants) instead of the general pack.
    pub specialise: bool,
}

/// One option set: a profile, or the base profile with one option overridden.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct RunSpec {
    /// `LOW`, or `HIGH+SSR_STEPS=24`.
    pub name: String,
    /// `profile` or `sweep`.
    pub kind: String,
    pub profile: String,
    /// The overridden option (sweeps).
    pub knob: Option<String>,
    pub value: Option<String>,
}

impl RunSpec {
    pub fn profile(name: &str) -> RunSpec {
        RunSpec { name: name.to_string(), kind: "profile".into(), profile: name.to_string(), knob: None, value: None }
    }
    pub fn sweep(profile: &str, knob: &str, value: &str) -> RunSpec {
        RunSpec {
            name: format!("{profile}+{knob}={value}"),
            kind: "sweep".into(),
            profile: profile.to_string(),
            knob: Some(knob.to_string()),
            value: Some(value.to_string()),
        }
    }
}

/// One run on one scene.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    pub scene: String,
    pub run: RunSpec,
    /// Median composite time over the frames (GPU timestamps, else wall).
    pub composite_ms: f64,
    /// Median one-tap pass-through composite time over the same frames.
    pub passthrough_ms: f64,
    /// composite_ms / passthrough_ms.
    pub ratio: f64,
    /// Every timed frame's composite and pass-through times, in order: their spread says how
    /// far apart two runs must be for a Pareto verdict ([`pareto::ratio_spread`]).
    pub composite_frames_ms: Vec<f64>,
    pub passthrough_frames_ms: Vec<f64>,
    pub error: ErrorMetrics,
    /// Sum of squared rgb differences over the pixels / (3 pixels): to aggregate PSNR.
    pub mse: f64,
    /// The error against the truth over the scene's compared pixels ([`TruthFrame::compared`]);
    /// None where there are none (no water in view).
    pub truth_error: Option<ErrorMetrics>,
    /// Largest |timed composite output − the harness frame's composite output| (rgba): the
    /// timed pass computes the image whose error is reported (0 when it does).
    pub timed_image_difference: f64,
}

/// One run over all scenes.
#[derive(Clone, Debug, Serialize)]
pub struct Aggregate {
    pub run: RunSpec,
    /// Mean over scenes of the composite / pass-through ratio.
    pub ratio: f64,
    /// Mean over scenes of the ratio's relative spread (interquartile range of the per-frame
    /// ratios over their median; NaN with a single frame).
    pub ratio_spread: f64,
    pub composite_ms: f64,
    pub passthrough_ms: f64,
    /// Largest max abs of any scene.
    pub max_abs: f64,
    /// Over all scenes' pixels.
    pub rmse: f64,
    pub psnr: f64,
    /// Mean over scenes of the mean FLIP.
    pub mean_flip: f64,
    /// Against the truth, over the scenes with compared pixels: the largest max abs, RMSE and
    /// PSNR from the mean of the scenes' MSE, the mean of their mean FLIP.
    pub truth: Option<ErrorMetrics>,
    /// Its place in (ratio, mean FLIP) against the other runs, within the timing noise.
    pub verdict: pareto::Verdict,
    /// Runs that dominate it beyond the timing noise, with the smaller of their two relative
    /// improvements, largest first.
    pub dominated_by: Vec<(String, f64)>,
    /// Runs at least as accurate whose time is within the combined spread of this one's,
    /// fastest first.
    pub ties_with: Vec<String>,
}

#[derive(Clone, Debug, Serialize)]
pub struct BenchResult {
    pub adapter: String,
    /// `gpu` (timestamps) or `wall`.
    pub timing_source: String,
    pub frames: usize,
    pub resolution: Option<[u32; 2]>,
    pub reference_stride: usize,
    pub reference_settings: String,
    pub truth_options: String,
    /// Per scene, the pixels compared with the truth.
    pub truth_pixels: BTreeMap<String, usize>,
    /// The run pictured beside the truth (`truth/<scene>-<run>.png`, for the scenes with
    /// compared pixels): the base profile when it ran.
    pub pictured_run: String,
    pub base_profile: String,
    pub scenes: Vec<String>,
    pub rows: Vec<Row>,
    pub aggregates: Vec<Aggregate>,
    /// Files written, relative to the output folder.
    pub files: Vec<String>,
    pub command: String,
    /// Resident memory of the process at the end of the runs (Linux VmRSS), MiB.
    pub rss_mib_end: Option<f64>,
}


/// A run is "near" the front when no run beats it by more than this in both time and error.
pub const NEAR_FRONT: f64 = 0.05;

/// Registers DejaVu Sans as plotters' "sans-serif" (the `dejavu` crate's copy: no system
/// fonts), for the plot and the heat-map legends.
fn register_font() {
    static FONT: std::sync::Once = std::sync::Once::new();
    FONT.call_once(|| {
        let _ = plotters::style::register_font("sans-serif", plotters::style::FontStyle::Normal, dejavu::sans::regular());
    });
}

fn err(e: impl std::fmt::Display) -> String {
    e.to_string()
}

/// The profiles of the manifest, then the sweeps of [`SWEPT_KNOBS`] around the default profile.
pub fn default_runs(source_dir: &Path) -> Result<(String, Vec<RunSpec>), String> {
    let source = PackSource::load(source_dir).map_err(|d| d.message.clone())?;
    let options = tidepack_pack::pack_options::collect(&source).map_err(|d| format!("{} option errors", d.len()))?;
    let base = source.manifest.pack.default_profile.clone();
    let mut runs: Vec<RunSpec> = source.manifest.profiles.iter().map(|p| RunSpec::profile(&p.name)).collect();
    for knob in SWEPT_KNOBS {
        let option = options.get(knob).ok_or_else(|| format!("settings.glsl has no option {knob}"))?;
        let values: Vec<String> = match &option.kind {
            OptionKind::Switch { .. } => vec!["off".into(), "on".into()],
            OptionKind::Value { values, .. } => values.clone(),
        };
        runs.extend(values.iter().map(|v| RunSpec::sweep(&base, knob, v)));
    }
    Ok((base, runs))
}

fn option_key(pack: &LoadedPack) -> String {
    pack.options
        .iter()
        .map(|(k, v)| match v {
            OptionValue::Switch(b) => format!("{k}={}", if *b { "on" } else { "off" }),
            OptionValue::Value(s) => format!("{k}={s}"),
        })
        .collect::<Vec<_>>()
        .join(" ")
}

fn load_pack(source_dir: &Path, run: &RunSpec, specialisation: Option<&Specialisation>) -> Result<LoadedPack, String> {
    let options = match (&run.knob, &run.value) {
        (Some(k), Some(v)) => vec![(k.clone(), v.clone())],
        _ => vec![],
    };
    let selection = PackSelection { source_dir: source_dir.to_path_buf(), dialect: Dialect::Glsl330, profile: Some(run.profile.clone()), options };
    program::load_specialised(&selection, specialisation).map_err(|e| format!("{}: {e}", run.name))
}

/// The scenes to run (all, or those of `scene_filter`); a filter naming no scene is an error
/// listing the scenes there are.
pub fn scene_files(config: &BenchConfig) -> Result<Vec<(String, PathBuf)>, String> {
    let all: Vec<(String, PathBuf)> = tidepack_harness::scene::scene_files(&config.scenes_dir)
        .map_err(|e| e.to_string())?
        .into_iter()
        .filter_map(|p| Some((p.file_stem()?.to_string_lossy().into_owned(), p)))
        .collect();
    if all.is_empty() {
        return Err(format!("no scenes (*.toml) in {}", config.scenes_dir.display()));
    }
    let missing: Vec<&str> =
        config.scene_filter.iter().filter(|n| !all.iter().any(|(name, _)| name == *n)).map(String::as_str).collect();
    if !missing.is_empty() {
        let available: Vec<&str> = all.iter().map(|(name, _)| name.as_str()).collect();
        return Err(format!(
            "no scene named {} in {}; the scenes there are {}",
            missing.join(", "),
            config.scenes_dir.display(),
            available.join(", ")
        ));
    }
    Ok(all.into_iter().filter(|(n, _)| config.scene_filter.is_empty() || config.scene_filter.contains(n)).collect())
}

/// Runs the benchmark and writes every output file.
pub fn run(config: &BenchConfig) -> Result<BenchResult, String> {
    let (base, default) = default_runs(&config.source_dir)?;
    let runs = config.runs.clone().unwrap_or(default);
    let scenes: Vec<(String, Scene)> = scene_files(config)?
        .into_iter()
        .map(|(name, path)| {
            let scene = Scene::load(&path).map_err(err)?;
            let scene = match config.resolution {
                Some([w, h]) => scene.with_resolution(w, h),
                None => scene,
            };
            Ok((name, scene))
        })
        .collect::<Result<_, String>>()?;
    let gpu = Gpu::new().map_err(err)?;
    let frames = config.frames.max(1);

    let bar = if config.progress {
        indicatif::ProgressBar::new(scenes.len() as u64)
    } else {
        indicatif::ProgressBar::hidden()
    };
    bar.set_style(
        indicatif::ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} {msg}").map_err(err)?.progress_chars("=> "),
    );

    // The reference: converged settings, fed the G-buffers of the base profile's frame (every
    // profile but LOW has the same gbuffers_water options; LOW's flat surface counts as error).
    let base_pack = load_pack(&config.source_dir, &RunSpec::profile(&base), None)?;
    let settings = tidepack_reference::ReferenceSettings::converged();
    let mut references: BTreeMap<String, ReferenceImage> = BTreeMap::new();
    for (name, scene) in &scenes {
        bar.set_message(format!("reference {name}"));
        let frame = render_wgpu(&gpu, &base_pack, scene).map_err(err)?;
        let inputs = tidepack_reference::harness::inputs(&base_pack, scene, &frame)?;
        let mut image = tidepack_reference::render(&inputs, &settings, config.reference_stride)?;
        fill_strided(&mut image, config.reference_stride);
        references.insert(name.clone(), image);
        bar.inc(1);
    }

    let mut files = Vec::new();
    // The truth, once per scene: it depends on the scene alone (and the absorption density,
    // which every profile shares).
    let mut truths: BTreeMap<String, TruthFrame> = BTreeMap::new();
    for (name, scene) in &scenes {
        bar.set_message(format!("truth {name}"));
        truths.insert(name.clone(), TruthFrame::trace(scene, &settings, config.reference_stride)?);
    }

    for folder in ["heatmaps", "truth"] {
        std::fs::create_dir_all(config.out_dir.join(folder)).map_err(|e| format!("cannot create {}: {e}", config.out_dir.join(folder).display()))?;
    }
    // The run pictured beside the truth: the base profile, else the first run.
    let pictured = runs.iter().find(|r| r.name == base).or(runs.first()).map(|r| r.name.clone()).unwrap_or_default();
    for (name, truth) in &truths {
        let file = format!("truth/{name}.png");
        truth.rgb8().save(config.out_dir.join(&file)).map_err(|e| format!("cannot write {file}: {e}"))?;
        files.push(file);
    }
    // Option sets that come out equal (a sweep value that is the base's own) are measured once:
    // `set_of_run[i]` is the index in `sets` of run i's option set.
    struct OptionSet {
        pack: LoadedPack,
        /// The first run with these options (the profiles come first, so a repeated option set
        /// is a sweep value equal to the base profile's).
        run: RunSpec,
        /// One composite pipeline per frame size.
        runners: BTreeMap<(u32, u32), CompositeOnly>,
        /// Per scene, in scene order.
        rows: Vec<Row>,
    }
    let mut sets: Vec<OptionSet> = Vec::new();
    let mut keys: Vec<String> = Vec::new();
    let mut set_of_run = Vec::new();
    for run in &runs {
        let pack = load_pack(&config.source_dir, run, None)?;
        let key = option_key(&pack);
        match keys.iter().position(|k| *k == key) {
            Some(i) => set_of_run.push(i),
            None => {
                set_of_run.push(sets.len());
                keys.push(key);
                sets.push(OptionSet { pack, run: run.clone(), runners: BTreeMap::new(), rows: Vec::new() });
            }
        }
    }
    let pictured_set = runs.iter().position(|r| r.name == pictured).map_or(0, |i| set_of_run[i]);
    bar.set_length((scenes.len() * (1 + sets.len() + frames + 1)) as u64);
    let mut timing_gpu = true;
    for (name, scene) in &scenes {
        let values = uniforms::values(scene, Pass::Fullscreen);
        let size = (scene.width(), scene.height());
        // Every option set's whole frame once: the G-buffers composite is timed over, and the
        // composite image whose error is measured.
        let mut prepared = Vec::new();
        // With `specialise`, each option set's pack specialised for this scene, with its own
        // pipeline; otherwise the general pack and its pipeline for this frame size.
        let specialisation = config.specialise.then(|| uniforms::scene_specialisation(scene, name));
        let mut specialised: Vec<Option<(LoadedPack, CompositeOnly)>> = Vec::new();
        for (set_index, set) in sets.iter_mut().enumerate() {
            bar.set_message(format!("{} {name} (RSS {:.0} MiB)", set.run.name, tidepack_harness::resident_mib().unwrap_or(f64::NAN)));
            let own = match &specialisation {
                Some(spec) => {
                    let pack = load_pack(&config.source_dir, &set.run, Some(spec))?;
                    let runner = CompositeOnly::new(&gpu, &pack, size.0, size.1, &values).map_err(err)?;
                    Some((pack, runner))
                }
                None => {
                    if !set.runners.contains_key(&size) {
                        set.runners.insert(size, CompositeOnly::new(&gpu, &set.pack, size.0, size.1, &values).map_err(err)?);
                    }
                    None
                }
            };
            let pack = own.as_ref().map_or(&set.pack, |(pack, _)| pack);
            let frame = render_wgpu(&gpu, pack, scene).map_err(err)?;
            let (error, map) = metrics::error(&frame.image, &references[name]);
            let truth = &truths[name];
            let against_truth = metrics::error_where(&frame.image, &truth.image, &truth.compared);
            if set.run.kind == "profile" {
                let file = format!("heatmaps/{name}-{}.png", set.run.name);
                metrics::write_heatmap(&map, &config.out_dir.join(&file))?;
                files.push(file);
                if let Some((_, truth_map)) = &against_truth {
                    let file = format!("heatmaps/{name}-{}-truth.png", set.run.name);
                    metrics::write_heatmap(truth_map, &config.out_dir.join(&file))?;
                    files.push(file);
                }
            }
            if let (Some((_, truth_map)), true) = (&against_truth, set_index == pictured_set) {
                let file = format!("truth/{name}-{pictured}.png");
                metrics::side_by_side(&truth.rgb8(), &frame.image, truth_map)?
                    .save(config.out_dir.join(&file))
                    .map_err(|e| format!("cannot write {file}: {e}"))?;
                files.push(file);
            }
            prepared.push((GBuffers::from_frame(&frame), frame.image, error, against_truth.map(|(e, _)| e)));
            specialised.push(own);
            bar.inc(1);
        }
        // Rounds: every option set renders one frame of composite and of the pass-through per
        // round, starting with a different set each round, so that load changes on a shared
        // machine hit all sets alike. Round 0 is the warm-up (llvmpipe compiles the shader
        // variant at the first draw) and is dropped.
        let mut times: Vec<(Vec<f64>, Vec<f64>)> = vec![(Vec::new(), Vec::new()); sets.len()];
        let mut differences = vec![0.0f64; sets.len()];
        for round in 0..=frames {
            bar.set_message(format!("{name}: timing round {round}/{frames} (RSS {:.0} MiB)", tidepack_harness::resident_mib().unwrap_or(f64::NAN)));
            for k in 0..sets.len() {
                let i = (k + round) % sets.len();
                let set = &sets[i];
                let (g, image, _, _) = &prepared[i];
                let (pack, runner) = match &specialised[i] {
                    Some((pack, runner)) => (pack, runner),
                    None => (&set.pack, &set.runners[&size]),
                };
                let timed = runner.time(&gpu, pack, g, &values, 1).map_err(err)?;
                timing_gpu &= timed.gpu_timestamps;
                if round > 0 {
                    times[i].0.push(timed.composite_ms[0]);
                    times[i].1.push(timed.passthrough_ms[0]);
                }
                if round == frames {
                    differences[i] = timed
                        .image
                        .pixels
                        .iter()
                        .zip(&image.pixels)
                        .flat_map(|(a, b)| (0..4).map(move |c| if a[c] == b[c] { 0.0 } else { (a[c] as f64 - b[c] as f64).abs() }))
                        .fold(0.0, f64::max);
                }
            }
            bar.inc(1);
        }
        for (i, set) in sets.iter_mut().enumerate() {
            let (c, p) = (tidepack_harness::median(&times[i].0), tidepack_harness::median(&times[i].1));
            let (error, truth_error) = (prepared[i].2, prepared[i].3);
            set.rows.push(Row {
                scene: name.clone(),
                run: set.run.clone(),
                composite_ms: c,
                passthrough_ms: p,
                ratio: c / p,
                composite_frames_ms: times[i].0.clone(),
                passthrough_frames_ms: times[i].1.clone(),
                error,
                mse: error.rmse * error.rmse,
                truth_error,
                timed_image_difference: differences[i],
            });
        }
    }
    let rows: Vec<Row> = runs
        .iter()
        .zip(&set_of_run)
        .flat_map(|(run, &i)| sets[i].rows.iter().map(move |r| Row { run: run.clone(), ..r.clone() }))
        .collect();
    bar.finish_and_clear();

    let aggregates = output::aggregate(&runs, &rows);
    let a = &gpu.adapter;
    let mut result = BenchResult {
        adapter: format!("{} ({:?}, {} {})", a.name, a.backend, a.driver, a.driver_info).trim().to_string(),
        timing_source: if timing_gpu { "gpu" } else { "wall" }.into(),
        frames,
        resolution: config.resolution,
        reference_stride: config.reference_stride,
        reference_settings: format!("{settings:?}"),
        truth_options: format!("{:?}", TruthOptions { stride: config.reference_stride, ..TruthOptions::default() }),
        pictured_run: pictured,
        truth_pixels: truths.iter().map(|(n, t)| (n.clone(), t.compared.iter().filter(|&&c| c).count())).collect(),
        base_profile: base,
        scenes: scenes.iter().map(|(n, _)| n.clone()).collect(),
        rows,
        aggregates,
        files,
        command: config.command.clone(),
        rss_mib_end: tidepack_harness::resident_mib(),
    };
    output::write_all(config, &mut result)?;
    Ok(result)
}

/// A scene as the truth renders it, for scoring the pack's frames.
pub struct TruthFrame {
    /// Linear colour, bottom row first, as the composite's output.
    pub image: ReferenceImage,
    /// The pixels the water model is scored on: traced, some ray of them met water, and no
    /// overlay (rain, clouds, particles, the hand: the truth leaves them out) in front.
    pub compared: Vec<bool>,
}

impl TruthFrame {
    /// Traces `scene` with the absorption of `settings`, one sample at each pixel's centre
    /// (where the composite shades), every `stride`-th pixel.
    pub fn trace(scene: &Scene, settings: &tidepack_reference::ReferenceSettings, stride: usize) -> Result<TruthFrame, String> {
        let options = TruthOptions { stride, ..TruthOptions::default() };
        let traced = tidepack_truth::render(scene, settings, &options)?;
        let compared = (0..traced.pixels.len()).map(|i| traced.evaluated[i] && traced.water[i] && !traced.overlay[i]).collect();
        Ok(TruthFrame { image: ReferenceImage { width: traced.width, height: traced.height, pixels: traced.pixels }, compared })
    }

    /// As the 8-bit framebuffer would hold it, top row first.
    pub fn rgb8(&self) -> image::RgbImage {
        let (w, h) = (self.image.width as u32, self.image.height as u32);
        image::RgbImage::from_raw(w, h, metrics::reference_rgb8_top_first(&self.image)).expect("three bytes a pixel")
    }
}

/// With a stride above 1, each evaluated pixel stands for its stride × stride block.
fn fill_strided(image: &mut ReferenceImage, stride: usize) {
    if stride <= 1 {
        return;
    }
    let (w, h) = (image.width, image.height);
    for y in 0..h {
        for x in 0..w {
            image.pixels[y * w + x] = image.pixels[(y / stride * stride) * w + x / stride * stride];
        }
    }
}
