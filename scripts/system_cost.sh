#!/usr/bin/env bash
# Cost of one block of the system of units (rtl/system.f: tess_distributor, tess_reassembly,
# tess_patch_count, tess_system) on its own: scripts/block_cost.sh with rtl/system.f read after
# rtl/tess.f.
#
# Usage: scripts/system_cost.sh MODULE [RTL_DIR] [-chparam NAME VALUE ...]
set -euo pipefail
module=${1:?usage: system_cost.sh MODULE [RTL_DIR] [-chparam NAME VALUE ...]}
shift
args=()
if (($#)) && [[ $1 != -chparam ]]; then args+=("$1"); shift; fi
exec "$(dirname "${BASH_SOURCE[0]}")/block_cost.sh" "$module" "${args[@]}" -list system.f "$@"
