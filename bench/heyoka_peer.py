"""heyoka peer of the rocking solver: the same model, integrated by heyoka.py's Taylor integrator.

The physics is not re-typed: each kernel's CasADi instruction tape (``rocking_derive.ir.tape``) is
replayed, once per variant, into heyoka ``expression`` objects (the rocking and contact right-hand
sides and the uplift functions, which heyoka's ``taylor_adaptive`` compiles with LLVM) and into
straight-line Python functions of floats (uplift functions, theta'' at lift-off, kinetic energy,
impact maps: what the driver evaluates once per event). No CasADi function is called while a
simulation runs. The hybrid logic (phases, impact policy, rest rule) is the Python peers' shared
driver, ``bench/hybrid.py``; this file is its integrator: heyoka's ``propagate_until`` over each
span between kinks of the excitation (the ends of a pulse, the samples of a record), stopped by
heyoka's own terminal, directional events (``t_event``: uplift, impact, overturning), with the
turning points (max theta) a non-terminal event. Between kinks the ground acceleration is
``c0 sin(c1 t + c2)`` or ``c0 + c1 t``, its coefficients runtime parameters. The integrators (one
rocking and one contact integrator per variant, excitation kind, tolerance and overturning angle)
are built once and reused by every run: a phase sets the time, the state and the parameters.

The state is integrated in the study's scales, X = [theta/alpha, u/u_s, theta'/(alpha p),
u'/ud_s] (the scales are runtime parameters), so heyoka's single tolerance plays the part of the
Rust run's rtol with its scaled atol.

    PYTHONPATH=derive python bench/heyoka_peer.py target/bench/cases.json target/bench/heyoka.json \
        [--quick] [--tols 1e-7,1e-9] [--repeats 5] [--only fig3-vvel]

Timings: the process's CPU time (time.process_time, as the Rust study's), median of the repeats, per
simulation: on a machine shared with other builds, wall time measures the others too. The one-time
LLVM compilation of the integrators is excluded and reported apart (wall time).
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
from hybrid import IMPACT, LEFT, OVERTURN, RIGHT, Case, Driver, Motion  # noqa: E402
from rocking_derive import ir, kernels, models  # noqa: E402


def _zero():
    return hy.expression(0.0)


def _sign(a):
    return hy.select(hy.gt(a, _zero()), hy.expression(1.0),
                     hy.select(hy.lt(a, _zero()), hy.expression(-1.0), _zero()))


# The tape's operations (crates/rocking-codegen's schema) as heyoka expressions ...
UNARY = {
    "neg": lambda a: -a,
    "twice": lambda a: 2.0 * a,
    "sq": lambda a: a * a,
    "sqrt": hy.sqrt,
    "sin": hy.sin,
    "cos": hy.cos,
    "tan": hy.tan,
    "exp": hy.exp,
    "log": hy.log,
    "inv": lambda a: 1.0 / a,
    "assign": lambda a: a,
    "fabs": lambda a: hy.select(hy.lt(a, _zero()), -a, a),
    "sign": _sign,
}
BINARY = {
    "add": lambda a, b: a + b,
    "sub": lambda a, b: a - b,
    "mul": lambda a, b: a * b,
    "div": lambda a, b: a / b,
    "pow": lambda a, b: a**b,
    "constpow": lambda a, b: a**b,
    "atan2": hy.atan2,
}
# ... and as Python source on floats.
PYTHON = {
    "neg": "-{0}", "twice": "2.0 * {0}", "sq": "{0} * {0}", "sqrt": "sqrt({0})", "sin": "sin({0})",
    "cos": "cos({0})", "tan": "tan({0})", "exp": "exp({0})", "log": "log({0})", "inv": "1.0 / {0}",
    "assign": "{0}", "fabs": "abs({0})", "sign": "sign({0})", "add": "{0} + {1}", "sub": "{0} - {1}",
    "mul": "{0} * {1}", "div": "{0} / {1}", "pow": "{0} ** {1}", "constpow": "{0} ** {1}",
    "atan2": "atan2({0}, {1})",
}


def _py_sign(x):
    return 1.0 if x > 0 else (-1.0 if x < 0 else 0.0 * x)  # CasADi's sign: 0 at 0, NaN at NaN


PY_NAMESPACE = {"sqrt": math.sqrt, "sin": math.sin, "cos": math.cos, "tan": math.tan, "exp": math.exp,
                "log": math.log, "atan2": math.atan2, "sign": _py_sign}


def walk(f, load, const, apply) -> list:
    """The outputs of a CasADi function's instruction tape evaluated in another algebra: `load(i, j)`
    gives element j of input i, `const(v)` a constant, `apply(op, args)` an operation's result."""
    work, out = {}, {}
    for row in ir.tape(f):
        op, dest, args = row[0], row[1], row[2:]
        if op == "input":
            work[dest] = load(args[0], args[1])
        elif op == "output":
            out[dest] = work[args[0]]
        elif op == "const":
            work[dest] = const(float(args[0]))
        else:
            work[dest] = apply(op, [work[a] for a in args])
    return [out[k] for k in range(len(out))]


