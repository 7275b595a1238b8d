//! Placing point labels on a plot so that they do not overlap each other or the markers.
//!
//! Greedy: labels are placed in order (put the important ones first); each takes the first
//! free place among candidates around its point, nearest ring first, right of the point before
//! left, above and below. Runs of the bench sit close together on the Pareto plot (sweep values
//! a few percent apart), where labels at one fixed offset pile up.

/// A rectangle in pixels, `x0..x1` by `y0..y1` (y down).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rect {
    pub x0: i32,
    pub y0: i32,
    pub x1: i32,
    pub y1: i32,
}

impl Rect {
    pub fn new(x0: i32, y0: i32, width: i32, height: i32) -> Rect {
        Rect { x0, y0, x1: x0 + width, y1: y0 + height }
    }

    /// The square of half-side `r` around a point.
    pub fn around((x, y): (i32, i32), r: i32) -> Rect {
        Rect { x0: x - r, y0: y - r, x1: x + r, y1: y + r }
    }

    fn overlap(&self, o: &Rect) -> i64 {
        let w = (self.x1.min(o.x1) - self.x0.max(o.x0)).max(0) as i64;
        let h = (self.y1.min(o.y1) - self.y0.max(o.y0)).max(0) as i64;
        w * h
    }

    pub fn overlaps(&self, o: &Rect) -> bool {
        self.overlap(o) > 0
    }

    fn inside(&self, bounds: &Rect) -> bool {
        self.x0 >= bounds.x0 && self.y0 >= bounds.y0 && self.x1 <= bounds.x1 && self.y1 <= bounds.y1
    }
}

/// A label to place: the point it names and the size of its text, pixels.
#[derive(Clone, Copy, Debug)]
pub struct Label {
    pub anchor: (i32, i32),
    pub size: (i32, i32),
}

/// Rings of candidate places tried around a point before settling for the least overlap.
const RINGS: i32 = 8;

/// The box of each label, in order: inside `bounds` where it fits, overlapping no label placed
/// before it and none of `obstacles` (markers, the legend) when a place within [`RINGS`] rings
/// of `gap` pixels allows, else where it overlaps least.
pub fn place(labels: &[Label], obstacles: &[Rect], bounds: Rect, gap: i32) -> Vec<Rect> {
    let mut placed: Vec<Rect> = Vec::with_capacity(labels.len());
    for label in labels {
        let ((x, y), (w, h)) = (label.anchor, label.size);
        let mut best: Option<(i64, Rect)> = None;
        'rings: for ring in 1..=RINGS {
            let d = gap * ring;
            // Right, left, above, below, then the diagonals.
            let candidates = [
                (x + d, y - h / 2),
                (x - d - w, y - h / 2),
                (x - w / 2, y - d - h),
                (x - w / 2, y + d),
                (x + d, y - d - h),
                (x + d, y + d),
                (x - d - w, y - d - h),
                (x - d - w, y + d),
            ];
            for (cx, cy) in candidates {
                let r = Rect::new(cx, cy, w, h);
                if !r.inside(&bounds) {
                    continue;
                }
                let cost: i64 = placed.iter().chain(obstacles).map(|o| r.overlap(o)).sum();
                if best.is_none_or(|(c, _)| cost < c) {
                    best = Some((cost, r));
                }
                if cost == 0 {
                    break 'rings;
                }
            }
        }
        // Nothing fits inside the bounds: right of the point, clamped into them.
        let r = best.map(|(_, r)| r).unwrap_or_else(|| {
            let x0 = (x + gap).clamp(bounds.x0, (bounds.x1 - w).max(bounds.x0));
            let y0 = (y - h / 2).clamp(bounds.y0, (bounds.y1 - h).max(bounds.y0));
            Rect::new(x0, y0, w, h)
        });
        placed.push(r);
    }
    placed
}

#[cfg(test)]
mod tests {
    use super::*;

    const BOUNDS: Rect = Rect { x0: 0, y0: 0, x1: 800, y1: 600 };

    fn markers(labels: &[Label]) -> Vec<Rect> {
        labels.iter().map(|l| Rect::around(l.anchor, 6)).collect()
    }

    #[test]
    fn a_lone_label_sits_right_of_its_point() {
        let labels = [Label { anchor: (100, 100), size: (40, 16) }];
        let placed = place(&labels, &markers(&labels), BOUNDS, 10);
        assert_eq!(placed, vec![Rect::new(110, 92, 40, 16)]);
    }

    #[test]
    fn labels_of_clustered_points_do_not_overlap_each_other_or_the_markers() {
        // Twelve points within a few pixels of each other, as sweep values a percent apart
        // are on the Pareto plot, and a row of points a label's width apart.
        let mut labels: Vec<Label> =
            (0..12).map(|i| Label { anchor: (400 + (i % 4) * 3, 300 + (i / 4) * 4), size: (30 + 4 * (i % 3), 17) }).collect();
        labels.extend((0..6).map(|i| Label { anchor: (100 + 25 * i, 500), size: (44, 17) }));
        let obstacles = markers(&labels);
        let placed = place(&labels, &obstacles, BOUNDS, 10);
        assert_eq!(placed.len(), labels.len());
        for (i, a) in placed.iter().enumerate() {
            assert!(a.inside(&BOUNDS), "{a:?}");
            for b in &placed[i + 1..] {
                assert!(!a.overlaps(b), "{a:?} overlaps {b:?}");
            }
            for m in &obstacles {
                assert!(!a.overlaps(m), "{a:?} covers the marker {m:?}");
            }
            // Near enough to read as its point's label.
            let (x, y) = labels[i].anchor;
            let dx = (a.x0 - x).max(x - a.x1).max(0);
            let dy = (a.y0 - y).max(y - a.y1).max(0);
            assert!(dx.max(dy) <= 10 * RINGS, "{a:?} far from {:?}", labels[i].anchor);
        }
    }

    #[test]
    fn labels_at_the_edge_stay_inside() {
        let labels = [Label { anchor: (795, 5), size: (60, 17) }, Label { anchor: (2, 598), size: (60, 17) }];
        for r in place(&labels, &markers(&labels), BOUNDS, 10) {
            assert!(r.inside(&BOUNDS), "{r:?}");
        }
    }
}
