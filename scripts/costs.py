#!/usr/bin/python3
"""Hardware cost of every RTL configuration in a sweep's results, joined to its rows.

    costs.py RESULTS.csv [-o OUT.csv] [--where KEY=V[,V...] ...]... [--cache DIR] [--jobs J]
             [--no-xilinx] [--tessim PATH] [--dry-run | --cached-only | --require-cached]

For each distinct RTL configuration among the rows (the parameters that `tessim schema` maps to a
tess_unit parameter; the normal mode is an input of the RTL and the GPE is not part of it),
scripts/yosys_cost.py composes the unit's cost from per-module Yosys 0.23 records (docs/rtl.md,
Cost method: generic `synth` cells and flip-flops, `stat -tech cmos` transistors after flip-flop
legalisation, `synth_xilinx` LUT/FF/DSP, logic depth through the hierarchy). Adds to every row of
a costed configuration:

    cost_unit_*   whole unit (transistors, cells, flops, depth, xilinx_lut, xilinx_ff, xilinx_dsp, ...)
    cost_cpg_*    the CPG (its module and submodules, times its cpg_copies copies)
    cost_int_*    one INT block alone
    cost_int_all_transistors   N x one INT block
    cost_rest_transistors      unit - CPG - N INT blocks (TE control, contexts, buffers, FIFOs, FSUs,
                               the CPG copies' turn pointers and write-port select)
    cost_clock_levels          the configuration's cycle time in gate levels: the depth budget
                               (yosys_cost.DEPTH_BUDGET, 48) or its deepest path if longer
    cost_time_throughput       vertices per budget cycle: throughput x budget / cost_clock_levels
                               (the rate at the configuration's own clock, in a time unit common
                               to every configuration; the GPE's K counts cycles of that clock)
    cost_time_throughput_per_mtr  cost_time_throughput per million unit transistors

Rows of the gpe CPG mapping get the same figures (the RTL has a dedicated CPG; subtract cost_cpg_*
for a unit whose CPG runs on the geometry engine).

Records are kept in docs/results/costs/modules/, one JSON per module and parameter set, under a
SHA-256 of what Yosys reads for that module (scripts/yosys_cost.py): an RTL edit re-synthesizes the
records of the modules it changes, nothing else. --where restricts the configurations costed (e.g.
--where int_latency=1 te_contexts=4 int_blocks=1,2,4; the key `grid` matches the rows of the named
grids); --where may be given several times, a row is costed when it matches any of them; rows
outside get no cost columns.

Writes OUT.csv (default: RESULTS-costs.csv beside RESULTS.csv; --in-place overwrites RESULTS.csv)
and its JSON twin, like scripts/sweep.py.
"""

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import sweep  # noqa: E402  (shared CSV/JSON writer and reader)
import yosys_cost  # noqa: E402  (per-module records, composed)
import cost_records  # noqa: E402  (composed results kept per configuration and RTL)

REPO = Path(__file__).resolve().parent.parent

# Row parameter -> tess_unit parameter, from `tessim schema` (set by main()).
RTL_PARAMS = []
RTL_DEFAULTS = {}  # parameter key -> default, for results that do not list it
SYMBOLS = {}  # tess_unit parameter -> symbol of docs/microarchitecture.md
BLOCK_PREFIX = {"tess_unit": "cost_unit", "tess_cpg": "cost_cpg", "tess_int": "cost_int"}


def parse_value(text):
    for conv in (int, float):
        try:
            return conv(text)
        except ValueError:
            pass
    return {"true": True, "false": False}.get(text, text)


def parse_where(groups):
    """One dict KEY -> set of values per --where group (a row matches any group)."""
    parsed = []
    for items in groups or [[]]:
        where = {}
        for item in items:
            if "=" not in item:
                raise ValueError(f"--where '{item}': expected KEY=VALUE[,VALUE...]")
            key, values = item.split("=", 1)
            where[key] = {parse_value(v) for v in values.split(",")}
        parsed.append(where)
    return parsed


