#!/usr/bin/python3
"""How much scalar tags shift the CPG/TE balance: cycles per vertex against the number of INT
blocks N for plain PN and scalar-tagged PN (the cycle model with cpg_tags 0 and 1) at L = 4, 8
and 16, on meshes with hard edges made ST-meshes by `tessim stpn-import`.

    /usr/bin/python3 scripts/stpn_study.py --tessim build/bin/tessim --out docs/results

writes OUT/stpn.csv, OUT/stpn_cycles_per_vertex.png (and .svg) and prints the Markdown table of
docs/results/load-balancing.md §12; scripts/results.sh runs it with the small set. Every run is
deterministic (no random stalls), so a rerun reproduces every number.

With --cost-cache DIR it also costs the CPG that takes scalar tags against the plain one
(scripts/costs.py, Yosys module records looked up in DIR), writes OUT/stpn_costs.csv and
prints a second table; --require-cached synthesizes nothing (fails if a cost is not recorded).
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

MODELS = "/usr/share/assimp/models"
MESHES = ["Collada/Cinema4D.dae", "OBJ/spider.obj"]
FACTORS = [4, 8, 16]
INT_BLOCKS = [1, 2, 3, 4]
CPGS = {"sequential": [], "one lane, r = 4": ["--cpg-digit-bits", "4"]}


def run(tessim, args):
    out = subprocess.run([tessim, *args], check=True, capture_output=True, text=True)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tessim", default="build/bin/tessim")
    ap.add_argument("--out", default="stpn-study", help="output directory (default ./stpn-study)")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--cost-cache", help="Yosys result cache of scripts/costs.py: also cost the tagged CPG")
    ap.add_argument("--require-cached", action="store_true", help="with --cost-cache: synthesize nothing")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)

    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        st_meshes = {}
        for m in MESHES:
            path = os.path.join(tmp, os.path.basename(m).rsplit(".", 1)[0] + "_st.ply")
            run(a.tessim, ["stpn-import", os.path.join(MODELS, m), "-o", path])
            st_meshes[m] = path

        def point(key):
            mesh, cpg, L, N, tags = key
            stats = os.path.join(tmp, f"{abs(hash(key))}.json")
            run(a.tessim, ["sim", st_meshes[mesh], "-L", str(L), "--int-blocks", str(N), "--cpg-tags", str(tags),
                           "--stats", stats, *CPGS[cpg]])
            with open(stats) as f:
                s = json.load(f)
            return {"mesh": mesh, "cpg": cpg, "tess_factor": L, "int_blocks": N, "cpg_tags": tags,
                    "cycles": s["cycles"], "vertices": s["vertices_out"],
                    "cycles_per_vertex": s["cycles_per_vertex"], "cpg_cycles": s["cpg_cycles_per_triangle"],
                    "cpg_tag_cycles": s["cpg_tag_cycles"], "triangles": s["triangles"],
                    "bottleneck": s["bottleneck"].split(":")[0]}

        keys = [(m, c, L, N, t) for m in MESHES for c in CPGS for L in FACTORS for N in INT_BLOCKS for t in (0, 1)]
        with ThreadPoolExecutor(a.jobs) as pool:
            rows = list(pool.map(point, keys))

    csv_path = os.path.join(a.out, "stpn.csv")
    with open(csv_path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    # Reproducible output, as scripts/plots.py: no date, fixed SVG ids.
    plt.rcParams.update({"svg.hashsalt": "tessim", "svg.fonttype": "path"})

    fig, axes = plt.subplots(len(MESHES), len(CPGS), figsize=(10, 7.5), sharex=True, squeeze=False)
    colours = {4: "tab:blue", 8: "tab:orange", 16: "tab:green"}
    for i, m in enumerate(MESHES):
        for j, c in enumerate(CPGS):
            ax = axes[i][j]
            for L in FACTORS:
                for tags, style in ((0, "--"), (1, "-")):
                    pts = sorted((r["int_blocks"], r["cycles_per_vertex"]) for r in rows
                                 if r["mesh"] == m and r["cpg"] == c and r["tess_factor"] == L and r["cpg_tags"] == tags)
                    ax.plot([p[0] for p in pts], [p[1] for p in pts], style, marker="o", color=colours[L],
                            label=f"L = {L}, {'STPN' if tags else 'PN'}")
            ax.set_title(f"{os.path.basename(m)} (ST-mesh), CPG {c}", fontsize=10)
            ax.set_xticks(INT_BLOCKS)
            ax.grid(alpha=0.3)
            if i == len(MESHES) - 1:
                ax.set_xlabel("INT blocks N")
            if j == 0:
                ax.set_ylabel("cycles per vertex (K = 8)")
    axes[0][0].legend(fontsize=8, ncol=2)
    fig.suptitle("Plain PN (dashed) and scalar-tagged PN (solid): cycles per output vertex", fontsize=11)
    fig.tight_layout()
    png = os.path.join(a.out, "stpn_cycles_per_vertex.png")
    fig.savefig(png, dpi=90, metadata={"Software": None})
    fig.savefig(png[:-4] + ".svg", metadata={"Date": None})

    print("| mesh | CPG | L | PN, N = 1 / 2 / 3 / 4 | STPN, N = 1 / 2 / 3 / 4 | tag cycles per triangle | limit (STPN, N = 2) |")
    print("|---|---|---|---|---|---|---|")
    for m in MESHES:
        for c in CPGS:
            for L in FACTORS:
                sel = [r for r in rows if r["mesh"] == m and r["cpg"] == c and r["tess_factor"] == L]
                pn = [r for r in sel if r["cpg_tags"] == 0]
                st = [r for r in sel if r["cpg_tags"] == 1]
                pn.sort(key=lambda r: r["int_blocks"])
                st.sort(key=lambda r: r["int_blocks"])
                per_tri = st[0]["cpg_tag_cycles"] / st[0]["triangles"]
                limit = next(r["bottleneck"] for r in st if r["int_blocks"] == 2)
                print(f"| {os.path.basename(m)} | {c} | {L} | " + " / ".join(f"{r['cycles_per_vertex']:.2f}" for r in pn) +
                      " | " + " / ".join(f"{r['cycles_per_vertex']:.2f}" for r in st) + f" | {per_tri:.1f} | {limit} |")
    print(f"wrote {csv_path} and {png}", file=sys.stderr)
    if a.cost_cache:
        print()
        cost_table(a)


def cost_table(a):
    """The CPG that takes scalar tags against the plain one, sequential and r = 4, in the unit with
    N = 2 (default widths): Yosys records composed by scripts/costs.py."""
    schema = json.loads(run(a.tessim, ["schema"]).stdout)
    defaults = {p["key"]: p["default"] for p in schema["parameters"]}
    rows = []
    for cpg, flags in CPGS.items():
        digit_bits = int(flags[1]) if flags else defaults["cpg_digit_bits"]
        for tags in (0, 1):
            row = dict(defaults)
            row.update({"point": f"stpn-cost-{len(rows)}", "grids": "stpn_cost", "status": "ok", "cpg": cpg,
                        "cpg_digit_bits": digit_bits, "cpg_tags": tags})
            rows.append(row)
    csv_path = os.path.join(a.out, "stpn_costs.csv")
    with tempfile.TemporaryDirectory() as tmp:
        work = os.path.join(tmp, "costs.csv")
        with open(work, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)
        here = os.path.dirname(os.path.abspath(__file__))
        subprocess.run([sys.executable, os.path.join(here, "costs.py"), work, "--in-place", "--tessim", a.tessim,
                        "--cache", a.cost_cache, "--where", "grid=stpn_cost"]
                       + (["--require-cached"] if a.require_cached else []), check=True)
        with open(work, newline="") as f:
            costed = list(csv.DictReader(f))
    keep = ["cpg", "cpg_digit_bits", "cpg_tags"] + [k for k in costed[0] if k.startswith("cost_cpg_")
                                                     or k in ("cost_unit_transistors", "cost_unit_depth")]
    with open(csv_path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keep, extrasaction="ignore")
        w.writeheader()
        w.writerows(costed)
    print("| CPG | tags | CPG transistors | CPG cells | CPG flip-flops | CPG depth | CPG LUTs (Xilinx) | CPG DSPs | "
          "unit transistors (N = 2) | tags add (CPG transistors) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for cpg in CPGS:
        plain, tagged = (next(r for r in costed if r["cpg"] == cpg and int(r["cpg_tags"]) == t) for t in (0, 1))
        for r in (plain, tagged):
            add = (f"+{100 * (float(r['cost_cpg_transistors']) / float(plain['cost_cpg_transistors']) - 1):.0f} %"
                   if r is tagged else "–")
            print(f"| {cpg} | {'STPN' if int(r['cpg_tags']) else 'PN'} | {int(float(r['cost_cpg_transistors'])):,} | "
                  f"{int(float(r['cost_cpg_cells'])):,} | {int(float(r['cost_cpg_flops'])):,} | "
                  f"{int(float(r['cost_cpg_depth']))} | {int(float(r.get('cost_cpg_xilinx_lut') or 0)):,} | "
                  f"{int(float(r.get('cost_cpg_xilinx_dsp') or 0))} | {int(float(r['cost_unit_transistors'])):,} | {add} |")
    print(f"wrote {csv_path}", file=sys.stderr)


if __name__ == "__main__":
    main()
