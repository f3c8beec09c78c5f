#!/usr/bin/python3
"""Hardware cost of every RTL configuration in a sweep's results, joined to its rows.

    costs.py RESULTS.csv [-o OUT.csv] [--where KEY=V[,V...] ...]... [--compose-cpg] [--cache DIR]
             [--no-xilinx] [--tessim PATH] [--dry-run | --cached-only | --require-cached]

For each distinct RTL configuration among the rows (the parameters that `tessim schema` maps to a
tess_unit parameter: int_blocks, int_latency, te_contexts, coord_int_bits, coord_frac_bits,
bary_bits, tri_fifo_depth, vtx_fifo_depth; the normal mode is an input of the RTL and the GPE is
not part of it) runs scripts/synth.sh, which synthesizes the
whole unit, the CPG and one INT block with Yosys 0.23 (docs/rtl.md, Synthesis: generic `synth`
cells and flip-flops, `stat -tech cmos` transistors after flip-flop legalisation, `synth_xilinx`
LUT/FF/DSP, `ltp` logic depth after flatten). Adds to every row of a costed configuration:

    cost_unit_*   whole unit (transistors, cells, flops, depth, xilinx_lut, xilinx_ff, xilinx_dsp, ...)
    cost_cpg_*    the CPG alone
    cost_int_*    one INT block alone
    cost_int_all_transistors   N x one INT block
    cost_rest_transistors      unit - CPG - N INT blocks (TE control, contexts, buffers, FIFOs)

Rows of the gpe CPG mapping get the same figures (the RTL has a dedicated CPG; subtract cost_cpg_*
for a unit whose CPG runs on the geometry engine).

Synthesis takes minutes per configuration, so results are cached (default: docs/results/costs/,
one JSON per configuration) under a SHA-256 of the configuration, the content of every RTL
source, of synth.sh and the Yosys version: a changed RTL re-synthesizes, an unchanged one never.
--where restricts the configurations costed (e.g. --where int_latency=1 te_contexts=4
int_blocks=1,2,4; the key `grid` matches the rows of the named grids); --where may be given
several times, a row is costed when it matches any of them; rows outside get no cost columns.

--compose-cpg costs a configuration whose CPG is not the sequential one (cpg_lanes, cpg_digit_bits
away from their defaults) without synthesizing its whole unit: the unit with the sequential CPG and
otherwise the same parameters is synthesized (or looked up), the CPG variant alone is synthesized
(synth.sh --cpg-only), and the unit's figures become unit - sequential CPG + CPG variant (cells,
flip-flops, transistors, LUT/FF/DSP/CARRY4 add; the depth is the larger of the two, since the CPG's
results are registered before they leave it). Such rows have cost_composed = 1
(docs/results/load-balancing.md says how close the composition is to a whole-unit synthesis).

Writes OUT.csv (default: RESULTS-costs.csv beside RESULTS.csv; --in-place overwrites RESULTS.csv)
and its JSON twin, like scripts/sweep.py.
"""

import argparse
import hashlib
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import sweep  # noqa: E402  (shared CSV/JSON writer and reader)

REPO = Path(__file__).resolve().parent.parent
CACHE_SCHEMA = 2

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


def digest_text(script):
    """The synthesis script as the digest sees it: its comment lines do not change what Yosys
    computes, so editing them keeps the recorded costs valid (the RTL is hashed verbatim)."""
    return b"\n".join(line for line in script.split(b"\n") if not line.lstrip().startswith(b"#"))


def snapshot_sources(synth, directory):
    """Copies the RTL and the synthesis script into `directory` (rtl/, scripts/ as in the repo, so
    synth.sh finds the RTL next to itself) and returns the copy of synth.sh and the SHA-256 of
    what was copied. Every synthesis of the run reads this snapshot, so an RTL file edited while
    the run goes on cannot end up under the digest of another version."""
    h = hashlib.sha256()
    (directory / "rtl").mkdir()
    (directory / "scripts").mkdir()
    for path in sorted((REPO / "rtl").glob("tess_*.sv")) + [Path(synth)]:
        data = path.read_bytes()
        h.update(path.name.encode())
        h.update(digest_text(data) if path == Path(synth) else data)
        target = directory / ("scripts" if path == Path(synth) else "rtl") / path.name
        target.write_bytes(data)
    copy = directory / "scripts" / Path(synth).name
    copy.chmod(0o755)
    return copy, h.hexdigest()


def yosys_version():
    try:
        return subprocess.run(["yosys", "-V"], capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError) as e:
        raise SystemExit(f"costs.py: error: yosys not available: {e}")


