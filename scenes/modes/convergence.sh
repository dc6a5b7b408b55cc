#!/usr/bin/env bash
# The convergence study of docs/modes.md: how much the deformation coordinates a model lacks change
# a run. Each case runs with the paper's one-coordinate model (`cubic`) and with the Ritz bases of
# two and three functions (`polynomial2/3`: η², η³, η⁴) and of one to eight clamped-free
# cantilever modes (`cantilever_modes1` .. `cantilever_modes8`), all at the `accurate` preset so
# that the differences are the models', not the integrator's (its error there is ~1e-12). Prints
# one markdown table per case (the wind turbine's with its fixed-base twin's peak base moment and
# the ratio), then `rocking convergence` over the cantilever-mode chain n = 1 .. 8: the n from
# which each quantity changes by less than 1 %.
# Usage: bash scenes/modes/convergence.sh            the table of runs
#        bash scenes/modes/convergence.sh --cost     also instructions per step inside the
#                                                    solver (valgrind's callgrind, counting in
#                                                    driver::simulate only: deterministic on a
#                                                    shared machine)
# ROCKING names a built binary (default: the release build, built first).
set -euo pipefail
cd "$(dirname "$0")/../.."
cost=false
case ${1:-} in
"") ;;
--cost) cost=true ;;
*)
    echo "usage: bash scenes/modes/convergence.sh [--cost]" >&2
    exit 2
    ;;
esac
if [ -z "${ROCKING:-}" ]; then
    cargo build --release -q -p rocking-cli
    ROCKING=$PWD/target/release/rocking
fi
work=$(mktemp -d /tmp/rocking-modes.XXXXXX)
trap 'rm -rf "$work"' EXIT

models=(cubic polynomial2 polynomial3)
chain=""
for n in 1 2 3 4 5 6 7 8; do
    models+=("cantilever_modes$n")
    chain+="${chain:+,}cantilever_modes$n"
done
# case name | scene | overrides (space-separated --set values)
cases=(
    "Fig. 3 with a column mass (γ_mc = 0.5)|scenes/fig3-vvel.toml|structure.gamma_mc=0.5"
    "Fig. 5 flexible (ω_n/p = 5)|scenes/fig5-flexible.toml|"
    "Fig. 5 stiff (ω_n/p = 20)|scenes/fig5-stiff.toml|"
    "Wind turbine, El Centro × 3 (SI)|scenes/wind-turbine-elcentro.toml|output.fixed_base_reference=true"
)
for case in "${cases[@]}"; do
    IFS='|' read -r name scene sets <<<"$case"
    echo
    echo "**$name** (\`$scene\`${sets:+, \`$sets\`})"
    echo
    echo "| model | n | ω_1, ω_2, ω_3 … ω_n (fixed base) | max θ/α | max u/u_cr | first impact | impacts | overturned | max M/(W B) | max V/W | max M_el/(W B) | fixed base: max M/(W B), ratio | steps | instructions per step |"
    echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
    for model in "${models[@]}"; do
        args=(run "$scene" --json --set "structure.model=$model" --set solver.accuracy=accurate
            --set output.plots=false)
        for s in $sets; do args+=(--set "$s"); done
        "$ROCKING" "${args[@]}" --out "$work/$model" >"$work/run.json"
        check=(check "$scene" --json --set "structure.model=$model")
        for s in $sets; do check+=(--set "$s"); done
        "$ROCKING" "${check[@]}" >"$work/check.json"
        per_step=""
        if $cost; then
            valgrind --tool=callgrind --callgrind-out-file="$work/cg.out" \
                "--toggle-collect=*driver::simulate*" "$ROCKING" "${args[@]}" \
                --out "$work/$model-cg" >/dev/null 2>"$work/cg.log"
            per_step=$(sed -n 's/^summary: *//p' "$work/cg.out")
        fi
        python3 - "$work/run.json" "$work/check.json" "$model" "$per_step" <<'PY'
import json, sys
run = json.load(open(sys.argv[1]))
check = json.load(open(sys.argv[2]))
model, instructions = sys.argv[3], sys.argv[4]
derived = check["derived"]
omega = derived.get("fixed_base_frequencies") or [derived["omega_n"]]
unit = "rad/s" if run["derived"].get("p_per_second") else "p"
def num(key, fmt):
    v = run.get(key)
    return "–" if v is None else format(v, fmt)
steps = run["solver_stats"]["steps"]
per = f"{int(instructions) / steps:,.0f}" if instructions else ""
print("| " + " | ".join([
    f"`{model}`", str(len(omega)),
    ", ".join(f"{w:.4g}" for w in omega[:3]) + (f" … {omega[-1]:.4g}" if len(omega) > 3 else "") + f" {unit}",
    num("max_theta_over_alpha", ".5f"), num("max_u_over_ucr", ".4f"),
    num("first_impact_time", ".5f"), str(run["impacts"]), "yes" if run["overturned"] else "no",
    num("max_base_moment_over_wb", ".4f"), num("max_base_shear_over_w", ".4f"),
    num("max_elastic_base_moment_over_wb", ".4f"),
    f"{run['fixed_base']['max_base_moment_over_wb']:.4f}, {run['base_moment_ratio']:.4f}"
    if run.get("fixed_base") else "–",
    str(steps), per]) + " |")
PY
    done
    conv=(convergence "$scene" --models "$chain" --set solver.accuracy=accurate --set output.plots=false)
    for s in $sets; do conv+=(--set "$s"); done
    echo
    echo '```'
    "$ROCKING" "${conv[@]}" --out "$work/convergence"
    echo '```'
done
