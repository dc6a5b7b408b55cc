"""Independent reference values for rocking_motion::intensity on real PEER records.

Writes crates/rocking-motion/tests/fixtures/im_reference.json, read by the test
crates/rocking-motion/tests/intensity.rs. Run from the repository root:

    python3 -m venv .venv-im && .venv-im/bin/pip install scipy==1.17.1 numpy==2.4.6
    .venv-im/bin/python bench/im_reference.py

What each reference computes (acceleration a = samples x 9.80665 m/s^2, taken as
the piecewise-linear interpolant of its samples from rest, as the Rust code does):

- PGA: max |a| (numpy).
- PGV, PGD: v and d at the samples by scipy.signal.lsim of the double integrator
  (x' = [v, a], linear interpolation of the input: exact, by matrix exponential),
  plus the extrema inside a step: a = 0 (linear) for v, v = 0 (quadratic, roots by
  numpy.roots per step) for d, each evaluated from the step's polynomial.
- Arias: pi/(2g) * scipy.integrate.simpson of a^2 on the grid refined by the step
  midpoints (Simpson is exact for the quadratic a^2 of each step).
- D5-95: cumulative integral of a^2 at the samples (Simpson per step, as above);
  the crossings of 5 % and 95 % solved inside their step by scipy.optimize.brentq.
- Tm: numpy.fft.rfft of the n samples, frequencies 0.25-20 Hz (Rathje et al. 1998).
- Spectral: scipy.signal.lsim of u'' + 2 zeta w u' + w^2 u = -a (linear
  interpolation of the input: exact); Sd = max|u|, Sv = max|u'|,
  Sa = max|2 zeta w u' + w^2 u| over the samples, PSA = w^2 Sd.
"""

import json
import pathlib

import numpy as np
import scipy
from scipy import integrate, optimize, signal

G = 9.80665
ROOT = pathlib.Path(__file__).resolve().parent.parent
DATA = ROOT.parent / "shared" / "data" / "ground-motions"
OUT = ROOT / "crates" / "rocking-motion" / "tests" / "fixtures" / "im_reference.json"
RECORDS = ["elCentro.AT2", "ARL360.at2", "A-TIN000.AT2", "RIO270.AT2", "EIL-EW.AT2", "BAR315.AT2"]
PERIODS = [0.1, 0.5, 1.0, 2.0, 4.5]
DAMPINGS = [0.0, 0.05, 0.2]


def read_at2(path):
    lines = path.read_bytes().decode().split("\n")  # not splitlines: some files end lines with CR CR LF
    head = lines[3].upper().replace(",", " ").replace("=", " ").split()
    npts = int(head[head.index("NPTS") + 1])
    dt = float(head[head.index("DT") + 1])
    vals = np.array([float(x) for line in lines[4:] for x in line.replace(",", " ").split()])
    assert len(vals) == npts, path
    return dt, vals * G


def peaks_v_d(dt, a):
    n = len(a)
    t = np.arange(n) * dt
    sys = signal.StateSpace([[0.0, 1.0], [0.0, 0.0]], [[0.0], [1.0]], np.eye(2), [[0.0], [0.0]])
    _, _, x = signal.lsim(sys, a, t, interp=True)
    d, v = x[:, 0], x[:, 1]
    pgv, pgd = np.max(np.abs(v)), np.max(np.abs(d))
    c = np.diff(a) / dt
    # v inside a step: vertex where a = 0
    k = np.nonzero(a[:-1] * a[1:] < 0)[0]
    s = -a[k] / c[k]
    if len(k):
        pgv = max(pgv, np.max(np.abs(v[k] + a[k] * s + 0.5 * c[k] * s**2)))
    # d inside a step: roots of v(s) = v_k + a_k s + c_k s^2 / 2
    for i in range(n - 1):
        for r in np.roots([0.5 * c[i], a[i], v[i]]) if c[i] != 0 else ([-v[i] / a[i]] if a[i] else []):
            if np.isreal(r) and 0 < r.real < dt:
                s = r.real
                pgd = max(pgd, abs(d[i] + v[i] * s + a[i] * s**2 / 2 + c[i] * s**3 / 6))
    return pgv, pgd


def cumulative_a2(dt, a):
    mid = 0.5 * (a[:-1] + a[1:])
    steps = dt / 6.0 * (a[:-1] ** 2 + 4 * mid**2 + a[1:] ** 2)  # Simpson, exact per step
    return np.concatenate([[0.0], np.cumsum(steps)])


def arias(dt, a):
    fine = np.empty(2 * len(a) - 1)
    fine[0::2] = a
    fine[1::2] = 0.5 * (a[:-1] + a[1:])
    return np.pi / (2 * G) * integrate.simpson(fine**2, dx=dt / 2)


def d5_95(dt, a):
    cum = cumulative_a2(dt, a)
    total = cum[-1]

    def first_time(level):
        k = int(np.searchsorted(cum, level, side="left")) - 1
        k = max(k, 0)
        c = (a[k + 1] - a[k]) / dt
        f = lambda s: cum[k] + a[k] ** 2 * s + a[k] * c * s**2 + c**2 * s**3 / 3 - level
        return k * dt + optimize.brentq(f, 0.0, dt, xtol=1e-15, rtol=4 * np.finfo(float).eps)

    return first_time(0.95 * total) - first_time(0.05 * total)


def mean_period(dt, a):
    amp2 = np.abs(np.fft.rfft(a)) ** 2
    f = np.fft.rfftfreq(len(a), dt)
    band = (f >= 0.25) & (f <= 20.0)
    return np.sum(amp2[band] / f[band]) / np.sum(amp2[band])


def spectral(dt, a, period, zeta):
    w = 2 * np.pi / period
    t = np.arange(len(a)) * dt
    A = [[0.0, 1.0], [-(w**2), -2 * zeta * w]]
    C = [[1.0, 0.0], [0.0, 1.0], [w**2, 2 * zeta * w]]
    sys = signal.StateSpace(A, [[0.0], [-1.0]], C, [[0.0], [0.0], [0.0]])
    _, y, _ = signal.lsim(sys, a, t, interp=True)
    sd = np.max(np.abs(y[:, 0]))
    return {
        "period": period,
        "damping": zeta,
        "sd_m": sd,
        "sv_m_s": np.max(np.abs(y[:, 1])),
        "sa_m_s2": np.max(np.abs(y[:, 2])),
        "psa_m_s2": w**2 * sd,
    }


def main():
    out = {
        "generated_by": ".venv-im/bin/python bench/im_reference.py "
        f"(numpy {np.__version__}, scipy {scipy.__version__})",
        "units": "accelerations m/s^2 (samples in g x 9.80665), velocities m/s, displacements m, "
        "Arias m/s, times s",
        "records": [],
    }
    for name in RECORDS:
        dt, a = read_at2(DATA / name)
        pgv, pgd = peaks_v_d(dt, a)
        out["records"].append(
            {
                "file": name,
                "pga_m_s2": float(np.max(np.abs(a))),
                "pgv_m_s": float(pgv),
                "pgd_m": float(pgd),
                "arias_m_s": float(arias(dt, a)),
                "d5_95_s": float(d5_95(dt, a)),
                "mean_period_s": float(mean_period(dt, a)),
                "spectral": [
                    {k: float(v) for k, v in spectral(dt, a, T, z).items()}
                    for T in PERIODS
                    for z in DAMPINGS
                ],
            }
        )
        print(name, "done")
    OUT.parent.mkdir(parents=True, exist_ok=True)
    OUT.write_text(json.dumps(out, indent=1) + "\n")
    print("wrote", OUT)


if __name__ == "__main__":
    main()
