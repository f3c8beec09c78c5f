#!/usr/bin/python3
"""Parameter sweeps of the cycle model: every point one `tessim sim` run, results as tidy CSV/JSON.

    sweep.py SPEC.json -o results.csv [--jobs N] [--shard i/n] [--cache DIR] [--tessim PATH]
    sweep.py merge PART.csv [PART.csv ...] -o results.csv [--tessim PATH]

SPEC.json (examples in scripts/sweeps/):

    {
      "base":  { "mesh": "PLY/Wuson.ply", "gpe_cycles": 8 },           # defaults of every point
      "grids": [                                                       # union of Cartesian products
        { "name": "int_vs_gpe", "int_blocks": [1, 2, 3], "gpe_cycles": [4, 8] },
        { "name": "widths", "coord_frac_bits": [12, 16, 20], "errors": true }
      ]
    }

A spec without "grids" is one grid (its top-level keys). A scalar stands for a one-element list.
Keys: every key of a tessim config file (the "parameters" of `tessim schema`, which this script
reads: names, column order, defaults; README.md, Configuration files), plus
  mesh    a mesh file; a relative path is looked up next to the spec, then under
          /usr/share/assimp/models;
  camera, viewport, pixels_per_segment
          an adaptive workload (`tessim sim --adaptive screen --camera ...`): each triangle gets
          the D3D11 factors its edges' projected lengths ask for (docs/patterns.md §7); camera is
          "eye=x,y,z,target=x,y,z,fov=deg", viewport "WxH";
  partitioning
          the unit generates the D3D11 pattern with this spacing (`tessim sim --partitioning`):
          integer, pow2, fractional_odd, fractional_even; with a camera the default is integer,
          without one every factor is tess_factor;
  errors  true: also measure the fixed-point error of the run against the float64 reference
          (`tessim sim --errors`, vertex by vertex): positions relative to the input mesh's
          bounding-box diagonal, normals as angles in radians; columns error.*, and
          error.arithmetic.* for the unit's arithmetic alone against its derived bound.

Output: one row per distinct point (a point listed by two grids runs once; column `grids` names
both), in spec order, with every parameter and every statistic of `tessim sim --stats` flattened
into columns (`te.busy`, `int.blocks.0.utilisation`, `analytic.bounds.cpg`, ...). `-o X.csv`
writes X.csv and X.json (the same rows, typed).

Cache and resume: each finished point is stored at once in the cache directory (default:
OUTPUT.cache/) under a SHA-256 of its full configuration, the content of its mesh and the content
of the tessim binary. A rerun skips cached points, so an interrupted sweep resumes where it
stopped and loses only the points that were running; a rebuilt tessim reruns everything.

Sharding: `--shard i/n` (1 <= i <= n) runs every n-th point starting at the i-th, for n
independent jobs of a batch scheduler. Combine the parts with `sweep.py merge part*.csv -o all.csv`
(rows sorted by their index in the full spec, column `point`), or point every job at one shared
--cache and rerun the unsharded spec once: it only collects.

Batch schedulers: `--slurm SCRIPT [--slurm-tasks n]` writes a Slurm job array whose n tasks are
the shards (one shared cache) and SCRIPT.merge.sh, the merge step to run after them; the header
of SCRIPT shows the two sbatch commands.

Exit status: 0 when the points ran (points the tool rejects as bad input, e.g. widths too narrow
for the mesh, are rows with status `input_error` and its message); 1 when a run crashed or was
killed, or when every point was rejected (a misspelt key); 2 for a bad spec or command line.
"""

import argparse
import concurrent.futures
import csv
import hashlib
import itertools
import json
import math
import os
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path


REPO = Path(__file__).resolve().parent.parent
ASSIMP_MODELS = Path("/usr/share/assimp/models")
CACHE_SCHEMA = 4  # bump when the cache record or the error measurement changes

