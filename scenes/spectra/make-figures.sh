#!/usr/bin/env bash
# Rebuilds the figures of docs/gallery.md, docs/spectra.md and docs/design-forces.md: the paper's
# Figs 3-10 from the figure files of scenes/paper (one `rocking figure` command: each spectrum is
# computed once, journaled in out/figure-cache/ and shared by Figs 6-9), the one-axis line plot,
# the design-force figures and the animation of the Fig. 3 run. Figure files are drawn at their
# printed width (PNG at the figure file's dpi: 300 for the committed images) with their captions beside them (NAME.caption.md). The images are the same bytes on every machine.
# Usage: bash scenes/spectra/make-figures.sh           draw them into docs/img/
#        bash scenes/spectra/make-figures.sh --check   draw them aside and compare with docs/img/
#                                                      (exit 1 naming the files that differ)
# ROCKING names a built binary (default: the release build, built first), e.g. the test
# profile's target/debug/rocking in CI: the images are the same bytes.
set -euo pipefail
cd "$(dirname "$0")/../.."
mode=${1:---write}
case $mode in
--write | --check) ;;
*)
    echo "usage: bash scenes/spectra/make-figures.sh [--check]" >&2
    exit 2
    ;;
esac
if [ -z "${ROCKING:-}" ]; then
    cargo build --release -q -p rocking-cli
    ROCKING=$PWD/target/release/rocking
fi
start=$(date +%s)
rocking=$ROCKING
work=$(mktemp -d /tmp/rocking-figures.XXXXXX)
trap 'rm -rf "$work"' EXIT
# `rocking spectrum` exits 1 when some cells failed (they are marked in cells.csv and meta.json,
# and the figure is still drawn); any other failure stops the script.
spectrum() { "$rocking" spectrum "$@" || { s=$?; [ "$s" -eq 1 ] || exit "$s"; }; }

# Each drawn file and where it is committed.
"$rocking" figure scenes/paper/fig*.toml --out "$work/paper" --quiet >/dev/null
pairs=()
for f in "$work"/paper/*.svg "$work"/paper/*.png "$work"/paper/*.caption.md; do
    pairs+=("$f" "docs/img/paper/$(basename "$f")")
done
# A one-axis sweep (line plot): Fig. 8, α = 0.1, ω_n/p = 5, ω_p/p = 5, against the amplitude.
spectrum scenes/spectra/fig8.toml --quiet --out "$work/fig8-line" --set structure.alpha=0.1 \
    --axis "excitation.amplitude=1:20:40" | sed -n 1p
pairs+=("$work/fig8-line/line.png" docs/img/spectra/fig8-line.png)
pairs+=("$work/fig8-line/line.svg" docs/img/spectra/fig8-line.svg)
# The design forces (docs/design-forces.md), at print size: the Fig-8 structure's spectra of the
# base moment over its fixed-base twin's and of the friction it needs (the sweep of
# scenes/spectra/fig8-forces.toml), and the wind turbine rocking against fixed.
"$rocking" figure scenes/forces/*.toml --out "$work/forces" --quiet >/dev/null
for f in "$work"/forces/*.svg "$work"/forces/*.png "$work"/forces/*.caption.md; do
    pairs+=("$f" "docs/img/forces/$(basename "$f")")
done
# The animation of the Fig. 3 scene (docs/img/fig3-vvel.gif).
"$rocking" run scenes/fig3-vvel.toml --animate --out "$work/fig3-vvel-animation" | sed -n 2p
pairs+=("$work/fig3-vvel-animation/animation.gif" docs/img/fig3-vvel.gif)

differ=0
for ((k = 0; k < ${#pairs[@]}; k += 2)); do
    drawn=${pairs[k]} committed=${pairs[k + 1]}
    if [ "$mode" = --write ]; then
        mkdir -p "$(dirname "$committed")"
        cp "$drawn" "$committed"
    elif ! cmp -s "$drawn" "$committed"; then
        echo "differs from a redraw: $committed" >&2
        differ=1
    fi
done
if [ "$mode" = --check ]; then
    if [ "$differ" -ne 0 ]; then
        echo "redraw with: bash scenes/spectra/make-figures.sh (and say why they changed)" >&2
        exit 1
    fi
    echo "$((${#pairs[@]} / 2)) committed images are the bytes a redraw gives"
fi
echo "figures made in $(($(date +%s) - start)) s"
