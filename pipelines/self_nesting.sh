#!/bin/bash
# Nesting flotsam in itself: a run over a box of the real layout, its sides forced by the
# outline that a coarser run over the whole flume wrote (--boundary-output), against one
# fine run over the whole flume (docs/gis.md, "Forcing from a regional model").
#
# Usage: pipelines/self_nesting.sh FLOTSAM DEM SERIES RUNS_DIR [COARSE FINE DURATION BOX]
#
# SERIES is a WG1 record (runs/bc/wg1_r00.csv) driving the west side of the whole flume as
# a total level; COARSE and FINE are the grid spacings [m] (0.04 and 0.02), DURATION the
# simulated time [s] (150), BOX x0,x1,y0,y1 [m] on the fine grid's cell edges
# (-1.005,8.005,-3.505,-0.005: the city, its west side in the flume's water, its south side
# across the port entrance). Three flows, one thread each, run one after another:
#   coarse  the whole flume at COARSE, writing the box's outline every 0.05 s
#   box     the box alone at FINE, west and south sides forced by that outline
#   fine    the whole flume at FINE (the reference)
# and 25 floating boxes around FD's start replayed through each. Writes
# RUNS_DIR/self-nesting/{cost.txt,flow_error.csv,debris_error.csv} and checks the box run
# against the tolerances of pipelines/nesting_check.py (exit 1 when one is passed).
set -euo pipefail
[ $# -ge 4 ] || { echo "usage: $0 FLOTSAM DEM SERIES RUNS_DIR [COARSE FINE DURATION BOX]" >&2; exit 2; }
flotsam=$(realpath "$1"); dem=$2; series=$3; out=$4/self-nesting
coarse=${5:-0.04}; fine=${6:-0.02}; duration=${7:-150}; box=${8:--1.005,8.005,-3.505,-0.005}
python=${PYTHON:-/usr/bin/python3}
mkdir -p "$out"
scene() {  # name resolution [options]
  local name=$1 res=$2; shift 2
  [ -f "$out/$name.nc" ] || "$flotsam" scene import --dem "$dem" --resolution "$res" --out "$out/$name.nc" "$@" >/dev/null
}
scene coarse-scene "$coarse"
scene fine-scene "$fine"
scene box-scene "$fine" --extent "$box" --crs local
flow() {  # name scene options...
  local name=$1 scene=$2; shift 2
  [ -f "$out/$name.nc" ] && return
  /usr/bin/time -f "$name %U %S" -a -o "$out/cost.txt" "$flotsam" hydro --scene "$out/$scene.nc" --duration "$duration" \
    --threads 1 --quiet --out "$out/$name.nc" "$@"
}
flow coarse coarse-scene --west-series "$series" --boundary-output "$out/outline.nc" --boundary-box "$box"
flow box box-scene --west-forcing "$out/outline.nc" --south-forcing "$out/outline.nc"
flow fine fine-scene --west-series "$series"
PYTHONPATH=. "$python" -m pipelines.flow_error --box "$box" "$out/fine-scene.nc" "$out/fine.nc" "$out/coarse.nc" "$out/box.nc" \
  > "$out/flow_error.csv"
at=$(for x in 1.27 1.32 1.37 1.42 1.47; do for y in -2.25 -2.20 -2.15 -2.10 -2.05; do echo "--at $x,$y,0"; done; done)
for f in fine coarse box; do
  [ -f "$out/$f.traj.nc" ] || "$flotsam" debris --flow "$out/$f.nc" --scene "$out/$f-scene.nc" $at --quiet \
    --out "$out/$f.traj.nc"
done
PYTHONPATH=. "$python" -m pipelines.debris_error "$out/fine.traj.nc" "$out/coarse.traj.nc" "$out/box.traj.nc" \
  --times 30,60,"$duration" > "$out/debris_error.csv"
cat "$out/cost.txt" "$out/flow_error.csv" "$out/debris_error.csv"
PYTHONPATH=. "$python" -m pipelines.nesting_check "$out/flow_error.csv" "$out/fine.nc" --debris "$out/debris_error.csv"
