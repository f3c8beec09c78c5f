#!/usr/bin/python3
"""Soak test of the lock-step co-simulation: many seeds, every fault-free RTL build (N = 1..4 with
the sequential CPG, the CPG variants, other FIFO depths and widths), every normal mode the unit implements, factors 1..16, random and constant geometry-engine stalls, real meshes
(uniform and adaptive factors) and random triangle streams (with degenerate ones; half of them with
D3D11 patterns and resets at random cycles), on every core.
Prints each job as it ends and the totals: vertices, cycles, seeds, wall time, mismatches.

    scripts/soak.py [--tessim build/bin/tessim] [--vertices 10000000] [--jobs N] [--seed S]

Exit status 0 only when every run agreed (docs/verification.md, Soak)."""

import argparse
import concurrent.futures
import os
import random
import re
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import rtl_builds  # noqa: E402
import sweep  # noqa: E402

REPO = Path(__file__).resolve().parent.parent
MODELS = Path("/usr/share/assimp/models")
MESHES = [MODELS / "PLY/Wuson.ply", MODELS / "STL/sphereWithHole.stl", MODELS / "OBJ/spider.obj"]
MODES = ["quadratic", "reflect", "linear"]
RAN = re.compile(r"ran (\d+) cycles, (\d+) triangles in, (\d+) vertices out")


def soak_builds(tessim):
    """The fault-free fast builds of `tessim schema` (rtl/builds.json), each with the hardware
    flags that select it: the verification build (same hardware as n2) and the fault-injected
    ones are left out."""
    return [(b["name"], b["flags"]) for b in rtl_builds.builds(tessim) if not b["verif"] and b["inject_bug"] == 0]


def job_args(rng, index, builds):
    """One co-simulation job: a stream, a configuration and a run of consecutive seeds."""
    build, hardware = builds[index % len(builds)]  # every build equally often
    args = ["cosim", "--variant", build] + hardware + ["--normals", rng.choice(MODES),
            "--gpe-cycles", str(rng.choice([1, 2, 4, 7, 8, 12])),
            "--gpe-stall-prob", str(rng.choice([0.0, 0.0, 0.1, 0.3, 0.6])),
            "--seed", str(rng.randrange(1, 2**31)), "--seeds", "4"]
    kind = index % 3
    if kind == 0:
        args += ["--random", str(rng.choice([200, 500, 1000])), "--random-max-L", "16"]
        what = "random triangles"
        if rng.random() < 0.5:  # D3D11 patterns, with resets at random cycles (inside them too)
            args += ["--partitioning", "mixed", "--random-resets", str(rng.choice([3, 6, 9]))]
            what = "random D3D11 triangles, resets"
    elif kind == 1:
        mesh = rng.choice(MESHES)
        args += [str(mesh), "-L", str(rng.randint(1, 16))]
        what = mesh.name
    else:
        mesh = MESHES[0]
        eye = rng.uniform(2.0, 12.0)
        args += [str(mesh), "--adaptive", "screen", "--camera", f"eye={eye:.3f},1.2,-{eye:.3f},target=0,0.6,-0.2",
                 "--pixels-per-segment", str(rng.choice([6, 10, 16]))]
        what = f"{mesh.name} adaptive"
    return args, what


def run(tessim, args):
    start = time.monotonic()
    proc = subprocess.run([str(tessim)] + args, capture_output=True, text=True)
    runs = [tuple(int(x) for x in m.groups()) for m in RAN.finditer(proc.stdout)]
    passes = proc.stdout.count("\nPASS: ")
    fails = proc.stdout.count("\nFAIL: ") + (0 if proc.returncode in (0, 1) else 1)
    return {"status": proc.returncode, "runs": runs, "passes": passes, "fails": fails,
            "seconds": time.monotonic() - start, "output": proc.stdout + proc.stderr}


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tessim", default=str(REPO / "build" / "bin" / "tessim"))
    ap.add_argument("--vertices", type=float, default=1e7, help="stop once this many vertices agreed")
    ap.add_argument("--min-seeds", type=int, default=100, help="and at least this many seeds ran")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--seed", type=int, default=1, help="seeds the choice of jobs")
    args = ap.parse_args(argv)
    try:
        soak = soak_builds(args.tessim)
    except sweep.SpecError as e:
        raise SystemExit(f"soak: {e}")
    rng = random.Random(args.seed)
    start = time.monotonic()
    totals = {"vertices": 0, "cycles": 0, "seeds": 0, "mismatches": 0, "jobs": 0}
    builds = set()
    index = 0
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        pending = {}

        def submit():
            nonlocal index
            job, what = job_args(rng, index, soak)
            index += 1
            pending[pool.submit(run, args.tessim, job)] = (job, what)

        for _ in range(args.jobs):
            submit()
        while pending:
            done, _ = concurrent.futures.wait(pending, return_when=concurrent.futures.FIRST_COMPLETED)
            for f in done:
                job, what = pending.pop(f)
                r = f.result()
                totals["jobs"] += 1
                totals["seeds"] += r["passes"] + r["fails"]
                totals["mismatches"] += r["fails"]
                totals["cycles"] += sum(c for c, _, _ in r["runs"])
                totals["vertices"] += sum(v for _, _, v in r["runs"])
                build = job[job.index("--variant") + 1]
                builds.add(build)
                print(f"[{time.monotonic() - start:7.1f}s] {build:8s} "
                      f"{job[job.index('--normals') + 1]:9s} {what:28s} {r['passes']} pass {r['fails']} fail "
                      f"({r['seconds']:.1f}s)  total {totals['vertices']:,} vertices", flush=True)
                if r["fails"]:
                    print("  " + " ".join(job) + "\n" + r["output"], flush=True)
                enough = totals["vertices"] >= args.vertices and totals["seeds"] >= args.min_seeds
                if not enough:
                    submit()
    wall = time.monotonic() - start
    print(f"soak: {totals['vertices']:,} vertices, {totals['cycles']:,} cycles, {totals['seeds']} seeds in "
          f"{totals['jobs']} jobs (builds {', '.join(sorted(builds))}), {wall:.0f} s wall on {args.jobs} workers, "
          f"{totals['mismatches']} mismatches")
    return 0 if totals["mismatches"] == 0 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
