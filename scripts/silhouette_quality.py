#!/usr/bin/python3
"""Outline quality per triangle: silhouette-adaptive tessellation against uniform PN.

On a camera path of views around each mesh, renders (tessim render, one sample per pixel, no
caption) the truth, uniform PN at L = 32, then uniform PN at several L and the silhouette rule
(--adaptive silhouette) at several outline tolerances, with plain PN patches (β = 0.25 and a
narrower band, β = 0.08) and with the silhouette blend (β = 0.25 and β = 1), and the contour rule
(--adaptive contour) with plain PN patches and with the blend (β = 0.25). The
outline of a picture is the boundary of the surface's coverage: surface pixels with a
4-neighbour of background colour. The outline error of a picture is measured against the
truth's outline in both directions (every outline pixel's distance to the nearest outline pixel
of the other picture): the mean over all those distances, and their maximum (the Hausdorff
distance), in pixels. Triangles are those the tessellation spends on the whole mesh.

Writes OUT/quality.csv (one row per mesh, view and configuration), OUT/quality.json (per mesh
and configuration: mean and max over the views) and OUT/quality.png (error against triangles),
and prints, per variant, the fewest triangles that reach the mean outline error of uniform PN at
L = 8, and whether the target holds on every mesh: some variant does it with at most 30 % of its
triangles.

Usage: silhouette_quality.py --tessim build/bin/tessim [--out docs/results/silhouette]
                             [--views 8] [--size 640x480] [--distance 1.5] [--jobs 2] [--replot]
"""
import argparse
import concurrent.futures
import csv
import json
import math
import os
import re
import subprocess
import sys
import tempfile

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

MESHES = {
    "Wuson": "/usr/share/assimp/models/PLY/Wuson.ply",
    "sphereWithHole": "/usr/share/assimp/models/STL/sphereWithHole.stl",
}
TRUTH_L = 32
UNIFORM_L = [1, 2, 3, 4, 6, 8, 12, 16]
REFERENCE_L = 8
OUTLINE_TOLERANCE = [2, 1, 0.5, 0.25, 0.125, 0.0625, 0.03125]
# The outline rules' variants: the --silhouette text each adds (None: none, β = 0.25, the
# patches plain PN), how the plot draws it, and the --adaptive rule: the per-edge silhouette rule,
# or the contour rule (every edge of a patch the view contour can cross taken as silhouette).
VARIANTS = {
    "rule": (None, "s-", "silhouette rule, beta 0.25, PN patches", "silhouette"),
    "rule-narrow": ("camera,beta=0.08,blend=off", "D-", "silhouette rule, beta 0.08, PN patches", "silhouette"),
    "blend": ("camera", "^-", "silhouette rule + blend, beta 0.25", "silhouette"),
    "blend-wide": ("camera,beta=1", "v-", "silhouette rule + blend, beta 1", "silhouette"),
    "contour": (None, "P-", "contour rule, beta 0.25, PN patches", "contour"),
    "contour-blend": ("camera", "X-", "contour rule + blend, beta 0.25", "contour"),
}
TARGET_SHARE = 0.30
BACKGROUND = (0.94, 0.94, 0.93)  # render::RenderOptions::background, linear; compared after sRGB below


def bbox(tessim, mesh):
    out = subprocess.run([tessim, "info", mesh, "--json"], check=True, capture_output=True, text=True).stdout
    info = json.loads(out)
    lo, hi = np.array(info["bbox"]["min"]), np.array(info["bbox"]["max"])
    return lo, hi


def camera_path(lo, hi, views, distance):
    """Views on a circle around the box centre at `distance` diagonals, elevations alternating 12 and 32 degrees."""
    centre = (lo + hi) / 2
    radius = distance * np.linalg.norm(hi - lo)
    path = []
    for k in range(views):
        az = math.radians(360.0 * k / views + 10.0)
        el = math.radians(12.0 if k % 2 == 0 else 32.0)
        eye = centre + radius * np.array([math.cos(el) * math.sin(az), math.sin(el), math.cos(el) * math.cos(az)])
        path.append((eye, centre))
    return path


def fmt(v):
    return ",".join(f"{x:.9g}" for x in v)


def render(tessim, mesh, camera, size, pattern, png):
    eye, target = camera
    cam = f"eye={fmt(eye)},target={fmt(target)},fov=40"
    args = [tessim, "render", mesh, "--size", size, "--no-supersample", "--no-caption", "--quiet", "-o", png]
    if pattern[0] == "uniform":
        args += ["-L", str(pattern[1]), "--view-camera", cam]
    else:
        args += ["--adaptive", VARIANTS[pattern[0]][3], "--camera", cam, "--viewport", size, "--outline-tolerance",
                 str(pattern[1])]
        silhouette = VARIANTS[pattern[0]][0]
        if silhouette:
            args += ["--silhouette", silhouette]
    out = subprocess.run(args, check=True, capture_output=True, text=True).stdout
    m = re.search(r"(\d+) input triangles, (\d+) ", out)
    return int(m.group(2))


