#!/usr/bin/env bash
# Functional coverage campaign of the co-simulation (docs/verification.md, Coverage): runs a set
# of `tessim cosim` streams chosen to close the coverage bins, accumulating into one file, and
# prints which bins were reached.
#   bash scripts/coverage.sh [OUT.json]      (default build/coverage.json; TESSIM=path/to/tessim)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-build/coverage.json}
tessim=${TESSIM:-build/bin/tessim}
rm -f "$out"
# --variant n3_lat3 and its hardware flags, from `tessim schema` (rtl/builds.json)
args=$(/usr/bin/python3 scripts/rtl_builds.py --tessim "$tessim" args n3_lat3)
read -ra n3 <<< "$args"
resets=$(seq -s, 97 1013 40000)  # resets spread over the run: the CPG is caught in each state
run() { "$tessim" cosim --coverage "$out" "$@" > /dev/null || { echo "coverage: FAIL: tessim cosim $*" >&2; exit 1; }; }
for mode in quadratic reflect linear; do
  for n in 1 2 3 4; do
    run --random 400 --random-max-L 64 --normals "$mode" --int "$n" --gpe-cycles 1 --seed 11
    run --random 200 --random-max-L 16 --normals "$mode" --int "$n" --gpe-cycles 8 --stall 0.3 --seed 12 --reset-at "$resets"
  done
  run --random 300 --random-max-L 64 --normals "$mode" "${n3[@]}" --gpe-cycles 2 --stall 0.2 --seed 13
  run --random 120 --random-max-L 8 --random-extent 30 --normals "$mode" --gpe-cycles 1 --seed 14
  run /usr/share/assimp/models/PLY/Wuson.ply -L 2 --normals "$mode" --gpe-cycles 20
done
# A reset in the CPG's one-cycle states, at the cycles they occur in a fresh quadratic stream
# (C = 245): idle (cycle 0, nothing in the TRI FIFO yet), accept (cycle 1), write (cycle 246).
for at in 1 2 247; do run --random 3 --random-max-L 2 --gpe-cycles 1 --reset-at "$at"; done
"$tessim" cosim --coverage "$out" --random 1 --random-max-L 1 | sed -n '/^functional coverage/,$p'
