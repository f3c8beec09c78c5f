#!/usr/bin/env bash
# The installed tree is enough to build against (ctest: install_consumer; docs/install.md):
# `cmake --install BUILD --prefix TMP`, then tests/install/consumer/ (copied out of the source
# tree) configured with CMAKE_PREFIX_PATH=TMP and built, and its cycle count checked against the
# installed `tessim sim` on the same mesh and configuration.
#   install_test.sh CMAKE BUILD_DIR SOURCE_DIR [cmake args for the consumer...]
set -euo pipefail
cmake_bin=$1 build=$2 source=$3
shift 3
mesh=/usr/share/assimp/models/PLY/Wuson.ply
L=4 N=3

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
prefix=$tmp/prefix
fail() { echo "install_consumer: $*" >&2; exit 1; }

"$cmake_bin" --install "$build" --prefix "$prefix" > "$tmp/install.log"

# What a consumer finds there.
for f in lib/libtessim_base.a lib/libtessim_model.a lib/libtessim_sim.a lib/libtessim_render.a \
         lib/cmake/tessim/tessimConfig.cmake lib/cmake/tessim/tessimConfigVersion.cmake \
         lib/cmake/tessim/tessimTargets.cmake include/tessim/model/mesh_io.hpp \
         include/tessim/model/base/error.hpp include/tessim/sim/run/simulate.hpp include/tessim/render/raster.hpp bin/tessim lib/tessim/tessim_imageio.so; do
  [ -e "$prefix/$f" ] || fail "$f was not installed"
done
# Nothing installed points back into the source or build tree.
if grep -rlF -e "$source" -e "$build" "$prefix/lib/cmake" "$prefix/include"; then
  fail "installed files name the source or build tree (above)"
fi

# Every installed header, against the installed include directory alone: no header needs one
# that was left out.
headers=$(cd "$prefix/include/tessim" && find . -name '*.hpp' -o -name '*.h' | sort)
for h in $headers; do echo "#include \"${h#./}\""; done > "$tmp/all_headers.cpp"
c++ -std=c++20 -fsyntax-only -I"$prefix/include/tessim" "$tmp/all_headers.cpp" \
  || fail "the installed headers do not compile on their own"

# The consumer, outside the source tree, against the package only.
cp -r "$source/tests/install/consumer" "$tmp/consumer"
"$cmake_bin" -S "$tmp/consumer" -B "$tmp/build" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_EXPORT_COMPILE_COMMANDS=ON "$@" > "$tmp/configure.log" || { cat "$tmp/configure.log"; fail "configure failed"; }
"$cmake_bin" --build "$tmp/build" -j2 > "$tmp/build.log" 2>&1 || { cat "$tmp/build.log"; fail "build failed"; }
# Its compile and link lines use the installed tree only.
if grep -lF -e "$source" -e "$build" "$tmp/build/compile_commands.json" "$tmp/build/CMakeFiles/consumer.dir/link.txt"; then
  fail "the consumer's compile or link line names the source or build tree (above)"
fi
grep -qF -- "-I$prefix/include/tessim" "$tmp/build/compile_commands.json" \
  || grep -qF -- "-isystem $prefix/include/tessim" "$tmp/build/compile_commands.json" \
  || fail "the consumer does not include from $prefix/include/tessim"

out=$("$tmp/build/consumer" "$mesh" $L $N "$tmp/picture.png")
echo "$out"
cli=$("$prefix/bin/tessim" sim "$mesh" -L $L --int-blocks $N)
echo "$cli"

cycles=$(sed -n 's/^cycles \([0-9]*\) vertices.*/\1/p' <<< "$out")
vertices=$(sed -n 's/^cycles [0-9]* vertices \([0-9]*\)$/\1/p' <<< "$out")
ref_vertices=$(sed -n 's/^reference \([0-9]*\) vertices.*/\1/p' <<< "$out")
cli_cycles=$(sed -n 's/^result *\([0-9]*\) cycles.*/\1/p' <<< "$cli")
cli_vertices=$(sed -n 's/^result *[0-9]* cycles *\([0-9]*\) vertices.*/\1/p' <<< "$cli")
[ -n "$cycles" ] && [ "$cycles" = "$cli_cycles" ] || fail "consumer: '$cycles' cycles, tessim sim: '$cli_cycles'"
[ -n "$vertices" ] && [ "$vertices" = "$cli_vertices" ] && [ "$ref_vertices" = "$cli_vertices" ] \
  || fail "vertices: consumer cycle model '$vertices', reference '$ref_vertices', tessim sim '$cli_vertices'"
# The installed RTL, in a tree built with it: the same cycles as the installed cycle model.
if [ -x "$tmp/build/rtl_consumer" ]; then
  "$tmp/build/rtl_consumer" "$mesh" 2 || fail "the installed RTL does not run as the cycle model"
elif [ -e "$prefix/lib/libtessim_rtl.a" ]; then
  fail "tessim::rtl is installed but find_package(tessim COMPONENTS rtl) did not find it"
fi
# The image writer was found through the package's tessim_IMAGEIO_PLUGIN.
[ "$(head -c 4 "$tmp/picture.png" | od -An -c | tr -d ' ')" = '211PNG' ] || fail "no PNG written"
echo "install_consumer: $cycles cycles, $vertices vertices, as tessim sim"