def outline(png):
    img = mpimg.imread(png)[:, :, :3]
    srgb = np.array([round(255 * (1.055 * c ** (1 / 2.4) - 0.055)) / 255 for c in BACKGROUND])
    surface = np.any(np.abs(img - srgb) > 1.5 / 255, axis=2)
    inner = surface.copy()
    inner[1:, :] &= surface[:-1, :]
    inner[:-1, :] &= surface[1:, :]
    inner[:, 1:] &= surface[:, :-1]
    inner[:, :-1] &= surface[:, 1:]
    edge = surface & ~inner
    return np.argwhere(edge).astype(np.float64)


def nearest(a, b):
    """For each point of a, the distance to the nearest point of b."""
    out = np.empty(len(a))
    for i in range(0, len(a), 512):
        d = ((a[i:i + 512, None, :] - b[None, :, :]) ** 2).sum(axis=2)
        out[i:i + 512] = np.sqrt(d.min(axis=1))
    return out


def outline_error(test, truth):
    if len(test) == 0 or len(truth) == 0:
        return float("inf"), float("inf")
    d = np.concatenate([nearest(test, truth), nearest(truth, test)])
    return float(d.mean()), float(d.max())


def configurations():
    return [("uniform", L) for L in UNIFORM_L] + [(v, t) for v in VARIANTS for t in OUTLINE_TOLERANCE]


def label(pattern):
    if pattern[0] == "uniform":
        return f"uniform L={pattern[1]}"
    return f"{pattern[0]} T={pattern[1]:g}"


def run_view(tessim, name, mesh, view, camera, size, scratch):
    truth_png = os.path.join(scratch, f"{name}-{view}-truth.png")
    render(tessim, mesh, camera, size, ("uniform", TRUTH_L), truth_png)
    truth = outline(truth_png)
    rows = []
    for pattern in configurations():
        png = os.path.join(scratch, f"{name}-{view}-{pattern[0]}-{pattern[1]}.png")
        triangles = render(tessim, mesh, camera, size, pattern, png)
        mean, worst = outline_error(outline(png), truth)
        rows.append({"mesh": name, "view": view, "eye": fmt(camera[0]), "config": label(pattern), "kind": pattern[0],
                     "value": pattern[1], "triangles": triangles, "outline_pixels": len(truth),
                     "mean_error_px": mean, "max_error_px": worst})
        os.remove(png)
    os.remove(truth_png)
    return rows


def summarize(rows):
    summary = {}
    for r in rows:
        s = summary.setdefault(r["mesh"], {}).setdefault(r["config"], {"kind": r["kind"], "value": r["value"],
                                                                       "views": 0, "triangles": 0.0,
                                                                       "mean_error_px": 0.0, "max_error_px": 0.0})
        s["views"] += 1
        s["triangles"] += r["triangles"]
        s["mean_error_px"] += r["mean_error_px"]
        s["max_error_px"] = max(s["max_error_px"], r["max_error_px"])
    for per_mesh in summary.values():
        for s in per_mesh.values():
            s["triangles"] /= s["views"]
            s["mean_error_px"] /= s["views"]
    return summary


def verdict(per_mesh, kind):
    """The cheapest configuration of `kind` at least as good as uniform L = 8 (mean error)."""
    ref = per_mesh[f"uniform L={REFERENCE_L}"]
    ok = [(s["triangles"], c, s) for c, s in per_mesh.items()
          if s["kind"] == kind and s["mean_error_px"] <= ref["mean_error_px"]]
    if not ok:
        return {"reference": ref, "best": None, "share": None, "met": False}
    triangles, config, s = min(ok, key=lambda t: t[0])
    share = triangles / ref["triangles"]
    # Between the measured tolerances (a factor of 2 apart): where the curve, straight between
    # neighbouring points in log-log, crosses the reference error.
    pts = sorted((v["triangles"], v["mean_error_px"]) for v in per_mesh.values() if v["kind"] == kind)
    interpolated = triangles
    for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
        if e0 > ref["mean_error_px"] >= e1 and e0 > e1 > 0:
            f = math.log(e0 / ref["mean_error_px"]) / math.log(e0 / e1)
            interpolated = math.exp(math.log(t0) + f * math.log(t1 / t0))
            break
    return {"reference": ref, "best": config, "best_stats": s, "share": share,
            "share_interpolated": interpolated / ref["triangles"], "met": share <= TARGET_SHARE}


KINDS = (("uniform", "o-", "uniform PN, L = 1..16"),) + tuple((k, v[1], v[2]) for k, v in VARIANTS.items())