DEFAULT_TESSIM = REPO / "build" / "bin" / "tessim"
# Keys that are not tessim configuration keys.
# An adaptive workload (tessim sim --adaptive screen): the camera and its viewport and target
# segment length; each triangle then gets its own factors (docs/patterns.md §7). `partitioning`
# makes the unit generate the D3D11 pattern (with a camera: integer unless given; without:
# every factor tess_factor).
ADAPTIVE_KEYS = ("camera", "viewport", "pixels_per_segment")
PATTERN_KEYS = ADAPTIVE_KEYS + ("partitioning",)
SWEEP_KEYS = ("mesh", "errors") + PATTERN_KEYS
# Statistics that are not columns: the config is already the parameter columns, the mesh path
# is the `mesh` parameter, the units are in docs/statistics.md and `tessim schema`, and the
# timeline is a time series of up to 256 buckets, not a figure of the point.
STATS_SKIP = ("config", "mesh", "units", "timeline")


class SpecError(Exception):
    pass


# --------------------------------------------------------------------------- tessim schema

_SCHEMAS = {}


def schema(tessim):
    """`tessim schema`: the unit's parameters (key, flag, kind, type, range, default, RTL name),
    the INT operations and the CPG cycles per normal mode and coordinate format, as C++ defines
    them (sim/config/params.hpp). Raises SpecError when the binary cannot say."""
    tessim = str(tessim)
    if tessim not in _SCHEMAS:
        try:
            proc = subprocess.run([tessim, "schema"], capture_output=True, text=True)
        except OSError as e:
            raise SpecError(f"tessim binary '{tessim}' cannot run (build it, or give --tessim): {e}")
        if proc.returncode != 0:
            raise SpecError(f"'{tessim} schema' exited {proc.returncode}: {proc.stderr.strip()}")
        _SCHEMAS[tessim] = json.loads(proc.stdout)
    return _SCHEMAS[tessim]


def param_order(sch):
    """Column order of the parameters: the mesh, the schema's parameters in its order, errors.
    Keys not listed follow in alphabetical order."""
    return ["mesh", *PATTERN_KEYS] + [p["key"] for p in sch["parameters"]] + ["errors"]


def defaults(sch):
    return {p["key"]: p["default"] for p in sch["parameters"]}


# --------------------------------------------------------------------------- spec

def resolve_mesh(value, spec_dir):
    p = Path(value)
    if p.is_absolute():
        return str(p)
    for base in (spec_dir, ASSIMP_MODELS):
        if (base / p).exists():
            return str((base / p).resolve())
    raise SpecError(f"mesh '{value}' not found next to the spec or under {ASSIMP_MODELS}")


def expand(spec, spec_dir):
    """Points of the spec in order: list of (params dict, grid names)."""
    if not isinstance(spec, dict):
        raise SpecError("the spec must be a JSON object")
    base = spec.get("base", {})
    grids = spec.get("grids")
    if grids is None:
        grids = [{k: v for k, v in spec.items() if k not in ("base", "description")}]
    if not isinstance(base, dict) or not isinstance(grids, list) or not grids:
        raise SpecError("'base' must be an object and 'grids' a non-empty list of objects")
    points, index = [], {}
    for g, grid in enumerate(grids):
        if not isinstance(grid, dict):
            raise SpecError(f"grid {g} is not an object")
        name = str(grid.get("name", f"grid{g}"))
        axes = {k: v for k, v in grid.items() if k != "name"}
        keys = list(axes)
        lists = []
        for k in keys:
            vals = axes[k] if isinstance(axes[k], list) else [axes[k]]
            if not vals:
                raise SpecError(f"grid '{name}': '{k}' has no values")
            lists.append(vals)
        for combo in itertools.product(*lists):
            params = dict(base)
            params.update(zip(keys, combo))
            if "mesh" not in params:
                raise SpecError(f"grid '{name}': no mesh (give 'mesh' in base or in the grid)")
            params["mesh"] = resolve_mesh(params["mesh"], spec_dir)
            params["errors"] = bool(params.get("errors", False))
            if "camera" not in params and any(k in params for k in ADAPTIVE_KEYS):
                raise SpecError(f"grid '{name}': viewport and pixels_per_segment need a camera")
            ident = json.dumps(params, sort_keys=True)
            if ident in index:
                names = points[index[ident]][1]
                if name not in names:
                    names.append(name)
            else:
                index[ident] = len(points)
                points.append((params, [name]))
    return points


