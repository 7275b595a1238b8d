//! Pareto verdicts in (time, error) that admit when the timing noise cannot decide them.
//!
//! Errors are deterministic (the same image every run), times are not: on a shared machine
//! two option sets a few percent apart swap places from one run to the next. A comparison
//! therefore only counts when the times differ by more than the two runs' combined spread
//! (interquartile range of their per-frame times); otherwise it is a tie within timing noise.

use serde::Serialize;

/// Linear-interpolated quantile `q` (0..1) of `samples`; NaN for none.
fn quantile(samples: &[f64], q: f64) -> f64 {
    let mut sorted = samples.to_vec();
    sorted.sort_by(f64::total_cmp);
    match sorted.len() {
        0 => f64::NAN,
        n => {
            let at = q * (n - 1) as f64;
            let (lo, hi) = (at.floor() as usize, at.ceil() as usize);
            sorted[lo] + (sorted[hi] - sorted[lo]) * (at - lo as f64)
        }
    }
}

/// Interquartile range of `samples` over their median. NaN for fewer than two samples: one
/// frame says nothing about the noise. The IQR rather than min–max so that a single frame hit
/// by another process does not turn every verdict into a tie.
pub fn relative_spread(samples: &[f64]) -> f64 {
    if samples.len() < 2 {
        return f64::NAN;
    }
    (quantile(samples, 0.75) - quantile(samples, 0.25)) / tidepack_harness::median(samples)
}

/// Relative spread of the composite / pass-through ratio, from the per-frame ratios: each
/// frame times the two passes back to back, so a load change that slows both cancels out.
pub fn ratio_spread(composite_ms: &[f64], passthrough_ms: &[f64]) -> f64 {
    let ratios: Vec<f64> = composite_ms.iter().zip(passthrough_ms).map(|(c, p)| c / p).collect();
    relative_spread(&ratios)
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    /// No other run is at least as accurate and faster beyond the noise, and none is within
    /// the noise of it in time while at least as accurate.
    Front,
    /// Not dominated beyond the noise, but a run at least as accurate is within the timing
    /// noise of it: which of the two is faster, and so whether this one is on the front, the
    /// times cannot tell.
    Tie,
    /// Another run is at least as accurate and faster by more than the combined spread.
    Dominated,
}

