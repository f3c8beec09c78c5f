#!/usr/bin/python3
"""The study's configurations in silicon units: area (mm²), clock (MHz), throughput (Mvertices/s)
on the OSU 0.18 um cells, beside the generic proxies they replace (docs/silicon.md).

    silicon_study.py [--record] [--jobs J] [--write | --check]

For the N sweep at the defaults and the CPG-variant grid of the study (edge lanes 1, 3 x divider
digit bits 1, 2, 4, 8, 24 x N = 1..4), composes each configuration's silicon cost from the records
of scripts/silicon.py (`--record` maps the missing ones: minutes per CPG variant; without it a
missing record is an error), joins the generic cost the study used (logic depth, transistors:
scripts/cost_records.py's stored results) and the simulated throughput of docs/results/results.csv
(grid `cpg`: sphereWithHole, quadratic normals, the geometry engine at K = 4 cycles per vertex, L =
4 and 16), and writes docs/results/silicon/configurations.csv and the tables of docs/silicon.md
between its `silicon-tables` marks (`--check` fails unless both are current).

Throughput in Mvertices/s is the simulated vertices per cycle times the configuration's own clock.
The geometry engine's K counts cycles of that same clock, as simulated: a faster unit gets a
proportionally faster geometry engine (docs/silicon.md, Limits).
"""

import argparse
import csv
import io
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import cost_records  # noqa: E402
import doc_block  # noqa: E402
import silicon  # noqa: E402

REPO = Path(__file__).resolve().parent.parent
OUT = REPO / "docs" / "results" / "silicon" / "configurations.csv"
DOC = REPO / "docs" / "silicon.md"
RESULTS = REPO / "docs" / "results" / "results.csv"
BEGIN = "<!-- silicon-tables:begin (scripts/silicon_study.py --write) -->"
END = "<!-- silicon-tables:end -->"
LEVELS = (4, 16)
WORKLOAD = {"grids": "cpg", "mesh": "sphereWithHole.stl", "normals": "quadratic", "gpe_cycles": "4"}


def configurations():
    """The N sweep at the defaults, then the CPG-variant grid (lanes x digit bits x N)."""
    configs = [{"IntBlocks": n} for n in (1, 2, 3, 4, 6)]
    for r in (1, 2, 4, 8, 24):
        for lanes in (1, 3):
            for n in (1, 2, 3, 4):
                c = {"IntBlocks": n, "CpgDigitBits": r, "CpgLanes": lanes}
                if not (r == 1 and lanes == 1):
                    configs.append(c)
    # What shortens the paths the defaults are limited by: the study's pick within the depth
    # budget, the CPG's products registered with three-cycle INT blocks (and four CP buffers).
    configs += [{"CpBuffers": 4, "CpgProductReg": 1, "IntLatency": 3},
                {"CpBuffers": 4, "CpgLanes": 3, "CpgProductReg": 1, "IntLatency": 3}]
    return configs


def full(params):
    """A configuration with the study's keys filled in from the defaults."""
    return {"IntBlocks": params.get("IntBlocks", 2), "CpgLanes": params.get("CpgLanes", 1),
            "CpgDigitBits": params.get("CpgDigitBits", 1), "CpgProductReg": params.get("CpgProductReg", 0),
            "IntLatency": params.get("IntLatency", 1), "CpBuffers": params.get("CpBuffers", 2)}


def throughputs():
    """(int_blocks, cpg_lanes, cpg_digit_bits, L) -> simulated vertices per cycle."""
    out = {}
    with open(RESULTS, newline="") as f:
        for r in csv.DictReader(f):
            if "cpg" not in r["grids"].split(";") or not r["mesh"].endswith(WORKLOAD["mesh"]):
                continue
            if r["normals"] != WORKLOAD["normals"] or r["gpe_cycles"] != WORKLOAD["gpe_cycles"]:
                continue
            if (r["cpg_copies"], r["cp_buffers"], r["int_latency"], r["te_contexts"], r["cpg_mapping"]) != \
                    ("1", "2", "1", "4", "dedicated"):
                continue
            key = (int(r["int_blocks"]), int(r["cpg_lanes"]), int(r["cpg_digit_bits"]), int(r["tess_factor"]))
            out[key] = float(r["throughput"])
    return out


