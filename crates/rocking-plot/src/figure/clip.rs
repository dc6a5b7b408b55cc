//! Cutting a polyline to a panel's rectangle: a line that leaves the panel (an overturning run's
//! θ, a zoom's window, an inset's range) is cut at the edge, not drawn over its neighbours.

/// The parts of a polyline inside the rectangle `((x0, x1), (y0, y1))`, cut where it crosses the
/// edges (Liang–Barsky on each segment).
pub fn clip(
    points: &[(f64, f64)],
    ((x0, x1), (y0, y1)): ((f64, f64), (f64, f64)),
) -> Vec<Vec<(f64, f64)>> {
    let mut pieces: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut current: Vec<(f64, f64)> = Vec::new();
    for w in points.windows(2) {
        let (a, b) = (w[0], w[1]);
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        let mut inside = true;
        for (p, q) in [
            (-dx, a.0 - x0),
            (dx, x1 - a.0),
            (-dy, a.1 - y0),
            (dy, y1 - a.1),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    inside = false;
                }
            } else {
                let r = q / p;
                if p < 0.0 {
                    t0 = t0.max(r);
                } else {
                    t1 = t1.min(r);
                }
            }
        }
        if !inside || t0 > t1 || !(a.1.is_finite() && b.1.is_finite()) {
            if current.len() > 1 {
                pieces.push(std::mem::take(&mut current));
            }
            current.clear();
            continue;
        }
        let start = (a.0 + t0 * dx, a.1 + t0 * dy);
        let end = (a.0 + t1 * dx, a.1 + t1 * dy);
        if current.last() != Some(&start) {
            if current.len() > 1 {
                pieces.push(std::mem::take(&mut current));
            }
            current.clear();
            current.push(start);
        }
        current.push(end);
        if t1 < 1.0 {
            pieces.push(std::mem::take(&mut current));
        }
    }
    if current.len() > 1 {
        pieces.push(current);
    }
    pieces
}

#[cfg(test)]
mod tests {
    use super::clip;

    #[test]
    fn a_line_leaving_the_panel_is_cut_at_its_edge() {
        let pts = [(0.0, 0.0), (1.0, 1.0), (2.0, 3.0), (3.0, 1.0), (4.0, 0.5)];
        let pieces = clip(&pts, ((0.0, 4.0), (-1.0, 2.0)));
        assert_eq!(pieces.len(), 2, "{pieces:?}");
        assert_eq!(pieces[0], vec![(0.0, 0.0), (1.0, 1.0), (1.5, 2.0)]);
        assert_eq!(pieces[1], vec![(2.5, 2.0), (3.0, 1.0), (4.0, 0.5)]);
        // A window of x: the ends are interpolated.
        let pieces = clip(&pts, ((0.5, 1.25), (-1.0, 2.0)));
        assert_eq!(pieces, vec![vec![(0.5, 0.5), (1.0, 1.0), (1.25, 1.5)]]);
    }
}
