//! Aggregation over scenes, the Pareto front, and the files: terminal table, CSV, JSON, the
//! plot (plotters, bitmap backend) and the Markdown report.

use std::fmt::Write as _;
use std::path::Path;

use plotters::prelude::*;

use crate::metrics::psnr_of_mse;
use crate::labels;
use crate::pareto::{self, Verdict};
use crate::{Aggregate, BenchConfig, BenchResult, ErrorMetrics, NEAR_FRONT, Row, RunSpec};

fn mean(v: impl Iterator<Item = f64>) -> f64 {
    let (s, n) = v.fold((0.0, 0usize), |(s, n), x| (s + x, n + 1));
    if n == 0 { f64::NAN } else { s / n as f64 }
}

/// Per run over all scenes, with the Pareto verdicts in (ratio, mean FLIP).
pub fn aggregate(runs: &[RunSpec], rows: &[Row]) -> Vec<Aggregate> {
    let mut out: Vec<Aggregate> = runs
        .iter()
        .map(|run| {
            let r: Vec<&Row> = rows.iter().filter(|r| r.run.name == run.name).collect();
            let mse = mean(r.iter().map(|r| r.mse));
            Aggregate {
                run: run.clone(),
                ratio: mean(r.iter().map(|r| r.ratio)),
                ratio_spread: mean(r.iter().map(|r| pareto::ratio_spread(&r.composite_frames_ms, &r.passthrough_frames_ms))),
                composite_ms: mean(r.iter().map(|r| r.composite_ms)),
                passthrough_ms: mean(r.iter().map(|r| r.passthrough_ms)),
                max_abs: r.iter().map(|r| r.error.max_abs).fold(0.0, f64::max),
                rmse: mse.sqrt(),
                psnr: psnr_of_mse(mse),
                mean_flip: mean(r.iter().map(|r| r.error.mean_flip)),
                truth: truth_aggregate(&r),
                verdict: Verdict::Front,
                dominated_by: vec![],
                ties_with: vec![],
            }
        })
        .collect();
    let points: Vec<pareto::Point> =
        out.iter().map(|a| pareto::Point { time: a.ratio, time_spread: a.ratio_spread, error: a.mean_flip }).collect();
    let names: Vec<String> = out.iter().map(|a| a.run.name.clone()).collect();
    for (a, j) in out.iter_mut().zip(pareto::judge(&points)) {
        a.verdict = j.verdict;
        a.dominated_by = j.dominated_by.into_iter().map(|(i, m)| (names[i].clone(), m)).collect();
        a.ties_with = j.ties_with.into_iter().map(|i| names[i].clone()).collect();
    }
    out
}

/// The error against the truth over the scenes that have compared pixels.
fn truth_aggregate(rows: &[&Row]) -> Option<ErrorMetrics> {
    let scored: Vec<ErrorMetrics> = rows.iter().filter_map(|r| r.truth_error).collect();
    if scored.is_empty() {
        return None;
    }
    let mse = mean(scored.iter().map(|e| e.rmse * e.rmse));
    Some(ErrorMetrics {
        max_abs: scored.iter().map(|e| e.max_abs).fold(0.0, f64::max),
        rmse: mse.sqrt(),
        psnr: psnr_of_mse(mse),
        mean_flip: mean(scored.iter().map(|e| e.mean_flip)),
    })
}

/// Not dominated beyond the timing noise, or beaten by no run by more than [`NEAR_FRONT`] in
/// both coordinates.
pub fn near_front(a: &Aggregate) -> bool {
    a.verdict != Verdict::Dominated || a.dominated_by.first().is_none_or(|(_, m)| *m <= NEAR_FRONT)
}

/// How many runs' verdicts are ties within the timing noise.
pub fn tie_count(result: &BenchResult) -> usize {
    result.aggregates.iter().filter(|a| a.verdict == Verdict::Tie).count()
}

fn front_label(a: &Aggregate) -> String {
    match a.verdict {
        Verdict::Front => "front".into(),
        Verdict::Tie => {
            let more = if a.ties_with.len() > 1 { format!(" and {} more", a.ties_with.len() - 1) } else { String::new() };
            format!("tie within timing noise (with {}{more})", a.ties_with[0])
        }
        Verdict::Dominated if near_front(a) => format!("near ({} by {:.1}%)", a.dominated_by[0].0, 100.0 * a.dominated_by[0].1),
        Verdict::Dominated => format!("dominated by {} (by {:.0}%)", a.dominated_by[0].0, 100.0 * a.dominated_by[0].1),
    }
}