def tessim_config(params):
    return {k: v for k, v in params.items() if k not in SWEEP_KEYS}


# --------------------------------------------------------------------------- hashing

def file_sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def point_key(params, mesh_sha, tessim_sha):
    ident = {"schema": CACHE_SCHEMA, "config": tessim_config(params), "errors": params["errors"],
             "mesh_sha256": mesh_sha, "tessim_sha256": tessim_sha}
    adaptive = {k: params[k] for k in ADAPTIVE_KEYS if k in params}
    if adaptive:
        ident["adaptive"] = adaptive
    if "partitioning" in params:
        ident["partitioning"] = params["partitioning"]
    return hashlib.sha256(json.dumps(ident, sort_keys=True).encode()).hexdigest()


# --------------------------------------------------------------------------- running one point

def remote_point(tessim, params, key):
    """One point on a Dask worker: its own Runner and scratch directory (the worker's tessim
    process is the same binary, so the record is the one a local run makes)."""
    workdir = tempfile.mkdtemp(prefix="tessim-sweep-worker-")
    try:
        return Runner(Path(tessim), workdir).point(params, key)
    finally:
        shutil.rmtree(workdir, ignore_errors=True)


class DaskPool:
    """The sweep's executor on a Dask distributed scheduler (python3-distributed)."""

    def __init__(self, address, tessim):
        try:
            import distributed
        except ImportError:
            raise SpecError("--scheduler needs Dask distributed (Debian: python3-distributed)")
        self.distributed = distributed
        try:
            self.client = distributed.Client(address, timeout="10s")
        except OSError as e:
            raise SpecError(f"--scheduler {address}: {e}")
        self.tessim = str(tessim)

    def submit(self, params, key):
        return self.client.submit(remote_point, self.tessim, params, key, key=f"tessim-point-{key}", pure=False)

    def as_completed(self, futures):
        return self.distributed.as_completed(list(futures))

    def shutdown(self, wait=True, cancel_futures=False):
        if self.client is not None:  # closing the client releases (and so cancels) its futures
            self.client.close()
            self.client = None


class Runner:
    """Runs points; tracks child processes so an interrupt can end them."""

    def __init__(self, tessim, workdir):
        self.tessim = tessim
        self.workdir = Path(workdir)
        self.lock = threading.Lock()
        self.children = set()
        self.stopping = False
        self.infos = {}       # mesh -> `tessim info --json`

    def run(self, args, what):
        proc = subprocess.Popen([str(self.tessim)] + args, stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True)
        with self.lock:
            if self.stopping:
                proc.kill()
            self.children.add(proc)
        try:
            out, err = proc.communicate()
        finally:
            with self.lock:
                self.children.discard(proc)
        if proc.returncode == 2:
            raise InputRejected(err.strip() or f"{what}: exit status 2")
        if proc.returncode != 0:
            raise RuntimeError(f"{what}: exit status {proc.returncode}: {err.strip()}")
        return out

    def stop(self):
        with self.lock:
            self.stopping = True
            for p in self.children:
                p.kill()

    def point(self, params, key):
        tmp = Path(tempfile.mkdtemp(prefix=f"pt-{key[:12]}-", dir=self.workdir))
        try:
            cfg = tmp / "config.json"
            cfg.write_text(json.dumps(tessim_config(params)))
            stats = tmp / "stats.json"
            args = ["sim", params["mesh"], "--config", str(cfg), "--stats", str(stats)]
            if params["errors"]:
                args.append("--errors")
            if "camera" in params:
                args += ["--adaptive", "screen", "--camera", str(params["camera"])]
                if "viewport" in params:
                    args += ["--viewport", str(params["viewport"])]
                if "pixels_per_segment" in params:
                    args += ["--pixels-per-segment", str(params["pixels_per_segment"])]
            if "partitioning" in params:
                args += ["--partitioning", str(params["partitioning"])]
            try:
                self.run(args, f"sim {params['mesh']}")
            except InputRejected as e:
                # The config file is a temporary of this run: name the point's configuration instead.
                return {"status": "input_error", "message": str(e).replace(str(cfg), "the point's configuration")}
            record = {"status": "ok", "stats": json.loads(stats.read_text())}
            if params["errors"]:
                # Measured by tessim itself (sim --errors): against the mesh's float reference.
                record["errors"] = record["stats"].pop("errors")
            return record
        finally:
            shutil.rmtree(tmp, ignore_errors=True)

    def mesh_info(self, mesh):
        with self.lock:
            if mesh in self.infos:
                return self.infos[mesh]
        info = json.loads(self.run(["info", mesh, "--json"], f"info {mesh}"))
        with self.lock:
            self.infos[mesh] = info
        return info


