"""The hybrid driver of the Python peers: phases, impact policy, rest rule and bookkeeping, once.

It follows the Rust driver (crates/rocking/src/driver.rs): full contact, rocking about either
corner, the impact at theta = 0 decided by VVEL, ADJex, Housner or a fixed restitution, no impact
creating kinetic energy (`Driver.without_energy_gain`), the rest rule (a rocking rate below the
rest rate settles the base in full contact, and after a rest the base lifts no earlier than the
end of the first contact step) and overturning. A peer supplies two things and nothing else:

* `physics`: pointwise quantities of the derivation, evaluated however the peer likes (CasADi
  functions, heyoka compiled functions): ``uplift(u, u', ug) -> (f_+, f_-)``,
  ``theta_ddot(s, u, u', ug)`` (the rocking theta'' at theta = theta' = 0),
  ``kinetic(x, s)`` and ``impact(name, u, u', theta', s)`` (the output vector of the kernel
  `name`), with ``fields(name)``, the kernel's output names in order;
* `phases`: its integrator of the two phases, ``contact(t0, u, u', settling) -> (t, s, u, u')``
  (s the corner that lifts at t, None when the run reached its end) and
  ``rocking(t0, s, x0, n) -> (t, event, x, max |theta| on the way)`` (event IMPACT, OVERTURN or
  None at the end; n as in the Rust driver: theta's order of vanishing at t0; x0 and x are
  [theta, u, theta', u']).

Numbers cross this interface as Python floats where the peer can: arithmetic on numpy scalars
costs several times more, which matters on the per-event path of a fast integrator.

The answers are the study's (`rocking-bench`, crates/rocking-bench/src/study.rs): max theta/alpha,
the significant impacts' tau (|theta'| >= 0.01 alpha p) and every impact's (rests included),
overturning, the final scaled state.
"""

from __future__ import annotations

import bisect
import math

import numpy as np

RIGHT, LEFT = 1.0, -1.0
IMPACT, OVERTURN = 0, 1


class Motion:
    """The ground acceleration of a case: a one-period sine pulse, a record (linear between
    samples) or none; `kinks` are where it is not smooth, and every phase restarts there."""

    def __init__(self, m: dict):
        self.kind = m["kind"]
        if self.kind == "sine":
            self.a, self.w, self.t0 = m["amplitude"], m["omega"], m["start"]
            self.t1 = self.t0 + 2 * math.pi / self.w
            self.kinks = [self.t0, self.t1]
        elif self.kind == "record":
            self.dt = m["dt"]
            self.samples = np.asarray(m["samples"], dtype=float)
            self.grid = self.dt * np.arange(len(self.samples))
            self.kinks = self.grid.tolist()
            self.t1 = self.grid[-1]
        elif self.kind == "none":
            self.kinks, self.t1 = [], 0.0
        else:
            raise ValueError(f"unsupported motion {self.kind}")

    def accel(self, t: float) -> float:
        if self.kind == "sine":
            return self.a * math.sin(self.w * (t - self.t0)) if self.t0 <= t <= self.t1 else 0.0
        if self.kind == "record":
            return float(np.interp(t, self.grid, self.samples, left=0.0, right=0.0)) if t <= self.t1 else 0.0
        return 0.0

    def next_stop(self, t: float, t_end: float) -> float:
        """The first kink after t (not t itself, within rounding), or t_end."""
        i = bisect.bisect_right(self.kinks, t * (1 + 1e-15) + 1e-300)
        return min(self.kinks[i], t_end) if i < len(self.kinks) else t_end


