#!/usr/bin/python3
"""The cost tables of docs/rtl.md, from the recorded per-module Yosys records.

    cost_tables.py [--cache DIR] [--write FILE | --check FILE]

Prints (or writes between the `<!-- cost-tables:begin -->` and `<!-- cost-tables:end -->` marks
of FILE, or checks that FILE holds exactly) three tables: the whole unit at N = 1, 2, 3, 4, 6 with
the other parameters at their defaults; the default unit (N = 2) by module record; and the deepest
path of the default unit through the hierarchy. Every figure is composed by scripts/yosys_cost.py
from docs/results/costs/modules/ and nothing is synthesized: a record missing for the current RTL
is an error that names the module.
"""

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import yosys_cost  # noqa: E402
import cost_records  # noqa: E402
import doc_block  # noqa: E402  (the marked block of a document)

BEGIN = "<!-- cost-tables:begin (scripts/cost_tables.py --write docs/rtl.md) -->"
END = "<!-- cost-tables:end -->"
INT_BLOCKS = (1, 2, 3, 4, 6)


def num(n):
    return f"{n:,}".replace(",", "\u202f") if isinstance(n, int) else str(n)


def tables(cache):
    out = []
    results = {n: cost_records.cost({"IntBlocks": n}, cache, require_cached=True) for n in INT_BLOCKS}
    out.append("| N | generic cells | flip-flops | CMOS transistors | logic depth | LUT | FF | DSP48 | CARRY4 |")
    out.append("|---|---|---|---|---|---|---|---|---|")
    for n, r in results.items():
        u = r["blocks"]["tess_unit"]
        x = u.get("xilinx", {})
        out.append(f"| {n} | {num(u['cells'])} | {num(u['flops'])} | {num(u['transistors'])} | {u['depth']} | "
                   f"{num(x.get('lut', '-'))} | {num(x.get('ff', '-'))} | {num(x.get('dsp', '-'))} | "
                   f"{num(x.get('carry4', '-'))} |")
    default = results[2]
    unit = default["blocks"]["tess_unit"]["transistors"]
    out.append("")
    out.append("| module record (N = 2) | instances | transistors each | share of the unit | flip-flops each | "
               "own logic depth |")
    out.append("|---|---|---|---|---|---|")
    for rec in sorted(default["records"], key=lambda r: -r["transistors"] * r["instances"]):
        share = 100.0 * rec["transistors"] * rec["instances"] / unit
        out.append(f"| {rec['module']} | {rec['instances']} | {num(rec['transistors'])} | {share:.1f} % | "
                   f"{num(rec['flops'])} | {rec['depth']} |")
    out.append("")
    out.append("Deepest path of the default unit (gates counted so far where it crosses a module boundary):")
    out.append("")
    for where, gates in default["blocks"]["tess_unit"]["critical_path"]:
        out.append(f"    {gates:>4}  {where.strip()}")
    return "\n".join(out) + "\n"


def main(argv):
    ap = argparse.ArgumentParser(prog="cost_tables.py", description=__doc__.split("\n\n")[0])
    ap.add_argument("--cache", default=str(yosys_cost.REPO / "docs" / "results" / "costs" / "modules"))
    group = ap.add_mutually_exclusive_group()
    group.add_argument("--write", metavar="FILE", help="replace the marked block of FILE")
    group.add_argument("--check", metavar="FILE", help="fail unless the marked block of FILE is current")
    args = ap.parse_args(argv)
    try:
        text = tables(args.cache)
    except yosys_cost.CostError as e:
        print(f"cost_tables.py: error: {e}", file=sys.stderr)
        return 1
    target = args.write or args.check
    if not target:
        sys.stdout.write(text)
        return 0
    return doc_block.replace_or_check(target, BEGIN, END, text, bool(args.check), "cost_tables.py",
                                      "the cost tables of the records", f"scripts/cost_tables.py --write {target}")


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
