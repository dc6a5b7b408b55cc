"""python -m rocking_derive --out DIR: writes DIR/ir/<variant>.json and DIR/errata.md."""

from __future__ import annotations

import argparse
import pathlib
import sys

from . import errata, ir
from .models import VARIANTS


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="rocking_derive", description=__doc__)
    ap.add_argument("--out", required=True, type=pathlib.Path, help="output directory")
    ap.add_argument("--only", help="derive only this variant (for quick experiments)")
    args = ap.parse_args(argv)
    (args.out / "ir").mkdir(parents=True, exist_ok=True)
    for variant in VARIANTS:
        if args.only and variant.name != args.only:
            continue
        text = ir.dumps(ir.variant_ir(variant))
        (args.out / "ir" / f"{variant.name}.json").write_text(text)
        print(f"derived {variant.name}", file=sys.stderr)
    if not args.only or args.only == "ground":
        (args.out / "ir" / "ground").mkdir(exist_ok=True)
        (args.out / "ir" / "ground" / "ground.json").write_text(ir.dumps(ir.ground_ir()))
        print("derived ground", file=sys.stderr)
    if not args.only:
        report, problems = errata.report()
        (args.out / "errata.md").write_text(report)
        if problems:
            for p in problems:
                print(f"errata self-check failed: {p}", file=sys.stderr)
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
