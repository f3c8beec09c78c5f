"""The rows of a sweep's results CSV for scripts/plots.py (scripts/sweep.py's output, with the
cost_* columns of scripts/costs.py): loading, picking rows by grid and parameter, the number
formats and title phrases of the figures and tables, and the figures' matplotlib style, which
every plots_* module gets by importing `plt` from here."""

import csv
import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

REPO = Path(__file__).resolve().parent.parent

# Reproducible SVG output (no date, fixed ids).
plt.rcParams.update({
    "svg.hashsalt": "tessim",
    "svg.fonttype": "path",
    "figure.dpi": 100,
    "savefig.dpi": 120,
    "font.size": 9,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "legend.fontsize": 8,
})


def parse_value(text):
    if text == "":
        return None
    if text in ("true", "false"):
        return text == "true"
    try:
        return int(text)
    except ValueError:
        pass
    try:
        return float(text)
    except ValueError:
        return text


def load_rows(path):
    with open(path, newline="") as f:
        rows = [{k: parse_value(v) for k, v in r.items()} for r in csv.DictReader(f)]
    for r in rows:
        r["grid_set"] = set(str(r.get("grids") or "").split(";"))
    return [r for r in rows if r.get("status") == "ok"]


def in_grid(rows, name, **where):
    out = []
    for r in rows:
        if name not in r["grid_set"]:
            continue
        if all(r.get(k) == v for k, v in where.items()):
            out.append(r)
    return out


def distinct(rows, key):
    return sorted({r[key] for r in rows if r.get(key) is not None})


def mesh_name(path):
    return Path(str(path)).name


def share(r, key):
    return r[key] / r["cycles"] if r.get(key) is not None and r["cycles"] else float("nan")


def fmt_kb(x):
    return f"{x:,.0f}" if x >= 1000 else f"{x:.4g}"


def fmt(x, digits=3):
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "–"
    if isinstance(x, float):
        return f"{x:.{digits}g}"
    return str(x)


SYMBOLS = {}  # parameter key -> symbol of docs/microarchitecture.md, from `tessim schema` (main)


def workload(rows, *keys):
    """The parameters among `keys` that all rows share, as a short phrase for titles."""
    parts = []
    for k in keys:
        vals = distinct(rows, k)
        if len(vals) != 1:
            continue
        v = vals[0]
        if k == "mesh":
            parts.append(mesh_name(v))
        elif k == "normals":
            parts.append(f"{v} normals")
        elif k == "cpg_mapping":
            parts.append(f"CPG {v}")
        else:
            parts.append(f"{SYMBOLS.get(k, k)} = {v}")
    return ", ".join(parts)


def camera_distance(camera):
    """Distance from the eye to the target of a camera spec "eye=x,y,z,target=x,y,z[,fov=..]"."""
    parts = dict(item.split("=") for item in camera.replace(",target=", ";target=").replace(",fov=", ";fov=")
                 .split(";"))
    eye = [float(x) for x in parts["eye"].split(",")]
    target = [float(x) for x in parts.get("target", "0,0,0").split(",")]
    return math.dist(eye, target)
