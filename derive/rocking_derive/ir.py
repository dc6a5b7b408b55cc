"""CasADi function -> language-neutral intermediate form (a JSON instruction list) + golden samples."""

from __future__ import annotations

import json
import math
import random

import casadi as ca
import mpmath

from . import __version__
from .kernels import Kernel, kernels
from .models import VARIANTS, BaseMass, ColumnMass, LumpedMass, Variant

OP_NAMES = {}
for _name in dir(ca):
    if _name.startswith("OP_"):
        OP_NAMES.setdefault(getattr(ca, _name), _name[3:].lower())


def casadi_function(k: Kernel) -> ca.Function:
    ins = [ca.vertcat(*i.symbols) for i in k.inputs]
    out = ca.densify(ca.vertcat(*k.output.exprs))
    return ca.Function(k.name, ins, [out], [i.name for i in k.inputs], [k.output.name],
                       {"cse": True, "live_variables": False})


def tape(f: ca.Function) -> list[list]:
    """The CSE'd instruction list: [op, out, args...]; see the schema in crates/rocking-codegen."""
    rows = []
    for k in range(f.n_instructions()):
        op = f.instruction_id(k)
        ins, outs = f.instruction_input(k), f.instruction_output(k)
        if op == ca.OP_INPUT:
            rows.append(["input", outs[0], ins[0], ins[1]])
        elif op == ca.OP_OUTPUT:
            if outs[0] != 0:
                raise ValueError("one output per function")
            rows.append(["output", outs[1], ins[0]])
        elif op == ca.OP_CONST:
            rows.append(["const", outs[0], number(f.instruction_constant(k))])
        else:
            rows.append([OP_NAMES[op], outs[0], *ins])
    return rows


def number(v: float):
    v = float(v)
    if math.isnan(v):
        return "nan"
    if math.isinf(v):
        return "inf" if v > 0 else "-inf"
    return v


SAMPLE_RANGES = {
    "theta": (-0.3, 0.3), "u": (-0.05, 0.05), "theta_dot": (-1.0, 1.0), "u_dot": (-0.5, 0.5),
    "ug": (-3.0, 3.0), "eta": (0.0, 1.0),
    # the ground's kernels (ground.py): settlement, its rate, the load
    "v": (-0.02, 0.05), "v_dot": (-0.5, 0.5), "w": (1.0, 1000.0),
    # the accelerations of the free-base forces (free_base.py)
    "theta_ddot": (-1.0, 1.0), "v_ddot": (-1.0, 1.0), "u_ddot": (-1.0, 1.0),
}


class Sampler:
    """Uniform samples from Python's Mersenne Twister through ``random()`` alone, whose sequence
    for a seed is guaranteed across Python versions and machines."""

    def __init__(self, seed: int):
        self._rng = random.Random(seed)

    def uniform(self, lo: float, hi: float) -> float:
        return lo + (hi - lo) * self._rng.random()


def sample_range(element: str) -> tuple[float, float]:
    """The sampling range of an input element; ``u_2``, ``u_dot_3`` sample as ``u``, ``u_dot``."""
    stem = element.rstrip("0123456789")
    return SAMPLE_RANGES[element] if element in SAMPLE_RANGES else SAMPLE_RANGES[stem.removesuffix("_")]


def sample_params(variant: Variant, rng: Sampler) -> list[float]:
    h = rng.uniform(5, 30)
    b = h * rng.uniform(0.05, 0.3)
    m = rng.uniform(1, 3)
    values = {
        "h": h, "b": b, "m": m, "m_c": m * rng.uniform(0.2, 2), "m_b": m * rng.uniform(0.2, 2),
        "zeta": rng.uniform(0.0, 0.05), "g": 9.81,
    }
    values["i_bc"] = rng.uniform(0.9, 1.2) * 4 / 3 * values["m_b"] * b**2
    m_tilde = m + 0.25 * values["m_c"]
    values["ei"] = (rng.uniform(3, 30)) ** 2 * (9.81 / h) * m_tilde * h**3 / 3
    for p in variant.model.extra_params:
        values[p.name] = p.default * rng.uniform(0.5, 1.5) if p.default else rng.uniform(0.5, 1.5)
    # A modal damping matrix (several coordinates): symmetric positive definite, of the size of
    # 2 zeta omega m with the sampled omega (sqrt(ei / (m_tilde h^3))), its correlations below 1/2.
    damping = [p for p in variant.model.params if p.derived == "modal_damping"]
    if damping:
        scale = 2 * math.sqrt(values["ei"] * m_tilde / h**3)
        n = variant.model.coordinates
        diagonal = [scale * rng.uniform(0.0, 0.05) for _ in range(n)]
        for i in range(n):
            for j in range(i, n):
                c = diagonal[i] if i == j else rng.uniform(-0.5, 0.5) * math.sqrt(diagonal[i] * diagonal[j])
                values[f"c_{i + 1}_{j + 1}"] = c
    return [values[p.name] for p in variant.model.params]


