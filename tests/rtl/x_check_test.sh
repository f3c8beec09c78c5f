#!/usr/bin/env bash
# The X checks (`TESS_ASSERT_KNOWN, rtl/tess_assert.svh) fire on an X and only then. Verilator is
# 2-state, so a 4-state simulator runs them: iverilog 11, on tess_fifo with its push strobe
# driven to X for a cycle (tests/rtl/x_check_tb.sv). iverilog 11 has no concurrent assertions,
# so the testbench defines TESS_ASSERT_IMMEDIATE (the X checks as immediate checks at the clock
# edge), and it has no `int unsigned` parameters, so they are read as `int` (same values).
#
#   x_check_test.sh RTL_DIR TESTS_RTL_DIR WORK_DIR
set -euo pipefail
rtl=${1:?usage: x_check_test.sh RTL_DIR TESTS_RTL_DIR WORK_DIR}
tb_dir=${2:?}
work=${3:?}
mkdir -p "$work"
sed 's/int unsigned/int/g' "$rtl/tess_fifo.sv" > "$work/tess_fifo.sv"
iverilog -g2012 -DTESS_ASSERT_IMMEDIATE -o "$work/x_check.vvp" \
  "$rtl/tess_assert.svh" "$work/tess_fifo.sv" "$tb_dir/x_check_tb.sv"

fail=0
clean=$(vvp -n "$work/x_check.vvp" +x=0 2>&1)
grep -q 'x_check_tb: done, x=0' <<<"$clean" || { echo "x_check_test: the known run did not finish:" >&2; echo "$clean" >&2; fail=1; }
if grep -q 'failed' <<<"$clean"; then
  echo "x_check_test: an X check fired with every input known:" >&2; echo "$clean" >&2; fail=1
fi
dirty=$(vvp -n "$work/x_check.vvp" +x=1 2>&1)
grep -q 'x_check_tb: done, x=1' <<<"$dirty" || { echo "x_check_test: the X run did not finish:" >&2; echo "$dirty" >&2; fail=1; }
if ! grep -q 'PushKnown_A failed' <<<"$dirty"; then
  echo "x_check_test: PushKnown_A did not fire on an X push strobe:" >&2; echo "$dirty" >&2; fail=1
fi
((fail == 0)) && echo "x_check_test: PushKnown_A fires on an X push strobe and stays silent otherwise"
exit $fail
