"""Deformable cantilevers that uplift and rock on a rigid base (Vassiliou, Mackie & Stojadinović
2015), from Python.

The package runs the same library code as the ``rocking`` command: a scene loaded here is
validated with the same messages, ``Scene.run().summary`` is what ``rocking run --json`` prints,
and ``spectrum``/``batch`` plan their cells as ``rocking spectrum``/``rocking batch`` do.
Simulations and sweeps release the GIL; sweeps use all cores (or ``threads``).

Errors carry the command's message. Bad input (a scene, a record, an argument) raises
:class:`ValueError` (the message names the file and the key); a run that failed though its input
was valid raises :class:`SimulationError` (a :class:`RuntimeError`: the integrator, a guard such as
``max_steps``, a non-finite result); a file that cannot be read or written raises :class:`OSError`;
anything else is a defect and raises :class:`RuntimeError`.

>>> import rocking
>>> scene = rocking.load_scene("scenes/fig3-vvel.toml", set={"excitation.amplitude": 1.2})
>>> result = scene.run()
>>> result.summary.max_theta_over_alpha            # doctest: +SKIP
"""

from __future__ import annotations

import json
import os
import tempfile
from typing import Any, Dict, Iterable, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _rocking

__version__: str = _rocking.__version__

#: A run that failed though its input was valid (a :class:`RuntimeError`).
SimulationError = _rocking.SimulationError

__all__ = [
    "Batch",
    "Excitation",
    "Fragility",
    "Result",
    "Scene",
    "SimulationError",
    "Spectrum",
    "Structure",
    "Summary",
    "batch",
    "columns",
    "figure",
    "ida",
    "load_scene",
    "models",
    "simulate",
    "spectrum",
]

PathLike = Union[str, "os.PathLike[str]"]
Overrides = Union[None, Mapping[str, Any], Sequence[str]]


def _toml_value(v: Any) -> str:
    """One value in TOML syntax (numbers round-trip exactly: ``repr`` of a float)."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float, np.integer, np.floating)):
        return repr(float(v)) if isinstance(v, (float, np.floating)) else str(int(v))
    if isinstance(v, (str, os.PathLike)):
        return json.dumps(os.fspath(v))  # a TOML basic string
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    raise ValueError(f"cannot write {v!r} ({type(v).__name__}) as a scene value")


def _sets(set: Overrides) -> List[str]:
    """Overrides as ``key.path=value`` strings, from a dict or a list of such strings. A value of
    ``None`` removes the key (``key.path=null``), e.g. ``{"effects.impact": None}`` to put a
    rigid-surface scene on a compliant ground."""
    if set is None:
        return []
    if isinstance(set, Mapping):
        return [f"{k}={'null' if v is None else _toml_value(v)}" for k, v in set.items()]
    if isinstance(set, str):
        return [set]
    return [str(s) for s in set]


#: Summary keys whose value may be unbounded, written ``"inf"`` in the JSON (which has no
#: infinity): ``max_required_friction`` once the vertical reaction falls below zero.
_UNBOUNDED = ("max_required_friction",)


def _numbers(data: Any) -> Any:
    """A summary's values with ``"inf"`` read as ``float('inf')`` at the keys of
    :data:`_UNBOUNDED` (also inside ``fixed_base``)."""
    if isinstance(data, dict):
        return {
            k: float("inf") if k in _UNBOUNDED and v == "inf" else _numbers(v)
            for k, v in data.items()
        }
    return data


class Summary:
    """A run's summary: every field of ``rocking run --json`` as an attribute
    (``max_theta_over_alpha``, ``overturned``, ``impacts``, ``derived``, ...). An unbounded
    ``max_required_friction`` (the JSON's ``"inf"``: R_v fell below zero, first at
    ``first_lift_off_time``) is ``float('inf')`` here; :meth:`to_dict` keeps the JSON's ``"inf"``."""

    def __init__(self, data: Dict[str, Any]) -> None:
        self._data = data
        self.__dict__.update(_numbers(data))

    def to_dict(self) -> Dict[str, Any]:
        """The summary as a dict, equal to the JSON that ``rocking run --json`` prints."""
        return json.loads(json.dumps(self._data))

    def __repr__(self) -> str:
        s = self._data
        return (
            f"Summary(max_theta_over_alpha={s['max_theta_over_alpha']!r}, "
            f"overturned={s['overturned']!r}, impacts={s['impacts']!r}, "
            f"kernel_variant={s['kernel_variant']!r})"
        )


