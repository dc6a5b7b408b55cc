"""Tests of the installed `rocking` package against the `rocking` command.

The command is found through ROCKING_CLI (set by .ci/python.sh), else target/debug/rocking
(the build `cargo test` makes for the command's own tests).
Scenes are read from the repository this file belongs to.
"""

import csv
import json
import re
import os
import subprocess
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import rocking

REPO = Path(__file__).resolve().parents[3]
CLI = os.environ.get("ROCKING_CLI", str(REPO / "target" / "debug" / "rocking"))
SCENES = sorted((REPO / "scenes").glob("*.toml"))
FIG3 = REPO / "scenes" / "fig3-vvel.toml"
FIG8 = REPO / "scenes" / "spectra" / "fig8.toml"
SMALL_AXES = ["excitation.omega_p_over_p=2:6:3", "excitation.amplitude=2:8:4"]


def cli(*args: str) -> str:
    """Runs the command, returns its standard output (fails the test on a non-zero exit)."""
    done = subprocess.run([CLI, *args], capture_output=True, text=True, cwd=REPO)
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_the_scenes_are_found():
    assert len(SCENES) >= 5, SCENES


@pytest.mark.parametrize("scene", SCENES, ids=lambda p: p.name)
def test_summary_equals_the_commands_json(scene, tmp_path):
    expected = json.loads(cli("run", "--json", str(scene), "--out", str(tmp_path / "out")))
    got = rocking.load_scene(str(scene)).run().summary.to_dict()
    assert got == expected


def test_summary_attributes_are_the_dicts_fields():
    s = rocking.load_scene(FIG3).run().summary
    d = s.to_dict()
    assert s.max_theta_over_alpha == d["max_theta_over_alpha"]
    assert s.impacts == d["impacts"] and s.impacts > 0
    assert s.derived["alpha"] == 0.2


def test_an_unbounded_required_friction_is_infinity():
    """Fig. 3 (VVEL): R_v falls below zero, so no friction holds the base there; the JSON's
    "inf" is float('inf') as an attribute, and the dict keeps the command's "inf"."""
    s = rocking.load_scene(FIG3).run().summary
    assert s.max_required_friction == float("inf")
    assert s.first_lift_off_time > 0.0
    assert s.to_dict()["max_required_friction"] == "inf"


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def same_field(got, text):
    """Whether a value Python returns is a CSV field the command wrote."""
    if text == "":
        return got is None or got == ""
    if isinstance(got, bool):
        return str(got).lower() == text
    if isinstance(got, str):
        return got == text
    return got == float(text)


@pytest.mark.parametrize("scene", SCENES, ids=lambda p: p.name)
def test_history_and_events_equal_the_commands_csv(scene, tmp_path):
    """Every example: Python's history and events are the command's history.csv and events.csv,
    column for column, and the columns are those `rocking.columns()` declares."""
    out = tmp_path / "out"
    cli("run", str(scene), "--out", str(out))
    result = rocking.load_scene(scene).run()
    if not (out / "history.csv").exists():
        assert result.history is None
        return
    rows = read_csv(out / "history.csv")
    h = result.history
    assert len(rows) == len(h["tau"]) > 1
    declared = [c["name"] for c in rocking.columns()["history"]]
    fixed = [n for n in rows[0] if not re.fullmatch(r"u(_dot)?_\d+", n)]
    assert fixed == [n for n in declared if n in fixed]
    for name in rows[0]:
        if name == "phase":
            assert list(h["phase"]) == [r["phase"] for r in rows]
        elif rows[0][name] == "":
            assert name not in h  # seconds of a dimensionless scene
        else:
            assert h[name].dtype == np.float64
            assert np.array_equal(h[name], [float(r[name]) for r in rows]), name
    if not (out / "events.csv").exists():
        return
    events = read_csv(out / "events.csv")
    with open(out / "events.csv") as f:
        header = f.readline().strip().split(",")
    assert header == [c["name"] for c in rocking.columns()["events"]]
    assert len(result.events) == len(events)
    for got, want in zip(result.events, events):
        assert all(same_field(got.get(k), v) for k, v in want.items()), (got, want)


