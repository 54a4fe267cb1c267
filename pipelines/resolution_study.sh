#!/usr/bin/env bash
# Resolution judged by the debris answer (make -f Makefile.pipeline resolution-debris;
# docs/studies/resolution_by_debris.md).
#
# The real layout's ten 1 cm flows are the reference. Each grid of RESOLUTION_GRIDS is
# swept with the bodies on the 1 cm ground (the pipeline's default) and on the flows' own
# beds. The chaos floor: copies of the 1 cm flows with their fields kept to each of
# RESOLUTION_FLOOR_BITS significant bits (a change of at most 2^-(N+1) of each value),
# swept and counted the same way; a grid's difference is called real only beyond both the
# records' interval and that floor. Each copy is remade when its 1 cm flow is newer.
# Makes only what is missing, then writes the tables into $RUNS/resolution-debris.md, with
# the flows' errors at the debris' points against their cost ($RUNS/resolution-cost.png;
# the cost from the flows' make output, kept in $RUNS/flows-real-RES.make.log).
#
# Called by the make target, which sets MAKE, JOBS, RUNS, PYTHON, FLOTSAM, SWEEP_SPEC,
# REALISATIONS, RESOLUTION_GRIDS and RESOLUTION_FLOOR_BITS; the make target's command-line
# variables reach the inner makes through MAKEFLAGS.
set -eo pipefail
mk() { $MAKE -f Makefile.pipeline "$@"; }
omp_passive() { env OMP_WAIT_POLICY="${OMP_WAIT_POLICY:-passive}" "$@"; }

# The 1 cm reference flows, their sweep and statistics.
mk -j"$JOBS" real-scene flows RES=0.01 SCENE="$RUNS/real-0.01.nc" 2>&1 | tee -a "$RUNS/flows-real-0.01.make.log"
mk sweep stats RES=0.01 SCENE="$RUNS/real-0.01.nc"

# The chaos floor.
for b in $RESOLUTION_FLOOR_BITS; do
  d=$RUNS/flows-real-0.01-q$b; sweep=$RUNS/sweep-real-0.01-q$b.nc; stats=$RUNS/stats-real-0.01-q$b; mkdir -p "$d"
  for r in $REALISATIONS; do
    f=$RUNS/flows-real-0.01/flow_r$r.nc
    if [ ! "$d/flow_r$r.nc" -nt "$f" ]; then $PYTHON -m pipelines.subsample_flow "$f" 1 "$d/flow_r$r.nc" --keep-bits "$b"; fi
  done
  if [ ! -f "$stats.nc" ] || [ -n "$(find "$d" -name 'flow_r*.nc' -newer "$stats.nc")" ]; then
    omp_passive $FLOTSAM sweep --spec "$SWEEP_SPEC" --scene "$RUNS/real-0.01.nc" \
      $(for r in $REALISATIONS; do echo --flow "$d/flow_r$r.nc"; done) --threads "$JOBS" --quiet --out "$sweep"
    $FLOTSAM stats --sweep "$sweep" --scene "$RUNS/real-0.01.nc" --out "$stats.nc" --csv "$stats"
  fi
done

# The coarser grids, on the 1 cm ground and on their own beds.
for r in $RESOLUTION_GRIDS; do
  mk -j"$JOBS" real-scene flows RES="$r" SCENE="$RUNS/real-$r.nc" 2>&1 | tee -a "$RUNS/flows-real-$r.make.log"
  mk sweep stats RES="$r" SCENE="$RUNS/real-$r.nc" GROUND="$RUNS/real-0.01.nc"
  mk sweep stats RES="$r" SCENE="$RUNS/real-$r.nc" GROUND=
done

# The tables.
variants=""
for r in $RESOLUTION_GRIDS; do variants="$variants real-$r-on-real-0.01 real-$r"; done
floors=""
for b in $RESOLUTION_FLOOR_BITS; do floors="$floors real-0.01-q$b"; done
costs=()
for r in $RESOLUTION_GRIDS; do costs+=("$r m=$RUNS/flows-real-$r:$RUNS/flows-real-$r.make.log"); done
stats_args=()
for v in $variants; do stats_args+=("$v=$RUNS/stats-$v"); done
for b in $RESOLUTION_FLOOR_BITS; do stats_args+=(--floor "$b bits=$RUNS/stats-real-0.01-q$b"); done
{
  for v in $variants $floors; do
    for set in control all; do
      echo "### $v against 1 cm ($set)"; echo
      $PYTHON -m pipelines.resolution_debris --ref "$RUNS/sweep-real-0.01.nc" --test "$RUNS/sweep-$v.nc" --set $set; echo
    done
  done
  echo "### The flows against the 1 cm flows (error at the debris' points against processor s a flow)"; echo
  $PYTHON -m pipelines.resolution_cost "$RUNS/real-0.01.nc" "1 cm=$RUNS/flows-real-0.01:$RUNS/flows-real-0.01.make.log" \
    "${costs[@]}" --csv "$RUNS/resolution-cost.csv" --png "$RUNS/resolution-cost.png"; echo
  echo "### The paper's statistics"; echo
  $PYTHON -m pipelines.resolution_stats "1 cm=$RUNS/stats-real-0.01" "${stats_args[@]}"
} > "$RUNS/resolution-debris.md.part"
mv "$RUNS/resolution-debris.md.part" "$RUNS/resolution-debris.md"
cat "$RUNS/resolution-debris.md"
