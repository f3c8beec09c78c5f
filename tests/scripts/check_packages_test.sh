#!/usr/bin/env bash
# scripts/check_packages.py can fail: a file of a package missing from the allowed list, a
# program that belongs to no package, and a trace with interleaved and failed calls are each
# reported; the same inputs with the full list of scripts/setup.sh pass.
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
check=("/usr/bin/python3" "$root/scripts/check_packages.py")
work=$(mktemp -d -p /var/tmp tessim-check-packages.XXXXXX)
trap 'rm -rf "$work"' EXIT
fail=0
expect() {  # expect STATUS PATTERN ARGS...: the check exits STATUS and prints PATTERN
  local want=$1 pattern=$2; shift 2
  local out status
  out=$("${check[@]}" "$@" 2>&1); status=$?
  if [[ $status -ne $want ]] || ! grep -q -- "$pattern" <<<"$out"; then
    echo "FAIL: check_packages.py $* -> exit $status (want $want, output matching '$pattern'):"
    echo "$out"
    fail=1
  else
    echo "ok: check_packages.py $* -> exit $status"
  fi
}

header=/usr/include/assimp/scene.h      # libassimp-dev
program=$(readlink -f /usr/bin/verilator) # verilator
/usr/bin/python3 -c 'import sys; sys.path.insert(0, sys.argv[1]); import check_packages; print("\n".join(check_packages.setup_packages()))' \
  "$root/scripts" >"$work/all.txt"
grep -vx 'libassimp-dev' "$work/all.txt" >"$work/no-assimp.txt"

# Files, with the full list: OK; without libassimp-dev: its header is reported.
expect 0 "OK" files --packages "$work/all.txt" "$header" --executed "$program"
expect 1 "package 'libassimp-dev' is used" files --packages "$work/no-assimp.txt" "$header" --executed "$program"
# setup.sh's own list is the default.
expect 0 "OK" files "$header"
# A program outside the repository and any Debian package (a copy of true, not in /tmp).
cp /bin/true "$work/true"
expect 1 "program '$work/true' was run but belongs to no Debian package" \
  files --packages "$work/all.txt" --executed "$work/true"

# A trace as strace -f writes it: an interleaved (unfinished / resumed) open of the header, a
# failed look-up of a file of a package that is installed but not allowed, an execve.
cat >"$work/trace.txt" <<TRACE
100 openat(AT_FDCWD, "$header", O_RDONLY <unfinished ...>
101 execve("$program", ["verilator"], 0x7ffd /* 3 vars */) = 0
101 newfstatat(AT_FDCWD, "/usr/include/assimp/nonexistent.h", 0x7ffd, 0) = -1 ENOENT (No such file or directory)
100 <... openat resumed>) = 3
TRACE
expect 0 "2 files touched, 1 programs run" report --packages "$work/all.txt" "$work/trace.txt"
expect 1 "package 'libassimp-dev' is used" report --packages "$work/no-assimp.txt" "$work/trace.txt"
# Only the failed look-up: nothing was touched, nothing to report.
grep ENOENT "$work/trace.txt" >"$work/failed.txt"
expect 0 "0 files touched" report --packages "$work/no-assimp.txt" "$work/failed.txt"
exit $fail
