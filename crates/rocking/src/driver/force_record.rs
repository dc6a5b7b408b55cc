//! The forces at one instant and the record of their extremes along a run: values, not the
//! evaluation (that is [`super::forces`]), so that the run's state can hold the record.

use rocking_kernels::kernels::index::forces_rocking as fk;

use crate::results::{ForceSummary, Time};

/// The forces at one instant: in the model's units (a history row), or normalised by the total
/// weight W and the uplift moment W B (the extremes the summary reports).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Forces {
    /// M_b, or M_b / (W B).
    pub(super) moment: f64,
    /// V_b, or V_b / W.
    pub(super) shear: f64,
    /// M_el, or M_el / (W B).
    pub(super) elastic: f64,
    /// R_h, or R_h / W.
    pub(super) horizontal: f64,
    /// R_v, or R_v / W.
    pub(super) vertical: f64,
}

/// The number of quantities whose extremes a run reports.
pub(super) const MEASURES: usize = 5;

// [`Forces::measures`] and the public [`ForceExtreme`](crate::ForceExtreme) (whose set,
// `ForceExtremes`, holds one flag per measure) name the same quantities in the same order.
const _: () = assert!(crate::ForceExtreme::VerticalReaction as usize + 1 == MEASURES);

impl Forces {
    /// The forces a force kernel returns (`forces_contact`, `forces_rocking` and
    /// `section_forces` name their outputs alike), in the model's units.
    pub(super) fn of_kernel(f: &[f64; 6]) -> Forces {
        Forces {
            moment: f[fk::MOMENT],
            shear: f[fk::SHEAR],
            elastic: f[fk::MOMENT_ELASTIC],
            horizontal: f[fk::REACTION_H],
            vertical: f[fk::REACTION_V],
        }
    }

    /// The forces in the model's units normalised by the weight `w` and the moment `wb` = W B.
    pub(super) fn per_weight(self, w: f64, wb: f64) -> Forces {
        Forces {
            moment: self.moment / wb,
            shear: self.shear / w,
            elastic: self.elastic / wb,
            horizontal: self.horizontal / w,
            vertical: self.vertical / w,
        }
    }

    /// The quantities whose largest value is reported, in the order of [`ForceRecord::max`] and
    /// of [`ForceExtreme`](crate::ForceExtreme):
    /// |M_b|, |V_b|, |M_el|, the required friction |R_h| / R_v (−∞ where R_v <= 0, left out of
    /// its largest value: where R_v < 0 no friction holds, which the summary reports as an
    /// unbounded demand from the first lift-off, [`ForceRecord::first_lift_off`]), and −R_v (its largest is the smallest
    /// vertical reaction).
    pub(super) fn measures(&self) -> [f64; MEASURES] {
        [
            self.moment.abs(),
            self.shear.abs(),
            self.elastic.abs(),
            self.required_friction(),
            -self.vertical,
        ]
    }

    pub(super) fn required_friction(&self) -> f64 {
        if self.vertical > 0.0 {
            self.horizontal.abs() / self.vertical
        } else {
            f64::NEG_INFINITY
        }
    }
}

/// The extremes of the forces so far.
#[derive(Clone, Copy, Debug)]
pub(super) struct ForceRecord {
    /// The largest of each of [`Forces::measures`].
    pub(super) max: [f64; MEASURES],
    /// When the required friction first exceeded the scene's coefficient.
    pub(super) first_slip: Option<f64>,
    /// When R_v first fell below zero.
    pub(super) first_lift_off: Option<f64>,
}

impl Default for ForceRecord {
    fn default() -> Self {
        ForceRecord {
            max: [f64::NEG_INFINITY; MEASURES],
            first_slip: None,
            first_lift_off: None,
        }
    }
}

impl ForceRecord {
    /// Records the largest values `peak` of the reported quantities, reached at the times
    /// `when`, and an assumption's failure among them at its time in `when` (where none is
    /// recorded yet: a step refines it to the first instant before); `friction` is the
    /// coefficient the scene counts on, if any.
    pub(super) fn record(
        &mut self,
        peak: &[f64; MEASURES],
        when: [f64; MEASURES],
        friction: Option<f64>,
    ) {
        let rec = self;
        for (max, v) in rec.max.iter_mut().zip(peak) {
            *max = max.max(*v);
        }
        if rec.first_slip.is_none() && friction.is_some_and(|mu| peak[3] > mu) {
            rec.first_slip = Some(when[3]);
        }
        if rec.first_lift_off.is_none() && peak[4] > 0.0 {
            rec.first_lift_off = Some(when[4]);
        }
    }

    /// The force extremes of the run, as the summary reports them (`time`: a solver time in
    /// the run's units).
    pub(super) fn summary(&self, time: impl Fn(f64) -> Time) -> ForceSummary {
        let r = self;
        ForceSummary {
            max_base_moment_over_wb: r.max[0],
            max_base_shear_over_w: r.max[1],
            max_elastic_base_moment_over_wb: r.max[2],
            // Unbounded from the first lift-off (R_v < 0): the largest |R_h| / R_v sampled
            // before it depends on how close the steps come to R_v = 0 (ForceSummary's doc).
            max_required_friction: if r.first_lift_off.is_some() {
                f64::INFINITY
            } else {
                r.max[3].max(0.0)
            },
            min_vertical_reaction_over_w: -r.max[4],
            first_slip_time: r.first_slip.map(&time),
            first_lift_off_time: r.first_lift_off.map(&time),
        }
    }
}