/// The sentence that counts the ties, for the table and the report.
fn ties_sentence(result: &BenchResult) -> String {
    format!(
        "{} of {} Pareto verdicts are ties within timing noise: a run at least as accurate is closer in time than the two runs' \
         combined spread (interquartile range of the per-frame composite / pass-through ratios), so which is faster the \
         times cannot tell; more --frames narrow the spread.",
        tie_count(result),
        result.aggregates.len()
    )
}

fn db(psnr: f64) -> String {
    if psnr.is_finite() { format!("{psnr:.1}") } else { "identical".into() }
}

/// The aggregate table, one line per run (terminal).
pub fn table(result: &BenchResult) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<34} {:>9} {:>7} {:>10} {:>9} {:>8} {:>9} {:>10} {:>10} {:>11}  pareto",
        "run (mean over scenes)", "comp/pt", "spread", "comp ms", "max abs", "RMSE", "PSNR dB", "mean FLIP", "truth dB", "truth FLIP"
    );
    for a in &result.aggregates {
        let (truth_db, truth_flip) = a.truth.map_or(("–".to_string(), "–".to_string()), |t| (db(t.psnr), format!("{:.5}", t.mean_flip)));
        let _ = writeln!(
            s,
            "{:<34} {:>8.2}x {:>7} {:>10.3} {:>9.4} {:>8.5} {:>9} {:>10.5} {:>10} {:>11}  {}",
            a.run.name,
            a.ratio,
            spread(a.ratio_spread),
            a.composite_ms,
            a.max_abs,
            a.rmse,
            db(a.psnr),
            a.mean_flip,
            truth_db,
            truth_flip,
            front_label(a)
        );
    }
    let _ = writeln!(s, "{}", ties_sentence(result));
    s
}

/// A relative spread as "±2.1%"; "?" with a single frame.
fn spread(relative: f64) -> String {
    if relative.is_finite() { format!("±{:.1}%", 100.0 * relative) } else { "?".into() }
}

