#!/usr/bin/env bash
# Sets everything up (packages, build) and runs the test suite: every test but the long
# campaigns (ctest label `campaign`; docs/verification.md, Test budget).
#
# The build and the tests run under scripts/check_packages.py, which records every file they
# open or run and fails if one belongs to a Debian package that scripts/setup.sh does not install
# (so a missing install step fails here, not on someone else's fresh machine). The trace is
# kept in build/package-trace.txt.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh --deps
/usr/bin/python3 scripts/check_packages.py run --trace build/package-trace.txt -- \
  bash -c 'bash scripts/setup.sh && ctest --test-dir build --output-on-failure -j2 -LE campaign'
