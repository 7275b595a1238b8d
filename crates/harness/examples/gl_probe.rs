//! Diagnostic: where OpenGL and wgpu differ, stage by stage (depth buffers
//! bit for bit, colour buffers, composite output), with the worst pixels listed and a difference
//! image in target/gl-probe/ (red: output over 1/255, green: depth0 differs).
//!
//!     cargo run --release -p tidepack-harness --example gl_probe
//!
//! PROBE_SCENES=a,b (default: all)  PROBE_DIALECT=120|330  PROBE_NUDGE=dx,dy,dz (camera offset
//! in blocks)
//! PROBE_IMAGE_BITS=1 (also count output pixels differing at all, and by more than 0.1/255).

use std::path::{Path, PathBuf};

use tidepack_harness::images::{self, FloatImage};
use tidepack_harness::{Gpu, PackSelection, Scene, gl, program, render_gl, render_wgpu};
use tidepack_pack::Dialect;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Pixels whose largest channel difference exceeds `threshold` (`0.0`: any bit).
fn differing(name: &str, a: &FloatImage, b: &FloatImage, threshold: f32) -> Vec<(u32, u32, f32)> {
    let mut v = Vec::new();
    for y in 0..a.height {
        for x in 0..a.width {
            let (p, q) = (a.at(x, y), b.at(x, y));
            let d = (0..4).map(|c| (p[c] - q[c]).abs()).fold(0.0f32, f32::max);
            if d > threshold || (threshold == 0.0 && p.map(f32::to_bits) != q.map(f32::to_bits)) {
                v.push((x, y, d));
            }
        }
    }
    let max = images::max_channel_difference(a, b).into_iter().fold(0.0f32, f32::max);
    println!("  {name:<10} {:>6} pixels differ by more than {threshold:e}, max {max:e}", v.len());
    v
}

fn main() {
    let names: Vec<String> = match std::env::var("PROBE_SCENES") {
        Ok(s) => s.split(',').map(str::to_string).collect(),
        Err(_) => {
            let files = tidepack_harness::scene::scene_files(&root().join("tests/scenes")).unwrap_or_else(|e| panic!("{e}"));
            files.iter().filter_map(|p| p.file_stem().map(|s| s.to_string_lossy().into_owned())).collect()
        }
    };
    let nudge: Vec<f64> =
        std::env::var("PROBE_NUDGE").map(|s| s.split(',').map(|v| v.parse().unwrap()).collect()).unwrap_or(vec![0.0; 3]);
    let dialect = if std::env::var("PROBE_DIALECT").as_deref() == Ok("120") { Dialect::Glsl120 } else { Dialect::Glsl330 };
    let pack = program::load(&PackSelection { source_dir: root().join("shaderpack"), dialect, profile: None, options: vec![] }).unwrap();
    let gpu = Gpu::new().unwrap();
    let ctx = gl::context().unwrap();
    let out = root().join("target/gl-probe");
    for name in &names {
        let mut s = Scene::load(&root().join(format!("tests/scenes/{name}.toml"))).unwrap();
        for (i, d) in nudge.iter().enumerate() {
            s.camera.position[i] += d;
        }
        let w = render_wgpu(&gpu, &pack, &s).unwrap();
        let g = render_gl(&ctx, &pack, &s).unwrap();
        println!("{name} ({dialect}, camera nudged by {nudge:?}):");
        differing("depth1", &w.depth1, &g.depth1, 0.0);
        let d0 = differing("depth0", &w.depth0, &g.depth0, 0.0);
        for (b, img) in &w.buffers {
            differing(&format!("colortex{b}"), img, &g.buffers[b], 0.0);
        }
        if std::env::var("PROBE_IMAGE_BITS").is_ok() {
            differing("image bits", &w.image, &g.image, 0.0);
            differing("image 0.1", &w.image, &g.image, 0.1 / 255.0);
        }
        let img = differing("image", &w.image, &g.image, images::OVER_1_255);
        let max = images::max_channel_difference(&w.image, &g.image);
        println!("  SUMMARY {name:<18} max diff (x/255) {:?}, {} pixels over 1/255", max.map(|d| (d * 255.0 * 100.0).round() / 100.0), img.len());
        let mut worst = img.clone();
        worst.sort_by(|a, b| b.2.total_cmp(&a.2));
        for &(x, y, d) in worst.iter().take(20) {
            let i = (y * s.width() + x) as usize;
            println!(
                "    ({x},{y} from the bottom) {:.1}/255: wgpu {:?} gl {:?}; depth0 {} / {}; depth1 {} / {}; colortex4.a {} / {}",
                d * 255.0,
                w.image.pixels[i],
                g.image.pixels[i],
                w.depth0.pixels[i][0],
                g.depth0.pixels[i][0],
                w.depth1.pixels[i][0],
                g.depth1.pixels[i][0],
                w.buffers[&4].pixels[i][3],
                g.buffers[&4].pixels[i][3],
            );
        }
        let mut diff = FloatImage::new(s.width(), s.height());
        for &(x, y, _) in &img {
            diff.pixels[(y * s.width() + x) as usize][0] = 1.0;
        }
        for &(x, y, _) in &d0 {
            diff.pixels[(y * s.width() + x) as usize][1] = 1.0;
        }
        let slug = dialect.slug();
        diff.write_png(&out.join(format!("{name}.{slug}.diff.png")), false).unwrap();
        w.image.write_png(&out.join(format!("{name}.{slug}.wgpu.png")), false).unwrap();
        g.image.write_png(&out.join(format!("{name}.{slug}.gl.png")), false).unwrap();
    }
}