def rtl_config(row):
    # A results file written before a parameter existed holds its default (`tessim schema`).
    return tuple((name, int(row[key] if key in row else RTL_DEFAULTS[key])) for key, name in RTL_PARAMS)


def describe(config):
    return " ".join(f"{SYMBOLS.get(name) or name}={value}" for name, value in config)


def load_rtl_params(tessim):
    """The parameters of the RTL and their symbols, as `tessim schema` lists them."""
    sch = sweep.schema(tessim)
    RTL_PARAMS[:] = [(p["key"], p["rtl"]) for p in sch["parameters"] if p["rtl"]]
    RTL_DEFAULTS.update({p["key"]: p["default"] for p in sch["parameters"] if p["rtl"]})
    SYMBOLS.update({p["rtl"]: p["symbol"] for p in sch["parameters"] if p["rtl"]})
    return sch


def cost_columns(result, n_blocks):
    cols = {}
    for block, entry in result["blocks"].items():
        prefix = BLOCK_PREFIX.get(block)
        if prefix is None:
            continue
        for k in ("transistors", "cells", "flops", "depth"):
            if entry.get(k) is not None:
                cols[f"{prefix}_{k}"] = entry[k]
        for k, v in (entry.get("xilinx") or {}).items():
            cols[f"{prefix}_xilinx_{k}"] = v
    if "cost_int_transistors" in cols:
        cols["cost_int_all_transistors"] = n_blocks * cols["cost_int_transistors"]
        if "cost_unit_transistors" in cols and "cost_cpg_transistors" in cols:
            cols["cost_rest_transistors"] = (cols["cost_unit_transistors"] - cols["cost_cpg_transistors"]
                                             - cols["cost_int_all_transistors"])
    cols["cost_synth_seconds"] = result.get("seconds")
    if cols.get("cost_unit_depth") is not None:
        cols["cost_clock_levels"] = yosys_cost.clock_levels(cols["cost_unit_depth"])
    return cols


def time_columns(row):
    """Throughput per unit of time at the configuration's clock (module docstring)."""
    levels, throughput = row.get("cost_clock_levels"), row.get("throughput")
    if levels is None or throughput is None:
        return {}
    per_time = float(throughput) * yosys_cost.DEPTH_BUDGET / float(levels)
    return {"cost_time_throughput": per_time,
            "cost_time_throughput_per_mtr": per_time / (float(row["cost_unit_transistors"]) / 1e6)}


