//! Aggregation over scenes, the Pareto front, and the files: terminal table, CSV, JSON, the
//! plot (plotters, bitmap backend) and the Markdown report.

use std::fmt::Write as _;
use std::path::Path;

use plotters::prelude::*;

use crate::metrics::psnr_of_mse;
use crate::{Aggregate, BenchConfig, BenchResult, NEAR_FRONT, Row, RunSpec};

fn mean(v: impl Iterator<Item = f64>) -> f64 {
    let (s, n) = v.fold((0.0, 0usize), |(s, n), x| (s + x, n + 1));
    if n == 0 { f64::NAN } else { s / n as f64 }
}

/// Per run over all scenes, with the Pareto front in (ratio, mean FLIP).
pub fn aggregate(runs: &[RunSpec], rows: &[Row]) -> Vec<Aggregate> {
    let mut out: Vec<Aggregate> = runs
        .iter()
        .map(|run| {
            let r: Vec<&Row> = rows.iter().filter(|r| r.run.name == run.name).collect();
            let mse = mean(r.iter().map(|r| r.mse));
            Aggregate {
                run: run.clone(),
                ratio: mean(r.iter().map(|r| r.ratio)),
                composite_ms: mean(r.iter().map(|r| r.composite_ms)),
                passthrough_ms: mean(r.iter().map(|r| r.passthrough_ms)),
                max_abs: r.iter().map(|r| r.error.max_abs).fold(0.0, f64::max),
                rmse: mse.sqrt(),
                psnr: psnr_of_mse(mse),
                mean_flip: mean(r.iter().map(|r| r.error.mean_flip)),
                on_front: true,
                dominated_by: vec![],
            }
        })
        .collect();
    let points: Vec<(String, f64, f64)> = out.iter().map(|a| (a.run.name.clone(), a.ratio, a.mean_flip)).collect();
    for a in &mut out {
        for (name, t, e) in &points {
            let dominates = *t <= a.ratio && *e <= a.mean_flip && (*t < a.ratio || *e < a.mean_flip);
            if dominates {
                a.on_front = false;
                // How much better the dominating run is in its weaker coordinate.
                let margin = (1.0 - t / a.ratio).min(1.0 - e / a.mean_flip.max(f64::MIN_POSITIVE));
                a.dominated_by.push((name.clone(), margin));
            }
        }
        a.dominated_by.sort_by(|x, y| y.1.total_cmp(&x.1));
    }
    out
}

/// On the front, or beaten by no run by more than [`NEAR_FRONT`] in both coordinates.
pub fn near_front(a: &Aggregate) -> bool {
    a.on_front || a.dominated_by.first().is_none_or(|(_, m)| *m <= NEAR_FRONT)
}

fn front_label(a: &Aggregate) -> String {
    if a.on_front {
        "front".into()
    } else if near_front(a) {
        format!("near ({} by {:.1}%)", a.dominated_by[0].0, 100.0 * a.dominated_by[0].1)
    } else {
        format!("dominated by {} (by {:.0}%)", a.dominated_by[0].0, 100.0 * a.dominated_by[0].1)
    }
}

fn db(psnr: f64) -> String {
    if psnr.is_finite() { format!("{psnr:.1}") } else { "identical".into() }
}

/// The aggregate table, one line per run (terminal).
pub fn table(result: &BenchResult) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<34} {:>9} {:>10} {:>9} {:>8} {:>9} {:>10}  pareto",
        "run (mean over scenes)", "comp/pt", "comp ms", "max abs", "RMSE", "PSNR dB", "mean FLIP"
    );
    for a in &result.aggregates {
        let _ = writeln!(
            s,
            "{:<34} {:>8.2}x {:>10.3} {:>9.4} {:>8.5} {:>9} {:>10.5}  {}",
            a.run.name,
            a.ratio,
            a.composite_ms,
            a.max_abs,
            a.rmse,
            db(a.psnr),
            a.mean_flip,
            front_label(a)
        );
    }
    s
}

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) { format!("\"{}\"", s.replace('"', "\"\"")) } else { s.to_string() }
}

pub fn csv(result: &BenchResult) -> String {
    let mut s = String::from(
        "scene,run,kind,profile,knob,value,composite_ms,passthrough_ms,ratio,max_abs,rmse,psnr_db,mean_flip,pareto\n",
    );
    let line = |s: &mut String, scene: &str, run: &RunSpec, c: f64, p: f64, r: f64, m: f64, rmse: f64, psnr: f64, f: f64, front: &str| {
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{c:.6},{p:.6},{r:.4},{m:.6e},{rmse:.6e},{},{f:.6e},{}",
            csv_field(scene),
            csv_field(&run.name),
            run.kind,
            csv_field(&run.profile),
            run.knob.as_deref().unwrap_or(""),
            run.value.as_deref().unwrap_or(""),
            if psnr.is_finite() { format!("{psnr:.3}") } else { "inf".into() },
            csv_field(front)
        );
    };
    for r in &result.rows {
        line(&mut s, &r.scene, &r.run, r.composite_ms, r.passthrough_ms, r.ratio, r.error.max_abs, r.error.rmse, r.error.psnr, r.error.mean_flip, "");
    }
    for a in &result.aggregates {
        line(&mut s, "ALL", &a.run, a.composite_ms, a.passthrough_ms, a.ratio, a.max_abs, a.rmse, a.psnr, a.mean_flip, &front_label(a));
    }
    s
}

