//! `tidepack compare`: our pack beside released packs on the same scenes (docs/compare.md). Each
//! pack draws each scene twice, with its water and without (the scene's water taken out, all
//! else equal), in alternating rounds so that load on a shared machine hits both alike. The
//! water's cost is the difference of the two frames' median times in units of the one-tap
//! pass-through measured in the same frames; the pictures go side by side, a row per scene.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::Serialize;
use tidepack_harness::any_pack::AnyPack;
use tidepack_harness::job::file_stem;
use tidepack_harness::{Gpu, Scene, water_cost};
use tidepack_loader::Configuration;
use tidepack_pack::Dialect;
use tidepack_pack::build::BuildOptions;

use crate::metrics;

/// The scenes the comparison draws by default, relative to the scenes folder, with what each
/// shows: the shore by day and by night, under water, rain, stained glass.
pub const DEFAULT_SCENES: [(&str, &str); 5] = [
    ("blocks/shore.toml", "shore"),
    ("case3_under_up.toml", "under water"),
    ("rain_over_lake.toml", "rain"),
    ("glass.toml", "stained glass"),
    ("blocks/shore_night.toml", "night"),
];

#[derive(Clone, Debug)]
pub struct CompareConfig {
    /// Our pack's source (pack.toml and shaders/): built into `out_dir` and drawn first.
    pub source_dir: PathBuf,
    /// Released packs (folders or zips), drawn after ours in this order.
    pub packs: Vec<PathBuf>,
    /// Scene files with a short label each.
    pub scenes: Vec<(PathBuf, String)>,
    /// Frames per rendering (the first is left out of the medians: llvmpipe compiles then).
    pub frames: usize,
    /// Renderings of each of the two scenes (with and without water), alternating.
    pub rounds: usize,
    pub out_dir: PathBuf,
    /// Also write the Markdown page here, its pictures in `<stem>/` beside it.
    pub report: Option<PathBuf>,
    /// The command line, quoted on the page.
    pub command: String,
}

/// One pack on one scene.
#[derive(Clone, Debug, Serialize)]
pub struct Measurement {
    pub pack: String,
    pub scene: String,
    /// Median frame time with the water, and without it (ms; GPU timestamps where the adapter
    /// has them), each the median over the rounds of the rounds' medians.
    pub wet_ms: f64,
    pub dry_ms: f64,
    /// Median one-tap pass-through over every frame of both.
    pub passthrough_ms: f64,
    /// The frame with water over the pass-through.
    pub frame_cost: f64,
    /// (wet − dry) over the pass-through: what the water costs this pack.
    pub water_cost: f64,
    /// Relative spread of the water cost: the interquartile range of the per-round differences
    /// over their median difference (NaN with fewer than 2 rounds).
    pub water_cost_spread: f64,
    /// NaN or Inf pixels on the screen with water.
    pub non_finite_pixels: usize,
    /// The screen with water, relative to the output folder.
    pub picture: String,
}

/// A pack that could not draw a scene, with why.
#[derive(Clone, Debug, Serialize)]
pub struct Failure {
    pub pack: String,
    pub scene: String,
    pub error: String,
}

#[derive(Clone, Debug, Serialize)]
pub struct CompareResult {
    pub adapter: String,
    pub frames: usize,
    pub rounds: usize,
    /// Packs in the order drawn (ours first) and scenes with their labels.
    pub packs: Vec<String>,
    pub scenes: Vec<(String, String)>,
    pub measurements: Vec<Measurement>,
    pub failures: Vec<Failure>,
    /// Programs a loader runs that a pack failed to load (the frame is then not the loader's).
    pub failed_programs: Vec<(String, String, String)>,
    /// Per scene, the pictures side by side (relative to the output folder).
    pub rows: Vec<(String, String)>,
    pub command: String,
}

fn err(e: impl std::fmt::Display) -> String {
    e.to_string()
}

/// Why no comparison was made. `cannot_run`: the input could not be read or no driver is
/// there (the command line's exit 2); otherwise the run itself failed.
#[derive(Debug)]
pub struct CompareError {
    pub message: String,
    pub cannot_run: bool,
}

