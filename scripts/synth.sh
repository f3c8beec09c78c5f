#!/usr/bin/env bash
# Hardware cost of one configuration of the unit with Yosys, flattened (docs/rtl.md: cost method;
# the study composes the same figures from per-module records, scripts/yosys_cost.py, and this
# flat synthesis measures how close the composition is):
#   - generic `synth` cell count and flip-flops,
#   - `stat -tech cmos` transistor estimate after flip-flop legalisation (async2sync;
#     dfflegalize -cell $_DFF_P_ 01), so that every cell has a cost and the total is exact,
#   - `synth_xilinx` LUT / FF / DSP / CARRY4 counts,
#   - logic depth: `ltp -noff` on the flattened generic netlist (a critical-path proxy).
# For the whole unit and, unless --no-blocks, for the blocks tess_cpg and tess_int on their own
# (each with `hierarchy -top` on that module, parameters as inside the unit).
#
# Usage: scripts/synth.sh [options] [N] [-chparam NAME VALUE ...]
#   N                   INT blocks (IntBlocks), default tess_pkg::IntBlocks
#   -chparam NAME VALUE any other parameter of tess_unit (those of tess_pkg, e.g. IntLatency)
#   --json FILE         also write the numbers as JSON (FILE = - for stdout only)
#   --no-blocks         only the whole unit
#   --cpg-only          only the CPG
#   --no-xilinx         skip synth_xilinx
#   --jobs J            Yosys runs in parallel (default 2)
#   --keep DIR          keep the Yosys logs and reports in DIR
set -euo pipefail

usage() { sed -n '2,21p' "$0" | sed 's/^# \{0,1\}//'; }

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
json=""
blocks=1
xilinx=1
jobs=2
keep=""
declare -A params=()
declare -a order=()

set_param() {
  [[ -v "params[$1]" ]] || order+=("$1")
  params[$1]=$2
}

while (($#)); do
  case "$1" in
    -h|--help) usage; exit 0 ;;
    --json) json=${2:?--json needs a file}; shift 2 ;;
    --no-blocks) blocks=0; shift ;;
    --cpg-only) blocks=2; shift ;;
    --no-xilinx) xilinx=0; shift ;;
    --jobs) jobs=${2:?--jobs needs a number}; shift 2 ;;
    --keep) keep=${2:?--keep needs a directory}; shift 2 ;;
    -chparam)
      [[ $# -ge 3 ]] || { echo "synth.sh: -chparam needs NAME VALUE" >&2; exit 2; }
      set_param "$2" "$3"; shift 3 ;;
    [0-9]*) set_param IntBlocks "$1"; shift ;;
    *) echo "synth.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
# Parameter defaults from the package (every tess_unit parameter has one there). A parameter set
# to its default is dropped: Yosys elaborates an explicitly parameterised top slightly differently
# (a few tenths of a percent of the cells), and one configuration must give one result however it
# is spelt.
pkg_default() { sed -n "s/^ *localparam int unsigned $1 *= *\([0-9]*\);.*/\1/p" "$root/rtl/tess_pkg.sv"; }
for name in "${order[@]}"; do
  [[ ${params[$name]} =~ ^[0-9]+$ ]] || { echo "synth.sh: $name must be a number" >&2; exit 2; }
  [[ $name =~ ^[A-Za-z]+$ && -n $(pkg_default "$name") ]] || { echo "synth.sh: tess_unit has no parameter '$name'" >&2; exit 2; }
done
declare -a kept=()
for name in "${order[@]}"; do
  if [[ ${params[$name]} == "$(pkg_default "$name")" ]]; then unset "params[$name]"; else kept+=("$name"); fi
done
order=("${kept[@]}")

command -v yosys > /dev/null || { echo "synth.sh: yosys not found" >&2; exit 2; }

# The sources of rtl/tess.f, in its order.
sources=$(/usr/bin/python3 "$root/scripts/rtl_sources.py" "$root/rtl/tess.f" | tr '\n' ' ')

if [[ -n $keep ]]; then
  mkdir -p "$keep"
  work=$(cd "$keep" && pwd)
else
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
fi

value() { if [[ -v "params[$1]" ]]; then echo "${params[$1]}"; else pkg_default "$1"; fi; }
I=$(value CoordIntBits); F=$(value CoordFracBits); B=$(value BaryBits)
N=$(value IntBlocks); LAT=$(value IntLatency); V=$(value Contexts)
CL=$(value CpgLanes); CR=$(value CpgDigitBits); CT=$(value CpgTags)
W=$((1 + I + F))
idx_bits=1; while (( (1 << idx_bits) < V )); do idx_bits=$((idx_bits + 1)); done