def spearman(xs, ys):
    """Spearman's rank correlation (ties share their mean rank)."""
    def ranks(v):
        order = sorted(range(len(v)), key=lambda i: v[i])
        r = [0.0] * len(v)
        i = 0
        while i < len(order):
            j = i
            while j + 1 < len(order) and v[order[j + 1]] == v[order[i]]:
                j += 1
            for k in range(i, j + 1):
                r[order[k]] = (i + j) / 2 + 1
            i = j + 1
        return r

    rx, ry = ranks(xs), ranks(ys)
    mx, my = sum(rx) / len(rx), sum(ry) / len(ry)
    cov = sum((a - mx) * (b - my) for a, b in zip(rx, ry))
    vx = sum((a - mx) ** 2 for a in rx) ** 0.5
    vy = sum((b - my) ** 2 for b in ry) ** 0.5
    return cov / (vx * vy) if vx and vy else float("nan")


def rows(record, jobs, missing):
    """The table's rows; configurations without records (when not recording) are appended to
    `missing` instead."""
    thr = throughputs()
    out = []
    for params in configurations():
        try:
            s = silicon.cost(params, jobs=jobs, require_cached=not record, log=sys.stderr if record else None)
        except silicon.SiliconError:
            if record:
                raise
            missing.append(params)
            continue
        g = cost_records.cost(params)
        c = full(params)
        unit, cpg, one_int = s["blocks"]["tess_unit"], s["blocks"]["tess_cpg"], s["blocks"]["tess_int"]
        te = s["blocks"]["tess_te"]
        row = {"int_blocks": c["IntBlocks"], "cpg_lanes": c["CpgLanes"], "cpg_digit_bits": c["CpgDigitBits"],
               "cpg_product_reg": c["CpgProductReg"], "int_latency": c["IntLatency"], "cp_buffers": c["CpBuffers"],
               "area_mm2": round(unit["area_um2"] / 1e6, 4), "area_cpg_mm2": round(cpg["area_um2"] / 1e6, 4),
               "area_int_mm2": round(one_int["area_um2"] / 1e6, 4),
               "area_seq_mm2": round(unit["area_seq_um2"] / 1e6, 4), "cells": unit["cells"],
               "leakage_uw": round(unit["leakage_nw"] / 1e3, 2),
               "clock_ns": unit["clock_ns"], "clock_mhz": round(1000.0 / unit["clock_ns"], 2),
               "cpg_path_ns": cpg["clock_ns"], "te_path_ns": te["clock_ns"],
               "critical_from": unit["critical_path_ends"]["from"], "critical_to": unit["critical_path_ends"]["to"],
               "generic_depth": g["blocks"]["tess_unit"]["depth"],
               "generic_transistors": g["blocks"]["tess_unit"]["transistors"]}
        for level in LEVELS:
            plain = c["CpgProductReg"] == 0 and c["IntLatency"] == 1 and c["CpBuffers"] == 2
            t = thr.get((c["IntBlocks"], c["CpgLanes"], c["CpgDigitBits"], level)) if plain else None
            row[f"vertices_per_cycle_L{level}"] = round(t, 5) if t is not None else ""
            row[f"mvertices_per_s_L{level}"] = round(t * row["clock_mhz"], 2) if t is not None else ""
            row[f"mvertices_per_s_mm2_L{level}"] = round(t * row["clock_mhz"] / row["area_mm2"], 2) \
                if t is not None else ""
        out.append(row)
    return out


def csv_text(table):
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=list(table[0]), lineterminator="\n")
    w.writeheader()
    w.writerows(table)
    return buf.getvalue()