/// bench.csv: a row per (scene, run), then a row per run over all scenes (scene `ALL`, with its
/// Pareto verdict). Fields with commas, quotes or line breaks are quoted by the `csv` crate.
pub fn csv(result: &BenchResult) -> String {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record([
        "scene", "run", "kind", "profile", "knob", "value", "composite_ms", "passthrough_ms", "ratio", "ratio_spread", "max_abs", "rmse",
        "psnr_db", "mean_flip", "pareto", "truth_max_abs", "truth_rmse", "truth_psnr_db", "truth_mean_flip",
    ])
    .expect("CSV into memory");
    let psnr_field = |psnr: f64| if psnr.is_finite() { format!("{psnr:.3}") } else { "inf".into() };
    let error_fields = |e: &ErrorMetrics| [format!("{:.6e}", e.max_abs), format!("{:.6e}", e.rmse), psnr_field(e.psnr), format!("{:.6e}", e.mean_flip)];
    let mut record = |scene: &str, run: &RunSpec, [c, p, r, spread]: [f64; 4], error: &ErrorMetrics, front: &str, truth: Option<&ErrorMetrics>| {
        let times = [format!("{c:.6}"), format!("{p:.6}"), format!("{r:.4}"), format!("{spread:.4}")];
        let truth = truth.map_or_else(|| [(); 4].map(|_| String::new()), error_fields);
        let text = [scene, &run.name, &run.kind, &run.profile, run.knob.as_deref().unwrap_or(""), run.value.as_deref().unwrap_or("")];
        let error = error_fields(error);
        let numbers = times.iter().chain(&error).map(String::as_str);
        w.write_record(text.into_iter().chain(numbers).chain([front]).chain(truth.iter().map(String::as_str))).expect("CSV into memory");
    };
    for r in &result.rows {
        let spread = pareto::ratio_spread(&r.composite_frames_ms, &r.passthrough_frames_ms);
        record(&r.scene, &r.run, [r.composite_ms, r.passthrough_ms, r.ratio, spread], &r.error, "", r.truth_error.as_ref());
    }
    for a in &result.aggregates {
        let error = ErrorMetrics { max_abs: a.max_abs, rmse: a.rmse, psnr: a.psnr, mean_flip: a.mean_flip };
        record("ALL", &a.run, [a.composite_ms, a.passthrough_ms, a.ratio, a.ratio_spread], &error, &front_label(a), a.truth.as_ref());
    }
    String::from_utf8(w.into_inner().expect("CSV into memory")).expect("CSV of UTF-8 fields")
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

/// Time (composite / pass-through) against mean FLIP, log error axis: each run with its timing
/// spread as a horizontal bar (± the spread); the front as a red step line, red rings on front
/// verdicts and orange rings on ties within the timing noise; profiles as labelled black
/// squares, each swept knob in its own colour, labelled with its value. Labels are placed by
/// [`labels::place`], clear of each other, the markers, the bars and the legend.
pub fn plot(result: &BenchResult, path: &Path) -> Result<(), String> {
    crate::register_font();
    let e = |e: &dyn std::fmt::Display| format!("plot: {e}");
    let aggs: Vec<&Aggregate> = result.aggregates.iter().filter(|a| a.ratio.is_finite() && a.mean_flip.is_finite()).collect();
    let floor = 1e-5;
    let at = |a: &Aggregate| (a.ratio, a.mean_flip.max(floor));
    // ± the whole spread, so that two bars overlap exactly when the runs' times are a tie.
    let bar = |a: &Aggregate| if a.ratio_spread.is_finite() { a.ratio * a.ratio_spread } else { 0.0 };
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for a in &aggs {
        x0 = x0.min(a.ratio - bar(a));
        x1 = x1.max(a.ratio + bar(a));
        y0 = y0.min(a.mean_flip.max(floor));
        y1 = y1.max(a.mean_flip.max(floor));
    }
    if aggs.is_empty() {
        (x0, x1, y0, y1) = (0.0, 1.0, floor, 1.0);
    }
    let pad = ((x1 - x0) * 0.08).max(0.05);
    let root = BitMapBackend::new(path, (1400, 900)).into_drawing_area();
    root.fill(&WHITE).map_err(|x| e(&x))?;
    let mut chart = ChartBuilder::on(&root)
        .caption("tidepack: composite time against error (mean over scenes)", ("sans-serif", 28))
        .margin(20)
        .x_label_area_size(64)
        .y_label_area_size(96)
        .build_cartesian_2d((x0 - pad)..(x1 + pad), (y0 / 1.6..y1 * 1.6).log_scale())
        .map_err(|x| e(&x))?;
    chart
        .configure_mesh()
        .x_desc(format!(
            "composite / pass-through composite time ({} timestamps, median of {} frames; bars: ± interquartile range, overlapping: no order in time)",
            result.timing_source, result.frames
        ))
        .y_desc("mean FLIP against the f64 reference (log)")
        .label_style(("sans-serif", 18))
        .axis_desc_style(("sans-serif", 20))
        .draw()
        .map_err(|x| e(&x))?;
    chart
        .draw_series(aggs.iter().filter(|a| bar(a) > 0.0).map(|a| {
            let (x, y) = at(a);
            ErrorBar::new_horizontal(y, x - bar(a), x, x + bar(a), RGBColor(120, 120, 120).stroke_width(2), 8)
        }))
        .map_err(|x| e(&x))?;
    // The step line joins the runs no other run beats beyond the noise, keeping, from the
    // fastest on, only those more accurate than every faster one (ties may cross each other).
    let mut front: Vec<(f64, f64)> = aggs.iter().filter(|a| a.verdict != Verdict::Dominated).map(|a| at(a)).collect();
    front.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut steps: Vec<(f64, f64)> = Vec::new();
    for p in front {
        match steps.last() {
            Some(last) if p.1 >= last.1 => {}
            Some(last) => steps.extend([(p.0, last.1), p]),
            None => steps.push(p),
        }
    }
    chart
        .draw_series(LineSeries::new(steps, RED.stroke_width(2)))
        .map_err(|x| e(&x))?
        .label("Pareto front")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], RED.stroke_width(2)));
    let tie_colour = RGBColor(255, 140, 0);
    for (verdict, colour, label) in [(Verdict::Front, RED, "front"), (Verdict::Tie, tie_colour, "tie within timing noise")] {
        chart
            .draw_series(aggs.iter().filter(|a| a.verdict == verdict).map(|a| Circle::new(at(a), 10, colour.stroke_width(3))))
            .map_err(|x| e(&x))?
            .label(label)
            .legend(move |(x, y)| Circle::new((x + 9, y), 6, colour.stroke_width(2)));
    }
    let mut families: Vec<String> = Vec::new();
    for f in aggs.iter().map(|a| family(a)).filter(|f| f != "profile") {
        if !families.contains(&f) {
            families.push(f);
        }
    }
    let colour_of = |a: &Aggregate| families.iter().position(|f| *f == family(a)).map_or(BLACK, |i| PALETTE[i % PALETTE.len()]);
    for fam in &families {
        let colour = PALETTE[families.iter().position(|f| f == fam).unwrap_or(0) % PALETTE.len()];
        chart
            .draw_series(aggs.iter().filter(|a| &family(a) == fam).map(|a| Circle::new(at(a), 6, colour.filled())))
            .map_err(|x| e(&x))?
            .label(format!("{fam} sweep"))
            .legend(move |(x, y)| Circle::new((x + 9, y), 6, colour.filled()));
    }
    chart
        .draw_series(aggs.iter().filter(|a| a.run.kind == "profile").map(|a| EmptyElement::at(at(a)) + Rectangle::new([(-7, -7), (7, 7)], BLACK.filled())))
        .map_err(|x| e(&x))?
        .label("profile")
        .legend(|(x, y)| Rectangle::new([(x + 3, y - 6), (x + 15, y + 6)], BLACK.filled()));
    let legend_font = 16;
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", legend_font))
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(|x| e(&x))?;

    // Labels in pixels: profiles first (they matter most), then the sweep values.
    let (xs, ys) = chart.plotting_area().get_pixel_range();
    let bounds = labels::Rect { x0: xs.start, y0: ys.start, x1: xs.end, y1: ys.end };
    let mut obstacles: Vec<labels::Rect> = aggs.iter().map(|a| labels::Rect::around(chart.backend_coord(&at(a)), 13)).collect();
    obstacles.extend(aggs.iter().filter(|a| bar(a) > 0.0).map(|a| {
        let (x, y) = at(a);
        let (left, right) = (chart.backend_coord(&(x - bar(a), y)), chart.backend_coord(&(x + bar(a), y)));
        labels::Rect { x0: left.0, y0: left.1 - 5, x1: right.0, y1: right.1 + 5 }
    }));
    // The legend box at the upper right, measured generously from its widest entry.
    let entries: Vec<String> = ["Pareto front", "front", "tie within timing noise", "profile"]
        .map(String::from)
        .into_iter()
        .chain(families.iter().map(|f| format!("{f} sweep")))
        .collect();
    let legend_style: TextStyle = ("sans-serif", legend_font).into();
    let widest = entries.iter().map(|t| root.estimate_text_size(t, &legend_style).map_or(0, |s| s.0 as i32)).max().unwrap_or(0);
    obstacles.push(labels::Rect { x0: xs.end - widest - 70, y0: ys.start, x1: xs.end, y1: ys.start + 20 + entries.len() as i32 * (legend_font + 8) });
    let mut ordered: Vec<&&Aggregate> = aggs.iter().filter(|a| a.run.kind == "profile").collect();
    // A sweep to the base profile's own value is the profile's measurement: its point is the
    // profile's, and the profile's label names it.
    let on_profile = |a: &Aggregate| aggs.iter().any(|p| p.run.kind == "profile" && at(p) == at(a));
    ordered.extend(aggs.iter().filter(|a| a.run.kind != "profile" && !on_profile(a)));
    let mut texts = Vec::new();
    for a in &ordered {
        let (text, style): (String, TextStyle) = if a.run.kind == "profile" {
            (a.run.name.clone(), ("sans-serif", 24).into_font().color(&BLACK))
        } else {
            (a.run.value.clone().unwrap_or_default(), ("sans-serif", 18).into_font().color(&colour_of(a)))
        };
        let (w, h) = root.estimate_text_size(&text, &style).map_err(|x| e(&x))?;
        // A few pixels of margin around the text, so that neighbours do not touch.
        texts.push((labels::Label { anchor: chart.backend_coord(&at(a)), size: (w as i32 + 2 * PAD, h as i32 + 2 * PAD) }, text, style));
    }
    const PAD: i32 = 3;
    let gap = 16;
    let boxes = labels::place(&texts.iter().map(|t| t.0).collect::<Vec<_>>(), &obstacles, bounds, gap);
    for ((label, text, style), b) in texts.into_iter().zip(boxes) {
        // A label pushed out beyond the first ring gets a leader line to its point.
        let (x, y) = label.anchor;
        let nearest = (x.clamp(b.x0, b.x1), y.clamp(b.y0, b.y1));
        if (nearest.0 - x).abs().max((nearest.1 - y).abs()) > gap + 2 {
            root.draw(&PathElement::new(vec![(x, y), nearest], RGBColor(150, 150, 150))).map_err(|x| e(&x))?;
        }
        root.draw(&Text::new(text, (b.x0 + PAD, b.y0 + PAD), style)).map_err(|x| e(&x))?;
    }
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
        if let (Some(ta), Some(tb)) = (a.truth, b.truth) {
            let _ = writeln!(
                s,
                "Against the truth (water pixels, all scenes): {} {} dB PSNR, mean FLIP {:.5}; {} {} dB, {:.5}.",
                names[0].1,
                db(ta.psnr),
                ta.mean_flip,
                names[1].1,
                db(tb.psnr),
                tb.mean_flip
            );
        }
    }
    s
}

