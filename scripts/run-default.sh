#!/usr/bin/env bash
# Sets up what the main job needs (packages, the tessim binary with the default RTL build) and
# runs it on the built-in default mesh (Debian's assimp-testmodels Wuson): cycle simulation with
# the default configuration, lock-step co-simulation against the RTL, and a flat-versus-PN
# picture. It neither builds nor runs the tests: scripts/run-tests.sh does.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS
bash scripts/setup.sh --default-job
MESH=/usr/share/assimp/models/PLY/Wuson.ply
mkdir -p results
build/bin/tessim sim "$MESH" --stats results/default-stats.json
build/bin/tessim cosim "$MESH" --int 2 -L 8 --stall 0.3
build/bin/tessim render "$MESH" -L 4 --compare flat -o results/default-render.png
echo "results in results/: default-stats.json, default-render.png ($((SECONDS - start)) s)"
