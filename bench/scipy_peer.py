"""SciPy peer of the rocking solver: the same model, written as a researcher would with solve_ivp.

The physics is not re-typed: the right-hand sides, uplift functions and impact maps are the CasADi
functions built by the derivation package (``rocking_derive``), called with numpy arrays. The
hybrid logic (full contact, rocking about either corner, impacts with VVEL / ADJex / Housner,
overturning, the rest rule) is written here in Python around ``solve_ivp(method='DOP853',
events=...)`` with terminal, directional events, restarting at every event and at every kink of
the excitation (the ends of a pulse, the samples of a record), like the Rust driver.

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
import math
import os
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "derive"))
from rocking_derive import ir, kernels, models  # noqa: E402


class Kernels:
    """The CasADi functions of one variant, called with numpy arrays."""

    def __init__(self, variant_name: str):
        variant = next(v for v in models.VARIANTS if v.name == variant_name)
        self.f = {k.name: ir.casadi_function(k) for k in kernels.kernels(variant)}

    def __call__(self, name, *args):
        return np.asarray(self.f[name](*args)).ravel()


class Motion:
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
            self.kinks = list(self.grid)
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
        for k in self.kinks:
            if k > t * (1 + 1e-15) + 1e-300:
                return min(k, t_end)
        return t_end


def simulate(case: dict, kern: Kernels, motion: Motion, rtol: float) -> dict:
    """One hybrid simulation; returns the answer and the number of RHS evaluations."""
    p = np.asarray(case["params"], dtype=float)
    alpha, pf = case["alpha"], case["p"]
    us, uds = case["u_scale"], case["ud_scale"]
    atol_c = rtol * np.array([us, uds])
    atol_r = rtol * np.array([alpha, us, alpha * pf, uds])
    t_end, over = case["t_end"], case["overturn_angle"]
    rest = case["rest_rate"] * alpha * pf
    significant = 0.01 * alpha * pf
    impact_model = case["impact"]
    th0, u0, td0, ud0 = case["initial"]

    nfev = 0
    max_theta = abs(th0)
    impacts, all_impacts = [], []
    overturn = None

    if th0 != 0.0 or td0 != 0.0:
        s = 1.0 if th0 > 0 or (th0 == 0 and td0 > 0) else -1.0
        phase = ("rock", 0.0, s, np.array([th0, u0, td0, ud0]), 0 if th0 != 0 else 1)
    else:
        phase = ("contact", 0.0, np.array([u0, ud0]))

    final = None
    while True:
        if phase[0] == "contact":
            _, t, y = phase
            f = [kern("uplift", y, motion.accel(t), s_, p)[0] for s_ in (1.0, -1.0)]
            if f[0] > 0 or f[1] > 0:
                s = 1.0 if f[0] > 0 else -1.0
                phase = ("rock", t, s, np.array([0.0, y[0], 0.0, y[1]]), 2)
                continue

            def rhs(t, y):
                return kern("contact_rhs", y, motion.accel(t), p)

            def up_right(t, y):
                return kern("uplift", y, motion.accel(t), 1.0, p)[0]

            def up_left(t, y):
                return kern("uplift", y, motion.accel(t), -1.0, p)[0]

            for ev in (up_right, up_left):
                ev.terminal, ev.direction = True, 1.0
            uplifted = None
            while t < t_end:
                t_stop = motion.next_stop(t, t_end)
                sol = solve_ivp(rhs, (t, t_stop), y, method="DOP853", rtol=rtol, atol=atol_c,
                                events=(up_right, up_left))
                nfev += sol.nfev
                if sol.status == 1:
                    hits = [(te[0], k) for k, te in enumerate(sol.t_events) if len(te)]
                    te, k = min(hits)
                    uplifted = (te, 1.0 if k == 0 else -1.0, sol.y_events[k][0])
                    break
                t, y = sol.t[-1], sol.y[:, -1]
            if uplifted is None:
                final = (t, np.array([0.0, y[0], 0.0, y[1]]))
                break
            te, s, ye = uplifted
            phase = ("rock", te, s, np.array([0.0, ye[0], 0.0, ye[1]]), 2)
            continue

        _, t0, s, x0, n = phase

        def rhs(t, x, s=s):
            return kern("rocking_rhs", x, motion.accel(t), s, p)

        if n == 0:
            start_limit = s * x0[0]
        elif n == 1:
            start_limit = s * x0[2]
        else:
            start_limit = s * kern("rocking_rhs", x0, motion.accel(t0), s, p)[2] / 2.0

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
        hit = None
        while t < t_end:
            t_stop = motion.next_stop(t, t_end)
            sol = solve_ivp(rhs, (t, t_stop), x, method="DOP853", rtol=rtol, atol=atol_r,
                            events=(impact, overturn_ev, turning))
            nfev += sol.nfev
            max_theta = max(max_theta, float(np.max(np.abs(sol.y[0]))))
            if len(sol.y_events[2]):
                max_theta = max(max_theta, float(np.max(np.abs(sol.y_events[2][:, 0]))))
            if sol.status == 1:
                hits = [(te[0], k) for k, te in enumerate(sol.t_events[:2]) if len(te)]
                te, k = min(hits)
                hit = (te, k, sol.y_events[k][0])
                break
            t, x = sol.t[-1], sol.y[:, -1]
        if hit is None:
            final = (t, x)
            break
        te, k, xe = hit
        if k == 1:
            overturn = te
            max_theta = max(max_theta, abs(xe[0]))
            final = (te, xe)
            break
        # impact at theta = 0: the corner -s hits the ground
        u, ud, td = xe[1], xe[3], xe[2]
        all_impacts.append(te * pf)
        if abs(td) >= significant:
            impacts.append(te * pf)
        xi = np.array([u, ud, td])
        s2 = -s
        after = None  # ("contact", u_dot) or ("rock", theta_dot, u_dot)
        if impact_model == "vvel":
            v = kern("impact_vvel", xi, s, p)
            after = ("rock", v[1], v[2]) if v[0] != 0 else ("contact", v[2])
        elif impact_model == "adjex":
            a = kern("impact_adjex", xi, s, p)
            e_i = a[5]
            contact = (a[1], ("contact", a[0]))
            rocking = (a[4], ("rock", a[2], a[3]))
            momentum = (a[7], ("contact", a[6]))
            best = rocking if (s2 * a[2] > 0 and rocking[0] < contact[0]) else contact
            if best[0] <= e_i:
                after = best[1]
            elif momentum[0] <= e_i:
                after = momentum[1]
            else:
                after = (momentum if momentum[0] < best[0] else best)[1]
        elif impact_model == "housner":
            h = kern("impact_housner", xi, s, p)
            after = ("rock", h[0], h[1]) if s2 * h[0] > 0 else ("contact", ud)
        else:
            raise ValueError(impact_model)
        if after[0] == "rock" and abs(after[1]) < rest:
            after = ("contact", after[2])
        if after[0] == "contact":
            phase = ("contact", te, np.array([u, after[1]]))
        else:
            phase = ("rock", te, s2, np.array([0.0, u, after[1], after[2]]), 1)

    tf, xf = final
    return {
        "max_theta_over_alpha": max_theta / alpha,
        "impacts": impacts,
        "all_impacts": all_impacts,
        "impact_count": len(all_impacts),
        "overturned": overturn is not None,
        "overturn_tau": None if overturn is None else overturn * pf,
        "final_state": [xf[0] / alpha, xf[1] / us, xf[2] / (alpha * pf), xf[3] / uds],
        "final_tau": tf * pf,
        "nfev": nfev,
    }


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
                    ans = [simulate(case, kern, Motion(motions[i]), tol) for i in idx]
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
