//! Renders one scene with every pack of a folder through `render --pack --gl` and prints, per
//! pack, whether it rendered as `render` would exit 0, the renderer that drew it (wgpu, or
//! OpenGL where wgpu cannot, and why), how far Mesa's OpenGL screen is from wgpu's, the frame's
//! cost against a one-tap pass-through, its water's cost (the scene with its water minus the
//! same scene without, through wgpu, where wgpu draws the pack), how many things it uses that
//! the harness does not imitate, and why a pack failed. A pack that does not render under OptiFine is tried under
//! Iris (a pack for Iris alone shows an "Iris required" screen under OptiFine); the row names
//! the loader it rendered under, and a list after the table says why OptiFine did not.
//! tools/render-corpus runs it. `--no-water-cost` leaves the water's cost out (a third of the
//! time), for a run that asks only which packs render.
//!
//!     render_corpus [--no-water-cost] SCENE.toml OUT_DIR PACK_DIR...

use std::path::PathBuf;

use tidepack_harness::any_pack::AnyPack;
use tidepack_harness::job::{self, AnyPackJob, AnyPackReport};
use tidepack_harness::{Gpu, Loader, Scene, water_cost};
use tidepack_loader::option_space::Configuration;

/// Frames of each rendering and renderings with and without water for the water's cost.
const WATER_COST_FRAMES: usize = 3;
const WATER_COST_ROUNDS: usize = 2;

fn main() {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let water_costs = match args.first().map(String::as_str) {
        Some("--no-water-cost") => {
            args.remove(0);
            false
        }
        _ => true,
    };
    let [scene, out, packs @ ..] = args.as_slice() else {
        eprintln!("usage: render_corpus [--no-water-cost] SCENE.toml OUT_DIR PACK_DIR...");
        std::process::exit(2);
    };
    println!("| pack | result | renderer | screen vs OpenGL: pixels over 1/255 (largest, x/255) | frame / pass-through | water / pass-through | not imitated |");
    println!("|---|---|---|---:|---:|---:|---:|");
    let (mut by_wgpu, mut by_opengl) = (0, 0);
    let mut under_iris = Vec::new();
    for pack in packs {
        let path = PathBuf::from(pack);
        let name = path.file_name().map_or_else(|| pack.clone(), |n| n.to_string_lossy().into_owned());
        let run = |loader: Loader| {
            let job = AnyPackJob {
                scene: PathBuf::from(scene),
                pack: path.clone(),
                configuration: Configuration { loader, ..Configuration::default() },
                out_dir: PathBuf::from(out).join(&name),
                buffers: false,
                gl: true,
                frames: 3,
                expect: None,
                bless: false,
                max_flip: 0.0,
                gl_max_pixels: None,
            };
            job::run_any_pack(&job).map_err(|e| cell(&e.to_string())).map(|report| (failure(&report), report))
        };
        // A pack for Iris alone (one that shows an "Iris required" screen under OptiFine, fails
        // there, or has no program where OptiFine looks) is rendered under Iris, and the row
        // says so; where OptiFine loads none of its programs, Iris's verdict is the pack's.
        let mut outcome = run(Loader::default());
        let rendered = |o: &Result<(Option<String>, AnyPackReport), String>| matches!(o, Ok((None, report)) if report.pack_programs > 0);
        if !rendered(&outcome) {
            let optifine = match &outcome {
                Ok((Some(why), _)) | Err(why) => why.clone(),
                Ok((None, _)) => "no program of the pack where OptiFine looks: the game's own shading".to_string(),
            };
            let none_loaded = matches!(&outcome, Ok((None, _)));
            let iris = run(Loader::Iris);
            if rendered(&iris) {
                outcome = iris.map(|(_, report)| (None, report));
                under_iris.push((name.clone(), optifine));
            } else if none_loaded {
                outcome = iris.map(|(why, report)| (why.or_else(|| Some("no program of the pack loaded under either loader".to_string())), report));
            }
        }
        match outcome {
            Ok((failure, report)) => {
                let gl = report.gl.as_ref();
                let screen = gl.and_then(|g| g.steps.last()).and_then(|s| {
                    let (name, d) = s.max_difference_255.iter().next()?;
                    Some(format!("{} ({:.2})", s.pixels_over_1_255[name], d.iter().fold(0f32, |m, c| m.max(*c))))
                });
                let result = match failure {
                    Some(why) => why,
                    None => {
                        if report.renderer.wgpu_cannot_draw.is_some() { by_opengl += 1 } else { by_wgpu += 1 }
                        format!("rendered ({})", report.rendered.loader)
                    }
                };
                let renderer = match (&report.renderer.wgpu_cannot_draw, gl) {
                    (Some(why), Some(gl)) => format!(
                        "OpenGL; wgpu beside it on {} steps, not on {} (wgpu: {})",
                        gl.steps.len(),
                        gl.wgpu_cannot_draw.len(),
                        cell(why)
                    ),
                    (Some(why), None) => format!("OpenGL (wgpu: {})", cell(why)),
                    (None, _) => "wgpu".to_string(),
                };
                let t = &report.timing;
                let water = if water_costs && report.renderer.wgpu_cannot_draw.is_none() && report.pack_programs > 0 {
                    water_cost_of(&path, &report.rendered.loader, scene).unwrap_or_else(|e| format!("- ({})", cell(&e)))
                } else {
                    "-".to_string()
                };
                println!(
                    "| {name} | {result} | {renderer} | {} | {:.1}x | {water} | {} |",
                    screen.unwrap_or_else(|| "-".into()),
                    t.frame_ms / t.passthrough_ms,
                    report.not_modelled.len()
                );
            }
            Err(e) => println!("| {name} | {e} | - | - | - | - | - |"),
        }
    }
    println!(
        "\n{} of {} packs rendered as `render --pack --gl` exits 0: {by_wgpu} by wgpu with OpenGL agreeing, {by_opengl} by OpenGL where wgpu cannot draw a program (wgpu agreeing on the steps it draws)",
        by_wgpu + by_opengl,
        packs.len()
    );
    for (name, optifine) in &under_iris {
        println!("- {name} rendered under Iris; under OptiFine: {optifine}");
    }
}

