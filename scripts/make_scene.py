#!/usr/bin/python3
"""Writes a scene for `tessim sim SCENE.scene.json` (docs/scenes.md) from Debian's meshes
(assimp-testmodels): the shipped scenes and larger ones of the same kind.

Presets:
- herd: a flat ground (a cube flattened to a slab, not tessellated), a herd of Wusons on a grid
  going away from the camera, the front row with screen-adaptive factors and the rest uniform
  (L = 8 for the second row, L = 4 behind), sphereWithHole blobs with the contour rule, and two
  spiders as untessellated props; the camera walks in towards the herd.
- figures: sydney figures in a circle, uniform L = 6, with an untessellated ground and boxes; the
  camera circles them at two heights.

The camera path has --frames cameras (one frame each); --rows and --columns scale the herd.

Usage: make_scene.py --preset herd|figures [--frames 12] [--rows 3] [--columns 3]
                     [--clock-mhz 53.6] -o scenes/NAME.scene.json
       make_scene.py --check   (the shipped scenes are what the presets make)
"""
import argparse
import json
import math
import os
import sys

MODELS = "/usr/share/assimp/models"


def ground(size, y):
    # cube.ply spans 0..1 on every axis: centred, flattened, and its top at height y.
    return {"name": "ground", "mesh": f"{MODELS}/PLY/cube.ply", "tessellation": "none",
            "instances": [{"translate": [-size / 2, y - 0.05, -size / 2], "scale": [size, 0.05, size]}]}


def herd(args):
    # Wuson stands on y = 0 and is 3.2 long along z: a grid of them, facing the camera's path.
    near, rows = [], {}
    for r in range(args.rows):
        for c in range(args.columns):
            inst = {"translate": [4.0 * (c - (args.columns - 1) / 2), 0.0, -5.0 * r], "rotate_y_deg": 25.0 * c}
            if r == 0:
                near.append(inst)
            else:
                rows.setdefault(8 if r == 1 else 4, []).append(inst)
    draws = [ground(12.0 * max(args.rows, args.columns), 0.0)]
    draws.append({"name": "Wuson, front row (screen-adaptive)", "mesh": f"{MODELS}/PLY/Wuson.ply",
                  "tessellation": "adaptive", "rule": "screen", "pixels_per_segment": 6, "instances": near})
    for L, instances in sorted(rows.items(), reverse=True):
        if instances:
            draws.append({"name": f"Wuson, uniform L = {L}", "mesh": f"{MODELS}/PLY/Wuson.ply", "tessellation": "uniform",
                          "L": L, "instances": instances})
    draws.append({"name": "sphereWithHole (contour rule)", "mesh": f"{MODELS}/STL/sphereWithHole.stl",
                  "tessellation": "adaptive", "rule": "contour", "outline_tolerance": 0.5,
                  "instances": [{"translate": [x, 0.0, 3.0], "scale": 0.5} for x in (-6.0, 6.0)]})
    draws.append({"name": "spider props", "mesh": f"{MODELS}/OBJ/spider.obj", "tessellation": "none",
                  "instances": [{"translate": [x, 0.4, -2.5], "scale": 0.01} for x in (-2.0, 2.0)]})
    cameras = []
    for k in range(args.frames):
        # Walking in from 20 units to 4 in front of the first row: its factors grow along the path.
        s = k / max(1, args.frames - 1)
        eye = [-3.0 + 4.0 * s, 2.5, 20.0 - 16.0 * s]
        cameras.append({"eye": eye, "target": [0.0, 0.8, -2.5 * (args.rows - 1)], "fov_deg": 50})
    return draws, cameras


def figures(args):
    # sydney is 60 units tall, standing on y = -24 or so: scaled to 1.8 m, feet near y = 0.
    count = args.rows * args.columns
    radius = 3.0
    instances = [{"translate": [radius * math.sin(2 * math.pi * i / count), 0.75,
                                radius * math.cos(2 * math.pi * i / count)], "scale": 0.03,
                  "rotate_y_deg": 360.0 * i / count} for i in range(count)]
    draws = [ground(20.0, 0.0),
             {"name": "sydney figures, uniform L = 6", "mesh": f"{MODELS}/MD2/sydney.md2", "tessellation": "uniform",
              "L": 6, "instances": instances},
             {"name": "boxes", "mesh": f"{MODELS}/PLY/cube.ply", "tessellation": "none",
              "instances": [{"translate": [x, 0.0, z], "scale": 0.6} for x, z in ((-1, -1), (1, 1), (0.5, -1.5))]}]
    cameras = []
    for k in range(args.frames):
        a = 2 * math.pi * k / args.frames
        h = 1.5 if k % 2 == 0 else 3.0
        cameras.append({"eye": [8.0 * math.sin(a), h, 8.0 * math.cos(a)], "target": [0.0, 0.9, 0.0], "fov_deg": 45})
    return draws, cameras


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--preset", choices=("herd", "figures"))
    ap.add_argument("--frames", type=int, default=12)
    ap.add_argument("--rows", type=int, default=3)
    ap.add_argument("--columns", type=int, default=3)
    ap.add_argument("--clock-mhz", type=float, default=53.6,
                    help="the unit's clock for frame times (default: the default unit at 0.18 um, docs/silicon.md)")
    ap.add_argument("-o", "--output")
    ap.add_argument("--check", action="store_true",
                    help="instead of writing: fail unless scenes/herd and scenes/figures are what their presets make")
    args = ap.parse_args()
    if args.check:
        return check_shipped()
    if not args.output or not args.preset:
        sys.exit("make_scene: --preset and -o are required (except with --check)")
    if args.frames < 1 or args.rows < 1 or args.columns < 1:
        sys.exit("make_scene: --frames, --rows and --columns must be at least 1")
    with open(args.output, "w") as f:
        f.write(scene_text(args))
    return 0


def scene_text(args):
    draws, cameras = (herd if args.preset == "herd" else figures)(args)
    scene = {"format": "tessim-scene", "version": 1,
             "description": f"scripts/make_scene.py --preset {args.preset} --frames {args.frames} --rows {args.rows} "
                            f"--columns {args.columns} --clock-mhz {args.clock_mhz:g}",
             "clock_mhz": args.clock_mhz, "viewport": [1280, 720], "draws": draws, "camera_path": cameras}
    return json.dumps(scene, indent=1) + "\n"


def check_shipped():
    """The shipped scenes are this script's output with its defaults (ctest scene_files)."""
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    stale = []
    for preset in ("herd", "figures"):
        args = argparse.Namespace(preset=preset, frames=12, rows=3, columns=3, clock_mhz=53.6)
        with open(os.path.join(root, "scenes", f"{preset}.scene.json")) as f:
            if f.read() != scene_text(args):
                stale.append(preset)
    print("make_scene: " + (f"stale: {', '.join(stale)}" if stale else "scenes/herd and scenes/figures are current"))
    return 1 if stale else 0


if __name__ == "__main__":
    sys.exit(main())
