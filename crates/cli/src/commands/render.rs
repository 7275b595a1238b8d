//! `tidepack render SCENE.toml`: renders one scene headless through the harness (wgpu on
//! lavapipe, optionally also Mesa's OpenGL) and writes the image and a JSON report.
//! Exit code 0: written; 1: the pack or scene does not render; 2: no driver (the message
//! names the Debian package) or the input cannot be read.

use std::path::PathBuf;
use std::process::ExitCode;

use super::{CANNOT_RUN, FINDINGS};

use clap::{Args, ValueEnum};
use tidepack_harness::HarnessError;

use super::configuration::ConfigurationArgs;
use tidepack_harness::job::{self, RenderJob};
use tidepack_pack::Dialect;

#[derive(Args)]
pub struct RenderArgs {
    /// Scene file, or the name of a scene tidepack carries (those of tests/scenes:
    /// case4_above_near, rain_over_lake, glass_over_land, …; a wrong name lists them).
    pub scene: PathBuf,
    /// GLSL dialect of the shipped text to render.
    #[arg(long, value_enum, default_value_t = RenderDialect::V330)]
    pub dialect: RenderDialect,
    /// Profile, options, dimension and loader (for our pack, `--profile` names a profile of
    /// pack.toml, whose values become the defaults; `--dimension` applies to `--pack` only).
    #[command(flatten)]
    pub configuration: ConfigurationArgs,
    /// Folder the PNG and JSON files are written to.
    #[arg(long, default_value = "render")]
    pub out: PathBuf,
    /// Also write colortex0, colortex4, depthtex0 and depthtex1 as PNG.
    #[arg(long)]
    pub buffers: bool,
    /// Also render through Mesa's OpenGL (the shipped text, unlowered) and report the
    /// largest difference per channel.
    #[arg(long)]
    pub gl: bool,
    /// Also render the pack specialised for this scene (uniforms it fixes folded into
    /// constants, as `build --scene` ships it) and report its composite time against the
    /// general pack's.
    #[arg(long)]
    pub specialise: bool,
    /// Folder with pack.toml and the shader templates.
    #[arg(long, default_value = "shaderpack")]
    pub source: PathBuf,
    /// Render any OptiFine or Iris pack (folder or zip) instead of ours: its whole pipeline,
    /// with every pass's time and NaN/Inf count, and what it uses that the harness does not
    /// imitate listed by name. With `--gl`, every step is also drawn through Mesa's OpenGL
    /// and compared texture by texture; `--profile` and `--set` choose the pack's option values.
    /// `--dialect`, `--specialise` and `--source` apply to our pack only.
    #[arg(long, value_name = "PATH", conflicts_with_all = ["specialise"])]
    pub pack: Option<PathBuf>,
    /// With --pack: frames to render; pass times and the frame's cost against a one-tap
    /// pass-through are medians over the frames after the first.
    #[arg(long, default_value_t = 1, requires = "pack", value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub frames: u32,
    /// With --pack: compare the screen with the blessed `DIR/<scene>.png` by mean FLIP, write
    /// the FLIP map and the difference beside the screen, and fail above --max-flip.
    #[arg(long, value_name = "DIR", requires = "pack")]
    pub expect: Option<PathBuf>,
    /// With --expect: write the screen as the blessed image instead of comparing.
    #[arg(long, requires = "expect")]
    pub bless: bool,
    /// With --expect: the largest mean FLIP that passes.
    #[arg(long, default_value_t = 0.03, requires = "expect")]
    pub max_flip: f64,
    /// With --pack --gl: the most pixels of one texture after one step that may differ
    /// between wgpu and OpenGL by more than 1/255; past it the run fails, naming the step where
    /// the renderers part [default: one pixel in 10,000 of the screen, at least 16].
    #[arg(long, value_name = "PIXELS", requires = "gl")]
    pub gl_max_pixels: Option<usize>,
}

#[derive(Clone, Copy, ValueEnum)]
pub enum RenderDialect {
    /// `#version 120`
    #[value(name = "120")]
    V120,
    /// `#version 330 compatibility`
    #[value(name = "330")]
    V330,
}