fn family(a: &Aggregate) -> String {
    a.run.knob.clone().unwrap_or_else(|| "profile".into())
}

const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
    RGBColor(188, 189, 34),
];

/// Time (composite / pass-through) against mean FLIP, log error axis; the front as a red step
/// line, profiles as labelled black squares, each swept knob in its own colour.
pub fn plot(result: &BenchResult, path: &Path) -> Result<(), String> {
    static FONT: std::sync::Once = std::sync::Once::new();
    FONT.call_once(|| {
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, dejavu::sans::regular());
    });
    let e = |e: &dyn std::fmt::Display| format!("plot: {e}");
    let aggs: Vec<&Aggregate> = result.aggregates.iter().filter(|a| a.ratio.is_finite() && a.mean_flip.is_finite()).collect();
    let floor = 1e-5;
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for a in &aggs {
        x0 = x0.min(a.ratio);
        x1 = x1.max(a.ratio);
        y0 = y0.min(a.mean_flip.max(floor));
        y1 = y1.max(a.mean_flip.max(floor));
    }
    if aggs.is_empty() {
        (x0, x1, y0, y1) = (0.0, 1.0, floor, 1.0);
    }
    let pad = ((x1 - x0) * 0.08).max(0.05);
    let root = BitMapBackend::new(path, (1100, 720)).into_drawing_area();
    root.fill(&WHITE).map_err(|x| e(&x))?;
    let mut chart = ChartBuilder::on(&root)
        .caption("tidepack: composite time against error (mean over scenes)", ("sans-serif", 22))
        .margin(16)
        .x_label_area_size(48)
        .y_label_area_size(72)
        .build_cartesian_2d((x0 - pad)..(x1 + pad), (y0 / 1.6..y1 * 1.6).log_scale())
        .map_err(|x| e(&x))?;
    chart
        .configure_mesh()
        .x_desc(format!("composite / pass-through composite time ({} timestamps, median of {} frames)", result.timing_source, result.frames))
        .y_desc("mean FLIP against the f64 reference (log)")
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(|x| e(&x))?;
    let mut front: Vec<(f64, f64)> = aggs.iter().filter(|a| a.on_front).map(|a| (a.ratio, a.mean_flip.max(floor))).collect();
    front.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut steps = Vec::new();
    for (i, p) in front.iter().enumerate() {
        if i > 0 {
            steps.push((p.0, front[i - 1].1));
        }
        steps.push(*p);
    }
    chart
        .draw_series(LineSeries::new(steps, RED.stroke_width(2)))
        .map_err(|x| e(&x))?
        .label("Pareto front")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], RED.stroke_width(2)));
    chart
        .draw_series(front.iter().map(|p| Circle::new(*p, 9, RED.stroke_width(2))))
        .map_err(|x| e(&x))?;
    let mut families: Vec<String> = aggs.iter().map(|a| family(a)).filter(|f| f != "profile").collect();
    families.dedup();
    for (i, fam) in families.iter().enumerate() {
        let colour = PALETTE[i % PALETTE.len()];
        chart
            .draw_series(aggs.iter().filter(|a| &family(a) == fam).map(|a| Circle::new((a.ratio, a.mean_flip.max(floor)), 5, colour.filled())))
            .map_err(|x| e(&x))?
            .label(format!("{fam} sweep"))
            .legend(move |(x, y)| Circle::new((x + 9, y), 5, colour.filled()));
        chart
            .draw_series(aggs.iter().filter(|a| &family(a) == fam).map(|a| {
                Text::new(a.run.value.clone().unwrap_or_default(), (a.ratio, a.mean_flip.max(floor)), ("sans-serif", 11).into_font().color(&colour))
            }))
            .map_err(|x| e(&x))?;
    }
    let profiles: Vec<&&Aggregate> = aggs.iter().filter(|a| a.run.kind == "profile").collect();
    chart
        .draw_series(profiles.iter().map(|a| {
            let p = (a.ratio, a.mean_flip.max(floor));
            EmptyElement::at(p) + Rectangle::new([(-6, -6), (6, 6)], BLACK.filled()) + Text::new(a.run.name.clone(), (9, -18), ("sans-serif", 16))
        }))
        .map_err(|x| e(&x))?
        .label("profile")
        .legend(|(x, y)| Rectangle::new([(x + 3, y - 5), (x + 13, y + 5)], BLACK.filled()));
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 13))
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(|x| e(&x))?;
    root.present().map_err(|x| e(&x))?;
    Ok(())
}

