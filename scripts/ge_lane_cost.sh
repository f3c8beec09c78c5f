#!/usr/bin/env bash
# Cost of one ALU lane of the geometry engine (rtl/ge/, docs/results/ge_lane/), by the generic
# flow of scripts/block_cost.sh (`synth -flatten`, flip-flops legalised, `stat -tech cmos`,
# `ltp -noff`): cells, flip-flops, transistors, logic depth of the FP32 fused multiply-add lane,
# of the fixed-point lane in the unit's format (W = 1 + CoordIntBits + CoordFracBits) and of the
# fixed-point lane at W = 32 (IntBits = 31 - CoordFracBits). With -xilinx also `synth_xilinx
# -flatten`: LUTs, CARRY4s, flip-flops, DSP48E1s. This converts the unit's transistors into GE
# lanes; the lanes are not part of the unit and rtl/tess.f does not list them.
#
# Also the lane of the GE as a shader core (ge_shader_lane: the FP32 lane with its register file,
# operand network and write-back) and the issue logic its lanes share (ge_simd_issue).
#
# Usage: scripts/ge_lane_cost.sh [-xilinx] [-json FILE]
#   prints one line per lane; -json also writes the numbers as JSON to FILE.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
ge="$root/rtl/ge"
xilinx=0
json=""
while (($#)); do
  case $1 in
    -xilinx) xilinx=1; shift ;;
    -json) [[ $# -ge 2 ]] || { echo "ge_lane_cost.sh: -json needs a file" >&2; exit 2; }; json=$2; shift 2 ;;
    *) echo "usage: ge_lane_cost.sh [-xilinx] [-json FILE]" >&2; exit 2 ;;
  esac
done
all_sources=$(/usr/bin/python3 "$root/scripts/rtl_sources.py" "$ge/ge.f" | tr '\n' ' ')
# The plain lanes are read with the files they were first costed with (the package and the two
# lanes): ABC's result depends on the set of modules read, and with the shader core's files too
# the FP32 lane maps to 50 586 transistors instead of 50 520.
lane_sources=$(/usr/bin/python3 "$root/scripts/rtl_sources.py" "$ge/ge.f" | grep -E '/(tess_pkg|ge_fma_lane|ge_mac_lane)\.sv$' | tr '\n' ' ')
sources=$lane_sources
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The fixed-point format: the package defaults the lane takes.
pkg_value() { sed -n "s/.*localparam int unsigned $1 *= *\([0-9]*\);.*/\1/p" "$root/rtl/tess_pkg.sv"; }
int_bits=$(pkg_value CoordIntBits)
frac_bits=$(pkg_value CoordFracBits)
width=$((1 + int_bits + frac_bits))
w32_int_bits=$((31 - frac_bits))

# cost NAME TOP [CHPARAM...]: sets the globals cells, flops, transistors, depth, seconds (and
# luts, carry, xflops, dsps with -xilinx) and prints the line.
cost() {
  local name=$1 top=$2 chparam=${3:-}
  local log="$work/$name" start end stat
  mkdir -p "$log"
  start=$(date +%s.%N)
  yosys -q -l "$log/log" -p "read_verilog -sv $sources; ${chparam:+chparam $chparam $top;} \
    hierarchy -check -top $top; synth -flatten; tee -q -o $log/cells stat; \
    async2sync; dfflegalize -cell \$_DFF_P_ 01; tee -q -o $log/cmos stat -tech cmos; \
    tee -q -o $log/ltp ltp -noff" > /dev/null
  end=$(date +%s.%N)
  stat=$(/usr/bin/python3 "$root/scripts/yosys_stat.py" generic "$log/cells" "$log/cmos" "$log/ltp")
  read -r cells flops transistors depth <<< "$stat"
  seconds=$(awk -v a="$start" -v b="$end" 'BEGIN {printf "%.1f", b - a}')
  local line="$name: cells $cells, flip-flops $flops, transistors $transistors, depth $depth (synthesis ${seconds} s)"
  if ((xilinx)); then
    start=$(date +%s.%N)
    yosys -q -p "read_verilog -sv $sources; ${chparam:+chparam $chparam $top;} \
      hierarchy -check -top $top; synth_xilinx -flatten -top $top; tee -q -o $log/xilinx stat" > /dev/null
    end=$(date +%s.%N)
    stat=$(/usr/bin/python3 "$root/scripts/yosys_stat.py" xilinx "$log/xilinx")
    read -r luts xflops dsps carry _ <<< "$stat"
    xseconds=$(awk -v a="$start" -v b="$end" 'BEGIN {printf "%.1f", b - a}')
    line+="; xilinx: LUTs $luts, CARRY4 $carry, flip-flops $xflops, DSP48E1 $dsps (${xseconds} s)"
  fi
  echo "$line"
}

entry() {  # JSON object of the last cost() call, with extra "key": value pairs
  local extra=${1:-}
  printf '{"cells": %s, "flip_flops": %s, "transistors": %s, "depth": %s' \
    "$cells" "$flops" "$transistors" "$depth"
  if ((xilinx)); then
    printf ', "xilinx": {"luts": %s, "carry4": %s, "flip_flops": %s, "dsp48e1": %s}' "$luts" "$carry" "$xflops" "$dsps"
  fi
  printf '%s}' "$extra"
}

cost ge_fma_lane ge_fma_lane
fma_json=$(entry ', "format": "fp32"')
cost ge_mac_lane ge_mac_lane
mac_json=$(entry ", \"width\": $width, \"int_bits\": $int_bits, \"frac_bits\": $frac_bits")
cost ge_mac_lane_w32 ge_mac_lane "-set IntBits $w32_int_bits"
w32_json=$(entry ", \"width\": 32, \"int_bits\": $w32_int_bits, \"frac_bits\": $frac_bits")

# A lane of the GE as a shader core: the FP32 lane with its register file (Regs per wave, Waves
# waves), operand network and write-back; and the issue logic its W lanes share.
lane_param() { sed -n "s/.*parameter int unsigned $2 *= *\([0-9]*\),.*/\1/p" "$ge/$1.sv"; }
regs=$(lane_param ge_shader_lane Regs)
waves=$(lane_param ge_shader_lane Waves)
pc_bits=$(lane_param ge_simd_issue PcBits)
sources=$all_sources
cost ge_shader_lane ge_shader_lane
shader_json=$(entry ", \"regs\": $regs, \"waves\": $waves, \"register_bits\": $((32 * regs * waves))")
cost ge_simd_issue ge_simd_issue
issue_json=$(entry ", \"waves\": $waves, \"pc_bits\": $pc_bits")

if [[ -n $json ]]; then
  printf '{\n  "ge_fma_lane": %s,\n  "ge_mac_lane": %s,\n  "ge_mac_lane_w32": %s,\n  "ge_shader_lane": %s,\n  "ge_simd_issue": %s\n}\n' \
    "$fma_json" "$mac_json" "$w32_json" "$shader_json" "$issue_json" > "$json"
fi
