"""heyoka peer of the rocking solver: the same model, integrated by heyoka.py's Taylor integrator.

The physics is not re-typed: each kernel's CasADi instruction tape (``rocking_derive.ir.tape``) is
replayed into heyoka ``expression`` objects (rocking and contact right-hand sides, uplift
functions), so heyoka's ``taylor_adaptive`` (compiled with LLVM at run time) integrates exactly the
derivation's equations; the impact maps are evaluated through the CasADi functions, as in the SciPy
peer. The hybrid logic (full contact, rocking about either corner, impacts with VVEL / ADJex /
Housner, overturning, the rest rule) is the SciPy peer's, written here in Python around
``propagate_until`` with heyoka's own terminal, directional events (``t_event``: uplift, impact,
overturning) and a non-terminal event at the turning points (max theta), restarting at every event
and at every kink of the excitation (the ends of a pulse, the samples of a record; between samples
the ground acceleration is linear in time, with its coefficients as runtime parameters).

The state is integrated in the study's scales, X = [theta/alpha, u/u_s, theta'/(alpha p),
u'/ud_s] (the scales are runtime parameters), so heyoka's single tolerance plays the part of the
Rust run's rtol with its scaled atol.

    PYTHONPATH=derive python bench/heyoka_peer.py target/bench/cases.json target/bench/heyoka.json \
        [--quick] [--tols 1e-7,1e-9] [--repeats 5] [--only fig3-vvel]

Timings: time.perf_counter, median of the repeats, per simulation; the one-time LLVM compilation of
the integrators (one per variant, excitation kind and tolerance) is excluded and reported apart.
"""

from __future__ import annotations

import argparse
import atexit
import json
import math
import os
import shutil
import sys
import tempfile
import time

# heyoka 7.13 keeps the machine code it compiles in a persistent cache ($XDG_CACHE_HOME/heyoka,
# else ~/.cache/heyoka), so a second run would report almost no compile time. The peer compiles
# into a fresh, temporary cache (set before heyoka is imported), so the compile time it reports is
# the one-time cost on a clean machine; HEYOKA_PEER_KEEP_CACHE=1 uses the user's cache instead.
if os.environ.get("HEYOKA_PEER_KEEP_CACHE") != "1":
    _CACHE = tempfile.mkdtemp(prefix="heyoka-peer-cache-")
    os.environ["XDG_CACHE_HOME"] = _CACHE
    atexit.register(shutil.rmtree, _CACHE, True)

import heyoka as hy  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "derive"))
from rocking_derive import ir, kernels, models  # noqa: E402

UNARY = {
    "neg": lambda a: -a,
    "twice": lambda a: 2.0 * a,
    "sq": lambda a: hy.square(a) if hasattr(hy, "square") else a * a,
    "sqrt": hy.sqrt,
    "sin": hy.sin,
    "cos": hy.cos,
    "tan": hy.tan,
    "exp": hy.exp,
    "log": hy.log,
    "inv": lambda a: 1.0 / a,
    "assign": lambda a: a,
}
BINARY = {
    "add": lambda a, b: a + b,
    "sub": lambda a, b: a - b,
    "mul": lambda a, b: a * b,
    "div": lambda a, b: a / b,
    "pow": lambda a, b: a**b,
    "constpow": lambda a, b: a**b,
}


def replay(f, inputs: list[list]) -> list:
    """The outputs of a CasADi function as heyoka expressions: its instruction tape replayed on
    ``inputs`` (one list of expressions per input, element by element)."""
    work, out = {}, {}
    for row in ir.tape(f):
        op, dest, args = row[0], row[1], row[2:]
        if op == "input":
            work[dest] = inputs[args[0]][args[1]]
        elif op == "output":
            out[dest] = work[args[0]]
        elif op == "const":
            work[dest] = hy.expression(float(args[0]))
        elif op in UNARY:
            work[dest] = UNARY[op](work[args[0]])
        elif op in BINARY:
            work[dest] = BINARY[op](work[args[0]], work[args[1]])
        else:
            raise ValueError(f"tape op {op!r} has no heyoka translation")
    return [out[k] for k in range(len(out))]


# Tapes longer than this are compiled in compact mode (heyoka loops over the operations instead
# of unrolling them: much faster to compile, slower to run).
COMPACT_OPS = int(os.environ.get("HEYOKA_PEER_COMPACT_OPS", "1000"))


def tape_ops(f) -> int:
    return sum(1 for r in ir.tape(f) if r[0] not in ("input", "output", "const"))