def _table(columns: Optional[Dict[str, Any]]) -> Optional[Dict[str, Any]]:
    """Columns from the compiled module: float64 bytes become numpy arrays."""
    if columns is None:
        return None
    return {
        k: np.frombuffer(v, dtype=np.float64) if isinstance(v, bytes) else np.asarray(v)
        for k, v in columns.items()
    }


class Result:
    """One simulation: ``summary``, ``history`` (the columns of history.csv as numpy arrays) and
    ``events`` (the rows of events.csv as dicts)."""

    def __init__(self, output: Any) -> None:
        self._output = output
        self.summary = Summary(json.loads(output.summary_json))
        self._history: Optional[Dict[str, np.ndarray]] = None
        self._events: Optional[List[Dict[str, Any]]] = None

    @property
    def history(self) -> Optional[Dict[str, np.ndarray]]:
        """The time history (columns named as in history.csv: ``tau``, ``t_s`` when the scene is
        physical, ``theta_over_alpha``, ``u_over_ucr``, ..., ``phase``), or None when the scene
        asks for none (set ``output.history_dt``). Built on first access."""
        if self._history is None:
            self._history = _table(self._output.history())
        return self._history

    @property
    def events(self) -> Optional[List[Dict[str, Any]]]:
        """Uplifts, impacts, rests and overturning, one dict per row of events.csv, or None when
        the run logged no events (set ``output.events = true``)."""
        if self._events is None:
            cols = _table(self._output.events())
            if cols is None:
                return None
            n = len(next(iter(cols.values()))) if cols else 0
            self._events = [
                {k: (v[i].item() if hasattr(v[i], "item") else v[i]) for k, v in cols.items()}
                for i in range(n)
            ]
        return self._events

    def to_dataframe(self) -> Any:
        """The history as a pandas DataFrame (needs pandas: ``pip install pandas``)."""
        try:
            import pandas as pd
        except ImportError as e:  # pragma: no cover - depends on the environment
            raise ImportError("Result.to_dataframe() needs pandas: pip install pandas") from e
        if self.history is None:
            raise ValueError(
                "the run has no history: set output.history_dt in the scene or in set={...}"
            )
        return pd.DataFrame(self.history)

    def animation(
        self,
        path: Optional[PathLike] = None,
        *,
        frames: Optional[int] = None,
        width: Optional[int] = None,
        height: Optional[int] = None,
    ) -> bytes:
        """The animated GIF of the run (base, deformed column, top mass, moving ground, with τ
        and θ/α on each frame), the same bytes as ``rocking run --animate``. ``frames`` (2-400),
        ``width`` (160-800) and ``height`` (120-600) default to the scene's ``[output]
        animation_*`` keys. Written to ``path`` when given (whole or not at all); in a notebook,
        ``IPython.display.Image(data=result.animation())`` shows it. Needs the run's history:
        load the scene with ``set={"output.animation": True}``."""
        data = self._output.animation(frames, width, height)
        if path is not None:
            target = os.path.abspath(os.fspath(path))
            fd, tmp = tempfile.mkstemp(prefix=".animation-", dir=os.path.dirname(target))
            try:
                with os.fdopen(fd, "wb") as f:
                    f.write(data)
                os.replace(tmp, target)
            except BaseException:
                os.unlink(tmp)
                raise
        return data

    def __repr__(self) -> str:
        return f"Result({self.summary!r})"


class Scene:
    """A scene (TOML) loaded and validated with its overrides. ``run()`` simulates it."""

    def __init__(self, inner: Any) -> None:
        self._inner = inner

    @classmethod
    def load(cls, path: PathLike, set: Overrides = None) -> "Scene":
        """Loads the scene file ``path`` with overrides (``{"structure.alpha": 0.15}`` or
        ``["structure.alpha=0.15"]``; ``None`` or ``null`` removes a key)."""
        return cls(_rocking.Scene.load(os.fspath(path), _sets(set)))

    @classmethod
    def from_toml(
        cls,
        text: str,
        base_dir: PathLike = ".",
        name: str = "<scene>.toml",
        set: Overrides = None,
    ) -> "Scene":
        """A scene from its TOML text. Relative paths in it (records) are resolved against
        ``base_dir``; ``name`` names it in messages and in ``summary.scene``."""
        path = os.path.join(os.fspath(base_dir), name)
        return cls(_rocking.Scene.from_text(text, path, _sets(set)))

    @property
    def path(self) -> str:
        """The scene's path (as given)."""
        return os.fspath(self._inner.path)

    @property
    def text(self) -> str:
        """The scene's TOML text."""
        return self._inner.text

    @property
    def title(self) -> Optional[str]:
        """The scene's title."""
        return self._inner.title

    @property
    def kernel_variant(self) -> Tuple[str, List[str]]:
        """The kernel variant the solver runs and the reasons it was picked."""
        return self._inner.kernel_variant

    def with_set(self, set: Overrides) -> "Scene":
        """The same scene with more overrides."""
        return Scene(_rocking.Scene.from_text(self.text, self.path, self._inner.sets + _sets(set)))

    def run(self) -> Result:
        """Simulates the scene (the GIL is released) and returns the :class:`Result`."""
        return Result(self._inner.run())

    def __repr__(self) -> str:
        return f"Scene({self.path!r}, title={self.title!r})"


