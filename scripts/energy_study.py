#!/usr/bin/python3
"""Energy per vertex of the characterized configurations, side by side (docs/silicon.md, Energy).

    energy_study.py --tessim BIN [--write | --check]

Runs `tessim power` for every configuration of docs/results/silicon/energy/ on Wuson at L = 8 and
on the adaptive view of the characterization, with and without clock gating, and writes
docs/results/silicon/energy_study.json, the figure docs/results/silicon_energy.{png,svg} (energy
per vertex by block) and the table of docs/silicon.md between its `energy-tables` marks
(`--check` fails unless the JSON and the table are what the runs give now).
"""

import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import doc_block  # noqa: E402

REPO = Path(__file__).resolve().parent.parent
ENERGY = REPO / "docs" / "results" / "silicon" / "energy"
OUT = REPO / "docs" / "results" / "silicon" / "energy_study.json"
FIGURE = REPO / "docs" / "results" / "silicon_energy"
DOC = REPO / "docs" / "silicon.md"
BEGIN = "<!-- energy-tables:begin (scripts/energy_study.py --write) -->"
END = "<!-- energy-tables:end -->"
KAIST = {"mvertices_per_s": 120.0, "nj_per_vertex": 2.3}  # docs/results/silicon/outside.json


def flags_of(params, schema):
    by_rtl = {p["rtl"]: p["flag"] for p in schema["parameters"] if p.get("rtl")}
    out = []
    for k, v in sorted(params.items()):
        if k not in by_rtl:
            raise SystemExit(f"energy_study.py: error: the RTL parameter {k} has no tessim flag")
        out += [by_rtl[k], str(v)]
    return out


def power(tessim, args, tmp):
    out = Path(tmp) / "power.json"
    proc = subprocess.run([tessim, "power", *args, "--json", str(out), "--quiet"], capture_output=True, text=True)
    if proc.returncode != 0:
        raise SystemExit(f"energy_study.py: error: tessim power {' '.join(args)}:\n{proc.stderr}")
    return json.loads(out.read_text())


def calibrating(c, cls):
    """The workload that calibrates a pattern class in a characterization."""
    return next(w for w, v in c["workloads"].items() if v["class"] == cls and v["role"] == "calibrates")


def rows(tessim):
    schema = json.loads(subprocess.run([tessim, "schema"], capture_output=True, text=True, check=True).stdout)
    out = []
    with tempfile.TemporaryDirectory(prefix="tessim-energy-study-") as tmp:
        for path in sorted(ENERGY.glob("*.json"), key=lambda p: json.loads(p.read_text())["params"].get("IntBlocks", 2)):
            c = json.loads(path.read_text())
            config = flags_of(c["params"], schema)
            for wname, wargs in c["workloads"].items():
                args = [a if not a.startswith("PLY/") else f"/usr/share/assimp/models/{a}" for a in wargs["args"]]
                for gating in (False, True):
                    r = power(tessim, args + config + (["--clock-gating"] if gating else []), tmp)
                    # Enable-based gating at its floor: every flip-flop clocked only in the cycles
                    # its value changes (the characterization's floor per block, this class).
                    cal = calibrating(c, wargs["class"])
                    floor = {b["name"]: b["clock_floor_pj_per_cycle"][cal] for b in c["blocks"]}
                    at_floor = {b["name"]: (b["energy_nj"] - b["clock_energy_nj"] + floor[b["name"]] * r["cycles"] * 1e-3)
                                / r["vertices"] for b in r["blocks"]}
                    floor_nj = sum(at_floor.values())
                    out.append({
                        "configuration": c["name"], "params": c["params"], "workload": wname, "clock_gating": gating,
                        "area_mm2": round(r["area_mm2"], 4), "clock_mhz": round(r["clock_mhz"], 2),
                        "mvertices_per_s": round(r["mvertices_per_s"], 3), "power_mw": round(r["power_mw"], 2),
                        "leakage_mw": round(r["leakage_mw"], 4), "clock_mw": round(r["clock_mw"], 2),
                        "data_mw": round(r["data_mw"], 2), "idle_power_mw": round(r["idle_power_mw"], 3),
                        "energy_nj_per_vertex": round(r["energy_nj_per_vertex"], 4),
                        "enable_gating_floor_nj_per_vertex": round(floor_nj, 4),
                        "vertices": r["vertices"], "cycles": r["cycles"],
                        "blocks": {b["name"]: round(b["energy_nj_per_vertex"], 4) for b in r["blocks"]},
                        "blocks_at_gating_floor": {k: round(v, 4) for k, v in at_floor.items()},
                        "validation": [v for v in c["validation"] if v["workload"] == wname and v["block"] == "unit"],
                    })
    return out


