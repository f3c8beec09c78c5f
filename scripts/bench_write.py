#!/usr/bin/python3
"""Write bandwidth of the float reference against the machine's own bound.

Runs `tessim tessellate MESH -L L -o DIR/out.ply` several times, the same with `-o -` into
/dev/null (evaluation and packing alone), and `dd bs=1M` writing a file of the same size into
the same directory, interleaved so that a change of machine
load hits all three alike. Prints the median wall time and bandwidth of each and the ratio of
tessim's bandwidth to dd's. The output file is removed before each run, so every
run writes a fresh file, as dd does.

    /usr/bin/python3 scripts/bench_write.py build/bin/tessim [--mesh M] [-L 32] [--dir /dev/shm] [--runs 9]
"""
import argparse
import os
import resource
import statistics
import subprocess
import time

DEFAULT_MESH = "/usr/share/assimp/models/PLY/Wuson.ply"
BLOCK = 1 << 20


def timed(fn):
    """Wall seconds and CPU seconds (user + system) of the children fn starts."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    fn()
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime), (after.ru_stime - before.ru_stime)


def plain_write(path, size):
    """The machine's bound: dd writing 1 MiB blocks of zeros into a fresh file of (about) the size."""
    blocks = -(-size // BLOCK)
    subprocess.run(["dd", "if=/dev/zero", f"of={path}", f"bs={BLOCK}", f"count={blocks}", "status=none"], check=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("tessim")
    ap.add_argument("--mesh", default=DEFAULT_MESH)
    ap.add_argument("-L", type=int, default=32)
    ap.add_argument("--dir", default="/dev/shm", help="where the files are written (default: tmpfs)")
    ap.add_argument("--runs", type=int, default=9)
    args = ap.parse_args()

    out = os.path.join(args.dir, "bench_write_tessim.ply")
    ref = os.path.join(args.dir, "bench_write_dd.bin")
    tess = [args.tessim, "tessellate", args.mesh, "-L", str(args.L)]

    def run_file():
        if os.path.exists(out):
            os.remove(out)
        subprocess.run(tess + ["-o", out], check=True, stdout=subprocess.DEVNULL)

    def run_null():
        with open(os.devnull, "wb") as sink:
            subprocess.run(tess + ["-o", "-"], check=True, stdout=sink, stderr=subprocess.DEVNULL)

    run_file()  # warm the page cache with the mesh and the binary; learn the size
    size = os.path.getsize(out)

    def run_plain():
        if os.path.exists(ref):
            os.remove(ref)
        plain_write(ref, size)

    rows = {"tessim -o FILE": run_file, "tessim -o - (no I/O)": run_null, "dd bs=1M": run_plain}
    samples = {name: [] for name in rows}
    for _ in range(args.runs):
        for name, fn in rows.items():
            samples[name].append(timed(fn))
    for path in (out, ref):
        if os.path.exists(path):
            os.remove(path)

    med = {name: tuple(statistics.median(s[i] for s in runs) for i in range(3)) for name, runs in samples.items()}
    plain = med["dd bs=1M"][0]
    print(f"{args.mesh}, L = {args.L}: {size / 1e6:.1f} MB of binary PLY into {args.dir}, median of {args.runs} runs")
    print(f"{'':24s} {'wall s':>8s} {'user s':>8s} {'sys s':>8s} {'GB/s':>7s}")
    for name in ("tessim -o FILE", "tessim -o - (no I/O)", "dd bs=1M"):
        wall, user, sys_ = med[name]
        print(f"{name:24s} {wall:8.4f} {user:8.4f} {sys_:8.4f} {size / wall / 1e9:7.2f}")
    print(f"tessim writes at {plain / med['tessim -o FILE'][0]:.2f}x dd's bandwidth")


if __name__ == "__main__":
    main()
