#!/bin/bash
# The hydro speed levers at the production setting, each against the 1 cm reference
# (docs/studies/hydro_speed_levers.md).
#
# Usage: pipelines/hydro_levers.sh FLOTSAM DEM RUNS_DIR [BASELINE_FLOW]
#
# Real layout, pump forcing, 0-150 s, nested 4:1 west of x = -1.2 m (the scene's
# recommended grids), one thread per flow, run one after another. Each lever is one
# flow at 2 cm (and the 1 cm ensemble's setting at 1 cm); the reference is the 1 cm flow
# with Heun steps, plain fronts and float64 state (about 40 processor minutes). BASELINE_FLOW, a 2 cm flow of another build made with the same
# forcing (pipelines/speed_ratio.py leaves one), joins the error tables. Writes
# RUNS_DIR/levers/{cost.txt,flow_error.csv,debris_error.csv}.
set -euo pipefail
[ $# -ge 3 ] || { echo "usage: $0 FLOTSAM DEM RUNS_DIR [BASELINE_FLOW]" >&2; exit 2; }
flotsam=$(realpath "$1"); dem=$2; out=$3/levers; baseline=${4:-}
python=${PYTHON:-/usr/bin/python3}
mkdir -p "$out"
for res in 0.01 0.02; do
  [ -f "$out/real-$res.nc" ] || "$flotsam" scene import --dem "$dem" --resolution $res --out "$out/real-$res.nc" >/dev/null
done
flow() {  # name resolution options...
  local name=$1 res=$2; shift 2
  [ -f "$out/$name.nc" ] && return
  /usr/bin/time -f "$name %U %S" -a -o "$out/cost.txt" "$flotsam" hydro --scene "$out/real-$res.nc" --west pump \
    --duration 150 --threads 1 --quiet --out "$out/$name.nc" "$@"
}
# Every option a lever changes is given, so the names say the same whatever the default.
f64="--precision float64"
flow reference-1cm 0.01 --time-stepping heun $f64
flow split-f32 0.02 --precision float32
flow split-f32-cfl0.9 0.02 --precision float32 --cfl 0.9
flow split-f64 0.02 $f64
flow split-f64-cfl0.9 0.02 $f64 --cfl 0.9
flow split-f64-dry1e-9 0.02 $f64 --dry-depth 1e-9
flow heun-plain 0.02 --time-stepping heun $f64
flow heun-tracked 0.02 --time-stepping heun --fronts tracked --dry-depth 1e-9 $f64
# The 1 cm flow as the ensemble at RES=0.01 runs it (split steps, float32).
flow split-f32-1cm 0.01 --precision float32
levers="split-f32 split-f32-cfl0.9 split-f64 split-f64-cfl0.9 split-f64-dry1e-9 heun-plain heun-tracked split-f32-1cm"
flows=$(for l in $levers; do echo "$out/$l.nc"; done)
[ -n "$baseline" ] && flows="$flows $baseline"
PYTHONPATH=. "$python" -m pipelines.flow_error "$out/real-0.01.nc" "$out/reference-1cm.nc" $flows > "$out/flow_error.csv"
# The debris answer: 25 floating boxes on a 5 x 5 grid 5 cm apart around FD's start, on
# the 1 cm ground, through each flow and through the reference.
at=$(for x in 1.27 1.32 1.37 1.42 1.47; do for y in -2.25 -2.20 -2.15 -2.10 -2.05; do echo "--at $x,$y,0"; done; done)
"$flotsam" debris --flow "$out/reference-1cm.nc" --scene "$out/real-0.01.nc" $at --quiet --out "$out/reference-1cm.traj.nc"
# The chaos floor: the same boxes started 1 mm further east, in the reference flow.
shifted=$(for x in 1.271 1.321 1.371 1.421 1.471; do for y in -2.25 -2.20 -2.15 -2.10 -2.05; do echo "--at $x,$y,0"; done; done)
"$flotsam" debris --flow "$out/reference-1cm.nc" --scene "$out/real-0.01.nc" $shifted --quiet \
  --out "$out/reference-1cm-shift1mm.traj.nc"
trajs="$out/reference-1cm-shift1mm.traj.nc"
for f in $flows; do
  t="$out/$(basename "$f" .nc).traj.nc"
  case $f in
    *-1cm.nc) "$flotsam" debris --flow "$f" --scene "$out/real-0.01.nc" $at --quiet --out "$t" ;;
    *) "$flotsam" debris --flow "$f" --scene "$out/real-0.02.nc" --ground "$out/real-0.01.nc" $at --quiet --out "$t" ;;
  esac
  trajs="$trajs $t"
done
PYTHONPATH=. "$python" -m pipelines.debris_error "$out/reference-1cm.traj.nc" $trajs > "$out/debris_error.csv"
cat "$out/cost.txt" "$out/flow_error.csv" "$out/debris_error.csv"