impl CompareError {
    fn cannot_run(message: impl std::fmt::Display) -> CompareError {
        CompareError { message: message.to_string(), cannot_run: true }
    }
}

impl From<String> for CompareError {
    fn from(message: String) -> CompareError {
        CompareError { message, cannot_run: false }
    }
}

impl std::fmt::Display for CompareError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

/// A pack's name for the tables: its folder or zip name.
fn pack_name(path: &Path) -> String {
    path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_else(|| path.display().to_string())
}

/// Builds our pack (GLSL 330, default profile) into `out_dir/pack` and returns its zip.
fn build_ours(source_dir: &Path, out_dir: &Path) -> Result<PathBuf, CompareError> {
    let options = BuildOptions {
        source_dir: source_dir.to_path_buf(),
        out_dir: out_dir.join("pack"),
        dialects: vec![Dialect::Glsl330],
        profile: None,
        coverage: Default::default(),
        specialisation: None,
    };
    let report = tidepack_pack::build::build(&options, None).map_err(|f| {
        let first = f.diagnostics.first().map_or_else(String::new, |d| format!(": {}", d.message));
        if f.usage {
            CompareError::cannot_run(format!("cannot read our pack's source {}{first}", source_dir.display()))
        } else {
            CompareError::from(format!("our pack does not build ({} errors{first})", f.diagnostics.len()))
        }
    })?;
    Ok(report.outcomes.into_iter().next().map(|o| o.zip).ok_or_else(|| "the build wrote no zip".to_string())?)
}

/// Draws every pack on every scene, writes the pictures, the JSON and the page.
pub fn run(config: &CompareConfig) -> Result<CompareResult, CompareError> {
    // A pack that is not there is the command line's mistake, found before an hour of drawing.
    for pack in &config.packs {
        std::fs::metadata(pack).map_err(|e| CompareError::cannot_run(format!("cannot read pack {}: {e}", pack.display())))?;
    }
    std::fs::create_dir_all(config.out_dir.join("screens")).map_err(|e| format!("cannot create {}: {e}", config.out_dir.display()))?;
    let scenes: Vec<(String, String, Scene)> = config
        .scenes
        .iter()
        .map(|(path, label)| {
            let scene = Scene::load(path).map_err(CompareError::cannot_run)?;
            Ok((scene.name.clone(), label.clone(), scene))
        })
        .collect::<Result<_, CompareError>>()?;
    let ours = build_ours(&config.source_dir, &config.out_dir)?;
    let packs: Vec<PathBuf> = std::iter::once(ours).chain(config.packs.iter().cloned()).collect();
    let names: Vec<String> = packs.iter().map(|p| pack_name(p)).collect();
    let gpu = Gpu::new().map_err(|e| match e {
        tidepack_harness::HarnessError::NoAdapter(_) => CompareError::cannot_run(e),
        e => CompareError::from(e.to_string()),
    })?;
    let frames = config.frames.max(2);
    let rounds = config.rounds.max(1);
    let mut measurements = Vec::new();
    let mut failures = Vec::new();
    let mut failed_programs = Vec::new();
    // pictures[scene][pack]: the screen, or None where the pack could not draw it.
    let mut pictures: Vec<Vec<Option<image::RgbImage>>> = vec![Vec::new(); scenes.len()];
    for (path, name) in packs.iter().zip(&names) {
        let pack = match AnyPack::load(path, &Configuration::default()) {
            Ok(pack) => pack,
            Err(e) => {
                for (scene, _, _) in &scenes {
                    failures.push(Failure { pack: name.clone(), scene: scene.clone(), error: e.to_string() });
                }
                pictures.iter_mut().for_each(|row| row.push(None));
                continue;
            }
        };
        failed_programs.extend(pack.failed.iter().map(|(program, why)| (name.clone(), program.clone(), why.clone())));
        for (index, (scene_name, _, scene)) in scenes.iter().enumerate() {
            match measure(&gpu, &pack, scene, frames, rounds) {
                Ok((mut m, screen)) => {
                    m.pack = name.clone();
                    m.scene = scene_name.clone();
                    m.picture = format!("screens/{}-{}.png", file_stem(scene_name), file_stem(name));
                    screen.save(config.out_dir.join(&m.picture)).map_err(|e| format!("cannot write {}: {e}", m.picture))?;
                    pictures[index].push(Some(screen));
                    measurements.push(m);
                }
                Err(e) => {
                    failures.push(Failure { pack: name.clone(), scene: scene_name.clone(), error: e });
                    pictures[index].push(None);
                }
            }
        }
    }
    let mut rows = Vec::new();
    for ((scene_name, _, _), row) in scenes.iter().zip(&pictures) {
        let file = format!("{}.png", file_stem(scene_name));
        side_by_side(row).save(config.out_dir.join(&file)).map_err(|e| format!("cannot write {file}: {e}"))?;
        rows.push((scene_name.clone(), file));
    }
    let a = &gpu.adapter;
    let result = CompareResult {
        adapter: format!("{} ({:?}, {} {})", a.name, a.backend, a.driver, a.driver_info).trim().to_string(),
        frames,
        rounds,
        packs: names,
        scenes: scenes.iter().map(|(n, l, _)| (n.clone(), l.clone())).collect(),
        measurements,
        failures,
        failed_programs,
        rows,
        command: config.command.clone(),
    };
    write(config, &result)?;
    Ok(result)
}