def test_forces_and_the_fixed_base_twin():
    """The design forces of docs/design-forces.md, from Python: the wind turbine under El Centro
    rocks, which cuts its base moment below the fixed-base twin's; its shear peaks before uplift."""
    turbine = REPO / "scenes" / "wind-turbine-elcentro.toml"
    d = rocking.load_scene(str(turbine), set={"output.fixed_base_reference": True}).run()
    d = d.summary.to_dict()
    fixed = d["fixed_base"]
    assert d["base_moment_ratio"] == d["max_base_moment_over_wb"] / fixed["max_base_moment_over_wb"]
    assert 0.8 < d["base_moment_ratio"] < 0.9  # 0.854
    assert d["base_shear_ratio"] == 1.0
    assert 1.0 < d["max_base_moment_over_wb"] < fixed["max_base_moment_over_wb"]
    assert 0.0 < d["min_vertical_reaction_over_w"] < 1.0 and d["warnings"] == []
    h = rocking.load_scene(str(turbine)).run().history
    assert max(abs(h["base_moment_over_wb"])) <= d["max_base_moment_over_wb"] * (1 + 1e-12)


def test_dataframe():
    pd = pytest.importorskip("pandas")
    df = rocking.load_scene(FIG3).run().to_dataframe()
    assert isinstance(df, pd.DataFrame)
    assert df["theta_over_alpha"].abs().max() == pytest.approx(
        rocking.load_scene(FIG3).run().summary.max_theta_over_alpha, rel=1e-3
    )


def test_scene_from_toml_is_the_file():
    text = FIG3.read_text()
    a = rocking.Scene.from_toml(text, base_dir=FIG3.parent, name=FIG3.name).run()
    b = rocking.load_scene(FIG3).run()
    assert a.summary.to_dict() == b.summary.to_dict()


def test_overrides_as_dict_or_list_are_the_commands_set(tmp_path):
    expected = json.loads(
        cli("run", "--json", str(FIG3), "--set", "excitation.amplitude=1.2",
            "--out", str(tmp_path / "o"))
    )
    for s in ({"excitation.amplitude": 1.2}, ["excitation.amplitude=1.2"]):
        assert rocking.load_scene(str(FIG3), set=s).run().summary.to_dict() == expected


def test_spectrum_equals_the_commands_cells_csv(tmp_path):
    out = tmp_path / "spectrum"
    args = ["spectrum", str(FIG8), "--out", str(out), "--quiet"]
    for a in SMALL_AXES:
        args += ["--axis", a]
    cli(*args)
    rows = read_csv(out / "cells.csv")
    sp = rocking.spectrum(FIG8, axes=SMALL_AXES, threads=2)
    assert sp.keys == ["excitation.omega_p_over_p", "excitation.amplitude"]
    assert sp.classes.shape == (3, 4) and len(rows) == 12
    flat = list(zip(sp.classes.ravel(), sp.max_theta_over_alpha.ravel(), sp.impacts.ravel()))
    for (cls, mx, imp), r, (i, j) in zip(flat, rows, np.ndindex(3, 4)):
        assert cls == r["class"]
        assert mx == float(r["max_theta_over_alpha"])
        assert imp == int(r["impacts"])
        assert sp.axes[0][i] == float(r["excitation.omega_p_over_p"])
        assert sp.axes[1][j] == float(r["excitation.amplitude"])
        assert sp.class_names[sp.codes[i, j]] == cls
    assert sp.overturned.any() and not sp.overturned.all()
    assert sp.failures == []


def test_cells_beyond_the_model_are_their_own_class_as_in_the_command(tmp_path):
    """The Fig. 6 panel whose mass matrix turns singular: class `beyond-model`, masked values,
    listed apart from failures, the same cells as the command's cells.csv."""
    fig6 = REPO / "scenes" / "spectra" / "fig6.toml"
    axes = ["excitation.omega_p_over_p=3.5:4.3:5", "excitation.amplitude=17:21:5"]
    sets = ["--set", "structure.omega_n_over_p=2.5", "--set", "structure.alpha=0.2"]
    out = tmp_path / "fig6"
    cli("spectrum", str(fig6), "--out", str(out), "--quiet", *sets,
        "--axis", axes[0], "--axis", axes[1])
    rows = read_csv(out / "cells.csv")
    scene = rocking.load_scene(
        str(fig6), set={"structure.omega_n_over_p": 2.5, "structure.alpha": 0.2}
    )
    sp = rocking.spectrum(scene, axes=axes, threads=2)
    assert [r["class"] for r in rows] == sp.classes.ravel().tolist()
    beyond = sp.classes == "beyond-model"
    assert beyond.sum() >= 3 and sp.failures == []
    assert len(sp.beyond_model) == beyond.sum()
    assert (sp.without_result == beyond).all()
    assert sp.max_theta_over_alpha.mask[beyond].all()
    assert not sp.overturned[beyond].any()


