#!/usr/bin/python3
"""The fair outline metric and popping, for the outline-driven tessellation rules.

What is measured (docs/results/silhouette.md, "The fair metric"):
- Views: VIEWS cameras on one continuous path around each mesh (azimuth 10 + 360 s degrees,
  elevation 22 + 10 sin(2 azimuth) degrees, DISTANCE bounding-box diagonals from the box centre,
  field of view FOV), pictures of SIZE pixels.
- Outline: every visible contour, outer outline and interior occluding contours (a leg in front
  of the body), found by `tessim render --contours` at SAMPLES x SAMPLES samples per pixel: covered
  samples next to background or to a sample farther in view depth by more than a hundredth of
  the bounding-box diagonal.
- Outline error of a picture against the truth's: every contour sample's distance to the nearest
  contour sample of the other picture, both ways, in pixels; the mean (and the 95th percentile
  and the maximum). Per configuration: the mean over the views and its spread across them.
- Truth: plain PN at L = TRUTH_L; for the blended variants also their own limit, the blended
  surface at L = TRUTH_L with the blend's eye at the camera, so that neither is penalised for
  converging to a different surface.
- Share of L = 8's triangles: where a rule's curve (mean triangles, mean error over the views;
  straight between neighbouring tolerances in log-log) crosses uniform PN at L = 8's mean error,
  divided by L = 8's triangles; per view as well (the view's own curve against the view's L = 8).
- Popping: at every view, the camera moves on along the path by STEP_DEG of azimuth (one frame at
  60 frames per second while orbiting at 30 degrees per second). The picture of the next frame
  with the tessellation updated for it is compared with the same picture with the previous frame's
  tessellation (factors and blend eye): both are seen from the same camera, so the camera's motion
  cancels and what remains is the jump the update makes. Reported as the contour distance between
  the two (mean over both contours; the largest single jump, averaged over the frames; the share
  of frames where some contour point jumps more than VISIBLE_POP_PX) and the coverage that changes
  (samples that flip, in pixels of area per pixel of outline). A smooth change (the blend's eye
  moving) shows as small jumps every frame, a factor switching as rare large ones. Uniform patterns do not change with
  the view: their popping is zero by construction and is not rendered. Compared at equal
  triangles: each rule's popping, interpolated in log(triangles), at uniform L = 4's triangle count.

Writes OUT/fair.csv (a row per mesh, view and configuration), OUT/fair.json, OUT/fair.md (its
tables) and OUT/fair.png; --replot rebuilds the last two from fair.json. About 10 minutes on two
cores.

Usage: silhouette_fair.py --tessim build/bin/tessim [--out docs/results/silhouette] [--jobs 2]
                          [--views 24] [--mesh NAME ...] [--replot]
"""
import argparse
import concurrent.futures
import csv
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from silhouette_quality import REFERENCE_L, TARGET_SHARE, bbox, fmt  # noqa: E402

