//! Where a spectrum turns from upright to overturned. On the grid of a two-axis sweep: the cell
//! edges between an overturned cell and an upright one (survived or no uplift), joined into
//! lines ([`cell_edges`], [`polylines`]): drawn on the rocking spectra, exactly between the cells
//! that differ. Along one column of the grid (one ω_p/p): the lowest amplitude that overturns,
//! bracketed by the cells ([`lowest_overturning`]), which Fig. 9's lines follow and a figure may
//! refine by bisection.

/// A segment, in the axes' values.
pub type Segment = [(f64, f64); 2];

/// The lower and upper edge of cell `k` of an axis whose cell centres are `v` (sorted): halfway
/// to the neighbours, half a step beyond the first and last.
pub fn cell_bounds(v: &[f64], k: usize) -> (f64, f64) {
    let n = v.len();
    if n < 2 {
        let h = 0.5f64.max(v[0].abs() * 0.05);
        return (v[0] - h, v[0] + h);
    }
    let lo = if k == 0 {
        v[0] - (v[1] - v[0]) / 2.0
    } else {
        (v[k - 1] + v[k]) / 2.0
    };
    let hi = if k + 1 == n {
        v[n - 1] + (v[n - 1] - v[n - 2]) / 2.0
    } else {
        (v[k] + v[k + 1]) / 2.0
    };
    (lo, hi)
}

/// The edges between neighbouring cells of which one overturned (`Some(true)`) and the other
/// stayed upright (`Some(false)`); a failed cell (`None`) borders nothing. `over[i][j]` is the
/// cell at (`xs[i]`, `ys[j]`).
pub fn cell_edges(over: &[Vec<Option<bool>>], xs: &[f64], ys: &[f64]) -> Vec<Segment> {
    let differ = |a: Option<bool>, b: Option<bool>| matches!((a, b), (Some(x), Some(y)) if x != y);
    let mut out = Vec::new();
    for i in 0..xs.len() {
        let (x0, x1) = cell_bounds(xs, i);
        for j in 0..ys.len() {
            let (y0, y1) = cell_bounds(ys, j);
            if i + 1 < xs.len() && differ(over[i][j], over[i + 1][j]) {
                out.push([(x1, y0), (x1, y1)]);
            }
            if j + 1 < ys.len() && differ(over[i][j], over[i][j + 1]) {
                out.push([(x0, y1), (x1, y1)]);
            }
        }
    }
    out
}

/// The lowest overturning amplitude of one column of cells, as the cells bracket it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Lowest {
    /// No cell of the column overturned.
    Never,
    /// The lowest cell already overturned: at or below this amplitude.
    AtOrBelow(f64),
    /// Upright at the first amplitude, overturned at the second, the next cell up.
    Between(f64, f64),
}

/// The lowest overturning amplitude of a column: `cells` are (amplitude, overturned) sorted by
/// amplitude, failed cells left out.
pub fn lowest_overturning(cells: &[(f64, bool)]) -> Lowest {
    match cells.iter().position(|c| c.1) {
        None => Lowest::Never,
        Some(0) => Lowest::AtOrBelow(cells[0].0),
        Some(k) => Lowest::Between(cells[k - 1].0, cells[k].0),
    }
}

/// The segments joined into polylines at their shared ends (neighbouring edges take a shared
/// corner from the same [`cell_bounds`] expression, so ends match exactly): dashes then run on
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

    #[test]
    fn the_boundary_runs_exactly_between_overturned_and_upright_cells() {
        // A staircase with an island, a failed cell and uneven steps.
        let xs = [1.0, 2.0, 4.0, 5.0, 7.0];
        let ys = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
        let step = [3, 2, 2, 1, 4];
        let mut over: Vec<Vec<Option<bool>>> = step
            .iter()
            .map(|&s| (0..ys.len()).map(|j| Some(j >= s)).collect())
            .collect();
        over[1][4] = Some(false); // a survival island
        over[3][4] = None; // failed
        let segments = cell_edges(&over, &xs, &ys);
        // Each segment is a shared edge of two cells, one overturned and one upright.
        let cell_of = |x: f64, y: f64| {
            let i = (0..xs.len()).find(|&i| {
                let (a, b) = cell_bounds(&xs, i);
                a < x && x < b
            });
            let j = (0..ys.len()).find(|&j| {
                let (a, b) = cell_bounds(&ys, j);
                a < y && y < b
            });
            (i, j)
        };
        let mut found = std::collections::BTreeSet::new();
        for [p, q] in &segments {
            let mid = ((p.0 + q.0) / 2.0, (p.1 + q.1) / 2.0);
            let pair = if p.0 == q.0 {
                // Vertical: the cells left and right of it.
                let (_, j) = cell_of(mid.0, mid.1);
                let (l, _) = cell_of(mid.0 - 1e-9, mid.1);
                let (r, _) = cell_of(mid.0 + 1e-9, mid.1);
                ((l.unwrap(), j.unwrap()), (r.unwrap(), j.unwrap()))
            } else {
                let (i, _) = cell_of(mid.0, mid.1);
                let (_, d) = cell_of(mid.0, mid.1 - 1e-9);
                let (_, u) = cell_of(mid.0, mid.1 + 1e-9);
                ((i.unwrap(), d.unwrap()), (i.unwrap(), u.unwrap()))
            };
            let (a, b) = (over[pair.0 .0][pair.0 .1], over[pair.1 .0][pair.1 .1]);
            assert!(
                a.is_some() && b.is_some() && a != b,
                "{pair:?}: {a:?} {b:?}"
            );
            assert!(found.insert(pair), "{pair:?} twice");
        }
        // And every such pair has its segment.
        let mut expected = std::collections::BTreeSet::new();
        for i in 0..xs.len() {
            for j in 0..ys.len() {
                for (k, l) in [(i + 1, j), (i, j + 1)] {
                    if k < xs.len() && l < ys.len() {
                        if let (Some(a), Some(b)) = (over[i][j], over[k][l]) {
                            if a != b {
                                expected.insert(((i, j), (k, l)));
                            }
                        }
                    }
                }
            }
        }
        assert_eq!(found, expected);
        // The island is a closed loop of its own.
        let lines = polylines(&segments);
        assert!(
            lines.iter().any(|l| l.len() == 5 && l.first() == l.last()),
            "{lines:?}"
        );
    }

    #[test]
    fn the_lowest_overturning_amplitude_is_bracketed_by_its_column() {
        assert_eq!(
            lowest_overturning(&[(1.0, false), (2.0, false)]),
            Lowest::Never
        );
        assert_eq!(
            lowest_overturning(&[(1.0, true), (2.0, false)]),
            Lowest::AtOrBelow(1.0)
        );
        assert_eq!(
            lowest_overturning(&[(1.0, false), (2.0, true), (3.0, false), (4.0, true)]),
            Lowest::Between(1.0, 2.0)
        );
    }
}
