//! A fast subset of the stress sweep (docs/stress.md): every category at 16x9 through the real
//! composite on lavapipe, against the f64 reference. Needs lavapipe (Debian
//! mesa-vulkan-drivers; tools/test installs it): without it this fails naming the package.

use std::path::Path;

use tidepack_stress::{CATEGORIES, Category, StressOptions, run, tables};

#[test]
fn stress_subset_is_finite_and_close_to_the_reference() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut opts = StressOptions::new(&root);
    opts.cases = 260;
    opts.width = 16;
    opts.height = 9;
    let report = run(&opts, &mut |m| eprintln!("{m}")).unwrap_or_else(|e| panic!("{e}"));
    println!("{}", tables(&report));
    assert_eq!(report.cases, 260);
    assert_eq!(report.non_finite_pixels, 0, "NaN/Inf pixels in the composite output");
    for c in &report.categories {
        assert!(c.cases > 0, "{} ran no case", c.category);
        assert_eq!(c.reference_non_finite_pixels, 0, "{}: the reference is not finite", c.category);
        // Isolated pixels may differ where the model has a threshold (see docs/reference.md);
        // the RMSE over a category stays far below one 8-bit step.
        assert!(c.rmse < RMSE_BOUND, "{}: RMSE {:.3e} against the reference (worst: {})", c.category, c.rmse, c.worst_case);
        assert!(c.max_error.is_finite() && c.max_error <= 1.0, "{}: max error {}", c.category, c.max_error);
    }
    // Shader arithmetic stays as precise far from the origin as at it: against the reference fed
    // the same f32 uniforms, the 3e7 row is no worse than a few times the origin row.
    let at = |m: f64| report.distance.iter().find(|r| r.magnitude == m).expect("row");
    assert!(at(3e7).rmse_f32_inputs <= 4.0 * at(0.0).rmse_f32_inputs.max(1e-3), "{:?} vs {:?}", at(3e7), at(0.0));
}

const RMSE_BOUND: f64 = 0.02;

/// The sweep runs exactly the number of cases asked for, and refuses none.
#[test]
fn the_sweep_runs_exactly_the_cases_asked_for() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut opts = StressOptions::new(&root);
    opts.width = 16;
    opts.height = 9;
    opts.cases = 0;
    let error = run(&opts, &mut |_| {}).unwrap_err();
    assert!(error.contains("at least one case"), "{error}");
    opts.cases = 5;
    let mut messages = Vec::new();
    let report = run(&opts, &mut |m| messages.push(m.to_string())).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(report.cases, 5);
    let ran: Vec<Category> = report.categories.iter().filter(|c| c.cases > 0).map(|c| c.category).collect();
    assert_eq!(ran, CATEGORIES[..5]);
    assert!(messages.iter().any(|m| m.contains(&format!("only the first 5 of the {} categories", CATEGORIES.len()))), "{messages:?}");
}
