#!/usr/bin/env bash
# Regenerates the figures and tables of the load-balancing study (docs/results/load-balancing.md),
# from nothing on a fresh machine: installs the packages, builds tessim, sweeps, costs, plots.
#
#   scripts/results.sh            small sweep (scripts/sweeps/small.json, sphereWithHole.stl):
#                                 docs/results/*.png|svg, tables.md, results.csv
#   scripts/results.sh --full     full sweep (scripts/sweeps/full.json, Wuson.ply and more):
#                                 docs/results/full/
#   scripts/results.sh --adaptive adaptive D3D11 workloads on Wuson.ply (scripts/sweeps/adaptive.json):
#                                 docs/results/adaptive/ (no hardware cost needed)
#
# Options:
#   --jobs N            points simulated in parallel (default: the number of cores)
#   --build-dir DIR     where tessim is built when --tessim is not given (default build-results:
#                       a tessim-only build without the RTL models, tests or benchmarks)
#   --tessim PATH       use this tessim binary, build nothing
#   --out DIR           write the figures, tables and results there instead of docs/results[/full]
#   --resynth           synthesize every module record again (into DIR/costs-cache) instead of
#                       using the Yosys records kept in docs/results/costs/modules/
#   --recorded-costs    synthesize nothing: fail if a configuration has no recorded cost for the
#                       current RTL (the check the test suite runs)
#
# Steps: packages (scripts/setup.sh --deps); tessim; the sweep (resumable: its cache is
# DIR/results/<set>/cache, rerun to continue after an interruption); the hardware costs
# (scripts/costs.py: each configuration is composed from per-module Yosys records, looked up in
# docs/results/costs/modules/ by a hash of what Yosys reads for the module and synthesized when
# missing: an RTL edit costs the records of the modules it touches); the figures (scripts/plots.py).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)

set_name=small
jobs=$(nproc)
build=build-results
tessim=""
out=""
cost_cache="$root/docs/results/costs/modules"
cost_mode=()
while (($#)); do
  case "$1" in
    --full) set_name=full; shift ;;
    --adaptive) set_name=adaptive; shift ;;
    --jobs) jobs=${2:?--jobs needs a number}; shift 2 ;;
    --build-dir) build=${2:?--build-dir needs a directory}; shift 2 ;;
    --tessim) tessim=$(realpath "${2:?--tessim needs a path}"); shift 2 ;;
    --out) out=$(realpath -m "${2:?--out needs a directory}"); shift 2 ;;
    --resynth) cost_cache=""; shift ;;
    --recorded-costs) cost_mode=(--require-cached); shift ;;
    -h|--help) sed -n '2,27p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "results.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[[ $build = /* ]] || build="$root/$build"
[[ -n $cost_cache ]] || cost_cache="$build/costs-cache"

python=/usr/bin/python3   # Debian's interpreter: numpy and matplotlib come from apt
bash scripts/setup.sh --deps
if [[ -z $tessim ]]; then
  tessim="$build/bin/tessim"
  if [[ ! -f $build/CMakeCache.txt ]]; then
    cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DTESSIM_BUILD_RTL=OFF -DTESSIM_BUILD_TESTS=OFF \
      -DTESSIM_BUILD_BENCH=OFF ${TESSIM_CMAKE_ARGS:-}
  fi
  cmake --build "$build" -j"$jobs" --target tessim
fi
[[ -x $tessim ]] || { echo "results.sh: $tessim is not an executable" >&2; exit 2; }

if [[ $set_name == small ]]; then
  [[ -n $out ]] || out="$root/docs/results"
  # The Pareto figure needs the unit's cost at each N of the balance grid (default widths, Λ = 1,
  # V = 4); the small set keeps to the N that matter for the conclusions, and the CPG variants of
  # the cpg grid.
  cost_filter=(--where grid=balance int_blocks=1,2,3,4,6 --where grid=cpg
               --where grid=cpg_copies,cpg_copies_adaptive,cpg_budget,cpg_budget_adaptive)
elif [[ $set_name == full ]]; then
  [[ -n $out ]] || out="$root/docs/results/full"
  cost_filter=(--where grid=balance,costs int_blocks=1,2,3,4,5,6)
else
  [[ -n $out ]] || out="$root/docs/results/$set_name"
  cost_filter=()
fi
work="$build/results/$set_name"
mkdir -p "$work" "$out"

start=$SECONDS
"$python" scripts/sweep.py "scripts/sweeps/$set_name.json" -o "$work/results.csv" --cache "$work/cache" \
  --jobs "$jobs" --tessim "$tessim"
if ((${#cost_filter[@]})); then
  "$python" scripts/costs.py "$work/results.csv" --in-place --tessim "$tessim" --cache "$cost_cache" --jobs "$jobs" \
    "${cost_filter[@]}" \
    "${cost_mode[@]}"
fi
cp "$work/results.csv" "$out/results.csv"
"$python" scripts/plots.py "$out/results.csv" --out "$out" --tessim "$tessim"
if [[ $set_name == small ]]; then
  # Scalar tags against plain PN (load-balancing.md §12): meshes of their own, made by stpn-import.
  # and the Yosys cost of the CPG that takes them against the plain one.
  "$python" scripts/stpn_study.py --tessim "$tessim" --out "$out" --jobs "$jobs" --cost-cache "$cost_cache" \
    "${cost_mode[@]}" > "$out/stpn_table.md"
fi
echo "results.sh: $set_name set done in $((SECONDS - start)) s: $out" >&2
