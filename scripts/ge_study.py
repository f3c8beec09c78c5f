#!/usr/bin/python3
"""The unit or the geometry engine: where to spend the transistors (docs/results/load-balancing.md §15).

On Wuson, for uniform L = 1..16 and the three adaptive views of §13 (screen rule, 6 pixels per
segment; with displacement the screen+nyquist rule, so that no view aliases), without and with a
sine displacement (amplitude 0.02, frequency 80: a wavelength of 0.079, 2 % of the diagonal), and
for geometry engines of K = 2, 4, 8 and 16 cycles of their own work per vertex (four ALU lanes,
docs/microarchitecture.md §12), measures with `tessim sim`:

    (a) unit      the cheapest unit of a grid within the depth budget (INT latency 3, registered CPG
                  products, four control-point buffers; N = 1, 2, 4, 7 INT blocks, V = 4 or 8
                  contexts; CPG 1x1, 3x1 or 3x1 x4) that keeps the GE at >= 97 % of its rate, or the
                  fastest when none does; its transistors from scripts/costs.py (Yosys records);
    (b) gpe       evaluation on the GE (evaluation gpe, cpg_mapping host: the host computes the ten
                  and six coefficients, Boubekeur & Schlick); no unit transistors;
    (c) gpe+lanes the GE given the transistors of (a), less the fixed-function pattern generator it keeps
                  in front of them (the DPG and a factor setup unit, their Yosys records), as extra ALU lanes, each an FP32 fused
                  multiply-add lane of docs/results/ge_lane/costs.json: (c1, measured) the lanes
                  serve the shader's evaluation and displacement, K unchanged; (c2, a model from the
                  measured shader slots) they serve all of the GE's work, its own K * 4 issue slots
                  per vertex included: min(1, lanes / (4 K + slots)) vertices per cycle;
    (c*) the same with lanes of a shader core: each the FP32 lane with its register file, operand network
                  and write-back (ge_shader_lane) and 1/32 of a SIMD's issue logic (ge_simd_issue), from
                  docs/results/ge_lane/costs.json (c*1 measured, c*2 the model).

Writes OUT/study.csv (one row per workload, displacement, K and architecture: vertices, cycles,
throughput, GE cycles per vertex by part, the unit's configuration and transistors), OUT/study.md
(the verdict table, the verdict with shader-core lanes, the bus traffic and the stored patterns'
memory), OUT/verdict.json (every point's vertices per cycle by architecture), OUT/verdict.png/.svg
(throughput against L per K) and OUT/aliasing.png (the displacement at L = 2 and with Nyquist
factors, as the seed's Figure 4).

Usage: ge_study.py --tessim build/bin/tessim [--out docs/results/ge] [--jobs 2] [--replot]
                   [--steps units,cost,ge,pictures,report]
"""
import argparse
import concurrent.futures
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
MESH = "/usr/share/assimp/models/PLY/Wuson.ply"
LS = list(range(1, 17))
VIEWS = {"nearest": "1.3,0.95,-1.55", "middle": "2.6,1.3,-2.9", "farthest": "5.2,2.0,-5.6"}
TARGET = "0,0.6,-0.2"
KS = [2, 4, 8, 16]
BASE_LANES = 4
DISPLACE = ["--displace", "sine", "--amplitude", "0.02", "--frequency", "80"]
UNIT_BASE = {"int_latency": 3, "cpg_product_reg": 1, "cp_buffers": 4, "cpg_digit_bits": 1, "normals": "quadratic"}
UNITS = [dict(int_blocks=n, te_contexts=4 if n <= 2 else 8, cpg_lanes=lanes, cpg_copies=copies)
         for n in (1, 2, 4, 7) for lanes, copies in ((1, 1), (3, 1), (3, 4))]
KEEPS_UP = 0.97
CORE_SIMD = 32  # lanes that share one issue logic in (c*)


def unit_name(u):
    return f"N={u['int_blocks']} V={u['te_contexts']} {u['cpg_lanes']}x1" + (
        f" x{u['cpg_copies']}" if u["cpg_copies"] > 1 else "")