/// The header of the profile and Pareto tables (Markdown).
const AGGREGATE_HEADER: &str = "comp/pt ± spread | composite ms | PSNR dB | mean FLIP | max abs | truth PSNR dB | truth mean FLIP | Pareto |\n\
                                |---|---|---|---|---|---|---|---|---|";

/// One run of the profile and Pareto tables (Markdown).
fn aggregate_line(a: &Aggregate) -> String {
    format!(
        "| {} | {:.2}× {} | {:.3} | {} | {:.5} | {:.4} | {} | {} |\n",
        a.run.name,
        a.ratio,
        spread(a.ratio_spread),
        a.composite_ms,
        db(a.psnr),
        a.mean_flip,
        a.max_abs,
        truth_cells(a.truth.as_ref()),
        front_label(a)
    )
}

/// "PSNR | mean FLIP" against the truth, or dashes where nothing was compared.
fn truth_cells(truth: Option<&ErrorMetrics>) -> String {
    truth.map_or_else(|| "– | –".to_string(), |t| format!("{} | {:.5}", db(t.psnr), t.mean_flip))
}

/// How much lower a run's mean FLIP against the truth must be than the base profile's for the
/// report to call it closer: smaller differences are the last digits of the same picture.
pub const CLOSER_TO_TRUTH: f64 = 0.01;

