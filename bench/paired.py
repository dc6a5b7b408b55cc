"""Issue 31's heyoka targets timed in alternated rounds: the study's matched points, both tools
in the same minutes.

The study (`cargo xtask bench`) times Rust first and heyoka minutes later, each once; between
such runs heyoka's time per simulation on one case moved by 20 % while Rust's moved 2-5 %, so
a ratio of the study is one draw. This script takes the study's matched points at the targets'
error levels (`rocking-bench pairs`: per case and level, every heyoka tolerance, the cheapest
Rust configuration and the cheapest preset that meet it) and times them again in rounds, each
round every heyoka point (in this process, as `heyoka_peer.py` times it) and every Rust
configuration (`rocking-bench probe`, process CPU time), the order reversed every other round.
heyoka's time of a round is its fastest tolerance that meets the level, in that round: its cost
is nearly flat in the tolerance (0.6-1.0 ms per simulation from 1e-5 to 1e-9 on Fig. 3 in the
study's runs), so the study's one draw per tolerance does not tell which is its strongest. It
writes per point the median time and range over the rounds, and per case and level the ratio
heyoka / Rust of each round, median and range, to DIR/paired.json, which
`rocking-bench report` turns into a table of docs/accuracy.md (`cargo xtask bench` runs this
script after the heyoka peer).

    cargo build --release -p rocking-bench
    PYTHONPATH=derive .venv/bin/python bench/paired.py [--dir target/bench] \\
        [--cases fig3-vvel,fig3-adjex,fig5-flexible] [--levels 1e-9,1e-12] [--rounds 8] \\
        [--seconds 1] [--out target/bench/paired.json]
"""

from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import heyoka_peer as peer  # noqa: E402

PROBE = re.compile(r": ([0-9.]+) ms per simulation")


def probe_seconds(binary: str, case: str, method: str, tol: float, seconds: float) -> float:
    """Rust's CPU time per simulation of one configuration, from `rocking-bench probe`."""
    out = subprocess.run([binary, "probe", case, method, repr(tol), repr(seconds)],
                         check=True, capture_output=True, text=True).stdout
    m = PROBE.search(out)
    if not m:
        raise RuntimeError(f"rocking-bench probe printed no time: {out!r}")
    return float(m.group(1)) * 1e-3


def spread(xs: list) -> dict:
    """Median, smallest and largest of a list of numbers, and the list (one per round)."""
    return {"median": float(np.median(xs)), "min": float(min(xs)), "max": float(max(xs)),
            "rounds": [float(x) for x in xs]}


def fail(message: str):
    """Bad input: the message on stderr, exit status 2."""
    print(f"paired.py: {message}", file=sys.stderr)
    sys.exit(2)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--dir", default="target/bench")
    ap.add_argument("--bin", default="target/release/rocking-bench")
    ap.add_argument("--cases", default="fig3-vvel,fig3-adjex,fig5-flexible")
    ap.add_argument("--levels", default="1e-9,1e-12")
    ap.add_argument("--rounds", type=int, default=8)
    ap.add_argument("--seconds", type=float, default=1.0, help="each Rust probe's timing (s)")
    ap.add_argument("--out", default=None, help="JSON results (default DIR/paired.json)")
    args = ap.parse_args()
    if args.rounds < 1 or args.rounds > 100:
        fail(f"--rounds {args.rounds}: must be in 1..=100")
    if not 0.1 <= args.seconds <= 60:
        fail(f"--seconds {args.seconds}: must be in [0.1, 60]")
    try:
        levels = [float(x) for x in args.levels.split(",")]
    except ValueError:
        fail(f"--levels {args.levels!r}: comma-separated numbers, e.g. 1e-9,1e-12")
    names = args.cases.split(",")
    pairs = json.loads(subprocess.run([args.bin, "pairs", "--dir", args.dir], check=True,
                                      capture_output=True, text=True).stdout)
    rows = [r for r in pairs if r["case"] in names and any(abs(r["level"] / x - 1) < 1e-9 for x in levels)]
    if not rows:
        fail(f"no matched point for cases {names} at levels {levels} in {args.dir}")
    cases = {c["name"]: c for c in json.load(open(os.path.join(args.dir, "cases.json")))["cases"]}
    # The distinct points to time, each once per round.
    hy_points = sorted({(r["case"], t) for r in rows for t in r["heyoka"]["candidates"]})
    rust_points = sorted({(r["case"], c["method"], c["tol"]) for r in rows
                          for c in (r["rust"], r["preset"]) if c})
    models = {}
    for name, tol in hy_points:
        case = cases[name]
        model = models.setdefault(case["variant"], peer.Model(case["variant"]))
        peer.compile_point(model, case, peer.cells(case), tol)
    times = {p: [] for p in hy_points + rust_points}
    for r in range(args.rounds):
        order = [("heyoka", p) for p in hy_points] + [("rust", p) for p in rust_points]
        if r % 2:
            order.reverse()
        for tool, p in order:
            if tool == "heyoka":
                case = cases[p[0]]
                med, _, _ = peer.time_point(models[case["variant"]], case, peer.cells(case), p[1], 5)
            else:
                med = probe_seconds(args.bin, *p, args.seconds)
            times[p].append(med)
        print(f"round {r + 1} of {args.rounds} done", file=sys.stderr)
    out = {"rounds": args.rounds, "rust_seconds": args.seconds, "rows": []}
    for row in rows:
        # Per round, heyoka's fastest tolerance among those that meet the level.
        tols = row["heyoka"]["candidates"]
        fastest = [min(tols, key=lambda t: times[(row["case"], t)][r]) for r in range(args.rounds)]
        h = [times[(row["case"], t)][r] for r, t in enumerate(fastest)]
        # The tolerance fastest in most rounds (the tighter one on a tie) names the row.
        tol = max(tols, key=lambda t: (fastest.count(t), -t))
        entry = {"case": row["case"], "level": row["level"], "heyoka_tol": tol,
                 "heyoka_fastest": fastest, "heyoka_s": spread(h)}
        line = (f"{row['case']} <= {row['level']:.0e}: heyoka {tol:.0e} (fastest in "
                f"{fastest.count(tol)} of {args.rounds} rounds) {1e6 * np.median(h):.0f} us")
        for key in ("rust", "preset"):
            c = row[key]
            if not c:
                continue
            t = times[(row["case"], c["method"], c["tol"])]
            ratio = [a / b for a, b in zip(h, t)]
            entry[key] = {"method": c["method"], "tol": c["tol"], "name": c.get("name"),
                          "seconds": spread(t), "ratio": spread(ratio)}
            line += (f"; {c.get('name') or key} {c['method']} {c['tol']:.0e} {1e6 * np.median(t):.0f} us, "
                     f"ratio {np.median(ratio):.2f}x ({min(ratio):.2f}-{max(ratio):.2f})")
        print(line, file=sys.stderr)
        out["rows"].append(entry)
    # Whole or not at all: the report skips a paired.json it cannot read.
    path = args.out or os.path.join(args.dir, "paired.json")
    with open(path + ".tmp", "w") as f:
        json.dump(out, f, indent=1)
    os.replace(path + ".tmp", path)


if __name__ == "__main__":
    main()
