#!/usr/bin/env bash
# The screenshot of docs/verification.md (Waveforms): a real divergence, the injected rounding bug
# of the RTL build n2_bug1, as gtkwave shows it with the layout `tessim cosim --wave` writes.
#   scripts/wave_screenshot.sh [OUT.png] [TESSIM]
# Needs gtkwave (scripts/setup.sh) and, for a display, xvfb and xauth (Debian packages; not needed
# by the build or the tests, so setup.sh leaves them out).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=$(realpath -m "${1:-$root/docs/images/cosim_divergence_gtkwave.png}")
tessim=${2:-$root/build/bin/tessim}
for tool in gtkwave xvfb-run; do
  command -v "$tool" > /dev/null || { echo "wave_screenshot.sh: $tool not found (apt-get install gtkwave xvfb xauth)" >&2; exit 2; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# Exit status 1: the divergence this picture is about.
"$tessim" cosim --random 8 --random-max-L 4 --variant n2_bug1 --gpe-cycles 1 --wave "$work/divergence.fst" \
  --wave-window 40 | sed -n '/FAIL: first/,/waveform/p' || true
[[ -s $work/divergence.gtkw ]] || { echo "wave_screenshot.sh: no divergence recorded" >&2; exit 1; }
cat > "$work/grab.tcl" <<TCL
gtkwave::/File/Grab_To_File $out
gtkwave::/File/Quit
TCL
xvfb-run -a -s "-screen 0 1600x1200x24" gtkwave -S "$work/grab.tcl" "$work/divergence.gtkw" > "$work/gtkwave.log" 2>&1
[[ -s $out ]] || { cat "$work/gtkwave.log" >&2; exit 1; }
echo "wave_screenshot.sh: wrote $out"
