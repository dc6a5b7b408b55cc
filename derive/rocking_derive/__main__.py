"""python -m rocking_derive --out DIR: writes DIR/ir/<variant>.json, DIR/ir/ground/ground.json and
DIR/errata.md, in ROCKING_DERIVE_JOBS worker processes (default: the CPUs it may use). With
--only NAME[,NAME...] it writes only the IR of the named variants (and of the ground if `ground` is
named), and no errata; an unknown name is an error."""

from __future__ import annotations

import argparse
import multiprocessing
import os
import pathlib
import sys
from concurrent.futures import ProcessPoolExecutor

from . import errata, ir
from .models import VARIANTS


def _jobs() -> int:
    """Worker processes: ROCKING_DERIVE_JOBS, else the CPUs this process may use."""
    text = os.environ.get("ROCKING_DERIVE_JOBS")
    if text is None:
        return max(1, len(os.sched_getaffinity(0)))
    if not text.isdigit() or int(text) < 1:
        raise SystemExit(f"ROCKING_DERIVE_JOBS = {text!r}: expected a whole number >= 1")
    return int(text)


def _only(text: str) -> set[str]:
    """The names of `--only a,b`: each a variant of models.VARIANTS or `ground`."""
    names = [n.strip() for n in text.split(",")]
    if any(not n for n in names):
        raise SystemExit(f"rocking_derive: --only {text!r}: empty variant name")
    known = {v.name for v in VARIANTS} | {"ground"}
    unknown = [n for n in names if n not in known]
    if unknown:
        raise SystemExit(
            f"rocking_derive: --only: unknown variant(s) {', '.join(unknown)}; the variants of "
            f"rocking_derive/models.py are {', '.join(v.name for v in VARIANTS)} (and ground)"
        )
    return set(names)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="rocking_derive", description=__doc__)
    ap.add_argument("--out", required=True, type=pathlib.Path, help="output directory")
    ap.add_argument(
        "--only",
        metavar="NAME[,NAME...]",
        help="derive only these variants (`ground`: the ground's IR), and write no errata",
    )
    args = ap.parse_args(argv)
    only = _only(args.only) if args.only is not None else None
    (args.out / "ir").mkdir(parents=True, exist_ok=True)
    # Worker processes forked after the imports (importing the derivation costs ~6 s of CPU,
    # which a spawned worker would pay again). No variant's IR depends on what its process
    # derived before: the committed IR, derived in one process in VARIANTS order, is also what
    # one fresh process per variant writes, and `cargo xtask regen --check` compares the bytes on
    # every run. The largest bases (most coordinates) go first, so that the workers finish
    # together.
    names = [v.name for v in sorted(VARIANTS, key=lambda v: -v.model.coordinates)]
    names = [n for n in names if only is None or n in only]
    context = multiprocessing.get_context("fork")
    with ProcessPoolExecutor(_jobs(), mp_context=context) as pool:
        jobs = [pool.submit(ir.write_variant, name, args.out) for name in names]
        if only is None or "ground" in only:
            (args.out / "ir" / "ground").mkdir(exist_ok=True)
            jobs.append(pool.submit(ir.write_ground, args.out))
        report = None if only is not None else pool.submit(errata.report)
        for job in jobs:
            print(f"derived {job.result()}", file=sys.stderr)
        if report is not None:
            text, problems = report.result()
            (args.out / "errata.md").write_text(text)
            if problems:
                for p in problems:
                    print(f"errata self-check failed: {p}", file=sys.stderr)
                return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