class InputRejected(Exception):
    """tessim exited with status 2: the point's input is invalid (a result, not a failure)."""


# --------------------------------------------------------------------------- rows

def flatten(prefix, value, out):
    if isinstance(value, dict):
        for k, v in value.items():
            flatten(f"{prefix}.{k}" if prefix else k, v, out)
    elif isinstance(value, list):
        for i, v in enumerate(value):
            flatten(f"{prefix}.{i}", v, out)
    else:
        out[prefix] = value


def make_row(index, params, grids, key, record, tessim_sha, order):
    row = {"point": index, "key": key[:16], "grids": ";".join(grids), "status": record["status"]}
    conf = dict(params)
    if record["status"] == "ok":
        for k, v in record["stats"]["config"].items():
            conf.setdefault(k, v)
    known = [k for k in order if k in conf]
    for k in known + sorted(k for k in conf if k not in order):
        row[k] = conf[k]
    if record["status"] == "ok":
        stats = {k: v for k, v in record["stats"].items() if k not in STATS_SKIP}
        flatten("", stats, row)
        if "errors" in record:
            flatten("error", record["errors"], row)
    row["message"] = record.get("message", "")
    row["tessim_sha256"] = tessim_sha[:16]
    return row


LEAD_COLUMNS = ["point", "key", "grids", "status"]
# The figures a reader looks at first, right after the parameters.
HEADLINE_STATS = ["triangles", "triangles_in", "vertices_out", "cycles", "cycles_per_vertex",
                  "throughput", "bottleneck", "analytic.cycles_per_vertex", "analytic.bottleneck"]
TRAIL_COLUMNS = ["message", "tessim_sha256"]
# Top-level statistics besides the unit's run counters (which `tessim schema` lists).
TOP_LEVEL_STATS = {"triangles", "cycles_per_vertex", "throughput", "bottleneck", "cpg_cycles_per_triangle",
                   "wall_seconds", "schema_version"}


def natural_key(name):
    """int.blocks.10 after int.blocks.9."""
    return [(0, int(p), "") if p.isdigit() else (1, 0, p) for p in name.split(".")]


def columns_of(rows, order, run_counters=()):
    """Lead columns, parameters, headline statistics, the other statistics (natural order),
    the error and cost columns, then message and binary hash."""
    present = set()
    for r in rows:
        present.update(r)
    params = [k for k in order if k in present]
    rest = sorted(present - set(LEAD_COLUMNS) - set(params) - set(HEADLINE_STATS) - set(TRAIL_COLUMNS),
                  key=natural_key)
    stats = [k for k in rest if not k.startswith(("error.", "cost_"))]
    extra = [k for k in rest if k.startswith("error.")] + [k for k in rest if k.startswith("cost_")]
    # Configuration keys this script does not know yet are the undotted names that are not
    # top-level statistics of tessim (only their column position depends on it).
    unknown_params = [k for k in stats if "." not in k and k not in TOP_LEVEL_STATS and k not in run_counters]
    stats = [k for k in stats if k not in unknown_params]
    return ([k for k in LEAD_COLUMNS if k in present] + params + unknown_params +
            [k for k in HEADLINE_STATS if k in present] + stats + extra +
            [k for k in TRAIL_COLUMNS if k in present])


def csv_value(v):
    if v is None:
        return ""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return repr(v)
    return v


