#!/usr/bin/env bash
# The installed package as its users meet it: installs the build into a fresh prefix, moves the prefix elsewhere
# (nothing may refer to the build or source tree), then builds and runs every example of docs/examples against it,
# out of tree: the C++ program (CMake and pkg-config), the SystemC sc_main, the DPI-C testbench and the Python
# script, and runs the installed tool. Exits non-zero at the first failure, saying which.
#   bash tests/install/consumers.sh BUILD_DIR WORK_DIR [--cost]
# --cost also synthesises a scene's device with the installed tool (`voxcd size --cost`, yosys; about a minute):
# the RTL must come from the installed share/voxcd/rtl.
set -euo pipefail
build=$(cd "$1" && pwd)
work=$2
cost=${3:-}
src=$(cd "$(dirname "$0")/../.." && pwd)
rm -rf "$work" && mkdir -p "$work"
work=$(cd "$work" && pwd)
step() { echo "== consumers: $*"; }
fail() { echo "consumers: FAILED: $*" >&2; exit 1; }
export SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=1

step "cmake --install $build --prefix $work/staging, then moved to $work/prefix"
cmake --install "$build" --prefix "$work/staging" >/dev/null
mv "$work/staging" "$work/prefix"
P=$work/prefix
# The package's text files must not name the build tree, the source tree or the staging prefix.
if grep -rlI -e "$build" -e "$src/" -e "$work/staging" "$P/lib/cmake" "$P/lib/pkgconfig" "$P/include" "$P/share"; then
  fail "the files above refer to the build or source tree"
fi
[ -e "$P/include/voxcd/voxcd.h" ] || fail "no umbrella header include/voxcd/voxcd.h"
if find "$P/include" -path '*detail*' -o -name server_protocol.h -o -path '*/cli/*' | grep -q .; then
  fail "internal headers were installed: $(find "$P/include" -path '*detail*' -o -name server_protocol.h -o -path '*/cli/*')"
fi

step "the public headers: each includes only installed headers and compiles on its own"
inc="$P/include"
while IFS= read -r h; do
  rel=${h#"$inc/"}
  while IFS= read -r dep; do
    [ -e "$inc/$dep" ] || fail "$rel includes $dep, which is not installed (an internal header)"
  done < <(sed -n 's/^#include "\(voxcd\/[^"]*\)".*/\1/p' "$h")
  case "$rel" in
    voxcd/sysc/*) flags=$(pkg-config --cflags systemc) ;;
    *) flags="" ;;
  esac
  # shellcheck disable=SC2086
  echo "#include <$rel>" | c++ -std=c++17 -fsyntax-only -I"$inc" -isystem /usr/include/eigen3 $flags -x c++ - ||
    fail "$rel does not compile on its own"
done < <(find "$inc" -name '*.h')
# The umbrella includes the public API and nothing of the library's inside.
if grep -n '#include "voxcd/host/\(object/\(voxelize\|object_type\|object_file\)\|scene/scene\|pairs/\(collide\|collider\|image\|contacts\)\|regress\|sizing\)' "$inc/voxcd/voxcd.h"; then
  fail "the umbrella header includes an internal header"
fi

step "the installed tool"
"$P/bin/voxcd" --version | tee "$work/version.txt"
# Every backend of a full build is installed ready: the rtl backend's module from lib/voxcd, the server from libexec.
for b in ref cpu rtl sysc-rtl sysc-tlm; do
  grep -Eq "^  $b +ready\$" "$work/version.txt" || fail "the installed $b backend is not ready (voxcd --version above)"
done
"$P/bin/voxcd" conform --generate --seed 3 --jobs 20 -o "$work/generated.vec" >/dev/null
"$P/bin/voxcd" conform --backend rtl --cycles "$work/generated.vec" | grep -q "^1 passed, 0 failed" || fail "voxcd conform --backend rtl"
"$P/bin/voxcd" simulate --frames 3 --objects 32 | grep -q "state hash" || fail "voxcd simulate"
if "$P/bin/voxcd" conform --help >/dev/null 2>&1 && [ -x "$P/libexec/voxcd/voxcd_sysc_server" ]; then
  "$P/bin/voxcd" simulate --frames 2 --objects 16 --backend sysc-tlm | grep -q "state hash" ||
    fail "voxcd simulate --backend sysc-tlm (the server in libexec/voxcd)"
fi

if [ "$cost" = --cost ]; then
  step "voxcd size --cost with the installed RTL"
  out=$("$P/bin/voxcd" size "$src/tests/scenes/small.json" --cost)
  echo "$out" | grep -E "^cost .*LUTs" || fail "voxcd size --cost printed no cost: $out"
fi

step "C++ example with CMake (find_package(voxcd), voxcd::host)"
cmake -S "$src/docs/examples/cpp" -B "$work/cpp" -G Ninja -DCMAKE_PREFIX_PATH="$P" >/dev/null
cmake --build "$work/cpp" >/dev/null
"$work/cpp/contacts" >/dev/null
"$work/cpp/world"
(cd "$work" && "$work/cpp/errors" >/dev/null) ||
  fail "docs/examples/cpp/errors.cpp: an error was not caught by its name"

step "C++ example with pkg-config"
export PKG_CONFIG_PATH="$P/lib/pkgconfig"
# shellcheck disable=SC2046
c++ -std=c++17 -O1 -o "$work/contacts_pc" "$src/docs/examples/cpp/contacts.cpp" $(pkg-config --cflags --libs voxcd)
"$work/contacts_pc" >/dev/null

grep -q "voxcd::sysc" "$P/lib/cmake/voxcd/voxcdTargets.cmake" || fail "the installed package has no voxcd::sysc"
step "SystemC example (voxcd::sysc, the TLM target through the address map)"
cmake -S "$src/docs/examples/systemc" -B "$work/systemc" -G Ninja -DCMAKE_PREFIX_PATH="$P" >/dev/null
cmake --build "$work/systemc" >/dev/null
"$work/systemc/platform"

grep -q "voxcd::dpi" "$P/lib/cmake/voxcd/voxcdTargets.cmake" || fail "the installed package has no voxcd::dpi"
{
  step "DPI-C testbench (voxcd::dpi, share/voxcd/rtl)"
  cmake -S "$src/docs/examples/dpi" -B "$work/dpi" -G Ninja -DCMAKE_PREFIX_PATH="$P" >/dev/null
  cmake --build "$work/dpi" -j2 >/dev/null
  ran=0
  for tb in "$work"/dpi/tb_*; do
    [ -x "$tb" ] && [ -f "$tb" ] || continue
    "$tb" && ran=1
  done
  [ $ran = 1 ] || fail "no DPI testbench was built in $work/dpi"
}

pydir=$(find "$P" -type d -name dist-packages | head -n 1)
[ -n "$pydir" ] && ls "$pydir"/voxcd*.so >/dev/null 2>&1 || fail "the installed package has no Python module under $P"
[ -e "$pydir/voxcd.pyi" ] || fail "the installed package has no type stubs voxcd.pyi beside the Python module"
step "Python module from $pydir"
PYTHONPATH="$pydir" /usr/bin/python3 -c "import voxcd; print(voxcd.__version__, voxcd.backends())"
ran=0
for script in "$src"/docs/examples/python/*.py; do
  (cd "$work" && PYTHONPATH="$pydir" /usr/bin/python3 "$script" >/dev/null) || fail "$script"
  ran=1
done
[ $ran = 1 ] || fail "no Python example in $src/docs/examples/python"
echo "consumers: every example built and ran against $P"