def replay(f, inputs: list[list]) -> list:
    """The outputs of a CasADi function as heyoka expressions of ``inputs`` (one list of
    expressions per input, element by element)."""

    def apply(op, args):
        if op in UNARY:
            return UNARY[op](*args)
        if op in BINARY:
            return BINARY[op](*args)
        raise ValueError(f"tape op {op!r} has no heyoka translation")

    return walk(f, lambda i, j: inputs[i][j], hy.expression, apply)


def python_function(f):
    """A CasADi function as a straight-line Python function of its inputs (each a sequence of
    floats) returning a tuple: its tape, one statement per instruction. For the few evaluations per
    event, plain Python floats beat both a CasADi call (~50-150 us) and a heyoka ``cfunc`` call
    (~6 us: numpy argument checks), at about 1 us for 60 operations."""
    body = []

    def bind(expr):
        body.append(f"w{len(body)} = {expr}")
        return f"w{len(body) - 1}"

    def apply(op, args):
        if op not in PYTHON:
            raise ValueError(f"tape op {op!r} has no Python translation")
        return bind(PYTHON[op].format(*args))

    out = walk(f, lambda i, j: bind(f"i{i}[{j}]"), lambda v: bind(repr(v)), apply)
    names = ", ".join(f"i{k}" for k in range(f.n_in()))
    src = (f"def {f.name()}({names}):\n    " + "\n    ".join(body or ["pass"])
           + "\n    return (" + "".join(o + ", " for o in out) + ")\n")
    namespace = dict(PY_NAMESPACE, inf=math.inf, nan=math.nan)
    exec(compile(src, f"<tape {f.name()}>", "exec"), namespace)
    return namespace[f.name()]


# Tapes longer than this are compiled in compact mode (heyoka loops over the operations instead
# of unrolling them: much faster to compile, slower to run).
COMPACT_OPS = int(os.environ.get("HEYOKA_PEER_COMPACT_OPS", "1000"))


def tape_ops(f) -> int:
    return sum(1 for r in ir.tape(f) if r[0] not in ("input", "output", "const"))


class Physics:
    """The pointwise physics of one variant (see `hybrid`), as Python functions of the tapes."""

    def __init__(self, f: dict, names: dict):
        self.py = {name: python_function(f[name]) for name in
                   ("uplift", "rocking_rhs", "energy", "impact_vvel", "impact_adjex", "impact_housner")}
        self.names = names
        self.kinetic_index = names["energy"].index("kinetic")
        self.theta_ddot_index = names["rocking_rhs"].index("theta_ddot")
        self.p = None  # the parameter vector of the case being run (a list of floats)

    def fields(self, name):
        return self.names[name]

    def uplift(self, u, u_dot, ug):
        up = self.py["uplift"]
        return (up((u, u_dot), (ug,), (RIGHT,), self.p)[0], up((u, u_dot), (ug,), (LEFT,), self.p)[0])

    def theta_ddot(self, s, u, u_dot, ug):
        return self.py["rocking_rhs"]((0.0, u, 0.0, u_dot), (ug,), (s,), self.p)[self.theta_ddot_index]

    def kinetic(self, x, s):
        return self.py["energy"](x, (s,), self.p)[self.kinetic_index]

    def impact(self, name, u, u_dot, theta_dot, s):
        return self.py[name]((u, u_dot, theta_dot), (s,), self.p)


