"""OpenSees peer: a rigid(-ish) block in free rocking with the RockingBC element (openseespy).

The model follows the RockingBC "Free" example of Avgenakis & Psycharis (2020), OpenSees's
macroelement for deformable rocking bodies: a rectangular block (B = 1 m wide, α = 0.2, made
nearly rigid by a small e0 = ρ g H / E), pushed statically to θ0 = α/2 and released. The first
impact (θ = 0) of a rigid block is at a quarter of Housner's exact period, which in τ = p t
(p = sqrt(3 g / 4 R) for a rectangle) is the same number as for the project's point-mass block:
the error of each tool is measured against it. Rust's numbers for the same simulated duration
(τ = 4) come from ``rocking-bench run`` (``rust.json``, ``housner_block``).

    python bench/opensees_rocking.py target/bench/rust.json target/bench/opensees.json [--quick]
"""

from __future__ import annotations

import ctypes
import glob
import json
import math
import os
import sys
import time


def preload_bundled_libs():
    """openseespylinux ships libblas/liblapack/libgfortran in its lib/ folder without an rpath;
    preload them so the import works on machines without system BLAS (no LD_LIBRARY_PATH needed)."""
    try:
        import importlib.util

        spec = importlib.util.find_spec("openseespylinux")
        if spec is None or not spec.submodule_search_locations:
            return
        lib = os.path.join(list(spec.submodule_search_locations)[0], "lib")
        for name in ("libquadmath.so.0", "libgfortran.so.4", "libgomp.so.1", "libblas.so.3", "liblapack.so.3"):
            for path in glob.glob(os.path.join(lib, name)):
                ctypes.CDLL(path, mode=ctypes.RTLD_GLOBAL)
    except OSError:
        pass


