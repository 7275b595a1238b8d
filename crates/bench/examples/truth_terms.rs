//! How much of the model's distance from the truth one physical law makes: each profile's frame
//! against the truth with the radiance law (L/n² kept across the surface: a floor seen from the
//! air at 1/1.78 of its radiance in the water, the sky through Snell's window at 1.78 times) and
//! without it, with the mean luminance of the pack and of the truth over the compared pixels.
//!
//!     cargo run --release -p tidepack-bench --example truth_terms -- [SCENE ...]
//!
//! Without scenes: case1_above_dry, case2_under_down, case3_under_up, case4_above_near.

use std::path::Path;

use tidepack_bench::{TruthFrame, metrics};
use tidepack_harness::{Gpu, PackSelection, Scene, program, render_wgpu};
use tidepack_pack::Dialect;
use tidepack_reference::ReferenceImage;
use tidepack_truth::TruthOptions;

const PROFILES: [&str; 4] = ["LOW", "MEDIUM", "HIGH", "ULTRA"];

/// Rec. 709 luminance of a colour clamped to what the framebuffer holds.
fn luminance(rgb: [f64; 3]) -> f64 {
    let [r, g, b] = rgb.map(|c| c.clamp(0.0, 1.0));
    0.2126 * r + 0.7152 * g + 0.0722 * b
}

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut scenes: Vec<String> = std::env::args().skip(1).collect();
    if scenes.is_empty() {
        scenes = ["case1_above_dry", "case2_under_down", "case3_under_up", "case4_above_near"].map(String::from).to_vec();
    }
    let gpu = Gpu::new().unwrap_or_else(|e| panic!("{e}"));
    let settings = tidepack_reference::ReferenceSettings::converged();
    println!("{:<24} {:<7} {:>14} {:>14} {:>14} {:>14} {:>10} {:>12} {:>14}", "scene", "profile", "PSNR dB (law)", "FLIP (law)", "PSNR dB (no)", "FLIP (no)", "pack lum", "truth lum", "truth lum (no)");
    for name in &scenes {
        let scene = Scene::load(&root.join(format!("tests/scenes/{name}.toml"))).unwrap_or_else(|e| panic!("{name}: {e}"));
        let truths: Vec<TruthFrame> = [true, false]
            .map(|law| {
                let traced = tidepack_truth::render(&scene, &settings, &TruthOptions { radiance_scaling: law, ..TruthOptions::default() })
                    .unwrap_or_else(|e| panic!("{name}: {e}"));
                let compared = (0..traced.pixels.len()).map(|i| traced.water[i] && !traced.overlay[i]).collect();
                TruthFrame { image: ReferenceImage { width: traced.width, height: traced.height, pixels: traced.pixels }, compared }
            })
            .into();
        let compared = &truths[0].compared;
        let mean_over_compared = |values: &dyn Fn(usize) -> f64| {
            let n = compared.iter().filter(|&&c| c).count().max(1);
            (0..compared.len()).filter(|&i| compared[i]).map(values).sum::<f64>() / n as f64
        };
        let truth_luminance = truths.iter().map(|t| mean_over_compared(&|i| luminance(t.image.pixels[i].to_array()))).collect::<Vec<_>>();
        for profile in PROFILES {
            let selection = PackSelection { source_dir: root.join("shaderpack"), dialect: Dialect::Glsl330, profile: Some(profile.into()), options: vec![] };
            let pack = program::load_specialised(&selection, None).unwrap_or_else(|e| panic!("{profile}: {e}"));
            let frame = render_wgpu(&gpu, &pack, &scene).unwrap_or_else(|e| panic!("{name}: {e}"));
            let errors: Vec<_> = truths
                .iter()
                .map(|t| metrics::error_where(&frame.image, &t.image, &t.compared).map(|(e, _)| e).unwrap_or_else(|| panic!("{name} shows no water")))
                .collect();
            let pack_luminance = mean_over_compared(&|i| luminance(frame.image.pixels[i].map(f64::from)[..3].try_into().expect("rgb")));
            println!(
                "{:<24} {:<7} {:>14.1} {:>14.4} {:>14.1} {:>14.4} {:>10.4} {:>12.4} {:>14.4}",
                name, profile, errors[0].psnr, errors[0].mean_flip, errors[1].psnr, errors[1].mean_flip, pack_luminance, truth_luminance[0], truth_luminance[1]
            );
        }
    }
}
