"""Checks of the Python peers' shared driver and of the heyoka peer's translations of the tapes.

    PYTHONPATH=derive .venv/bin/python -m unittest bench/test_peers.py

CI runs it with the derivation's .venv (numpy, CasADi): the shared driver's tests run there, the
heyoka translations skip unless `cargo xtask bench` has installed bench/requirements.txt.
"""

from __future__ import annotations

import math
import os
import sys
import unittest

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hybrid import LEFT, RIGHT, Case, Driver, Motion  # noqa: E402

VARIANTS = ("full", "point_mass", "rigid", "massless_column")
# h, b, EI, m, m_c, m_b, I_bc, zeta, g of the study's full-mass case (every VARIANTS member has them).
PARAMS = [0.9950041652780258, 0.09983341664682815, 10.144053190446806, 1.0, 1.0, 2.0,
          0.026577896211677828, 0.005, 1.0]


def case_dict(**over) -> dict:
    c = {"name": "test", "params": [1.0], "alpha": 0.2, "p": 2.0, "u_scale": 1e-3, "ud_scale": 1e-2,
         "t_end": 1.0, "overturn_angle": 1.5, "rest_rate": 1e-4, "impact": "vvel",
         "initial": [0.0, 0.0, 0.0, 0.0]}
    c.update(over)
    return c


class Quadratic:
    """A fake physics: kinetic energy theta'^2 + u'^2 (plus `rest`), maps returning given outputs."""

    def __init__(self, outputs: dict, rest: float = 0.0):
        self.outputs, self.rest = outputs, rest

    def fields(self, name):
        return list(self.outputs[name])

    def impact(self, name, u, u_dot, theta_dot, s):
        return list(self.outputs[name].values())

    def kinetic(self, x, s):
        return x[2] ** 2 + x[3] ** 2 + self.rest


class EnergyCap(unittest.TestCase):
    def driver(self, outputs, rest=0.0, **case):
        return Driver(Case(case_dict(**case)), Quadratic(outputs, rest), None)

    def test_a_gaining_map_keeps_the_pre_impact_kinetic_energy(self):
        # Housner on a deformable column: rocking on with more kinetic energy than before.
        # Energies include the fake's rest part 0.01: 0.04 of motion before, 0.25 after.
        d = self.driver({"impact_housner": {"theta_dot": -0.3, "u_dot": 0.4, "energy_after": 0.26,
                                            "energy_before": 0.05}}, rest=0.01, impact="housner")
        phase = d.impact(0.1, RIGHT, 0.0, 0.0, 0.2)
        _, t, s2, x, n = phase
        self.assertEqual((t, s2, n), (0.1, LEFT, 1))
        self.assertAlmostEqual(x[2] ** 2 + x[3] ** 2, 0.04, delta=1e-15)
        self.assertAlmostEqual(x[2] / x[3], -0.3 / 0.4, delta=1e-15)  # the direction is kept
        self.assertEqual(d.energy_capped, 1)

    def test_a_map_that_loses_energy_is_not_touched(self):
        d = self.driver({"impact_vvel": {"rock": 0.0, "theta_dot": 0.0, "u_dot": 0.1,
                                         "energy_after": 0.01, "energy_before": 0.04}})
        self.assertEqual(d.impact(0.1, RIGHT, 0.0, 0.0, 0.2), ("contact", 0.1, 0.0, 0.1, False))
        self.assertEqual(d.energy_capped, 0)

    def test_the_energy_cap_short_circuit_agrees_with_the_full_test(self):
        # without_energy_gain skips the rest energy when e_after <= e_before: the full test
        # (subtracting the rest energy from both) must never find a gain there.
        rng = np.random.default_rng(1)
        d = self.driver({})
        for _ in range(20000):
            e_before, rest = rng.uniform(-1, 1, 2) * 10.0 ** rng.integers(-12, 3, 2)
            e_after = e_before - abs(e_before * rng.normal()) * 10.0 ** rng.integers(-17, 0)
            t_before, t_after = e_before - rest, e_after - rest
            self.assertFalse(t_after > t_before * (1.0 + 1e-9) and t_after > 0.0)
            self.assertEqual(d.without_energy_gain(("contact", 1.0), e_after, e_before, 0.0, 1.0), ("contact", 1.0))

    def test_adjex_takes_the_least_gain_when_every_candidate_gains(self):
        out = {"impact_adjex": {"u_dot_contact": 0.1, "energy_contact": 0.09, "theta_dot_rocking": -0.2,
                                "u_dot_rocking": 0.0, "energy_rocking": 0.08, "energy_before": 0.04,
                                "u_dot_momentum": 0.3, "energy_momentum": 0.07}}
        d = self.driver(out, impact="adjex")
        _, _, _, u_dot, settle = d.impact(0.1, RIGHT, 0.0, 0.0, 0.2)
        # momentum (0.07) has the least gain; its u' is then capped to keep 0.04.
        self.assertAlmostEqual(u_dot, 0.3 * math.sqrt(0.04 / 0.07), delta=1e-15)
        self.assertEqual(d.energy_capped, 1)
        self.assertFalse(settle)

    def test_a_negligible_rocking_rate_is_a_rest_not_an_impact(self):
        d = self.driver({})
        phase = d.impact(0.5, RIGHT, 1e-4, 0.3, 1e-6)
        self.assertEqual(phase, ("contact", 0.5, 1e-4, 0.3, True))
        self.assertEqual((d.impact_count, len(d.all_impacts), d.impacts), (0, 1, []))