MESHES = {
    "Wuson": "/usr/share/assimp/models/PLY/Wuson.ply",
    "sphereWithHole": "/usr/share/assimp/models/STL/sphereWithHole.stl",
    "sydney": "/usr/share/assimp/models/MD2/sydney.md2",
}
VIEWS = 24
STEP_DEG = 0.5
SIZE = (480, 360)
SAMPLES = 4
DISTANCE = 1.5
FOV = 40.0
TRUTH_L = 32
UNIFORM_L = [2, 3, 4, 6, 8, 12]
SCREEN_PIXELS_PER_SEGMENT = [16, 8, 4, 2, 1]
TOLERANCE = [1, 0.5, 0.25, 0.125, 0.0625, 0.03125, 0.015625]
VISIBLE_POP_PX = 0.5  # a frame pops visibly when some contour point jumps farther
POPPING_BUDGET_L = 4  # popping compared at uniform L = 4's triangle count
# Kind: (tessim arguments given a setting, the setting's name, plot style, legend, blended surface).
KINDS = {
    "uniform": (lambda v: ["-L", str(v)], "L", "o-", "uniform PN", False),
    "screen": (lambda v: ["--adaptive", "screen", "--pixels-per-segment", str(v)], "px/segment", "s--",
               "screen-adaptive factors", False),
    "silhouette": (lambda v: ["--adaptive", "silhouette", "--outline-tolerance", str(v)], "T", "^-",
                   "silhouette rule (per edge), PN patches", False),
    "silhouette-blend": (lambda v: ["--adaptive", "silhouette", "--outline-tolerance", str(v), "--silhouette",
                                    "camera"], "T", "v-", "silhouette rule + blend", True),
    "contour": (lambda v: ["--adaptive", "contour", "--outline-tolerance", str(v)], "T", "P-",
                "contour rule (per patch), PN patches", False),
    "contour-blend": (lambda v: ["--adaptive", "contour", "--outline-tolerance", str(v), "--silhouette", "camera"],
                      "T", "X-", "contour rule + blend", True),
    # Fractional odd spacing moves vertices continuously as a factor grows instead of adding a
    # segment at once: D3D11's answer to popping, at a few more triangles per factor.
    "screen-fractional": (lambda v: ["--adaptive", "screen", "--partitioning", "fractional_odd",
                                     "--pixels-per-segment", str(v)], "px/segment", "s:",
                          "screen-adaptive, fractional_odd", False),
    "contour-fractional": (lambda v: ["--adaptive", "contour", "--partitioning", "fractional_odd",
                                      "--outline-tolerance", str(v)], "T", "P:", "contour rule, fractional_odd", False),
}
SETTINGS = {"uniform": UNIFORM_L, "screen": SCREEN_PIXELS_PER_SEGMENT, "silhouette": TOLERANCE,
            "silhouette-blend": TOLERANCE, "contour": TOLERANCE, "contour-blend": TOLERANCE,
            "screen-fractional": SCREEN_PIXELS_PER_SEGMENT, "contour-fractional": TOLERANCE}
RULES = [k for k in KINDS if k != "uniform"]
OUTLINE_RULES = [k for k in RULES if not k.startswith("screen")]


def camera(centre, radius, s):
    az = math.radians(10.0 + 360.0 * s)
    el = math.radians(22.0 + 10.0 * math.sin(2.0 * az))
    eye = centre + radius * np.array([math.cos(el) * math.sin(az), math.sin(el), math.cos(el) * math.cos(az)])
    return f"eye={fmt(eye)},target={fmt(centre)},fov={FOV:g}"


def write_paths(lo, hi, scratch, name):
    """Two view paths: the views alone, and per view (view; next frame; next frame's picture with
    the view's tessellation)."""
    centre = (lo + hi) / 2
    radius = DISTANCE * float(np.linalg.norm(hi - lo))
    views, frames = [], []
    for k in range(VIEWS):
        s0 = k / VIEWS
        s1 = s0 + STEP_DEG / 360.0
        c0, c1 = camera(centre, radius, s0), camera(centre, radius, s1)
        views.append(c0)
        frames += [c0, c1, f"{c1} ; {c0}"]
    paths = {}
    for kind, lines in (("views", views), ("frames", frames)):
        paths[kind] = os.path.join(scratch, f"{name}-{kind}.path")
        with open(paths[kind], "w") as f:
            f.write("\n".join(lines) + "\n")
    return paths


def run(tessim, mesh, path, extra, out):
    w, h = SIZE
    args = [tessim, "render", mesh, "--view-path", path, "--size", f"{w}x{h}", "--viewport", f"{w}x{h}",
            "--contours", out, "--contour-samples", str(SAMPLES), "--quiet"] + extra
    # --viewport belongs to --adaptive: uniform runs leave it out.
    if "--adaptive" not in extra:
        i = args.index("--viewport")
        del args[i:i + 2]
    subprocess.run(args, check=True, capture_output=True, text=True)
    with open(out) as f:
        doc = json.load(f)
    os.remove(out)
    frames = []
    for fr in doc["frames"]:
        xy = (np.asarray(fr["contour"], dtype=np.float64).reshape(-1, 2) + 0.5) / SAMPLES
        frames.append({"triangles": fr["triangles"], "contour": xy, "coverage": np.asarray(fr["coverage"], np.int64)})
    return frames


