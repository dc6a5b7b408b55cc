#!/usr/bin/env python3
"""Study 1 of issue 44 (docs/ground.md): the Fig-8 spectrum on a Winkler bed against the rigid
surface, from the cells.csv files of the spectra (standard library only).

    python3 scenes/spectra/ground-study1.py RIGID_DIR BED_DIR=OMEGA_V_OVER_P ...

prints, per spectrum, the cells per class; per bed against the rigid surface, the cells whose
overturning changed; and the overturning boundary per frequency column: the lowest amplitude
a_p/(g tan α) at which the structure overturns, its shift on the bed (median, quartiles, range
over the columns, and at a few columns), with columns whose boundary a failed cell hides left
out and counted. When the spectra report `solver_stats.steps`, also the steps: total, mean per
cell, and for the upright cells on a bed (which run to the pulse's end plus `after_excitation`
= 20) the steps per τ and per vertical period 2π/ω_v.
"""

import csv
import math
import statistics
import sys
from collections import Counter

FREQ, AMP = "excitation.omega_p_over_p", "excitation.amplitude"
CLASSES = ["no-uplift", "survived", "overturned-no-impact", "overturned-one-impact",
           "overturned-impacts", "beyond-model", "failed"]


def load(directory):
    with open(f"{directory}/cells.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    return {(float(r[FREQ]), float(r[AMP])): r for r in rows}


def overturned(cls):
    return None if cls in ("failed", "beyond-model") else cls.startswith("overturned")


def boundary(cells):
    """Per frequency column: the lowest overturning amplitude, None when none overturns, or
    'hidden' when a cell without a result lies below the first overturning one."""
    out = {}
    for f in sorted({k[0] for k in cells}):
        column = sorted((a, cells[(f, a)]["class"]) for (g, a) in cells if g == f)
        first = None
        for a, c in column:
            o = overturned(c)
            if o is None:
                first = "hidden"
                break
            if o:
                first = a
                break
        out[f] = first
    return out


def quartiles(xs):
    q = statistics.quantiles(xs, n=4) if len(xs) > 1 else [xs[0]] * 3
    return q[0], q[1], q[2]


def steps(runs, after=20.0):
    if not all("solver_stats.steps" in next(iter(c.values())) for _, c in runs):
        return
    print("\nsteps (the preset's method on both grounds)")
    print("| ground | total steps | mean per cell | upright cells: steps per τ | per 2π/ω_v |")
    print("|---|---|---|---|---|")
    for label, cells in runs:
        rows = [r for r in cells.values() if r["solver_stats.steps"]]
        total = sum(float(r["solver_stats.steps"]) for r in rows)
        per_tau = per_period = "-"
        try:
            omega_v = float(label)
        except ValueError:
            omega_v = None
        if omega_v:
            up = [r for r in rows if overturned(r["class"]) is False]
            t = sum(2 * math.pi / float(r[FREQ]) + after for r in up)
            n = sum(float(r["solver_stats.steps"]) for r in up)
            per_tau = f"{n / t:.1f}"
            per_period = f"{n / t * 2 * math.pi / omega_v:.2f}"
        print(f"| {label} | {total:,.0f} | {total / len(rows):,.0f} | {per_tau} | {per_period} |")


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    runs = []
    for i, arg in enumerate(argv[1:]):
        directory, _, label = arg.partition("=")
        runs.append((label or ("rigid" if i == 0 else directory), load(directory)))
    print("cells per class")
    print("| ground | " + " | ".join(CLASSES) + " |")
    print("|---" * (len(CLASSES) + 1) + "|")
    for label, cells in runs:
        n = Counter(r["class"] for r in cells.values())
        print(f"| {label} | " + " | ".join(str(n.get(c, 0)) for c in CLASSES) + " |")
    steps(runs)
    rigid_label, rigid = runs[0]
    b0 = boundary(rigid)
    amps = sorted({k[1] for k in rigid})
    step = amps[1] - amps[0]
    print(f"\noverturning boundary: lowest overturning a_p/(g tan α) per ω_p/p column "
          f"(grid step {step:.4f})")
    for label, cells in runs[1:]:
        both = [k for k in rigid if k in cells]
        o0 = [overturned(rigid[k]["class"]) for k in both]
        o1 = [overturned(cells[k]["class"]) for k in both]
        flip_up = sum(1 for a, b in zip(o0, o1) if a is True and b is False)
        flip_down = sum(1 for a, b in zip(o0, o1) if a is False and b is True)
        b1 = boundary(cells)
        shifts, hidden, none = [], 0, 0
        for f in sorted(b0):
            x0, x1 = b0[f], b1.get(f)
            if x0 == "hidden" or x1 == "hidden":
                hidden += 1
            elif x0 is None or x1 is None:
                none += 1
            else:
                shifts.append((f, x1 - x0, x0, x1))
        print(f"\n{label} against {rigid_label}: {flip_up} cells overturn on {rigid_label} "
              f"and stand on {label}, {flip_down} the other way")
        if shifts:
            d = [s[1] for s in shifts]
            q1, q2, q3 = quartiles(d)
            print(f"  boundary shift over {len(d)} columns: median {q2:+.3f}, quartiles "
                  f"{q1:+.3f} .. {q3:+.3f}, range {min(d):+.3f} .. {max(d):+.3f}; up in "
                  f"{sum(x > 0 for x in d)}, down in {sum(x < 0 for x in d)}, same in "
                  f"{sum(x == 0 for x in d)}; {hidden} columns hidden by failed cells, "
                  f"{none} without overturning on one of the two")
            freqs = sorted(b0)
            picks = [min(freqs, key=lambda f: abs(f - t)) for t in (1.0, 2.0, 3.0, 5.0, 7.0, 10.0)]
            cols = {s[0]: s for s in shifts}
            print("  | ω_p/p | rigid | bed | shift |")
            print("  |---|---|---|---|")
            for f in picks:
                if f in cols:
                    _, dd, x0, x1 = cols[f]
                    print(f"  | {f:.2f} | {x0:.2f} | {x1:.2f} | {dd:+.2f} |")
                else:
                    print(f"  | {f:.2f} | {b0[f]} | {b1.get(f)} | - |")


if __name__ == "__main__":
    main(sys.argv)
