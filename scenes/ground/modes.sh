#!/usr/bin/env bash
# Issue 44, study 2 (docs/ground.md): docs/modes.md's convergence study repeated on compliant
# ground. Does the peak base moment's growth with the number of cantilever modes shrink when the
# impacts are no longer rigid? Each case runs `rocking convergence` over cubic and
# cantilever_modes1 .. cantilever_modes8 at the `accurate` preset, on the rigid surface (VVEL
# impacts) and on tensionless Winkler beds (ζ_v = 0.05; ω_v/p = 50 and 200 for the dimensionless
# cases, the footing of scenes/ground/turbine-elcentro.toml for the wind turbine), and prints one
# markdown table per case.
# Usage: bash scenes/ground/modes.sh        (ROCKING names a built binary; default: release)
set -euo pipefail
cd "$(dirname "$0")/../.."
if [ -z "${ROCKING:-}" ]; then
    cargo build --release -q -p rocking-cli
    ROCKING=$PWD/target/release/rocking
fi
work=$(mktemp -d /tmp/rocking-ground-modes.XXXXXX)
trap 'rm -rf "$work"' EXIT

models=cubic
for n in 1 2 3 4 5 6 7 8; do models+=",cantilever_modes$n"; done
quantities=max_theta_over_alpha,impacts,max_base_moment_over_wb,max_base_shear_over_w

# A rigid-surface scene goes on a bed by overrides: without its impact map, with a [ground] table.
bed="effects.impact=null ground.kind=winkler ground.zeta_v=0.05 ground.omega_v_over_p"

# case | ground | scene | overrides (space-separated --set values)
runs=(
    "Fig. 3, γ_mc = γ_mb = 0.5|rigid (VVEL)|scenes/fig3-vvel.toml|structure.gamma_mc=0.5 structure.gamma_mb=0.5"
    "Fig. 3, γ_mc = γ_mb = 0.5|bed ω_v/p = 50|scenes/ground-winkler.toml|structure.gamma_mc=0.5 ground.omega_v_over_p=50"
    "Fig. 3, γ_mc = γ_mb = 0.5|bed ω_v/p = 200|scenes/ground-winkler.toml|structure.gamma_mc=0.5 ground.omega_v_over_p=200"
    "Fig. 5 flexible (ω_n/p = 5)|rigid (VVEL)|scenes/fig5-flexible.toml|"
    "Fig. 5 flexible (ω_n/p = 5)|bed ω_v/p = 50|scenes/fig5-flexible.toml|$bed=50"
    "Fig. 5 flexible (ω_n/p = 5)|bed ω_v/p = 200|scenes/fig5-flexible.toml|$bed=200"
    "Fig. 5 stiff (ω_n/p = 20)|rigid (VVEL)|scenes/fig5-stiff.toml|"
    "Fig. 5 stiff (ω_n/p = 20)|bed ω_v/p = 50|scenes/fig5-stiff.toml|$bed=50"
    "Fig. 5 stiff (ω_n/p = 20)|bed ω_v/p = 200|scenes/fig5-stiff.toml|$bed=200"
    "Wind turbine, El Centro × 3|rigid (VVEL)|scenes/wind-turbine-elcentro.toml|output.fixed_base_reference=true"
    "Wind turbine, El Centro × 3|bed G = 60 MPa (ω_v/p = 231)|scenes/ground/turbine-elcentro.toml|"
)
last=""
i=0
for run in "${runs[@]}"; do
    IFS='|' read -r name ground scene sets <<<"$run"
    i=$((i + 1))
    args=(convergence "$scene" --models "$models" --set solver.accuracy=accurate
        --set output.plots=false --out "$work/$i")
    q=$quantities
    case $scene in *turbine*) q+=",base_moment_ratio" ;; esac
    args+=(--quantities "$q")
    for s in $sets; do args+=(--set "$s"); done
    "$ROCKING" "${args[@]}" >"$work/$i.txt" 2>"$work/$i.err" || {
        cat "$work/$i.err" >&2
        exit 1
    }
    if [ "$name" != "$last" ]; then
        echo
        echo "**$name**"
        echo
        case $scene in
        *turbine*) echo "| ground | M_b/(W B): n = 1 (cubic), 3, 8 | growth 1 → 8 | M_b converged to 1 % from | V_b/W: n = 1, 3, 8 | V_b converged from | max θ/α, n = 8 | impacts (landings), n = 1 / 8 | M_b over its twin's: n = 1, 3, 8 |" ;
            echo "|---|---|---|---|---|---|---|---|---|" ;;
        *) echo "| ground | M_b/(W B): n = 1 (cubic), 3, 8 | growth 1 → 8 | M_b converged to 1 % from | V_b/W: n = 1, 3, 8 | V_b converged from | max θ/α, n = 8 | impacts (landings), n = 1 / 8 |" ;
            echo "|---|---|---|---|---|---|---|---|" ;;
        esac
        last=$name
    fi
    python3 - "$work/$i/convergence.json" "$ground" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
names = [m["name"] for m in d["models"]]
q = {x["name"]: x for x in d["quantities"]}
def at(key, model):
    return q[key]["values"][names.index(model)]
def conv(key):
    x = q[key]
    return f"n = {x['converged_n']}" if x.get("converged_n") else "not converged"
m = [at("max_base_moment_over_wb", k) for k in ("cubic", "cantilever_modes3", "cantilever_modes8")]
v = [at("max_base_shear_over_w", k) for k in ("cubic", "cantilever_modes3", "cantilever_modes8")]
row = [sys.argv[2], ", ".join(f"{x:.3f}" for x in m), f"{100 * (m[2] / m[0] - 1):+.0f} %",
       conv("max_base_moment_over_wb"), ", ".join(f"{x:.3f}" for x in v),
       conv("max_base_shear_over_w"), f"{at('max_theta_over_alpha', 'cantilever_modes8'):.3f}",
       f"{at('impacts', 'cubic'):.0f} / {at('impacts', 'cantilever_modes8'):.0f}"]
if "base_moment_ratio" in q:
    row.append(", ".join(f"{at('base_moment_ratio', k):.3f}"
                         for k in ("cubic", "cantilever_modes3", "cantilever_modes8")))
print("| " + " | ".join(row) + " |")
PY
done