/// The water's cost to the pack at `path` under `loader` on `scene`, in pass-throughs.
fn water_cost_of(path: &std::path::Path, loader: &str, scene: &str) -> Result<String, String> {
    let loader: Loader = loader.parse()?;
    let pack = AnyPack::load(path, &Configuration { loader, ..Configuration::default() }).map_err(|e| e.to_string())?;
    let scene = Scene::load(std::path::Path::new(scene)).map_err(|e| e.to_string())?;
    let gpu = Gpu::new().map_err(|e| e.to_string())?;
    let (cost, _) = water_cost::measure(&gpu, &pack, &scene, WATER_COST_FRAMES, WATER_COST_ROUNDS).map_err(|e| e.to_string())?;
    Ok(format!("{:.1}x", cost.water_cost()))
}

/// Why a run does not count as rendered (`render` would not exit 0), or `None`.
fn failure(report: &AnyPackReport) -> Option<String> {
    let gl = report.gl.as_ref();
    if let Some(refused) = gl.and_then(|g| g.refused.as_ref()) {
        Some(format!("OpenGL refuses: {}", cell(refused)))
    } else if let Some((program, why)) = report.failed_programs.first() {
        Some(format!("{program} does not load: {}", cell(why)))
    } else if report.non_finite_pixels > 0 {
        let first = report.first_non_finite.as_ref().map_or(String::new(), |f| format!(", {f}"));
        Some(format!("{} NaN/Inf pixels{first}", report.non_finite_pixels))
    } else {
        report.gl_disagreement.as_ref().map(|d| {
            let mut not_counted = Vec::new();
            if d.sensitive > 0 {
                not_counted.push(format!("{} the pack's own noise", d.sensitive));
            }
            if d.undefined > 0 {
                not_counted.push(format!("{} with undefined derivatives", d.undefined));
            }
            let sensitive = if not_counted.is_empty() { String::new() } else { format!(" ({})", not_counted.join(", ")) };
            let file = d.file.as_ref().map_or(String::new(), |file| format!(" ({file})"));
            format!("the renderers part at {}{file}: {} differs on {} pixels{sensitive}", d.pass, d.texture, d.pixels)
        })
    }
}

/// A message on one line, short enough for a table cell, without `|`. wgpu's messages repeat
/// their cause: the last 160 characters say it.
fn cell(text: &str) -> String {
    let line = text.split_whitespace().collect::<Vec<_>>().join(" ").replace('|', "/");
    let chars: Vec<char> = line.chars().collect();
    if chars.len() <= 160 { line } else { format!("…{}", chars[chars.len() - 160..].iter().collect::<String>()) }
}