def plot(summary, verdicts, path):
    fig, axes = plt.subplots(1, len(summary), figsize=(6.2 * len(summary), 4.8))
    for ax, (name, per_mesh) in zip(np.atleast_1d(axes), summary.items()):
        for kind, style, text in KINDS:
            pts = sorted((s["triangles"], s["mean_error_px"], s["value"]) for s in per_mesh.values() if s["kind"] == kind)
            ax.plot([p[0] for p in pts], [p[1] for p in pts], style, label=text, ms=4)
            for t, e, v in pts:
                ax.annotate(f"{v:g}", (t, e), textcoords="offset points", xytext=(3, 3), fontsize=6)
        ref = verdicts[name]["rule"]["reference"]
        ax.axhline(ref["mean_error_px"], color="grey", lw=0.8, ls="--")
        ax.axvline(TARGET_SHARE * ref["triangles"], color="grey", lw=0.8, ls=":")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("triangles on the whole mesh (mean over the views)")
        ax.set_ylabel("mean outline error against PN at L = 32 (pixels)")
        parts = []
        for kind in VARIANTS:
            v = verdicts[name][kind]
            parts.append(f"{kind} " + ("-" if v["share"] is None else f"{100 * v['share_interpolated']:.0f} %"))
        ax.set_title(f"{name}: share of L = 8's triangles at its error (dashed; dotted = 30 %)\n" + ", ".join(parts),
                     fontsize=8)
        ax.grid(True, which="both", lw=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tessim", required=True)
    ap.add_argument("--out", default="docs/results/silhouette")
    ap.add_argument("--views", type=int, default=8)
    ap.add_argument("--size", default="640x480")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--distance", type=float, default=1.5, help="camera distance in bounding-box diagonals")
    ap.add_argument("--replot", action="store_true", help="read OUT/quality.csv instead of rendering")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    rows = []
    if args.replot:
        with open(os.path.join(args.out, "quality.csv")) as f:
            for r in csv.DictReader(f):
                r["view"] = int(r["view"])
                r["value"] = float(r["value"]) if r["kind"] != "uniform" else int(r["value"])
                for k in ("triangles", "outline_pixels"):
                    r[k] = int(r[k])
                for k in ("mean_error_px", "max_error_px"):
                    r[k] = float(r[k])
                rows.append(r)
    with tempfile.TemporaryDirectory() as scratch, concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        futures = []
        for name, mesh in ({} if args.replot else MESHES).items():
            if not os.path.exists(mesh):
                sys.exit(f"silhouette_quality: {mesh} is missing (scripts/setup.sh installs assimp-testmodels)")
            lo, hi = bbox(args.tessim, mesh)
            for view, camera in enumerate(camera_path(lo, hi, args.views, args.distance)):
                futures.append(pool.submit(run_view, args.tessim, name, mesh, view, camera, args.size, scratch))
        for f in futures:
            rows.extend(f.result())
    rows.sort(key=lambda r: (r["mesh"], r["view"], r["kind"], r["value"]))
    with open(os.path.join(args.out, "quality.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    summary = summarize(rows)
    verdicts = {name: {kind: verdict(per_mesh, kind) for kind in VARIANTS}
                for name, per_mesh in summary.items()}
    with open(os.path.join(args.out, "quality.json"), "w") as f:
        json.dump({"views": args.views, "size": args.size, "distance": args.distance,
                   "truth_L": TRUTH_L, "reference_L": REFERENCE_L, "target_share": TARGET_SHARE,
                   "summary": summary, "verdicts": verdicts}, f, indent=1)
    plot(summary, verdicts, os.path.join(args.out, "quality.png"))
    met = True
    for name, by_kind in verdicts.items():
        ref = by_kind["rule"]["reference"]
        print(f"{name}: uniform L={REFERENCE_L}: {ref['triangles']:.0f} triangles, mean outline error "
              f"{ref['mean_error_px']:.4f} px, max {ref['max_error_px']:.1f} px")
        for kind, v in by_kind.items():
            if v["best"] is None:
                print(f"  {kind}: no configuration reaches it")
                continue
            s = v["best_stats"]
            print(f"  {kind}: {v['best']}: {s['triangles']:.0f} triangles ({100 * v['share']:.1f} %), mean "
                  f"{s['mean_error_px']:.4f} px, max {s['max_error_px']:.1f} px; interpolated between tolerances "
                  f"{100 * v['share_interpolated']:.1f} %")
        met = met and any(v["met"] for v in by_kind.values())
    print(f"target (L = {REFERENCE_L}'s mean outline error with at most {100 * TARGET_SHARE:.0f} % of its "
          f"triangles, on every mesh): {'met' if met else 'NOT met'}")
    return 0 if met else 1


if __name__ == "__main__":
    sys.exit(main())
