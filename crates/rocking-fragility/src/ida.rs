//! Incremental dynamic analysis of one record by hunt-and-fill
//! (Vamvatsikos & Cornell 2002, *EESD* 31(3), §6): step the intensity up
//! with a growing step until the structure collapses (hunt), bisect between
//! the highest survivor and the lowest collapse until they are within a
//! relative tolerance (bracket), then run in the largest gaps below the
//! capacity until none is wider than a stated fraction of it (fill).
//!
//! **Resurrection** (a survivor above a collapse): the capacity is the
//! *first* collapse, the lowest collapsing IM, as the paper recommends. A
//! fill run that collapses below the current capacity becomes the new
//! capacity and is bracketed in turn; the survivors above it stay on the
//! curve. A band of collapse narrower than the fill gap can still be missed:
//! that is the resolution `max_gap` states.

use std::fmt;

/// What one analysis at an intensity level reports.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Outcome {
    /// The structure collapsed (overturned).
    pub collapsed: bool,
    /// The response measure, e.g. max |θ|/α.
    pub response: f64,
}

/// One run of the IDA curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IdaPoint {
    /// Intensity level.
    pub im: f64,
    /// The outcome at that level.
    pub outcome: Outcome,
}

/// The settings of hunt-and-fill (the paper's defaults scaled to the IM).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HuntFill {
    /// First intensity level (> 0).
    pub first: f64,
    /// First hunting step (> 0).
    pub step: f64,
    /// Added to the step after every hunting run (≥ 0): the step grows so
    /// that a strong structure is reached in few runs.
    pub step_increment: f64,
    /// Relative tolerance of the capacity: the highest survivor below it is
    /// within `tolerance × capacity` (0 < tolerance < 1).
    pub tolerance: f64,
    /// Fill until no gap between runs below the capacity (from IM 0) is
    /// wider than `max_gap × capacity` (≥ tolerance).
    pub max_gap: f64,
    /// Most analyses to run (≥ 1).
    pub max_runs: usize,
}

/// The IDA curve of one record.
#[derive(Debug, Clone, PartialEq)]
pub struct Ida {
    /// The lowest IM at which a run collapsed.
    pub capacity: f64,
    /// The highest IM below the capacity at which a run survived (0 if none):
    /// the true threshold lies in (survived_below, capacity].
    pub survived_below: f64,
    /// Every run, sorted by IM.
    pub points: Vec<IdaPoint>,
}

impl Ida {
    /// Number of analyses run.
    pub fn runs(&self) -> usize {
        self.points.len()
    }
}

/// A setting of [`HuntFill`] outside its range.
#[derive(Debug, Clone, PartialEq)]
pub struct HuntFillError {
    /// The field of [`HuntFill`].
    pub field: &'static str,
    /// The value given.
    pub value: f64,
    /// What is allowed, with the field's name (`tolerance in (0, 1)`).
    pub allowed: &'static str,
}

impl fmt::Display for HuntFillError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "HuntFill: expected {}, found {}",
            self.allowed, self.value
        )
    }
}

impl std::error::Error for HuntFillError {}

/// Why an IDA did not finish.
#[derive(Debug)]
pub enum IdaError<E> {
    /// A setting of [`HuntFill`] is invalid.
    InvalidParameter(HuntFillError),
    /// The analysis at `im` failed.
    Analysis {
        /// The intensity level of the failed run.
        im: f64,
        /// The analysis' error.
        source: E,
    },
    /// `max_runs` analyses ran before the capacity was bracketed and filled;
    /// the runs so far, sorted by IM, are returned.
    RunBudget {
        /// What was still to do.
        stage: &'static str,
        /// The runs so far.
        points: Vec<IdaPoint>,
    },
}

impl<E: fmt::Display> fmt::Display for IdaError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            IdaError::InvalidParameter(m) => write!(f, "invalid parameter: {m}"),
            IdaError::Analysis { im, source } => write!(f, "analysis at IM {im} failed: {source}"),
            IdaError::RunBudget { stage, points } => {
                let top = points.iter().map(|p| p.im).fold(0.0, f64::max);
                write!(
                    f,
                    "hunt-and-fill: max_runs = {} analyses ran before {stage} \
                     (highest IM run {top})",
                    points.len()
                )
            }
        }
    }
}

