#!/usr/bin/python3
"""The configurations the study costs, their composed costs, and pruning of superseded records.

    cost_records.py list [--tessim PATH] [--write | --check]
    cost_records.py record [--jobs J]
    cost_records.py prune [--dry-run]
    cost_records.py check

docs/results/costs/configurations.json is the one list of every unit configuration the project
costs: each as its tess_unit parameters that differ from tess_pkg's defaults, with the committed
files that use its cost (every CSV under docs/results/ with cost columns, and docs/rtl.md's cost
tables). `list --write` rebuilds it from those files (it needs `tessim schema` for the mapping of
result columns onto tess_unit parameters); `list --check` fails when it is out of date.

A configuration's cost is composed from per-module Yosys records (scripts/yosys_cost.py), which
needs the unit elaborated by Yosys: 10-30 s a configuration on the 2-core machine, so about twenty
minutes for the study's hundred-odd configurations. The composed result is therefore kept too, in
docs/results/costs/configurations/<key>.json, under a SHA-256 of the record schema, the Yosys
version, the RTL sources' names and text (comments and white space aside) and the parameters: any
other edit of the RTL misses every composed result, and the configuration is elaborated and
composed again from its records. A composed result is used only while every record it names is present.

    record   composes every listed configuration of the current RTL (synthesizing the records it
             lacks, `--jobs` Yosys processes at a time) and stores the composed results
    prune    deletes the module records and composed results that no listed configuration of the
             current RTL uses (a configuration not composed yet keeps the records it has)
    check    fails, naming them, unless every listed configuration has a composed result of the
             current RTL whose records are all present
"""

import argparse
import csv
import hashlib
import json
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import yosys_cost  # noqa: E402  (per-module records, composed)

REPO = Path(__file__).resolve().parent.parent
COSTS = REPO / "docs" / "results" / "costs"
MODULES = COSTS / "modules"
LIST = COSTS / "configurations.json"
# The cost tables of docs/rtl.md (scripts/cost_tables.py): N = 1..4, 6 at the defaults.
COST_TABLE_CONFIGS = [{"IntBlocks": n} for n in (1, 2, 3, 4, 6)]


def composed_dir(cache):
    """Composed results beside the module records: costs/modules -> costs/configurations."""
    cache = Path(cache)
    return cache.parent / "configurations" if cache.name == "modules" else cache / "configurations"


def normalized(params, rtl_dir=REPO / "rtl"):
    """The parameters that differ from tess_pkg's defaults, as ints, in name order."""
    defaults = yosys_cost.package_defaults(rtl_dir)
    return {k: int(v) for k, v in sorted(params.items()) if int(v) != defaults.get(k)}


def without_comments(text):
    """SystemVerilog text without its comments and with runs of white space as one space: a
    comment or a re-indentation changes no composed key (string literals are kept as written)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            out.append(text[i:j + 1])
            i = j + 1
        elif text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
            out.append(" ")
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            i = n if j < 0 else j + 2
            out.append(" ")
        else:
            out.append(c)
            i += 1
    return " ".join("".join(out).split())


def sources_digest(rtl_dir=REPO / "rtl"):
    """SHA-256 of the RTL sources' names and text, comments and white space aside."""
    h = hashlib.sha256()
    for path in yosys_cost.rtl_sources(rtl_dir):
        h.update(path.name.encode() + b"\0" + without_comments(path.read_text()).encode() + b"\0")
    return h.hexdigest()


def composed_key(params, xilinx, rtl_dir=REPO / "rtl", yosys=None, digest=None):
    ident = {"schema": yosys_cost.RECORD_SCHEMA, "yosys": yosys or yosys_cost.yosys_version(), "xilinx": xilinx,
             "sources": digest or sources_digest(rtl_dir), "params": normalized(params, rtl_dir)}
    return hashlib.sha256(json.dumps(ident, sort_keys=True).encode()).hexdigest()


def load_composed(path, cache):
    """The stored composed result at `path`, or None if absent or if a record it names is gone."""
    if not path.exists():
        return None
    result = json.loads(path.read_text())
    if any(not (Path(cache) / f"{r['key']}.json").exists() for r in result["records"]):
        return None
    result["synthesized"] = 0
    return result


def cost(params, cache=MODULES, rtl_dir=REPO / "rtl", jobs=2, xilinx=True, require_cached=False, log=None,
         yosys=None, digest=None):
    """yosys_cost.cost(), through the store of composed results: no Yosys run when the current
    RTL's composed result is stored and its records are present; otherwise elaborated, composed
    and stored."""
    path = composed_dir(cache) / f"{composed_key(params, xilinx, rtl_dir, yosys, digest)}.json"
    result = load_composed(path, cache)
    if result is not None:
        return result
    result = yosys_cost.cost(params, cache, rtl_dir, jobs, xilinx, require_cached, log)
    path.parent.mkdir(parents=True, exist_ok=True)
    stored = dict(result, synthesized=0)
    tmp = path.with_suffix(".tmp")
    tmp.write_text(json.dumps(stored, indent=1, sort_keys=True) + "\n")
    tmp.replace(path)
    return result


def read_list(path=None):
    return json.loads(Path(path or LIST).read_text())["configurations"]


def study_configurations(tessim):
    """Every configuration the committed study files cost, with the files that use it."""
    import costs  # noqa: E402  (the row -> tess_unit parameter mapping of `tessim schema`)
    costs.load_rtl_params(tessim)
    used = {}

    def add(params, user):
        key = json.dumps(normalized(params), sort_keys=True)
        used.setdefault(key, set()).add(user)

    for path in sorted((REPO / "docs" / "results").rglob("*.csv")):
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
        for r in rows:
            if r.get("cost_unit_transistors"):
                row = {k: costs.parse_value(v) for k, v in r.items() if v != ""}
                add(dict(costs.rtl_config(row)), str(path.relative_to(REPO)))
    for params in COST_TABLE_CONFIGS:
        add(params, "docs/rtl.md")
    return [{"params": json.loads(k), "used_by": sorted(v)} for k, v in sorted(used.items())]