def coverage_mask(runs):
    w, h = SIZE[0] * SAMPLES, SIZE[1] * SAMPLES
    edges = np.zeros((h, w + 1), np.int32)
    r = runs.reshape(-1, 3)
    np.add.at(edges, (r[:, 0], r[:, 1]), 1)
    np.add.at(edges, (r[:, 0], r[:, 2]), -1)
    return np.cumsum(edges, axis=1)[:, :w] > 0


def contour_distance(a, b):
    """Every contour point's distance to the other contour, both ways: (mean, 95th percentile, max)."""
    from scipy.spatial import cKDTree  # here: the replot and the tables need no SciPy

    if len(a) == 0 or len(b) == 0:
        return float("inf"), float("inf"), float("inf")
    d = np.concatenate([cKDTree(b).query(a)[0], cKDTree(a).query(b)[0]])
    return float(d.mean()), float(np.percentile(d, 95)), float(d.max())


def measure(name, kind, value, frames, truth, blend_truth):
    rows = []
    per_view = 3 if kind in RULES else 1
    for view in range(VIEWS):
        f0 = frames[per_view * view]
        mean, p95, worst = contour_distance(f0["contour"], truth[view]["contour"])
        row = {"mesh": name, "view": view, "kind": kind, "value": value, "triangles": f0["triangles"],
               "outline_px": len(truth[view]["contour"]) / SAMPLES, "error_px": mean, "error_p95_px": p95,
               "error_max_px": worst, "error_own_limit_px": "", "pop_px": 0.0, "pop_max_px": 0.0,
               "pop_coverage_px": 0.0}
        if KINDS[kind][4]:
            row["error_own_limit_px"] = contour_distance(f0["contour"], blend_truth[view]["contour"])[0]
        if per_view == 3:
            updated, stale = frames[3 * view + 1], frames[3 * view + 2]
            pm, _, pmax = contour_distance(updated["contour"], stale["contour"])
            flips = np.count_nonzero(coverage_mask(updated["coverage"]) ^ coverage_mask(stale["coverage"]))
            row.update(pop_px=pm, pop_max_px=pmax,
                       pop_coverage_px=flips / SAMPLES ** 2 / max(1.0, len(updated["contour"]) / SAMPLES))
        rows.append(row)
    return rows


def spread(values):
    values = sorted(values)
    return {"mean": statistics.fmean(values), "std": statistics.pstdev(values), "min": values[0],
            "median": statistics.median(values), "max": values[-1]}


def crossing(points, target):
    """Triangles where a curve of (triangles, error) points, straight between neighbours in
    log-log, first reaches `target` error going to more triangles; None if it never does."""
    pts = sorted(points)
    if pts and pts[0][1] <= target:
        return pts[0][0]
    for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
        if e0 > target >= e1 and e1 > 0:
            f = math.log(e0 / target) / math.log(e0 / e1)
            return math.exp(math.log(t0) + f * math.log(t1 / t0))
    return None


def at_budget(points, budget):
    """A curve of (triangles, y) interpolated in log(triangles) at `budget`; None outside it."""
    pts = sorted(points)
    for (t0, y0), (t1, y1) in zip(pts, pts[1:]):
        if t0 <= budget <= t1 and t1 > t0:
            f = math.log(budget / t0) / math.log(t1 / t0)
            return y0 + f * (y1 - y0)
    return None


