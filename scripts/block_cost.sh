#!/usr/bin/env bash
# Cost of one block of the unit on its own, by the generic flow of scripts/synth.sh (docs/rtl.md:
# `synth -flatten`, flip-flops legalised, `stat -tech cmos`, `ltp -noff`): cells, flip-flops,
# transistors, logic depth. For blocks synth.sh does not report separately (the DPG, the FSU),
# and, with -list system.f, the blocks of the system of units (scripts/system_cost.sh).
#
# Usage: scripts/block_cost.sh MODULE [RTL_DIR] [-list FILE.f ...] [-chparam NAME VALUE ...]
#   RTL_DIR   where tess.f and the sources it lists are (default: rtl/); another checkout's
#             rtl/ costs an older version of a block the same way.
#   -list     a further source list in RTL_DIR, read after tess.f
set -euo pipefail
module=${1:?usage: block_cost.sh MODULE [RTL_DIR] [-list FILE.f ...] [-chparam NAME VALUE ...]}
shift
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
rtl="$root/rtl"
if (($#)) && [[ $1 != -chparam && $1 != -list ]]; then rtl=$1; shift; fi
lists="tess.f"
chparam=""
while (($#)); do
  case $1 in
    -list) [[ $# -ge 2 ]] || { echo "block_cost.sh: -list needs a file" >&2; exit 2; }; lists+=" $2"; shift 2 ;;
    -chparam) [[ $# -ge 3 ]] || { echo "block_cost.sh: expected -chparam NAME VALUE" >&2; exit 2; }
              chparam+=" -set $2 $3"; shift 3 ;;
    *) echo "block_cost.sh: unexpected '$1' (expected -list FILE.f or -chparam NAME VALUE)" >&2; exit 2 ;;
  esac
done
listings=()
for list in $lists; do listings+=("$rtl/$list"); done
sources=$(/usr/bin/python3 "$root/scripts/rtl_sources.py" "${listings[@]}" | tr '\n' ' ')
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
yosys -q -l "$work/log" -p "read_verilog -sv $sources; ${chparam:+chparam$chparam $module;} \
  hierarchy -check -top $module; synth -flatten; tee -q -o $work/cells stat; \
  async2sync; dfflegalize -cell \$_DFF_P_ 01; tee -q -o $work/cmos stat -tech cmos; \
  tee -q -o $work/ltp ltp -noff" > /dev/null
stat=$(/usr/bin/python3 "$root/scripts/yosys_stat.py" generic "$work/cells" "$work/cmos" "$work/ltp")
read -r cells flops transistors depth <<< "$stat"
echo "$module${chparam:+ ($chparam )}: cells $cells, flip-flops $flops, transistors $transistors, depth $depth"
