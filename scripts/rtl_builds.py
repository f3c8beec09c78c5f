#!/usr/bin/python3
"""The Verilated builds of the unit as `tessim schema` lists them (rtl/builds.json, embedded in
tessim): scripts take a build's flags from here instead of spelling them.

    rtl_builds.py [--tessim build/bin/tessim] args NAME    --variant NAME and its hardware flags
    rtl_builds.py [--tessim build/bin/tessim] names        every build, one a line

`args` prints the arguments separated by spaces (no argument contains one), for a shell array:
    n3=($(/usr/bin/python3 scripts/rtl_builds.py --tessim "$tessim" args n3_lat3))
"""
import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import sweep  # noqa: E402

REPO = Path(__file__).resolve().parent.parent


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


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tessim", default=str(REPO / "build" / "bin" / "tessim"))
    sub = ap.add_subparsers(dest="what", required=True)
    sub.add_parser("args").add_argument("name")
    sub.add_parser("names")
    a = ap.parse_args(argv)
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
