#!/usr/bin/python3
"""What silhouettes do to the unit's balance (docs/results/load-balancing.md §14).

On the camera path of scripts/silhouette_quality.py (8 views around Wuson and sphereWithHole at
one bounding-box diagonal, 800x600, fov 40), runs `tessim sim` for three workloads per view:

    silhouette   --adaptive silhouette --outline-tolerance 0.5 --silhouette camera: the silhouette
                 rule's factors and the blend on the unit (alpha_bits 8)
    screen       --adaptive screen --pixels-per-segment 6: the study's adaptive rule (§10)
    uniform      -L 8: the outline quality the silhouette rule is measured against

on CPG configurations within the depth budget (INT latency 3, registered CPG products, four
control-point buffers; one lane or three lanes of one bit, 1 to 8 copies) for two geometry
engines (N = 2, K = 8 and N = 4, K = 4). Each configuration's transistors and depth come from
scripts/costs.py (per-module Yosys records, synthesized when missing).

Writes OUT/study.csv (one row per mesh, view, workload, configuration and GE: the parameters,
the vertices, patches, cycles and throughput, the limiter, and the cost columns), and OUT/study.md:
per mesh, workload and GE the mean vertices per patch (and the share of single-triangle patches)
and each configuration's throughput as a
share of the GE's rate (its worst view and its mean over the path), and the cheapest
configuration that keeps every view at 97 % or more.

Usage: silhouette_study.py --tessim build/bin/tessim [--out docs/results/silhouette] [--jobs 2]
                           [--replot]
"""
import argparse
import concurrent.futures
import csv
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import silhouette_quality as quality  # noqa: E402  (meshes and camera path)

VIEWS, DISTANCE, SIZE, FOV = 8, 1.0, "800x600", 40
# The unit around the CPG: within the depth budget (docs/rtl.md), as load-balancing.md §13's picks.
BASE = {"int_latency": 3, "cpg_product_reg": 1, "cp_buffers": 4, "te_contexts": 4, "alpha_bits": 8,
        "normals": "quadratic"}
GES = [{"int_blocks": 2, "gpe_cycles": 8}, {"int_blocks": 4, "gpe_cycles": 4}]
CPGS = [(1, 1), (1, 2), (3, 1), (3, 2), (3, 4), (3, 8)]  # (lanes, copies), one digit bit a cycle
WORKLOADS = ["silhouette", "screen", "uniform"]
KEEPS_UP = 0.97
COST_COLUMNS = ["cost_unit_transistors", "cost_cpg_transistors", "cost_unit_depth"]


def workload_args(kind, camera):
    eye, target = camera
    cam = f"eye={quality.fmt(eye)},target={quality.fmt(target)},fov={FOV}"
    if kind == "silhouette":
        return ["--adaptive", "silhouette", "--camera", cam, "--viewport", SIZE, "--outline-tolerance", "0.5",
                "--silhouette", "camera"]
    if kind == "screen":
        return ["--adaptive", "screen", "--camera", cam, "--viewport", SIZE, "--pixels-per-segment", "6"]
    return ["-L", "8"]


def config_name(lanes, copies):
    return f"{lanes}x1" + (f" x{copies}" if copies > 1 else "")


def run_point(tessim, point, scratch):
    params = dict(BASE, **point["ge"], cpg_lanes=point["lanes"], cpg_copies=point["copies"], cpg_digit_bits=1)
    args = [tessim, "sim", quality.MESHES[point["mesh"]]] + workload_args(point["workload"], point["camera"])
    for key, value in params.items():
        args += ["--" + key.replace("_", "-"), str(value)]
    stats = os.path.join(scratch, f"{point['index']}.json")
    subprocess.run(args + ["--stats", stats], check=True, capture_output=True, text=True)
    with open(stats) as f:
        s = json.load(f)
    os.remove(stats)
    row = {"mesh": point["mesh"], "view": point["view"], "workload": point["workload"],
           "config": config_name(point["lanes"], point["copies"]), "status": "ok"}
    row.update(params)
    row.update({"vertices": s["vertices_out"], "patches": s["triangles_in"],
                "single_triangles": s["workload"]["vertices_per_patch_log2_histogram"][0], "cycles": s["cycles"],
                "throughput": s["throughput"], "ge_share": s["throughput"] * params["gpe_cycles"],
                "cpg_cycles_per_triangle": s["cpg_cycles_per_triangle"], "limit": s["bottleneck"].split(":")[0]})
    return row


