#!/usr/bin/env bash
# Rebuilds the spectrum figures of docs/spectra.md (the paper's Figs 6-9) from the scenes here.
# Usage: bash scenes/spectra/make-figures.sh [cells per axis, default 40]
set -euo pipefail
cd "$(dirname "$0")/../.."
n=${1:-40}
cargo build --release -q -p rocking-cli
rocking=target/release/rocking
# `rocking spectrum` exits 1 when some cells failed (they are marked in cells.csv and meta.json,
# and the figure is still drawn); any other failure stops the script.
spectrum() { "$rocking" spectrum "$@" || { s=$?; [ "$s" -eq 1 ] || exit "$s"; }; }
img=docs/img/spectra
mkdir -p "$img"
for fig in 6 7 8; do
  for alpha in 0.1 0.2; do
    for wn in 2.5 5 10 20 rigid; do
      name="fig$fig-alpha$alpha-wn$wn"
      if [ "$wn" = rigid ]; then set_wn=(--set effects.flexibility=false); else set_wn=(--set "structure.omega_n_over_p=$wn"); fi
      spectrum "scenes/spectra/fig$fig.toml" --quiet --out "out/spectra/$name" \
        --set "structure.alpha=$alpha" "${set_wn[@]}" \
        --axis "excitation.omega_p_over_p=1:10:$n" --axis "excitation.amplitude=1:20:$n" | sed -n 1p
      cp "out/spectra/$name/spectrum.png" "$img/$name.png"
    done
  done
done
spectrum scenes/spectra/fig9.toml --quiet --out out/spectra/fig9 | sed -n 1p
cp out/spectra/fig9/spectrum.png "$img/fig9.png"