fn agg<'a>(result: &'a BenchResult, name: &str) -> Option<&'a Aggregate> {
    result.aggregates.iter().find(|a| a.run.name == name)
}

/// Error of a two-valued knob's runs per scene and over scenes (Markdown).
fn knob_table(result: &BenchResult, knob: &str, labels: &[(&str, &str)]) -> String {
    let mut s = String::new();
    let names: Vec<(String, &str)> = labels.iter().map(|(v, l)| (format!("{}+{knob}={v}", result.base_profile), *l)).collect();
    let _ = write!(s, "| scene |");
    for (_, l) in &names {
        let _ = write!(s, " {l} PSNR dB | {l} mean FLIP | {l} max abs |");
    }
    let _ = writeln!(s);
    let _ = writeln!(s, "|---|{}", "---|---|---|".repeat(names.len()));
    for scene in result.scenes.iter().map(String::as_str).chain(["**all scenes**"]) {
        let _ = write!(s, "| {scene} |");
        for (name, _) in &names {
            let cell = if scene == "**all scenes**" {
                agg(result, name).map(|a| (a.psnr, a.mean_flip, a.max_abs))
            } else {
                result.rows.iter().find(|r| &r.run.name == name && r.scene == scene).map(|r| (r.error.psnr, r.error.mean_flip, r.error.max_abs))
            };
            match cell {
                Some((p, f, m)) => {
                    let _ = write!(s, " {} | {f:.5} | {m:.4} |", db(p));
                }
                None => s.push_str(" – | – | – |"),
            }
        }
        let _ = writeln!(s);
    }
    if let (Some(a), Some(b)) = (agg(result, &names[0].0), names.get(1).and_then(|n| agg(result, &n.0))) {
        let _ = writeln!(
            s,
            "\nTime over all scenes: {} {:.2}× the pass-through, {} {:.2}×.",
            names[0].1, a.ratio, names[1].1, b.ratio
        );
    }
    s
}

