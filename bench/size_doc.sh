#!/usr/bin/env bash
# bench/size_doc.sh: regenerates the worked example, the accuracy sweep, the contact-accuracy sweep and the depth
# choices of docs/size.md by running voxcd size on tests/scenes/mixed.json (the example at 10,000 frames/s with --cost:
# two yosys runs, about a minute; the depth choice with --cost maps onto the OSU 0.18 um cells, about a minute), and
# the choice of dense or sparse storage on tests/scenes/large.json and paper.json.
# Usage: bash bench/size_doc.sh [BUILD_DIR]   (default build/)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
voxcd="$build/voxcd"
cd "$root"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
{
  echo '```'
  args=(size tests/scenes/mixed.json --rate 10000 --cost)
  echo "\$ build/voxcd ${args[*]}"
  "$voxcd" "${args[@]}"
  echo '```'
} >"$tmp/example.md"
{
  echo '```'
  for a in 0.1 0.03 0.01 0.003 0.001; do
    echo "\$ build/voxcd size tests/scenes/mixed.json --accuracy $a | grep -E '^(configuration|error) '"
    "$voxcd" size tests/scenes/mixed.json --accuracy "$a" | grep -E '^(configuration|error) '
  done
  echo '```'
} >"$tmp/accuracy.md"
{
  echo '```'
  for c in 2 0.5 0.3 0.25 0.1; do
    echo "\$ build/voxcd size tests/scenes/mixed.json --contact-accuracy $c | grep -E '^(configuration|contacts|memory|frame rate) '"
    "$voxcd" size tests/scenes/mixed.json --contact-accuracy "$c" 2>&1 | grep -E '^(configuration|contacts|memory|frame rate) |cannot be met' || true
  done
  echo '```'
} >"$tmp/contact.md"
{
  echo '```'
  for a in "--clock 50 --target asic-osu018 --cost" "--clock 40 --target ice40-hx8k" "--clock 100 --target xilinx-7" \
           "--clock 250 --target asic-osu018"; do
    echo "\$ build/voxcd size tests/scenes/mixed.json $a | grep -E '^(configuration|frame rate|latency|depth|area|block RAMs) '"
    # shellcheck disable=SC2086
    "$voxcd" size tests/scenes/mixed.json $a 2>&1 | grep -E '^(configuration|frame rate|latency|depth|area|block RAMs) |cannot be met' || true
  done
  echo '```'
} >"$tmp/target.md"
{
  echo '```'
  echo "\$ build/voxcd size tests/scenes/large.json"
  "$voxcd" size tests/scenes/large.json
  for a in "tests/scenes/large.json --storage dense" "tests/scenes/paper.json" \
           "tests/scenes/paper.json --contact-accuracy 1"; do
    echo "\$ build/voxcd size $a | grep -E '^(configuration|storage) '"
    # shellcheck disable=SC2086
    "$voxcd" size $a | grep -E '^(configuration|storage) '
  done
  echo '```'
} >"$tmp/storage.md"
bash bench/splice.sh docs/size.md size-example "$tmp/example.md"
bash bench/splice.sh docs/size.md size-storage "$tmp/storage.md"
bash bench/splice.sh docs/size.md size-target "$tmp/target.md"
bash bench/splice.sh docs/size.md size-contact "$tmp/contact.md"
bash bench/splice.sh docs/size.md size-accuracy "$tmp/accuracy.md"