/// The base profile against the truth, and the runs cheaper than it whose water is closer to the
/// truth (mean FLIP against it lower by more than [`CLOSER_TO_TRUTH`]) (Markdown).
fn truth_findings(result: &BenchResult) -> String {
    let mut s = String::new();
    let Some(base) = agg(result, &result.base_profile).filter(|a| a.truth.is_some()) else {
        return s;
    };
    let base_truth = base.truth.expect("filtered");
    let mut closer: Vec<&Aggregate> = result
        .aggregates
        .iter()
        .filter(|a| {
            a.run.name != base.run.name
                && a.ratio < base.ratio
                && a.truth.is_some_and(|t| t.mean_flip < (1.0 - CLOSER_TO_TRUTH) * base_truth.mean_flip)
        })
        .collect();
    closer.sort_by(|a, b| a.truth.map(|t| t.mean_flip).unwrap_or(f64::NAN).total_cmp(&b.truth.map(|t| t.mean_flip).unwrap_or(f64::NAN)));
    let _ = writeln!(
        s,
        "{} against the truth: {} dB PSNR, mean FLIP {:.5} (against the converged model: {} dB, {:.5}).\n",
        base.run.name,
        db(base_truth.psnr),
        base_truth.mean_flip,
        db(base.psnr),
        base.mean_flip
    );
    if closer.is_empty() {
        let _ = writeln!(s, "No run cheaper than {} is closer to the truth.\n", base.run.name);
    } else {
        let _ = writeln!(
            s,
            "Cheaper than {} ({:.2}× {}) and closer to the truth by more than {:.0}% in mean FLIP:\n",
            base.run.name,
            base.ratio,
            spread(base.ratio_spread),
            100.0 * CLOSER_TO_TRUTH
        );
        for a in closer {
            let t = a.truth.expect("filtered");
            let _ = writeln!(
                s,
                "- {}: {:.2}× {}, truth mean FLIP {:.5} ({:+.0}%), truth PSNR {} dB; against the converged model {} dB, mean FLIP {:.5}.",
                a.run.name,
                a.ratio,
                spread(a.ratio_spread),
                t.mean_flip,
                100.0 * (t.mean_flip / base_truth.mean_flip - 1.0),
                db(t.psnr),
                db(a.psnr),
                a.mean_flip
            );
        }
        let _ = writeln!(
            s,
            "\nA time difference smaller than the two runs' spreads is a tie within timing noise (see the Pareto table).\n"
        );
    }
    s
}