class Model:
    """One variant: its CasADi functions (used only to build), the `Physics` and the heyoka
    integrators built from the tapes."""

    def __init__(self, variant_name: str):
        variant = next(v for v in models.VARIANTS if v.name == variant_name)
        ks = kernels.kernels(variant)
        self.f = {k.name: ir.casadi_function(k) for k in ks}
        self.physics = Physics(self.f, {k.name: k.output.elements for k in ks})
        self.np = len(variant.model.params)
        self.built = {}
        self.compile_s = 0.0

    def integrators(self, kind: str, tol: float, over: float):
        """(rocking, contact, turning-point box, compile seconds, compact modes) for an excitation
        kind ('sine' or 'linear'), tol and the overturning angle. Parameters: the kernels' p, then
        s, the four scales, the excitation's coefficients."""
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
        turn = [0.0]  # the largest |theta/alpha| at a turning point of the phase
        # LLVM's fast-math flags (reassociation, reciprocals, contraction): 27-30 % less time per
        # simulation on the full-mass cases, 3 % on the point-mass one, errors unchanged
        # (bench/NOTES.md).
        opts = {"fast_math": True}

        def on_turn(ta, t, d_sgn):
            turn[0] = max(turn[0], abs(ta.update_d_output(t)[0]))

        ev_r = [
            # impact: s theta falls through 0. A phase starts at theta = 0 exactly, and heyoka 7.13
            # misses the next root when the step's event polynomial has an exact root at the start
            # (a post-impact bounce shorter than the first step is never detected); the offset
            # 1e-30 (in theta/alpha) removes that root and moves the impact by 1e-30/|theta'|.
            hy.t_event(s * X[0] + 1e-30, direction=hy.event_direction.negative),
            hy.t_event(s * d[0] * X[0] - over, direction=hy.event_direction.positive),
        ]
        # Only the maxima of s theta (theta' falling through zero about the right corner, rising
        # about the left) can be the phase's max |theta|: half the callbacks of a turning-point event.
        nt_r = [hy.nt_event(s * X[2], on_turn, direction=hy.event_direction.negative)]
        ta_r = hy.taylor_adaptive(sys_r, [0.0] * 4, tol=tol, compact_mode=compact,
                                  pars=[0.0] * npar, t_events=ev_r, nt_events=nt_r, **opts)
        if ta_r.order != heyoka_order(tol):
            raise RuntimeError(f"heyoka runs order {ta_r.order} at tol {tol:g}, "
                               f"not heyoka_order's {heyoka_order(tol)}: the tolerance grid needs it")
        # full contact
        Y = hy.make_vars("u", "ud")
        y = [d[1] * Y[0], d[3] * Y[1]]
        rhs_c = replay(self.f["contact_rhs"], [y, [ug], par])
        sys_c = [(Y[0], rhs_c[0] / d[1]), (Y[1], rhs_c[1] / d[3])]
        ev_c = [hy.t_event(replay(self.f["uplift"], [y, [ug], [hy.expression(sg)], par])[0],
                           direction=hy.event_direction.positive) for sg in (RIGHT, LEFT)]
        compact_c = tape_ops(self.f["contact_rhs"]) + tape_ops(self.f["uplift"]) > COMPACT_OPS
        ta_c = hy.taylor_adaptive(sys_c, [0.0] * 2, tol=tol, compact_mode=compact_c,
                                  pars=[0.0] * npar, t_events=ev_c, **opts)
        dt = time.perf_counter() - t0
        self.compile_s += dt
        self.built[key] = (ta_r, ta_c, turn, dt, (compact, compact_c))
        return self.built[key]


def outcome_event(oc) -> int | None:
    """Index of the terminal event that stopped propagate_until or step, or None."""
    k = int(oc)  # terminal event i stops with taylor_outcome(-i - 1); the others are < -2**32
    return -k - 1 if -(2**31) < k < 0 else None


class Excitation:
    """The excitation's coefficients per span between kinks, as the integrators' parameters."""

    def __init__(self, motion: Motion):
        self.motion = motion
        if motion.kind == "record":
            slope = np.diff(motion.samples) / motion.dt
            self.c0 = (motion.samples[:-1] - slope * motion.grid[:-1]).tolist()
            self.c1 = slope.tolist()
        self.zero = (0.0, 0.0) if motion.kind != "sine" else (0.0, 0.0, 0.0)

    def coeffs(self, t: float, t_stop: float):
        """The span's coefficients on [t, t_stop] (t_stop the next kink or the end)."""
        m = self.motion
        tm = 0.5 * (t + t_stop)
        if m.kind == "sine":
            return (m.a, m.w, -m.w * m.t0) if m.t0 <= tm <= m.t1 else self.zero
        if m.kind == "record" and tm <= m.t1:
            i = min(int(tm / m.dt), len(self.c1) - 1)
            return (self.c0[i], self.c1[i])
        return self.zero