def workloads():
    for L in LS:
        yield f"L={L}", False, ["-L", str(L)]
        yield f"L={L}", True, ["-L", str(L)] + DISPLACE
    for view, eye in VIEWS.items():
        camera = ["--camera", f"eye={eye},target={TARGET}", "--pixels-per-segment", "6", "--partitioning", "integer"]
        yield view, False, ["--adaptive", "screen"] + camera
        yield view, True, ["--adaptive", "screen+nyquist"] + camera + DISPLACE


def run(tessim, args, params, scratch, index):
    cmd = [tessim, "sim", MESH, "--quiet"] + args
    for key, value in params.items():
        cmd += ["--" + key.replace("_", "-"), str(value)]
    stats = os.path.join(scratch, f"{index}.json")
    subprocess.run(cmd + ["--stats", stats], check=True, capture_output=True, text=True)
    with open(stats) as f:
        s = json.load(f)
    os.remove(stats)
    ge = s["ge"]["cycles_per_vertex"]
    return {"vertices": s["vertices_out"], "patches": s["triangles_in"], "cycles": s["cycles"],
            "throughput": s["throughput"], "ge_base": ge["base"], "ge_evaluation": ge["evaluation"],
            "ge_displacement": ge["displacement"], "ge_total": ge["total"],
            "shader_slots": s["ge"]["shader_slots_per_vertex"],
            "limit": s["bottleneck"].split(":")[0]}


def lane_costs():
    with open(os.path.join(HERE, "..", "docs", "results", "ge_lane", "costs.json")) as f:
        return json.load(f)


def lane_transistors():
    """A bare FP32 fused multiply-add lane (c)."""
    return lane_costs()["ge_fma_lane"]["transistors"]


FRONT_END = ("tess_dpg", "tess_fsu", "tess_fsu_edge")  # the fixed-function tessellator the lanes sit behind


def front_end_transistors():
    """The pattern generator (c) keeps in front of its lanes, as Direct3D 11 does: the DPG and one
    factor setup unit of the default configuration's Yosys records (they do not depend on N, the
    contexts or the CPG); charged to the lanes' budget."""
    sys.path.insert(0, HERE)
    import cost_records  # noqa: E402
    records = cost_records.cost({}, require_cached=True)["records"]
    return sum(r["transistors"] for r in records if r["module"] in FRONT_END)


def core_lane_transistors():
    """A lane of a shader core (c*): the FP32 lane with its register file, operand network and
    write-back (ge_shader_lane), and its share of the issue logic of a SIMD of CORE_SIMD lanes."""
    c = lane_costs()
    return c["ge_shader_lane"]["transistors"] + c["ge_simd_issue"]["transistors"] / CORE_SIMD


def run_points(tessim, points, jobs):
    """Each point (head, workload args, parameters) as one `tessim sim` run: its row."""
    with tempfile.TemporaryDirectory(prefix="tessim-ge-study-") as scratch:
        def one(i):
            head, args, params = points[i]
            row = dict(head, status="ok")  # costs.py costs the rows of successful runs
            row.update(params)
            row.update(run(tessim, args, params, scratch, i))
            return row
        with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
            return list(pool.map(one, range(len(points))))


def simulate_units(tessim, out_csv, jobs):
    """Every unit of the grid on every workload and K: the rows (a) chooses from."""
    points = []
    for name, displaced, args in workloads():
        for k in KS:
            for u in UNITS:
                head = {"workload": name, "displaced": int(displaced), "K": k, "arch": "unit", "config": unit_name(u)}
                points.append((head, args, dict(UNIT_BASE, **u, gpe_cycles=k)))
    write_csv(out_csv, run_points(tessim, points, jobs))


def cost_units(tessim, out_csv, jobs):
    """The unit rows' transistors from scripts/costs.py (Yosys records, synthesized when missing)."""
    subprocess.run([sys.executable, os.path.join(HERE, "costs.py"), out_csv, "--in-place", "--tessim", tessim,
                    "--jobs", str(jobs), "--no-xilinx"], check=True)
    twin = os.path.splitext(out_csv)[0] + ".json"  # the CSV holds every column; the twin would be 2 MB
    if os.path.exists(twin):
        os.remove(twin)