def write_atomic(path, text):
    path = Path(path)
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(text)
    os.replace(tmp, path)


def write_results(rows, out_csv, order, run_counters=()):
    """`order`: param_order() of the schema; `run_counters`: its statistics.per_run."""
    out_csv = Path(out_csv)
    cols = columns_of(rows, order, run_counters)
    import io
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(cols)
    for r in rows:
        w.writerow([csv_value(r.get(c)) for c in cols])
    write_atomic(out_csv, buf.getvalue())
    write_atomic(out_csv.with_suffix(".json"), json.dumps(rows, indent=1) + "\n")


# --------------------------------------------------------------------------- progress

def fmt_time(s):
    if s is None or not math.isfinite(s):
        return "--:--"
    s = int(s + 0.5)
    return f"{s // 3600}:{s // 60 % 60:02d}:{s % 60:02d}" if s >= 3600 else f"{s // 60}:{s % 60:02d}"


class Progress:
    """Progress bar with rate and ETA on stderr, redrawn in place; only on a terminal and without
    --quiet (otherwise only the final line). The ETA weighs each point by its expected simulated
    cycles; the rate counts the points run (not those taken from the cache)."""

    def __init__(self, total_points, cached, total_weight, quiet=False):
        self.total = total_points
        self.done = cached
        self.cached = cached
        self.total_weight = total_weight
        self.done_weight = 0.0
        self.start = time.monotonic()
        self.shown = sys.stderr.isatty() and not quiet
        self.last = 0.0
        self.failed = 0
        self.width = 0
        self.draw(force=True)

    def advance(self, weight, failed=False):
        self.done += 1
        self.done_weight += weight
        self.failed += failed
        self.draw()

    def draw(self, force=False, final=False):
        now = time.monotonic()
        # Off the terminal (or --quiet) only the final line, a summary like the rows line after it.
        if (not self.shown and not final) or (not force and not final and now - self.last < 0.1):
            return
        self.last = now
        elapsed = now - self.start
        frac = self.done / self.total if self.total else 1.0
        eta = None
        if self.done_weight > 0 and self.total_weight > 0:
            eta = elapsed * (self.total_weight - self.done_weight) / self.done_weight
        width = 30
        bar = "#" * int(width * frac) + "." * (width - int(width * frac))
        rate = (self.done - self.cached) / elapsed if elapsed > 0 else 0.0
        msg = (f"[{bar}] {self.done}/{self.total} points ({self.cached} cached"
               f"{', %d rejected' % self.failed if self.failed else ''}) "
               f"{rate:.3g} points/s elapsed {fmt_time(elapsed)} ETA {fmt_time(0 if final else eta)}")
        if self.shown:
            sys.stderr.write("\r" + msg.ljust(self.width) + ("\n" if final else ""))
        else:
            sys.stderr.write(msg + "\n")
        self.width = len(msg)
        sys.stderr.flush()


def expected_cycles(params, triangles, sch):
    """Rough simulated cycles of a point (for the ETA only): the slowest of the INT blocks, the
    geometry engine and the CPG, with the INT ops and CPG cycles that `tessim schema` gives."""
    p = dict(defaults(sch))
    p.update(params)
    L = int(p["tess_factor"])
    patch = (L + 1) * (L + 2) // 2
    mode = str(p["normals"])
    ops = sch["int_ops_per_mode"].get(mode, sch["int_ops_per_mode"]["quadratic"])["ops_per_vertex"]
    k = float(p["gpe_cycles"]) / (1.0 - min(float(p["gpe_stall_prob"]), 0.99))
    if p["cpg_mapping"] == "gpe":
        cpg = int(p["cpg_gpe_cycles"])
    else:
        rows = sch["cpg_cycles"].get(mode, sch["cpg_cycles"]["quadratic"])
        cpg = next((r["cycles"] for r in rows if r["coord_int_bits"] == p["coord_int_bits"]
                    and r["coord_frac_bits"] == p["coord_frac_bits"]), max(r["cycles"] for r in rows))
        # A faster CPG variant: its C at the default format, scaled to this format's C.
        variants = sch.get("cpg_cycles_by_variant", [])
        base = next((r for r in variants if r["cpg_lanes"] == 1 and r["cpg_digit_bits"] == 1
                     and r.get("cpg_product_reg", 0) == 0), None)
        this = next((r for r in variants if r["cpg_lanes"] == p.get("cpg_lanes", 1)
                     and r["cpg_digit_bits"] == p.get("cpg_digit_bits", 1)
                     and r.get("cpg_product_reg", 0) == p.get("cpg_product_reg", 0)), None)
        if base and this and mode in this:
            cpg = cpg * this[mode] / base[mode]
    per_vertex = max(ops / int(p["int_blocks"]), k, cpg / patch, 1.0)
    cost = triangles * patch * per_vertex
    return cost * 3 if params["errors"] else cost