# chparam -set before hierarchy (hierarchy -chparam trips an assertion in Yosys 0.23 when a
# value equals the default of a module with submodules).
chparams_for() {
  local module=$1 out="" name
  case "$module" in
    tess_unit)
      for name in "${order[@]}"; do out+="chparam -set $name ${params[$name]} tess_unit; "; done ;;
    tess_cpg)
      out="chparam -set CoordIntBits $I -set CoordFracBits $F -set CpgLanes $CL -set CpgDigitBits $CR -set CpgTags $CT tess_cpg; " ;;
    tess_int)
      out="chparam -set CoordWidth $W -set BaryBits $B -set Latency $LAT -set TagWidth $((idx_bits + 4)) tess_int; " ;;
  esac
  echo "$out"
}

generic_job() {  # module
  local m=$1
  yosys -q -l "$work/$m.generic.log" -p "read_verilog -sv $sources; $(chparams_for "$m") \
    hierarchy -check -top $m; synth -flatten; tee -q -o $work/$m.cells stat; \
    async2sync; dfflegalize -cell \$_DFF_P_ 01; tee -q -o $work/$m.cmos stat -tech cmos; \
    tee -q -o $work/$m.ltp ltp -noff" > /dev/null
}

xilinx_job() {  # module
  local m=$1
  yosys -q -l "$work/$m.xilinx.log" -p "read_verilog -sv $sources; $(chparams_for "$m") \
    hierarchy -check -top $m; synth_xilinx -flatten; tee -q -o $work/$m.xil stat" > /dev/null
}

modules=(tess_unit)
((blocks == 1)) && modules+=(tess_cpg tess_int)
((blocks == 2)) && modules=(tess_cpg)
tasks=()
for m in "${modules[@]}"; do
  tasks+=("generic_job $m")
  ((xilinx)) && tasks+=("xilinx_job $m")
done

start=$SECONDS
failed=0
running=0
for t in "${tasks[@]}"; do
  if ((running >= jobs)); then
    wait -n || failed=1
    running=$((running - 1))
  fi
  $t &
  running=$((running + 1))
done
while ((running > 0)); do
  wait -n || failed=1
  running=$((running - 1))
done
if ((failed)); then
  echo "synth.sh: a Yosys run failed; logs:" >&2
  for log in "$work"/*.log; do echo "== $log" >&2; grep -i -m5 "error" "$log" >&2 || true; done
  [[ -n $keep ]] || echo "(rerun with --keep DIR to keep the logs)" >&2
  exit 1
fi
elapsed=$((SECONDS - start))

param_text=""
for name in "${order[@]}"; do param_text+="$name=${params[$name]} "; done

/usr/bin/python3 - "$root/scripts" "$work" "$json" "$elapsed" "$xilinx" "${param_text% }" \
  "I=$I F=$F B=$B N=$N latency=$LAT V=$V" "${modules[@]}" <<'PY'
import json, os, sys

sys.path.insert(0, sys.argv[1])
import yosys_stat

work, json_path, elapsed, xilinx, overrides, config = sys.argv[2:8]
modules = sys.argv[8:]
xilinx = xilinx == "1"

def read(path):
    with open(path) as f:
        return f.read()

result = {"yosys": "0.23", "overrides": overrides, "config": config, "seconds": int(elapsed), "blocks": {}}
for m in modules:
    entry = yosys_stat.generic(*(read(os.path.join(work, m + ext)) for ext in (".cells", ".cmos", ".ltp")))
    if xilinx:
        entry["xilinx"] = yosys_stat.xilinx(yosys_stat.cell_table(read(os.path.join(work, m + ".xil")))[1])
    result["blocks"][m] = entry

if json_path != "-":
    print(f"Yosys 0.23 synthesis of tess_unit ({config}; {result['seconds']} s)")
    head = f"{'block':<10} {'cells':>8} {'flops':>7} {'transistors':>12} {'depth':>6}"
    if xilinx:
        head += f" {'LUT':>7} {'FF':>6} {'DSP':>4} {'CARRY4':>7}"
    print(head)
    for m, e in result["blocks"].items():
        tr = f"{e['transistors']}{'' if e['transistors_exact'] else '+'}"
        line = f"{m:<10} {e['cells']:>8} {e['flops']:>7} {tr:>12} {e['depth'] if e['depth'] is not None else '?':>6}"
        if xilinx:
            x = e["xilinx"]
            line += f" {x['lut']:>7} {x['ff']:>6} {x['dsp']:>4} {x['carry4']:>7}"
        print(line)
if json_path:
    text = json.dumps(result, indent=2)
    if json_path == "-":
        print(text)
    else:
        with open(json_path, "w") as f:
            f.write(text + "\n")
PY
