#!/usr/bin/python3
"""Mutation campaign: proves that the lock-step co-simulation catches real bugs.

Each mutant of scripts/mutants/mutants.json is one plausible single-point bug in the RTL (or in
the cycle model). The script applies it to a private copy of the repository (rtl/ itself is never
touched, so the recorded Yosys costs stay valid), rebuilds `tessim` there with the RTL builds the
stimulus needs, and runs the stimulus until one run fails. It prints a table: mutant, caught by
(outputs / counters / hang / reference), the stimulus that caught it, the first divergent cycle
and the seconds spent. It fails if a mutant not declared equivalent survives, if a declared
equivalent one is caught (its argument is wrong), or if the unmutated copy fails any stimulus.

    /usr/bin/python3 scripts/mutants.py [--work DIR] [--only ID,ID] [--markdown OUT.md] [--all-stimuli] [--keep-copy]

The work directory (default build/mutants) keeps the copy and its build between runs; a mutant
then costs one Verilator run of the changed model and the stimulus (about 1-3 minutes).
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import rtl_builds  # noqa: E402
import sweep  # noqa: E402
import yosys_cost  # noqa: E402  (tess_pkg's defaults)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# The campaign's builds: together they have every class of parameter value of the shipped builds
# (rtl_builds.uncovered_classes; tests/scripts/mutant_classes_test.py), so that a bug visible only
# at, say, three CPG copies is reachable.
RTL_BUILDS = ["n1", "n3_lat3", "n2_w28b20", "n1_w20b18", "n1_r4", "n4_l3r24"]
# Test binaries built beside tessim for the stimuli that drive the unit below the host (raw and
# directed D3D11 factors, searched rounding ties).
TEST_TARGETS = ["fsu_cosim_test", "silhouette_cosim_test", "ties_cosim_test"]
WUSON = "/usr/share/assimp/models/PLY/Wuson.ply"


def cosim(name, build, *args):
    return {"name": name, "build": build, "args": list(args)}


def test(name, binary, test_filter, builds):
    return {"name": name, "test": binary, "filter": test_filter, "builds": builds}


def stimulus():
    """The stimulus, in order; a mutant is run until the first failure. Together: every normal
    mode, N = 1 to 4, INT latency 3, no / constant / random backpressure, degenerate triangles, a
    real mesh, saturation, and every class of parameter value of the shipped builds. Each `tessim
    cosim` stimulus names its build; its flags come from `tessim schema` (rtl/builds.json)."""
    N3, N1 = "n3_lat3", "n1"
    # The builds with the free parameters away from their defaults: FIFO depths 3 and 5, W = 28
    # and 20, B = 20 and 18.
    W28, W20 = "n2_w28b20", "n1_w20b18"
    # Three CPG copies on one radix-16 lane (1-bit alpha), five on three whole-quotient lanes with N = 4
    # (16-bit alpha): rings of copies that do not wrap by themselves.
    R4, L3R24 = "n1_r4", "n4_l3r24"
    alpha_builds = [N3, W28, W20, R4, L3R24]
    return [
        cosim("random quadratic N=3 K=1", N3, "--random", "60", "--random-max-L", "6", "--gpe-cycles", "1"),
        cosim("random linear N=3 stall", N3, "--random", "60", "--random-max-L", "6", "--normals", "linear",
              "--stall", "0.3", "--gpe-cycles", "2"),
        cosim("random reflect N=3 K=8", N3, "--random", "40", "--random-max-L", "5", "--normals", "reflect"),
        cosim("saturating quadratic N=3", N3, "--random", "120", "--random-max-L", "3", "--random-extent", "30",
              "--gpe-cycles", "1"),
        cosim("saturating reflect N=1", N1, "--random", "120", "--random-max-L", "3", "--random-extent", "30",
              "--normals", "reflect", "--gpe-cycles", "1"),
        cosim("Wuson L=3 quadratic N=3", N3, WUSON, "-L", "3"),
        # n3_lat3 takes scalar tags: with cpg_tags 1 the random triangles carry random tags.
        cosim("random tagged N=3 stall", N3, "--random", "40", "--random-max-L", "4", "--stall", "0.3",
              "--gpe-cycles", "2"),
        cosim("random tagged reflect N=3", N3, "--random", "30", "--random-max-L", "3", "--normals", "reflect",
              "--gpe-cycles", "1"),
        cosim("random linear N=1 K=1", N1, "--random", "40", "--random-max-L", "6", "--normals", "linear",
              "--gpe-cycles", "1"),
        # The D3D11 pattern: random factors, a partitioning drawn per triangle, and one partitioning on N = 1.
        cosim("random D3D11 mixed N=3 stall", N3, "--random", "40", "--random-max-L", "10", "--partitioning", "mixed",
              "--stall", "0.3", "--gpe-cycles", "2"),
        cosim("random D3D11 fractional_odd N=1", N1, "--random", "40", "--random-max-L", "12", "--partitioning",
              "fractional_odd", "--gpe-cycles", "1"),
        # Resets at random cycles, aimed in turn at any cycle, the inner rings of a D3D11 patch (large
        # factors) and the CPG mid-triangle.
        cosim("random resets D3D11 mixed N=3 stall", N3, "--random", "16", "--random-max-L", "40", "--partitioning",
              "mixed", "--random-resets", "9", "--stall", "0.2", "--gpe-cycles", "2"),
        # The free parameters away from their defaults, fast and slow GE (K = 16 is slower than either TE:
        # the VTX FIFO fills), uniform and D3D11 patterns, saturation.
        cosim("W=28 B=20 D3D11 mixed N=2 K=1", W28, "--random", "30", "--random-max-L", "10", "--partitioning",
              "mixed", "--gpe-cycles", "1"),
        cosim("W=20 B=18 random quadratic N=1 K=1", W20, "--random", "30", "--random-max-L", "6", "--gpe-cycles", "1"),
        cosim("W=28 B=20 random linear N=2 slow GE", W28, "--random", "30", "--random-max-L", "6", "--normals",
              "linear", "--gpe-cycles", "16"),
        cosim("W=20 B=18 random linear N=1 slow GE", W20, "--random", "30", "--random-max-L", "6", "--normals",
              "linear", "--gpe-cycles", "16"),
        cosim("W=20 B=18 saturating reflect N=1", W20, "--random", "60", "--random-max-L", "3", "--random-extent",
              "30", "--normals", "reflect", "--gpe-cycles", "1"),
        # Raw D3D11 factors, every value the interface admits (tests/cosim/fsu_cosim_test.cpp, on n3_lat3).
        test("FSU raw factors N=3 (fsu_cosim_test)", "fsu_cosim_test", "FsuRawFactors.*", [N3]),
        # Streams searched for the rare triangles whose output the rounding of alpha w decides
        # (tests/cosim/silhouette_cosim_test.cpp), on every build of the copy that takes alpha.
        test("alpha rounding ties (silhouette_cosim_test)", "silhouette_cosim_test",
             "CosimSilhouette.RoundingTies*", alpha_builds),
        # Small patches on the CPG-bound builds of several copies: the rings of 3 and 5 copies wrap
        # many times; tags and alpha on both, D3D11 on the five-copy one.
        cosim("random tagged quadratic N=1 Mc=3 K=1", R4, "--random", "80", "--random-max-L", "3", "--gpe-cycles", "1"),
        cosim("random D3D11 mixed N=4 Mc=5 stall", L3R24, "--random", "60", "--random-max-L", "4", "--partitioning",
              "mixed", "--stall", "0.2", "--gpe-cycles", "1"),
        cosim("random reflect N=4 Mc=5 K=1", L3R24, "--random", "80", "--random-max-L", "2", "--normals", "reflect",
              "--gpe-cycles", "1"),
        # The D3D11 pattern's structural corners, enumerated (tests/cosim/fsu_cosim_test.cpp
        # D3d11Corners): outer factors 1 with inner factors 2..8, factors next to every integer at the
        # ring transitions, every partitioning, on every build of the copy.
        test("D3D11 corners (fsu_cosim_test)", "fsu_cosim_test", "D3d11Corners.*", RTL_BUILDS),
        # Exact ties of every rounding the unit makes, searched (tests/cosim/ties_cosim_test.cpp).
        test("exact rounding ties (ties_cosim_test)", "ties_cosim_test", "ExactTies*", RTL_BUILDS),
    ]


def reached_builds(stimuli):
    """The builds the stimuli run on, in RTL_BUILDS order."""
    names = set()
    for s in stimuli:
        names.update(s["builds"] if "test" in s else [s["build"]])
    return [b for b in RTL_BUILDS if b in names] + sorted(names - set(RTL_BUILDS))


def uncovered(stimuli):
    """[(parameter, class, shipped build)] the stimuli do not reach (rtl_builds.uncovered_classes)."""
    shipped = json.load(open(os.path.join(ROOT, "rtl", "builds.json")))["builds"]
    by_name = {b["name"]: b for b in shipped}
    reached = [by_name[n] for n in reached_builds(stimuli)]
    return rtl_builds.uncovered_classes(shipped, reached, yosys_cost.package_defaults(os.path.join(ROOT, "rtl")))


def command(stim, tessim):
    if "test" in stim:  # a test binary of the same build
        return [os.path.join(os.path.dirname(tessim), stim["test"]), "--gtest_filter=" + stim["filter"]]
    return [tessim, "cosim"] + stim["args"] + rtl_builds.cosim_args(tessim, stim["build"])


def run(cmd, **kw):
    return subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, **kw)


def copy_tree(dst):
    """Brings the copy up to the working tree's tracked files, deleting files that are no longer
    tracked (a stale source would still be globbed into the build)."""
    files = run(["git", "ls-files"], cwd=ROOT).stdout.split()
    tracked = set(files)
    for base, _, names in os.walk(dst):
        for n in names:
            rel = os.path.relpath(os.path.join(base, n), dst)
            if rel not in tracked:
                os.remove(os.path.join(base, n))
    for f in files:
        src = os.path.join(ROOT, f)
        out = os.path.join(dst, f)
        if not os.path.isfile(src):
            continue
        os.makedirs(os.path.dirname(out), exist_ok=True)
        if not os.path.exists(out) or open(src, "rb").read() != open(out, "rb").read():
            shutil.copy2(src, out)


def build(src, bld, log):
    if not os.path.exists(os.path.join(bld, "CMakeCache.txt")):
        args = ["cmake", "-S", src, "-B", bld, "-DCMAKE_BUILD_TYPE=Release", "-DTESSIM_BUILD_TESTS=ON",
                "-DTESSIM_BUILD_BENCH=OFF", "-DTESSIM_RTL_VARIANTS=" + ";".join(RTL_BUILDS),
                # Not driven by the stimuli: the system of units' models would be rebuilt per mutant.
                "-DTESSIM_BUILD_SYSTEM_RTL=OFF", "-DTESSIM_BUILD_PYTHON=OFF"]
        if shutil.which("ccache"):
            args.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
        r = run(args)
        log.write(r.stdout)
        if r.returncode:
            return False
    r = run(["cmake", "--build", bld, "-j2", "--target", "tessim"] + TEST_TARGETS)
    log.write(r.stdout)
    return r.returncode == 0


def classify(output):
    """caught-by and first divergent cycle of a failing `tessim cosim` report."""
    m = re.search(r"first divergence at cycle (\d+) in (\S+)", output)
    if m:
        field = m.group(2)
        if field == "progress":
            return "hang", int(m.group(1))
        if field.startswith("counters") or field.startswith("perf"):
            return "counters", int(m.group(1))
        return "outputs (" + field + ")", int(m.group(1))
    if "counters: DIFFER" in output:
        return "counters (end of run)", None
    if "beyond bound" in output:
        return "reference", None
    if "Assertion" in output or "%Error" in output:
        return "assertion", None
    return "run failed", None


def apply(src, mutant):
    path = os.path.join(src, mutant["file"])
    text = open(path).read()
    for edit in [{"find": mutant["find"], "replace": mutant["replace"]}] + mutant.get("also", []):
        count = text.count(edit["find"])
        if count != 1:
            raise SystemExit("mutants: %s: expected the text once in %s, found it %d times: %s"
                             % (mutant["id"], mutant["file"], count, edit["find"]))
        text = text.replace(edit["find"], edit["replace"])
    with open(path, "w") as f:
        f.write(text)


def restore(src, mutant):
    shutil.copy2(os.path.join(ROOT, mutant["file"]), os.path.join(src, mutant["file"]))
    os.utime(os.path.join(src, mutant["file"]))  # newer than the mutant's build: rebuild


def stimulate(tessim, stimuli, log, stop_at_first=True):
    """Runs the stimuli; returns [(index, output)] of the failures (only the first one when
    stop_at_first), empty when every stimulus passes."""
    failures = []
    for i, stim in enumerate(stimuli):
        cmd = command(stim, tessim)
        r = run(cmd, timeout=1800)
        log.write("$ %s\n%s\n" % (" ".join(cmd), r.stdout))
        if r.returncode != 0:
            failures.append((i, r.stdout))
            if stop_at_first:
                break
    return failures


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--work", default=os.path.join(ROOT, "build", "mutants"), help="work directory")
    ap.add_argument("--only", default="", help="comma-separated mutant ids")
    ap.add_argument("--markdown", default="", help="also write the table as Markdown to this file")
    ap.add_argument("--keep-copy", action="store_true",
                    help="use the copy in the work directory as it stands (do not refresh it from the working tree)")
    ap.add_argument("--all-stimuli", action="store_true",
                    help="run every stimulus on each mutant and list all that catch it (default: stop at the first)")
    args = ap.parse_args()

    stimuli = stimulus()
    missing = uncovered(stimuli)
    if missing:
        raise SystemExit("mutants: the stimulus reaches no build with " + "; ".join(
            "%s %s (as %s has)" % m for m in missing))
    table = json.load(open(os.path.join(ROOT, "scripts", "mutants", "mutants.json")))["mutants"]
    if args.only:
        wanted = set(args.only.split(","))
        unknown = wanted - {m["id"] for m in table}
        if unknown:
            raise SystemExit("mutants: unknown mutant(s): " + ", ".join(sorted(unknown)))
        table = [m for m in table if m["id"] in wanted]
    src, bld = os.path.join(args.work, "src"), os.path.join(args.work, "build")
    os.makedirs(src, exist_ok=True)
    log = open(os.path.join(args.work, "mutants.log"), "w")
    if not args.keep_copy:
        copy_tree(src)
    tessim = os.path.join(bld, "bin", "tessim")

    t0 = time.time()
    if not build(src, bld, log):
        raise SystemExit("mutants: the unmutated copy does not build (see %s)" % log.name)
    stimuli = stimulus()
    try:
        for s in stimuli:
            if "build" in s:
                rtl_builds.cosim_args(tessim, s["build"])
    except sweep.SpecError as e:
        raise SystemExit("mutants: %s" % e)
    failed = stimulate(tessim, stimuli, log)
    if failed:
        raise SystemExit("mutants: the unmutated copy fails '%s' (see %s)" % (stimuli[failed[0][0]]["name"], log.name))
    print("unmutated: builds and passes all %d stimuli (%.0f s)" % (len(stimuli), time.time() - t0), flush=True)

    rows, problems = [], []
    for m in table:
        t = time.time()
        apply(src, m)
        try:
            if not build(src, bld, log):
                caught, stim, cycle = "build failed", "-", None
            else:
                failures = stimulate(tessim, stimuli, log, stop_at_first=not args.all_stimuli)
                if not failures:
                    caught, stim, cycle = "SURVIVED", "-", None
                else:
                    caught, cycle = classify(failures[0][1])
                    stim = stimuli[failures[0][0]]["name"]
                    if args.all_stimuli:  # every stimulus that catches it, with its first divergent cycle
                        stim = "; ".join("%s (%s)" % (stimuli[i]["name"], classify(out)[1]) for i, out in failures)
        finally:
            restore(src, m)
        seconds = time.time() - t
        equivalent = m.get("equivalent")
        if caught == "SURVIVED" and not equivalent:
            problems.append("%s survived" % m["id"])
        if caught == "build failed":  # not a bug the verification found: the mutant must be fixed
            problems.append("%s does not build (see %s)" % (m["id"], log.name))
        if caught != "SURVIVED" and equivalent:
            problems.append("%s is declared equivalent but was caught (%s)" % (m["id"], caught))
        verdict = "equivalent (argued)" if equivalent and caught == "SURVIVED" else caught
        rows.append((m["id"], m["block"], m["what"], verdict, stim, "-" if cycle is None else str(cycle),
                     "%.0f" % seconds))
        print("%-22s %-26s %-28s %-8s %5s s" % (m["id"], verdict[:26], stim[:28], rows[-1][5], rows[-1][6]),
              flush=True)

    header = ("mutant", "block", "bug", "caught by", "stimulus", "first divergent cycle", "seconds")
    md = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    md += ["| " + " | ".join(r) + " |" for r in rows]
    caught = sum(1 for r in rows if r[3] not in ("SURVIVED", "equivalent (argued)", "build failed"))
    summary = "%d mutants: %d caught, %d argued equivalent, %d survived; %.0f s" % (
        len(rows), caught, sum(1 for r in rows if r[3] == "equivalent (argued)"),
        sum(1 for r in rows if r[3] == "SURVIVED"), time.time() - t0)
    print("\n" + "\n".join(md) + "\n\n" + summary)
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write("\n".join(md) + "\n\n" + summary + "\n")
    if problems:
        print("mutants: FAIL: " + "; ".join(problems), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