class Excitation(unittest.TestCase):
    def test_next_stop_is_the_first_kink_after_t(self):
        m = Motion({"kind": "record", "dt": 0.01, "samples": [0.0, 1.0, -1.0, 0.5, 0.0]})
        self.assertEqual(m.next_stop(0.0, 1.0), 0.01)
        self.assertEqual(m.next_stop(0.01, 1.0), 0.02)  # not t itself
        self.assertEqual(m.next_stop(0.015, 1.0), 0.02)
        self.assertEqual(m.next_stop(0.04, 1.0), 1.0)
        self.assertEqual(m.next_stop(0.0, 0.005), 0.005)


class TapeTranslations(unittest.TestCase):
    """The heyoka peer's straight-line Python functions and heyoka expressions, against CasADi."""

    @classmethod
    def setUpClass(cls):
        try:
            import heyoka_peer
        except ImportError as e:  # heyoka not installed
            raise unittest.SkipTest(f"heyoka peer not importable: {e}")
        cls.hp = heyoka_peer

    def test_the_tolerance_grid_has_one_tolerance_per_heyoka_order(self):
        tols = self.hp.grid_tols(5, 12)
        self.assertEqual(tols, [1e-5, 3e-6, 3e-7, 1e-7, 1e-8, 1e-9, 1e-10, 3e-11, 3e-12])
        self.assertEqual([self.hp.heyoka_order(t) for t in tols], list(range(7, 16)))
        x, v = self.hp.hy.make_vars("x", "v")
        for tol in (3e-6, 1e-6, 3e-9, 1e-8):  # heyoka's own order, both ends of an order's range
            ta = self.hp.hy.taylor_adaptive([(x, v), (v, -x)], [0.0, 1.0], tol=tol)
            self.assertEqual(ta.order, self.hp.heyoka_order(tol), f"tol {tol:g}")

    def inputs(self, f, rng):
        """A plausible point: the full-mass case's structure (fig5-flexible), small states, s = +-1."""
        def one(name, n):
            if name == "p":
                return np.array(PARAMS)
            if name == "s":
                return rng.choice([-1.0, 1.0], 1)
            if name == "eta":
                return rng.uniform(0, 1, 1)
            return rng.uniform(-0.05, 0.05, n)
        return [one(f.name_in(i), f.size1_in(i)) for i in range(f.n_in())]

    def test_python_functions_match_casadi_on_every_kernel(self):
        rng = np.random.default_rng(7)
        for name in VARIANTS:
            model = self.hp.Model(name)
            for kname, f in model.f.items():
                fn = self.hp.python_function(f)
                for _ in range(5):
                    args = self.inputs(f, rng)
                    want = np.asarray(f(*args)).ravel()
                    got = np.array(fn(*[a.tolist() for a in args]))
                    with self.subTest(variant=name, kernel=kname):
                        np.testing.assert_allclose(got, want, rtol=1e-13, atol=1e-13)

    def test_heyoka_expressions_match_casadi_on_the_impact_maps(self):
        # The maps use sign and fabs, which the replay builds from heyoka's select.
        hy = self.hp.hy
        rng = np.random.default_rng(8)
        for name in VARIANTS:
            model = self.hp.Model(name)
            for kname in ("impact_vvel", "impact_adjex", "impact_housner", "uplift", "rocking_rhs"):
                f = model.f[kname]
                syms = [[hy.expression(f"x{i}_{j}") for j in range(f.size1_in(i))] for i in range(f.n_in())]
                flat = [v for group in syms for v in group]
                cf = hy.cfunc(self.hp.replay(f, syms), flat)
                for _ in range(5):
                    args = self.inputs(f, rng)
                    want = np.asarray(f(*args)).ravel()
                    got = cf(np.concatenate(args))
                    with self.subTest(variant=name, kernel=kname):
                        finite = np.isfinite(want)
                        np.testing.assert_array_equal(np.isfinite(got), finite)
                        np.testing.assert_allclose(got[finite], want[finite], rtol=1e-12, atol=1e-13)


if __name__ == "__main__":
    unittest.main()