def simulate(tessim, out_csv, jobs):
    points = []
    for mesh, path in quality.MESHES.items():
        lo, hi = quality.bbox(tessim, path)
        for view, camera in enumerate(quality.camera_path(lo, hi, VIEWS, DISTANCE)):
            for workload in WORKLOADS:
                if workload == "uniform" and view > 0:
                    continue  # the same patches from every view
                for ge in GES:
                    for lanes, copies in CPGS:
                        points.append({"index": len(points), "mesh": mesh, "view": view, "camera": camera,
                                       "workload": workload, "ge": ge, "lanes": lanes, "copies": copies})
    with tempfile.TemporaryDirectory(prefix="tessim-silhouette-study-") as scratch:
        with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
            rows = list(pool.map(lambda p: run_point(tessim, p, scratch), points))
    twin = os.path.splitext(out_csv)[0] + ".json"  # costs.py's JSON twin of an earlier run would win
    if os.path.exists(twin):
        os.remove(twin)
    with open(out_csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    print(f"silhouette_study.py: {len(rows)} runs -> {out_csv}", file=sys.stderr)


def cost(tessim, out_csv, jobs):
    here = os.path.dirname(os.path.abspath(__file__))
    subprocess.run([sys.executable, os.path.join(here, "costs.py"), out_csv, "--in-place", "--tessim", tessim,
                    "--jobs", str(jobs)], check=True)


def report(out_csv, out_md):
    with open(out_csv) as f:
        rows = list(csv.DictReader(f))
    lines = ["<!-- scripts/silhouette_study.py: regenerate, do not edit -->", ""]
    groups = {}
    for r in rows:
        groups.setdefault((r["mesh"], r["workload"], r["int_blocks"], r["gpe_cycles"]), []).append(r)
    for (mesh, workload, n, k), group in sorted(groups.items(), key=lambda g: (g[0][0], WORKLOADS.index(g[0][1]), -int(g[0][3]))):
        views = sorted({r["view"] for r in group})
        first = [r for r in group if r["config"] == group[0]["config"]]
        per_patch = sum(int(r["vertices"]) for r in first) / sum(int(r["patches"]) for r in first)
        single = sum(int(r["single_triangles"]) for r in first) / sum(int(r["patches"]) for r in first)
        lines.append(f"**{mesh}, {workload}, N = {n}, K = {k}** ({len(views)} view{'s' if len(views) > 1 else ''}, "
                     f"{per_patch:.1f} vertices per patch, {single:.0%} of the patches single triangles, "
                     f"{sum(int(r['vertices']) for r in first) / len(views):.0f} vertices per view)")
        lines.append("")
        lines.append("| CPG | C | transistors (M) | depth | share of the GE's rate: worst view | mean | cycles per view | limiter (worst view) |")
        lines.append("|---|---|---|---|---|---|---|---|")
        best = None
        for lanes, copies in CPGS:
            name = config_name(lanes, copies)
            runs = [r for r in group if r["config"] == name]
            worst = min(runs, key=lambda r: float(r["ge_share"]))
            mean = sum(float(r["ge_share"]) for r in runs) / len(runs)
            mtr = float(worst.get("cost_unit_transistors") or "nan") / 1e6
            depth = worst.get("cost_unit_depth") or "–"
            cycles = sum(int(r["cycles"]) for r in runs) / len(runs)
            lines.append(f"| {name} | {worst['cpg_cycles_per_triangle']} | {mtr:.2f} | {depth} | "
                         f"{float(worst['ge_share']):.4f} | {mean:.4f} | {cycles:,.0f} | {worst['limit']} |")
            if float(worst["ge_share"]) >= KEEPS_UP and (best is None or mtr < best[1]):
                best = (name, mtr)
        lines.append("")
        lines.append(f"Cheapest at ≥ {KEEPS_UP:.0%} of the GE's rate on every view: "
                     + (f"**{best[0]}** ({best[1]:.2f} M transistors)." if best else "none of these."))
        lines.append("")
    with open(out_md, "w") as f:
        f.write("\n".join(lines))
    print(f"silhouette_study.py: {out_md}", file=sys.stderr)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--tessim", default="build/bin/tessim")
    ap.add_argument("--out", default="docs/results/silhouette")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--replot", action="store_true", help="only rewrite study.md from study.csv")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    out_csv = os.path.join(args.out, "study.csv")
    if not args.replot:
        simulate(os.path.abspath(args.tessim), out_csv, args.jobs)
        cost(os.path.abspath(args.tessim), out_csv, args.jobs)
    report(out_csv, os.path.join(args.out, "study.md"))


if __name__ == "__main__":
    main()