/// The report; `image` is the plot's path and `pictures` the folder of the truth comparisons,
/// both relative to the report.
pub fn markdown(result: &BenchResult, image: &str, pictures: &str) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# Accuracy and cost of the profiles and quality knobs\n");
    let _ = writeln!(s, "Generated by `tidepack bench` (crates/bench); regenerate with\n\n    {}\n", result.command);
    let _ = writeln!(
        s,
        "- Adapter: {}; times from {} timestamps, median of {} frames per option set and scene after one warm-up frame, the option sets taking turns frame by frame \
         (so load changes on a shared machine hit them alike). Time is the \
         composite pass over the one-tap pass-through composite of the same frames (\"comp/pt\"), averaged over scenes; its spread (±) \
         is the interquartile range of the per-frame ratios over their median, averaged over scenes. Two runs whose times differ \
         by less than their combined spread are a tie within timing noise, not a Pareto verdict. Each scene is \
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
    let _ = writeln!(
        s,
        "- Truth: `tidepack-truth` (docs/truth.md), a physically based f64 ray tracer of the same scenes ({}), one \
         sample at each pixel's centre. It scores the model's error, where the converged reference scores the \
         discretisation's. Compared over the pixels where the truth's rays met water and no overlay (rain, clouds, \
         particles, the hand, which the truth leaves out) lies in front; Distant Horizons' LODs are not traced, so \
         their pixels are not compared. \"Truth\" columns: PSNR from the mean MSE of those pixels, mean FLIP over \
         them; dry pixels would score the same in every run.\n",
        result.truth_options
    );
    let _ = writeln!(s, "## Profiles\n");
    let _ = writeln!(s, "| profile | {AGGREGATE_HEADER}");
    for a in result.aggregates.iter().filter(|a| a.run.kind == "profile") {
        s.push_str(&aggregate_line(a));
    }
    let dominated: Vec<&Aggregate> = result.aggregates.iter().filter(|a| a.run.kind == "profile" && !near_front(a)).collect();
    if dominated.is_empty() {
        let _ = writeln!(
            s,
            "\nEvery profile is on the Pareto front, tied with a run on it within timing noise, or within {:.0}% of it in both time and error.",
            100.0 * NEAR_FRONT
        );
    } else {
        for a in dominated {
            let others: Vec<String> = a.dominated_by.iter().take(4).map(|(n, m)| format!("{n} ({:.0}%)", 100.0 * m)).collect();
            let _ = writeln!(s, "\n**{} is dominated** by {}: each is both faster and more accurate.", a.run.name, others.join(", "));
        }
    }
    let _ = writeln!(s, "\n{}", ties_sentence(result));
    let _ = writeln!(s, "\n![time against error]({image})\n");
    let _ = writeln!(s, "## Against the truth\n");
    s.push_str(&truth_findings(result));
    let profiles: Vec<&str> = result.aggregates.iter().filter(|a| a.run.kind == "profile").map(|a| a.run.name.as_str()).collect();
    let columns: Vec<String> = profiles.iter().map(|p| format!("{p} truth PSNR dB | {p} truth mean FLIP")).collect();
    let _ = writeln!(s, "| scene | compared pixels | {} |", columns.join(" | "));
    let _ = writeln!(s, "|---|---|{}", "---|---|".repeat(profiles.len()));
    for scene in &result.scenes {
        let pixels = result.truth_pixels.get(scene).copied().unwrap_or(0);
        let cells: Vec<String> = profiles
            .iter()
            .map(|p| truth_cells(result.rows.iter().find(|r| &r.scene == scene && r.run.name == *p).and_then(|r| r.truth_error.as_ref())))
            .collect();
        let _ = writeln!(s, "| {scene} | {pixels} | {} |", cells.join(" | "));
    }
    let _ = writeln!(
        s,
        "\nWhere {} differs from the truth: the truth (left), {} (middle) and FLIP between them over the compared pixels \
         (right; black where nothing is compared), at half size.\n",
        result.pictured_run, result.pictured_run
    );
    for (scene, _) in result.truth_pixels.iter().filter(|(_, n)| **n > 0) {
        let _ = writeln!(s, "![{scene}: truth, {run}, FLIP]({pictures}/{scene}-{run}.png)\n", run = result.pictured_run);
    }
    let _ = writeln!(s, "## Schlick against exact Fresnel ({} with `FRESNEL_EXACT` off and on)\n", result.base_profile);
    s.push_str(&knob_table(result, "FRESNEL_EXACT", &[("off", "Schlick"), ("on", "exact")]));
    let _ = writeln!(s, "\n## Ramp against Beer–Lambert ({} with `ABSORPTION_MODEL` 0 and 1)\n", result.base_profile);
    s.push_str(&knob_table(result, "ABSORPTION_MODEL", &[("0", "ramp"), ("1", "Beer–Lambert")]));
    let _ = writeln!(s, "\n## Every run (Pareto table, mean over scenes)\n");
    let _ = writeln!(s, "| run | {AGGREGATE_HEADER}");
    let mut sorted: Vec<&Aggregate> = result.aggregates.iter().collect();
    sorted.sort_by(|a, b| a.ratio.total_cmp(&b.ratio));
    for a in sorted {
        s.push_str(&aggregate_line(a));
    }
    let _ = writeln!(s, "\n## Profiles per scene\n");
    let _ = writeln!(s, "| scene | profile | comp/pt | PSNR dB | mean FLIP | max abs | truth PSNR dB | truth mean FLIP |");
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|");
    for scene in &result.scenes {
        for r in result.rows.iter().filter(|r| &r.scene == scene && r.run.kind == "profile") {
            let _ = writeln!(
                s,
                "| {scene} | {} | {:.2}× | {} | {:.5} | {:.4} | {} |",
                r.run.name,
                r.ratio,
                db(r.error.psnr),
                r.error.mean_flip,
                r.error.max_abs,
                truth_cells(r.truth_error.as_ref())
            );
        }
    }
    let _ = writeln!(
        s,
        "\nCSV, JSON, FLIP heat-maps per scene and profile against the converged model (`heatmaps/<scene>-<profile>.png`) and \
         against the truth (`heatmaps/<scene>-<profile>-truth.png`), and the truth's images (`truth/<scene>.png`) are in the \
         bench's --out folder."
    );
    s
}

