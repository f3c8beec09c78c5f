#!/usr/bin/python3
"""ctest sweep_smoke: scripts/sweep.py on the 4-point spec smoke.json.

Checks, independently of sweep.py's own code: 4 rows with status ok; every statistic of a
direct `tessim sim --stats` run of the same point is a column with the same value; every
configuration key is a parameter column; the error columns of the point that asks for them are
within the documented bound; a rerun takes everything from the cache and writes the same CSV; a
lost cache entry is recomputed alone; two shards merged, a Slurm job array run task by task and
a Dask cluster of two worker processes give the same rows as the plain run; plots.py draws a
figure of these rows (--x, --y, --hue) and names an unknown column.
"""

import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
SWEEP = HERE.parent / "sweep.py"
SPEC = HERE / "smoke.json"


def fail(msg):
    print(f"sweep_smoke: FAIL: {msg}", file=sys.stderr)
    sys.exit(1)


def run_sweep(tessim, out, cache, *extra):
    proc = subprocess.run([sys.executable, str(SWEEP), str(SPEC), "-o", str(out), "--jobs", "2",
                           "--tessim", tessim, "--cache", str(cache), *extra],
                          capture_output=True, text=True)
    if proc.returncode != 0:
        fail(f"sweep.py {' '.join(extra)} exited {proc.returncode}: {proc.stderr}")
    return proc.stderr


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def flatten(prefix, value, out):
    if isinstance(value, dict):
        for k, v in value.items():
            flatten(f"{prefix}.{k}" if prefix else k, v, out)
    elif isinstance(value, list):
        for i, v in enumerate(value):
            flatten(f"{prefix}.{i}", v, out)
    else:
        out[prefix] = value