def load_scene(path: PathLike, set: Overrides = None) -> Scene:
    """Loads a scene file with overrides; see :meth:`Scene.load`."""
    return Scene.load(path, set)


def _scene(scene: Union[Scene, PathLike]) -> Scene:
    return scene if isinstance(scene, Scene) else Scene.load(scene)


class Spectrum:
    """A spectrum over one or more axes of scene values. Grids have one dimension per axis (the
    last axis varies fastest, as in cells.csv)."""

    def __init__(self, raw: Dict[str, Any]) -> None:
        #: The axes' scene keys, e.g. ``["excitation.omega_p_over_p", "excitation.amplitude"]``.
        self.keys: List[str] = list(raw["keys"])
        #: The axes' values (one array per axis: float64, or str for a text axis such as
        #: ``structure.model=cubic,cantilever_modes2``).
        self.axes: List[np.ndarray] = [
            np.asarray(t) if t else np.frombuffer(v, dtype=np.float64)
            for v, t in zip(raw["values"], raw["texts"])
        ]
        shape = tuple(len(a) for a in self.axes)
        names = np.asarray(raw["classes"])
        #: Class names (as in cells.csv), the index of ``codes``.
        self.class_names: List[str] = sorted(set(names.tolist()))
        lookup = {n: i for i, n in enumerate(self.class_names)}
        #: Class code per cell (an index into ``class_names``).
        self.codes: np.ndarray = np.array([lookup[n] for n in names], dtype=np.int64).reshape(shape)
        #: Class name per cell.
        self.classes: np.ndarray = names.reshape(shape)
        #: True where a cell has no result: the simulation failed, or left the model's
        #: validity (class ``beyond-model``: the mass matrix became singular).
        self.without_result: np.ndarray = ~np.asarray(raw["has_result"], dtype=bool).reshape(shape)
        self._overturned = np.asarray(raw["overturned"], dtype=bool).reshape(shape)
        #: max θ/α per cell (masked where a cell has no result).
        self.max_theta_over_alpha: np.ma.MaskedArray = np.ma.masked_array(
            np.frombuffer(raw["max_theta_over_alpha"], dtype=np.float64).reshape(shape),
            self.without_result,
        )
        #: Impacts per cell (on compliant ground: landings, a corner pressing again).
        self.impacts: np.ndarray = np.asarray(raw["impacts"], dtype=np.int64).reshape(shape)
        #: The quantities of the scene's ``[sweep] report`` (e.g. the ground's
        #: ``max_ground_pressure_over_mean``), one grid per name, masked where a cell has no
        #: result or its run no value (a time such as ``first_uplift_time`` of an event that did
        #: not happen): the columns of cells.csv (runs.csv) after ``impacts``, empty there.
        self.reported: Dict[str, np.ma.MaskedArray] = {}
        for k, v in raw["reported"].items():
            values = np.frombuffer(v, dtype=np.float64).reshape(shape)
            self.reported[k] = np.ma.masked_array(values, self.without_result | np.isnan(values))
        #: Failed cells: (cell index, message).
        self.failures: List[Tuple[int, str]] = list(raw["failures"])
        #: Cells beyond the model's validity: (cell index, message).
        self.beyond_model: List[Tuple[int, str]] = list(raw["beyond_model"])

    @property
    def overturned(self) -> np.ndarray:
        """True where the structure overturned (False where a cell has no result)."""
        return self._overturned

    def __repr__(self) -> str:
        return f"{type(self).__name__}(keys={self.keys}, shape={self.classes.shape})"


