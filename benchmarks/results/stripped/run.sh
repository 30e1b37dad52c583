#!/usr/bin/env bash
# Every benchmark scene with its method sections ([sph], [spfem], [spfem.implicit]) removed, run
# through sph and espfem at the smoke test's spacings (tests/benchmarks/smoke_benchmark_test.cpp;
# the footing at 0.25 for both):
# what the methods' defaults give on each scene, beside what the scene's own options give.
# Writes stripped.md here; one thread per run, two runs at a time.
set -u
cd "$(dirname "$0")/../../.."
out=runs/stripped; mkdir -p $out
./duet --help > /dev/null  # build once; the runs call the program itself (two `./duet` at once
duet=build/benchmarks/duet  # would both check the build)
cases="bar:0.01 cantilever:0.02 cantilever-2:0.02 oedometer:0.05 collapse:0.01 collapse-bui:0.01
  footing:0.25 footing-deep:0.25 cavity:0.5 strip-sand:0.125"
one() { scene=$1; dp=$2; method=$3; variant=$4; file=benchmarks/scenes/$scene.toml
  if [[ $variant == stripped ]]; then
    # The scene less its method tables (a table runs to the next header), written beside the runs
    # with its reference curve's relative path made absolute.
    file=$out/$scene-stripped.toml
    awk '/^\[/{skip = ($0 ~ /^\[(sph|spfem|spfem\.implicit)\]/)} !skip' \
      benchmarks/scenes/$scene.toml | sed "s#\"\.\./references/#\"$PWD/benchmarks/references/#" > $file
  fi
  OMP_NUM_THREADS=1 $duet run $file --method $method --spacing $dp \
    --out $out/$scene-$method-$variant > $out/$scene-$method-$variant.log 2>&1; }
for c in $cases; do
  scene=${c%%:*}; dp=${c##*:}
  for method in sph espfem; do
    one $scene $dp $method scene & one $scene $dp $method stripped; wait
  done
done
/usr/bin/python3 - "$out" > benchmarks/results/stripped/stripped.md <<'PY'
import json, pathlib, sys
out = pathlib.Path(sys.argv[1])
def cell(d):
    m = json.loads((d / "metrics.json").read_text())
    if m["status"] != "completed":
        return "failed at t = %.3g s: %s" % (m["end_time"], (m["failure"] or {}).get("reason", "")[:90])
    errs = [a["signed_error"] for a in m["accuracy"].values() if a.get("signed_error") is not None]
    worst = max(errs, key=abs) if errs else None
    text = "completed" + ("" if worst is None else ", worst %+.1f %%" % (100 * worst))
    if m["warnings"]: text += " (warned: %d)" % len(m["warnings"])
    return text
print("| scene | method | the scene's options | its method sections removed |")
print("|---|---|---|---|")
for d in sorted(out.glob("*-scene")):
    stripped = out / (d.name[:-len("scene")] + "stripped")
    scene, method = d.name[:-len("-scene")].rsplit("-", 1)
    print("| %s | %s | %s | %s |" % (scene, method, cell(d), cell(stripped)))
PY
cat benchmarks/results/stripped/stripped.md