def summarize(rows):
    meshes, popping = [], {}
    for name in MESHES:
        mine = [r for r in rows if r["mesh"] == name]
        configs = {}
        for r in mine:
            configs.setdefault((r["kind"], r["value"]), []).append(r)
        summary = {}
        for (kind, value), rs in configs.items():
            s = {"kind": kind, "value": value, "triangles": spread([r["triangles"] for r in rs]),
                 "error_px": spread([r["error_px"] for r in rs]), "error_p95_px": spread([r["error_p95_px"] for r in rs]),
                 "error_max_px": max(r["error_max_px"] for r in rs)}
            if KINDS[kind][4]:
                s["error_own_limit_px"] = spread([r["error_own_limit_px"] for r in rs])
            if kind in RULES:
                s["pop_px"] = spread([r["pop_px"] for r in rs])
                s["pop_max_px"] = spread([r["pop_max_px"] for r in rs])
                s["pop_frames_over_half_px"] = sum(r["pop_max_px"] > VISIBLE_POP_PX for r in rs) / len(rs)
                s["pop_coverage_px"] = spread([r["pop_coverage_px"] for r in rs])
            summary[f"{kind} {KINDS[kind][1]}={value:g}"] = s
        ref = summary[f"uniform L={REFERENCE_L}"]
        ref_tri, ref_err = ref["triangles"]["mean"], ref["error_px"]["mean"]
        shares, per_view_shares, own_limit_shares = {}, {}, {}
        for kind in RULES:
            pts = [(s["triangles"]["mean"], s["error_px"]["mean"]) for s in summary.values() if s["kind"] == kind]
            t = crossing(pts, ref_err)
            shares[kind] = None if t is None else t / ref_tri
            if KINDS[kind][4]:
                pts = [(s["triangles"]["mean"], s["error_own_limit_px"]["mean"]) for s in summary.values()
                       if s["kind"] == kind]
                t = crossing(pts, ref_err)
                own_limit_shares[kind] = None if t is None else t / ref_tri
            views = []
            for view in range(VIEWS):
                ref_v = next(r for r in mine if r["view"] == view and r["kind"] == "uniform" and r["value"] == REFERENCE_L)
                pts = [(r["triangles"], r["error_px"]) for r in mine if r["view"] == view and r["kind"] == kind]
                t = crossing(pts, ref_v["error_px"])
                views.append(None if t is None else t / ref_v["triangles"])
            reached = [v for v in views if v is not None]
            per_view_shares[kind] = {"reached_in_views": len(reached), **(spread(reached) if reached else {})}
        met = {k: v for k, v in shares.items() if v is not None and k in OUTLINE_RULES}
        best = min(met, key=met.get) if met else None
        budget = summary[f"uniform L={POPPING_BUDGET_L}"]["triangles"]["mean"]
        pops = {}
        for kind in RULES:
            pts = [s for s in summary.values() if s["kind"] == kind]
            pops[kind] = {m: at_budget([(s["triangles"]["mean"], s[m]["mean"]) for s in pts], budget)
                          for m in ("pop_px", "pop_max_px", "pop_coverage_px", "error_px")}
            pops[kind]["pop_frames_over_half_px"] = at_budget(
                [(s["triangles"]["mean"], s["pop_frames_over_half_px"]) for s in pts], budget)
        popping[name] = {"budget_triangles": budget, "budget": f"uniform L={POPPING_BUDGET_L}'s triangles",
                         "uniform": {"pop_px": 0.0, "pop_max_px": 0.0, "pop_coverage_px": 0.0,
                                     "pop_frames_over_half_px": 0.0,
                                     "error_px": summary[f"uniform L={POPPING_BUDGET_L}"]["error_px"]["mean"]},
                         **pops}
        meshes.append({"mesh": name, "file": MESHES[name], "views": VIEWS,
                       "reference": {"config": f"uniform L={REFERENCE_L}", "triangles": ref_tri, "error_px": ref_err,
                                     "error_px_spread": ref["error_px"]},
                       "share_of_l8_triangles": None if best is None else met[best], "best_rule": best,
                       "share_by_rule": shares, "share_against_own_limit": own_limit_shares,
                       "share_per_view": per_view_shares,
                       "target_met": best is not None and met[best] <= TARGET_SHARE, "summary": summary})
    return meshes, popping


