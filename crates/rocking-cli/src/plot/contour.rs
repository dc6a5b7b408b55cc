//! Marching squares on a grid of yes/no cells (overturned or not): the boundary between the two
//! classes as line segments through the midpoints between neighbouring cells of different class
//! (the paper's Fig. 9 boundaries, drawn between cells rather than along cell edges).

/// A segment of a contour, in the axes' values.
pub type Segment = [(f64, f64); 2];

/// The contour between `true` and `false` cells of the grid `inside[i][j]` whose cell centres
/// are at (`xs[i]`, `ys[j]`). Each segment joins the midpoints of two sides of a square of four
/// neighbouring cell centres, on the sides whose ends differ. Where a square is a saddle (its
/// diagonals differ), the `true` cells are taken as joined through its centre.
pub fn contour(inside: &[Vec<bool>], xs: &[f64], ys: &[f64]) -> Vec<Segment> {
    let mut out = Vec::new();
    for i in 0..xs.len().saturating_sub(1) {
        for j in 0..ys.len().saturating_sub(1) {
            // Corners counter-clockwise: a (i, j), b (i+1, j), c (i+1, j+1), d (i, j+1).
            let corner = [
                inside[i][j],
                inside[i + 1][j],
                inside[i + 1][j + 1],
                inside[i][j + 1],
            ];
            let (xm, ym) = ((xs[i] + xs[i + 1]) / 2.0, (ys[j] + ys[j + 1]) / 2.0);
            // Side k joins corner k and corner k+1.
            let mid = [(xm, ys[j]), (xs[i + 1], ym), (xm, ys[j + 1]), (xs[i], ym)];
            let crossed: Vec<usize> = (0..4)
                .filter(|&k| corner[k] != corner[(k + 1) % 4])
                .collect();
            match crossed.len() {
                2 => out.push([mid[crossed[0]], mid[crossed[1]]]),
                4 => {
                    // Saddle: cut off each `false` corner k by the sides that meet at it
                    // (sides k-1 and k).
                    for k in (0..4).filter(|&k| !corner[k]) {
                        out.push([mid[(k + 3) % 4], mid[k]]);
                    }
                }
                _ => {}
            }
        }
    }
    out
}