def variant(r):
    radix = 2 ** r["cpg_digit_bits"]
    text = f"{r['cpg_lanes']} lane{'s' if r['cpg_lanes'] > 1 else ''}, radix {radix if r['cpg_digit_bits'] < 24 else '2^24'}"
    if r["cpg_product_reg"]:
        text += ", products registered"
    if r["int_latency"] != 1 or r["cp_buffers"] != 2:
        text += f", Λ = {r['int_latency']}, Nb = {r['cp_buffers']}"
    return text


def flips(table, generic, silicon_key):
    """Pairs that the generic proxy orders one way and silicon the other."""
    out = []
    for i, a in enumerate(table):
        for b in table[i + 1:]:
            ga, gb = generic(a), generic(b)
            sa, sb = a[silicon_key], b[silicon_key]
            if ga == gb or sa == sb:
                continue
            if (ga > gb) != (sa > sb):
                out.append((a, b))
    return out


def doc_tables(table, missing=()):
    lines = []
    if missing:
        lines += [f"Not recorded yet, so not in the tables ({len(missing)} configurations; "
                  "`scripts/silicon_study.py --record --write` maps them): "
                  + "; ".join(", ".join(f"{k} = {v}" for k, v in m.items()) for m in missing) + ".", ""]
    n_sweep = [r for r in table if r["cpg_lanes"] == 1 and r["cpg_digit_bits"] == 1 and r["cpg_product_reg"] == 0]
    lines += ["**The unit by N** (defaults otherwise: one-lane radix-2 CPG, Λ = 1, V = 4); throughput on "
              "sphereWithHole, quadratic normals, K = 4:", "",
              "| N | area mm² | of it CPG | one INT | flip-flop area | leakage µW | clock ns | MHz "
              "| Mvertices/s L = 4 | L = 16 | Mvertices/s per mm², L = 16 |",
              "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in sorted(n_sweep, key=lambda r: r["int_blocks"]):
        lines.append(f"| {r['int_blocks']} | {r['area_mm2']:.2f} | {r['area_cpg_mm2']:.2f} | {r['area_int_mm2']:.2f} "
                     f"| {r['area_seq_mm2']:.2f} | {r['leakage_uw']:.1f} | {r['clock_ns']:.2f} | {r['clock_mhz']:.1f} "
                     f"| {r['mvertices_per_s_L4'] or '–'} | {r['mvertices_per_s_L16'] or '–'} "
                     f"| {r['mvertices_per_s_mm2_L16'] or '–'} |")
    lines += ["", "**CPG variants at N = 2**, each with its own clock:", "",
              "| CPG | area mm² | CPG mm² | clock ns | MHz | generic depth | Mvertices/s L = 4 | L = 16 "
              "| critical path (start → end) |", "|---|---|---|---|---|---|---|---|---|"]
    for r in [r for r in table if r["int_blocks"] == 2]:
        lines.append(f"| {variant(r)} | {r['area_mm2']:.2f} | {r['area_cpg_mm2']:.2f} | {r['clock_ns']:.2f} "
                     f"| {r['clock_mhz']:.1f} | {r['generic_depth']} | {r['mvertices_per_s_L4'] or '–'} "
                     f"| {r['mvertices_per_s_L16'] or '–'} | `{r['critical_from']}` → `{r['critical_to']}` |")
    by_cpg = [r for r in table if r["cpg_path_ns"] >= r["clock_ns"]]
    te = [r["te_path_ns"] for r in table]
    lines += ["", f"**What sets the clock.** The CPG's path sets it in {len(by_cpg)} of the {len(table)} configurations "
              f"(from {min(r['cpg_path_ns'] for r in table):.2f} to {max(r['cpg_path_ns'] for r in table):.2f} ns); "
              f"the TE's loop through an INT block (operand select, the INT block's sum, the result register) takes "
              f"{min(te):.2f} to {max(te):.2f} ns. With the CPG's path shortened, that loop would allow "
              f"{1000.0 / max(te):.1f} to {1000.0 / min(te):.1f} MHz."]
    rho = spearman([r["generic_depth"] for r in table], [r["clock_ns"] for r in table])
    lines += ["", f"**Does the generic depth rank the configurations as static timing does?** Over the "
              f"{len(table)} configurations above, Spearman's rank correlation between the generic logic depth "
              f"and the STA clock period is **{rho:.3f}**."]
    depth_levels = {r["generic_depth"] for r in table}
    lines.append(f"The generic depth takes {len(depth_levels)} distinct values over them "
                 f"({', '.join(str(d) for d in sorted(depth_levels))} levels).")
    for level in LEVELS:
        with_thr = [r for r in table if r[f"mvertices_per_s_L{level}"] != ""]
        if len(with_thr) < 2:
            continue
        generic = [r[f"vertices_per_cycle_L{level}"] * 48.0 / max(48, r["generic_depth"]) for r in with_thr]
        sil = [r[f"mvertices_per_s_L{level}"] for r in with_thr]
        rho = spearman(generic, sil)
        flipped = flips(with_thr, lambda r: r[f"vertices_per_cycle_L{level}"] * 48.0 / max(48, r["generic_depth"]),
                        f"mvertices_per_s_L{level}")
        lines.append(f"At L = {level}, throughput per unit time by the generic depth budget (48 levels) against "
                     f"Mvertices/s at the STA clock: rank correlation **{rho:.3f}** over {len(with_thr)} "
                     f"configurations, {len(flipped)} of {len(with_thr) * (len(with_thr) - 1) // 2} pairs ordered "
                     f"the other way.")
    best = {}
    for level in LEVELS:
        cand = [r for r in table if r[f"mvertices_per_s_L{level}"] != ""]
        if cand:
            best[level] = (max(cand, key=lambda r: r[f"mvertices_per_s_L{level}"]),
                           max(cand, key=lambda r: r[f"mvertices_per_s_mm2_L{level}"]))
    if best:
        lines += ["", "| L | fastest (Mvertices/s) | most per mm² (Mvertices/s per mm²) |", "|---|---|---|"]
        for level, (fast, dense) in best.items():
            lines.append(f"| {level} | N = {fast['int_blocks']}, {variant(fast)}: {fast[f'mvertices_per_s_L{level}']} "
                         f"at {fast['clock_mhz']:.1f} MHz, {fast['area_mm2']:.2f} mm² "
                         f"| N = {dense['int_blocks']}, {variant(dense)}: {dense[f'mvertices_per_s_mm2_L{level}']} "
                         f"({dense[f'mvertices_per_s_L{level}']} Mvertices/s, {dense['area_mm2']:.2f} mm²) |")
    lines += outside_comparison(table)
    lines += flat_comparison()
    return "\n".join(lines) + "\n"


def outside_comparison(table, level=16):
    """The fastest configuration at L = `level` beside the published figures of
    docs/results/silicon/outside.json: per clock everywhere, absolute rates at 0.18 um only."""
    cand = [r for r in table if r[f"mvertices_per_s_L{level}"] != ""]
    if not cand:
        return []
    best = max(cand, key=lambda r: r[f"mvertices_per_s_L{level}"])
    per_vertex = 2.0 * level * level / ((level + 1) * (level + 2))  # a patch's triangles per its vertices
    vpc = best[f"vertices_per_cycle_L{level}"]
    chips = json.loads((OUT.parent / "outside.json").read_text())["chips"]
    lines = ["", f"**Beside other tessellation hardware** (docs/results/silicon/outside.json; this unit at L = {level}, "
             f"where a patch has {per_vertex:.3f} triangles per vertex it outputs):", "",
             "| what | node | vertices per clock | triangles per clock | MHz | Mvertices/s | area mm² | kind |",
             "|---|---|---|---|---|---|---|---|",
             f"| this unit, N = {best['int_blocks']}, {variant(best)} | 0.18 µm (composed) | {vpc:.3f} "
             f"| {vpc * per_vertex:.3f} | {best['clock_mhz']:.1f} | {best[f'mvertices_per_s_L{level}']} "
             f"| {best['area_mm2']:.2f} | fixed function, one unit |"]
    for c in chips:
        tpc = c.get("triangles_per_clock")
        lines.append(f"| {c['name']} | {str(c['node_um']) + ' µm' if 'node_um' in c else '–'} "
                     f"| {c.get('vertices_per_clock', '–')} | {tpc if tpc is not None else '–'} "
                     f"| {c.get('clock_mhz', '–')} | {c.get('mvertices_per_s', '–')} | – | {c['kind']} |")
    kaist = next((c for c in chips if "mvertices_per_s" in c), None)
    if kaist:
        units = -(-kaist["mvertices_per_s"] // best[f"mvertices_per_s_L{level}"])
        lines += ["", f"To match the {kaist['name']}'s {kaist['mvertices_per_s']} Mvertices/s at L = {level}, one unit of "
                  f"the fastest configuration falls short by {kaist['mvertices_per_s'] / best[f'mvertices_per_s_L{level}']:.1f}×: "
                  f"at least {int(units)} such units ({int(units) * best['area_mm2']:.0f} mm², if a system of units "
                  f"scaled linearly), or more vertices per clock from each."]
    return lines


def flat_comparison():
    """Composed against flattened for the configurations with a committed flattened run
    (docs/results/silicon/flat/*.json, written by `scripts/silicon.py --flat --json`)."""
    runs = sorted((OUT.parent / "flat").glob("*.json"))
    if not runs:
        return []
    lines = ["", "**Composed against flattened** (the unit mapped and timed in one piece; "
             "`scripts/silicon.py --flat -chparam ... --json docs/results/silicon/flat/NAME.json`):", "",
             "| configuration | area composed mm² | flattened | difference | clock composed ns | flattened "
             "| difference | flattened worst path |", "|---|---|---|---|---|---|---|---|"]
    for path in runs:
        f = json.loads(path.read_text())
        c = silicon.cost(f["params"], require_cached=True)
        name = ", ".join(f"{k} = {v}" for k, v in f["params"].items()) or "defaults"
        da = 100.0 * (c["area_mm2"] - f["area_mm2"]) / f["area_mm2"]
        dc = 100.0 * (c["clock_ns"] - f["clock_ns"]) / f["clock_ns"]
        lines.append(f"| {name} | {c['area_mm2']:.3f} | {f['area_mm2']:.3f} | {da:+.1f} % | {c['clock_ns']:.2f} "
                     f"| {f['clock_ns']:.2f} | {dc:+.1f} % | `{f['worst']['from']}` → `{f['worst']['to']}` |")
    return lines


def main(argv):
    ap = argparse.ArgumentParser(prog="silicon_study.py", description=__doc__.split("\n\n")[0])
    ap.add_argument("--record", action="store_true", help="map and time the records that are missing")
    ap.add_argument("--jobs", type=int, default=2)
    g = ap.add_mutually_exclusive_group()
    g.add_argument("--write", action="store_true", help="write the CSV and docs/silicon.md's tables")
    g.add_argument("--check", action="store_true", help="fail unless both are current")
    args = ap.parse_args(argv)
    missing = []
    try:
        table = rows(args.record, args.jobs, missing)
    except (silicon.SiliconError, cost_records.yosys_cost.CostError) as e:
        print(f"silicon_study.py: error: {e}", file=sys.stderr)
        return 1
    text, doc = csv_text(table), doc_tables(table, missing)
    if args.check:
        if not OUT.exists() or OUT.read_text() != text:
            print(f"silicon_study.py: {OUT.relative_to(REPO)} is not current; run scripts/silicon_study.py --write",
                  file=sys.stderr)
            return 1
    elif args.write:
        OUT.parent.mkdir(parents=True, exist_ok=True)
        OUT.write_text(text)
    else:
        sys.stdout.write(text + "\n" + doc)
        return 0
    return doc_block.replace_or_check(DOC, BEGIN, END, doc, args.check, "silicon_study.py",
                                      "the silicon tables of the records", "scripts/silicon_study.py --write")


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
