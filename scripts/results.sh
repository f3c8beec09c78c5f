#!/usr/bin/env bash
# Regenerates the figures and tables of the load-balancing study (docs/results/load-balancing.md).
#
#   scripts/results.sh            small sweep (scripts/sweeps/small.json, sphereWithHole.stl):
#                                 docs/results/*.png|svg, tables.md, results.csv — a few minutes
#   scripts/results.sh --full     full sweep (scripts/sweeps/full.json, Wuson.ply and more):
#                                 docs/results/full/ — see load-balancing.md for the time it takes
#
# Options: --jobs N (parallel points, default: cores), --build-dir DIR (default build; tessim is
# configured and built there when missing), --resynth (ignore the committed Yosys results in
# docs/results/costs/ and synthesize again into DIR/costs-cache).
#
# Steps: build tessim; run the sweep (resumable: its cache is DIR/results/<set>/cache, rerun to
# continue after an interruption); join the hardware costs (scripts/costs.py: Yosys results are
# looked up in docs/results/costs/ by a hash of the RTL sources, synth.sh and the Yosys version,
# and synthesized when missing — minutes per configuration); draw the figures (scripts/plots.py).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)

set_name=small
jobs=$(nproc)
build=build
cost_cache="$root/docs/results/costs"
while (($#)); do
  case "$1" in
    --full) set_name=full; shift ;;
    --jobs) jobs=${2:?--jobs needs a number}; shift 2 ;;
    --build-dir) build=${2:?--build-dir needs a directory}; shift 2 ;;
    --resynth) cost_cache=""; shift ;;
    -h|--help) sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "results.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[[ -n $cost_cache ]] || cost_cache="$root/$build/costs-cache"

python=/usr/bin/python3   # Debian's interpreter: numpy and matplotlib come from apt
tessim="$root/$build/bin/tessim"
if [[ ! -x $tessim ]]; then
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release ${TESSIM_CMAKE_ARGS:-}
fi
cmake --build "$build" -j"$jobs" --target tessim

if [[ $set_name == small ]]; then
  out="$root/docs/results"
  # The Pareto figure needs the unit's cost at each N of the balance grid (default widths, Λ = 1,
  # V = 4); the small set keeps to the N that matter for the conclusions.
  cost_filter=(grid=balance int_blocks=1,2,3,4,6)
else
  out="$root/docs/results/full"
  cost_filter=(grid=balance,costs int_blocks=1,2,3,4,5,6)
fi
work="$root/$build/results/$set_name"
mkdir -p "$work" "$out"

start=$SECONDS
"$python" scripts/sweep.py "scripts/sweeps/$set_name.json" -o "$work/results.csv" --cache "$work/cache" \
  --jobs "$jobs" --tessim "$tessim"
"$python" scripts/costs.py "$work/results.csv" --cache "$cost_cache" --where "${cost_filter[@]}"
cp "$work/results.csv" "$out/results.csv"
"$python" scripts/plots.py "$out/results.csv" --out "$out" --tessim "$tessim"
echo "results.sh: $set_name set done in $((SECONDS - start)) s: $out" >&2
