#!/usr/bin/python3
"""Frame rates of the shipped scenes on every characterized configuration (docs/scenes.md).

Runs `tessim sim SCENE --stats` for each scene of scenes/*.scene.json on each configuration of
docs/results/silicon/configurations.csv (the cell-mapped units with their own clock and area,
docs/silicon.md) at K = 8 and K = 4 geometry-engine cycles per vertex (counted in the unit's
clock), and reports the worst frame of the camera path in cycles, in ms at the configuration's
own clock, and the frame rate it sustains; then, per scene and K, the smallest unit (area) that
sustains 60 frames per second, or the fastest when none does.

Writes OUT/study.csv (a row per scene, K and configuration), OUT/study.json (with every frame's
cycles), OUT/study.md (generated tables) and OUT/frames.png (frame time along the path). About a
minute on two cores.

Usage: scene_study.py --tessim build/bin/tessim [--out docs/results/scenes] [--jobs 2] [--check]
  --check: rebuild study.md from study.json and fail when it differs from the committed one.
"""
import argparse
import concurrent.futures
import csv
import json
import os
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = ["herd", "figures"]
GE_CYCLES = [8, 4]
TARGET_FPS = 60.0
FLAGS = [("int_blocks", "--int-blocks"), ("cpg_lanes", "--cpg-lanes"), ("cpg_digit_bits", "--cpg-digit-bits"),
         ("cpg_product_reg", "--cpg-product-reg"), ("int_latency", "--int-latency"), ("cp_buffers", "--cp-buffers")]


def silicon_configurations():
    """The configurations characterized in silicon, each with its own clock and area."""
    with open(os.path.join(ROOT, "docs/results/silicon/configurations.csv")) as f:
        return list(csv.DictReader(f))


def check_tables(out, stem, markdown, summarize, tool):
    """--check: OUT/STEM.md is what `markdown` makes of OUT/STEM.json, and its picks what `summarize`
    makes of its rows; 0 when both hold."""
    with open(os.path.join(out, f"{stem}.json")) as f:
        doc = json.load(f)
    with open(os.path.join(out, f"{stem}.md")) as f:
        same = f.read() == markdown(doc)
    picks_same = doc["picks"] == summarize(doc["rows"])
    print(f"{tool}: {stem}.md {'matches' if same else 'differs from'} {stem}.json; picks "
          f"{'match' if picks_same else 'differ from'} the rows")
    return 0 if same and picks_same else 1


def label(c):
    return (f"N={c['int_blocks']} {c['cpg_lanes']}x{c['cpg_digit_bits']}"
            + (" reg" if c["cpg_product_reg"] != "0" else "") + f" Λ={c['int_latency']} Nb={c['cp_buffers']}")


def run(tessim, scene, config, k, scratch):
    stats = os.path.join(scratch, f"{scene}-{k}-{label(config).replace(' ', '_').replace('=', '')}.json")
    args = [tessim, "sim", os.path.join(ROOT, "scenes", f"{scene}.scene.json"), "--gpe-cycles", str(k), "--quiet",
            "--stats", stats]
    for key, flag in FLAGS:
        args += [flag, config[key]]
    subprocess.run(args, check=True, capture_output=True, text=True)
    with open(stats) as f:
        doc = json.load(f)
    os.remove(stats)
    worst = max(fr["cycles"] for fr in doc["frames"])
    mean = sum(fr["cycles"] for fr in doc["frames"]) / len(doc["frames"])
    idle = sum(fr["unit_idle_cycles"] for fr in doc["frames"]) / sum(fr["cycles"] for fr in doc["frames"])
    mhz = float(config["clock_mhz"])
    return {"scene": scene, "gpe_cycles": k, "config": label(config), "area_mm2": float(config["area_mm2"]),
            "clock_mhz": mhz, "frames": len(doc["frames"]), "worst_cycles": worst, "mean_cycles": round(mean),
            "worst_ms": worst / (mhz * 1e3), "fps": mhz * 1e6 / worst, "unit_idle_share": idle,
            "tessellated_vertices": doc["frames"][0]["tessellated_vertices"],
            "max_tessellated_vertices": max(fr["tessellated_vertices"] for fr in doc["frames"]),
            "frame_cycles": [fr["cycles"] for fr in doc["frames"]]}


def summarize(rows):
    picks = []
    for scene in SCENES:
        for k in GE_CYCLES:
            mine = [r for r in rows if r["scene"] == scene and r["gpe_cycles"] == k]
            ok = [r for r in mine if r["fps"] >= TARGET_FPS]
            best = min(ok, key=lambda r: r["area_mm2"]) if ok else max(mine, key=lambda r: r["fps"])
            picks.append({"scene": scene, "gpe_cycles": k, "meets_60fps": bool(ok), "configs_meeting": len(ok),
                          "pick": best["config"], "fps": best["fps"], "area_mm2": best["area_mm2"],
                          "clock_mhz": best["clock_mhz"], "worst_ms": best["worst_ms"],
                          "clock_mhz_for_60fps": best["worst_cycles"] * TARGET_FPS / 1e6})
    return picks


