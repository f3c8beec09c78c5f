#!/usr/bin/python3
"""K derived from stated shader cores, and how many INT blocks a frame needs (docs/scenes.md).

The geometry engine as a shader core (docs/microarchitecture.md §12): W lanes, I wave
instructions a cycle, a clock of its own, a cross-clock FIFO from the unit. Its K — the unit's
cycles per vertex — follows from the per-vertex program and the two clocks, so it differs per
configuration of the study (each has its own clock at 0.18 µm, docs/results/silicon/
configurations.csv). For each stated core, this runs both shipped scenes on every configuration
with `tessim sim SCENE --ge-core-lanes W --ge-core-issue I --ge-core-mhz F --unit-mhz (its clock)`
and reports, per scene and core:
  - K at the configurations' clocks (the range), from the tool's statistics;
  - the smallest unit (area) that sustains 60 frames per second, or the fastest when none does;
  - how many INT blocks a frame needs: the fewest N whose best configuration's worst frame is within
    5 % of the best frame of all configurations (more blocks buy less than 5 %).
And the program's K for each core at a 100 MHz unit for the GE's other programs (shader work the
scenes do not run: displacement, evaluation on the GE), from `tessim sim` on one mesh.

Writes OUT/cores.json (every row, with its frames), OUT/cores.csv and OUT/cores.md (generated
tables). About five minutes on two cores.

Usage: core_study.py --tessim build/bin/tessim [--out docs/results/scenes] [--jobs 2] [--check]
  --check: rebuild cores.md and the picks from cores.json and fail when they differ.
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
from scene_study import FLAGS, ROOT, SCENES, TARGET_FPS, check_tables, label, silicon_configurations  # noqa: E402

WITHIN = 0.05  # "needs N INT blocks": the fewest N within 5 % of the best frame
# The stated cores: lanes, issue width, clock (MHz), and what each stands for.
CORES = [
    {"name": "vec4", "lanes": 4, "issue": 1, "mhz": 200,
     "about": "a vertex shader of the 0.18 µm era: one four-wide multiply-add a cycle"},
    {"name": "simd32", "lanes": 32, "issue": 1, "mhz": 300,
     "about": "one 32-lane SIMD of a unified shader core, one wave instruction a cycle"},
    {"name": "cu64", "lanes": 64, "issue": 1, "mhz": 200,
     "about": "a 64-lane compute unit (four SIMD16 taking one wave instruction a cycle between them)"},
]
FIFO = 64
# The GE's programs beyond its own work, for the K table (on Wuson at L = 4, a 100 MHz unit).
PROGRAMS = [("own work (transform, light)", []), ("+ sine displacement", ["--displace", "sine", "--amplitude", "0.02", "--frequency", "10"]),
            ("+ noise displacement", ["--displace", "noise", "--amplitude", "0.02", "--frequency", "10"]),
            ("+ evaluation of the patch (evaluation gpe)", ["--evaluation", "gpe"])]
PROGRAM_UNIT_MHZ = 100.0


def core_flags(core, unit_mhz):
    return ["--ge-core-lanes", str(core["lanes"]), "--ge-core-issue", str(core["issue"]),
            "--ge-core-mhz", str(core["mhz"]), "--unit-mhz", str(unit_mhz), "--ge-core-fifo", str(FIFO)]


def run(tessim, scene, config, core, scratch):
    stats = os.path.join(scratch, f"{scene}-{core['name']}-{label(config).replace(' ', '_').replace('=', '')}.json")
    mhz = float(config["clock_mhz"])
    args = [tessim, "sim", os.path.join(ROOT, "scenes", f"{scene}.scene.json"), "--quiet", "--stats", stats]
    args += core_flags(core, mhz)
    for key, flag in FLAGS:
        args += [flag, config[key]]
    subprocess.run(args, check=True, capture_output=True, text=True)
    with open(stats) as f:
        doc = json.load(f)
    os.remove(stats)
    worst = max(fr["cycles"] for fr in doc["frames"])
    return {"scene": scene, "core": core["name"], "config": label(config), "int_blocks": int(config["int_blocks"]),
            "area_mm2": float(config["area_mm2"]), "clock_mhz": mhz,
            "ge_cycles_per_vertex": doc["summary"]["ge_cycles_per_vertex"], "worst_cycles": worst,
            "worst_ms": worst / (mhz * 1e3), "fps": mhz * 1e6 / worst,
            "max_vertices": max(fr["vertices"] for fr in doc["frames"]),
            "frame_cycles": [fr["cycles"] for fr in doc["frames"]]}


def program_k(tessim, core, args, scratch):
    stats = os.path.join(scratch, f"program-{core['name']}-{'_'.join(args) or 'own'}.json")
    cmd = [tessim, "sim", "/usr/share/assimp/models/PLY/Wuson.ply", "-L", "4", "--quiet", "--stats", stats]
    subprocess.run(cmd + core_flags(core, PROGRAM_UNIT_MHZ) + args, check=True, capture_output=True, text=True)
    with open(stats) as f:
        c = json.load(f)["ge"]["core"]
    os.remove(stats)
    return {"slots": c["program_slots_per_vertex"], "wave_cycles": c["wave_cycles"], "k": c["cycles_per_vertex"]}


def summarize(rows):
    picks = []
    for scene in SCENES:
        for core in CORES:
            mine = [r for r in rows if r["scene"] == scene and r["core"] == core["name"]]
            ok = [r for r in mine if r["fps"] >= TARGET_FPS]
            pick = min(ok, key=lambda r: r["area_mm2"]) if ok else max(mine, key=lambda r: r["fps"])
            best_ms = min(r["worst_ms"] for r in mine)
            needed = min(r["int_blocks"] for r in mine if r["worst_ms"] <= best_ms * (1 + WITHIN))
            ks = [r["ge_cycles_per_vertex"] for r in mine]
            picks.append({"scene": scene, "core": core["name"], "k_min": min(ks), "k_max": max(ks),
                          "meets_60fps": bool(ok), "configs_meeting": len(ok), "pick": pick["config"],
                          "pick_int_blocks": pick["int_blocks"], "fps": pick["fps"], "area_mm2": pick["area_mm2"],
                          "clock_mhz": pick["clock_mhz"], "pick_k": pick["ge_cycles_per_vertex"],
                          "best_fps": max(r["fps"] for r in mine), "int_blocks_needed": needed,
                          "mvertices_per_s_for_60fps": pick["max_vertices"] * TARGET_FPS / 1e6,
                          "vertices_per_cycle_for_60fps": pick["max_vertices"] * TARGET_FPS / (pick["clock_mhz"] * 1e6)})
    return picks


def markdown(doc):
    out = ["<!-- generated by scripts/core_study.py from cores.json: do not edit -->", "",
           f"The stated cores (cross-clock FIFO of {FIFO} vertices):", "",
           "| core | lanes | issue | MHz | what it stands for |", "|---|---|---|---|---|"]
    for c in doc["cores"]:
        out.append(f"| {c['name']} | {c['lanes']} | {c['issue']} | {c['mhz']} | {c['about']} |")
    out += ["", f"K of each core's program, in cycles of a {PROGRAM_UNIT_MHZ:.0f} MHz unit (slots per vertex; core "
            "cycles per wave; K), from `tessim sim` statistics:", "",
            "| program | slots | " + " | ".join(f"{c['name']}: cycles/wave, K" for c in doc["cores"]) + " |",
            "|---|---|" + "---|" * len(doc["cores"])]
    for name, _ in PROGRAMS:
        cells = [doc["programs"][name][c["name"]] for c in doc["cores"]]
        out.append(f"| {name} | {cells[0]['slots']} | "
                   + " | ".join(f"{x['wave_cycles']}, {x['k']:.3f}" for x in cells) + " |")
    out += ["", "Per scene and core: K at the configurations' own clocks; the smallest unit that sustains 60 frames "
            "per second at its clock, or the fastest when none does; and the fewest INT blocks whose best "
            f"configuration is within {100 * WITHIN:.0f} % of the best frame (among the configurations "
            "characterized); and the vertex rate 60 frames per second would take (the path's largest frame), in "
            "Mvertices/s and in vertices per cycle of the pick's clock.", "",
            "| scene | core | K (unit cycles) | pick | N | K at the pick | meets 60 fps | units that do | fps | MHz | "
            "mm² | best fps | INT blocks needed | Mvertices/s for 60 fps | vertices/cycle for 60 fps |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for p in doc["picks"]:
        out.append(f"| {p['scene']} | {p['core']} | {p['k_min']:.3f}–{p['k_max']:.3f} | {p['pick']} | "
                   f"{p['pick_int_blocks']} | {p['pick_k']:.3f} | {'yes' if p['meets_60fps'] else 'no'} | "
                   f"{p['configs_meeting']} | {p['fps']:.1f} | {p['clock_mhz']:.1f} | {p['area_mm2']:.2f} | "
                   f"{p['best_fps']:.1f} | {p['int_blocks_needed']} | {p['mvertices_per_s_for_60fps']:.1f} | "
                   f"{p['vertices_per_cycle_for_60fps']:.2f} |")
    out += ["", "Every configuration and core (worst frame of the camera path):", "",
            "| scene | core | configuration | mm² | MHz | K | worst frame (cycles) | ms | fps |",
            "|---|---|---|---|---|---|---|---|---|"]
    for r in doc["rows"]:
        out.append(f"| {r['scene']} | {r['core']} | {r['config']} | {r['area_mm2']:.2f} | {r['clock_mhz']:.1f} | "
                   f"{r['ge_cycles_per_vertex']:.3f} | {r['worst_cycles']} | {r['worst_ms']:.2f} | {r['fps']:.1f} |")
    return "\n".join(out) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tessim")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs/results/scenes"))
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--check", action="store_true")
    args = ap.parse_args()
    if args.check:
        return check_tables(args.out, "cores", markdown, summarize, "core_study")
    if not args.tessim:
        sys.exit("core_study: --tessim is required (except with --check)")
    configs = silicon_configurations()
    os.makedirs(args.out, exist_ok=True)
    with tempfile.TemporaryDirectory() as scratch, concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        programs = {name: {c["name"]: pool.submit(program_k, args.tessim, c, flags, scratch) for c in CORES}
                    for name, flags in PROGRAMS}
        jobs = [pool.submit(run, args.tessim, s, c, core, scratch) for s in SCENES for core in CORES for c in configs]
        rows = [j.result() for j in jobs]
        programs = {name: {c: f.result() for c, f in per.items()} for name, per in programs.items()}
    doc = {"target_fps": TARGET_FPS, "within": WITHIN, "fifo": FIFO, "cores": CORES, "scenes": SCENES,
           "configurations": "docs/results/silicon/configurations.csv", "program_unit_mhz": PROGRAM_UNIT_MHZ,
           "programs": programs, "rows": rows, "picks": summarize(rows)}
    with open(os.path.join(args.out, "cores.json"), "w") as f:
        json.dump(doc, f, indent=1)
    with open(os.path.join(args.out, "cores.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=[k for k in rows[0] if k != "frame_cycles"], extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    with open(os.path.join(args.out, "cores.md"), "w") as f:
        f.write(markdown(doc))
    for p in doc["picks"]:
        print(f"{p['scene']} {p['core']}: K {p['k_min']:.3f}-{p['k_max']:.3f}; pick {p['pick']} {p['fps']:.1f} fps "
              f"({'meets' if p['meets_60fps'] else 'misses'} 60); needs N={p['int_blocks_needed']}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
