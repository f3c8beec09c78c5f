#!/usr/bin/env bash
# Installs everything tessim needs from Debian's archive (idempotent: installs only what is
# missing) and configures + builds the project into build/ with both cores.
#   scripts/setup.sh              every package, then the whole build (tests, benchmarks, the
#                                 Python module, every Verilated RTL build)
#   scripts/setup.sh --deps       every package only
#   scripts/setup.sh --default-job  the packages and the build the default job needs
#                                 (scripts/run-default.sh): the tessim binary with the default RTL
#                                 build (n2) for its co-simulation. A build/ that already has the
#                                 whole configuration keeps it; the whole setup later completes a
#                                 default-job build/ in place.
set -euo pipefail
cd "$(dirname "$0")/.."

mode=${1:-all}
case "$mode" in all|--deps|--default-job) ;; *) echo "setup.sh: unknown argument '$mode'" >&2; exit 2 ;; esac

# What the tessim binary needs to build and run, the default job's co-simulation included.
DEFAULT_PACKAGES=(
  build-essential cmake pkg-config
  libglm-dev                    # vector maths of the float reference
  libassimp-dev assimp-testmodels  # mesh import; real test meshes in /usr/share/assimp/models
  libopenimageio-dev            # PNG/EXR output of the renderer
  libcli11-dev                  # command-line parsing
  nlohmann-json3-dev            # config files, statistics, traces
  verilator                     # RTL simulation (lock-step co-simulation)
  zlib1g-dev                    # FST waveforms, compressed traces
  git                           # the tool version in the statistics; scripts/costs.py records the RTL's commit
)
# What the tests, benchmarks, the Python module and the study's scripts need beyond that.
FULL_PACKAGES=(
  libgtest-dev libgmock-dev     # unit tests
  libbenchmark-dev              # microbenchmarks
  yosys                         # synthesis for hardware cost
  qflow-tech-osu018             # OSU 0.18 um standard cells (Liberty with timing and power): silicon cost (scripts/silicon.py)
  opensta                       # OpenSTA: static timing of the cell-mapped netlists
  iverilog                      # 4-state simulation: the RTL's X checks fire on an X (tests/rtl/x_check_test.sh)
  python3-matplotlib python3-numpy  # plots (run with /usr/bin/python3)
  python3-scipy                 # scripts/silhouette_fair.py: nearest contour samples (k-d tree)
  python3-distributed           # sweep.py --scheduler: points on a Dask cluster
  clang libclang-rt-14-dev      # libFuzzer targets (fuzz/, scripts/fuzz.sh)
  llvm lld                      # their toolchain: llvm-symbolizer for sanitizer reports, the LLVM binutils CMake picks
  strace                        # scripts/check_packages.py: files the build and tests touch
  gtkwave                       # tessim cosim --wave: FST to VCD (fst2vcd), viewing the dumps with their .gtkw layout
  chromium                      # tessim report: the HTML run report checked in a headless browser
  pybind11-dev python3-dev      # the Python module (python/), numpy arrays out of the model and the cycle model
  python3-setuptools            # its configure: CMake's FindPython3 probes the interpreter through distutils
)

PACKAGES=("${DEFAULT_PACKAGES[@]}")
[[ $mode == --default-job ]] || PACKAGES+=("${FULL_PACKAGES[@]}")

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

[[ $mode == --deps ]] && exit 0

# The whole configuration states every option, so that it also completes a default-job build/.
FULL_OPTIONS=(-DTESSIM_BUILD_TESTS=ON -DTESSIM_BUILD_BENCH=ON -DTESSIM_BUILD_PYTHON=ON
              -DTESSIM_BUILD_RTL=ON -DTESSIM_BUILD_SYSTEM_RTL=ON -DTESSIM_RTL_VARIANTS=)
# The default job: no tests, benchmarks or Python module, and one Verilated build (the default
# configuration's; Verilator runs at configure time, one build at a time).
DEFAULT_OPTIONS=(-DTESSIM_BUILD_TESTS=OFF -DTESSIM_BUILD_BENCH=OFF -DTESSIM_BUILD_PYTHON=OFF
                 -DTESSIM_BUILD_RTL=ON -DTESSIM_BUILD_SYSTEM_RTL=OFF -DTESSIM_RTL_VARIANTS=n2)

if [[ $mode == --default-job ]]; then
  if grep -qs '^TESSIM_BUILD_TESTS:BOOL=ON' build/CMakeCache.txt && grep -qs '^TESSIM_RTL_VARIANTS:STRING=$' build/CMakeCache.txt; then
    options=()  # already the whole configuration: keep it, build tessim in it
  else
    options=("${DEFAULT_OPTIONS[@]}")
  fi
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${options[@]}" ${TESSIM_CMAKE_ARGS:-}
  cmake --build build -j2 --target tessim
else
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${FULL_OPTIONS[@]}" ${TESSIM_CMAKE_ARGS:-}
  cmake --build build -j2
fi