impl<E: fmt::Debug + fmt::Display> std::error::Error for IdaError<E> {}

impl HuntFill {
    fn check<E>(&self) -> Result<(), IdaError<E>> {
        let checks = [
            (
                "first",
                self.first,
                self.first.is_finite() && self.first > 0.0,
                "first > 0 and finite",
            ),
            (
                "step",
                self.step,
                self.step.is_finite() && self.step > 0.0,
                "step > 0 and finite",
            ),
            (
                "step_increment",
                self.step_increment,
                self.step_increment.is_finite() && self.step_increment >= 0.0,
                "step_increment >= 0 and finite",
            ),
            (
                "tolerance",
                self.tolerance,
                self.tolerance > 0.0 && self.tolerance < 1.0,
                "tolerance in (0, 1)",
            ),
            (
                "max_gap",
                self.max_gap,
                self.max_gap >= self.tolerance && self.max_gap < 1.0,
                "max_gap in [tolerance, 1)",
            ),
            (
                "max_runs",
                self.max_runs as f64,
                self.max_runs >= 1,
                "max_runs >= 1",
            ),
        ];
        match checks.into_iter().find(|&(_, _, ok, _)| !ok) {
            Some((field, value, _, allowed)) => Err(IdaError::InvalidParameter(HuntFillError {
                field,
                value,
                allowed,
            })),
            None => Ok(()),
        }
    }

    /// Trace the IDA curve of one record: `analyse(im)` runs the record
    /// scaled to intensity `im` and reports collapse and the response.
    ///
    /// # Errors
    /// Invalid settings, a failed analysis, or `max_runs` reached before
    /// the capacity is bracketed to `tolerance` and filled to `max_gap`.
    pub fn run<E, F>(&self, mut analyse: F) -> Result<Ida, IdaError<E>>
    where
        F: FnMut(f64) -> Result<Outcome, E>,
    {
        self.check()?;
        let mut points: Vec<IdaPoint> = Vec::new();
        let mut call = |im: f64, points: &mut Vec<IdaPoint>, stage| {
            if points.len() >= self.max_runs {
                points.sort_by(|a, b| a.im.total_cmp(&b.im));
                return Err(IdaError::RunBudget {
                    stage,
                    points: std::mem::take(points),
                });
            }
            let outcome = analyse(im).map_err(|source| IdaError::Analysis { im, source })?;
            points.push(IdaPoint { im, outcome });
            Ok(outcome.collapsed)
        };
        // hunt up
        let (mut im, mut step) = (self.first, self.step);
        while !call(im, &mut points, "the first collapse (hunt)")? {
            im += step;
            step += self.step_increment;
        }
        // bracket and fill, until neither has anything to do
        loop {
            points.sort_by(|a, b| a.im.total_cmp(&b.im));
            let first = points
                .iter()
                .position(|p| p.outcome.collapsed)
                .expect("the hunt ended on a collapse");
            let capacity = points[first].im;
            let below = if first > 0 { points[first - 1].im } else { 0.0 };
            if capacity - below > self.tolerance * capacity {
                call(0.5 * (below + capacity), &mut points, "the bracket closed")?;
                continue;
            }
            // widest gap among [0, runs below the capacity, capacity]
            let mut gap = (0.0, 0.0);
            let mut prev = 0.0;
            for p in &points[..=first] {
                if p.im - prev > gap.1 - gap.0 {
                    gap = (prev, p.im);
                }
                prev = p.im;
            }
            if gap.1 - gap.0 > self.max_gap * capacity {
                call(0.5 * (gap.0 + gap.1), &mut points, "the fill")?;
                continue;
            }
            return Ok(Ida {
                capacity,
                survived_below: below,
                points,
            });
        }
    }
}