def plot(doc, path):
    """Frame time along the camera path, per scene at K = 8: the default unit, each scene's pick,
    and the fastest unit, at their own clocks, against the 60 fps line."""
    fig, axes = plt.subplots(1, len(SCENES), figsize=(6.2 * len(SCENES), 4.2), squeeze=False)
    for ax, scene in zip(axes[0], SCENES):
        rows = [r for r in doc["rows"] if r["scene"] == scene and r["gpe_cycles"] == 8]
        pick = next(p for p in doc["picks"] if p["scene"] == scene and p["gpe_cycles"] == 8)
        shown = {"N=2 1x1 Λ=1 Nb=2": "default unit", pick["pick"]: "pick",
                 max(rows, key=lambda r: r["fps"])["config"]: "fastest"}
        for config, role in shown.items():
            r = next(x for x in rows if x["config"] == config)
            ms = [c / (r["clock_mhz"] * 1e3) for c in r["frame_cycles"]]
            ax.plot(range(len(ms)), ms, "o-", ms=3, label=f"{role}: {config}, {r['clock_mhz']:.1f} MHz")
        ax.axhline(1000.0 / TARGET_FPS, color="grey", lw=0.8, ls="--", label="60 frames per second")
        ax.set_xlabel("frame along the camera path")
        ax.set_ylabel("frame time (ms) at the unit's own clock, K = 8")
        ax.set_title(f"{scene}: {rows[0]['tessellated_vertices']} to {rows[0]['max_tessellated_vertices']} tessellated "
                     "vertices per frame", fontsize=9)
        ax.set_ylim(bottom=0)
        ax.grid(True, lw=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def markdown(doc):
    out = ["<!-- generated by scripts/scene_study.py from study.json: do not edit -->", "",
           "Per scene and K: the smallest unit (area at 0.18 µm) whose worst frame along the camera path "
           "sustains 60 frames per second at its own clock, or the fastest when none does; and the clock the "
           "pick would need for 60 frames per second.", "",
           "| scene | K | pick | meets 60 fps | units that do | worst frame (ms) | fps | MHz | mm² | MHz for 60 fps |",
           "|---|---|---|---|---|---|---|---|---|---|"]
    for p in doc["picks"]:
        out.append(f"| {p['scene']} | {p['gpe_cycles']} | {p['pick']} | {'yes' if p['meets_60fps'] else 'no'} | "
                   f"{p['configs_meeting']} | {p['worst_ms']:.2f} | {p['fps']:.1f} | {p['clock_mhz']:.1f} | "
                   f"{p['area_mm2']:.2f} | {p['clock_mhz_for_60fps']:.0f} |")
    out += ["", "Every configuration (worst frame of the path; unit idle: the share of the frames' cycles in "
            "untessellated draws):", "",
            "| scene | K | configuration | mm² | MHz | worst frame (cycles) | ms | fps | unit idle |",
            "|---|---|---|---|---|---|---|---|---|"]
    for r in doc["rows"]:
        out.append(f"| {r['scene']} | {r['gpe_cycles']} | {r['config']} | {r['area_mm2']:.2f} | {r['clock_mhz']:.1f} | "
                   f"{r['worst_cycles']} | {r['worst_ms']:.2f} | {r['fps']:.1f} | {100 * r['unit_idle_share']:.2f} % |")
    return "\n".join(out) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tessim")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs/results/scenes"))
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--check", action="store_true")
    args = ap.parse_args()
    if args.check:
        return check_tables(args.out, "study", markdown, summarize, "scene_study")
    if not args.tessim:
        sys.exit("scene_study: --tessim is required (except with --check)")
    configs = silicon_configurations()
    os.makedirs(args.out, exist_ok=True)
    with tempfile.TemporaryDirectory() as scratch, concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        jobs = [pool.submit(run, args.tessim, s, c, k, scratch) for s in SCENES for k in GE_CYCLES for c in configs]
        rows = [j.result() for j in jobs]
    doc = {"target_fps": TARGET_FPS, "scenes": SCENES, "gpe_cycles": GE_CYCLES,
           "configurations": "docs/results/silicon/configurations.csv", "rows": rows, "picks": summarize(rows)}
    with open(os.path.join(args.out, "study.json"), "w") as f:
        json.dump(doc, f, indent=1)
    with open(os.path.join(args.out, "study.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=[k for k in rows[0] if k != "frame_cycles"], extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    with open(os.path.join(args.out, "study.md"), "w") as f:
        f.write(markdown(doc))
    plot(doc, os.path.join(args.out, "frames.png"))
    for p in doc["picks"]:
        print(f"{p['scene']} K={p['gpe_cycles']}: {p['pick']}: {p['fps']:.1f} fps at {p['clock_mhz']:.1f} MHz, "
              f"{p['area_mm2']:.2f} mm2 ({'meets' if p['meets_60fps'] else 'misses'} 60 fps; "
              f"{p['clock_mhz_for_60fps']:.0f} MHz would)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