pub fn run(args: &RenderArgs) -> ExitCode {
    if let Some(pack) = &args.pack {
        return run_any_pack(args, pack);
    }
    let configuration = match args.configuration.configuration() {
        Ok(c) => c,
        Err(e) => return usage_error(&e),
    };
    let job = RenderJob {
        scene: args.scene.clone(),
        source_dir: args.source.clone(),
        dialect: match args.dialect {
            RenderDialect::V120 => Dialect::Glsl120,
            RenderDialect::V330 => Dialect::Glsl330,
        },
        profile: configuration.profile,
        options: configuration.options,
        loader: configuration.loader,
        distant_horizons: configuration.distant_horizons,
        out_dir: args.out.clone(),
        buffers: args.buffers,
        gl: args.gl,
        specialise: args.specialise,
    };
    let report = match job::run(&job) {
        Ok(r) => r,
        Err(e) => return failure(e),
    };
    say!("Rendered {}", report.rendered.describe(&format!("{}, {}, profile {}", report.dialect, report.rendered.loader, report.profile)));
    for p in &report.passes {
        say!("  {:<24} {:>9.3} ms ({})", p.pass, p.ms, if p.gpu_ms.is_some() { "GPU" } else { "wall" });
    }
    if let Some(r) = report.composite_over_passthrough {
        say!("  composite / pass-through {r:.1}x");
    }
    if report.non_finite_pixels > 0 {
        say!("  warning: {} pixels of the composite output are NaN or Inf", report.non_finite_pixels);
    }
    if let Some(gl) = &report.gl {
        let d = gl.max_difference.map(|c| c * 255.0);
        say!(
            "  OpenGL ({}): max difference per channel (x/255) R {:.2} G {:.2} B {:.2} A {:.2}, {} pixels over 1/255",
            gl.renderer, d[0], d[1], d[2], d[3], gl.pixels_over_1_255
        );
    }
    if let Some(spec) = &report.specialisation {
        super::print_specialisation(spec);
    }
    for f in &report.files {
        say!("  wrote {}", args.out.join(f).display());
    }
    ExitCode::SUCCESS
}

/// Prints a command-line mistake; exit code 2.
fn usage_error(message: &str) -> ExitCode {
    tell!("error: {message}");
    ExitCode::from(CANNOT_RUN)
}

/// Prints a harness error; exit code 2 where the input or a driver is missing, 1 otherwise.
fn failure(e: HarnessError) -> ExitCode {
    tell!("error: {e}");
    match e {
        HarnessError::NoAdapter(_)
        | HarnessError::NoGlDriver(_)
        | HarnessError::Io(_)
        | HarnessError::Scene(_)
        | HarnessError::Configuration(_) => ExitCode::from(CANNOT_RUN),
        _ => ExitCode::from(FINDINGS),
    }
}