def test_a_text_axis_gives_its_texts_and_the_commands_cells(tmp_path):
    scene = REPO / "scenes" / "fig5-flexible.toml"
    axes = ["structure.model=cubic,cantilever_modes2", "effects.impact=vvel,adjex"]
    out = tmp_path / "text"
    cli("spectrum", str(scene), "--out", str(out), "--quiet", "--axis", axes[0], "--axis", axes[1])
    rows = read_csv(out / "cells.csv")
    sp = rocking.spectrum(scene, axes=axes, threads=2)
    assert sp.axes[0].tolist() == ["cubic", "cantilever_modes2"]
    assert sp.axes[1].tolist() == ["vvel", "adjex"]
    got = [(m, i, float(x)) for (m, i), x in
           zip(np.ndindex(2, 2), sp.max_theta_over_alpha.ravel())]
    for (m, i, x), r in zip(got, rows):
        assert sp.axes[0][m] == r["structure.model"] and sp.axes[1][i] == r["effects.impact"]
        assert x == float(r["max_theta_over_alpha"])


def test_convergence_equals_the_commands_report(tmp_path):
    models = ["cubic", "cantilever_modes2", "cantilever_modes3"]
    out = tmp_path / "convergence"
    cli("convergence", str(FIG3), "--models", ",".join(models), "--set", "structure.gamma_mc=0.5",
        "--out", str(out))
    expected = json.loads((out / "convergence.json").read_text())
    scene = rocking.load_scene(str(FIG3), set={"structure.gamma_mc": 0.5})
    got = rocking.convergence(scene, models, threads=2)
    assert got == expected
    assert [m["n"] for m in got["models"]] == [1, 2, 3]
    with pytest.raises(ValueError, match="from 2 to 64 models"):
        rocking.convergence(scene, ["cubic"])


def test_batch_is_the_scene_run_per_record_and_scale(tmp_path):
    scene = REPO / "scenes" / "wind-turbine-elcentro.toml"
    record = REPO / "scenes" / "records" / "elCentro.AT2"
    b = rocking.batch(scene, records=[record], scales=[0.5, 2.0], threads=2)
    assert b.record_names == ["elCentro.AT2"] and list(b.scales) == [0.5, 2.0]
    assert b.classes.shape == (1, 2)
    for j, s in enumerate(b.scales):
        one = rocking.load_scene(scene, set={"excitation.scale": float(s)}).run().summary
        assert bool(b.overturned[0, j]) == one.overturned
        if not one.overturned:  # a cell stops early only once it has overturned
            assert b.max_theta_over_alpha[0, j] == one.max_theta_over_alpha