# --------------------------------------------------------------------------- commands

def parse_shard(text):
    try:
        i, n = (int(x) for x in text.split("/"))
    except ValueError:
        raise SpecError(f"--shard '{text}': expected i/n, e.g. 2/4")
    if not 1 <= i <= n:
        raise SpecError(f"--shard '{text}': need 1 <= i <= n")
    return i, n


def cmd_sweep(argv):
    ap = argparse.ArgumentParser(prog="sweep.py", description="Run a parameter sweep of tessim sim.",
                                 epilog="See the module docstring (head of this file) for the spec format.")
    ap.add_argument("spec", help="sweep specification (JSON)")
    ap.add_argument("-o", "--output", required=True, help="results CSV (a .json with the same rows is written next to it)")
    ap.add_argument("--jobs", "-j", type=int, default=os.cpu_count() or 1, help="points run in parallel (default: cores)")
    ap.add_argument("--shard", help="i/n: run only every n-th point starting at the i-th (1-based)")
    ap.add_argument("--cache", help="cache directory (default: OUTPUT.cache)")
    ap.add_argument("--tessim", default=str(DEFAULT_TESSIM), help="tessim binary (default: build/bin/tessim)")
    ap.add_argument("--quiet", "-q", action="store_true",
                    help="no progress line (shown on a terminal only: points done/total, rate, ETA)")
    ap.add_argument("--scheduler", metavar="ADDRESS",
                    help="run the points on a Dask distributed cluster (e.g. tcp://host:8786); its workers "
                         "must see the same tessim binary, meshes and cache paths (a shared file system)")
    ap.add_argument("--slurm", metavar="SCRIPT",
                    help="write a Slurm job-array script (one task per shard) and its merge step "
                         "SCRIPT.merge.sh instead of running the points")
    ap.add_argument("--slurm-tasks", type=int, default=8, help="array tasks (shards) for --slurm (default 8)")
    args = ap.parse_args(argv)
    if args.slurm:
        return write_slurm(args)

    try:
        spec_path = Path(args.spec)
        try:
            spec = json.loads(spec_path.read_text())
        except (OSError, json.JSONDecodeError) as e:
            raise SpecError(f"{args.spec}: {e}")
        points = expand(spec, spec_path.resolve().parent)
        shard = parse_shard(args.shard) if args.shard else (1, 1)
        if args.jobs < 1:
            raise SpecError("--jobs must be at least 1")
        tessim = Path(args.tessim)
        if not os.access(tessim, os.X_OK):
            raise SpecError(f"tessim binary '{tessim}' not found (build it, or give --tessim)")
        sch = schema(tessim)
        dask_pool = DaskPool(args.scheduler, tessim) if args.scheduler else None
    except SpecError as e:
        print(f"sweep.py: error: {e}", file=sys.stderr)
        return 2

    selected = [(i, p, g) for i, (p, g) in enumerate(points) if i % shard[1] == shard[0] - 1]
    cache = Path(args.cache) if args.cache else Path(args.output).with_name(Path(args.output).name + ".cache")
    cache.mkdir(parents=True, exist_ok=True)
    tessim_sha = file_sha256(tessim)

    workdir = tempfile.mkdtemp(prefix="tessim-sweep-")
    runner = Runner(tessim, workdir)
    try:
        meshes = sorted({p["mesh"] for _, p, _ in selected})
        mesh_sha = {m: file_sha256(m) for m in meshes}
        try:
            triangles = {m: int(runner.mesh_info(m)["triangles"]) for m in meshes}
        except (InputRejected, RuntimeError) as e:
            print(f"sweep.py: error: {e}", file=sys.stderr)
            return 2

        keyed = [(i, p, g, point_key(p, mesh_sha[p["mesh"]], tessim_sha)) for i, p, g in selected]
        records = {}
        todo = []
        for i, p, g, key in keyed:
            path = cache / key[:2] / f"{key}.json"
            if path.exists():
                try:
                    records[key] = json.loads(path.read_text())
                    continue
                except json.JSONDecodeError:
                    pass  # a damaged entry is simply recomputed
            todo.append((i, p, g, key))
        unique_todo = list({key: (i, p, g, key) for i, p, g, key in todo}.values())
        weights = {key: expected_cycles(p, triangles[p["mesh"]], sch) for _, p, _, key in unique_todo}
        progress = Progress(len(keyed), len(keyed) - len(unique_todo), sum(weights.values()), args.quiet)

        crashed = []
        if dask_pool:
            pool = dask_pool
        else:
            pool = concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs)
        interrupted = False

        def on_term(signum, frame):
            raise KeyboardInterrupt

        old_term = signal.signal(signal.SIGTERM, on_term)
        try:
            if args.scheduler:
                futures = {pool.submit(p, key): (i, p, g, key) for i, p, g, key in unique_todo}
            else:
                futures = {pool.submit(runner.point, p, key): (i, p, g, key) for i, p, g, key in unique_todo}
            for fut in pool.as_completed(futures) if args.scheduler else concurrent.futures.as_completed(futures):
                i, p, g, key = futures[fut]
                try:
                    record = fut.result()
                except Exception as e:  # a crash of tessim or of the measurement: not cached
                    crashed.append((i, str(e)))
                    progress.advance(weights[key], failed=True)
                    continue
                record["params"] = p
                record["tessim_sha256"] = tessim_sha
                path = cache / key[:2] / f"{key}.json"
                path.parent.mkdir(exist_ok=True)
                write_atomic(path, json.dumps(record))
                records[key] = record
                progress.advance(weights[key], failed=record["status"] != "ok")
        except KeyboardInterrupt:
            interrupted = True
            pool.shutdown(wait=False, cancel_futures=True)
            runner.stop()
        finally:
            signal.signal(signal.SIGTERM, old_term)
            pool.shutdown(wait=True, cancel_futures=True)
        progress.draw(final=True)
        if interrupted:
            print(f"sweep.py: interrupted; {len(records)} of {len(keyed)} points are in {cache}, "
                  "rerun the same command to resume", file=sys.stderr)
            return 130

        order = param_order(sch)
        rows = [make_row(i, p, g, key, records[key], tessim_sha, order) for i, p, g, key in keyed if key in records]
        write_results(rows, args.output, order, sch["statistics"]["per_run"])
        rejected = [r for r in rows if r["status"] != "ok"]
        if rejected:
            print(f"sweep.py: {len(rejected)} points rejected as bad input (status input_error), "
                  f"first: point {rejected[0]['point']}: {rejected[0]['message']}", file=sys.stderr)
        for i, msg in crashed:
            print(f"sweep.py: point {i} failed: {msg}", file=sys.stderr)
        print(f"sweep.py: {len(rows)} rows -> {args.output}, {Path(args.output).with_suffix('.json')}",
              file=sys.stderr)
        # Every point rejected is a broken spec (a misspelt key, a mesh the widths cannot hold).
        return 1 if crashed or (rows and len(rejected) == len(rows)) else 0
    finally:
        shutil.rmtree(workdir, ignore_errors=True)