class Phases:
    """The two phases integrated by the model's heyoka integrators (see the module doc)."""

    def __init__(self, case: Case, model: Model, motion: Motion, tol: float, driver: Driver):
        self.case, self.motion, self.driver = case, motion, driver
        self.excitation = Excitation(motion)
        kind = "sine" if motion.kind == "sine" else "linear"
        self.ta_r, self.ta_c, self.turn = model.integrators(kind, tol, case.overturn_angle)[:3]
        n = len(case.params)
        self.s_index, self.c_index = n, n + 5
        # Views on the integrators' state and parameters (valid while the integrators live).
        self.x_r, self.x_c = self.ta_r.state, self.ta_c.state
        self.p_r, self.p_c = self.ta_r.pars, self.ta_c.pars
        for pars in (self.p_r, self.p_c):
            pars[:n] = case.params
            pars[n + 1:n + 5] = case.scales
        self.scales = case.scales.tolist()
        self.steps = 0
        self.eps_t = 8 * float(np.finfo(float).eps)

    def span(self, pars, t: float) -> float:
        """Sets the excitation's coefficients from t to the next kink and returns the kink."""
        t_stop = self.motion.next_stop(t, self.case.t_end)
        c = self.excitation.coeffs(t, t_stop)
        pars[self.c_index:self.c_index + len(c)] = c
        return t_stop

    def contact(self, t, u, u_dot, settling):
        ta, x, t_end = self.ta_c, self.x_c, self.case.t_end
        _, us, _, uds = self.scales
        ta.time = t
        x[:] = (u / us, u_dot / uds)
        ta.reset_cooldowns()
        if settling:
            # The settling step: one step (a rising root inside it still lifts), then an f_s still
            # above zero lifts at its end.
            t_stop = self.span(self.p_c, t)
            oc, _ = ta.step(max_delta_t=t_stop - t)
            self.steps += 1
            k = outcome_event(oc)
            t = ta.time
            y = x.tolist()
            if k is not None:
                return t, RIGHT if k == 0 else LEFT, y[0] * us, y[1] * uds
            s = self.driver.lift_side(y[0] * us, y[1] * uds, self.motion.accel(t))
            if s is not None:
                return t, s, y[0] * us, y[1] * uds
        k = None
        while t < t_end and k is None:
            oc, _, _, n, *_ = ta.propagate_until(self.span(self.p_c, t))
            self.steps += n
            k = outcome_event(oc)
            t = ta.time
        y = x.tolist()
        return t, None if k is None else (RIGHT if k == 0 else LEFT), y[0] * us, y[1] * uds

    def rocking(self, t0, s, x0, n):
        ta, x, pars, turn = self.ta_r, self.x_r, self.p_r, self.turn
        t_end, alpha = self.case.t_end, self.case.alpha
        a, us, ap, uds = self.scales
        ta.time = t0
        x[:] = (x0[0] / a, x0[1] / us, x0[2] / ap, x0[3] / uds)
        ta.reset_cooldowns()
        pars[self.s_index] = s
        turn[0] = 0.0
        t, k, max_theta = t0, None, 0.0
        while t < t_end:
            oc, _, _, steps, *_ = ta.propagate_until(self.span(pars, t))
            self.steps += steps
            k = outcome_event(oc)
            t = ta.time
            if k == IMPACT and t - t0 <= self.eps_t * max(1.0, abs(t0)):
                continue  # the phase's own start at theta = 0 (uplift: a double root), not an impact
            max_theta = max(max_theta, abs(x[0]) * alpha)
            if k is not None:
                break
        y = x.tolist()
        event = None if k is None else (IMPACT, OVERTURN)[k]
        return t, event, (y[0] * a, y[1] * us, y[2] * ap, y[3] * uds), float(max(max_theta, turn[0] * alpha))