class Case:
    """One case of `cases.json` (written by `rocking-bench run`) with the driver's thresholds."""

    def __init__(self, case: dict):
        self.params = np.asarray(case["params"], dtype=float)
        self.alpha, self.p = case["alpha"], case["p"]
        self.u_scale, self.ud_scale = case["u_scale"], case["ud_scale"]
        # The natural scales of the rocking state [theta, u, theta', u'].
        self.scales = np.array([self.alpha, self.u_scale, self.alpha * self.p, self.ud_scale])
        self.t_end = case["t_end"]
        self.overturn_angle = case["overturn_angle"]
        self.rest_rate = case["rest_rate"] * self.alpha * self.p
        self.significant_rate = 0.01 * self.alpha * self.p
        self.impact = case["impact"]
        self.restitution = case.get("restitution")
        if self.impact == "restitution" and self.restitution is None:
            raise ValueError(f"case {case['name']}: impact = restitution needs the field 'restitution'")
        self.initial = [float(v) for v in case["initial"]]


class Driver:
    """One simulation's hybrid logic; `run` returns the study's answer."""

    def __init__(self, case: Case, physics, phases):
        self.case, self.physics, self.phases = case, physics, phases
        self.max_theta = abs(case.initial[0])
        self.impacts: list[float] = []  # tau of the significant impacts
        self.all_impacts: list[float] = []  # tau of every impact, rests included
        self.impact_count = 0  # impacts that were not rests (the Rust summary's `impacts`)
        self.energy_capped = 0
        self.overturn = None

    def lift_side(self, u: float, u_dot: float, ug: float, f=None):
        """The corner about which the base lifts from full contact at this state, or None: f_s > 0
        and the rocking equations give s theta'' > 0 (equivalent but within rounding of f_s = 0);
        `f` the uplift functions there when known."""
        f = self.physics.uplift(u, u_dot, ug) if f is None else f
        for k, s in ((0, RIGHT), (1, LEFT)):
            if f[k] > 0 and s * self.physics.theta_ddot(s, u, u_dot, ug) > 0:
                return s
        return None

    def run(self, motion: Motion) -> dict:
        c = self.case
        th0, u0, td0, ud0 = c.initial
        if th0 != 0.0 or td0 != 0.0:
            s = RIGHT if th0 > 0 or (th0 == 0 and td0 > 0) else LEFT
            phase = ("rock", 0.0, s, (th0, u0, td0, ud0), 0 if th0 != 0 else 1)
        else:
            phase = ("contact", 0.0, u0, ud0, False)
        while True:
            if phase[0] == "contact":
                _, t, u, ud, settle = phase
                # At every start of a contact phase the base may lift at once (the rigid limit's
                # impact, zero-length contact, re-uplift), except just after a rest.
                ug = motion.accel(t)
                f = self.physics.uplift(u, ud, ug)
                s = None if settle else self.lift_side(u, ud, ug, f)
                if s is None:
                    # The settling step exists for an f_s already above zero at the rest.
                    settling = settle and (f[0] > 0 or f[1] > 0)
                    t, s, u, ud = self.phases.contact(t, u, ud, settling)
                    if s is None:
                        final = (t, (0.0, u, 0.0, ud))
                        break
                phase = ("rock", t, s, (0.0, u, 0.0, ud), 2)
                continue
            _, t0, s, x0, n = phase
            t, event, x, max_theta = self.phases.rocking(t0, s, x0, n)
            self.max_theta = max(self.max_theta, max_theta)
            if event is None:
                final = (t, x)
                break
            if event == OVERTURN:
                self.overturn = t
                self.max_theta = max(self.max_theta, abs(x[0]))
                final = (t, x)
                break
            phase = self.impact(t, s, x[1], x[3], x[2])
        tf, xf = final
        return {
            "max_theta_over_alpha": self.max_theta / c.alpha,
            "impacts": self.impacts,
            "all_impacts": self.all_impacts,
            "impact_count": self.impact_count,
            "energy_capped": self.energy_capped,
            "overturned": self.overturn is not None,
            "overturn_tau": None if self.overturn is None else self.overturn * c.p,
            "final_state": (np.asarray(xf) / c.scales).tolist(),
            "final_tau": tf * c.p,
        }

    def without_energy_gain(self, after: tuple, e_after: float, e_before: float, u: float, s: float):
        """No impact may create kinetic energy: where the post-impact kinetic energy exceeds the
        pre-impact one (beyond 1e-9 relative; both less the part of a base at rest), the
        velocities are scaled by one common factor to keep it (the Rust driver's rule)."""
        if e_after <= e_before:
            return after  # the same test less the same rest energy cannot find a gain
        rest = self.physics.kinetic((0.0, u, 0.0, 0.0), s)
        t_before, t_after = e_before - rest, e_after - rest
        if not (t_after > t_before * (1.0 + 1e-9) and t_after > 0.0):
            return after
        self.energy_capped += 1
        k = math.sqrt(max(t_before, 0.0) / t_after)
        return (after[0], *(k * v for v in after[1:]))

    def impact(self, t: float, s: float, u: float, u_dot: float, theta_dot: float) -> tuple:
        """The impact at theta = 0 while rocking about s (the corner -s hits the ground): the next
        phase, ("contact", t, u, u', settle) or ("rock", t, -s, x, 1)."""
        c, ph = self.case, self.physics
        self.all_impacts.append(t * c.p)
        if abs(theta_dot) >= c.significant_rate:
            self.impacts.append(t * c.p)
        s2 = -s
        if abs(theta_dot) < c.rest_rate:
            # A negligible rocking excursion (grazing, the end of a Zeno sequence): the base
            # settles in full contact with the column's motion unchanged.
            e_before = ph.kinetic((0.0, u, theta_dot, u_dot), s)
            after = ("contact", u_dot)
            after = self.without_energy_gain(after, ph.kinetic((0.0, u, 0.0, u_dot), s2), e_before, u, s)
            return ("contact", t, u, after[1], True)
        self.impact_count += 1
        model = c.impact
        if model == "restitution":
            td = c.restitution * theta_dot
            after = ("rock", td, u_dot)
            e_after = ph.kinetic((0.0, u, td, u_dot), s2)
            e_before = ph.kinetic((0.0, u, theta_dot, u_dot), s)
        else:
            name = f"impact_{model}"
            if name not in ("impact_vvel", "impact_adjex", "impact_housner"):
                raise ValueError(f"unknown impact model {model!r}")
            v = dict(zip(ph.fields(name), ph.impact(name, u, u_dot, theta_dot, s)))
            if model == "vvel":
                after = ("rock", v["theta_dot"], v["u_dot"]) if v["rock"] != 0 else ("contact", v["u_dot"])
                e_after, e_before = v["energy_after"], v["energy_before"]
            elif model == "adjex":
                e_before = v["energy_before"]
                contact = (v["energy_contact"], ("contact", v["u_dot_contact"]))
                rocking = (v["energy_rocking"], ("rock", v["theta_dot_rocking"], v["u_dot_rocking"]))
                momentum = (v["energy_momentum"], ("contact", v["u_dot_momentum"]))
                best = rocking if (s2 * v["theta_dot_rocking"] > 0 and rocking[0] < contact[0]) else contact
                if best[0] <= e_before:
                    e_after, after = best
                elif momentum[0] <= e_before:
                    e_after, after = momentum
                else:  # every candidate gains energy (unspecified by the paper): the least
                    e_after, after = momentum if momentum[0] < best[0] else best
            else:  # housner
                e_before = v["energy_before"]
                if s2 * v["theta_dot"] > 0:
                    after, e_after = ("rock", v["theta_dot"], v["u_dot"]), v["energy_after"]
                else:  # a squat body whose angular momentum reverses cannot rock on: it stops
                    after, e_after = ("contact", u_dot), ph.kinetic((0.0, u, 0.0, u_dot), s2)
        rest = after[0] == "rock" and abs(after[1]) < c.rest_rate
        if rest:
            after = ("contact", after[2])
            e_after = ph.kinetic((0.0, u, 0.0, after[1]), s2)
        after = self.without_energy_gain(after, e_after, e_before, u, s2)
        if after[0] == "contact":
            return ("contact", t, u, after[1], rest)
        return ("rock", t, s2, (0.0, u, after[1], after[2]), 1)