/// One pack on one scene: the rounds with and without water, and the screen with water.
fn measure(gpu: &Gpu, pack: &AnyPack, scene: &Scene, frames: usize, rounds: usize) -> Result<(Measurement, image::RgbImage), String> {
    let (cost, image) = water_cost::measure(gpu, pack, scene, frames, rounds).map_err(err)?;
    let measurement = Measurement {
        pack: String::new(),
        scene: String::new(),
        wet_ms: cost.wet_ms,
        dry_ms: cost.dry_ms,
        passthrough_ms: cost.passthrough_ms,
        frame_cost: cost.frame_cost(),
        water_cost: cost.water_cost(),
        water_cost_spread: crate::pareto::relative_spread(&cost.differences).abs(),
        non_finite_pixels: image.non_finite(),
        picture: String::new(),
    };
    let rgb = image::RgbImage::from_raw(image.width, image.height, image.to_rgb8_top_first()).expect("three bytes a pixel");
    Ok((measurement, rgb))
}

/// A scene's screens left to right at half size, in pack order; grey where a pack could not
/// draw it.
fn side_by_side(screens: &[Option<image::RgbImage>]) -> image::RgbImage {
    let (w, h) = screens.iter().flatten().next().map_or((640, 360), |s| (s.width(), s.height()));
    let grey = image::RgbImage::from_pixel(w, h, image::Rgb([128, 128, 128]));
    let halves: Vec<image::RgbImage> = screens.iter().map(|s| metrics::half_size(s.as_ref().unwrap_or(&grey))).collect();
    metrics::panels(&halves)
}

fn cost(value: f64, spread: f64) -> String {
    if spread.is_finite() { format!("{value:.1}× ±{:.0}%", 100.0 * spread) } else { format!("{value:.1}×") }
}