class Model:
    """The CasADi functions of one variant, and heyoka integrators built from their tapes."""

    def __init__(self, variant_name: str):
        variant = next(v for v in models.VARIANTS if v.name == variant_name)
        self.f = {k.name: ir.casadi_function(k) for k in kernels.kernels(variant)}
        self.np = len(variant.model.params)
        self.built = {}
        self.compile_s = 0.0

    def __call__(self, name, *args):
        return np.asarray(self.f[name](*args)).ravel()

    def integrators(self, kind: str, tol: float, over: float):
        """(rocking, contact) integrators for an excitation kind ('sine' or 'linear'), tol and the
        overturning angle."""
        key = (kind, tol, over)
        if key in self.built:
            return self.built[key]
        t0 = time.perf_counter()
        n = self.np
        par = [hy.par[i] for i in range(n)]
        s = hy.par[n]
        d = [hy.par[n + 1 + i] for i in range(4)]
        c = [hy.par[n + 5 + i] for i in range(3)]
        ug = c[0] * hy.sin(c[1] * hy.time + c[2]) if kind == "sine" else c[0] + c[1] * hy.time
        npar = n + 5 + (3 if kind == "sine" else 2)
        # rocking about corner s
        X = hy.make_vars("th", "u", "thd", "ud")
        x = [d[i] * X[i] for i in range(4)]
        rhs = replay(self.f["rocking_rhs"], [x, [ug], [s], par])
        sys_r = [(X[i], rhs[i] / d[i]) for i in range(4)]
        compact = tape_ops(self.f["rocking_rhs"]) > COMPACT_OPS
        self.turning = []

        def on_turn(ta, t, d_sgn):
            ta.update_d_output(t)
            self.turning.append(abs(ta.d_output[0]))

        ev_r = [
            # impact: s theta falls through 0. A phase starts at theta = 0 exactly, and heyoka 7.13
            # misses the next root when the step's event polynomial has an exact root at the start
            # (a post-impact bounce shorter than the first step is never detected); the offset
            # 1e-30 (in theta/alpha) removes that root and moves the impact by 1e-30/|theta'|.
            hy.t_event(s * X[0] + 1e-30, direction=hy.event_direction.negative),
            hy.t_event(s * d[0] * X[0] - over, direction=hy.event_direction.positive),
        ]
        nt_r = [hy.nt_event(X[2], on_turn)]
        ta_r = hy.taylor_adaptive(sys_r, [0.0] * 4, tol=tol, compact_mode=compact,
                                  pars=[0.0] * npar, t_events=ev_r, nt_events=nt_r)
        # full contact
        Y = hy.make_vars("u", "ud")
        y = [d[1] * Y[0], d[3] * Y[1]]
        rhs_c = replay(self.f["contact_rhs"], [y, [ug], par])
        sys_c = [(Y[0], rhs_c[0] / d[1]), (Y[1], rhs_c[1] / d[3])]
        ev_c = [hy.t_event(replay(self.f["uplift"], [y, [ug], [hy.expression(sg)], par])[0],
                           direction=hy.event_direction.positive) for sg in (1.0, -1.0)]
        compact_c = tape_ops(self.f["contact_rhs"]) + tape_ops(self.f["uplift"]) > COMPACT_OPS
        # the uplift functions at the start of a contact phase, compiled by heyoka from the same tape
        yu, yd, g = hy.make_vars("yu", "yd", "g")
        pc = [hy.par[i] for i in range(n)]
        up = [replay(self.f["uplift"], [[yu, yd], [g], [hy.expression(sg)], pc])[0] for sg in (1.0, -1.0)]
        self.uplift_cf = hy.cfunc(up, [yu, yd, g])
        ta_c = hy.taylor_adaptive(sys_c, [0.0] * 2, tol=tol, compact_mode=compact_c,
                                  pars=[0.0] * npar, t_events=ev_c)
        dt = time.perf_counter() - t0
        self.compile_s += dt
        self.built[key] = (ta_r, ta_c, dt, compact, compact_c)
        return self.built[key]


class Motion:
    """Ground acceleration as segments on which it is c0 sin(c1 t + c2) ('sine') or c0 + c1 t."""

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
        self.integrator_kind = "sine" if self.kind == "sine" else "linear"

    def accel(self, t: float) -> float:
        if self.kind == "sine":
            return self.a * math.sin(self.w * (t - self.t0)) if self.t0 <= t <= self.t1 else 0.0
        if self.kind == "record":
            return float(np.interp(t, self.grid, self.samples, left=0.0, right=0.0)) if t <= self.t1 else 0.0
        return 0.0

    def coeffs(self, t: float, t_stop: float):
        """The segment's coefficients on [t, t_stop] (t_stop the next kink or the end)."""
        tm = 0.5 * (t + t_stop)
        if self.kind == "sine":
            if self.t0 <= tm <= self.t1:
                return (self.a, self.w, -self.w * self.t0)
            return (0.0, 0.0, 0.0)
        if self.kind == "record" and tm <= self.t1:
            i = min(int(tm / self.dt), len(self.samples) - 2)
            slope = (self.samples[i + 1] - self.samples[i]) / self.dt
            return (self.samples[i] - slope * self.grid[i], slope)
        return (0.0, 0.0)

    def next_stop(self, t: float, t_end: float) -> float:
        for k in self.kinks:
            if k > t * (1 + 1e-15) + 1e-300:
                return min(k, t_end)
        return t_end