def run_block(ops, dt_max: float, tau_end: float, alpha=0.2, ratio=0.5):
    B, w, rho, mu, g, nu, Nw = 1.0, 1.0, 2.5, 0.0, 9.81, 0.0, 15
    e0, sr = 5.0e-6, 5.0e-3
    H = B / math.tan(alpha)
    E = rho * g * H / e0
    sy = -rho * g * H / sr
    R = math.sqrt(H * H + B * B) / 2.0
    p = math.sqrt(3.0 * g / 4.0 / R)
    mass = H * B * w * rho
    inertia = mass * (B * B + H * H) / 12.0
    th0 = ratio * alpha

    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    ops.node(1, 0.0, 0.0)
    ops.node(2, 0.0, 0.5 * H)
    ops.node(3, 0.0, H)
    dt_min = 1.0e-8
    ops.element("RockingBC", 1, 2, 1, Nw, E, nu, sy, B, w, mu, "-convlim", 1e-15, "-useshear", 0,
                "-blevery", 1, "-useUelNM", 1, "-usecomstiff", 0, "-af", 1.0, "-aflim", 0.4,
                "-convlimmult", 1.0, "-maxtries", 50, "-NlimN", 0.001, "-NlimT", 1.0, "-Dtlim", dt_min,
                "-errorifNexceeds", 1)
    ops.geomTransf("Corotational", 1)
    ops.element("elasticBeamColumn", 2, 2, 3, B * w, E, w * B**3 / 12.0, 1)
    ops.fix(1, 1, 1, 1)
    ops.mass(2, mass, mass, inertia)
    ops.timeSeries("Linear", 1)
    ops.pattern("Plain", 1, 1)
    ops.load(2, 0.0, -mass * g, 0.0)
    ops.constraints("Transformation")
    ops.numberer("RCM")
    ops.system("UmfPack")
    ops.test("EnergyIncr", 1e-10, 100)
    ops.algorithm("Newton")
    ops.integrator("LoadControl", 0.1)
    ops.analysis("Static")
    ops.analyze(10)
    ops.loadConst("-time", 0.0)
    # pushover to θ0 (node 2 rotation)
    ops.timeSeries("Linear", 2)
    ops.pattern("Plain", 2, 2)
    ops.load(2, 1.0, 0.0, 0.0)
    d_max = -th0
    d_incr = 0.005 * d_max
    while True:
        cur = ops.nodeDisp(2, 3)
        if cur / d_max >= 1.0:
            break
        step = -min(abs(d_incr), abs(d_max - cur))
        ops.integrator("DisplacementControl", 2, 3, step)
        if ops.analyze(1) != 0:
            ops.integrator("DisplacementControl", 2, 3, step / 100)
            for _ in range(100):
                ops.analyze(1)
    ops.remove("loadPattern", 2)
    ops.setTime(0.0)
    ops.wipeAnalysis()
    ops.constraints("Transformation")
    ops.numberer("RCM")
    ops.system("UmfPack")
    ops.test("RelativeNormUnbalance", 1e-10, 100)
    ops.algorithm("Newton")
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")

    t_end = tau_end / p
    theta_prev, t_prev = ops.nodeDisp(2, 3), 0.0
    impacts = []
    dt = dt_max
    good = 0
    t0 = time.perf_counter()
    ok = 0
    while ops.getTime() < t_end:
        ok = ops.analyze(1, dt)
        if ok != 0 and dt <= dt_min:
            break
        if ok != 0:
            dt = max(dt_min, 0.5 * dt)
            good = 0
            continue
        good += 1
        if good >= 10:
            try:
                nmax = ops.eleResponse(1, "forceratioNmax")[0]
                tmax = ops.eleResponse(1, "forceratioTmax")[0]
                if nmax < 0.9 * 0.001 and tmax < 0.9:
                    dt = min(dt_max, 1.5 * dt)
            except Exception:
                dt = min(dt_max, 1.5 * dt)
        t, theta = ops.getTime(), ops.nodeDisp(2, 3)
        if theta_prev != 0.0 and theta_prev * theta <= 0.0 and theta != theta_prev:
            impacts.append(t_prev + (t - t_prev) * theta_prev / (theta_prev - theta))
        theta_prev, t_prev = theta, t
    seconds = time.perf_counter() - t0
    ops.wipe()
    return {"seconds": seconds, "impacts_tau": [x * p for x in impacts], "ok": ok, "p": p,
            "reached_tau": t_prev * p}


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    quick = "--quick" in sys.argv
    rust_path, out_path = args[0], args[1]
    rust = json.load(open(rust_path))
    hb = rust.get("housner_block", {})
    exact_q = hb.get("exact_quarter")
    tau_end = hb.get("tau_end", 4.0)
    out = {"rows": list(hb.get("rows", [])), "tau_end": tau_end}
    preload_bundled_libs()
    try:
        import openseespy.opensees as ops

        from importlib.metadata import version as _v

        version = _v("openseespy")
    except Exception as e:  # noqa: BLE001
        out["skipped"] = f"openseespy does not import here: {type(e).__name__}: {e}"
        json.dump(out, open(out_path, "w"))
        print(out["skipped"], file=sys.stderr)
        return
    try:
        ops.logFile(os.devnull, "-noEcho")  # OpenSees's step-failure chatter
    except Exception:  # noqa: BLE001
        pass
    # Δt_max = 1e-3 s already takes more than a minute (Δt drops to 1e-8 s around the impact)
    settings = [1e-3] if quick else [1e-3, 1e-4]
    for dt in settings:
        try:
            r = run_block(ops, dt, tau_end)
        except Exception as e:  # noqa: BLE001
            out["rows"].append({"tool": f"OpenSees {version} RockingBC", "setting": f"Δt_max = {dt:g} s",
                                "failed": f"{type(e).__name__}: {e}"})
            continue
        first = r["impacts_tau"][0] if r["impacts_tau"] else float("nan")
        err = abs(first - exact_q) / exact_q if exact_q else float("nan")
        out["rows"].append({"tool": f"OpenSees {version} RockingBC (Newmark, Newton)",
                            "setting": f"Δt_max = {dt:g} s", "seconds": r["seconds"], "quarter": first,
                            "quarter_err": err, "period": 4 * first, "period_err": err,
                            "reached_tau": r["reached_tau"], "ok": r["ok"]})
        print(f"opensees: dt_max {dt:g}: {r['seconds']:.2f} s, first impact τ {first:.6f} "
              f"(exact {exact_q:.6f}, rel err {err:.2e}), reached τ {r['reached_tau']:.3f}", file=sys.stderr)
    out["text"] = (f"Free rocking from θ0 = α/2 (α = 0.2), simulated to τ = p t = {tau_end:g} for both tools. "
                   f"Exact quarter period (Housner, quadrature): τ = {exact_q:.9f}. OpenSees: RockingBC "
                   "macroelement (Avgenakis & Psycharis 2020) after the 'Free' example of the OpenSees "
                   "documentation: a rectangular block, e0 = 5e-6 (nearly rigid), Newmark (average "
                   "acceleration) with Newton, adaptive Δt between 1e-8 s and Δt_max; the impact time is "
                   "the zero crossing of the base rotation, interpolated linearly between steps. Wall time "
                   "of the transient analysis only (time.perf_counter). Rust: process CPU time, median of "
                   "repeats; its first impact is located on the dense output.")
    json.dump(out, open(out_path, "w"))


if __name__ == "__main__":
    main()