/// The page: how it was measured, the cost table, and a row of pictures per scene.
pub fn markdown(result: &CompareResult, pictures: &str) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# Our water beside released packs\n");
    let _ = writeln!(s, "Generated by `tidepack compare` (crates/bench/src/compare.rs); regenerate with\n\n    {}\n", result.command);
    let _ = writeln!(
        s,
        "- Adapter: {}. Each pack draws each scene with its water and with the water taken out of the scene (everything \
         else equal), {} renderings of each, alternating, {} frames each; a rendering's time is the median of its frames \
         after the first (llvmpipe compiles shaders then), and the table gives the median over the renderings.",
        result.adapter, result.rounds, result.frames
    );
    let _ = writeln!(
        s,
        "- **Water cost**: (frame with water − frame without) / the one-tap pass-through (a full-screen copy of \
         colortex0) measured in the same frames, so that it reads in units of the cheapest full-screen pass. ± is the \
         interquartile range of the per-rendering differences over their median. **Frame**: the whole frame with \
         water in the same units.\n- Each pack is drawn as OptiFine draws it with its default options \
         (`tidepack render --pack`, docs/harness.md); tidepack's own is the GLSL 330 zip of `shaderpack/` at its \
         default profile.\n"
    );
    let _ = writeln!(s, "## Cost\n");
    let header: Vec<String> = result.scenes.iter().map(|(n, l)| format!("{l} (`{n}`) water / frame")).collect();
    let _ = writeln!(s, "| pack | {} |", header.join(" | "));
    let _ = writeln!(s, "|---|{}", "---|".repeat(result.scenes.len()));
    for pack in &result.packs {
        let cells: Vec<String> = result
            .scenes
            .iter()
            .map(|(scene, _)| match result.measurements.iter().find(|m| &m.pack == pack && &m.scene == scene) {
                Some(m) => format!("{} / {:.1}×", cost(m.water_cost, m.water_cost_spread), m.frame_cost),
                None => "did not draw".into(),
            })
            .collect();
        let _ = writeln!(s, "| {pack} | {} |", cells.join(" | "));
    }
    if !result.failures.is_empty() || !result.failed_programs.is_empty() {
        let _ = writeln!(s, "\n## What did not draw\n");
        for f in &result.failures {
            let _ = writeln!(s, "- {} on `{}`: {}", f.pack, f.scene, f.error);
        }
        for (pack, program, why) in &result.failed_programs {
            let _ = writeln!(s, "- {pack}: program {program} did not load ({why}), so its frames are not the loader's");
        }
    }
    let _ = writeln!(s, "\n## Pictures\n");
    let _ = writeln!(s, "Left to right: {}. Half size; grey where a pack did not draw the scene.\n", result.packs.join(", "));
    for ((scene, label), (_, file)) in result.scenes.iter().zip(&result.rows) {
        let _ = writeln!(s, "### {label} (`{scene}`)\n\n![{label}: {}]({pictures}/{file})\n", result.packs.join(", "));
    }
    s
}

/// compare.json, report.md and, with `report`, the page and its pictures beside it.
fn write(config: &CompareConfig, result: &CompareResult) -> Result<(), String> {
    let out = &config.out_dir;
    let json = serde_json::to_string_pretty(result).map_err(err)? + "\n";
    std::fs::write(out.join("compare.json"), json).map_err(|e| format!("cannot write compare.json: {e}"))?;
    std::fs::write(out.join("report.md"), markdown(result, ".")).map_err(|e| format!("cannot write report.md: {e}"))?;
    if let Some(report) = &config.report {
        let stem = report.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "compare".into());
        let dir = report.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
        let pictures_dir = dir.join(&stem);
        if pictures_dir.exists() {
            std::fs::remove_dir_all(&pictures_dir).map_err(|e| format!("cannot clear {}: {e}", pictures_dir.display()))?;
        }
        std::fs::create_dir_all(&pictures_dir).map_err(|e| format!("cannot create {}: {e}", pictures_dir.display()))?;
        for (_, file) in &result.rows {
            std::fs::copy(out.join(file), pictures_dir.join(file)).map_err(|e| format!("cannot copy {file}: {e}"))?;
        }
        std::fs::write(report, markdown(result, &stem)).map_err(|e| format!("cannot write {}: {e}", report.display()))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_scene_a_pack_could_not_draw_is_grey_beside_the_others() {
        let red = image::RgbImage::from_pixel(8, 4, image::Rgb([255, 0, 0]));
        let row = side_by_side(&[Some(red), None]);
        assert_eq!((row.width(), row.height()), (2 * 4 + metrics::PANEL_GAP, 2));
        assert_eq!(row.get_pixel(0, 0).0, [255, 0, 0]);
        assert_eq!(row.get_pixel(4 + metrics::PANEL_GAP, 0).0, [128, 128, 128]);
    }
}
