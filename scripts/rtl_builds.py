#!/usr/bin/python3
"""The Verilated builds of the unit as `tessim schema` lists them (rtl/builds.json, embedded in
tessim): scripts take a build's flags from here instead of spelling them.

    rtl_builds.py [--tessim build/bin/tessim] args NAME    --variant NAME and its hardware flags
    rtl_builds.py [--tessim build/bin/tessim] names        every build, one a line
    rtl_builds.py table [--write FILE | --check FILE]      the build table of docs/rtl.md

`args` prints the arguments separated by spaces (no argument contains one), for a shell array:
    n3=($(/usr/bin/python3 scripts/rtl_builds.py --tessim "$tessim" args n3_lat3))
`table` reads rtl/builds.json itself (no tessim needed) and prints the table, or writes it between
the `<!-- rtl-builds:begin -->` and `<!-- rtl-builds:end -->` marks of FILE, or checks that FILE
holds exactly that table (a ctest test).
"""
import argparse
import json
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import sweep  # noqa: E402
import yosys_cost  # noqa: E402  (tess_pkg's defaults)
import doc_block  # noqa: E402  (the marked block of a document)

REPO = Path(__file__).resolve().parent.parent
BUILDS_JSON = REPO / "rtl" / "builds.json"
BEGIN = "<!-- rtl-builds:begin (scripts/rtl_builds.py table --write docs/rtl.md) -->"
END = "<!-- rtl-builds:end -->"
# The Verilator options rtl/CMakeLists.txt gives a build.
VERIF_ARGS = "--x-assign unique --x-initial unique --assert"
FAST_ARGS = "--x-assign fast --x-initial fast"
# tess_unit parameters as docs/rtl.md writes them (Parameters); any other is written by its name.
SYMBOLS = {"IntBlocks": "N", "IntLatency": "Λ", "Contexts": "V", "TriFifoDepth": "Dt",
           "VtxFifoDepth": "Dv", "CpBuffers": "Nb", "BaryBits": "B", "CpgLanes": "Ec",
           "CpgDigitBits": "r", "CpgCopies": "Mc", "AlphaBits": "α A"}
CPG_SHAPE = ("CpgLanes", "CpgDigitBits")


def builds(tessim):
    """Every build: name, verif, inject_bug, parameters (tess_unit names), hardware (configuration
    keys), flags (the hardware flags that select it), triangle_bits, vertex_bits."""
    return sweep.schema(tessim)["rtl_builds"]


def build(tessim, name):
    for b in builds(tessim):
        if b["name"] == name:
            return b
    raise SystemExit(f"rtl_builds: no RTL build '{name}' in `{tessim} schema` "
                     f"(known: {', '.join(b['name'] for b in builds(tessim))})")


def cosim_args(tessim, name):
    """`tessim cosim` arguments that run build NAME: --variant NAME and its hardware flags."""
    return ["--variant", name] + build(tessim, name)["flags"]


def values(vs):
    """1 … 4 for a run of three or more consecutive integers, else 1, 2."""
    if len(vs) >= 3 and all(isinstance(v, int) for v in vs) and list(vs) == list(range(vs[0], vs[0] + len(vs))):
        return f"{vs[0]} … {vs[-1]}"
    return ", ".join(str(v) for v in vs)


def parameter_text(params, defaults):
    """A build's parameters as the table writes them, in builds.json's order; `params` maps each
    name to its value, or to a list of values for the one parameter a group of builds varies."""
    def one(name, v):
        return v if isinstance(v, list) else [v]

    def width(name):
        return params.get(name, defaults[name])

    parts, cpg_named = [], False
    for name, v in params.items():
        shown = values(one(name, v))
        if name in ("CoordIntBits", "CoordFracBits"):
            if name == "CoordFracBits" and "CoordIntBits" in params:
                continue  # written with CoordIntBits
            fields = [f"{s} = {params[n]}" for n, s in (("CoordIntBits", "I"), ("CoordFracBits", "F"))
                      if n in params]
            parts.append(f"W = {1 + width('CoordIntBits') + width('CoordFracBits')} ({', '.join(fields)})")
        elif name == "CpgTags":
            parts.append("scalar tags" if v == 1 else f"CpgTags = {shown}")
        elif name == "CpgProductReg":
            parts.append("registered products" if v == 1 else f"CpgProductReg = {shown}")
        elif name in SYMBOLS:
            text = f"{SYMBOLS[name]} = {shown}"
            if name in CPG_SHAPE and not cpg_named:
                text, cpg_named = "CPG " + text, True
            if name == "CpgDigitBits" and isinstance(v, int):
                w = 1 + width("CoordIntBits") + width("CoordFracBits")
                if v >= w:
                    text += " (a whole quotient a cycle)"
                elif w % v:
                    text += f" (D·r = {math.ceil(w / v) * v} > W)"
            parts.append(text)
        else:
            parts.append(f"{name} = {shown}")
    return ", ".join(parts)


