#!/usr/bin/env bash
# Which cells of the Fig-8 spectrum change class when the column has three deformation coordinates
# instead of the paper's one (docs/modes.md). Runs scenes/spectra/fig8.toml with the `cubic` model
# and with MODEL (default cantilever_modes3) at the same first fixed-base frequency, and prints the
# class changes (from → to, count) and the cells where max θ/α moved by more than 1 %.
# Usage: bash scenes/modes/fig8-classes.sh [MODEL] [--set KEY=VALUE ...]   (extra rocking flags
#        such as --axis to choose a smaller grid)
# ROCKING names a built binary (default: the release build, built first).
set -euo pipefail
cd "$(dirname "$0")/../.."
model=cantilever_modes3
if [ $# -gt 0 ] && [[ $1 != --* ]]; then
    model=$1
    shift
fi
if [ -z "${ROCKING:-}" ]; then
    cargo build --release -q -p rocking-cli
    ROCKING=$PWD/target/release/rocking
fi
work=$(mktemp -d /tmp/rocking-fig8-modes.XXXXXX)
trap 'rm -rf "$work"' EXIT
for m in cubic "$model"; do
    /usr/bin/time -f "$m: %U s user CPU" "$ROCKING" spectrum scenes/spectra/fig8.toml --quiet \
        --set "structure.model=$m" --out "$work/$m" "$@" | sed -n 1p
done
python3 - "$work/cubic/cells.csv" "$work/$model/cells.csv" "$model" <<'PY'
import csv, sys
from collections import Counter
one = list(csv.DictReader(open(sys.argv[1])))
many = list(csv.DictReader(open(sys.argv[2])))
model = sys.argv[3]
axes = [k for k in one[0] if k not in ("class", "max_theta_over_alpha", "impacts")]
changes, moved = Counter(), 0
for a, b in zip(one, many):
    assert [a[k] for k in axes] == [b[k] for k in axes], "the two grids differ"
    if a["class"] != b["class"]:
        changes[(a["class"], b["class"])] += 1
    ta, tb = float(a["max_theta_over_alpha"]), float(b["max_theta_over_alpha"])
    if not a["class"].startswith("overturned") and abs(tb - ta) > 0.01 * max(abs(ta), 1e-12):
        moved += 1
print(f"{len(one)} cells; {sum(changes.values())} change class with `{model}`:")
print()
print("| class with `cubic` | class with `" + model + "` | cells |")
print("|---|---|---|")
for (a, b), n in sorted(changes.items(), key=lambda kv: -kv[1]):
    print(f"| {a} | {b} | {n} |")
print()
print(f"cells that survive with `cubic` whose max θ/α moved by more than 1 %: {moved}")
# Where one mode is enough: by band of the first axis (ω_p/p for Fig. 8).
first = axes[0]
values = sorted({float(a[first]) for a in one})
edges = [values[0] + (values[-1] - values[0]) * k / 4 for k in range(5)]
print()
print(f"| {first} | cells | change class | survivors with max θ/α moved > 1 % |")
print("|---|---|---|---|")
for lo, hi in zip(edges, edges[1:]):
    band = [(a, b) for a, b in zip(one, many) if lo <= float(a[first]) <= hi and
            (float(a[first]) < hi or hi == edges[-1])]
    changed = sum(a["class"] != b["class"] for a, b in band)
    alive = [(a, b) for a, b in band if not a["class"].startswith("overturned")]
    far = sum(abs(float(b["max_theta_over_alpha"]) - float(a["max_theta_over_alpha"]))
              > 0.01 * max(abs(float(a["max_theta_over_alpha"])), 1e-12) for a, b in alive)
    print(f"| {lo:.3g}–{hi:.3g} | {len(band)} | {changed} ({100 * changed / len(band):.1f} %) | "
          f"{far} of {len(alive)} |")
PY
