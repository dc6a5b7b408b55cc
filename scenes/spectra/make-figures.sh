#!/usr/bin/env bash
# Rebuilds the figures of docs/gallery.md and docs/spectra.md: the paper's Figs 3-10 from the
# figure files of scenes/paper (one `rocking figure` command: each spectrum is computed once,
# journaled in out/figure-cache/ and shared by Figs 6-9), the one-axis line plot and the
# animation of the Fig. 3 run. The images are the same bytes on every machine.
# Usage: bash scenes/spectra/make-figures.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
cargo build --release -q -p rocking-cli
start=$(date +%s)
rocking=target/release/rocking
"$rocking" figure scenes/paper/fig*.toml --out docs/img/paper --quiet >/dev/null
# `rocking spectrum` exits 1 when some cells failed (they are marked in cells.csv and meta.json,
# and the figure is still drawn); any other failure stops the script.
spectrum() { "$rocking" spectrum "$@" || { s=$?; [ "$s" -eq 1 ] || exit "$s"; }; }
rm -rf out/spectra out/fig3-vvel-animation
mkdir -p docs/img/spectra
# A one-axis sweep (line plot): Fig. 8, α = 0.1, ω_n/p = 5, ω_p/p = 5, against the amplitude.
spectrum scenes/spectra/fig8.toml --quiet --out out/spectra/fig8-line --set structure.alpha=0.1 \
  --axis "excitation.amplitude=1:20:40" | sed -n 1p
cp out/spectra/fig8-line/line.png docs/img/spectra/fig8-line.png
cp out/spectra/fig8-line/line.svg docs/img/spectra/fig8-line.svg
# The animation of the Fig. 3 scene (docs/img/fig3-vvel.gif).
"$rocking" run scenes/fig3-vvel.toml --animate --out out/fig3-vvel-animation | sed -n 2p
cp out/fig3-vvel-animation/animation.gif docs/img/fig3-vvel.gif
echo "figures made in $(( $(date +%s) - start )) s"
