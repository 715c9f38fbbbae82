#!/usr/bin/env bash
# Replaces the lines between `<!-- bench:NAME:begin -->` and `<!-- bench:NAME:end -->` in DOC with FILE.
# Usage: bash bench/splice.sh DOC NAME FILE
set -euo pipefail
[ $# -eq 3 ] || { echo "usage: bash bench/splice.sh DOC NAME FILE" >&2; exit 2; }
doc=$1 name=$2 file=$3
begin="<!-- bench:$name:begin -->"
end="<!-- bench:$name:end -->"
grep -qF "$begin" "$doc" && grep -qF "$end" "$doc" || { echo "$doc lacks the markers $begin ... $end" >&2; exit 1; }
[ -s "$file" ] || { echo "$file is empty: $doc left as it was" >&2; exit 1; }
tmp=$(mktemp)
awk -v b="$begin" -v e="$end" -v f="$file" '
  $0 == b { print; while ((getline line < f) > 0) print line; skip = 1; next }
  $0 == e { skip = 0 }
  !skip { print }' "$doc" > "$tmp"
mv "$tmp" "$doc"
echo "wrote $doc ($name)"
