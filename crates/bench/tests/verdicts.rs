//! Pareto verdicts from synthetic per-frame timings, without a GPU: runs whose times differ by
//! less than their combined spread are reported as ties within timing noise, and the table and
//! the report count them.

use tidepack_bench::pareto::Verdict;
use tidepack_bench::{BenchResult, ErrorMetrics, Row, RunSpec, output};

fn row(run: &RunSpec, composite_frames_ms: Vec<f64>, passthrough_ms: f64, mean_flip: f64) -> Row {
    let composite_ms = tidepack_harness::median(&composite_frames_ms);
    let passthrough_frames_ms = vec![passthrough_ms; composite_frames_ms.len()];
    Row {
        scene: "synthetic".into(),
        run: run.clone(),
        composite_ms,
        passthrough_ms,
        ratio: composite_ms / passthrough_ms,
        composite_frames_ms,
        passthrough_frames_ms,
        error: ErrorMetrics { max_abs: mean_flip, rmse: mean_flip, psnr: 30.0, mean_flip },
        mse: mean_flip * mean_flip,
        truth_error: None,
        timed_image_difference: 0.0,
    }
}

fn bench_result(runs: &[RunSpec], rows: Vec<Row>) -> BenchResult {
    BenchResult {
        adapter: "synthetic".into(),
        timing_source: "gpu".into(),
        frames: 3,
        resolution: Some([160, 90]),
        reference_stride: 1,
        reference_settings: String::new(),
        truth_options: String::new(),
        truth_pixels: Default::default(),
        pictured_run: String::new(),
        base_profile: "HIGH".into(),
        scenes: vec!["synthetic".into()],
        aggregates: output::aggregate(runs, &rows),
        rows,
        files: vec![],
        command: "test".into(),
        rss_mib_end: None,
    }
}

#[test]
fn noisy_close_times_are_ties_and_the_report_counts_them() {
    let (medium, high, ultra) = (RunSpec::profile("MEDIUM"), RunSpec::profile("HIGH"), RunSpec::profile("ULTRA"));
    let runs = [medium.clone(), high.clone(), ultra.clone()];
    // --quick: three frames each. HIGH and ULTRA 4% apart with frames spread by about 10%:
    // which is faster flips from run to run. MEDIUM is twice as fast as both.
    let rows = vec![
        row(&medium, vec![5.0, 5.1, 5.2], 1.0, 0.010),
        row(&high, vec![9.0, 10.0, 11.0], 1.0, 0.0016),
        row(&ultra, vec![9.4, 10.4, 11.4], 1.0, 0.0012),
    ];
    let result = bench_result(&runs, rows);
    let verdict = |name: &str| result.aggregates.iter().find(|a| a.run.name == name).unwrap().verdict;
    assert_eq!(verdict("MEDIUM"), Verdict::Front);
    assert_eq!(verdict("HIGH"), Verdict::Tie);
    assert_eq!(verdict("ULTRA"), Verdict::Front);
    assert_eq!(output::tie_count(&result), 1);

    let table = output::table(&result);
    assert!(table.contains("tie within timing noise (with ULTRA)"), "{table}");
    assert!(table.contains("1 of 3 Pareto verdicts are ties within timing noise"), "{table}");
    let md = output::markdown(&result, "pareto.png", "truth");
    assert!(md.contains("| HIGH | 10.00× ±10.0% |"), "{md}");
    assert!(md.contains("1 of 3 Pareto verdicts are ties within timing noise"), "{md}");
    let csv = output::csv(&result);
    assert!(csv.lines().any(|l| l.starts_with("ALL,HIGH,") && l.ends_with(",tie within timing noise (with ULTRA),,,,")), "{csv}");

    // The same medians measured tightly: ULTRA is slower beyond the noise and more accurate,
    // so both are on the front.
    let tight = vec![
        row(&medium, vec![5.1, 5.1, 5.1], 1.0, 0.010),
        row(&high, vec![9.99, 10.0, 10.01], 1.0, 0.0016),
        row(&ultra, vec![10.39, 10.4, 10.41], 1.0, 0.0012),
    ];
    let tight = bench_result(&runs, tight);
    assert!(tight.aggregates.iter().all(|a| a.verdict == Verdict::Front), "{:?}", tight.aggregates);
    assert_eq!(output::tie_count(&tight), 0);
}

#[test]
fn a_run_beaten_beyond_the_noise_is_dominated() {
    let (a, b) = (RunSpec::sweep("HIGH", "SSR_STEPS", "16"), RunSpec::sweep("HIGH", "SSR_STEPS", "24"));
    let rows = vec![row(&a, vec![8.0, 8.1, 8.2], 1.0, 0.002), row(&b, vec![9.9, 10.0, 10.1], 1.0, 0.003)];
    let result = bench_result(&[a, b], rows);
    assert_eq!(result.aggregates[0].verdict, Verdict::Front);
    assert_eq!(result.aggregates[1].verdict, Verdict::Dominated);
    assert_eq!(result.aggregates[1].dominated_by[0].0, "HIGH+SSR_STEPS=16");
}

/// The plot draws spread bars, tie rings and placed labels for synthetic runs without a GPU.
#[test]
fn the_plot_of_synthetic_runs_is_written() {
    let profiles = ["LOW", "MEDIUM", "HIGH", "ULTRA"].map(RunSpec::profile);
    let sweeps = ["4", "6", "8", "10"].map(|v| RunSpec::sweep("HIGH", "SSR_STEPS", v));
    let runs: Vec<RunSpec> = profiles.into_iter().chain(sweeps).collect();
    // Close together, so that labels must move apart; errors falling run by run.
    let rows = runs
        .iter()
        .enumerate()
        .map(|(i, run)| {
            let t = 2.0 + i as f64 * 0.1;
            row(run, vec![t, t + 0.1, t + 0.3], 1.0, 0.1 / (1 + i) as f64)
        })
        .collect();
    let result = bench_result(&runs, rows);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("pareto.png");
    output::plot(&result, &path).unwrap();
    let image = image::open(&path).unwrap();
    assert_eq!((image.width(), image.height()), (1400, 900));
}

/// bench.csv quotes a field holding a quote and a comma, and reads back to the same fields.
#[test]
fn csv_fields_with_quotes_and_commas_read_back_intact() {
    let mut odd = RunSpec::profile("HIGH");
    odd.name = "HIGH+NOTE=\"a, b\"".into();
    odd.kind = "sweep".into();
    odd.knob = Some("NOTE".into());
    odd.value = Some("\"a, b\"".into());
    let result = bench_result(std::slice::from_ref(&odd), vec![row(&odd, vec![5.0, 5.1, 5.2], 1.0, 0.01)]);
    let text = output::csv(&result);
    assert!(text.contains(r#""HIGH+NOTE=""a, b""""#), "{text}");
    let mut reader = csv::Reader::from_reader(text.as_bytes());
    let columns = reader.headers().unwrap().len();
    let records: Vec<csv::StringRecord> = reader.records().map(Result::unwrap).collect();
    assert_eq!(records.len(), 2, "{text}");
    for (record, scene) in records.iter().zip(["synthetic", "ALL"]) {
        assert_eq!(record.len(), columns, "{text}");
        assert_eq!(&record[0], scene);
        assert_eq!(&record[1], "HIGH+NOTE=\"a, b\"");
        assert_eq!(&record[4], "NOTE");
        assert_eq!(&record[5], "\"a, b\"");
    }
}
