#!/usr/bin/env bash
# gcov line coverage of the C++ (model/, sim/, render/, app/) from the test suite
# (docs/verification.md, Coverage): a Debug build with --coverage and without the RTL
# (build-coverage/, CMake preset "coverage"), its ctest suite, then lines executed per layer.
#   bash scripts/cpp_coverage.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset coverage >/dev/null
cmake --build --preset coverage >/dev/null
find build-coverage -name '*.gcda' -delete
ctest --test-dir build-coverage -j2 -E 'results_small|check_packages|fuzz_short' >/dev/null || true
/usr/bin/python3 - "$PWD" <<'PY'
import collections, os, re, subprocess, sys
root = sys.argv[1]
lines = {}  # source -> (executed, total), the best record over all objects that include it
for d, _, files in os.walk(os.path.join(root, "build-coverage")):
    for f in files:
        if not f.endswith(".gcda"):
            continue
        out = subprocess.run(["gcov", "-n", "-o", d, os.path.join(d, f)], capture_output=True, text=True,
                             cwd=root).stdout
        for m in re.finditer(r"File '([^']+)'\nLines executed:([\d.]+)% of (\d+)", out):
            src, pct, total = os.path.realpath(os.path.join(root, m.group(1))), float(m.group(2)), int(m.group(3))
            if not src.startswith(root + "/") or "/build" in src[len(root):] or "/tests/" in src:
                continue
            done = round(pct * total / 100)
            if src not in lines or done > lines[src][0]:
                lines[src] = (done, total)
layers = collections.defaultdict(lambda: [0, 0])
for src, (done, total) in lines.items():
    layer = os.path.relpath(src, root).split("/")[0]
    for key in (layer, "all"):
        layers[key][0] += done
        layers[key][1] += total
for layer in sorted(layers, key=lambda k: (k == "all", k)):
    done, total = layers[layer]
    print("%-8s %6d of %6d lines  %5.1f%%" % (layer, done, total, 100.0 * done / total))
PY
