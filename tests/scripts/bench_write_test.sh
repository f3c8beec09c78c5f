#!/usr/bin/env bash
# scripts/bench_write.py end to end on a small job: it measures all three commands, reports a
# positive bandwidth ratio against dd and leaves no file behind.
set -euo pipefail
tessim=$1
dir=$2
here=$(cd "$(dirname "$0")/../.." && pwd)
rm -rf "$dir" && mkdir -p "$dir"
out=$(/usr/bin/python3 "$here/scripts/bench_write.py" "$tessim" -L 4 --runs 1 --dir "$dir")
echo "$out"
for row in "tessim -o FILE" "tessim -o - (no I/O)" "dd bs=1M"; do
  grep -qF "$row" <<<"$out" || { echo "missing row: $row"; exit 1; }
done
ratio=$(sed -n 's/^tessim writes at \([0-9.]*\)x dd.*/\1/p' <<<"$out")
awk -v r="$ratio" 'BEGIN { exit !(r > 0) }' || { echo "no positive ratio in the report"; exit 1; }
if compgen -G "$dir/bench_write_*" >/dev/null; then
  echo "files left behind in $dir"
  exit 1
fi