class Batch(Spectrum):
    """Every record at every scale factor: grids of shape (records, scales), or (records,
    scales, *axes) with the batch's own axes."""

    def __init__(self, raw: Dict[str, Any]) -> None:
        super().__init__(raw)
        #: The records' file names.
        self.record_names: List[str] = list(raw["record_names"])
        #: The records' canonical paths.
        self.record_paths: List[str] = list(raw["record_paths"])
        #: The scale factors.
        self.scales: np.ndarray = np.asarray(raw["scales"], dtype=np.float64)
        #: fragility.csv's rows as ``rocking batch`` writes them (the library's table), keyed by
        #: its columns: per cell of the batch's own axes (their keys first), then per scale
        #: factor, ``scale``, ``runs``, ``failed``, ``beyond_model``, ``completed``,
        #: ``overturned`` and ``fraction_overturned`` (None where no run has a result).
        self.fragility: List[Dict[str, Any]] = json.loads(raw["fragility"])

    def overturned_fraction(self) -> np.ndarray:
        """Per scale factor (and cell of the batch's own axes: shape (scales, *axes)), the
        fraction of records that overturned, of the runs with a result; NaN where no run has a
        result (fragility.csv leaves that field empty). Read from :attr:`fragility`."""
        f = np.array(
            [np.nan if r["fraction_overturned"] is None else r["fraction_overturned"] for r in self.fragility],
            dtype=np.float64,
        )
        return np.moveaxis(f.reshape(*self.classes.shape[2:], len(self.scales)), -1, 0)


def spectrum(
    scene: Union[Scene, PathLike],
    axes: Optional[Sequence[str]] = None,
    threads: Optional[int] = None,
) -> Spectrum:
    """Sweeps ``scene`` over ``axes`` (``"key.path=start:stop:count"`` or ``"key.path=v1,v2"``;
    default: the scene's ``[sweep] axes``, else the paper's), in parallel on ``threads`` threads
    (default: all cores), with the GIL released. Nothing is written to disk."""
    s = _scene(scene)
    return Spectrum(_rocking.spectrum(s._inner, list(axes or []), threads))


def batch(
    scene: Union[Scene, PathLike],
    records: Optional[Iterable[PathLike]] = None,
    scales: Optional[Iterable[float]] = None,
    threads: Optional[int] = None,
    axes: Optional[Sequence[str]] = None,
) -> Batch:
    """Runs a record scene for every record (AT2 files or folders of them; default: the scene's
    ``[sweep] records``) at every scale factor (default: ``[sweep] scales``, else 1) and every
    cell of ``axes`` (as ``rocking batch --axis``: ``"structure.model=cubic,cantilever_modes2"``,
    numbers or texts); grids of shape (records, scales, *axes)."""
    s = _scene(scene)
    recs = [os.fspath(r) for r in (records or [])]
    sc = [float(x) for x in (scales or [])]
    return Batch(_rocking.batch(s._inner, recs, sc, threads, list(axes or [])))


class Fragility:
    """A record-suite fragility study (:func:`ida`): ``fragility`` (what ``fragility.json`` of
    ``rocking ida`` holds: ``method`` "ida" or "multiple-stripe", ``median_m_s2``, ``beta``, the
    bootstrap intervals, and the ``capacities_m_s2`` or the ``stripes``) and ``records`` (per
    record its row of records.csv, keyed by its columns: ``record`` (the file name), ``path``,
    ``units``, the intensity measures, ``im_m_s2`` at scale 1, the capacity; and ``analyses``,
    its rows of ida.csv or stripes.csv)."""

    def __init__(self, fragility: Dict[str, Any], records: List[Dict[str, Any]]) -> None:
        self.fragility = fragility
        self.records = records
        self.median_m_s2: float = fragility["median_m_s2"]
        self.beta: float = fragility["beta"]

    def probability(self, im: Any) -> Any:
        """P(overturning | IM = im) of the fitted lognormal, for IM values in m/s² (numpy)."""
        from math import erf, log, sqrt

        f = np.vectorize(lambda x: 0.5 * (1 + erf(log(x / self.median_m_s2) / (self.beta * sqrt(2)))))
        return f(np.asarray(im, dtype=float))

    def __repr__(self) -> str:
        return (
            f"Fragility({self.fragility['method']}, median {self.median_m_s2:.4g} m/s², "
            f"beta {self.beta:.3f}, {len(self.records)} records)"
        )