def cmd_list(args):
    configs = study_configurations(args.tessim)
    text = json.dumps({"description": "Every unit configuration the project costs (scripts/cost_records.py list "
                                      "--write): tess_unit parameters that differ from tess_pkg's defaults, and "
                                      "the committed files that use the cost.",
                       "configurations": configs}, indent=1) + "\n"
    if args.write:
        LIST.write_text(text)
        print(f"cost_records.py: {len(configs)} configurations -> {LIST.relative_to(REPO)}")
        return 0
    if args.check:
        if not LIST.exists() or LIST.read_text() != text:
            print(f"cost_records.py: {LIST.relative_to(REPO)} is not the list of configurations the committed study "
                  f"files cost ({len(configs)}); run scripts/cost_records.py list --write", file=sys.stderr)
            return 1
        print(f"cost_records.py: {LIST.relative_to(REPO)}: {len(configs)} configurations, current")
        return 0
    for c in configs:
        print(json.dumps(c["params"]), " ".join(c["used_by"]))
    return 0


def current_results(cache, require, used_by=None):
    """(params, stored composed result or None) for every listed configuration, current RTL (or
    those that a file of `used_by` uses)."""
    yosys, digest = yosys_cost.yosys_version(), sources_digest()
    out = []
    for c in read_list():
        if used_by and not set(used_by) & set(c["used_by"]):
            continue
        path = composed_dir(cache) / f"{composed_key(c['params'], True, yosys=yosys, digest=digest)}.json"
        out.append((c["params"], load_composed(path, cache), path))
    if require:
        missing = [p for p, r, _ in out if r is None]
        if missing:
            raise yosys_cost.CostError(f"{len(missing)} listed configurations have no composed result of the "
                                       f"current RTL, e.g. {json.dumps(missing[0])}; run scripts/cost_records.py record")
    return out


def cmd_record(args):
    start = time.monotonic()
    todo = [p for p, r, _ in current_results(MODULES, False, args.used_by) if r is None]
    print(f"cost_records.py: {len(todo)} configurations to compose",
          file=sys.stderr, flush=True)
    yosys_cost.elaborate_all(todo, jobs=args.jobs)
    n = yosys_cost.synthesize_missing(todo, MODULES, jobs=args.jobs, log=sys.stderr)
    for params in todo:
        cost(params, MODULES, jobs=args.jobs)
    print(f"cost_records.py: {len(todo)} configurations composed, {n} records synthesized, "
          f"{time.monotonic() - start:.0f} s", file=sys.stderr)
    return 0


def cmd_prune(args):
    results = current_results(MODULES, False)
    keep_records = {r["key"] for _, result, _ in results if result for r in result["records"]}
    # A configuration not composed yet keeps whatever records of it are stored (its elaboration
    # names them): pruning never deletes work that `record` would redo.
    unrecorded = [params for params, result, _ in results if result is None]
    yosys_cost.elaborate_all(unrecorded, jobs=args.jobs)
    for params in unrecorded:
        keep_records |= yosys_cost.record_keys(params)
    keep_composed = {path.name for _, result, path in results if result}
    stale = [p for p in sorted(MODULES.glob("*.json")) if p.stem not in keep_records]
    stale += [p for p in sorted(composed_dir(MODULES).glob("*.json")) if p.name not in keep_composed]
    size = sum(p.stat().st_size for p in stale)
    verb = "would delete" if args.dry_run else "deleted"
    if not args.dry_run:
        for p in stale:
            p.unlink()
    print(f"cost_records.py: {verb} {len(stale)} files ({size / 1e6:.1f} MB) that no listed configuration of the "
          f"current RTL uses; kept {len(keep_records)} module records and {len(keep_composed)} composed results")
    return 0


def cmd_check(args):
    try:
        results = current_results(MODULES, True, args.used_by)
    except yosys_cost.CostError as e:
        print(f"cost_records.py: error: {e}", file=sys.stderr)
        return 1
    which = f"used by {', '.join(args.used_by)}" if args.used_by else "listed"
    print(f"cost_records.py: all {len(results)} configurations {which} recorded for the current RTL")
    return 0


def main(argv):
    ap = argparse.ArgumentParser(prog="cost_records.py", description=__doc__.split("\n\n")[0])
    sub = ap.add_subparsers(dest="command", required=True)
    p = sub.add_parser("list", help="the configurations the committed study files cost")
    p.add_argument("--tessim", default=str(REPO / "build" / "bin" / "tessim"))
    g = p.add_mutually_exclusive_group()
    g.add_argument("--write", action="store_true", help="write docs/results/costs/configurations.json")
    g.add_argument("--check", action="store_true", help="fail unless docs/results/costs/configurations.json is current")
    p = sub.add_parser("record", help="compose and store every listed configuration of the current RTL")
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--used-by", nargs="+", metavar="FILE", help="only the configurations these files use")
    p = sub.add_parser("prune", help="delete records no listed configuration of the current RTL uses")
    p.add_argument("--dry-run", action="store_true")
    p.add_argument("--jobs", type=int, default=2)
    p = sub.add_parser("check", help="every listed configuration recorded for the current RTL")
    p.add_argument("--used-by", nargs="+", metavar="FILE", help="only the configurations these files use")
    args = ap.parse_args(argv)
    return {"list": cmd_list, "record": cmd_record, "prune": cmd_prune, "check": cmd_check}[args.command](args)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
