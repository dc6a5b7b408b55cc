//! What a run on compliant ground records: the maxima at each state, history rows, the event
//! log, and the summary at its end.

use super::*;
use rocking_kernels::kernels::index::free_forces as ff;

impl<V: TaylorVariant, M: GroundMotion + ?Sized, const N: usize> GroundSim<'_, V, M, N> {
    /// The maxima at one state.
    pub(super) fn observe(&mut self, t: f64, y: &V::Y, s: f64, c: Contact) {
        let ug = self.motion.accel(t);
        let (acc, g) = self.k.accelerations(y, ug, s, c);
        let r = &mut self.rec;
        r.max_theta = r.max_theta.max(y.values()[Free::<V>::THETA].abs());
        let top = self.top(y, false);
        let r = &mut self.rec;
        r.max_u = r.max_u.max(top.abs());
        r.max_settlement = r.max_settlement.max(y.values()[Free::<V>::V] / self.v0);
        let pressure = g[go::PRESSURE_LO].max(g[go::PRESSURE_HI]) / self.mean_pressure;
        r.max_pressure = r.max_pressure.max(pressure);
        let least = g[go::PRESSURE_LO].min(g[go::PRESSURE_HI]) / self.mean_pressure;
        r.min_pressure = r.min_pressure.min(least);
        if self.opts.bearing_over_mean.is_some_and(|q| pressure > q) {
            r.first_bearing.get_or_insert(t);
        }
        r.min_contact = r.min_contact.min(contact_fraction(&g));
        if self.opts.forces {
            let f = V::free_forces(y, &acc, ug, s, &self.p);
            let (w, wb) = (self.weight, self.wb);
            let r = &mut self.rec;
            r.max_moment = r.max_moment.max(f[ff::MOMENT].abs() / wb);
            r.max_shear = r.max_shear.max(f[ff::SHEAR].abs() / w);
            r.max_elastic = r.max_elastic.max(f[ff::MOMENT_ELASTIC].abs() / wb);
            let (rh, rv) = (f[ff::REACTION_H] / w, f[ff::REACTION_V] / w);
            r.min_rv = r.min_rv.min(rv);
            let friction = required_friction(rh, rv);
            r.max_friction = r.max_friction.max(friction);
            if rv < 0.0 {
                r.first_pull.get_or_insert(t);
            }
            if let Some(mu) = self.opts.friction {
                if rv > 0.0 && friction > mu {
                    r.first_slip.get_or_insert(t);
                }
            }
        }
    }

    /// A history row at `t`.
    pub(super) fn record(&mut self, t: f64, y: &V::Y, s: f64, c: Contact) {
        let ug = self.motion.accel(t);
        let (acc, g) = self.k.accelerations(y, ug, s, c);
        let f = V::free_forces(y, &acc, ug, s, &self.p);
        let e = V::free_energy(y, s, &self.p);
        let row = HistoryRow {
            t,
            theta: y.values()[Free::<V>::THETA],
            u: self.top(y, false),
            theta_dot: y.values()[Free::<V>::THETA_DOT],
            u_dot: self.top(y, true),
            phase: c.phase(false),
            e_kin: e[KINETIC],
            e_total: self.total_energy(y, s, c),
            ug,
            base_moment: f[ff::MOMENT],
            base_shear: f[ff::SHEAR],
            elastic_base_moment: f[ff::MOMENT_ELASTIC],
            horizontal_reaction: f[ff::REACTION_H],
            vertical_reaction: f[ff::REACTION_V],
            ground: Some(GroundRow {
                settlement: y.values()[Free::<V>::V],
                contact_fraction: contact_fraction(&g),
                ground_pressure: g[go::PRESSURE_LO].max(g[go::PRESSURE_HI]),
                least_pressure: g[go::PRESSURE_LO].min(g[go::PRESSURE_HI]),
            }),
        };
        self.rec.history.push(row);
        if V::NQ > 1 {
            let y = y.values();
            self.rec
                .coordinates
                .extend_from_slice(&y[Free::<V>::us(false)]);
            self.rec
                .coordinates
                .extend_from_slice(&y[Free::<V>::us(true)]);
        }
    }

    pub(super) fn log(
        &mut self,
        t: f64,
        kind: EventKind,
        branch: &'static str,
        after: Phase,
        y: &V::Y,
    ) {
        if !self.opts.event_log {
            return;
        }
        let e = V::free_energy(y, 1.0, &self.p)[KINETIC] / self.derived.e_ref;
        let record = EventRecord {
            time: self.time(t),
            kind,
            branch,
            phase_after: after,
            theta_dot: y.values()[Free::<V>::THETA_DOT],
            u: self.top(y, false),
            u_dot: self.top(y, true),
            energy_before: e,
            energy_after: e,
        };
        self.rec.log.push(record);
    }

    /// The summary of a run that ended at `end` with the integrals `[w, d, dg]` (ground work,
    /// damping, the ground's dissipation), having started with the energy `e_initial`.
    pub(super) fn finish(&self, end: &End<V>, [w, d, dg]: [f64; 3], e_initial: f64) -> Summary {
        let End {
            phase,
            t,
            ref y,
            s,
            c,
        } = *end;
        let e_ref = self.derived.e_ref;
        let last = self.total_energy(y, s, c);
        let (energy, residual) = if self.opts.energy {
            let balance = EnergyBalance {
                initial: e_initial / e_ref,
                last: last / e_ref,
                ground_work: w / e_ref,
                damping: d / e_ref,
                impact_losses: 0.0,
                ground_dissipation: Some(dg / e_ref),
            };
            (Some(balance), Some((last - e_initial - w + d + dg) / e_ref))
        } else {
            (None, None)
        };
        let r = &self.rec;
        let forces = self.opts.forces.then(|| ForceSummary {
            max_base_moment_over_wb: r.max_moment,
            max_base_shear_over_w: r.max_shear,
            max_elastic_base_moment_over_wb: r.max_elastic,
            max_required_friction: r.max_friction,
            min_vertical_reaction_over_w: r.min_rv,
            first_slip_time: r.first_slip.map(|t| self.time(t)),
            first_lift_off_time: r.first_pull.map(|t| self.time(t)),
        });
        Summary {
            kernel_variant: V::NAME,
            max_theta_over_alpha: r.max_theta / self.derived.alpha,
            max_theta_over_theta_cr: r.max_theta / self.derived.theta_cr,
            max_u_over_ucr: if V::RIGID {
                0.0
            } else if !self.opts.max_deflection {
                f64::NAN
            } else {
                r.max_u / self.derived.u_cr
            },
            overturned: r.overturn.is_some(),
            overturn_time: r.overturn.map(|t| self.time(t)),
            impacts: r.landings,
            significant_impacts: r.significant_landings,
            energy_capped_impacts: 0,
            first_uplift_time: r.first_lift_off.map(|t| self.time(t)),
            first_impact_time: r.first_landing.map(|t| self.time(t)),
            final_phase: phase,
            end_time: self.time(t),
            energy_balance_residual: residual,
            energy,
            solver_stats: SolverStats {
                events: r.events,
                ..r.stats
            },
            forces,
            ground: Some(GroundSummary {
                max_ground_pressure_over_mean: r.max_pressure,
                min_ground_pressure_over_mean: r.min_pressure,
                min_contact_fraction: r.min_contact,
                lift_offs: r.lift_offs,
                max_settlement_over_static: r.max_settlement,
                ground_energy_dissipated: dg / e_ref,
                first_bearing_exceeded_time: (self.opts.bearing_over_mean)
                    .map(|_| r.first_bearing.map(|t| self.time(t))),
            }),
        }
    }

    /// The run's answer.
    pub(super) fn into_run(self, summary: Summary) -> Run {
        Run {
            summary,
            events: self.rec.log,
            history: self.rec.history,
            coordinates: self.rec.coordinates,
        }
    }
}

/// |R_h| / R_v; where R_v <= 0 unbounded unless R_h = 0 too.
pub(super) fn required_friction(rh: f64, rv: f64) -> f64 {
    if rv > 0.0 {
        rh.abs() / rv
    } else if rh == 0.0 {
        0.0
    } else {
        f64::INFINITY
    }
}
