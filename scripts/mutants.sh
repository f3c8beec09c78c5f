#!/usr/bin/env bash
# The mutation campaign (docs/verification.md, Mutation campaign): see scripts/mutants.py.
exec /usr/bin/python3 "$(dirname "$0")/mutants.py" "$@"