/// The segments joined into polylines at their shared ends (marching squares computes a shared
/// midpoint by the same expression in both squares, so ends match exactly): dashes then run on
/// along a boundary instead of restarting at every cell. A closed loop ends at its start.
pub fn polylines(segments: &[Segment]) -> Vec<Vec<(f64, f64)>> {
    use std::collections::HashMap;
    let key = |p: (f64, f64)| (p.0.to_bits(), p.1.to_bits());
    let mut at: HashMap<(u64, u64), Vec<usize>> = HashMap::new();
    for (k, s) in segments.iter().enumerate() {
        at.entry(key(s[0])).or_default().push(k);
        at.entry(key(s[1])).or_default().push(k);
    }
    let mut used = vec![false; segments.len()];
    // The segment at `p` not used yet, and its other end.
    let next = |p: (f64, f64), used: &mut Vec<bool>| -> Option<(f64, f64)> {
        let k = *at.get(&key(p))?.iter().find(|&&k| !used[k])?;
        used[k] = true;
        let s = segments[k];
        Some(if key(s[0]) == key(p) { s[1] } else { s[0] })
    };
    let mut out = Vec::new();
    // Open chains first, from an end that only one segment touches; then the closed loops.
    let mut starts: Vec<usize> = (0..segments.len()).collect();
    starts.sort_by_key(|&k| at[&key(segments[k][0])].len() != 1);
    for k in starts {
        if used[k] {
            continue;
        }
        used[k] = true;
        let mut line = vec![segments[k][0], segments[k][1]];
        while let Some(p) = next(*line.last().unwrap_or(&segments[k][1]), &mut used) {
            line.push(p);
        }
        while let Some(p) = next(line[0], &mut used) {
            line.insert(0, p);
        }
        out.push(line);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A staircase boundary: cell (i, j) is inside when j >= step[i].
    fn grid(step: &[usize], ny: usize) -> Vec<Vec<bool>> {
        step.iter()
            .map(|&s| (0..ny).map(|j| j >= s).collect())
            .collect()
    }

    #[test]
    fn the_contour_passes_between_cells_of_different_class() {
        let step = [4, 3, 3, 1, 5, 0];
        let ny = 6;
        let inside = grid(&step, ny);
        let xs: Vec<f64> = (0..step.len()).map(|i| 1.0 + 0.5 * i as f64).collect();
        let ys: Vec<f64> = (0..ny).map(|j| 10.0 + 2.0 * j as f64).collect();
        let segs = contour(&inside, &xs, &ys);
        assert!(!segs.is_empty());
        // Every end point is the midpoint of two neighbouring cells of different class.
        let class_at = |x: f64, y: f64| {
            let i = xs.iter().position(|&v| (v - x).abs() < 1e-12);
            let j = ys.iter().position(|&v| (v - y).abs() < 1e-12);
            (i, j)
        };
        let mut midpoints = std::collections::BTreeSet::new();
        for s in &segs {
            for &(x, y) in s {
                let (i, j) = match class_at(x, y) {
                    // On a vertical side: between (i, j) and (i, j+1).
                    (Some(i), None) => {
                        let j = ys.iter().position(|&v| v > y).expect("inside the grid") - 1;
                        assert_ne!(inside[i][j], inside[i][j + 1], "({x}, {y})");
                        (2 * i, 2 * j + 1)
                    }
                    // On a horizontal side: between (i, j) and (i+1, j).
                    (None, Some(j)) => {
                        let i = xs.iter().position(|&v| v > x).expect("inside the grid") - 1;
                        assert_ne!(inside[i][j], inside[i + 1][j], "({x}, {y})");
                        (2 * i + 1, 2 * j)
                    }
                    other => panic!("({x}, {y}) is not between two cells: {other:?}"),
                };
                midpoints.insert((i, j));
            }
        }
        // And every pair of neighbours of different class is crossed.
        let mut expected = std::collections::BTreeSet::new();
        for i in 0..xs.len() {
            for j in 0..ys.len() {
                if j + 1 < ys.len() && inside[i][j] != inside[i][j + 1] {
                    expected.insert((2 * i, 2 * j + 1));
                }
                if i + 1 < xs.len() && inside[i][j] != inside[i + 1][j] {
                    expected.insert((2 * i + 1, 2 * j));
                }
            }
        }
        assert_eq!(midpoints, expected);
    }

    #[test]
    fn a_uniform_grid_has_no_contour_and_a_saddle_cuts_off_the_outside_corners() {
        let xs = [0.0, 1.0];
        let ys = [0.0, 1.0];
        assert!(contour(&[vec![true; 2], vec![true; 2]], &xs, &ys).is_empty());
        assert!(contour(&[vec![false; 2], vec![false; 2]], &xs, &ys).is_empty());
        // inside at (0,0) and (1,1): the outside corners (1,0) and (0,1) are cut off.
        let segs = contour(&[vec![true, false], vec![false, true]], &xs, &ys);
        assert_eq!(segs.len(), 2);
        let cuts_off = |corner: (f64, f64)| {
            segs.iter().any(|s| {
                s.iter()
                    .all(|p| (p.0 - corner.0).abs() + (p.1 - corner.1).abs() == 0.5)
            })
        };
        assert!(cuts_off((1.0, 0.0)) && cuts_off((0.0, 1.0)), "{segs:?}");
    }

    #[test]
    fn segments_join_into_one_line_per_boundary() {
        let ys: Vec<f64> = (0..6).map(|j| j as f64 * 0.5).collect();
        let xs: Vec<f64> = (0..6).map(|i| i as f64).collect();
        // A staircase (one open line) and, apart, one inside cell (a closed loop of 4 segments).
        let mut inside = grid(&[1, 2, 2, 6, 6, 6], ys.len());
        inside[4][3] = true;
        let segments = contour(&inside, &xs, &ys);
        let lines = polylines(&segments);
        assert_eq!(lines.len(), 2, "{lines:?}");
        let total: usize = lines.iter().map(|l| l.len() - 1).sum();
        assert_eq!(total, segments.len(), "every segment is used once");
        let closed = lines.iter().filter(|l| l.first() == l.last()).count();
        assert_eq!(closed, 1, "the lone cell is a closed loop: {lines:?}");
    }
}
