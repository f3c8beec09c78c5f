#!/usr/bin/python3
"""Markdown table of the unit's parameters from `tessim schema` (README.md, Configuration files).

    params_table.py [--tessim PATH]

tests/sim/params_test.cpp checks that README.md lists every parameter with its flags, default and
range; rerun this and paste its output when a parameter changes.
"""

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import sweep  # noqa: E402  (schema reader)


def value_text(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    return str(v)


def range_text(p):
    if p["type"] == "enum":
        return ", ".join(p["choices"])
    if p["type"] == "uint64":
        return "0..2^64-1"
    def num(v):  # as sim::range_text prints it: integral bounds without a fraction
        return str(int(v)) if float(v).is_integer() else repr(v)
    return f"{num(p['minimum'])}..{num(p['maximum'])}"


def table(sch):
    lines = ["| key | flag (aliases) | kind | default | range | unit | RTL | meaning |",
             "|---|---|---|---|---|---|---|---|"]
    for p in sch["parameters"]:
        flags = f"`{p['flag']}`" + "".join(f", `{a}`" for a in p["aliases"])
        symbol = f"{p['symbol']}: " if p["symbol"] else ""
        rtl = f"`{p['rtl']}`" if p["rtl"] else "–"
        lines.append(f"| `{p['key']}` | {flags} | {p['kind']} | {value_text(p['default'])} | {range_text(p)} | "
                     f"{p['unit'] or '–'} | {rtl} | {symbol}{p['description']} |")
    return "\n".join(lines)


def main(argv):
    ap = argparse.ArgumentParser(prog="params_table.py", description=__doc__.split("\n\n")[0])
    ap.add_argument("--tessim", default=str(sweep.DEFAULT_TESSIM), help="tessim binary (default: build/bin/tessim)")
    args = ap.parse_args(argv)
    try:
        print(table(sweep.schema(args.tessim)))
    except sweep.SpecError as e:
        print(f"params_table.py: error: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