def plot(meshes, path):
    fig, axes = plt.subplots(2, len(meshes), figsize=(5.6 * len(meshes), 8.4), squeeze=False)
    colours = dict(zip(KINDS, plt.rcParams["axes.prop_cycle"].by_key()["color"]))
    for col, m in enumerate(meshes):
        ax, bx = axes[0][col], axes[1][col]
        for kind, (_, _, style, text, _) in KINDS.items():
            pts = sorted((s["triangles"]["mean"], s["error_px"]["mean"], s["error_px"]["min"], s["error_px"]["max"],
                          s.get("pop_max_px", {}).get("mean", 0.0)) for s in m["summary"].values() if s["kind"] == kind)
            t = [p[0] for p in pts]
            e = np.array([p[1] for p in pts])
            ax.errorbar(t, e, yerr=[e - [p[2] for p in pts], [p[3] for p in pts] - e], fmt=style, ms=4, lw=1,
                        elinewidth=0.5, capsize=2, label=text, color=colours[kind])
            if kind != "uniform":
                bx.plot(t, [p[4] for p in pts], style, ms=4, lw=1, label=text, color=colours[kind])
        ref = m["reference"]
        ax.axhline(ref["error_px"], color="grey", lw=0.8, ls="--")
        ax.axvline(TARGET_SHARE * ref["triangles"], color="grey", lw=0.8, ls=":")
        shares = [f"{k} {100 * v:.0f} %" for k, v in m["share_by_rule"].items() if v is not None]
        ax.set_title(f"{m['mesh']}: all visible contours, {m['views']} views, {SAMPLES}x{SAMPLES} samples/pixel; "
                     f"share of L = 8's\ntriangles at its error (dashed; dotted: 30 %): " + ", ".join(shares[:3]) +
                     ",\n" + ", ".join(shares[3:]), fontsize=7)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("triangles on the whole mesh (mean over the views)")
        ax.set_ylabel("mean contour error against PN at L = 32 (pixels)\nbars: the views' range")
        ax.grid(True, which="both", lw=0.3)
        ax.legend(fontsize=6)
        bx.axvline(m["summary"][f"uniform L={POPPING_BUDGET_L}"]["triangles"]["mean"], color="grey", lw=0.8, ls=":")
        bx.set_xscale("log")
        bx.set_xlabel("triangles on the whole mesh (mean over the views)")
        bx.set_ylabel("popping: largest contour jump in a frame when the\ntessellation follows a 0.5 degree step (px, mean)")
        bx.set_title(f"{m['mesh']}: popping (uniform: zero by construction; dotted: L = {POPPING_BUDGET_L}'s triangles)",
                     fontsize=7)
        bx.grid(True, which="both", lw=0.3)
        bx.legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def pct(v):
    return "never" if v is None else f"{100 * v:.1f} %"


