//! Renders one scene with every pack of a folder through `render --pack --gl` and prints, per
//! pack, whether it rendered as `render` would exit 0, the renderer that drew it (wgpu, or
//! OpenGL where wgpu cannot, and why), how far Mesa's OpenGL screen is from wgpu's, the frame's
//! cost against a one-tap pass-through, how many things it uses that the harness does not
//! imitate, and why a pack failed. tools/render-corpus runs it.
//!
//!     render_corpus SCENE.toml OUT_DIR PACK_DIR...

use std::path::PathBuf;

use tidepack_harness::job::{self, AnyPackJob};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [scene, out, packs @ ..] = args.as_slice() else {
        eprintln!("usage: render_corpus SCENE.toml OUT_DIR PACK_DIR...");
        std::process::exit(2);
    };
    println!("| pack | result | renderer | screen vs OpenGL: pixels over 1/255 (largest, x/255) | frame / pass-through | not imitated |");
    println!("|---|---|---|---:|---:|---:|");
    let (mut by_wgpu, mut by_opengl) = (0, 0);
    for pack in packs {
        let path = PathBuf::from(pack);
        let name = path.file_name().map_or_else(|| pack.clone(), |n| n.to_string_lossy().into_owned());
        let job = AnyPackJob {
            scene: PathBuf::from(scene),
            pack: path.clone(),
            configuration: Default::default(),
            out_dir: PathBuf::from(out).join(&name),
            buffers: false,
            gl: true,
            frames: 3,
            expect: None,
            bless: false,
            max_flip: 0.0,
            gl_max_pixels: None,
        };
        match job::run_any_pack(&job) {
            Ok(report) => {
                let gl = report.gl.as_ref();
                let screen = gl.and_then(|g| g.steps.last()).and_then(|s| {
                    let (name, d) = s.max_difference_255.iter().next()?;
                    Some(format!("{} ({:.2})", s.pixels_over_1_255[name], d.iter().fold(0f32, |m, c| m.max(*c))))
                });
                let failure = if let Some(refused) = gl.and_then(|g| g.refused.as_ref()) {
                    format!("OpenGL refuses: {}", cell(refused))
                } else if let Some((program, why)) = report.failed_programs.first() {
                    format!("{program} does not load: {}", cell(why))
                } else if report.non_finite_pixels > 0 {
                    format!("{} NaN/Inf pixels", report.non_finite_pixels)
                } else if let Some(d) = &report.gl_disagreement {
                    format!("the renderers part at {}: {} differs on {} pixels", d.pass, d.texture, d.pixels)
                } else {
                    if report.renderer.wgpu_cannot_draw.is_some() { by_opengl += 1 } else { by_wgpu += 1 }
                    "rendered".to_string()
                };
                let renderer = match &report.renderer.wgpu_cannot_draw {
                    Some(why) => format!("OpenGL (wgpu: {})", cell(why)),
                    None => "wgpu".to_string(),
                };
                let t = &report.timing;
                println!(
                    "| {name} | {failure} | {renderer} | {} | {:.1}x | {} |",
                    screen.unwrap_or_else(|| "-".into()),
                    t.frame_ms / t.passthrough_ms,
                    report.not_modelled.len()
                );
            }
            Err(e) => println!("| {name} | {} | - | - | - | - |", cell(&e.to_string())),
        }
    }
    println!(
        "\n{} of {} packs rendered as `render --pack --gl` exits 0: {by_wgpu} by wgpu with OpenGL agreeing, {by_opengl} by OpenGL where wgpu cannot draw them",
        by_wgpu + by_opengl,
        packs.len()
    );
}

/// A message on one line, short enough for a table cell, without `|`. wgpu's messages repeat
/// their cause: the last 160 characters say it.
fn cell(text: &str) -> String {
    let line = text.split_whitespace().collect::<Vec<_>>().join(" ").replace('|', "/");
    let chars: Vec<char> = line.chars().collect();
    if chars.len() <= 160 { line } else { format!("…{}", chars[chars.len() - 160..].iter().collect::<String>()) }
}
