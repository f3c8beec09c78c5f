#!/usr/bin/python3
"""Figures and tables of a sweep's results (scripts/sweep.py): the load-balancing study's, or any
one figure of any sweep.

    plots.py RESULTS.csv --out DIR                      the study (docs/results/load-balancing.md)
    plots.py RESULTS.csv --x KEY --y KEY [--hue KEY] [--facet KEY] [--where KEY=V[,V...] ...]
             [--logx] [--logy] [-o FIG.png]             one figure of any sweep

RESULTS.csv is the output of scripts/sweep.py, optionally with the cost_* columns of
scripts/costs.py. The study picks rows by the grid names of the specs in scripts/sweeps/ (column
`grids`) and by parameter values; a figure whose rows are absent is skipped with a note. It
writes into DIR (default ./plots, never the committed docs/results unless asked: results.sh
passes --out): one PNG and one SVG per figure, and tables.md with the numbers behind the figures.

A figure of any sweep: KEY is any column (a parameter such as int_blocks, a statistic such as
throughput or te.starved_by_cpg, a cost such as cost_unit_transistors); --hue draws one line per
value, --facet one panel per value, --where keeps matching rows; rows that agree on every other
key are averaged (the figure says how many); --where grid=NAME keeps the rows of a spec's grid. Writes FIG.png (default ./plot.png) and its SVG.

The parts live beside this file: plots_data (rows, formats, style), plots_output (PNG/SVG and
tables.md), plots_balance, plots_cpg, plots_workload, plots_adaptive, plots_mesh (the study's
figure families) and plots_generic (one figure of any sweep).
"""

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
# The study's parts, one module each (plots_data first: the Agg backend and the figures' style).
from plots_data import REPO, SYMBOLS, load_rows  # noqa: E402
from plots_adaptive import fig_adaptive, fig_adaptive_partitioning  # noqa: E402
from plots_balance import fig_cost, fig_throughput_vs_n, fig_utilisation_vs_n  # noqa: E402
from plots_cpg import fig_cpg_copies, fig_cpg_share, fig_cpg_variants  # noqa: E402
from plots_generic import generic_figure  # noqa: E402
from plots_mesh import bus_traffic, fig_errors  # noqa: E402
from plots_output import Output  # noqa: E402
from plots_workload import fig_contexts, fig_normals, fig_stall, tables_extra  # noqa: E402


def mesh_info_reader(tessim):
    """`tessim info --json` of a mesh (bounding box, diagonal, half-extent, welded vertices, edges
    and triangles), with the schema's arithmetic position bounds by (coord_int_bits,
    coord_frac_bits): nothing here re-derives what tessim computes."""
    import json
    import subprocess
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    import sweep
    cache = {}
    bounds = {}

    def info(mesh):
        if mesh in cache:
            return cache[mesh]
        try:
            if not bounds:
                for b in sweep.schema(str(tessim))["position_bound"]:
                    bounds[(b["coord_int_bits"], b["coord_frac_bits"])] = b["units"]
            j = json.loads(subprocess.run([str(tessim), "info", str(mesh), "--json"], check=True,
                                          capture_output=True, text=True).stdout)
            j["position_bound"] = bounds
            cache[mesh] = j
        except (OSError, subprocess.CalledProcessError, ValueError, KeyError, sweep.SpecError) as e:
            print(f"plots.py: tessim info {mesh}: {e}", file=sys.stderr)
            cache[mesh] = None
        return cache[mesh]

    return info


def main(argv):
    ap = argparse.ArgumentParser(description="Figures and tables of the load-balancing study.")
    ap.add_argument("results", help="results CSV of scripts/sweep.py (with cost_* columns of scripts/costs.py)")
    ap.add_argument("--out", default="plots", help="output directory of the study's figures (default ./plots)")
    ap.add_argument("--x", help="one figure of any sweep: the column on the x axis")
    ap.add_argument("--y", help="... on the y axis")
    ap.add_argument("--hue", help="... one line per value of this column")
    ap.add_argument("--facet", help="... one panel per value of this column")
    ap.add_argument("--where", nargs="*", action="append", default=[], metavar="KEY=V[,V...]",
                    help="... only rows with these values (repeat: any group)")
    ap.add_argument("--logx", action="store_true")
    ap.add_argument("--logy", action="store_true")
    ap.add_argument("-o", "--output", default="plot.png", help="... the figure (.png; an .svg is written beside it)")
    ap.add_argument("--tessim", default=str(REPO / "build" / "bin" / "tessim"),
                    help="tessim binary: its schema (symbols, interface widths) and mesh bounding boxes")
    args = ap.parse_args(argv)
    rows = load_rows(args.results)
    if not rows:
        print(f"plots.py: error: {args.results} has no rows with status ok", file=sys.stderr)
        return 2
    if args.x or args.y:
        if not (args.x and args.y):
            print("plots.py: error: --x and --y go together", file=sys.stderr)
            return 2
        return generic_figure(rows, args)
    try:
        source = str(Path(args.results).resolve().relative_to(REPO))
    except ValueError:
        source = args.results
    out = Output(args.out, source)
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    import sweep
    try:
        SYMBOLS.update({p["key"]: p["symbol"] for p in sweep.schema(args.tessim)["parameters"] if p["symbol"]})
        items = sweep.schema(args.tessim)["interface"]["items"]
    except (OSError, KeyError, sweep.SpecError) as e:
        print(f"plots.py: error: tessim schema: {e}", file=sys.stderr)
        return 2
    info = mesh_info_reader(args.tessim)
    fig_throughput_vs_n(rows, out)
    fig_utilisation_vs_n(rows, out)
    fig_cost(rows, out)
    fig_cpg_share(rows, out)
    fig_cpg_variants(rows, out)
    fig_cpg_copies(rows, out)
    fig_contexts(rows, out)
    fig_normals(rows, out)
    fig_stall(rows, out)
    fig_adaptive(rows, out)
    fig_adaptive_partitioning(rows, out)
    tables_extra(rows, out)
    fig_errors(rows, out, info)
    bus_traffic(rows, out, info, items)
    out.write_tables()
    for f in out.files:
        print(f"plots.py: wrote {f}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
