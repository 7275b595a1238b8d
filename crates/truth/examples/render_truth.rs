//! `cargo run --release -p tidepack-truth --example render_truth -- SCENE OUT.png [SAMPLES_PER_AXIS]`:
//! the truth of a scene (a file or a built-in scene's name) at its resolution, written as an
//! 8-bit PNG (linear colour clamped to 0..1, top row first as PNGs are), with the time taken.

use std::path::Path;
use std::time::Instant;

use tidepack_reference::ReferenceSettings;
use tidepack_scene::Scene;
use tidepack_truth::{TruthOptions, render};

fn main() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [scene, out, rest @ ..] = args.as_slice() else {
        return Err("usage: render_truth SCENE OUT.png [SAMPLES_PER_AXIS]".into());
    };
    let samples_per_axis = match rest.first() {
        Some(n) => n.parse().map_err(|e| format!("samples per axis {n}: {e}"))?,
        None => 1,
    };
    let scene = Scene::load(Path::new(scene)).map_err(|e| e.to_string())?;
    let start = Instant::now();
    let image = render(&scene, &ReferenceSettings::converged(), &TruthOptions { samples_per_axis, ..TruthOptions::default() })?;
    let seconds = start.elapsed().as_secs_f64();
    let (w, h) = (image.width, image.height);
    let mut bytes = Vec::with_capacity(w * h * 4);
    for y in (0..h).rev() {
        for x in 0..w {
            let c = image.pixels[y * w + x];
            bytes.extend(c.to_array().map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8));
            bytes.push(255);
        }
    }
    let png = image::RgbaImage::from_raw(w as u32, h as u32, bytes).ok_or("image size")?;
    png.save(out).map_err(|e| format!("cannot write {out}: {e}"))?;
    let water = image.water.iter().filter(|&&m| m).count();
    let overlay = image.overlay.iter().filter(|&&m| m).count();
    println!("{}: {w}x{h}, {samples_per_axis}² samples per pixel, {seconds:.2} s; {water} pixels see water, {overlay} are under an overlay", scene.name);
    Ok(())
}