def main(argv):
    ap = argparse.ArgumentParser(prog="costs.py", description=__doc__.split("\n\n")[0])
    ap.add_argument("results", help="results CSV of scripts/sweep.py (its JSON twin is read when present)")
    ap.add_argument("-o", "--output", help="output CSV (default: RESULTS-costs.csv beside RESULTS)")
    ap.add_argument("--in-place", action="store_true", help="overwrite RESULTS (and its JSON twin) instead")
    ap.add_argument("--where", nargs="*", action="append", metavar="KEY=V[,V...]",
                    help="cost only the configurations of rows matching all of these (repeat: any group)")
    ap.add_argument("--cache", default=str(REPO / "docs" / "results" / "costs" / "modules"),
                    help="module record directory (default: docs/results/costs/modules)")
    ap.add_argument("--jobs", type=int, default=2, help="Yosys processes in parallel (default 2)")
    ap.add_argument("--tessim", default=str(sweep.DEFAULT_TESSIM),
                    help="tessim binary whose `tessim schema` names the RTL parameters (default: build/bin/tessim)")
    ap.add_argument("--no-xilinx", action="store_true", help="skip synth_xilinx (faster; no LUT/FF/DSP columns)")
    ap.add_argument("--dry-run", action="store_true", help="list the configurations and whether they are cached")
    ap.add_argument("--cached-only", action="store_true",
                    help="join the cached configurations only, synthesize nothing (the others get no cost columns)")
    ap.add_argument("--require-cached", action="store_true",
                    help="synthesize nothing; fail, naming them, if configurations are not cached (a check that the "
                         "recorded costs belong to the current RTL)")
    args = ap.parse_args(argv)

    try:
        where = parse_where(args.where)
    except ValueError as e:
        print(f"costs.py: error: {e}", file=sys.stderr)
        return 2
    try:
        sch = load_rtl_params(args.tessim)
    except sweep.SpecError as e:
        print(f"costs.py: error: {e}", file=sys.stderr)
        return 2
    rows = sweep.read_rows(args.results)
    if rows and isinstance(rows[0].get("point"), str):  # a CSV without its JSON twin
        rows = [{k: parse_value(v) for k, v in r.items()} for r in rows]

    def matches(row, key, values):
        if key == "grid":  # membership in the row's grids ("a;b")
            return bool(set(str(row.get("grids", "")).split(";")) & {str(v) for v in values})
        return row.get(key) in values

    def selected(row):
        return row.get("status") == "ok" and any(all(matches(row, k, vals) for k, vals in w.items()) for w in where)

    configs = []
    for r in rows:
        if selected(r):
            c = rtl_config(r)
            if c not in configs:
                configs.append(c)

    xilinx = not args.no_xilinx
    cache = Path(args.cache)
    results = {}
    missing = []
    # Stored composed results of the current RTL first (scripts/cost_records.py); Yosys elaborates
    # only the configurations without one.
    yosys, digest = yosys_cost.yosys_version(), cost_records.sources_digest()
    stored = {}
    for c in configs:
        path = cost_records.composed_dir(cache) / f"{cost_records.composed_key(dict(c), xilinx, yosys=yosys, digest=digest)}.json"
        result = cost_records.load_composed(path, cache)
        if result is not None:
            stored[c] = result
    yosys_cost.elaborate_all([dict(c) for c in configs if c not in stored], jobs=args.jobs)
    for c in configs:
        try:
            results[c] = stored.get(c) or cost_records.cost(dict(c), cache, xilinx=xilinx, require_cached=True,
                                                            yosys=yosys, digest=digest)
        except yosys_cost.CostError:
            missing.append(c)
    print(f"costs.py: {len(configs)} RTL configurations, {len(configs) - len(missing)} with every module record "
          f"in {cache}, {len(missing)} to synthesize", file=sys.stderr)
    if args.dry_run:
        for c in configs:
            print(f"  {'cached ' if c in results else 'missing'}  {describe(c)}", file=sys.stderr)
        return 0
    if args.require_cached and missing:
        for c in missing:
            try:
                cost_records.cost(dict(c), cache, xilinx=xilinx, require_cached=True)
            except yosys_cost.CostError as e:
                print(f"costs.py: error: {describe(c)}: {e} (of the current RTL and {yosys_cost.yosys_version()}) "
                      f"in {cache}; run scripts/costs.py without --require-cached to synthesize it", file=sys.stderr)
        return 1
    if args.cached_only:
        missing = []
    start = time.monotonic()
    if missing:
        # Every record any configuration lacks, each once, args.jobs Yosys processes at a time.
        try:
            n = yosys_cost.synthesize_missing([dict(c) for c in missing], cache, xilinx=xilinx, jobs=args.jobs,
                                              log=sys.stderr)
            for c in missing:
                results[c] = cost_records.cost(dict(c), cache, xilinx=xilinx, require_cached=True)
        except (yosys_cost.CostError, OSError) as e:
            print(f"costs.py: error: {e}", file=sys.stderr)
            return 1
        print(f"costs.py: {n} records synthesized for {len(missing)} configurations in "
              f"{sweep.fmt_time(time.monotonic() - start)}", file=sys.stderr, flush=True)

    costed = 0
    for r in rows:
        for k in [k for k in r if k.startswith("cost_")]:
            del r[k]
        if selected(r) and rtl_config(r) in results:
            r.update(cost_columns(results[rtl_config(r)], int(r["int_blocks"])))
            r.update(time_columns(r))
            costed += 1
    out = args.output or (args.results if args.in_place else
                          str(Path(args.results).with_name(Path(args.results).stem + "-costs.csv")))
    sweep.write_results(rows, out, sweep.param_order(sch), sch["statistics"]["per_run"])
    print(f"costs.py: cost columns on {costed} of {len(rows)} rows -> {out}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