def _rounded(f):
    """An elementary function evaluated in mpmath at 113 bits and rounded once to f64: the
    correctly rounded value (up to a double rounding that is itself deterministic), independent
    of the machine's libm."""
    def g(*args):
        with mpmath.workprec(113):
            return float(f(*(mpmath.mpf(a) for a in args)))
    return g


#: Each instruction of the tape on Python floats. +, -, *, / and sqrt are IEEE operations
#: (correctly rounded everywhere); the transcendental ones are rounded once from mpmath.
REPLAY = {
    "add": lambda a, b: a + b, "sub": lambda a, b: a - b, "mul": lambda a, b: a * b,
    "div": lambda a, b: _ieee_div(a, b),
    "neg": lambda a: -a, "sq": lambda a: a * a, "twice": lambda a: 2.0 * a,
    "sqrt": lambda a: math.sqrt(a) if a >= 0 else math.nan, "fabs": abs,
    "sign": lambda a: math.nan if math.isnan(a) else float((a > 0) - (a < 0)),
    "sin": _rounded(mpmath.sin), "cos": _rounded(mpmath.cos), "atan2": _rounded(mpmath.atan2),
    "sinh": _rounded(mpmath.sinh), "cosh": _rounded(mpmath.cosh),
}


def _ieee_div(a: float, b: float) -> float:
    """a / b as IEEE 754 defines it (Python raises on a zero divisor instead)."""
    if b != 0:
        return a / b
    if a == 0 or math.isnan(a):
        return math.nan
    return math.copysign(math.inf, a) * math.copysign(1.0, b)


def replay(instructions: list[list], args: list[list[float]]) -> list[float]:
    """Evaluates a tape as the generated Rust does, op by op in f64, deterministically."""
    work: dict[int, float] = {}
    out: dict[int, float] = {}
    for row in instructions:
        op, dst = row[0], row[1]
        if op == "input":
            work[dst] = float(args[row[2]][row[3]])
        elif op == "const":
            work[dst] = _number_in(row[2])
        elif op == "output":
            out[dst] = work[row[2]]
        elif op in REPLAY:
            work[dst] = REPLAY[op](*(work[a] for a in row[2:]))
        else:
            raise ValueError(f"no deterministic replay of the CasADi operation {op!r}: add it to REPLAY")
    return [out[k] for k in range(len(out))]


def _number_in(v):
    return {"nan": math.nan, "inf": math.inf, "-inf": -math.inf}.get(v, v) if isinstance(v, str) else float(v)


def _close(a: float, b: float) -> bool:
    if math.isnan(a) or math.isnan(b) or math.isinf(a) or math.isinf(b):
        return a == b or (math.isnan(a) and math.isnan(b))
    return abs(a - b) <= 1e-11 * max(abs(a), abs(b), 1e-300) or abs(a - b) <= 1e-280


def golden(k: Kernel, f: ca.Function, instructions: list[list], variant: Variant,
           count: int = 3, seed: int = 20151122, ug_series: int = 0, sample=None) -> list[dict]:
    """Golden samples: the tape of ``f`` (the kernel ``k``'s inputs) replayed deterministically
    (``replay``) at pseudo-random inputs, checked here against CasADi's own evaluation of the
    function (which calls the machine's libm, so it is a check, never an output). With
    ``ug_series`` > 0 the ground acceleration is that many Taylor coefficients instead of a value.
    ``sample(rng)`` gives the parameters when there is no variant (the ground's kernels)."""
    rng = Sampler(seed + len(k.name))
    samples = []
    for j in range(count):
        args = []
        for inp in k.inputs:
            if inp.params:
                args.append(sample(rng) if sample else sample_params(variant, rng))
            elif inp.name == "s":
                args.append([1.0 if j % 2 == 0 else -1.0])
            elif inp.name == "ug" and ug_series:
                args.append([rng.uniform(*SAMPLE_RANGES["ug"]) / math.factorial(m) for m in range(ug_series)])
            else:
                args.append([rng.uniform(*sample_range(e)) for e in inp.elements])
        values = replay(instructions, args)
        casadi_values = [float(v) for v in ca.DM(f(*args)).full().reshape(-1)]
        bad = [(i, a, b) for i, (a, b) in enumerate(zip(values, casadi_values)) if not _close(a, b)]
        if len(values) != len(casadi_values) or bad:
            raise ValueError(f"{variant.name if variant else 'ground'}::{f.name()}: replay differs from CasADi at {bad[:3]}")
        samples.append({"inputs": args, "output": [number(v) for v in values]})
    return samples