def test_overturned_fraction_is_the_commands_fragility_csv(tmp_path):
    scene = REPO / "scenes" / "wind-turbine-elcentro.toml"
    record = REPO / "scenes" / "records" / "elCentro.AT2"
    out = tmp_path / "b"
    done = subprocess.run(
        [CLI, "batch", str(scene), "--records", str(record), "--scales", "0.5,2.0",
         "--out", str(out)],
        capture_output=True, text=True,
    )
    assert done.returncode == 0, done.stderr
    with open(out / "fragility.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    b = rocking.batch(scene, records=[record], scales=[0.5, 2.0])
    got = b.overturned_fraction()
    assert len(rows) == len(got) == len(b.fragility) == 2
    for row, x, r in zip(rows, got, b.fragility):
        assert x == float(row["fraction_overturned"])
        assert set(r) == set(row) and all(same_field(r[k], v) for k, v in row.items()), (r, row)


def test_a_scale_without_a_result_has_no_overturned_fraction():
    # fragility.csv leaves the field empty where no run of a scale has a result; Python gives NaN
    # (it gave 0.0, "none overturned"). Two records at two scales: the first scale's runs both
    # failed, the second's one overturned and one survived.
    nan = np.array([np.nan] * 4)
    raw = {
        "keys": ["excitation.path", "excitation.scale"],
        "values": [np.array([0.0, 1.0]).tobytes(), np.array([0.5, 2.0]).tobytes()],
        "texts": [["a", "b"], []],
        "classes": ["failed", "overturned-no-impact", "failed", "survived"],
        "has_result": [False, True, False, True],
        "overturned": [False, True, False, False],
        "max_theta_over_alpha": nan.tobytes(),
        "impacts": [0, 0, 0, 3],
        "reported": {},
        "failures": [(0, "x"), (2, "x")],
        "beyond_model": [],
        "record_names": ["a", "b"],
        "record_paths": ["a", "b"],
        "scales": [0.5, 2.0],
        # fragility.csv's rows as the library's table gives them.
        "fragility": json.dumps([
            {"scale": 0.5, "runs": 2, "failed": 2, "beyond_model": 0, "completed": 0,
             "overturned": 0, "fraction_overturned": None},
            {"scale": 2.0, "runs": 2, "failed": 0, "beyond_model": 0, "completed": 2,
             "overturned": 1, "fraction_overturned": 0.5},
        ]),
    }
    got = rocking.Batch(raw).overturned_fraction()
    assert got.shape == (2,) and np.isnan(got[0]) and got[1] == 0.5


def test_models_equal_the_commands_list():
    assert rocking.models() == json.loads(cli("models", "--json"))["models"]


@pytest.mark.parametrize(
    "set_, key",
    [
        ({"structure.alpha": -1}, "alpha"),
        ({"structure.alpah": 0.2}, "alpah"),
        (["excitation.omega_p_over_p=0"], "omega_p_over_p"),
        ({"solver.tol": 0}, "tol"),
    ],
)
def test_bad_input_raises_value_error_naming_the_key(set_, key):
    with pytest.raises(ValueError, match=key) as e:
        rocking.load_scene(FIG3, set=set_)
    assert str(FIG3) in str(e.value)


def test_bad_input_messages_are_the_commands(tmp_path):
    # The same message; each front end names the override its own way (`--set`, `set=`).
    done = subprocess.run(
        [CLI, "run", str(FIG3), "--set", "structure.alpha=-1", "--out", str(tmp_path / "o")],
        capture_output=True, text=True,
    )
    assert done.returncode == 2
    assert f"{FIG3}: --set structure.alpha=-1: " in done.stderr
    with pytest.raises(ValueError) as e:
        rocking.load_scene(str(FIG3), set=["structure.alpha=-1"])
    assert f"{FIG3}: set entry structure.alpha=-1: " in str(e.value)
    assert "--set" not in str(e.value)
    assert done.stderr.strip() == f"error: {e.value}".replace("set entry", "--set", 1)


def test_a_study_without_records_names_the_parameter_not_the_flag(tmp_path):
    # The library's error carries the data; each front end names its own argument.
    scene = REPO / "scenes" / "wind-turbine-elcentro.toml"
    empty = tmp_path / "no-records"
    empty.mkdir()
    done = subprocess.run(
        [CLI, "batch", str(scene), "--records", str(empty), "--out", str(tmp_path / "o")],
        capture_output=True, text=True,
    )
    assert done.returncode == 2
    assert "no records: give --records FILE|DIR or `records = [...]` in [sweep]" in done.stderr
    with pytest.raises(ValueError) as e:
        rocking.batch(scene, records=[empty])
    assert "no records: give records=[FILE|DIR, ...] or `records = [...]` in [sweep]" in str(e.value)
    assert "--records" not in str(e.value)


def test_a_run_that_fails_on_valid_input_raises_simulation_error(tmp_path):
    # Too few steps allowed: the guard stops the run. The input is valid, so the command exits 1
    # (not 2) and Python raises SimulationError, a RuntimeError, with the command's message.
    sets = ["solver.max_steps=50"]
    done = subprocess.run(
        [CLI, "run", str(FIG3), "--set", sets[0], "--out", str(tmp_path / "o")],
        capture_output=True, text=True,
    )
    assert done.returncode == 1
    scene = rocking.load_scene(str(FIG3), set=sets)
    with pytest.raises(rocking.SimulationError) as e:
        scene.run()
    assert isinstance(e.value, RuntimeError) and not isinstance(e.value, ValueError)
    assert "simulation stopped" in str(e.value) and "max_steps" in str(e.value)
    assert done.stderr.strip() == f"error: {e.value}"


def test_an_unwritable_cache_raises_os_error(tmp_path):
    not_a_dir = tmp_path / "file"
    not_a_dir.write_text("")
    with pytest.raises(OSError, match="Not a directory"):
        rocking.figure(REPO / "scenes" / "paper" / "fig6-alpha01.toml", cache=not_a_dir, cells=4)


def test_other_bad_inputs():
    with pytest.raises(ValueError, match="cannot read scene file"):
        rocking.load_scene(REPO / "scenes" / "no-such-scene.toml")
    with pytest.raises(ValueError, match="invalid TOML"):
        rocking.Scene.from_toml("[structure\nalpha = ")
    with pytest.raises(ValueError, match="excitation.amplitud"):
        rocking.spectrum(FIG8, axes=["excitation.amplitud=1:2:2"])
    with pytest.raises(ValueError, match="threads"):
        rocking.spectrum(FIG8, axes=SMALL_AXES, threads=0)
    with pytest.raises(ValueError, match="alpha"):
        rocking.Structure(omega_n_over_p=5.0, alpha=2.0)


def test_building_blocks_run_as_the_scene():
    structure = rocking.Structure(
        omega_n_over_p=11.9, alpha=0.2, gamma_mc=0.0, gamma_mb=0.0, gamma_ib=1.0,
        zeta=0.005, damping="fixed-base",
    )
    r = rocking.simulate(
        structure,
        rocking.Excitation.sine_pulse(omega_p_over_p=5.1, amplitude=1.30),
        rocking.Options(accuracy="accurate", after_excitation=6.8),
        rocking.Effects(impact="vvel", energy=True),
    )
    want = rocking.load_scene(FIG3).run().summary
    assert r.summary.max_theta_over_alpha == want.max_theta_over_alpha
    assert r.summary.impacts == want.impacts
    assert r.history is None  # no [output] asked for


def test_from_toml_reads_a_record_given_by_absolute_path():
    scene = rocking.load_scene(REPO / "scenes" / "wind-turbine-elcentro.toml")
    text = (REPO / "scenes" / "wind-turbine-elcentro.toml").read_text()
    assert 'path = "records/elCentro.AT2"' in text
    record = json.dumps(str(REPO / "scenes" / "records" / "elCentro.AT2"))
    moved = text.replace('"records/elCentro.AT2"', record)
    other = rocking.Scene.from_toml(moved, base_dir="/", name="x.toml").run().summary
    assert other.max_theta_over_alpha == scene.run().summary.max_theta_over_alpha


def test_the_gil_is_released_during_a_spectrum():
    """Another Python thread makes progress while a spectrum runs (no timing assert: with the
    GIL held by the call, the other thread could not run at all in the middle of it)."""
    stamps = []
    stop = threading.Event()

    def count():
        while not stop.is_set():
            for _ in range(1000):
                pass
            stamps.append(time.perf_counter())

    t = threading.Thread(target=count)
    t.start()
    try:
        start = time.perf_counter()
        sp = rocking.spectrum(
            FIG8, axes=["excitation.omega_p_over_p=1:10:16", "excitation.amplitude=1:20:16"],
            threads=1,
        )
        end = time.perf_counter()
    finally:
        stop.set()
        t.join()
    assert sp.classes.size == 256
    q = (end - start) / 4
    middle = [s for s in stamps if start + q < s < end - q]
    assert len(middle) > 10, (len(stamps), end - start)


def _at2_samples(path):
    """The samples and time step of a PEER AT2 file in g (4 header lines), parsed here in Python."""
    lines = Path(path).read_text().splitlines()
    dt = float(lines[3].split("DT=")[1].split()[0])
    return np.array([float(x) for line in lines[4:] for x in line.split()]), dt


def test_a_record_from_an_array_runs_as_its_file():
    path = REPO / "scenes" / "records" / "elCentro.AT2"
    samples, dt = _at2_samples(path)
    structure = rocking.Structure(h=120.0, b=6.0, ei=4.163e11, m=3.0e5, m_c=3.0e5, m_b=6.0e5,
                                  zeta=0.01, g=9.81)
    opts = rocking.Options(accuracy="default", after_excitation=10.0)
    effects = rocking.Effects(impact="vvel", energy=True)
    from_file = rocking.simulate(structure, rocking.Excitation.record(path, scale=3.0),
                                 opts, effects).summary.to_dict()
    from_array = rocking.simulate(structure,
                                  rocking.Excitation.samples(samples, dt, "g", scale=3.0),
                                  opts, effects).summary.to_dict()
    assert from_file["impacts"] > 0
    # The same record (samples, dt, units, PGA) described under its own path; all else equal.
    tail = lambda d: d.pop("excitation").split(" ", 2)[2]
    assert tail(from_array) == tail(from_file)
    assert from_array == from_file


@pytest.mark.parametrize("samples,dt,units,key", [
    ([0.0, float("nan"), 0.1], 0.01, "g", "acceleration[1]"),
    ([[0.0, 0.1]], 0.01, "g", "1-D"),
    ([0.0, 0.1, 0.0], -0.01, "g", "dt"),
    ([0.0, 0.1, 0.0], 0.01, "ft/s2", "units"),
])
def test_a_bad_array_record_raises_value_error_naming_it(samples, dt, units, key):
    structure = rocking.Structure(omega_n_over_p=5.0, alpha=0.1)
    with pytest.raises(ValueError, match=key.replace("[", r"\[").replace("]", r"\]")):
        rocking.simulate(structure, rocking.Excitation.samples(samples, dt, units))


def test_the_animation_is_the_commands_gif(tmp_path):
    sets = [
        "output.animation=true",
        "output.animation_frames=24",
        "output.animation_width=320",
        "output.animation_height=240",
    ]
    out = tmp_path / "out"
    args = ["run", str(FIG3), "--out", str(out)]
    for s in sets:
        args += ["--set", s]
    cli(*args)
    want = (out / "animation.gif").read_bytes()
    result = rocking.load_scene(FIG3, set=sets).run()
    path = tmp_path / "py.gif"
    got = result.animation(path)
    assert got == want and path.read_bytes() == want
    # GIF header: logical screen width and height, little-endian.
    assert got[:6] == b"GIF89a"
    assert int.from_bytes(got[6:8], "little") == 320
    assert int.from_bytes(got[8:10], "little") == 240
    # Other sizes than the scene's, within the command's bounds.
    small = result.animation(frames=5, width=160, height=120)
    assert int.from_bytes(small[6:8], "little") == 160 and small != got
    with pytest.raises(ValueError, match="frames = 1 is not allowed: 2 <= frames"):
        result.animation(frames=1)
    with pytest.raises(ValueError, match="width = 2000 is not allowed"):
        result.animation(width=2000)
    # Without history rows there is nothing to draw, and the message says how to get them.
    bare = rocking.load_scene(FIG3, set={"output.history": "none", "output.plots": False}).run()
    with pytest.raises(ValueError, match="animation = true"):
        bare.animation()


def test_ida_is_the_commands_study(tmp_path):
    gm = REPO.parent / "shared" / "data" / "ground-motions"
    recs = [str(gm / r) for r in ("A-ELC180.AT2", "A-PEL180.AT2", "A-BEN360.AT2")]
    scene = REPO / "scenes" / "wind-turbine-msa.toml"
    sets = ["ida.bootstrap=200", "ida.stripes=[4.0, 8.0, 16.0, 30.0]"]
    out = tmp_path / "msa"
    args = ["ida", str(scene), "--out", str(out), "--records", *recs]
    for s in sets:
        args += ["--set", s]
    cli(*args)
    want = json.loads((out / "fragility.json").read_text())
    got = rocking.ida(rocking.load_scene(scene, set=sets), records=recs)
    for key in ("method", "median_m_s2", "beta", "bootstrap", "stripes", "analyses", "im"):
        assert got.fragility[key] == want[key], key
    assert got.fragility["method"] == "multiple-stripe"
    # Per record: every column of records.csv, and its rows of stripes.csv as its analyses (the
    # same rows of the study's tables, so no column is the command's alone).
    rows = read_csv(out / "records.csv")
    analyses = read_csv(out / "stripes.csv")
    assert [r["record"] for r in got.records] == [r["record"] for r in rows]
    for r, row in zip(got.records, rows):
        assert set(r) == set(row) | {"analyses"}
        assert all(same_field(r[k], v) for k, v in row.items()), (r, row)
        assert len(r["analyses"]) == 4 and r["capacity_im_m_s2"] is None
        own = [a for a in analyses if a["record"] == r["record"]]
        assert len(own) == 4
        for a, want in zip(r["analyses"], own):
            assert set(a) == set(want) - {"record"}
            assert all(same_field(a[k], want[k]) for k in a), (a, want)
    # The fitted curve is the lognormal with that median and β.
    assert abs(got.probability(got.median_m_s2) - 0.5) < 1e-15
    with pytest.raises(ValueError, match="`stripes`"):
        rocking.ida(rocking.load_scene(scene, set=["ida.stripes=[-1.0]"]), records=recs)
