#!/usr/bin/env bash
# Rebuilds the spectrum figures of docs/spectra.md (the paper's Figs 6-9) from the scenes here.
# Usage: bash scenes/spectra/make-figures.sh [cells per axis, default 40]
set -euo pipefail
cd "$(dirname "$0")/../.."
n=${1:-40}
cargo build --release -q -p rocking-cli
start=$(date +%s)
rocking=target/release/rocking
# `rocking spectrum` exits 1 when some cells failed (they are marked in cells.csv and meta.json,
# and the figure is still drawn); any other failure stops the script.
spectrum() { "$rocking" spectrum "$@" || { s=$?; [ "$s" -eq 1 ] || exit "$s"; }; }
img=docs/img/spectra
mkdir -p "$img"
# Its own scratch outputs, made anew (a journal of another build would be refused, not resumed).
rm -rf out/spectra out/fig3-vvel-animation
for fig in 6 7 8; do
  for alpha in 0.1 0.2; do
    for wn in 2.5 5 10 20 rigid; do
      name="fig$fig-alpha$alpha-wn$wn"
      if [ "$wn" = rigid ]; then set_wn=(--set effects.flexibility=false); else set_wn=(--set "structure.omega_n_over_p=$wn"); fi
      spectrum "scenes/spectra/fig$fig.toml" --quiet --out "out/spectra/$name" \
        --set "structure.alpha=$alpha" "${set_wn[@]}" \
        --axis "excitation.omega_p_over_p=1:10:$n" --axis "excitation.amplitude=1:20:$n" | sed -n 1p
      cp "out/spectra/$name/spectrum.png" "$img/$name.png"
      cp "out/spectra/$name/spectrum.svg" "$img/$name.svg"
    done
  done
done
spectrum scenes/spectra/fig9.toml --quiet --out out/spectra/fig9 | sed -n 1p
cp out/spectra/fig9/spectrum.png "$img/fig9.png"
cp out/spectra/fig9/spectrum.svg "$img/fig9.svg"
# A one-axis sweep (line plot): Fig. 8, α = 0.1, ω_n/p = 5, ω_p/p = 5, against the amplitude.
spectrum scenes/spectra/fig8.toml --quiet --out out/spectra/fig8-line --set structure.alpha=0.1 \
  --axis "excitation.amplitude=1:20:$n" | sed -n 1p
cp out/spectra/fig8-line/line.png "$img/fig8-line.png"
cp out/spectra/fig8-line/line.svg "$img/fig8-line.svg"
# The animation of the Fig. 3 scene (docs/img/fig3-vvel.gif).
"$rocking" run scenes/fig3-vvel.toml --animate --out out/fig3-vvel-animation | sed -n 2p
cp out/fig3-vvel-animation/animation.gif docs/img/fig3-vvel.gif
echo "figures made in $(( $(date +%s) - start )) s"
