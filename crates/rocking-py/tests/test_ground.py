"""Compliant ground (issue 44) from Python: a run's ground columns and keys, and the ground's
keys reported by spectra and batches, equal to the command's outputs bit for bit.

The command is found as in test_rocking.py (ROCKING_CLI, else target/debug/rocking).
"""

import csv
import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import rocking

REPO = Path(__file__).resolve().parents[3]
CLI = os.environ.get("ROCKING_CLI", str(REPO / "target" / "debug" / "rocking"))
GROUND = REPO / "scenes" / "ground-winkler.toml"
GROUND_KEYS = [
    "max_ground_pressure_over_mean",
    "min_ground_pressure_over_mean",
    "min_contact_fraction",
    "lift_offs",
    "max_settlement_over_static",
    "ground_energy_dissipated",
]
REPORT = "sweep.report=[" + ", ".join(json.dumps(k) for k in GROUND_KEYS) + "]"


def cli(*args: str) -> str:
    done = subprocess.run([CLI, *args], capture_output=True, text=True, cwd=REPO)
    assert done.returncode == 0, done.stderr
    return done.stdout


def read_csv(path: Path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_a_ground_run_has_the_commands_ground_columns_and_keys(tmp_path):
    out = tmp_path / "run"
    expected = json.loads(cli("run", "--json", str(GROUND), "--out", str(out)))
    result = rocking.load_scene(GROUND).run()
    s = result.summary
    for k in GROUND_KEYS:
        assert getattr(s, k) == expected[k], k
    assert s.lift_offs > 0 and 0.0 < s.min_contact_fraction < 1.0
    history = result.history
    rows = read_csv(out / "history.csv")
    assert len(rows) == len(history["tau"]) > 100
    for col in ["settlement_over_static", "contact_fraction", "ground_pressure_over_mean",
                "least_ground_pressure_over_mean"]:
        want = np.array([float(r[col]) for r in rows])
        assert np.array_equal(history[col], want), col
    # The run lifted off the bed: some rows have part of the base in the air.
    assert history["contact_fraction"].min() < 1.0


def test_a_ground_spectrum_reports_the_ground_keys_as_the_command(tmp_path):
    axes = ["ground.omega_v_over_p=20,200", "excitation.amplitude=0.8,1.3"]
    out = tmp_path / "spectrum"
    args = ["spectrum", str(GROUND), "--quiet", "--out", str(out), "--set", REPORT]
    for a in axes:
        args += ["--axis", a]
    cli(*args)
    rows = read_csv(out / "cells.csv")
    scene = rocking.load_scene(GROUND, set=[REPORT])
    sp = rocking.spectrum(scene, axes=axes, threads=1)
    assert sp.keys == ["ground.omega_v_over_p", "excitation.amplitude"]
    assert sorted(sp.reported) == sorted(GROUND_KEYS)
    flat = {k: v.ravel() for k, v in sp.reported.items()}
    for i, r in enumerate(rows):
        assert sp.classes.ravel()[i] == r["class"]
        assert sp.max_theta_over_alpha.ravel()[i] == float(r["max_theta_over_alpha"])
        for k in GROUND_KEYS:
            assert flat[k][i] == float(r[k]), (i, k)
    # ω_v/p is not ignored: the stiffer bed presses harder under the lifted base.
    p = sp.reported["max_ground_pressure_over_mean"]
    assert not np.array_equal(p[0], p[1])


def test_a_time_of_an_event_that_did_not_happen_is_masked_as_the_command_leaves_it_empty(tmp_path):
    sets = ['sweep.report=["first_bearing_exceeded_time", "first_uplift_time"]',
            "effects.bearing_over_mean=3"]
    axes = ["effects.bearing_over_mean=2,50", "excitation.amplitude=0.3,1.3"]
    out = tmp_path / "bearing"
    args = ["spectrum", str(GROUND), "--quiet", "--out", str(out)]
    for s in sets:
        args += ["--set", s]
    for a in axes:
        args += ["--axis", a]
    cli(*args)
    rows = read_csv(out / "cells.csv")
    sp = rocking.spectrum(rocking.load_scene(GROUND, set=sets), axes=axes, threads=1)
    masked = 0
    for k in ["first_bearing_exceeded_time", "first_uplift_time"]:
        flat = sp.reported[k].ravel()
        for i, r in enumerate(rows):
            if r[k] == "":
                assert flat.mask[i], (i, k)
                masked += 1
            else:
                assert not flat.mask[i] and flat[i] == float(r[k]), (i, k)
    # The bearing of 50 mean pressures is never exceeded at either amplitude.
    assert masked == 2
    kinds = {q["key"]: q for q in rocking.columns()["reportable"]}
    assert kinds["first_bearing_exceeded_time"]["nullable"]
    assert kinds["first_bearing_exceeded_time"]["needs"] == ["ground", "bearing"]
    assert kinds["impacts"]["needs"] == [] and not kinds["impacts"]["nullable"]


def turbine_on_ground(directory: Path) -> Path:
    """The wind turbine's record scene on a Winkler bed (no rigid-surface impact map)."""
    text = (REPO / "scenes" / "wind-turbine-msa.toml").read_text()
    record = (REPO / "scenes" / "records" / "elCentro.AT2").resolve()
    text = text.replace('[effects]\nimpact = "vvel"\n', "").replace(
        'path = "records/elCentro.AT2"', f"path = {json.dumps(str(record))}"
    )
    assert "vvel" not in text
    text += '\n[ground]\nkind = "winkler"\nomega_v_over_p = 30.0\nzeta_v = 0.05\n'
    path = directory / "turbine-ground.toml"
    path.write_text(text)
    return path


def test_a_ground_batch_reports_the_ground_keys_as_the_command(tmp_path):
    scene = turbine_on_ground(tmp_path)
    record = str((REPO / "scenes" / "records" / "elCentro.AT2").resolve())
    out = tmp_path / "batch"
    cli("batch", str(scene), "--records", record, "--scales", "1,4", "--quiet",
        "--set", REPORT, "--out", str(out))
    rows = read_csv(out / "runs.csv")
    b = rocking.batch(rocking.load_scene(scene, set=[REPORT]), records=[record],
                      scales=[1.0, 4.0], threads=1)
    assert b.reported["lift_offs"].shape == (1, 2)
    for j, r in enumerate(rows):
        assert b.classes[0, j] == r["class"]
        for k in GROUND_KEYS:
            assert b.reported[k][0, j] == float(r[k]), (j, k)


def test_a_rigid_scene_goes_on_a_bed_with_none_removing_its_impact_map(tmp_path):
    """``{"effects.impact": None}`` removes the key, as the command's ``effects.impact=null``:
    the run equals the command's; a key the scene lacks is refused as bad input."""
    scene = REPO / "scenes" / "fig5-flexible.toml"
    bed = {"ground.kind": "winkler", "ground.omega_v_over_p": 50, "ground.zeta_v": 0.05}
    sets = [f"--set={k}={v}" for k, v in bed.items()]
    expected = json.loads(cli("run", "--json", str(scene), "--out", str(tmp_path / "run"),
                              *sets, "--set=effects.impact=null"))
    s = rocking.load_scene(scene, {**bed, "effects.impact": None}).run().summary
    assert s.lift_offs == expected["lift_offs"] > 0
    for k in GROUND_KEYS + ["max_base_moment_over_wb", "max_theta_over_alpha"]:
        assert getattr(s, k) == expected[k], k
    with pytest.raises(ValueError, match="effects.impact"):
        rocking.load_scene(scene, bed)
    with pytest.raises(ValueError, match="nothing to remove"):
        rocking.load_scene(scene, {"effects.impcat": None})
