#!/usr/bin/env bash
# Verilator code coverage of the RTL (docs/verification.md, Coverage): builds tessim with the RTL
# builds n1 and n3_lat3 verilated with --coverage (build-rtlcov/), runs a co-simulation campaign
# (every normal mode, N = 1 and 3 with INT latency 3, backpressure, saturation, resets, a real
# mesh), merges the counts and prints line / branch / toggle coverage per module. Annotated
# sources are left in build-rtlcov/rtlcov/annotated/.
#   bash scripts/rtl_coverage.sh
set -euo pipefail
cd "$(dirname "$0")/.."
bld=build-rtlcov
cmake -S . -B "$bld" -DCMAKE_BUILD_TYPE=Release -DTESSIM_BUILD_TESTS=OFF -DTESSIM_BUILD_BENCH=OFF \
  "-DTESSIM_RTL_VARIANTS=n1;n3_lat3" -DTESSIM_RTL_COVERAGE=ON >/dev/null
cmake --build "$bld" -j2 --target tessim >/dev/null
out="$bld/rtlcov"
rm -rf "$out"
mkdir -p "$out"
export TESSIM_RTL_COVERAGE_FILE="$PWD/$out/unit.dat"
tessim="$bld/bin/tessim"
# --variant NAME and the build's hardware flags, from `tessim schema` (rtl/builds.json)
args=$(/usr/bin/python3 scripts/rtl_builds.py --tessim "$tessim" args n3_lat3)
read -ra n3 <<< "$args"
args=$(/usr/bin/python3 scripts/rtl_builds.py --tessim "$tessim" args n1)
read -ra n1 <<< "$args"
resets=$(seq -s, 97 1013 20000)
run() { "$tessim" cosim "$@" >/dev/null || { echo "rtl_coverage: FAIL: tessim cosim $*" >&2; exit 1; }; }
for mode in quadratic reflect linear; do
  run --random 300 --random-max-L 64 --normals "$mode" "${n3[@]}" --gpe-cycles 2 --stall 0.2 --seed 21
  run --random 200 --random-max-L 16 --normals "$mode" "${n1[@]}" --gpe-cycles 1 --seed 22 --reset-at "$resets"
  run --random 150 --random-max-L 8 --normals "$mode" "${n3[@]}" --gpe-cycles 12 --seed 23 --reset-at "$resets"
  run --random 120 --random-max-L 6 --random-extent 30 --normals "$mode" "${n3[@]}" --gpe-cycles 1 --seed 24
  run --random 120 --random-max-L 6 --random-extent 30 --normals "$mode" "${n1[@]}" --gpe-cycles 1 --seed 25
  run /usr/share/assimp/models/PLY/Wuson.ply -L 2 --normals "$mode" "${n3[@]}" --gpe-cycles 20
done
verilator_coverage --write "$out/merged.dat" "$out"/unit.dat.* >/dev/null
verilator_coverage --annotate "$out/annotated" "$out/merged.dat" >/dev/null
/usr/bin/python3 - "$out/merged.dat" <<'PY'
import collections, re, sys
# A point per line: C '<key \x02 value, separated by \x01>' count; 'page' is v_<type>/<module>.
hit = collections.defaultdict(lambda: [0, 0])
for line in open(sys.argv[1], encoding="latin-1"):
    m = re.match(r"C '(.*)' (\d+)$", line.rstrip("\n"))
    if not m:
        continue
    fields = dict(kv.split("\x02", 1) for kv in m.group(1).split("\x01") if "\x02" in kv)
    kind, _, module = fields.get("page", "v_?/?").partition("/")
    kind = kind[2:]
    for key in ((kind, module), (kind, "all")):
        hit[key][1] += 1
        hit[key][0] += int(m.group(2)) > 0
kinds = sorted({k for k, _ in hit})
modules = sorted({mod for _, mod in hit if mod != "all"}) + ["all"]
print("%-12s" % "module" + "".join("%20s" % k for k in kinds))
for mod in modules:
    cells = []
    for k in kinds:
        c, t = hit.get((k, mod), (0, 0))
        cells.append("%20s" % ("%d/%d %5.1f%%" % (c, t, 100.0 * c / t) if t else "-"))
    print("%-12s" % mod + "".join(cells))
PY
