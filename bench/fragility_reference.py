"""Synthetic fragility data and their SciPy maximum-likelihood fits.

Writes crates/rocking-fragility/tests/fixtures/fragility_reference.json, read by
crates/rocking-fragility/tests/fit.rs. Run from the repository root:

    python3 -m venv .venv-im && .venv-im/bin/pip install scipy==1.17.1 numpy==2.4.6
    .venv-im/bin/python bench/fragility_reference.py

The data are drawn here (numpy, seeded) from known lognormal curves, and fitted
by scipy.optimize.minimize (Nelder-Mead on (ln theta, ln beta), tight tolerances)
of the negative log-likelihood, independently of the Rust code:
- capacities: -sum log lognormal pdf (scipy.stats.lognorm.logpdf, s = beta,
  scale = theta), i.e. the IDA fit;
- stripes: -sum [z log Phi(eta) + (n - z) log Phi(-eta)], eta = ln(x/theta)/beta
  (scipy.stats.norm.logcdf), the binomial likelihood of Baker (2015) without its
  constant.
"""

import json
import pathlib

import numpy as np
import scipy
from scipy import optimize, stats

ROOT = pathlib.Path(__file__).resolve().parent.parent
OUT = ROOT / "crates" / "rocking-fragility" / "tests" / "fixtures" / "fragility_reference.json"


def fit(nll, start):
    best = None
    for s in start:
        r = optimize.minimize(
            nll, s, method="Nelder-Mead",
            options={"xatol": 1e-13, "fatol": 1e-15, "maxiter": 20000, "maxfev": 40000},
        )
        if best is None or r.fun < best.fun:
            best = r
    return float(np.exp(best.x[0])), float(np.exp(best.x[1]))


def main():
    rng = np.random.default_rng(20021)
    # IDA capacities: theta = 1.2, beta = 0.4, 40 records
    cap_true = {"theta": 1.2, "beta": 0.4}
    caps = cap_true["theta"] * np.exp(cap_true["beta"] * rng.standard_normal(40))

    def nll_caps(p):
        return -np.sum(stats.lognorm.logpdf(caps, s=np.exp(p[1]), scale=np.exp(p[0])))

    cap_fit = fit(nll_caps, [[0.0, np.log(0.5)], [np.log(2.0), np.log(1.0)]])

    # multiple stripes: theta = 1.0, beta = 0.5, 9 levels x 40 records
    msa_true = {"theta": 1.0, "beta": 0.5}
    ims = np.array([0.25, 0.4, 0.6, 0.8, 1.0, 1.25, 1.6, 2.0, 2.6])
    n = np.full(len(ims), 40)
    z = rng.binomial(n, stats.norm.cdf(np.log(ims / msa_true["theta"]) / msa_true["beta"]))

    def nll_msa(p):
        eta = np.log(ims / np.exp(p[0])) / np.exp(p[1])
        return -np.sum(z * stats.norm.logcdf(eta) + (n - z) * stats.norm.logcdf(-eta))

    msa_fit = fit(nll_msa, [[0.0, np.log(0.5)], [np.log(2.0), np.log(1.0)]])

    out = {
        "generated_by": ".venv-im/bin/python bench/fragility_reference.py "
        f"(numpy {np.__version__}, scipy {scipy.__version__}; scipy.optimize.minimize Nelder-Mead)",
        "capacities": {
            "true": cap_true,
            "data": [float(c) for c in caps],
            "scipy": {"theta": cap_fit[0], "beta": cap_fit[1]},
        },
        "stripes": {
            "true": msa_true,
            "im": [float(x) for x in ims],
            "n": [int(x) for x in n],
            "collapsed": [int(x) for x in z],
            "scipy": {"theta": msa_fit[0], "beta": msa_fit[1]},
        },
    }
    OUT.parent.mkdir(parents=True, exist_ok=True)
    OUT.write_text(json.dumps(out, indent=1) + "\n")
    print(json.dumps({k: out[k]["scipy"] for k in ("capacities", "stripes")}), "\nwrote", OUT)


if __name__ == "__main__":
    main()