def set_pars(ta, p, s, scales, coeffs):
    pars = ta.pars
    n = len(p)
    pars[:n] = p
    pars[n] = s
    pars[n + 1:n + 5] = scales
    pars[n + 5:n + 5 + len(coeffs)] = coeffs


def outcome_event(oc) -> int | None:
    """Index of the terminal event that stopped propagate_until, or None (time limit)."""
    k = int(oc)  # terminal event i stops with taylor_outcome(-i - 1); the others are < -2**32
    return -k - 1 if -(2**31) < k < 0 else None


def simulate(case: dict, model: Model, motion: Motion, tol: float) -> dict:
    p = np.asarray(case["params"], dtype=float)
    alpha, pf = case["alpha"], case["p"]
    us, uds = case["u_scale"], case["ud_scale"]
    D = np.array([alpha, us, alpha * pf, uds])
    t_end = case["t_end"]
    over = case["overturn_angle"]
    rest = case["rest_rate"] * alpha * pf
    significant = 0.01 * alpha * pf
    impact_model = case["impact"]
    th0, u0, td0, ud0 = case["initial"]
    ta_r, ta_c = model.integrators(motion.integrator_kind, tol, over)[:2]
    eps_t = 8 * np.finfo(float).eps

    steps = 0
    max_theta = abs(th0)
    impacts, all_impacts = [], []
    overturn = None

    if th0 != 0.0 or td0 != 0.0:
        s = 1.0 if th0 > 0 or (th0 == 0 and td0 > 0) else -1.0
        phase = ("rock", 0.0, s, np.array([th0, u0, td0, ud0]))
    else:
        phase = ("contact", 0.0, np.array([u0, ud0]))

    final = None
    while True:
        if phase[0] == "contact":
            _, t, y = phase
            f = model.uplift_cf([y[0], y[1], motion.accel(t)], pars=p)
            if f[0] > 0 or f[1] > 0:
                s = 1.0 if f[0] > 0 else -1.0
                phase = ("rock", t, s, np.array([0.0, y[0], 0.0, y[1]]))
                continue
            ta_c.time = t
            ta_c.state[:] = [y[0] / us, y[1] / uds]
            ta_c.reset_cooldowns()
            uplifted = None
            while t < t_end:
                t_stop = motion.next_stop(t, t_end)
                set_pars(ta_c, p, 0.0, D, motion.coeffs(t, t_stop))
                oc, _, _, n, *_ = ta_c.propagate_until(t_stop)
                steps += n
                k = outcome_event(oc)
                t = ta_c.time
                if k is not None:
                    uplifted = (t, 1.0 if k == 0 else -1.0,
                                np.array([ta_c.state[0] * us, ta_c.state[1] * uds]))
                    break
            if uplifted is None:
                final = (t, np.array([0.0, ta_c.state[0] * us, 0.0, ta_c.state[1] * uds]))
                break
            te, s, ye = uplifted
            phase = ("rock", te, s, np.array([0.0, ye[0], 0.0, ye[1]]))
            continue

        _, t0, s, x0 = phase
        ta_r.time = t0
        ta_r.state[:] = x0 / D
        ta_r.reset_cooldowns()
        model.turning = []
        t = t0
        hit = None
        while t < t_end:
            t_stop = motion.next_stop(t, t_end)
            set_pars(ta_r, p, s, D, motion.coeffs(t, t_stop))
            oc, _, _, n, *_ = ta_r.propagate_until(t_stop)
            steps += n
            k = outcome_event(oc)
            t = ta_r.time
            if k == 0 and t - t0 <= eps_t * max(1.0, abs(t0)):
                continue  # the phase's own start at theta = 0 (uplift: a double root), not an impact
            max_theta = max(max_theta, abs(ta_r.state[0]) * alpha)
            if k is not None:
                hit = (t, k, ta_r.state * D)
                break
        if model.turning:
            max_theta = max(max_theta, max(model.turning) * alpha)
        if hit is None:
            final = (t, ta_r.state * D)
            break
        te, k, xe = hit
        if k == 1:
            overturn = te
            max_theta = max(max_theta, abs(xe[0]))
            final = (te, xe)
            break
        # impact at theta = 0: the corner -s hits the ground (maps through CasADi, as the SciPy peer)
        u, ud, td = xe[1], xe[3], xe[2]
        all_impacts.append(te * pf)
        if abs(td) >= significant:
            impacts.append(te * pf)
        xi = np.array([u, ud, td])
        s2 = -s
        if impact_model == "vvel":
            v = model("impact_vvel", xi, s, p)
            after = ("rock", v[1], v[2]) if v[0] != 0 else ("contact", v[2])
        elif impact_model == "adjex":
            a = model("impact_adjex", xi, s, p)
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
            h = model("impact_housner", xi, s, p)
            after = ("rock", h[0], h[1]) if s2 * h[0] > 0 else ("contact", ud)
        else:
            raise ValueError(impact_model)
        if after[0] == "rock" and abs(after[1]) < rest:
            after = ("contact", after[2])
        if after[0] == "contact":
            phase = ("contact", te, np.array([u, after[1]]))
        else:
            phase = ("rock", te, s2, np.array([0.0, u, after[1], after[2]]))

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
        "steps": steps,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("cases")
    ap.add_argument("out")
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--tols", default=None, help="comma-separated tolerances (default 1e-5,1e-7,1e-9,1e-10,1e-12; "
                    "--quick: 1e-5,1e-7,1e-9,1e-11)")
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--only", default=None, help="comma-separated case names")
    args = ap.parse_args()
    tols = [float(x) for x in (args.tols or ("1e-5,1e-7,1e-9,1e-11" if args.quick else "1e-5,1e-7,1e-9,1e-10,1e-12")).split(",")]
    cases = json.load(open(args.cases))["cases"]
    only = set(args.only.split(",")) if args.only else None
    built = {}
    out = {"tols": tols, "repeats": args.repeats, "cases": [],
           "versions": {"python": sys.version.split()[0], "numpy": np.__version__,
                        "heyoka": hy.__version__, "casadi": __import__("casadi").__version__},
           "compile_cache": "user" if os.environ.get("HEYOKA_PEER_KEEP_CACHE") == "1" else "fresh"}
    for case in cases:
        if only and case["name"] not in only:
            continue
        if case["variant"] not in built:
            built[case["variant"]] = Model(case["variant"])
        model = built[case["variant"]]
        motions = case["motions"]
        stride = 1
        if case.get("amplitudes"):
            stride = 3 if args.quick else 4  # the SciPy peer's cells of the slice
        idx = list(range(0, len(motions), stride))
        entry = {"name": case["name"], "cells": idx, "points": []}
        for tol in tols:
            failed = None
            try:
                # compile outside the timed runs (one integrator pair per excitation kind)
                compile_s, compact = 0.0, None
                for kind in sorted({Motion(motions[i]).integrator_kind for i in idx}):
                    _, _, dt, cr, cc = model.integrators(kind, tol, case["overturn_angle"])
                    compile_s += dt
                    compact = (cr, cc)
                times, answers = [], None
                t_all = time.perf_counter()
                while len(times) < args.repeats or (time.perf_counter() - t_all < 0.5 and len(times) < 50):
                    t0 = time.perf_counter()
                    ans = [simulate(case, model, Motion(motions[i]), tol) for i in idx]
                    times.append(time.perf_counter() - t0)
                    answers = ans
                    if times[0] > 20.0:
                        break
            except Exception as e:  # recorded, so the report shows it
                failed = f"{type(e).__name__}: {e}"
            if failed:
                entry["points"].append({"tol": tol, "failed": failed})
                print(f"heyoka peer: {case['name']} tol {tol:g}: FAILED {failed}", file=sys.stderr)
                continue
            med = float(np.median(times)) / len(idx)
            entry["points"].append({"tol": tol, "seconds": med, "repeats": len(times),
                                    "compile_s": compile_s, "compact_mode": compact,
                                    "steps": float(np.mean([a["steps"] for a in answers])),
                                    "answers": answers})
            print(f"heyoka peer: {case['name']} tol {tol:g}: {med * 1e3:.3f} ms per simulation "
                  f"({len(times)} repeats, {len(idx)} cells; compile {compile_s:.1f} s, compact {compact}), "
                  f"max θ/α = {answers[0]['max_theta_over_alpha']:.9f}, impacts {answers[0]['impact_count']}, "
                  f"overturned {answers[0]['overturned']}", file=sys.stderr)
        out["cases"].append(entry)
    out["compile_s"] = sum(m.compile_s for m in built.values())
    with open(args.out, "w") as f:
        json.dump(out, f)


if __name__ == "__main__":
    main()