#: Order of the golden Taylor coefficients (x_1 .. x_TAYLOR_ORDER of the solution).
TAYLOR_ORDER = 8

#: The kernels that are right-hand sides of an ODE (the solver's Taylor method expands them).
TAYLOR_RHS = ("rocking_rhs", "contact_rhs")


def taylor_golden(k: Kernel, variant: Variant, count: int = 2) -> list[dict]:
    """Golden Taylor coefficients of the solution of x' = k(x, ug(t), ...) at the sampled state:
    x_n = x^(n)/n!, with x^(n) from repeated Lie derivatives of the right-hand side taken by CasADi's
    own symbolic differentiation (the ground acceleration a polynomial whose Taylor coefficients
    are inputs). This is an algorithm independent of the Taylor-mode recurrences the codegen emits
    on the tape, which the Rust test `taylor_kernels_match_casadi_derivatives` compares with. The
    numbers are the deterministic replay of the derivative's tape, checked against CasADi's
    evaluation like ``golden``. Output layout: ``output[(n - 1) * dim + i]`` is coefficient n of
    component i."""
    x = ca.vertcat(*k.inputs[0].symbols)
    g = [ca.SX.sym(f"ug_{j}") for j in range(TAYLOR_ORDER)]
    ug = next(i for i in k.inputs if i.name == "ug").symbols[0]
    rhs = ca.substitute(ca.vertcat(*k.output.exprs), ug, g[0])

    def lie(e):
        """d/dt of e along the solution: the state moves with rhs, ug's coefficients shift."""
        d = ca.jtimes(e, x, rhs)
        for j in range(TAYLOR_ORDER - 1):
            d += ca.jacobian(e, g[j]) * ((j + 1) * g[j + 1])
        return d

    coefficients, derivative = [rhs], rhs
    for n in range(2, TAYLOR_ORDER + 1):
        derivative = lie(derivative)
        coefficients.append(derivative / math.factorial(n))
    ins = [ca.vertcat(*g) if i.name == "ug" else ca.vertcat(*i.symbols) for i in k.inputs]
    f = ca.Function(k.name + "_taylor", ins, [ca.densify(ca.vertcat(*coefficients))],
                    {"cse": True, "live_variables": False})
    return golden(k, f, tape(f), variant, count=count, seed=20251125, ug_series=TAYLOR_ORDER)


def mass_roles(model) -> dict[str, dict]:
    """What each parameter is to the model's masses: a mass ("column", "lumped", "base"; removable
    or not), the inertia of a base mass, or the height of a lumped mass (scenes and the solver's
    variant selection read these)."""
    roles = {}
    for mass in model.masses:
        if isinstance(mass, ColumnMass):
            roles[mass.mass] = {"mass": "column", "removable": True}
        elif isinstance(mass, LumpedMass):
            roles[mass.mass] = {"mass": "lumped", "removable": mass.removable}
            if isinstance(mass.eta, str):
                roles[mass.eta] = {"height_of": mass.mass}
        elif isinstance(mass, BaseMass):
            roles[mass.mass] = {"mass": "base", "removable": True}
            roles[mass.inertia] = {"inertia_of": mass.mass}
    return roles


def write_variant(name: str, out) -> str:
    """Derives the variant NAME and writes its IR to OUT/ir/NAME.json; returns NAME. A worker
    process's task in `python -m rocking_derive` (a module function, so that it pickles)."""
    variant = next(v for v in VARIANTS if v.name == name)
    (out / "ir" / f"{name}.json").write_text(dumps(variant_ir(variant)))
    return name


def write_ground(out) -> str:
    """The ground's IR, written to OUT/ir/ground/ground.json; returns "ground" (a worker's task)."""
    (out / "ir" / "ground" / "ground.json").write_text(dumps(ground_ir()))
    return "ground"