def ida(
    scene: Union[Scene, PathLike],
    records: Optional[Iterable[PathLike]] = None,
    threads: Optional[int] = None,
) -> Fragility:
    """Runs the scene's ``[ida]`` study as ``rocking ida`` does: every record (default: ``[ida]
    records``, else ``[sweep] records``) by hunt-and-fill IDA, or at every level of ``stripes``,
    then the lognormal fragility by maximum likelihood with its bootstrap band (GIL released)."""
    s = _scene(scene)
    recs = [os.fspath(r) for r in (records or [])]
    fragility, per_record = _rocking.ida(s._inner, recs, threads)
    return Fragility(json.loads(fragility), json.loads(per_record))


def convergence(
    scene: Union[Scene, PathLike],
    models: Sequence[str],
    quantities: Optional[Sequence[str]] = None,
    tolerance: float = 0.01,
    threads: Optional[int] = None,
) -> Dict[str, Any]:
    """How the scene's results converge with the number of deformation coordinates, as
    ``rocking convergence`` reports it: the scene run with each of ``models`` (in order, e.g.
    ``["cubic", "cantilever_modes2", "cantilever_modes3"]``); per quantity (default: max θ/α,
    impacts, max u/u_cr, the base moment, shear and elastic moment) its ``values`` per model,
    ``changes`` from the model before, and ``converged_n`` (``converged_model``): the first
    model from which every change is below ``tolerance`` (``None``: not converged). The
    dictionary is what convergence.json holds (GIL released)."""
    s = _scene(scene)
    raw = _rocking.convergence(s._inner, list(models), list(quantities or []), tolerance, threads)
    return json.loads(raw)


def figure(
    path: PathLike,
    cache: Optional[PathLike] = None,
    cells: Optional[int] = None,
    draft: bool = False,
    quiet: bool = True,
) -> Dict[str, bytes]:
    """The figure of a figure file (scenes/paper/fig8-alpha01.toml and the like), drawn as
    ``rocking figure`` draws it: ``{"svg": ..., "png": ..., "pdf": ..., "caption.md": ...}``,
    each the bytes the command writes (no caption for a ``draft``, which keeps the title and
    caption inside the image). Its sweeps are journaled in ``cache`` (default: a folder
    ``out/figure-cache`` beside the working directory, as the command's ``--cache``), so a second
    call reads them back; ``cells`` caps each ranged axis for a quick look (``--cells``)."""
    cache = cache if cache is not None else os.path.join("out", "figure-cache")
    return dict(_rocking.figure(os.fspath(path), os.fspath(cache), cells, draft, quiet))


def models() -> List[Dict[str, Any]]:
    """The generated models with their variants, parameters and effect switches, as
    ``rocking models --json`` lists them."""
    return json.loads(_rocking.models_json())["models"]


def columns() -> Dict[str, List[Dict[str, Any]]]:
    """What the results hold, declared once in the library: ``history`` and ``events``, the
    columns of ``Result.history`` / history.csv and ``Result.events`` / events.csv in order, each
    ``{name, label, unit, group, kind}`` (``label`` in the paper's notation, as the figures print
    it; ``unit`` what the raw quantity is divided by; ``group`` which runs have it: ``always``,
    ``forces``, ``ground``); ``reportable``, the summary quantities a sweep may report, each
    ``{key, label, needs, twin, forces, nullable}`` (needs: the conditions a run must meet to
    report it, such as ``ground`` or ``friction``, none for every run; forces: a run tracks the
    section forces for it; nullable: a run may have no value, the time of an event that did not
    happen)."""
    return json.loads(_rocking.columns_json())


class _Table:
    """A table of scene keys (a building block turned into scene text)."""

    _table = ""

    def __init__(self, **keys: Any) -> None:
        self.keys: Dict[str, Any] = {k: v for k, v in keys.items() if v is not None}

    def toml(self) -> str:
        lines = [f"[{self._table}]"] + [f"{k} = {_toml_value(v)}" for k, v in self.keys.items()]
        return "\n".join(lines) + "\n"

    def __repr__(self) -> str:
        args = ", ".join(f"{k}={v!r}" for k, v in self.keys.items())
        return f"{type(self).__name__}({args})"


