#!/usr/bin/env bash
# What a user sees, as SHA-256 digests: every example scene's `run --json` summary, summary.json,
# history.csv and events.csv, also by the Taylor method (`accurate`); the Fig-8 spectrum's
# cells.csv (100 x 100, one thread, `default` and `accurate`); the wind turbine's IDA and
# multiple-stripe studies (fragility.json, records.csv, ida.csv or stripes.csv; timing.json apart). A refactor must not change one byte of them:
#   bash .ci/digests.sh            compare with .ci/digests.txt (exit 1 and a diff when they differ)
#   bash .ci/digests.sh --update   rewrite .ci/digests.txt (an intended change of results: say why)
# ROCKING names a built binary (default: the test profile's, as `cargo test` builds it).
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:---check}
if [ -z "${ROCKING:-}" ]; then
    cargo build --profile test -p rocking-cli --bin rocking --quiet
    ROCKING=$PWD/target/debug/rocking
fi
work=$(mktemp -d /tmp/rocking-digests.XXXXXX)
trap 'rm -rf "$work"' EXIT

digest() { # NAME FILE
    printf '%s  %s\n' "$(sha256sum <"$2" | cut -d' ' -f1)" "$1"
}
{
    for scene in scenes/*.toml; do
        stem=$(basename "$scene" .toml)
        case $stem in *-ida | *-msa) continue ;; esac
        "$ROCKING" run "$scene" --json --out "$work/$stem" >"$work/$stem.json" 2>>"$work/stderr"
        digest "$stem run --json" "$work/$stem.json"
        for f in summary.json history.csv events.csv; do
            [ -f "$work/$stem/$f" ] && digest "$stem/$f" "$work/$stem/$f"
        done
        # The same scene by the Taylor method (the accurate preset), whatever the scene asks for.
        "$ROCKING" run "$scene" --set solver.accuracy=accurate --json --out "$work/$stem-acc" \
            >"$work/$stem-acc.json" 2>>"$work/stderr"
        digest "$stem accurate run --json" "$work/$stem-acc.json"
        for f in history.csv events.csv; do
            [ -f "$work/$stem-acc/$f" ] && digest "$stem accurate/$f" "$work/$stem-acc/$f"
        done
    done
    for acc in default accurate; do
        "$ROCKING" spectrum scenes/spectra/fig8.toml --set solver.accuracy=$acc --quiet --threads 1 \
            --out "$work/fig8-$acc" >/dev/null
        digest "fig8 spectrum $acc/cells.csv" "$work/fig8-$acc/cells.csv"
    done
    for study in wind-turbine-ida wind-turbine-msa; do
        "$ROCKING" ida "scenes/$study.toml" --out "$work/$study" >/dev/null 2>&1
        # Timing is apart, in timing.json (not a result).
        # records.csv names each record file by its absolute path: digest it relative to the
        # checkout's parent (where ../shared lies), so the digest does not depend on where the
        # repository is cloned.
        sed -i "s|$(dirname "$PWD")/||g" "$work/$study/records.csv"
        for f in fragility.json records.csv ida.csv stripes.csv; do
            [ -f "$work/$study/$f" ] && digest "$study/$f" "$work/$study/$f"
        done
    done
} >"$work/digests.txt"

case $mode in
--update)
    cp "$work/digests.txt" .ci/digests.txt
    echo "wrote .ci/digests.txt ($(wc -l <.ci/digests.txt) digests)"
    ;;
--check)
    if diff -u .ci/digests.txt "$work/digests.txt"; then
        echo "$(wc -l <.ci/digests.txt) digests of the example outputs unchanged"
    else
        echo "the outputs above changed: if that is intended, run bash .ci/digests.sh --update and say why" >&2
        exit 1
    fi
    ;;
*)
    echo "usage: bash .ci/digests.sh [--check|--update]" >&2
    exit 2
    ;;
esac
