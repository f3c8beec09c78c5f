#!/usr/bin/env bash
# The documented command of the load-balancing study regenerates every figure that
# docs/results/load-balancing.md shows, from the small sweep, with the recorded Yosys costs of
# the current RTL (a changed RTL without new cost records fails here, naming the configuration).
#
#   results_test.sh TESSIM WORKDIR
set -euo pipefail
tessim=${1:?usage: results_test.sh TESSIM WORKDIR}
work=${2:?usage: results_test.sh TESSIM WORKDIR}
root=$(cd "$(dirname "$0")/../.." && pwd)
out="$work/out"
rm -rf "$out"

bash "$root/scripts/results.sh" --tessim "$tessim" --build-dir "$work" --out "$out" --recorded-costs --jobs 2

fail=0
# Every image the page links, in both formats, non-empty.
mapfile -t figures < <(grep -o '([a-z_]*\.png)' "$root/docs/results/load-balancing.md" | tr -d '()' | sort -u)
((${#figures[@]} >= 8)) || { echo "results_test: only ${#figures[@]} figures linked from load-balancing.md" >&2; fail=1; }
for png in "${figures[@]}"; do
  for f in "$out/$png" "$out/${png%.png}.svg"; do
    [[ -s $f ]] || { echo "results_test: $f was not generated" >&2; fail=1; }
  done
done
# Nothing skipped for missing rows or costs.
[[ -s $out/tables.md ]] || { echo "results_test: no tables.md" >&2; fail=1; }
if grep -q '^### Skipped' "$out/tables.md"; then
  echo "results_test: plots.py skipped parts:" >&2
  sed -n '/^### Skipped/,$p' "$out/tables.md" >&2
  fail=1
fi
grep -q '^### Pareto front' "$out/tables.md" || { echo "results_test: no Pareto table (costs not joined)" >&2; fail=1; }
# The committed results were produced by the committed sweep spec: same points, same outcome.
if ! /usr/bin/python3 - "$root/docs/results/results.csv" "$out/results.csv" <<'EOF'
import csv, sys
def load(p):
    with open(p, newline="") as f:
        return {r["point"]: r for r in csv.DictReader(f)}
committed, fresh = load(sys.argv[1]), load(sys.argv[2])
if committed.keys() != fresh.keys():
    sys.exit(f"results_test: points differ from docs/results/results.csv: "
             f"{len(committed.keys() - fresh.keys())} only committed, {len(fresh.keys() - committed.keys())} only new")
bad = [p for p in fresh if fresh[p]["cycles"] != committed[p]["cycles"] or fresh[p]["vertices_out"] != committed[p]["vertices_out"]]
if bad:
    sys.exit(f"results_test: {len(bad)} points simulate differently from docs/results/results.csv, e.g. {bad[0]}")
# The committed costs are those of the current records: a record redone after an RTL change must
# be carried into the results (and the tables and docs drawn from them).
cost = [p for p in fresh if fresh[p].get("cost_unit_transistors") != committed[p].get("cost_unit_transistors")]
if cost:
    sys.exit(f"results_test: {len(cost)} points cost differently from docs/results/results.csv's cost columns "
             f"(e.g. {cost[0]}: {committed[cost[0]].get('cost_unit_transistors')} committed, "
             f"{fresh[cost[0]].get('cost_unit_transistors')} from the records); rerun scripts/results.sh")
print(f"results_test: {len(fresh)} points agree with docs/results/results.csv, cycles and costs")
EOF
then fail=1; fi
exit $fail
