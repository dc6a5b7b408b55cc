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
PY
