#!/usr/bin/env bash
# Installs everything tessim needs from Debian's archive (idempotent: installs only what is
# missing) and configures + builds the project into build/ with both cores.
#   scripts/setup.sh          packages, then the build
#   scripts/setup.sh --deps   packages only
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(
  build-essential cmake pkg-config
  libglm-dev                    # vector maths of the float reference
  libassimp-dev assimp-testmodels  # mesh import; real test meshes in /usr/share/assimp/models
  libopenimageio-dev            # PNG/EXR output of the renderer
  libcli11-dev                  # command-line parsing
  nlohmann-json3-dev            # config files, statistics, traces
  libgtest-dev libgmock-dev     # unit tests
  libbenchmark-dev              # microbenchmarks
  verilator                     # RTL simulation (lock-step co-simulation)
  yosys                         # synthesis for hardware cost
  iverilog                      # 4-state simulation: the RTL's X checks fire on an X (tests/rtl/x_check_test.sh)
  python3-matplotlib python3-numpy  # plots (run with /usr/bin/python3)
  python3-distributed           # sweep.py --scheduler: points on a Dask cluster
  clang libclang-rt-14-dev      # libFuzzer targets (fuzz/, scripts/fuzz.sh)
  llvm lld                      # their toolchain: llvm-symbolizer for sanitizer reports, the LLVM binutils CMake picks
  zlib1g-dev                    # FST waveforms
  git                           # scripts/costs.py records the commit its RTL was taken from
  strace                        # scripts/check_packages.py: files the build and tests touch
  gtkwave                       # tessim cosim --wave: FST to VCD (fst2vcd), viewing the dumps with their .gtkw layout
  chromium                      # tessim report: the HTML run report checked in a headless browser
  pybind11-dev python3-dev      # the Python module (python/), numpy arrays out of the model and the cycle model
  python3-setuptools            # its configure: CMake's FindPython3 probes the interpreter through distutils
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends "${missing[@]}"
fi

[[ ${1:-} == --deps ]] && exit 0

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release ${TESSIM_CMAKE_ARGS:-}
cmake --build build -j2