def simulate(case: Case, model: Model, motion: Motion, tol: float) -> dict:
    """One hybrid simulation: the answer, with the number of Taylor steps."""
    physics = model.physics
    physics.p = case.params.tolist()
    driver = Driver(case, physics, None)
    driver.phases = phases = Phases(case, model, motion, tol, driver)
    answer = driver.run(motion)
    answer["steps"] = phases.steps
    return answer


def cells(case: dict, quick: bool = False) -> list:
    """The cells of a case the peer runs: all, or on a spectrum slice the SciPy peer's."""
    stride = (3 if quick else 4) if case.get("amplitudes") else 1
    return list(range(0, len(case["motions"]), stride))


def compile_point(model: Model, case: dict, idx: list, tol: float) -> tuple:
    """Builds (compiles, outside any timed run) the integrators a case's cells `idx` need at
    `tol`: one pair per excitation kind. Returns the compile time (s) and the compact modes."""
    motions = case["motions"]
    compile_s, compact = 0.0, None
    for kind in sorted({"sine" if motions[i]["kind"] == "sine" else "linear" for i in idx}):
        *_, dt, compact = model.integrators(kind, tol, case["overturn_angle"])
        compile_s += dt
    return compile_s, compact


def time_point(model: Model, case: dict, idx: list, tol: float, repeats: int) -> tuple:
    """Process CPU time per simulation of the cells `idx` at `tol`: the median of at least
    `repeats` runs, repeated for at least 0.5 s (at most 50; one when a run exceeds 20 s).
    Returns the median per simulation, the run times and the last run's answers."""
    motions = case["motions"]
    times, answers = [], None
    t_all = time.process_time()
    while len(times) < repeats or (time.process_time() - t_all < 0.5 and len(times) < 50):
        t0 = time.process_time()
        answers = [simulate(Case(case), model, Motion(motions[i]), tol) for i in idx]
        times.append(time.process_time() - t0)
        if times[0] > 20.0:
            break
    return float(np.median(times)) / len(idx), times, answers


def heyoka_order(tol: float) -> int:
    """The Taylor order heyoka runs at a tolerance, ⌈−ln ε / 2 + 1⌉ (Jorba & Zou's choice; each
    integrator built checks it against its ``order``). Its step rule does not see ε otherwise:
    3e-8 and 1e-7 (both order 10) gave the same steps and answers on Fig. 3, to the last bit."""
    return math.ceil(-math.log(tol) / 2 + 1)


def grid_tols(loosest: int, tightest: int) -> list:
    """The study's grid (``study::grid`` in crates/rocking-bench: 1 and 3 in every decade) from
    1e-``loosest`` to 1e-``tightest``, one tolerance per heyoka order, the loosest that runs it: a
    second tolerance of the same order is the same configuration timed again, and the paired
    rounds' fastest-of-the-qualifying would then pick the luckier of two draws of one setting."""
    grid = []
    for k in range(loosest, tightest + 1):
        grid.append(float(f"1e-{k}"))
        if k < tightest:
            grid.append(float(f"3e-{k + 1}"))
    by_order = {}
    for tol in grid:
        by_order.setdefault(heyoka_order(tol), tol)
    return list(by_order.values())


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("cases")
    ap.add_argument("out")
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--tols", default=None, help="comma-separated tolerances (default: the study's grid "
                    "from 1e-5 to 1e-12, one per heyoka order, orders 7 to 15; --quick: 1e-5,1e-7,1e-9,1e-11)")
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--only", default=None, help="comma-separated case names")
    args = ap.parse_args()
    if args.tols:
        tols = [float(x) for x in args.tols.split(",")]
    else:
        tols = [1e-5, 1e-7, 1e-9, 1e-11] if args.quick else grid_tols(5, 12)
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
        idx = cells(case, args.quick)
        entry = {"name": case["name"], "cells": idx, "points": []}
        for tol in tols:
            failed = None
            try:
                compile_s, compact = compile_point(model, case, idx, tol)
                med, times, answers = time_point(model, case, idx, tol, args.repeats)
            except Exception as e:  # recorded, so the report shows it
                failed = f"{type(e).__name__}: {e}"
            if failed:
                entry["points"].append({"tol": tol, "failed": failed})
                print(f"heyoka peer: {case['name']} tol {tol:g}: FAILED {failed}", file=sys.stderr)
                continue
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
