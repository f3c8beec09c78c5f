#!/usr/bin/python3
"""Several units on one stream: how many, which distribution, how much reassembly buffer
(docs/results/load-balancing.md §16).

On the camera path of scripts/silhouette_quality.py (8 views around Wuson and sphereWithHole at one
bounding-box diagonal, 800x600, fov 40) with the screen rule (6 pixels per segment), runs `tessim
sim --units M` for M = 1, 2, 4, 8, 16 units with P = M geometry-engine ports at K = 1, every
distribution policy and reassembly buffers of R = 16 .. 16384 slots, in stream order and, for
least_loaded, unordered (what keeping the order costs). Each unit keeps up with small
patches on its own (load-balancing.md §13's fast unit: N = 14, V = 16, eight control-point buffers
and ten copies of the three-lane CPG of 4 bits a cycle, INT latency 1).

Writes OUT/study.csv (one row per mesh, view, M, policy, reassembly and R: vertices, patches,
cycles, throughput, the limit, the largest buffer occupancy, the stalls), OUT/study.md (per mesh, M
and policy: the worst view's and the mean vertices per cycle against R, and the smallest R that
keeps every view at 90 % of M; then ordered against unordered) and OUT/scaleout.png/.svg
(throughput against M; throughput against R, ordered and unordered).

Usage: scaleout_study.py --tessim build/bin/tessim [--out docs/results/scaleout] [--jobs 2] [--replot]
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
UNIT = {"gpe_cycles": 1, "int_blocks": 14, "te_contexts": 16, "cp_buffers": 8, "cpg_lanes": 3, "cpg_digit_bits": 4,
        "cpg_copies": 10}
MS = [1, 2, 4, 8, 16]
POLICIES = ["round_robin", "least_loaded", "earliest_finish"]
UNORDERED_POLICY = "least_loaded"  # without order to keep, the balancing policy
SLOTS = [16, 64, 256, 1024, 4096, 16384]
TARGET = 0.9


def run_point(tessim, point, scratch):
    eye, target = point["camera"]
    cam = f"eye={quality.fmt(eye)},target={quality.fmt(target)},fov={FOV}"
    params = dict(UNIT, units=point["M"])
    if point["M"] > 1:  # tessim refuses a system's options for one unit (they would be ignored)
        params.update(ge_ports=point["M"], distribution=point["policy"], reorder_slots=point["R"],
                      reassembly=point["reassembly"])
    # One thread a run: the points run side by side already.
    cmd = [tessim, "sim", quality.MESHES[point["mesh"]], "--quiet", "--threads", "1", "--adaptive", "screen", "--camera", cam,
           "--viewport", SIZE, "--pixels-per-segment", "6"]
    for key, value in params.items():
        cmd += ["--" + key.replace("_", "-"), str(value)]
    stats = os.path.join(scratch, f"{point['index']}.json")
    subprocess.run(cmd + ["--stats", stats], check=True, capture_output=True, text=True)
    with open(stats) as f:
        s = json.load(f)
    os.remove(stats)
    row = {"mesh": point["mesh"], "view": point["view"], "M": point["M"], "policy": point["policy"],
           "reassembly": point["reassembly"], "R": point["R"],
           "vertices": s["vertices_out"], "patches": s["triangles_in"], "cycles": s["cycles"],
           "throughput": s["throughput"], "limit": s["bottleneck"].split(":")[0]}
    system = s.get("system")
    if system:
        row.update({"max_occupancy": system["buffer"]["max_occupancy"],
                    "dispatch_stalls": system["stalls"]["dispatch"],
                    "units_blocked": system["stalls"]["units_blocked_by_buffer"],
                    "ports_waiting_for_unit": system["stalls"]["ports_waiting_for_unit"]})
    return row


def simulate(tessim, out_csv, jobs):
    points = []
    for mesh, path in quality.MESHES.items():
        lo, hi = quality.bbox(tessim, path)
        for view, camera in enumerate(quality.camera_path(lo, hi, VIEWS, DISTANCE)):
            for m in MS:
                for policy in POLICIES if m > 1 else POLICIES[:1]:
                    for r in SLOTS if m > 1 else SLOTS[-1:]:
                        points.append({"index": len(points), "mesh": mesh, "view": view, "camera": camera, "M": m,
                                       "policy": policy, "reassembly": "ordered", "R": r})
                for r in SLOTS if m > 1 else []:
                    points.append({"index": len(points), "mesh": mesh, "view": view, "camera": camera, "M": m,
                                   "policy": UNORDERED_POLICY, "reassembly": "unordered", "R": r})
    with tempfile.TemporaryDirectory(prefix="tessim-scaleout-") as scratch:
        with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
            rows = list(pool.map(lambda p: run_point(tessim, p, scratch), points))
    keys = []
    for r in rows:
        keys += [k for k in r if k not in keys]
    with open(out_csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)
    print(f"scaleout_study.py: {len(rows)} runs -> {out_csv}", file=sys.stderr)


def report(out_csv, out_dir):
    with open(out_csv) as f:
        rows = list(csv.DictReader(f))
    groups, by_mesh, unordered = {}, {}, {}
    for r in rows:
        if r["reassembly"] == "unordered":
            unordered.setdefault((r["mesh"], int(r["M"]), int(r["R"])), []).append(r)
            continue
        groups.setdefault((int(r["M"]), r["policy"], int(r["R"])), []).append(r)
        by_mesh.setdefault((r["mesh"], int(r["M"]), r["policy"], int(r["R"])), []).append(r)
    lines = ["<!-- scripts/scaleout_study.py: regenerate, do not edit -->", "",
             f"Vertices per cycle of M units with P = M ports at K = 1 on {VIEWS} views of each mesh (screen rule, "
             f"6 pixels per segment): the worst view / the mean over the views. Bold: every view at {TARGET:.0%} "
             "of M or more.", ""]
    for mesh in quality.MESHES:
        g0 = by_mesh[(mesh, 1, POLICIES[0], SLOTS[-1])]
        patches = sum(int(x["patches"]) for x in g0) / len(g0)
        per_patch = sum(int(x["vertices"]) for x in g0) / sum(int(x["patches"]) for x in g0)
        lines += [f"**{mesh}** ({patches:.0f} patches per view, {per_patch:.1f} vertices per patch)", "",
                  "| M | policy | " + " | ".join(f"R = {r}" for r in SLOTS) + f" | smallest R at {TARGET:.0%} |",
                  "|---|---|" + "---|" * len(SLOTS) + "---|"]
        for m in MS:
            for policy in POLICIES if m > 1 else POLICIES[:1]:
                cells, smallest = [], None
                for r in SLOTS if m > 1 else SLOTS[-1:]:
                    g = by_mesh[(mesh, m, policy, r)]
                    worst = min(float(x["throughput"]) for x in g)
                    mean = sum(float(x["throughput"]) for x in g) / len(g)
                    ok = worst >= TARGET * m
                    cells.append(f"**{worst:.3f} / {mean:.3f}**" if ok else f"{worst:.3f} / {mean:.3f}")
                    if ok and smallest is None:
                        smallest = r
                if m == 1:
                    cells = ["–"] * (len(SLOTS) - 1) + cells
                lines.append(f"| {m} | {policy} | " + " | ".join(cells) + f" | {smallest if smallest else 'none'} |")
        lines.append("")
    lines += ["**What keeping the order costs**: the worst view's vertices per cycle, in stream order with the "
              "better policy at that R / unordered (least_loaded; the ports take any unit's vertex), and the "
              f"smallest R that keeps every view at {TARGET:.0%} of M each way.", ""]
    for mesh in quality.MESHES:
        lines += [f"**{mesh}**", "",
                  "| M | " + " | ".join(f"R = {r}" for r in SLOTS) + " | smallest R, ordered / unordered |",
                  "|---|" + "---|" * len(SLOTS) + "---|"]
        for m in MS[1:]:
            cells, smallest = [], [None, None]
            for r in SLOTS:
                ordered = max(min(float(x["throughput"]) for x in by_mesh[(mesh, m, p, r)]) for p in POLICIES)
                free = min(float(x["throughput"]) for x in unordered[(mesh, m, r)])
                cells.append(f"{ordered:.3f} / {free:.3f}")
                for i, worst in enumerate((ordered, free)):
                    if worst >= TARGET * m and smallest[i] is None:
                        smallest[i] = r
            lines.append(f"| {m} | " + " | ".join(cells) + " | " +
                         " / ".join(str(x) if x else "none" for x in smallest) + " |")
        lines.append("")
    with open(os.path.join(out_dir, "study.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print(f"scaleout_study.py: {os.path.join(out_dir, 'study.md')}", file=sys.stderr)
    plot(groups, unordered, out_dir)


def plot(groups, unordered, out_dir):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    colours = {"round_robin": "#0072B2", "least_loaded": "#D55E00", "earliest_finish": "#009E73"}
    for policy in POLICIES:
        xs, ys = [], []
        for m in MS:
            g = groups[(m, policy if m > 1 else POLICIES[0], SLOTS[-1])]
            xs.append(m)
            ys.append(sum(float(x["throughput"]) for x in g) / len(g))
        left.plot(xs, ys, "o-", color=colours[policy], label=f"{policy}, R = {SLOTS[-1]}")
    left.plot(MS, MS, ":", color="grey", label="M vertices per cycle")
    left.set_xscale("log", base=2)
    left.set_yscale("log", base=2)
    left.set_xlabel("units M (P = M ports, K = 1)")
    left.set_ylabel("vertices per cycle (mean over the views)")
    left.legend(fontsize=8)
    left.grid(True, which="both", alpha=0.3)
    for i, m in enumerate(MS[1:]):
        colour = f"C{i}"
        ys = [min(float(x["throughput"]) for x in groups[(m, "round_robin", r)]) / m for r in SLOTS]
        right.plot(SLOTS, ys, "o-", color=colour, label=f"M = {m}")
        free = [min(float(x["throughput"]) for mesh in quality.MESHES for x in unordered[(mesh, m, r)]) / m
                for r in SLOTS]
        right.plot(SLOTS, free, "s--", color=colour, alpha=0.6, label=f"M = {m}, unordered")
    right.axhline(TARGET, color="grey", linestyle=":")
    right.set_xscale("log", base=2)
    right.set_xlabel("reassembly buffer R (vertex slots)")
    right.set_ylabel("worst view: vertices per cycle / M\n(round_robin; dashed: unordered, least_loaded)")
    right.legend(fontsize=8)
    right.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(out_dir, f"scaleout.{ext}"), dpi=110)
    print(f"scaleout_study.py: {os.path.join(out_dir, 'scaleout.png')}", file=sys.stderr)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--tessim", default="build/bin/tessim")
    ap.add_argument("--out", default="docs/results/scaleout")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--replot", action="store_true", help="only rewrite study.md and the figure from study.csv")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    out_csv = os.path.join(args.out, "study.csv")
    if not args.replot:
        simulate(os.path.abspath(args.tessim), out_csv, args.jobs)
    report(out_csv, args.out)


if __name__ == "__main__":
    main()
