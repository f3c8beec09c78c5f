#!/usr/bin/python3
"""Co-simulation of every CPG variant against every N: one RTL build per (edge lanes, digit bits,
INT blocks), verilated into a tree of its own, each run in lock-step against the cycle model in
every normal mode under random stalls, on random triangles (10 % degenerate), on saturating ones
and on a real mesh. The test suite co-simulates four of these builds (docs/verification.md); this
covers the whole matrix, which takes too long to build for every CI run.

    scripts/cpg_matrix.py [--build-dir build-cpg-matrix] [--lanes 1,3] [--digit-bits 1,2,4,8,24]
                          [--int 1,2,3,4] [--jobs N] [--seed S]

Prints one line per build and mode and a tally; exit status 0 only when every run agreed."""

import argparse
import concurrent.futures
import os
import re
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
WUSON = "/usr/share/assimp/models/PLY/Wuson.ply"
MODES = ["quadratic", "reflect", "linear"]
RAN = re.compile(r"ran (\d+) cycles, (\d+) triangles in, (\d+) vertices out")


def int_list(text):
    try:
        values = [int(x) for x in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a comma list of integers")
    if not values or min(values) < 1:
        raise argparse.ArgumentTypeError(f"'{text}': values must be >= 1")
    return values


def build_name(n, lanes, r):
    return f"m_n{n}_l{lanes}r{r}"


def configure_and_build(build_dir, builds, jobs):
    names = ";".join(name for name, _ in builds)
    extra = ";".join(f"{name}:" + ",".join(f"{k}={v}" for k, v in params) for name, params in builds)
    subprocess.run(["cmake", "-S", str(REPO), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
                    "-DTESSIM_BUILD_TESTS=OFF", "-DTESSIM_BUILD_BENCH=OFF", f"-DTESSIM_RTL_VARIANTS={names}",
                    f"-DTESSIM_RTL_EXTRA_VARIANTS={extra}"], check=True, stdout=subprocess.DEVNULL)
    subprocess.run(["cmake", "--build", str(build_dir), f"-j{jobs}", "--target", "tessim"], check=True,
                   stdout=subprocess.DEVNULL)


def stimuli(mode, seed):
    """The runs of one build in one mode: (what, tessim cosim arguments)."""
    return [
        ("random, stalls", ["--random", "40", "--random-max-L", "8", "--stall", "0.3", "--gpe-cycles", "2",
                            "--seed", str(seed), "--seeds", "2"]),
        ("random, K = 1", ["--random", "40", "--random-max-L", "4", "--gpe-cycles", "1", "--seed", str(seed + 1)]),
        ("saturating", ["--random", "60", "--random-max-L", "3", "--random-extent", "30", "--gpe-cycles", "1",
                        "--seed", str(seed + 2)]),
        ("Wuson L = 2, stalls", [WUSON, "-L", "2", "--stall", "0.2", "--gpe-cycles", "3", "--seed", str(seed + 3)]),
    ]


def run_build(tessim, name, n, lanes, r, seed):
    results = []
    hardware = ["--variant", name, "--int-blocks", str(n), "--cpg-lanes", str(lanes), "--cpg-digit-bits", str(r)]
    for mode in MODES:
        for what, args in stimuli(mode, seed):
            proc = subprocess.run([str(tessim), "cosim", "--normals", mode] + hardware + args,
                                  capture_output=True, text=True)
            vertices = sum(int(m.group(3)) for m in RAN.finditer(proc.stdout))
            ok = proc.returncode == 0 and "FAIL" not in proc.stdout
            results.append((mode, what, ok, vertices, "" if ok else proc.stdout[-2000:] + proc.stderr[-2000:]))
    return name, results


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build-dir", default=str(REPO / "build-cpg-matrix"))
    ap.add_argument("--lanes", type=int_list, default=[1, 3])
    ap.add_argument("--digit-bits", type=int_list, default=[1, 2, 4, 8, 24])
    ap.add_argument("--int", dest="int_blocks", type=int_list, default=[1, 2, 3, 4])
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args(argv)
    if any(l not in (1, 3) for l in args.lanes):
        ap.error("--lanes: the CPG has 1 or 3 edge lanes")

    matrix = [(n, lanes, r) for lanes in args.lanes for r in args.digit_bits for n in args.int_blocks]
    builds = [(build_name(n, lanes, r), [("IntBlocks", n), ("CpgLanes", lanes), ("CpgDigitBits", r)])
              for n, lanes, r in matrix]
    start = time.monotonic()
    print(f"cpg_matrix: verilating and building {len(builds)} RTL builds into {args.build_dir} ...", flush=True)
    configure_and_build(Path(args.build_dir), builds, args.jobs)
    print(f"cpg_matrix: built in {time.monotonic() - start:.0f} s", flush=True)
    tessim = Path(args.build_dir) / "bin" / "tessim"

    runs = failures = vertices = 0
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = [pool.submit(run_build, tessim, build_name(n, lanes, r), n, lanes, r, args.seed + i)
                   for i, (n, lanes, r) in enumerate(matrix)]
        for f in concurrent.futures.as_completed(futures):
            name, results = f.result()
            for mode, what, ok, v, output in results:
                runs += 1
                vertices += v
                if not ok:
                    failures += 1
                    print(f"  FAIL {name} {mode} {what}\n{output}", flush=True)
            print(f"{name:16s} {sum(ok for _, _, ok, _, _ in results)}/{len(results)} runs agree, "
                  f"{sum(v for _, _, _, v, _ in results):,} vertices", flush=True)
    print(f"cpg_matrix: {len(builds)} builds, {runs} runs, {vertices:,} vertices compared, {failures} failed, "
          f"{time.monotonic() - start:.0f} s")
    return 0 if failures == 0 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