fn run_any_pack(args: &RenderArgs, pack: &std::path::Path) -> ExitCode {
    let configuration = match args.configuration.configuration() {
        Ok(c) => c,
        Err(e) => return usage_error(&e),
    };
    let job = job::AnyPackJob {
        scene: args.scene.clone(),
        pack: pack.to_path_buf(),
        configuration,
        out_dir: args.out.clone(),
        buffers: args.buffers,
        gl: args.gl,
        frames: args.frames as usize,
        expect: args.expect.clone(),
        bless: args.bless,
        max_flip: args.max_flip,
        gl_max_pixels: args.gl_max_pixels,
    };
    let report = match job::run_any_pack(&job) {
        Ok(r) => r,
        Err(e) => return failure(e),
    };
    say!("Rendered {}", report.rendered.describe(&format!("{}, {}", report.pack, report.rendered.loader)));
    if let Some(why) = &report.renderer.wgpu_cannot_draw {
        say!("  drawn by {}, as wgpu cannot draw it: {why}", report.renderer.name);
    }
    if let Some(refused) = &report.renderer.opengl_refused {
        say!("  OpenGL refuses the frame too, so wgpu drew it without the programs naga cannot read: {refused}");
    }
    let source = if report.passes.iter().any(|p| p.gpu_ms.is_some()) { "GPU" } else { "wall" };
    // Which renderer drew each step, where any step was not wgpu's alone.
    let tagged = report.step_renderers.iter().any(|(_, by)| *by != job::StepRenderers::Wgpu);
    for (p, (_, by)) in report.passes.iter().zip(&report.step_renderers) {
        let time = format!("{:>9.3} ms", p.median_ms);
        let by = if tagged { format!("  [{}]", by.describe()) } else { String::new() };
        let bad: Vec<String> = p.non_finite.iter().filter(|(_, n)| **n > 0).map(|(b, n)| format!("{b}: {n} NaN/Inf")).collect();
        say!("  {:<40} {time}{by}{}", p.pass, if bad.is_empty() { String::new() } else { format!("  {}", bad.join(", ")) });
    }
    let t = &report.timing;
    say!(
        "  frame {:.3} ms, one-tap pass-through {:.3} ms: {:.1}x ({source} times, median of {} frame{})",
        t.frame_ms,
        t.passthrough_ms,
        t.frame_ms / t.passthrough_ms,
        t.frames.saturating_sub(1).max(1),
        if t.frames > 2 { "s after the first" } else { "" }
    );
    if let Some(gl) = &report.gl {
        if gl.steps.is_empty() && !gl.wgpu_cannot_draw.is_empty() {
            let why: Vec<&str> = gl.wgpu_cannot_draw.iter().map(|(_, why)| why.as_str()).collect();
            say!("  wgpu drew none of the steps beside OpenGL, which drew them alone: {}", why.join("; "));
        } else if !gl.wgpu_cannot_draw.is_empty() {
            let steps: Vec<&str> = gl.wgpu_cannot_draw.iter().map(|(step, _)| step.as_str()).collect();
            say!("  wgpu drew every other step from OpenGL's textures; OpenGL alone drew: {}", steps.join(", "));
        }
        say!(
            "  OpenGL ({}), largest difference per texture after each step both drew (x/255, colour/alpha; pixels over 1/255):",
            gl.renderer
        );
        for step in &gl.steps {
            let parts: Vec<String> = step
                .max_difference_255
                .iter()
                .map(|(t, d)| {
                    let mut sensitive = match step.sensitive_pixels.get(t) {
                        Some(n) => format!(", {n} of them the pack's own noise"),
                        None => String::new(),
                    };
                    if let Some(n) = step.undefined_pixels.get(t) {
                        sensitive.push_str(&format!(", {n} where GLSL leaves derivatives undefined"));
                    }
                    format!("{t} {:.2}/{:.2} ({} px{sensitive})", d[0].max(d[1]).max(d[2]), d[3], step.pixels_over_1_255[t])
                })
                .collect();
            if !parts.is_empty() {
                say!("    {:<38} {}", step.pass, parts.join(", "));
            }
        }
        if !report.gl_rewrites.is_empty() {
            say!("    rewritten for this driver, as lenient drivers take the text or where it passes this one's limits ({}):", report.gl_rewrites.len());
            for line in &report.gl_rewrites {
                say!("      {line}");
            }
        }
        if !gl.own_depth_mapping.is_empty() {
            say!("    drawn with OpenGL's own depth range: {}", gl.own_depth_mapping.join(", "));
        }
    }
    if !report.not_modelled.is_empty() {
        say!("  not imitated ({}):", report.not_modelled.len());
        for line in &report.not_modelled {
            say!("    {line}");
        }
    }
    for f in &report.files {
        say!("  wrote {}", args.out.join(f).display());
    }
    let mut failed = false;
    if let Some(expected) = &report.expected {
        match expected.mean_flip {
            None => say!("  blessed {}", expected.path),
            Some(flip) if expected.passed => say!("  mean FLIP {flip:.5} against {} (at most {})", expected.path, expected.max_flip),
            Some(flip) => {
                tell!("error: mean FLIP {flip:.5} against {} is over {}; see the .flip and .difference images", expected.path, expected.max_flip);
                failed = true;
            }
        }
    }
    if let Some(refused) = report.gl.as_ref().and_then(|gl| gl.refused.as_ref()) {
        tell!("error: Mesa's OpenGL refuses the pack, so the frames were not compared: {refused}");
        failed = true;
    }
    if let Some(d) = &report.gl_disagreement {
        let mut not_counted = Vec::new();
        if d.sensitive > 0 {
            not_counted.push(format!("{} of them the pack's own arithmetic noise, which a nudge of OpenGL's inputs shows", d.sensitive));
        }
        if d.undefined > 0 {
            not_counted.push(format!("{} where the step's implicit derivatives are undefined (a lookup in a branch its 2x2 quad takes apart)", d.undefined));
        }
        let sensitive = if not_counted.is_empty() { String::new() } else { format!(" ({}; not counted)", not_counted.join("; ")) };
        let file = d.file.as_ref().map_or(String::new(), |file| format!(" ({file})"));
        tell!(
            "error: wgpu and OpenGL part at step {}{file}: {} differs on {} pixels by more than 1/255 (up to {:.1}/255){sensitive}, over the {} allowed (--gl-max-pixels)",
            d.pass,
            d.texture,
            d.pixels,
            d.max_difference_255,
            d.max_pixels
        );
        failed = true;
    }
    if report.non_finite_pixels > 0 {
        let first = report.first_non_finite.as_ref().map_or(String::new(), |f| format!(": {f}"));
        tell!("error: {} pixels of the screen are NaN or Inf{first}", report.non_finite_pixels);
        failed = true;
    }
    for (program, why) in &report.failed_programs {
        tell!("error: {program} does not load, so the frame is not the one the loader draws: {why}");
        failed = true;
    }
    if report.pack_programs == 0 && report.failed_programs.is_empty() {
        let folder = if report.world.is_empty() { "shaders/".to_string() } else { format!("shaders/{}/", report.world) };
        tell!("error: {} loads no program of this pack (none in {folder}): the frame is the game's own shading, not the pack's", report.rendered.loader);
        failed = true;
    }
    if failed { ExitCode::from(FINDINGS) } else { ExitCode::SUCCESS }
}
