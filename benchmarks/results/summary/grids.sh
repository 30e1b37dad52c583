#!/usr/bin/env bash
# The compare grids behind summary.md / summary.png (benchmarks/RESULTS.md, "Accuracy against cost,
# every benchmark"): every run on one thread, the grids in two streams side by side (one per core
# of a 2-core machine; about 35 min of runs in all), then one summary.
set -u
cd "$(dirname "$0")/../../.."
# A grid whose folder already holds compare.csv is kept (rerun it by removing the folder).
grid() { out=$1; scene=$2; methods=$3; spacings=$4
  if [[ -f $out/$scene/compare.csv ]]; then echo "$out/$scene kept"; return; fi
  OMP_NUM_THREADS=1 ./duet compare benchmarks/scenes/$scene.toml --methods $methods \
    --spacings $spacings --target 0.05 --out $out/$scene > $out/$scene.log 2>&1
  echo "$(date +%T) $out/$scene done ($?)"; }
S=runs/summary; F=runs/summary-fine; mkdir -p $S $F
./duet --help > /dev/null  # build once, before the streams share the build folder
{
  grid $S oedometer sph,espfem,ispfem 0.05,0.025
  grid $S bar sph,espfem,ispfem 0.02,0.01
  grid $S cantilever sph,espfem,ispfem 0.02,0.01
  grid $S cantilever-2 sph,espfem,ispfem 0.02,0.01
  grid $S cantilever-3 sph,espfem,ispfem 0.02,0.01
  grid $S footing sph,espfem,ispfem 0.25,0.166667,0.125
  grid $F footing sph,espfem,ispfem 0.1
  grid $S footing-deep sph,espfem,ispfem 0.25
  grid $F footing-deep sph,espfem,ispfem 0.125
  grid $S strip-sand sph,espfem,ispfem 0.125,0.1
  grid $F strip-sand sph,espfem,ispfem 0.05
} &
{
  grid $S collapse sph,espfem 0.01,0.0075,0.005
  grid $S collapse-bui sph,espfem 0.01,0.0075,0.005
  grid $F collapse sph,espfem 0.0035
  grid $F collapse-bui sph,espfem 0.005,0.0035
  grid $S cavity sph,espfem,ispfem 0.5,0.35
  grid $F cavity espfem,ispfem 0.25
  grid $S footing-limit sph,espfem,ispfem 0.25
  grid $F footing-limit sph,espfem,ispfem 0.1
} &
wait
./duet summary $S/oedometer $S/bar $S/cantilever $S/cantilever-2 $S/cantilever-3 $S/footing \
  $F/footing $S/footing-limit $F/footing-limit $S/footing-deep $F/footing-deep $S/collapse $F/collapse $S/collapse-bui \
  $F/collapse-bui $S/cavity $F/cavity $S/strip-sand $F/strip-sand --out runs/summary-all
