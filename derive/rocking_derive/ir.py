"""CasADi function -> language-neutral intermediate form (a JSON instruction list) + golden samples."""

from __future__ import annotations

import json
import math

import casadi as ca
import numpy as np

from . import __version__
from .kernels import Kernel, kernels
from .models import BaseMass, ColumnMass, LumpedMass, Variant

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
    "ug": (-3.0, 3.0),
}


def sample_params(variant: Variant, rng) -> list[float]:
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
    return [values[p.name] for p in variant.model.params]


def golden(k: Kernel, f: ca.Function, variant: Variant, count: int = 3) -> list[dict]:
    rng = np.random.default_rng(abs(hash(k.name)) % 2**32 if False else 20151122 + len(k.name))
    samples = []
    for j in range(count):
        args = []
        for inp in k.inputs:
            if inp.params:
                args.append(sample_params(variant, rng))
            elif inp.name == "s":
                args.append([1.0 if j % 2 == 0 else -1.0])
            else:
                args.append([float(rng.uniform(*SAMPLE_RANGES[e])) for e in inp.elements])
        out = f(*args)
        values = np.array(out).reshape(-1)
        samples.append({"inputs": args, "output": [number(v) for v in values]})
    return samples


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


def variant_ir(variant: Variant) -> dict:
    functions = []
    for k in kernels(variant):
        f = casadi_function(k)
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
            "instructions": tape(f),
            "golden": golden(k, f, variant),
        })
    roles = mass_roles(variant.model)
    params = []
    for p in variant.model.params:
        entry = {"name": p.name, "doc": p.doc}
        entry.update({"physical": p.physical} if p.physical else {"default": p.default})
        entry.update(roles.get(p.name, {}))
        params.append(entry)
    return {
        "schema": 1,
        "generator": f"rocking_derive {__version__}",
        "casadi": ca.__version__,
        "source": "derive/rocking_derive/models.py",
        "model": variant.model.name,
        "variant": variant.name,
        "title": variant.title,
        "model_description": variant.model.description,
        "shape": variant.model.shape.description,
        "removed": list(variant.remove),
        "rigid": variant.rigid,
        "small_angle": variant.small_angle,
        "doc": (variant.model.description + ". Shape: " + variant.model.shape.description + "."
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
                    if fk in ("instructions", "golden", "inputs"):
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
