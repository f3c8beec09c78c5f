#!/usr/bin/env bash
# Runs the libFuzzer targets (docs/verification.md, Fuzzing), each for SECONDS (default 60):
#   bash scripts/fuzz.sh [SECONDS] [TARGET...]      targets: fuzz_mesh fuzz_mesh_checks fuzz_config fuzz_unit
# Builds them first (CMake preset "fuzz": clang, ASan + UBSan, build-fuzz/), seeds the mesh
# corpus from Debian's assimp-testmodels, and prints executions, executions per second and
# findings per target. Corpora and crash reproducers stay in build-fuzz/corpus/ and
# build-fuzz/findings/. Exit status 1 if a target found anything.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(fuzz_mesh fuzz_mesh_checks fuzz_config fuzz_unit)

cmake --preset fuzz >/dev/null
cmake --build --preset fuzz >/dev/null

corpus=build-fuzz/corpus
findings=build-fuzz/findings
mkdir -p "$corpus"/fuzz_mesh "$corpus"/fuzz_mesh_checks "$corpus"/fuzz_config "$corpus"/fuzz_unit "$findings"
# Mesh seeds: a format byte followed by a real file of that format (fuzz_mesh: 0 PLY, 1 OBJ,
# 2 STL, 3 OFF; fuzz_mesh_checks: 0 PLY, 1 OFF, 2 STL, 3 OBJ).
seed() {  # seed TARGET BYTE EXT
  while IFS= read -r f; do
    out="$corpus/$1/seed-$(basename "$f")"
    [ -e "$out" ] || { printf "\\x$(printf %02x "$2")" > "$out"; cat "$f" >> "$out"; }
  done < <(find /usr/share/assimp/models -iname "*.$3" -size -64k 2>/dev/null | sort)
}
seed fuzz_mesh 0 ply; seed fuzz_mesh 1 obj; seed fuzz_mesh 2 stl; seed fuzz_mesh 3 off
seed fuzz_mesh_checks 0 ply; seed fuzz_mesh_checks 1 off; seed fuzz_mesh_checks 2 stl; seed fuzz_mesh_checks 3 obj
# Configuration seeds: the keys of `tessim schema` with valid and edge values.
printf '{"int_blocks": 2, "tess_factor": 8}' > "$corpus/fuzz_config/seed-basic.json"
printf '{"int_blocks": 32, "int_latency": 8, "te_contexts": 16, "coord_int_bits": 8, "coord_frac_bits": 23, "bary_bits": 20, "normals": "reflect", "cpg_mapping": "gpe"}' \
  > "$corpus/fuzz_config/seed-limits.json"
printf '{"gpe_stall_prob": 0.99, "seed": 18446744073709551615, "gpe_cycles": 1e400}' > "$corpus/fuzz_config/seed-edges.json"

# LeakSanitizer cannot run under ptrace (the test command runs under strace for
# scripts/check_packages.py): leaks are then not checked, and the run says so.
leaks=1
if [ "$(awk '/^TracerPid:/ {print $2}' /proc/$$/status)" != 0 ]; then
  leaks=0
  echo "fuzz: running under a tracer: LeakSanitizer off" >&2
fi
export ASAN_OPTIONS="abort_on_error=1:detect_leaks=$leaks"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$PWD/tests/support/lsan.supp"
status=0
printf "%-12s %12s %12s %10s %s\n" target executions "exec/s" seconds findings
for t in "${targets[@]}"; do
  log="build-fuzz/$t.log"
  extra=()
  # Assimp leaks the partial scene of some files it rejects (tests/support/lsan.supp); libFuzzer's
  # per-input malloc/free balance then trips and its LeakSanitizer pass blames its own corpus
  # bookkeeping. Leaks of mesh loading are checked by the sanitizer suite instead.
  [ "$t" = fuzz_mesh ] && extra=(-detect_leaks=0)
  if "build-fuzz/bin/$t" "$corpus/$t" -max_total_time="$seconds" -print_final_stats=1 -timeout=20 -rss_limit_mb=2048 \
       "${extra[@]}" -artifact_prefix="$findings/$t-" >"$log" 2>&1; then
    found=none
  else
    found="see $log and $findings/"
    status=1
  fi
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  printf "%-12s %12s %12s %10s %s\n" "$t" "${runs:-?}" "${rate:-?}" "$seconds" "$found"
done
exit $status
