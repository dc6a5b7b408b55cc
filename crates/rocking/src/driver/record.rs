//! What a run records (values only, as the force record is): the maxima of θ and u, the counts
//! and first times of its events, the kinetic energy lost at impacts, the event log, the history
//! and the force record. The transitions write it through its methods for an uplift, an impact
//! and an overturning; the recorder adds the maxima inside steps and the rows, and reads it into
//! the summary.

use rocking_kernels::Array;

use super::force_record::ForceRecord;
use super::impact::Outcome;
use crate::results::{EventRecord, HistoryRow};

/// What the run has recorded so far.
#[derive(Default)]
pub(super) struct Record {
    pub(super) max_theta: f64,
    pub(super) max_u: f64,
    pub(super) impacts: u64,
    pub(super) significant: u64,
    pub(super) energy_capped: u64,
    pub(super) first_uplift: Option<f64>,
    pub(super) first_impact: Option<f64>,
    pub(super) overturn: Option<f64>,
    /// Kinetic energy lost at impacts (the energy balance's third term).
    pub(super) losses: f64,
    pub(super) log: Vec<EventRecord>,
    pub(super) history: Vec<HistoryRow>,
    /// u_1..u_n, u_1'..u_n' of each history row, for n > 1.
    pub(super) coordinates: Vec<f64>,
    /// The next time of the history grid.
    pub(super) next_grid: f64,
    /// The extremes of the section forces and reactions.
    pub(super) forces: ForceRecord,
}

impl Record {
    /// |θ| and the top deflection |u| at an instant.
    pub(super) fn track(&mut self, theta: f64, u: f64) {
        self.max_theta = self.max_theta.max(theta.abs());
        self.max_u = self.max_u.max(u.abs());
    }

    /// An uplift at `t`.
    pub(super) fn uplift(&mut self, t: f64) {
        self.first_uplift.get_or_insert(t);
    }

    /// The overturning at `t`, where θ and the top deflection are `theta` and `u`.
    pub(super) fn overturn(&mut self, t: f64, theta: f64, u: f64) {
        self.overturn = Some(t);
        self.track(theta, u);
    }

    /// An impact at `t` as the policy resolved it (`out`); `significant`: its |θ'| reached the
    /// significant rate.
    pub(super) fn impact<X: Array>(&mut self, t: f64, significant: bool, out: &Outcome<X>) {
        if significant {
            self.significant += 1;
        }
        if out.counted {
            self.impacts += 1;
            self.first_impact.get_or_insert(t);
        }
        if out.capped {
            self.energy_capped += 1;
        }
        self.losses += out.energy_before - out.energy_after();
    }
}