def table(data):
    shown = [r for r in data if r["workload"] in ("wuson_l8", "wuson_adaptive")]
    lines = ["| configuration | workload | gating | mm² | MHz | Mvertices/s | mW | clock mW | data mW | idle mW |"
             " nJ/vertex | at the gating floor | largest blocks (nJ/vertex) |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in shown:
        top = sorted(r["blocks"].items(), key=lambda kv: -kv[1])[:3]
        lines.append(f"| {r['configuration']} | {r['workload']} | {'yes' if r['clock_gating'] else 'no'} | "
                     f"{r['area_mm2']:.3f} | {r['clock_mhz']:.1f} | {r['mvertices_per_s']:.2f} | {r['power_mw']:.1f} | "
                     f"{r['clock_mw']:.1f} | {r['data_mw']:.1f} | {r['idle_power_mw']:.2f} | "
                     f"{r['energy_nj_per_vertex']:.2f} | {r['enable_gating_floor_nj_per_vertex']:.2f} | "
                     + ", ".join(f"{k} {v:.2f}" for k, v in top) + " |")
    best = min(data, key=lambda r: r["energy_nj_per_vertex"])
    fastest = max(data, key=lambda r: r["mvertices_per_s"])
    lines += ["", f"Lowest energy: {best['configuration']} on {best['workload']}"
              f"{' with clock gating' if best['clock_gating'] else ''}, {best['energy_nj_per_vertex']:.2f} nJ/vertex at "
              f"{best['mvertices_per_s']:.2f} Mvertices/s; fastest: {fastest['configuration']} on {fastest['workload']}, "
              f"{fastest['mvertices_per_s']:.2f} Mvertices/s. The KAIST chip's {KAIST['mvertices_per_s']:.0f} Mvertices/s at "
              f"{KAIST['nj_per_vertex']} nJ/vertex is {KAIST['mvertices_per_s'] / fastest['mvertices_per_s']:.1f}x the "
              f"fastest throughput here, and the lowest energy here is {best['energy_nj_per_vertex'] / KAIST['nj_per_vertex']:.1f}x "
              "the chip's.", "",
              "The action model against each workload's own propagated activity (data energy of the whole unit;"
              " the calibrating workloads match by construction):", "",
              "| configuration | workload | role | direct µJ | model µJ | error |", "|---|---|---|---|---|---|"]
    seen = set()
    for r in data:
        for v in r["validation"]:
            key = (r["configuration"], v["workload"])
            if key in seen:
                continue
            seen.add(key)
            lines.append(f"| {r['configuration']} | {v['workload']} | {v['role']} | {v['direct_pj'] / 1e6:.1f} | "
                         f"{v['predicted_pj'] / 1e6:.1f} | {100 * v['error']:+.1f} % |")
    checks = sorted((REPO / "docs" / "results" / "silicon" / "gate_check").glob("*.json"))
    if checks:
        lines += ["", "Gate-level simulation against the propagation on one record instance each "
                  "(`scripts/gate_check.py`, Wuson at L = 8, the same 10 000-cycle window; data energy per cycle):", "",
                  "| instance | cells | gate level pJ | propagated pJ | difference | with every probability 1/2 |",
                  "|---|---|---|---|---|---|"]
        for path in checks:
            g = json.loads(path.read_text())
            e = g["data_pj_per_cycle"]
            lines.append(f"| `{g['instance']}` | {g['cells']} | {e['gate_level']:.1f} | {e['propagated']:.1f} | "
                         f"{100 * g['difference']['propagated']:+.1f} % | {100 * g['difference']['propagated_p_half']:+.0f} % |")
    return "\n".join(lines) + "\n"


def figure(data, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    picked = []  # (label, blocks): per configuration ungated, gated and at the gating floor
    for r in data:
        if r["workload"] != "wuson_l8":
            continue
        picked.append((f"{r['configuration']}\n{'gated' if r['clock_gating'] else 'ungated'}", r["blocks"]))
        if r["clock_gating"]:
            picked.append((f"{r['configuration']}\ngating floor", r["blocks_at_gating_floor"]))
    # The blocks in data-flow order: the configuration with the most blocks (its INT blocks side by
    # side) first, then any others.
    names = []
    for _, blocks in sorted(picked, key=lambda p: -len(p[1])):
        for b in blocks:
            if b not in names:
                names.append(b)
    fig, ax = plt.subplots(figsize=(9, 4.2))
    labels = [label for label, _ in picked]
    bottom = [0.0] * len(picked)
    cmap = plt.get_cmap("tab20")
    for i, b in enumerate(names):
        values = [blocks.get(b, 0.0) for _, blocks in picked]
        ax.bar(labels, values, bottom=bottom, label=b, color=cmap(i % 20), width=0.6)
        bottom = [x + y for x, y in zip(bottom, values)]
    ax.axhline(KAIST["nj_per_vertex"], color="black", linestyle="--", linewidth=1)
    ax.text(-0.4, KAIST["nj_per_vertex"], "KAIST chip 2.3 nJ", va="bottom", ha="left", fontsize=8)
    ax.set_ylabel("energy per vertex (nJ)")
    ax.set_title("Wuson, L = 8, quadratic normals, K = 8: energy per vertex by block (OSU 0.18 µm)", fontsize=9)
    handles, legend_labels = ax.get_legend_handles_labels()  # top of the stack first
    ax.legend(handles[::-1], legend_labels[::-1], fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    fig.savefig(f"{path}.png", dpi=110)
    fig.savefig(f"{path}.svg", metadata={"Date": None})
    plt.close(fig)


def main(argv):
    ap = argparse.ArgumentParser(prog="energy_study.py", description=__doc__.split("\n\n")[0])
    ap.add_argument("--tessim", required=True)
    mode = ap.add_mutually_exclusive_group(required=True)
    mode.add_argument("--write", action="store_true")
    mode.add_argument("--check", action="store_true")
    args = ap.parse_args(argv)
    data = rows(args.tessim)
    text = json.dumps(data, indent=1) + "\n"
    if args.check:
        if not OUT.exists() or OUT.read_text() != text:
            print(f"energy_study.py: {OUT.relative_to(REPO)} differs from the runs; run scripts/energy_study.py --write",
                  file=sys.stderr)
            return 1
    else:
        OUT.write_text(text)
        figure(data, FIGURE)
    return doc_block.replace_or_check(DOC, BEGIN, END, table(data), args.check, "energy_study.py",
                                      "the energy table", "scripts/energy_study.py --write")


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