# The classes of a parameter's values that reach different logic: a bug that shows only at one of
# them (a ring pointer that wraps only at a power of two, a digit step that does not divide W) needs
# a build of that class. Counts of rings and lanes, latencies, widths and switches are classes by
# value; a FIFO depth by shape (a pointer that wraps by itself at a power of two, or not); the CPG's
# digit bits by how they meet W. InjectBug selects a deliberate fault, not a configuration.
def value_class(name, value, params):
    if name in ("TriFifoDepth", "VtxFifoDepth"):
        return "1" if value == 1 else "power of two" if value & (value - 1) == 0 else "not a power of two"
    if name == "CpgDigitBits":
        w = 1 + params["CoordIntBits"] + params["CoordFracBits"]
        return ("1 (bit-serial)" if value == 1 else "W (a whole quotient a cycle)" if value >= w
                else "divides W" if w % value == 0 else "does not divide W")
    return str(value)


def parameter_classes(parameters, defaults):
    """{(parameter, class)} of one build: every tess_unit parameter, those the build does not set at
    their tess_pkg defaults (`parameters`: builds.json's [name, value] pairs)."""
    params = dict(defaults)
    params.update(dict(parameters))
    skip = {"InjectBug"}
    return {(k, value_class(k, v, params)) for k, v in params.items()
            if k not in skip and (k in dict(parameters) or k in CLASSED_DEFAULTS)}


# tess_pkg defaults that configure the unit (the others are constants of the package).
CLASSED_DEFAULTS = ("CoordIntBits", "CoordFracBits", "BaryBits", "AlphaBits", "IntBlocks", "IntLatency", "Contexts",
                    "TriFifoDepth", "VtxFifoDepth", "CpBuffers", "CpgLanes", "CpgDigitBits", "CpgCopies",
                    "CpgProductReg", "CpgTags")


def uncovered_classes(shipped, reached, defaults):
    """The classes of the builds `shipped` (builds.json entries) that no build in `reached` has:
    [(parameter, class, first shipped build that has it)], empty when the campaign reaches them all."""
    have = set().union(*(parameter_classes(b["parameters"], defaults) for b in reached)) if reached else set()
    missing = {}
    for b in shipped:
        if dict(b["parameters"]).get("InjectBug"):
            continue
        for c in sorted(parameter_classes(b["parameters"], defaults) - have):
            missing.setdefault(c, b["name"])
    return [(k, v, name) for (k, v), name in sorted(missing.items())]


def groups(builds):
    """Consecutive builds that differ in one parameter's value only (n1 … n4), as lists."""
    out = []
    for b in builds:
        g = out[-1] if out else None
        if g and b["verif"] == g[0]["verif"] and [k for k, _ in b["parameters"]] == [k for k, _ in g[0]["parameters"]]:
            differ = {k for (k, x), (_, y) in zip(b["parameters"], g[0]["parameters"]) if x != y}
            fixed = {k for m in g[1:] for (k, x), (_, y) in zip(m["parameters"], g[0]["parameters"]) if x != y}
            if len(differ) == 1 and (not fixed or differ == fixed):
                g.append(b)
                continue
        out.append([b])
    return out


def names(items, ticked=True):
    q = (lambda s: f"`{s}`") if ticked else str
    return f"{q(items[0])} … {q(items[-1])}" if len(items) >= 3 else ", ".join(q(s) for s in items)


def table(builds_json=BUILDS_JSON, rtl_dir=REPO / "rtl"):
    """The table of the Verilated builds (docs/rtl.md, Verilated builds), from rtl/builds.json."""
    defaults = yosys_cost.package_defaults(rtl_dir)
    builds = json.loads(Path(builds_json).read_text())["builds"]
    out = ["| variant | model | parameters | Verilator options |", "|---|---|---|---|"]
    fast_written = False
    for g in groups(builds):
        params = {}
        for i, (k, v) in enumerate(g[0]["parameters"]):
            vs = [b["parameters"][i][1] for b in g]
            params[k] = vs if len(set(vs)) > 1 else v
        if g[0]["verif"]:
            opts = f"`{VERIF_ARGS}`"
        else:
            opts = "fast" if fast_written else f"`{FAST_ARGS}`"
            fast_written = True
        out.append(f"| {names([b['name'] for b in g])} | {names(['Vtess_' + b['name'] for b in g])} | "
                   f"{parameter_text(params, defaults)} | {opts} |")
    return "\n".join(out) + "\n"


def table_main(a):
    text = table()
    target = a.write or a.check
    if not target:
        sys.stdout.write(text)
        return 0
    return doc_block.replace_or_check(target, BEGIN, END, text, a.check, "rtl_builds.py", "the build table of rtl/builds.json",
                                      f"scripts/rtl_builds.py table --write {target}")


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tessim", default=str(REPO / "build" / "bin" / "tessim"))
    sub = ap.add_subparsers(dest="what", required=True)
    sub.add_parser("args").add_argument("name")
    sub.add_parser("names")
    tp = sub.add_parser("table").add_mutually_exclusive_group()
    tp.add_argument("--write", metavar="FILE", help="replace the marked block of FILE")
    tp.add_argument("--check", metavar="FILE", help="fail unless the marked block of FILE is current")
    a = ap.parse_args(argv)
    if a.what == "table":
        return table_main(a)
    try:
        if a.what == "args":
            print(" ".join(cosim_args(a.tessim, a.name)))
        else:
            print("\n".join(b["name"] for b in builds(a.tessim)))
    except sweep.SpecError as e:
        raise SystemExit(f"rtl_builds: {e}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