def cache_key(config, digest, yosys, xilinx, cpg_only=False):
    ident = {"schema": CACHE_SCHEMA, "params": dict(config), "sources_sha256": digest, "yosys": yosys,
             "xilinx": xilinx}
    if cpg_only:
        ident["blocks"] = "tess_cpg"
    return hashlib.sha256(json.dumps(ident, sort_keys=True).encode()).hexdigest()


# The CPG's own parameters, and the ones it shares with the unit (the coordinate format).
CPG_PARAMS = ("CpgLanes", "CpgDigitBits", "CpgTags")
CPG_FORMAT_PARAMS = ("CoordIntBits", "CoordFracBits")


def cpg_variant_of(config, defaults):
    """(base, cpg) if `config` has a CPG variant away from the defaults: the same configuration with
    the sequential CPG, and the parameters the CPG alone is synthesized with; else None."""
    values = dict(config)
    if all(values.get(p) == defaults.get(p) for p in CPG_PARAMS):
        return None
    base = tuple((n, defaults[n] if n in CPG_PARAMS else v) for n, v in config)
    cpg = tuple((n, v) for n, v in config if n in CPG_PARAMS + CPG_FORMAT_PARAMS)
    return base, cpg


def compose(base, cpg_result, base_config):
    """The unit of `base` with its CPG replaced by the variant of `cpg_result` (see --compose-cpg)."""
    out = json.loads(json.dumps(base))
    old, new = base["blocks"]["tess_cpg"], cpg_result["blocks"]["tess_cpg"]
    unit = out["blocks"]["tess_unit"]
    for k in ("cells", "flops", "transistors"):
        unit[k] = unit[k] - old[k] + new[k]
    unit["transistors_exact"] = unit.get("transistors_exact", True) and new.get("transistors_exact", True)
    unit["depth"] = max(unit["depth"], new["depth"])
    if unit.get("xilinx") and new.get("xilinx"):
        for k in unit["xilinx"]:
            unit["xilinx"][k] = unit["xilinx"][k] - old["xilinx"][k] + new["xilinx"][k]
    out["blocks"]["tess_cpg"] = new
    out["composed_from"] = {"unit": describe(base_config), "cpg": cpg_result.get("overrides", "")}
    out["seconds"] = base.get("seconds", 0) + cpg_result.get("seconds", 0)
    return out


def provenance():
    """The commit the RTL was taken from, and whether rtl/ or synth.sh differed from it."""
    def git(*args):
        try:
            return subprocess.run(["git", "-C", str(REPO), *args], capture_output=True, text=True,
                                  check=True).stdout.strip()
        except (OSError, subprocess.CalledProcessError):
            return None
    return {"commit": git("rev-parse", "HEAD"),
            "uncommitted_changes": bool(git("status", "--porcelain", "rtl", "scripts/synth.sh"))}


def synthesize(synth, config, xilinx, cpg_only=False):
    with tempfile.TemporaryDirectory(prefix="tessim-costs-") as tmp:
        out = Path(tmp) / "costs.json"
        args = ["bash", str(synth)]
        for name, value in config:
            args += ["-chparam", name, str(value)]
        args += ["--json", str(out)]
        if not xilinx:
            args.append("--no-xilinx")
        if cpg_only:
            args.append("--cpg-only")
        proc = subprocess.run(args, capture_output=True, text=True)
        if proc.returncode != 0:
            raise RuntimeError(f"synth.sh {describe(config)}: exit status {proc.returncode}:\n{proc.stderr.strip()}")
        return json.loads(out.read_text())


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
    cols["cost_composed"] = 1 if "composed_from" in result else 0
    return cols