def write_markdown(doc, path):
    """The tables of docs/results/silhouette.md's fair measurement, generated from fair.json."""
    out = ["<!-- generated by scripts/silhouette_fair.py from fair.json: do not edit -->", "",
           f"{doc['views']} views, {doc['size']} pixels, {doc['samples_per_pixel']}x{doc['samples_per_pixel']} "
           f"samples per pixel; truth {doc['truth']}.", "",
           "Share of uniform L = 8's triangles at its mean contour error (per view: the view's own crossing, "
           "min / median / max, and in how many views the measured tolerances reach it):", ""]
    names = [m["mesh"] for m in doc["meshes"]]
    out.append("| rule | " + " | ".join(names) + " |")
    out.append("|---|" + "---|" * len(names))
    out.append("| uniform L = 8: triangles, contour error (px) | " + " | ".join(
        f"{m['reference']['triangles']:.0f}, {m['reference']['error_px']:.4f}" for m in doc["meshes"]) + " |")
    for kind in RULES:
        cells = []
        for m in doc["meshes"]:
            share = m["share_by_rule"][kind]
            pv = m["share_per_view"][kind]
            cell = pct(share)
            if pv["reached_in_views"]:
                cell += (f" ({100 * pv['min']:.0f} / {100 * pv['median']:.0f} / {100 * pv['max']:.0f} %, "
                         f"{pv['reached_in_views']} of {m['views']})")
            own = m["share_against_own_limit"].get(kind)
            if own is not None or KINDS[kind][4]:
                cell += f"; own limit {pct(own)}"
            cells.append(cell)
        out.append(f"| {KINDS[kind][3]} | " + " | ".join(cells) + " |")
    out += ["", "Popping at equal triangles (uniform L = 4's count; interpolated in log(triangles)): the largest "
            "contour jump in a frame when the tessellation follows a 0.5° camera step (pixels, mean over the views), "
            "the share of frames where it exceeds 0.5 px, and the flipped coverage (pixels of area per pixel of "
            "outline). Uniform patterns do not pop.", ""]
    out.append("| rule | " + " | ".join(names) + " |")
    out.append("|---|" + "---|" * len(names))
    for kind in RULES:
        cells = []
        for m in doc["meshes"]:
            p = doc["popping"][m["mesh"]][kind]
            if p["pop_max_px"] is None:
                cells.append("outside the measured range")
                continue
            cells.append(f"{p['pop_max_px']:.3f} px, {100 * p['pop_frames_over_half_px']:.0f} %, "
                         f"{p['pop_coverage_px']:.4f}; error {p['error_px']:.4f} px")
        out.append(f"| {KINDS[kind][3]} | " + " | ".join(cells) + " |")
    out += ["", "Every configuration (mean over the views; in brackets the views' range):", ""]
    for m in doc["meshes"]:
        out += [f"**{m['mesh']}**", "", "| configuration | triangles | contour error (px) | 95th pct. | own limit | "
                "largest jump per frame (px) | frames > 0.5 px |", "|---|---|---|---|---|---|---|"]
        for config, s in m["summary"].items():
            own = f"{s['error_own_limit_px']['mean']:.4f}" if "error_own_limit_px" in s else ""
            pop = f"{s['pop_max_px']['mean']:.3f}" if "pop_max_px" in s else "0"
            frames = f"{100 * s['pop_frames_over_half_px']:.0f} %" if "pop_max_px" in s else "0 %"
            out.append(f"| {config} | {s['triangles']['mean']:.0f} | {s['error_px']['mean']:.4f} "
                       f"({s['error_px']['min']:.4f}–{s['error_px']['max']:.4f}) | {s['error_p95_px']['mean']:.3f} | "
                       f"{own} | {pop} | {frames} |")
        out.append("")
    with open(path, "w") as f:
        f.write("\n".join(out))