def read_rows(path):
    path = Path(path)
    if path.suffix == ".json":
        return json.loads(path.read_text())
    json_twin = path.with_suffix(".json")
    if json_twin.exists():
        return json.loads(json_twin.read_text())
    with open(path, newline="") as f:
        return [{k: v for k, v in r.items() if v != ""} for r in csv.DictReader(f)]


def write_slurm(args):
    """A Slurm job array whose tasks are the shards of the sweep, plus the merge step. Each task
    runs this script with --shard i/n into its own part file and one shared cache; the merge
    joins the parts in spec order (the same rows as an unsharded run)."""
    if args.slurm_tasks < 1:
        print("sweep.py: error: --slurm-tasks must be at least 1", file=sys.stderr)
        return 2
    if args.shard:
        print("sweep.py: error: --slurm makes the shards itself; leave out --shard", file=sys.stderr)
        return 2
    n = args.slurm_tasks
    here = Path(__file__).resolve()
    out = Path(args.output).resolve()
    cache = Path(args.cache).resolve() if args.cache else out.with_name(out.name + ".cache")
    spec = Path(args.spec).resolve()
    tessim = Path(args.tessim).resolve()
    part = f"{out.with_suffix('')}.part$SLURM_ARRAY_TASK_ID.csv"
    quote = shlex.quote
    script = f"""#!/bin/bash
# Generated by scripts/sweep.py --slurm: the sweep {spec.name} as {n} array tasks, one shard each.
# Submit with the merge step after it:
#   jid=$(sbatch --parsable {quote(args.slurm)}) && sbatch --dependency=afterok:$jid {quote(args.slurm)}.merge.sh
#SBATCH --job-name=tessim-sweep
#SBATCH --array=1-{n}
#SBATCH --cpus-per-task=2
#SBATCH --output={out.parent}/slurm-%A_%a.out
set -euo pipefail
exec /usr/bin/python3 {quote(str(here))} {quote(str(spec))} -o "{part}" --shard "$SLURM_ARRAY_TASK_ID/{n}" \
  --cache {quote(str(cache))} --tessim {quote(str(tessim))} --jobs "${{SLURM_CPUS_PER_TASK:-1}}"
"""
    parts = " ".join(quote(f"{out.with_suffix('')}.part{i}.csv") for i in range(1, n + 1))
    merge = f"""#!/bin/bash
# Generated by scripts/sweep.py --slurm: joins the {n} parts of {spec.name} into {out.name}.
#SBATCH --job-name=tessim-sweep-merge
#SBATCH --output={out.parent}/slurm-%j-merge.out
set -euo pipefail
exec /usr/bin/python3 {quote(str(here))} merge {parts} -o {quote(str(out))} --tessim {quote(str(tessim))}
"""
    for path, text in ((Path(args.slurm), script), (Path(args.slurm + ".merge.sh"), merge)):
        path.write_text(text)
        path.chmod(0o755)
    print(f"sweep.py: wrote {args.slurm} ({n} array tasks) and {args.slurm}.merge.sh", file=sys.stderr)
    return 0