pub fn write_all(config: &BenchConfig, result: &mut BenchResult) -> Result<(), String> {
    let out = &config.out_dir;
    let write = |name: &str, text: &str| std::fs::write(out.join(name), text).map_err(|e| format!("cannot write {}: {e}", out.join(name).display()));
    plot(result, &out.join("pareto.png"))?;
    result.files.extend(["bench.csv", "bench.json", "pareto.png", "report.md"].map(String::from));
    write("bench.csv", &csv(result))?;
    write("report.md", &markdown(result, "pareto.png", "truth"))?;
    write("bench.json", &(serde_json::to_string_pretty(result).map_err(|e| e.to_string())? + "\n"))?;
    if let Some(report) = &config.report {
        let stem = report.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "report".into());
        let image = format!("{stem}-pareto.png");
        let dir = report.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
        std::fs::copy(out.join("pareto.png"), dir.join(&image)).map_err(|e| format!("cannot copy the plot: {e}"))?;
        // The truth comparisons beside the report, in a folder of their own made anew.
        let pictures = format!("{stem}-truth");
        let pictures_dir = dir.join(&pictures);
        if pictures_dir.exists() {
            std::fs::remove_dir_all(&pictures_dir).map_err(|e| format!("cannot clear {}: {e}", pictures_dir.display()))?;
        }
        std::fs::create_dir_all(&pictures_dir).map_err(|e| format!("cannot create {}: {e}", pictures_dir.display()))?;
        for (scene, _) in result.truth_pixels.iter().filter(|(_, n)| **n > 0) {
            let file = format!("{scene}-{}.png", result.pictured_run);
            std::fs::copy(out.join("truth").join(&file), pictures_dir.join(&file)).map_err(|e| format!("cannot copy truth/{file}: {e}"))?;
        }
        std::fs::write(report, markdown(result, &image, &pictures)).map_err(|e| format!("cannot write {}: {e}", report.display()))?;
    }
    Ok(())
}