def simulate_ge(tessim, units_csv, out_csv, jobs):
    """(b) and (c) for every workload and K, (c) sized by the (a) that the unit rows choose."""
    picks = pick_units(read_csv(units_csv))
    lane, core_lane, front_end = lane_transistors(), core_lane_transistors(), front_end_transistors()
    base = {"evaluation": "gpe", "cpg_mapping": "host", "cpg_lanes": 1, "cpg_copies": 1, "cpg_product_reg": 0,
            "normals": "quadratic"}
    points = []
    for name, displaced, args in workloads():
        for k in KS:
            budget = float(picks[(name, displaced, k)]["cost_unit_transistors"]) - front_end
            lanes = BASE_LANES + int(budget // lane)
            core_lanes = BASE_LANES + int(budget // core_lane)
            for arch, params in (("gpe", dict(base, gpe_cycles=k, ge_alu_lanes=BASE_LANES)),
                                 ("gpe+lanes", dict(base, gpe_cycles=k, ge_alu_lanes=lanes)),
                                 ("gpe+core lanes", dict(base, gpe_cycles=k, ge_alu_lanes=core_lanes))):
                head = {"workload": name, "displaced": int(displaced), "K": k, "arch": arch,
                        "config": f"{params['ge_alu_lanes']} lanes"}
                points.append((head, args, params))
    write_csv(out_csv, run_points(tessim, points, jobs))


def write_csv(path, rows):
    keys = []
    for r in rows:
        keys += [k for k in r if k not in keys]
    twin = os.path.splitext(path)[0] + ".json"  # costs.py's JSON twin of an earlier run would win
    if os.path.exists(twin):
        os.remove(twin)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)
    print(f"ge_study.py: {len(rows)} runs -> {path}", file=sys.stderr)


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def share(r):
    """Vertices per cycle as a share of what the GE could take: 1 / (its cycles per vertex)."""
    return float(r["throughput"]) * int(r["ge_total"])


def pick_units(rows):
    """(a) per (workload, displaced, K): the cheapest unit at >= 97 % of the GE's rate, else the fastest."""
    groups = {}
    for r in rows:
        groups.setdefault((r["workload"], bool(int(r["displaced"])), int(r["K"])), []).append(r)
    picks = {}
    for key, group in groups.items():
        costed = [r for r in group if r.get("cost_unit_transistors")]
        good = [r for r in costed if share(r) >= KEEPS_UP]
        picks[key] = (min(good, key=lambda r: float(r["cost_unit_transistors"])) if good
                      else max(costed, key=lambda r: (float(r["throughput"]), -float(r["cost_unit_transistors"]))))
    return picks


def all_work_on_lanes(k, lanes, shader_slots):
    """(c2), a model: the GE's own work is K cycles on BASE_LANES lanes, K * BASE_LANES slots, and runs
    on the added lanes too, in one program with the shader; the DPG hands out one point a cycle."""
    return min(1.0, lanes / (k * BASE_LANES + shader_slots))


def workload_order(name):
    return (0, int(name[2:])) if name.startswith("L=") else (1, list(VIEWS).index(name))


def report(units_csv, ge_csv, out_dir):
    units = read_csv(units_csv)
    ge = read_csv(ge_csv)
    picks = pick_units(units)
    by = {(r["workload"], bool(int(r["displaced"])), int(r["K"]), r["arch"]): r for r in ge}
    lane, core_lane = lane_transistors(), core_lane_transistors()
    lines = ["<!-- scripts/ge_study.py: regenerate, do not edit -->", "",
             f"Wuson; vertices per cycle of each architecture (one clock for all); the GE's own work K cycles "
             f"per vertex on {BASE_LANES} lanes; (c) adds floor(unit transistors / {lane:,}) bare FP32 lanes to them, "
             f"(c\\*) floor(unit transistors / {core_lane:,.0f}) shader-core lanes (the FP32 lane with its register "
             f"file, operand network and write-back, and 1/{CORE_SIMD} of a SIMD's issue logic: "
             "docs/results/ge_lane/costs.json). "
             "(a), (b), (c1) and (c\\*1) are measured with `tessim sim`; (c2) and (c\\*2) are the model min(1, lanes / "
             "(4 K + shader slots)): the GE's own work also on the added lanes, in one program with the shader, at "
             "most one point a cycle from the DPG. Bold: the fastest; the fair comparison is (a) against (c\\*).", ""]
    verdict = []
    for k in KS:
        lines.append(f"**K = {k}**")
        lines.append("")
        lines.append("| workload | displaced | vertices | (a) unit: pick | M tr. | vertices/cycle | (b) GE: cycles/vertex | "
                     "vertices/cycle | (c) lanes | (c1) the shader on them | (c2) all GE work on them (model) | "
                     "(c\\*) core lanes | (c\\*1) | (c\\*2) (model) |")
        lines.append("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
        for name in sorted({r["workload"] for r in units}, key=workload_order):
            for displaced in (False, True):
                a = picks[(name, displaced, k)]
                b = by[(name, displaced, k, "gpe")]
                c1 = by[(name, displaced, k, "gpe+lanes")]
                s1 = by[(name, displaced, k, "gpe+core lanes")]
                values = [float(a["throughput"]), float(b["throughput"]), float(c1["throughput"]),
                          all_work_on_lanes(k, int(c1["ge_alu_lanes"]), int(b["shader_slots"])),
                          float(s1["throughput"]), all_work_on_lanes(k, int(s1["ge_alu_lanes"]), int(b["shader_slots"]))]
                best = max(values)
                cell = [f"**{v:.4f}**" if v == best else f"{v:.4f}" for v in values]
                lines.append(f"| {name} | {'sine' if displaced else '–'} | {int(a['vertices']):,} | {a['config']} | "
                             f"{float(a['cost_unit_transistors']) / 1e6:.2f} | {cell[0]} | {b['ge_total']} | {cell[1]} | "
                             f"{c1['ge_alu_lanes']} | {cell[2]} | {cell[3]} | {s1['ge_alu_lanes']} | {cell[4]} | "
                             f"{cell[5]} |")
                verdict.append({"K": k, "workload": name, "displaced": displaced, "a": values[0], "b": values[1],
                                "c1": values[2], "c2": values[3], "s1": values[4], "s2": values[5],
                                "lanes": int(c1["ge_alu_lanes"]), "core_lanes": int(s1["ge_alu_lanes"])})
        lines.append("")
    lines += fair_section(verdict, core_lane)
    lines += bus_section()
    with open(os.path.join(out_dir, "verdict.json"), "w") as f:
        json.dump({"lane_transistors": lane, "core_lane_transistors": core_lane, "core_simd": CORE_SIMD,
                   "front_end_transistors": front_end_transistors(), "front_end_modules": list(FRONT_END),
                   "points": verdict}, f, indent=1)
    with open(os.path.join(out_dir, "study.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print(f"ge_study.py: {os.path.join(out_dir, 'study.md')}", file=sys.stderr)
    plot(verdict, out_dir)


def fair_section(verdict, core_lane):
    """How the verdict moves when the lanes are costed as a shader core's: per comparison, the points
    (of all workloads and K) each side wins and the range of the ratio."""
    lines = [f"**The verdict with shader-core lanes** ({core_lane:,.0f} transistors a lane instead of "
             f"{lane_transistors():,}): points where the unit is faster, of {len(verdict) // 2} per displacement, and "
             "the range of (lanes / unit) vertices per cycle.", "",
             "| comparison | displaced | unit faster | lanes faster | lanes / unit |", "|---|---|---|---|---|"]
    for key, what in (("c1", "(c1) bare lanes, the shader on them"), ("s1", "(c\\*1) core lanes, the shader on them"),
                      ("c2", "(c2) bare lanes, all GE work (model)"), ("s2", "(c\\*2) core lanes, all GE work (model)")):
        for displaced in (False, True):
            pts = [v for v in verdict if v["displaced"] == displaced]
            ratios = [v[key] / v["a"] for v in pts]
            lines.append(f"| {what} | {'sine' if displaced else '–'} | {sum(r < 1 for r in ratios)} | "
                         f"{sum(r > 1 for r in ratios)} | {min(ratios):.2f}–{max(ratios):.2f} |")
    lines.append("")
    return lines


def bus_section():
    """The seed's §5 and §3.3 figures: what crosses the host bus per triangle, and the stored
    patterns' memory per level of detail."""
    lines = ["**Bus traffic per input triangle** (float32; the unit's own input port is in "
             "load-balancing.md §9): the coarse triangle, the seed's coefficients, and the host-tessellated patch "
             "(each patch's own vertices, as the unit emits them, and its triangles' 32-bit indices).", "",
             "| L | coarse triangle (3 × position + normal) B | coefficients: 10 + 6 control points (3 normals: linear) B | "
             "tessellated on the host B | stored pattern: vertices (u, v) + 16-bit indices B | all patterns 1..L kB |",
             "|---|---|---|---|---|---|"]
    total = 0
    for L in range(1, 65):
        verts = (L + 1) * (L + 2) // 2
        pattern = verts * 8 + L * L * 3 * 2
        total += pattern
        if L in (1, 2, 4, 8, 16, 32, 64):
            lines.append(f"| {L} | {3 * 24} | {16 * 12} ({13 * 12}) | {verts * 24 + L * L * 3 * 4:,} | {pattern:,} | "
                         f"{total / 1e3:,.2f} |")
    lines.append("")
    return lines


def plot(verdict, out_dir):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(KS), figsize=(4.2 * len(KS), 3.8), sharey=False)
    styles = {"a": ("(a) unit", "#0072B2"), "b": ("(b) GE evaluates", "#D55E00"),
              "c1": ("(c1) + bare lanes, shader", "#009E73"), "s1": ("(c*1) + shader-core lanes, shader", "#E69F00"),
              "s2": ("(c*2) + shader-core lanes, all GE work (model)", "#CC79A7")}
    for ax, k in zip(axes, KS):
        for key, (label, colour) in styles.items():
            for displaced, dash in ((False, "-"), (True, "--")):
                pts = sorted((int(v["workload"][2:]), v[key]) for v in verdict
                             if v["K"] == k and v["displaced"] == displaced and v["workload"].startswith("L="))
                ax.plot([p[0] for p in pts], [p[1] for p in pts], dash, color=colour,
                        label=label + (" (sine)" if displaced else "") if k == KS[0] else None)
        ax.set_title(f"K = {k}")
        ax.set_xlabel("L (uniform)")
        ax.set_yscale("log")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("vertices per cycle")
    fig.legend(loc="lower center", ncol=4, fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0.12, 1, 1))
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(out_dir, f"verdict.{ext}"), dpi=110)
    print(f"ge_study.py: {os.path.join(out_dir, 'verdict.png')}", file=sys.stderr)


def pictures(tessim, out_dir):
    """The seed's Figure 4: a displacement above the pattern's sampling rate aliases."""
    view = ["--view-camera", f"eye={VIEWS['nearest']},target={TARGET}", "--size", "640x480", "--quiet"]
    panels = [("L=2 (aliased)", ["-L", "2"]), ("Nyquist, 4 samples per wavelength", ["--adaptive", "nyquist"])]
    files = []
    for i, (caption, args) in enumerate(panels):
        path = os.path.join(out_dir, f"aliasing_{i}.png")
        subprocess.run([tessim, "render", MESH, "-o", path, "--caption", caption] + args + DISPLACE + view,
                       check=True, capture_output=True)
        files.append(path)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    images = [plt.imread(p) for p in files]
    fig, axes = plt.subplots(1, len(images), figsize=(6.4 * len(images), 5.0))
    for ax, img in zip(axes, images):
        ax.imshow(img)
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "aliasing.png"), dpi=100)
    for p in files:
        os.remove(p)
    print(f"ge_study.py: {os.path.join(out_dir, 'aliasing.png')}", file=sys.stderr)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--tessim", default="build/bin/tessim")
    ap.add_argument("--out", default="docs/results/ge")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--replot", action="store_true", help="only rewrite study.md and the figures from the CSVs")
    ap.add_argument("--steps", default="units,cost,ge,pictures,report",
                    help="comma-separated steps to run, in this order: units (simulate the unit grid), cost (its "
                         "Yosys records), ge (architectures b and c), pictures, report")
    args = ap.parse_args()
    steps = set(args.steps.split(",")) if not args.replot else {"report"}
    os.makedirs(args.out, exist_ok=True)
    tessim = os.path.abspath(args.tessim)
    units_csv = os.path.join(args.out, "units.csv")
    ge_csv = os.path.join(args.out, "study.csv")
    if "units" in steps:
        simulate_units(tessim, units_csv, args.jobs)
    if "cost" in steps:
        cost_units(tessim, units_csv, args.jobs)
    if "ge" in steps:
        simulate_ge(tessim, units_csv, ge_csv, args.jobs)
    if "pictures" in steps:
        pictures(tessim, args.out)
    if "report" in steps:
        report(units_csv, ge_csv, args.out)


if __name__ == "__main__":
    main()
