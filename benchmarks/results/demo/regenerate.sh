#!/usr/bin/env bash
# Runs `./duet demo` and copies what it prints into README.md: the block between the
# <!-- demo:begin --> and <!-- demo:end --> lines is this folder's compare.md as the demo wrote it,
# less its title line (tests/benchmarks/readme_demo_test.cpp checks that the two agree). Also keeps the demo's
# charts here. Usage: benchmarks/results/demo/regenerate.sh (from anywhere; about a minute).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../../.." && pwd)"
out="$root/runs/demo"
rm -rf "$out"
"$root/duet" demo --out "$out" > /dev/null
cp "$out/compare.md" "$out/compare.png" "$out/snapshots_equivalent_strain.png" "$here/"
/usr/bin/python3 - "$root/README.md" "$here/compare.md" <<'PY'
import sys
readme, table = sys.argv[1], sys.argv[2]
text = open(readme).read()
begin, end = "<!-- demo:begin -->\n", "<!-- demo:end -->"
head, rest = text.split(begin, 1)
_, tail = rest.split(end, 1)
# compare.md less its own title line: the README's paragraph introduces it
body = open(table).read().split("\n", 1)[1].lstrip("\n")
open(readme, "w").write(head + begin + body.rstrip("\n") + "\n" + end + tail)
PY
echo "README.md's demo block and $here regenerated"