class Structure(_Table):
    """A structure: the keys of a scene's ``[structure]`` table, dimensionless
    (``omega_n_over_p``, ``alpha``, ``gamma_mc``, ...) or physical (``h``, ``b``, ``ei``, ``m``,
    ...), with ``model=`` for any generated model and its own parameters (see :func:`models`).
    Validated when it is built, with the scene's messages."""

    _table = "structure"

    def __init__(self, **keys: Any) -> None:
        super().__init__(**keys)
        Scene.from_toml(self.toml(), name="<structure>.toml")


class Excitation(_Table):
    """A ground motion: the keys of a scene's ``[excitation]`` table."""

    _table = "excitation"

    def __init__(self, kind: str, **keys: Any) -> None:
        super().__init__(kind=kind, **keys)

    @classmethod
    def sine_pulse(cls, omega_p_over_p: Optional[float] = None, amplitude: Optional[float] = None,
                   **keys: Any) -> "Excitation":
        """One cycle of a_p sin(ω_p t); ``amplitude`` is a_p/(g tan α) (or give ``omega_p``,
        ``a_p``, ``amplitude_g``)."""
        return cls("sine-pulse", omega_p_over_p=omega_p_over_p, amplitude=amplitude, **keys)

    @classmethod
    def cosine_pulse(cls, omega_p_over_p: Optional[float] = None,
                     amplitude: Optional[float] = None, **keys: Any) -> "Excitation":
        """One cycle of a_p cos(ω_p t); keys as :meth:`sine_pulse`."""
        return cls("cosine-pulse", omega_p_over_p=omega_p_over_p, amplitude=amplitude, **keys)

    @classmethod
    def record(cls, path: PathLike, scale: Optional[float] = None,
               units: Optional[str] = None) -> "Excitation":
        """A PEER .AT2 record (read by the library: its time step and units as the command reads
        them); ``units`` ("g", "cm/s2", "m/s2") only when the header states none."""
        return cls("record", path=os.path.abspath(os.fspath(path)), scale=scale, units=units)

    @classmethod
    def samples(cls, acceleration: Any, dt: float, units: str,
                scale: Optional[float] = None) -> "Excitation":
        """A record given as an array of ground accelerations at time step ``dt`` (seconds) in
        ``units`` ("g", "cm/s2" or "m/s2"). The samples are written, exactly (shortest repr), to a
        plain-text record that lives as long as this object, and read by the library's text
        reader: the same unit conversion and checks as a record file in a scene."""
        a = np.asarray(acceleration, dtype=float)
        if a.ndim != 1 or a.size < 2:
            raise ValueError(f"acceleration: a 1-D array of at least 2 samples is needed, "
                             f"got shape {a.shape}")
        bad = np.flatnonzero(~np.isfinite(a))
        if bad.size:
            raise ValueError(f"acceleration[{bad[0]}] = {a[bad[0]]}: samples must be finite")
        if not (isinstance(dt, (int, float)) and np.isfinite(dt) and dt > 0):
            raise ValueError(f"dt = {dt!r}: the time step must be a finite number > 0 (s)")
        directory = tempfile.TemporaryDirectory(prefix="rocking-record-")
        path = os.path.join(directory.name, "samples.txt")
        with open(path, "w", encoding="utf-8") as f:
            f.write("# written by rocking.Excitation.samples\n")
            f.writelines(f"{float(x)!r}\n" for x in a)
        excitation = cls("record", path=path, format="text", dt=float(dt), units=units,
                         scale=scale)
        excitation._directory = directory  # removed with the object
        return excitation


class Options(_Table):
    """Solver settings: the keys of a scene's ``[solver]`` table (``accuracy``, ``method``,
    ``tol``, ``after_excitation``, ``t_end``, ...)."""

    _table = "solver"


class Effects(_Table):
    """Effect switches: the keys of a scene's ``[effects]`` table (``impact``, ``energy``,
    ``flexibility``, ...)."""

    _table = "effects"


class Output(_Table):
    """What a run records: the keys of a scene's ``[output]`` table (``history_dt``,
    ``events``)."""

    _table = "output"


def simulate(
    structure: Structure,
    motion: Excitation,
    options: Optional[Options] = None,
    effects: Optional[Effects] = None,
    output: Optional[Output] = None,
) -> Result:
    """Simulates ``structure`` under ``motion``: the building blocks are put together as a scene
    (so they are checked exactly as a scene file is) and run."""
    parts = [structure, motion, options, effects, output]
    text = "\n".join(p.toml() for p in parts if p is not None)
    return Scene.from_toml(text, name="<simulate>.toml").run()


__all__ += ["Effects", "Options", "Output"]