def main():
    global VIEWS
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tessim", required=True)
    ap.add_argument("--out", default="docs/results/silhouette")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--views", type=int, default=VIEWS, help="views on the path (a quick look: fewer)")
    ap.add_argument("--mesh", action="append", choices=list(MESHES), help="only these meshes")
    ap.add_argument("--replot", action="store_true", help="rebuild fair.md and fair.png from OUT/fair.json")
    args = ap.parse_args()
    if args.replot:
        with open(os.path.join(args.out, "fair.json")) as f:
            doc = json.load(f)
        write_markdown(doc, os.path.join(args.out, "fair.md"))
        plot(doc["meshes"], os.path.join(args.out, "fair.png"))
        return 0
    VIEWS = args.views
    for name in [m for m in MESHES if args.mesh and m not in args.mesh]:
        del MESHES[name]
    os.makedirs(args.out, exist_ok=True)
    start = time.time()
    rows = []
    with tempfile.TemporaryDirectory() as scratch, concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        for name, mesh in MESHES.items():
            if not os.path.exists(mesh):
                sys.exit(f"silhouette_fair: {mesh} is missing (scripts/setup.sh installs assimp-testmodels)")
            lo, hi = bbox(args.tessim, mesh)
            paths = write_paths(lo, hi, scratch, name)
            jobs = {("truth", "pn"): pool.submit(run, args.tessim, mesh, paths["views"], ["-L", str(TRUTH_L)],
                                                 os.path.join(scratch, f"{name}-truth.json")),
                    ("truth", "blend"): pool.submit(run, args.tessim, mesh, paths["views"],
                                                    ["-L", str(TRUTH_L), "--silhouette", "camera"],
                                                    os.path.join(scratch, f"{name}-blend-truth.json"))}
            for kind, settings in SETTINGS.items():
                for i, value in enumerate(settings):
                    path = paths["frames"] if kind in RULES else paths["views"]
                    jobs[(kind, value)] = pool.submit(run, args.tessim, mesh, path, KINDS[kind][0](value),
                                                      os.path.join(scratch, f"{name}-{kind}-{i}.json"))
            truth, blend_truth = jobs.pop(("truth", "pn")).result(), jobs.pop(("truth", "blend")).result()
            for (kind, value), job in jobs.items():
                rows += measure(name, kind, value, job.result(), truth, blend_truth)
            print(f"{name}: {len(jobs) + 2} runs measured, {time.time() - start:.0f} s", flush=True)
    with open(os.path.join(args.out, "fair.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})
    meshes, popping = summarize(rows)
    doc = {"views": VIEWS, "size": f"{SIZE[0]}x{SIZE[1]}", "samples_per_pixel": SAMPLES, "distance": DISTANCE,
           "fov_deg": FOV, "step_deg": STEP_DEG, "truth": f"PN at L={TRUTH_L}; blended variants also against the "
           f"blended surface at L={TRUTH_L}", "reference_L": REFERENCE_L, "target_share": TARGET_SHARE,
           "seconds": round(time.time() - start), "meshes": meshes, "popping": popping}
    with open(os.path.join(args.out, "fair.json"), "w") as f:
        json.dump(doc, f, indent=1)
    plot(meshes, os.path.join(args.out, "fair.png"))
    write_markdown(doc, os.path.join(args.out, "fair.md"))
    met = True
    for m in meshes:
        ref = m["reference"]
        print(f"{m['mesh']}: uniform L={REFERENCE_L}: {ref['triangles']:.0f} triangles, contour error "
              f"{ref['error_px']:.4f} px (views {ref['error_px_spread']['min']:.4f}..{ref['error_px_spread']['max']:.4f})")
        for kind, share in m["share_by_rule"].items():
            pv = m["share_per_view"][kind]
            own = m["share_against_own_limit"].get(kind)
            print(f"  {kind}: " + ("never reaches it" if share is None else f"{100 * share:.1f} % of L = 8's triangles")
                  + (f" (per view: {100 * pv['min']:.0f}..{100 * pv['max']:.0f} %, median {100 * pv['median']:.0f} %,"
                     f" reached in {pv['reached_in_views']} of {VIEWS})" if pv["reached_in_views"] else "")
                  + ("" if own is None else f"; against its own limit {100 * own:.1f} %"))
        p = popping[m["mesh"]]
        print(f"  popping at {p['budget_triangles']:.0f} triangles: " + ", ".join(
            f"{k} {p[k]['pop_max_px']:.3f} px largest jump, {100 * p[k]['pop_frames_over_half_px']:.0f} % of frames over "
            f"{VISIBLE_POP_PX} px" for k in RULES if p[k]["pop_px"] is not None))
        met = met and m["target_met"]
    print(f"target (L = {REFERENCE_L}'s contour error with at most {100 * TARGET_SHARE:.0f} % of its triangles, "
          f"every mesh): {'met' if met else 'NOT met'}; {time.time() - start:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