def same(csv_text, value):
    if isinstance(value, bool):
        return csv_text == ("true" if value else "false")
    if isinstance(value, float):
        return float(csv_text) == value
    return csv_text == str(value)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--tessim", required=True)
    tessim = ap.parse_args().tessim
    with tempfile.TemporaryDirectory(prefix="sweep-smoke-") as tmp:
        tmp = Path(tmp)
        out, cache = tmp / "results.csv", tmp / "cache"
        run_sweep(tessim, out, cache)
        rows = read_csv(out)
        if len(rows) != 4:
            fail(f"{len(rows)} rows, expected 4")
        if any(r["status"] != "ok" for r in rows):
            fail("a point did not run: " + "; ".join(r["message"] for r in rows if r["status"] != "ok"))
        if not (tmp / "results.json").exists() or len(json.loads((tmp / "results.json").read_text())) != 4:
            fail("results.json missing or not 4 rows")

        # plots.py draws one figure of any sweep: a line per --hue value, rows averaged; an unknown
        # column is an error naming it, and nothing is written.
        plots = HERE.parent / "plots.py"
        fig = tmp / "fig" / "cycles.png"
        proc = subprocess.run([sys.executable, str(plots), str(out), "--x", "int_blocks", "--y", "cycles",
                               "--hue", "errors", "-o", str(fig)], capture_output=True, text=True, cwd=tmp)
        if proc.returncode != 0 or not fig.exists() or not fig.with_suffix(".svg").exists():
            fail(f"plots.py --x/--y: exit {proc.returncode}, {proc.stderr}")
        proc = subprocess.run([sys.executable, str(plots), str(out), "--x", "int_blocks", "--y", "no_such_column",
                               "-o", str(tmp / "bad.png")], capture_output=True, text=True, cwd=tmp)
        if proc.returncode != 2 or "no_such_column" not in proc.stderr or (tmp / "bad.png").exists():
            fail(f"plots.py with an unknown column: exit {proc.returncode}, {proc.stderr}")

        # Every statistic of a direct run of the last point (N = 2, errors) is a column, same value.
        row = rows[-1]
        spec = json.loads(SPEC.read_text())
        config = dict(spec["base"], int_blocks=2)
        mesh = "/usr/share/assimp/models/" + config.pop("mesh")
        (tmp / "cfg.json").write_text(json.dumps(config))
        subprocess.run([tessim, "sim", mesh, "--config", str(tmp / "cfg.json"), "--stats", str(tmp / "s.json")],
                       check=True, capture_output=True)
        stats = json.loads((tmp / "s.json").read_text())
        for key, value in stats["config"].items():
            if key not in row:
                fail(f"parameter column '{key}' missing")
            if not same(row[key], value):
                fail(f"parameter {key}: CSV {row[key]!r}, tessim {value!r}")
        flat = {}
        # Not columns: the parameters, the units and the timeline (a time series).
        flatten("", {k: v for k, v in stats.items() if k not in ("config", "mesh", "units", "timeline")}, flat)
        for key, value in flat.items():
            if key not in row:
                fail(f"statistic column '{key}' missing")
            if key != "wall_seconds" and not same(row[key], value):
                fail(f"statistic {key}: CSV {row[key]!r}, direct run {value!r}")
        for r in rows:
            model, sim = float(r["analytic.cycles_per_vertex"]), float(r["cycles_per_vertex"])
            if not model <= sim <= 1.01 * model:
                fail(f"point {r['point']}: analytic {model} vs simulated {sim} cycles/vertex")

        # Error columns: only where asked, and within the arithmetic + quantization scale of F = 20.
        for r in rows:
            has = r.get("error.position_max", "") != ""
            if has != (r["errors"] == "true"):
                fail(f"point {r['point']}: error columns present={has}, errors={r['errors']}")
            if has and not (0 < float(r["error.position_max"]) < 1e-5 and
                            0 < float(r["error.normal_angle_max"]) < 1e-3):
                fail(f"point {r['point']}: errors out of range: {r['error.position_max']}, "
                     f"{r['error.normal_angle_max']}")
            if has and r.get("error.arithmetic.beyond_bound") != "0":
                fail(f"point {r['point']}: {r.get('error.arithmetic.beyond_bound')} vertices beyond the "
                     f"arithmetic bound")

        # Rerun: all cached, identical output.
        first = out.read_text()
        log = run_sweep(tessim, out, cache)
        if "4 cached" not in log or out.read_text() != first:
            fail(f"rerun did not come from the cache unchanged: {log}")
        # A lost entry (a point killed in flight) is recomputed alone.
        entries = sorted(cache.glob("*/*.json"))
        if len(entries) != 4:
            fail(f"{len(entries)} cache entries, expected 4")
        entries[0].unlink()
        log = run_sweep(tessim, out, cache)
        if "3 cached" not in log or len(read_csv(out)) != 4:
            fail(f"resume did not recompute exactly one point: {log}")

        # Shards 1/2 and 2/2, merged, give the same rows in the same order.
        run_sweep(tessim, tmp / "p1.csv", cache, "--shard", "1/2")
        run_sweep(tessim, tmp / "p2.csv", cache, "--shard", "2/2")
        if len(read_csv(tmp / "p1.csv")) != 2 or len(read_csv(tmp / "p2.csv")) != 2:
            fail("shards do not hold 2 rows each")
        subprocess.run([sys.executable, str(SWEEP), "merge", str(tmp / "p1.csv"), str(tmp / "p2.csv"),
                        "-o", str(tmp / "merged.csv"), "--tessim", tessim], check=True, capture_output=True)
        merged = [(r["key"], r["cycles"]) for r in read_csv(tmp / "merged.csv")]
        if merged != [(r["key"], r["cycles"]) for r in read_csv(out)]:
            fail("merged shards differ from the unsharded run")

        # A Slurm job array of 3 shards, its tasks run here as Slurm would (one environment
        # variable each) into a fresh cache, then its merge step: the same rows as the plain run.
        script = tmp / "sweep.sbatch"
        subprocess.run([sys.executable, str(SWEEP), str(SPEC), "-o", str(tmp / "slurm.csv"), "--cache",
                        str(tmp / "slurm-cache"), "--tessim", tessim, "--slurm", str(script), "--slurm-tasks", "3"],
                       check=True, capture_output=True)
        text = script.read_text()
        if "#SBATCH --array=1-3" not in text or "--shard \"$SLURM_ARRAY_TASK_ID/3\"" not in text:
            fail("the Slurm script does not map array tasks onto shards:\n" + text)
        for task in (1, 2, 3):
            env = dict(os.environ, SLURM_ARRAY_TASK_ID=str(task), SLURM_CPUS_PER_TASK="1")
            subprocess.run(["bash", str(script)], check=True, capture_output=True, env=env)
        subprocess.run(["bash", str(script) + ".merge.sh"], check=True, capture_output=True)
        columns = ("key", "point", "cycles", "vertices_out")
        slurm = [tuple(r[c] for c in columns) for r in read_csv(tmp / "slurm.csv")]
        if slurm != [tuple(r[c] for c in columns) for r in read_csv(out)]:
            fail("the Slurm job array's merged rows differ from the plain run")

        # A Dask cluster of two worker processes (as on other machines sharing the file system):
        # the same rows as the plain run.
        from distributed import LocalCluster
        with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
            subprocess.run([sys.executable, str(SWEEP), str(SPEC), "-o", str(tmp / "dask.csv"), "--cache",
                            str(tmp / "dask-cache"), "--tessim", tessim, "--scheduler", cluster.scheduler_address],
                           check=True, capture_output=True)
        dask = [tuple(r[c] for c in columns) for r in read_csv(tmp / "dask.csv")]
        if dask != [tuple(r[c] for c in columns) for r in read_csv(out)]:
            fail("the Dask cluster's rows differ from the plain run")
        if len(list((tmp / "dask-cache").glob("*/*.json"))) != 4:
            fail("the Dask run did not compute and cache all 4 points")
        bad = subprocess.run([sys.executable, str(SWEEP), str(SPEC), "-o", str(tmp / "x.csv"), "--tessim", tessim,
                              "--scheduler", "tcp://127.0.0.1:9"], capture_output=True, text=True)
        if bad.returncode != 2 or "--scheduler tcp://127.0.0.1:9" not in bad.stderr:
            fail(f"an unreachable scheduler is not a clear error: {bad.returncode} {bad.stderr}")
    print("sweep_smoke: OK")


if __name__ == "__main__":
    main()