def variant_ir(variant: Variant) -> dict:
    functions = []
    for k in kernels(variant):
        f = casadi_function(k)
        instructions = tape(f)
        functions.append({
            "name": k.name,
            "doc": k.doc,
            "inputs": [
                {"name": i.name, "doc": i.doc, "elements": i.elements,
                 **({"scalar": True} if i.scalar else {}), **({"params": True} if i.params else {})}
                for i in k.inputs
            ],
            "output": {"name": k.output.name, "doc": k.output.doc, "elements": k.output.elements,
                       "scalar": k.output.scalar},
            "instructions": instructions,
            "golden": golden(k, f, instructions, variant),
            **({"taylor_order": TAYLOR_ORDER, "taylor_golden": taylor_golden(k, variant)}
               if k.name in TAYLOR_RHS else {}),
        })
    roles = mass_roles(variant.model)
    params = []
    for p in variant.model.params:
        entry = {"name": p.name, "doc": p.doc}
        if p.derived:
            entry["derived"] = p.derived
        else:
            entry.update({"physical": p.physical} if p.physical else {"default": p.default})
        entry.update(roles.get(p.name, {}))
        params.append(entry)
    shape = variant.model.basis.description
    n = variant.model.coordinates
    return {
        "schema": 1,
        "generator": f"rocking_derive {__version__}",
        "casadi": ca.__version__,
        "source": "derive/rocking_derive/models.py",
        "model": variant.model.name,
        "variant": variant.name,
        "title": variant.title,
        "model_description": variant.model.description,
        "shape": shape,
        # One coordinate is the default, left out (so a one-function model's IR is as it was).
        **({"coordinates": n} if n > 1 else {}),
        "removed": list(variant.remove),
        "rigid": variant.rigid,
        "small_angle": variant.small_angle,
        "doc": (variant.model.description + (". Shape: " if n == 1 else ". Shape functions: ") + shape + "."
                + (" " + variant.doc if variant.doc else "")),
        "params": params,
        "functions": functions,
    }


def dumps(ir: dict) -> str:
    """Deterministic JSON: one instruction or golden sample per line, so diffs stay readable."""
    lines = ["{"]
    keys = list(ir)
    for n, key in enumerate(keys):
        comma = "," if n + 1 < len(keys) else ""
        if key == "functions":
            lines.append('  "functions": [')
            for fi, fn in enumerate(ir["functions"]):
                lines.append("    {")
                fkeys = list(fn)
                for m, fk in enumerate(fkeys):
                    fc = "," if m + 1 < len(fkeys) else ""
                    if fk in ("instructions", "golden", "inputs", "taylor_golden"):
                        lines.append(f'      "{fk}": [')
                        rows = fn[fk]
                        for r, row in enumerate(rows):
                            rc = "," if r + 1 < len(rows) else ""
                            lines.append("        " + json.dumps(row) + rc)
                        lines.append("      ]" + fc)
                    else:
                        lines.append(f'      "{fk}": {json.dumps(fn[fk])}{fc}')
                lines.append("    }" + ("," if fi + 1 < len(ir["functions"]) else ""))
            lines.append("  ]" + comma)
        elif key == "params":
            lines.append('  "params": [')
            for r, row in enumerate(ir["params"]):
                lines.append("    " + json.dumps(row) + ("," if r + 1 < len(ir["params"]) else ""))
            lines.append("  ]" + comma)
        else:
            lines.append(f'  "{key}": {json.dumps(ir[key])}{comma}')
    lines.append("}")
    return "\n".join(lines) + "\n"


def sample_ground_params(rng: Sampler) -> list[float]:
    """b, k, c of the ground's kernels (ground.PARAMS)."""
    b = rng.uniform(0.5, 3.0)
    return [b, rng.uniform(1e2, 1e5), rng.uniform(0.0, 1e3)]


def ground_ir() -> dict:
    """The IR of the ground's model-independent kernels (rendered into generated/src/ground.rs)."""
    from . import ground

    functions = []
    for k in ground.kernels():
        f = casadi_function(k)
        instructions = tape(f)
        functions.append({
            "name": k.name,
            "doc": k.doc,
            "inputs": [
                {"name": i.name, "doc": i.doc, "elements": i.elements,
                 **({"scalar": True} if i.scalar else {}), **({"params": True} if i.params else {})}
                for i in k.inputs
            ],
            "output": {"name": k.output.name, "doc": k.output.doc, "elements": k.output.elements,
                       "scalar": k.output.scalar},
            "instructions": instructions,
            "golden": golden(k, f, instructions, None, sample=sample_ground_params),
        })
    return {
        "schema": 1,
        "generator": f"rocking_derive {__version__}",
        "casadi": ca.__version__,
        "source": "derive/rocking_derive/ground.py",
        "model": "ground",
        "variant": "ground",
        "title": "The ground under the base: a tensionless Winkler bed and the two-spring foundation",
        "doc": ground.__doc__.strip().split("\n\n")[0].replace("\n", " "),
        "params": [{"name": name, "doc": doc} for name, doc in ground.PARAMS],
        "functions": functions,
    }