/// One run in the plane: time (lower is better), its relative spread, and error.
#[derive(Clone, Copy, Debug)]
pub struct Point {
    pub time: f64,
    /// Relative to `time`, as [`relative_spread`] gives it; NaN when unknown.
    pub time_spread: f64,
    pub error: f64,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Judgement {
    pub verdict: Verdict,
    /// Indices of the runs that dominate this one beyond the noise, with the smaller of their
    /// two relative improvements, largest first.
    pub dominated_by: Vec<(usize, f64)>,
    /// Indices of the runs at least as accurate whose time is within the combined spread,
    /// fastest first.
    pub ties_with: Vec<usize>,
}

/// The verdict of every point against all the others.
pub fn judge(points: &[Point]) -> Vec<Judgement> {
    points
        .iter()
        .enumerate()
        .map(|(i, a)| {
            let mut dominated_by = Vec::new();
            let mut ties_with = Vec::new();
            for (j, b) in points.iter().enumerate() {
                // The same point twice (one option set reached by two names) decides nothing.
                let same = b.time == a.time && b.error == a.error;
                if j == i || same || b.error > a.error {
                    continue;
                }
                let noise = a.time * a.time_spread + b.time * b.time_spread;
                let faster_by = a.time - b.time;
                if noise.is_finite() && faster_by > noise {
                    let margin = (1.0 - b.time / a.time).min(1.0 - b.error / a.error.max(f64::MIN_POSITIVE));
                    dominated_by.push((j, margin));
                } else if !noise.is_finite() || faster_by.abs() <= noise {
                    ties_with.push(j);
                }
            }
            dominated_by.sort_by(|x, y| y.1.total_cmp(&x.1));
            // The fastest first: the one most likely to beat this run in the next measurement.
            ties_with.sort_by(|&x, &y| points[x].time.total_cmp(&points[y].time));
            let verdict = if !dominated_by.is_empty() {
                Verdict::Dominated
            } else if !ties_with.is_empty() {
                Verdict::Tie
            } else {
                Verdict::Front
            };
            Judgement { verdict, dominated_by, ties_with }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(time: f64, time_spread: f64, error: f64) -> Point {
        Point { time, time_spread, error }
    }

    #[test]
    fn spread_is_the_interquartile_range_over_the_median() {
        // Quartiles 2 and 4 (linear interpolation), median 3.
        assert!((relative_spread(&[1.0, 3.0, 5.0]) - 2.0 / 3.0).abs() < 1e-12);
        assert_eq!(relative_spread(&[4.0, 4.0, 4.0, 4.0]), 0.0);
        // One slow frame among seven moves the IQR little.
        let s = relative_spread(&[10.0, 10.1, 10.0, 9.9, 10.0, 30.0, 10.1]);
        assert!(s < 0.02, "{s}");
        assert!(relative_spread(&[5.0]).is_nan());
        // Ratios frame by frame: a frame where both passes ran twice as slow is no noise.
        assert_eq!(ratio_spread(&[2.0, 4.0, 2.0], &[1.0, 2.0, 1.0]), 0.0);
    }

    #[test]
    fn times_closer_than_their_spread_are_a_tie_not_front_and_dominated() {
        // b is more accurate and nominally 3% faster, but each time spreads by 5%.
        let j = judge(&[point(1.00, 0.05, 0.02), point(0.97, 0.05, 0.01)]);
        assert_eq!(j[0].verdict, Verdict::Tie);
        assert_eq!(j[0].ties_with, vec![1]);
        assert!(j[0].dominated_by.is_empty());
        // b: nothing is at least as accurate, so b is on the front whatever the noise.
        assert_eq!(j[1].verdict, Verdict::Front);

        // The same times measured tightly: a verdict.
        let j = judge(&[point(1.00, 0.005, 0.02), point(0.97, 0.005, 0.01)]);
        assert_eq!(j[0].verdict, Verdict::Dominated);
        assert_eq!(j[0].dominated_by.len(), 1);
        assert!((j[0].dominated_by[0].1 - 0.03).abs() < 1e-12);
        assert_eq!(j[1].verdict, Verdict::Front);

        // Nominally on the front (faster, less accurate) but within the noise of a more
        // accurate run: also a tie, since the next run could put it behind.
        let j = judge(&[point(0.98, 0.05, 0.02), point(1.00, 0.05, 0.01)]);
        assert_eq!(j[0].verdict, Verdict::Tie);

        // Tied with two runs: the faster is named first.
        let j = judge(&[point(1.00, 0.05, 0.03), point(1.04, 0.05, 0.01), point(0.98, 0.05, 0.02)]);
        assert_eq!(j[0].ties_with, vec![2, 1]);

        // Far apart in time: the slower, more accurate run does not touch the faster one.
        let j = judge(&[point(1.0, 0.05, 0.02), point(2.0, 0.05, 0.01)]);
        assert_eq!((j[0].verdict, j[1].verdict), (Verdict::Front, Verdict::Front));
    }

    #[test]
    fn unknown_spread_supports_no_time_verdict_and_duplicates_decide_nothing() {
        let j = judge(&[point(2.0, f64::NAN, 0.02), point(1.0, f64::NAN, 0.01)]);
        assert_eq!(j[0].verdict, Verdict::Tie);
        // The same option set under two names.
        let j = judge(&[point(1.0, 0.0, 0.01), point(1.0, 0.0, 0.01)]);
        assert_eq!((j[0].verdict, j[1].verdict), (Verdict::Front, Verdict::Front));
        // Equal error, clearly different time: the slower one is dominated.
        let j = judge(&[point(1.0, 0.01, 0.01), point(1.5, 0.01, 0.01)]);
        assert_eq!((j[0].verdict, j[1].verdict), (Verdict::Front, Verdict::Dominated));
    }
}
