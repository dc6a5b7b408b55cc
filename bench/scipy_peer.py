"""SciPy peer of the rocking solver: the same model, written as a researcher would with solve_ivp.

The physics is not re-typed: the right-hand sides, uplift functions and impact maps are the CasADi
functions built by the derivation package (``rocking_derive``), called with numpy arrays. The
hybrid logic (full contact, rocking about either corner, impacts with VVEL / ADJex / Housner,
overturning, the rest rule) is the Python peers' shared driver, ``bench/hybrid.py``; this file is
its integrator: ``solve_ivp(method='DOP853', events=...)`` with terminal, directional events,
restarting at every event and at every kink of the excitation (the ends of a pulse, the samples
of a record), like the Rust driver.

    PYTHONPATH=derive python bench/scipy_peer.py target/bench/cases.json target/bench/scipy.json \
        [--quick] [--tols 1e-7,1e-10] [--repeats 3]

The cases (structure as the kernels' parameter vector, excitation, impact model, end time) come
from ``rocking-bench run``; the answers (max theta/alpha, impact times, overturning, final state)
and the timings (time.perf_counter, median of the repeats) go to the output JSON, which
``rocking-bench report`` compares with the Rust results.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time

import numpy as np
from scipy.integrate import DOP853, solve_ivp

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "derive"))
from hybrid import IMPACT, LEFT, OVERTURN, RIGHT, Case, Driver, Motion  # noqa: E402
from rocking_derive import ir, kernels, models  # noqa: E402


class Kernels:
    """The pointwise physics of one variant (see `hybrid`): the derivation's CasADi functions,
    called with numpy arrays."""

    def __init__(self, variant_name: str):
        variant = next(v for v in models.VARIANTS if v.name == variant_name)
        ks = kernels.kernels(variant)
        self.f = {k.name: ir.casadi_function(k) for k in ks}
        self.names = {k.name: k.output.elements for k in ks}
        self.kinetic_index = self.names["energy"].index("kinetic")
        self.theta_ddot_index = self.names["rocking_rhs"].index("theta_ddot")
        self.p = None  # the parameter vector of the case being run

    def __call__(self, name, *args):
        return np.asarray(self.f[name](*args)).ravel()

    def fields(self, name):
        return self.names[name]

    def uplift(self, u, u_dot, ug):
        y = np.array([u, u_dot])
        return (self("uplift", y, ug, 1.0, self.p)[0], self("uplift", y, ug, -1.0, self.p)[0])

    def theta_ddot(self, s, u, u_dot, ug):
        return self("rocking_rhs", np.array([0.0, u, 0.0, u_dot]), ug, s, self.p)[self.theta_ddot_index]

    def kinetic(self, x, s):
        return self("energy", np.asarray(x, dtype=float), s, self.p)[self.kinetic_index]

    def impact(self, name, u, u_dot, theta_dot, s):
        return self(name, np.array([u, u_dot, theta_dot]), s, self.p)


class Phases:
    """The two phases integrated by `solve_ivp(method='DOP853')`, restarted at every kink."""

    def __init__(self, case: Case, kern: Kernels, motion: Motion, rtol: float, driver: Driver):
        self.case, self.kern, self.motion, self.rtol, self.driver = case, kern, motion, rtol, driver
        self.atol_c = rtol * np.array([case.u_scale, case.ud_scale])
        self.atol_r = rtol * case.scales
        self.nfev = 0

    def contact(self, t, u, u_dot, settling):
        kern, motion, p, t_end = self.kern, self.motion, self.case.params, self.case.t_end
        y = np.array([u, u_dot])

        def rhs(t, y):
            return kern("contact_rhs", y, motion.accel(t), p)

        if settling:
            # The settling step: one step, then an f_s still above zero lifts at its end.
            solver = DOP853(rhs, t, y, motion.next_stop(t, t_end), rtol=self.rtol, atol=self.atol_c)
            solver.step()
            self.nfev += solver.nfev
            t, y = solver.t, solver.y
            s = self.driver.lift_side(y[0], y[1], motion.accel(t))
            if s is not None:
                return t, s, y[0], y[1]

        def up_right(t, y):
            return kern("uplift", y, motion.accel(t), 1.0, p)[0]

        def up_left(t, y):
            return kern("uplift", y, motion.accel(t), -1.0, p)[0]

        for ev in (up_right, up_left):
            ev.terminal, ev.direction = True, 1.0
        while t < t_end:
            t_stop = motion.next_stop(t, t_end)
            sol = solve_ivp(rhs, (t, t_stop), y, method="DOP853", rtol=self.rtol, atol=self.atol_c,
                            events=(up_right, up_left))
            self.nfev += sol.nfev
            if sol.status == 1:
                hits = [(te[0], k) for k, te in enumerate(sol.t_events) if len(te)]
                te, k = min(hits)
                ye = sol.y_events[k][0]
                return te, RIGHT if k == 0 else LEFT, ye[0], ye[1]
            t, y = sol.t[-1], sol.y[:, -1]
        return t, None, y[0], y[1]

    def rocking(self, t0, s, x0, n):
        kern, motion, p = self.kern, self.motion, self.case.params
        x0 = np.asarray(x0, dtype=float)
        over, t_end = self.case.overturn_angle, self.case.t_end

        def rhs(t, x, s=s):
            return kern("rocking_rhs", x, motion.accel(t), s, p)

        # The impact event s theta / (t - t0)^n, with its limit at t0 (equations.md 5, note 4).
        if n == 0:
            start_limit = s * x0[0]
        elif n == 1:
            start_limit = s * x0[2]
        else:
            start_limit = s * kern("rocking_rhs", x0, motion.accel(t0), s, p)[kern.theta_ddot_index] / 2.0

        def impact(t, x, s=s, t0=t0, n=n, lim=start_limit):
            dt = t - t0
            return s * x[0] / dt**n if dt > 0 else lim

        def overturn_ev(t, x, s=s):
            return s * x[0] - over

        def turning(t, x):
            return x[2]

        impact.terminal, impact.direction = True, -1.0
        overturn_ev.terminal, overturn_ev.direction = True, 1.0
        turning.terminal, turning.direction = False, 0.0
        t, x = t0, x0
        max_theta = 0.0
        while t < t_end:
            t_stop = motion.next_stop(t, t_end)
            sol = solve_ivp(rhs, (t, t_stop), x, method="DOP853", rtol=self.rtol, atol=self.atol_r,
                            events=(impact, overturn_ev, turning))
            self.nfev += sol.nfev
            max_theta = max(max_theta, float(np.max(np.abs(sol.y[0]))))
            if len(sol.y_events[2]):
                max_theta = max(max_theta, float(np.max(np.abs(sol.y_events[2][:, 0]))))
            if sol.status == 1:
                hits = [(te[0], k) for k, te in enumerate(sol.t_events[:2]) if len(te)]
                te, k = min(hits)
                return te, (IMPACT, OVERTURN)[k], sol.y_events[k][0], max_theta
            t, x = sol.t[-1], sol.y[:, -1]
        return t, None, x, max_theta


def simulate(case: Case, kern: Kernels, motion: Motion, rtol: float) -> dict:
    """One hybrid simulation: the answer, with the number of RHS evaluations."""
    kern.p = case.params
    driver = Driver(case, kern, None)
    driver.phases = phases = Phases(case, kern, motion, rtol, driver)
    answer = driver.run(motion)
    answer["nfev"] = phases.nfev
    return answer


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("cases")
    ap.add_argument("out")
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--tols", default=None, help="comma-separated tolerances (default 1e-7,1e-10)")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--only", default=None, help="comma-separated case names")
    args = ap.parse_args()
    tols = [float(x) for x in (args.tols or ("1e-7" if args.quick else "1e-7,1e-10")).split(",")]
    cases = json.load(open(args.cases))["cases"]
    only = set(args.only.split(",")) if args.only else None
    built = {}
    out = {"tols": tols, "repeats": args.repeats, "cases": [],
           "versions": {"python": sys.version.split()[0], "numpy": np.__version__,
                        "scipy": __import__("scipy").__version__, "casadi": __import__("casadi").__version__}}
    for case in cases:
        if only and case["name"] not in only:
            continue
        if case["variant"] not in built:
            t0 = time.perf_counter()
            built[case["variant"]] = Kernels(case["variant"])
            print(f"scipy peer: built the CasADi functions of {case['variant']} in "
                  f"{time.perf_counter() - t0:.1f} s", file=sys.stderr)
        kern = built[case["variant"]]
        motions = case["motions"]
        stride = 1
        if case.get("amplitudes"):
            # the slice: every 4th cell (every 3rd in --quick) keeps the Python run short
            stride = 3 if args.quick else 4
        idx = list(range(0, len(motions), stride))
        entry = {"name": case["name"], "cells": idx, "points": []}
        for tol in tols:
            times, answers, failed = [], None, None
            for r in range(args.repeats):
                t0 = time.perf_counter()
                try:
                    ans = [simulate(Case(case), kern, Motion(motions[i]), tol) for i in idx]
                except Exception as e:  # a researcher's script would just crash; record it
                    failed = f"{type(e).__name__}: {e}"
                    break
                times.append(time.perf_counter() - t0)
                answers = ans
                if r == 0 and times[0] > 20.0:
                    break  # slow enough: one run is a good measurement
            if failed:
                entry["points"].append({"tol": tol, "failed": failed})
                print(f"scipy peer: {case['name']} tol {tol:g}: FAILED {failed}", file=sys.stderr)
                continue
            med = float(np.median(times)) / len(idx)
            entry["points"].append({"tol": tol, "seconds": med, "repeats": len(times),
                                    "nfev": float(np.mean([a["nfev"] for a in answers])),
                                    "answers": answers})
            print(f"scipy peer: {case['name']} tol {tol:g}: {med:.3f} s per simulation "
                  f"({len(times)} repeats, {len(idx)} cells), max θ/α = {answers[0]['max_theta_over_alpha']:.6f}",
                  file=sys.stderr)
        out["cases"].append(entry)
    with open(args.out, "w") as f:
        json.dump(out, f)


if __name__ == "__main__":
    main()