def cmd_merge(argv):
    ap = argparse.ArgumentParser(prog="sweep.py merge",
                                 description="Merge the results of shards (CSV or JSON) into one table.")
    ap.add_argument("parts", nargs="+", help="results of the shards (X.csv reads X.json when it exists)")
    ap.add_argument("-o", "--output", required=True, help="merged CSV (and JSON next to it)")
    ap.add_argument("--tessim", default=str(DEFAULT_TESSIM),
                    help="tessim binary whose schema orders the parameter columns (default: build/bin/tessim)")
    args = ap.parse_args(argv)
    try:
        sch = schema(args.tessim)
        order = param_order(sch)
    except SpecError as e:
        print(f"sweep.py: error: {e}", file=sys.stderr)
        return 2
    rows, seen = [], set()
    for part in args.parts:
        for r in read_rows(part):
            if r["key"] not in seen:
                seen.add(r["key"])
                rows.append(r)
    rows.sort(key=lambda r: int(r["point"]))
    write_results(rows, args.output, order, sch["statistics"]["per_run"])
    print(f"sweep.py: merged {len(rows)} rows from {len(args.parts)} parts -> {args.output}", file=sys.stderr)
    return 0


def main(argv):
    if argv and argv[0] == "merge":
        return cmd_merge(argv[1:])
    return cmd_sweep(argv)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
