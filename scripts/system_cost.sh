#!/usr/bin/env bash
# Cost of one block of the system of units (rtl/system.f: tess_distributor, tess_reassembly,
# tess_patch_count, tess_system) on its own, by the generic flow of scripts/block_cost.sh
# (`synth -flatten`, flip-flops legalised, `stat -tech cmos`, `ltp -noff`): cells, flip-flops,
# transistors, logic depth. Reads rtl/tess.f (the package and the unit) and then rtl/system.f.
#
# Usage: scripts/system_cost.sh MODULE [RTL_DIR] [-chparam NAME VALUE ...]
#   RTL_DIR   where tess.f, system.f and the sources they list are (default: rtl/)
set -euo pipefail
module=${1:?usage: system_cost.sh MODULE [RTL_DIR] [-chparam NAME VALUE ...]}
shift
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
rtl="$root/rtl"
if (($#)) && [[ $1 != -chparam ]]; then rtl=$1; shift; fi
chparam=""
while (($#)); do
  [[ $1 == -chparam && $# -ge 3 ]] || { echo "system_cost.sh: expected -chparam NAME VALUE" >&2; exit 2; }
  chparam+=" -set $2 $3"; shift 3
done
list() { sed -e '/^ *\/\//d' -e '/^ *$/d' -e "s|^|$rtl/|" "$rtl/$1" | tr '\n' ' '; }
sources="$(list tess.f) $(list system.f)"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
yosys -q -l "$work/log" -p "read_verilog -sv $sources; ${chparam:+chparam$chparam $module;} \
  hierarchy -check -top $module; synth -flatten; tee -q -o $work/cells stat; \
  async2sync; dfflegalize -cell \$_DFF_P_ 01; tee -q -o $work/cmos stat -tech cmos; \
  tee -q -o $work/ltp ltp -noff" > /dev/null
cells=$(sed -n 's/^ *Number of cells: *\([0-9]*\)/\1/p' "$work/cells" | tail -1)
flops=$({ grep -E '^\s+\$_(S?DFF|DFFE|SDFFE|SDFFCE|ALDFF|DFFSR|DLATCH)' "$work/cells" || true; } | awk '{s += $2} END {print s + 0}')
transistors=$(sed -n 's/.*Estimated number of transistors: *\([0-9+]*\).*/\1/p' "$work/cmos" | tail -1)
depth=$(sed -n 's/.*Longest topological path in .* (length=\([0-9]*\)).*/\1/p' "$work/ltp" | tail -1)
echo "$module${chparam:+ ($chparam )}: cells $cells, flip-flops $flops, transistors $transistors, depth $depth"