pub fn markdown(result: &BenchResult, image: &str) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# Accuracy and cost of the profiles and quality knobs\n");
    let _ = writeln!(s, "Generated by `tidepack bench` (crates/bench); regenerate with\n\n    {}\n", result.command);
    let _ = writeln!(
        s,
        "- Adapter: {}; times from {} timestamps, median of {} frames per option set and scene after one warm-up frame, the option sets taking turns frame by frame \
         (so load changes on a shared machine hit them alike). Time is the \
         composite pass over the one-tap pass-through composite of the same frames (\"comp/pt\"), averaged over scenes. Each scene is \
         rendered once per option set through the whole harness; composite is then re-run alone over that frame's G-buffers \
         (`tidepack_harness::composite_only`, pipeline made once per option set, uniform blocks bound as read-only storage so that \
         lavapipe does not recompile the shader at every draw; see docs/stress.md, \"Memory\"). The timed pass's image equals the \
         harness frame's to within {:e} (largest difference, any run, scene and channel).",
        result.adapter,
        if result.timing_source == "gpu" { "GPU" } else { "wall-clock (no GPU" },
        result.frames,
        result.rows.iter().map(|r| r.timed_image_difference).fold(0.0, f64::max)
    );
    if let Some(rss) = result.rss_mib_end {
        let _ = writeln!(s, "- Resident memory of the bench at the end of the runs: {rss:.0} MiB.");
    }
    let _ = writeln!(
        s,
        "- Scenes: {} ({}).",
        result.scenes.join(", "),
        match result.resolution {
            Some([w, h]) => format!("each at {w}×{h}"),
            None => "each at its own resolution".into(),
        }
    );
    let _ = writeln!(
        s,
        "- Reference: `tidepack-reference` at `ReferenceSettings::converged()` (64 wave bisection steps, 48 SSR steps, \
         32 SSR refinement steps, exact Fresnel, Beer–Lambert, 2 normal octaves, 3 caustic sample pairs), {}, \
         fed the G-buffers of the {} profile's frame. LOW's flat (unswelled) surface therefore counts as error, as do \
         look differences (fewer octaves or caustic pairs, Schlick, the ramp).",
        if result.reference_stride <= 1 { "every pixel".to_string() } else { format!("every {}th pixel", result.reference_stride) },
        result.base_profile
    );
    let _ = writeln!(
        s,
        "- Error: rgb of the composite output against the reference, both clamped to 0..1: max abs, RMSE, PSNR \
         (10·log10(1/MSE); over all scenes from the mean MSE) and mean FLIP (NVIDIA FLIP, LDR, 67 pixels per degree, \
         on the 8-bit images the framebuffer would hold).\n"
    );
    let _ = writeln!(s, "## Profiles\n");
    let _ = writeln!(s, "| profile | comp/pt | composite ms | PSNR dB | mean FLIP | max abs | Pareto |");
    let _ = writeln!(s, "|---|---|---|---|---|---|---|");
    for a in result.aggregates.iter().filter(|a| a.run.kind == "profile") {
        let _ = writeln!(
            s,
            "| {} | {:.2}× | {:.3} | {} | {:.5} | {:.4} | {} |",
            a.run.name,
            a.ratio,
            a.composite_ms,
            db(a.psnr),
            a.mean_flip,
            a.max_abs,
            front_label(a)
        );
    }
    let dominated: Vec<&Aggregate> = result.aggregates.iter().filter(|a| a.run.kind == "profile" && !near_front(a)).collect();
    if dominated.is_empty() {
        let _ = writeln!(s, "\nEvery profile is on the Pareto front or within {:.0}% of it in both time and error.", 100.0 * NEAR_FRONT);
    } else {
        for a in dominated {
            let others: Vec<String> = a.dominated_by.iter().take(4).map(|(n, m)| format!("{n} ({:.0}%)", 100.0 * m)).collect();
            let _ = writeln!(s, "\n**{} is dominated** by {}: each is both faster and more accurate.", a.run.name, others.join(", "));
        }
    }
    let _ = writeln!(s, "\n![time against error]({image})\n");
    let _ = writeln!(s, "## Schlick against exact Fresnel ({} with `FRESNEL_EXACT` off and on)\n", result.base_profile);
    s.push_str(&knob_table(result, "FRESNEL_EXACT", &[("off", "Schlick"), ("on", "exact")]));
    let _ = writeln!(s, "\n## Ramp against Beer–Lambert ({} with `ABSORPTION_MODEL` 0 and 1)\n", result.base_profile);
    s.push_str(&knob_table(result, "ABSORPTION_MODEL", &[("0", "ramp"), ("1", "Beer–Lambert")]));
    let _ = writeln!(s, "\n## Every run (Pareto table, mean over scenes)\n");
    let _ = writeln!(s, "| run | comp/pt | composite ms | PSNR dB | mean FLIP | max abs | Pareto |");
    let _ = writeln!(s, "|---|---|---|---|---|---|---|");
    let mut sorted: Vec<&Aggregate> = result.aggregates.iter().collect();
    sorted.sort_by(|a, b| a.ratio.total_cmp(&b.ratio));
    for a in sorted {
        let _ = writeln!(
            s,
            "| {} | {:.2}× | {:.3} | {} | {:.5} | {:.4} | {} |",
            a.run.name,
            a.ratio,
            a.composite_ms,
            db(a.psnr),
            a.mean_flip,
            a.max_abs,
            front_label(a)
        );
    }
    let _ = writeln!(s, "\n## Profiles per scene\n");
    let _ = writeln!(s, "| scene | profile | comp/pt | PSNR dB | mean FLIP | max abs |");
    let _ = writeln!(s, "|---|---|---|---|---|---|");
    for scene in &result.scenes {
        for r in result.rows.iter().filter(|r| &r.scene == scene && r.run.kind == "profile") {
            let _ = writeln!(s, "| {scene} | {} | {:.2}× | {} | {:.5} | {:.4} |", r.run.name, r.ratio, db(r.error.psnr), r.error.mean_flip, r.error.max_abs);
        }
    }
    let _ = writeln!(
        s,
        "\nCSV, JSON and FLIP heat-maps per scene and profile (`heatmaps/<scene>-<profile>.png`) are in the bench's --out folder."
    );
    s
}

pub fn write_all(config: &BenchConfig, result: &mut BenchResult) -> Result<(), String> {
    let out = &config.out_dir;
    let write = |name: &str, text: &str| std::fs::write(out.join(name), text).map_err(|e| format!("cannot write {}: {e}", out.join(name).display()));
    plot(result, &out.join("pareto.png"))?;
    result.files.extend(["bench.csv", "bench.json", "pareto.png", "report.md"].map(String::from));
    write("bench.csv", &csv(result))?;
    write("report.md", &markdown(result, "pareto.png"))?;
    write("bench.json", &(serde_json::to_string_pretty(result).map_err(|e| e.to_string())? + "\n"))?;
    if let Some(report) = &config.report {
        let stem = report.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "report".into());
        let image = format!("{stem}-pareto.png");
        let dir = report.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
        std::fs::copy(out.join("pareto.png"), dir.join(&image)).map_err(|e| format!("cannot copy the plot: {e}"))?;
        std::fs::write(report, markdown(result, &image)).map_err(|e| format!("cannot write {}: {e}", report.display()))?;
    }
    Ok(())
}
