#!/bin/sh
# bench/mutation.sh [BUILD]: the full mutation run of the conformance suite (docs/verification.md, "Mutation
# testing"). Configures BUILD (default build/) with -DVOXCD_MUTATION_FULL=ON, builds the mutants' schema
# (bench/mutation/generate.py: a seeded sample of single-point mutants of rtl/, each linted in every configuration of
# bench/mutation/configs.txt) with the tool and the tests that run it, runs every mutant through the suite's stages
# two at a time (bench/mutation/run.py) and writes the rows to bench/mutation/results.tsv and the summary to
# bench/mutation/summary.md (bench/mutation/report.py), which docs/verification.md quotes.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
build=${1:-$root/build}
start=$(date +%s)
cmake -S "$root" -B "$build" -DVOXCD_MUTATION_FULL=ON >/dev/null
cmake --build "$build" --target voxcd test_rtl mutation_models mutation_full_backend mutation_full_test_axi -j2
built=$(date +%s)
/usr/bin/python3 "$here/mutation/run.py" --mutants "$build/tests/mutation/mutation_full/mutants.tsv" \
  --configs "$here/mutation/configs.txt" --module "$build/mutation_full_backend.so" \
  --voxcd "$build/voxcd" --test-rtl "$build/test_rtl" --test-axi "$build/mutation_full_test_axi" \
  --models-check "$build/mutation_models" --vectors "$root/tests/vectors" \
  --out "$here/mutation/results.tsv"
end=$(date +%s)
/usr/bin/python3 "$here/mutation/report.py" "$here/mutation/results.tsv" "$here/mutation/equivalent.tsv" \
  --explained "$here/mutation/explained.tsv" --build-seconds $((built - start)) --run-seconds $((end - built)) > "$here/mutation/summary.md"
cat "$here/mutation/summary.md"