def main(argv):
    ap = argparse.ArgumentParser(prog="costs.py", description=__doc__.split("\n\n")[0])
    ap.add_argument("results", help="results CSV of scripts/sweep.py (its JSON twin is read when present)")
    ap.add_argument("-o", "--output", help="output CSV (default: RESULTS-costs.csv beside RESULTS)")
    ap.add_argument("--in-place", action="store_true", help="overwrite RESULTS (and its JSON twin) instead")
    ap.add_argument("--where", nargs="*", action="append", metavar="KEY=V[,V...]",
                    help="cost only the configurations of rows matching all of these (repeat: any group)")
    ap.add_argument("--compose-cpg", action="store_true",
                    help="cost a CPG variant as the unit with the sequential CPG, minus that CPG, plus the variant "
                         "synthesized alone")
    ap.add_argument("--cache", default=str(REPO / "docs" / "results" / "costs"), help="cache directory")
    ap.add_argument("--synth", default=str(REPO / "scripts" / "synth.sh"), help="synthesis script")
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
    if not Path(args.synth).exists():
        print(f"costs.py: error: {args.synth} not found", file=sys.stderr)
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

    # --compose-cpg: a CPG variant needs the unit with the sequential CPG and the variant alone.
    rtl_defaults = {p["rtl"]: p["default"] for p in sch["parameters"] if p["rtl"]}
    composed = {}
    if args.compose_cpg:
        for c in list(configs):
            parts = cpg_variant_of(c, rtl_defaults)
            if parts:
                composed[c] = parts
                configs.remove(c)
                if parts[0] not in configs:
                    configs.append(parts[0])
    cpg_configs = sorted({parts[1] for parts in composed.values()})

    xilinx = not args.no_xilinx
    snapshot = tempfile.TemporaryDirectory(prefix="tessim-costs-src-")
    synth, digest = snapshot_sources(args.synth, Path(snapshot.name))
    yosys = yosys_version()
    source = provenance()
    cache = Path(args.cache)
    cache.mkdir(parents=True, exist_ok=True)
    results = {}
    missing = []
    cpg_results = {}
    for c in configs:
        path = cache / f"{cache_key(c, digest, yosys, xilinx)}.json"
        if path.exists():
            results[c] = json.loads(path.read_text())["result"]
        else:
            missing.append((c, path, False))
    for c in cpg_configs:
        path = cache / "cpg" / f"{cache_key(c, digest, yosys, xilinx, cpg_only=True)}.json"
        if path.exists():
            cpg_results[c] = json.loads(path.read_text())["result"]
        else:
            missing.append((c, path, True))
    total = len(configs) + len(cpg_configs)
    print(f"costs.py: {len(configs)} RTL configurations and {len(cpg_configs)} CPG variants alone, "
          f"{total - len(missing)} cached, {len(missing)} to synthesize", file=sys.stderr)
    if args.dry_run:
        for c in configs:
            print(f"  {'cached ' if c in results else 'missing'}  {describe(c)}", file=sys.stderr)
        for c in cpg_configs:
            print(f"  {'cached ' if c in cpg_results else 'missing'}  CPG alone: {describe(c)}", file=sys.stderr)
        return 0

    if args.require_cached and missing:
        for c, _, cpg_only in missing:
            print(f"costs.py: error: no recorded cost of {'the CPG alone, ' if cpg_only else ''}{describe(c)} for "
                  f"the current RTL, synth.sh and "
                  f"{yosys} in {cache}; run scripts/costs.py without --require-cached to synthesize it",
                  file=sys.stderr)
        return 1
    if args.cached_only:
        missing = []
    start = time.monotonic()
    for i, (c, path, cpg_only) in enumerate(missing):
        t0 = time.monotonic()
        print(f"costs.py: [{i + 1}/{len(missing)}] synthesizing {'the CPG alone, ' if cpg_only else ''}"
              f"{describe(c)} ...", file=sys.stderr, flush=True)
        try:
            result = synthesize(synth, c, xilinx, cpg_only)
        except (RuntimeError, OSError, json.JSONDecodeError) as e:
            print(f"costs.py: error: {e}", file=sys.stderr)
            return 1
        record = {"params": dict(c), "sources_sha256": digest, "yosys": yosys, "xilinx": xilinx,
                  "source": source, "result": result}
        path.parent.mkdir(parents=True, exist_ok=True)
        sweep.write_atomic(path, json.dumps(record, indent=1) + "\n")
        (cpg_results if cpg_only else results)[c] = result
        done = time.monotonic() - start
        eta = done / (i + 1) * (len(missing) - i - 1)
        print(f"costs.py: [{i + 1}/{len(missing)}] done in {time.monotonic() - t0:.0f} s, "
              f"ETA {sweep.fmt_time(eta)}", file=sys.stderr, flush=True)

    for c, (base, cpg) in composed.items():
        if base in results and cpg in cpg_results:
            results[c] = compose(results[base], cpg_results[cpg], base)

    costed = 0
    for r in rows:
        for k in [k for k in r if k.startswith("cost_")]:
            del r[k]
        if selected(r) and rtl_config(r) in results:
            r.update(cost_columns(results[rtl_config(r)], int(r["int_blocks"])))
            costed += 1
    out = args.output or (args.results if args.in_place else
                          str(Path(args.results).with_name(Path(args.results).stem + "-costs.csv")))
    sweep.write_results(rows, out, sweep.param_order(sch))
    print(f"costs.py: cost columns on {costed} of {len(rows)} rows -> {out}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
