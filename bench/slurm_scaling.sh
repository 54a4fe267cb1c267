#!/usr/bin/env bash
# How the ensemble and a sharded sweep scale with Slurm nodes (docs/cluster.md): the same
# flows and sweep here (make -j1, make -j2) and through a Slurm of 1 and 2 one-core nodes
# on this machine (tests/slurm/slurm_cluster.sh), with the wall time of each, and a check
# that all four give the same bytes. Figures printed, never asserted.
#
#   bench/slurm_scaling.sh [RES=0.04] [COUNT=4] [DURATION=120] [SHARDS=4] [MAKE VARIABLES...]
#   make -f Makefile.pipeline bench-slurm
#
# Needs Slurm's programs (make -f Makefile.pipeline test-slurm installs them) and a
# built flotsam; runs in a temporary folder (KEEP=1 keeps it).
set -uo pipefail
cd "$(dirname "$0")/.."
RES=${1:-0.04}
COUNT=${2:-4}
DURATION=${3:-120}
SHARDS=${4:-4}
shift $(($# < 4 ? $# : 4))
BUILD=${BUILD:-build}
. tests/slurm/slurm_cluster.sh
[ -x "$BUILD/flotsam" ] || { echo "slurm_scaling: build first (make -f Makefile.pipeline build)"; exit 1; }
[ -z "$(slurm_programs_missing)" ] || { echo "slurm_scaling: Slurm is not installed:$(slurm_programs_missing)"; exit 1; }

T=$(mktemp -d "${TMPDIR:-/tmp}/flotsam-scaling.XXXXXX")
chmod 755 "$T"
cleanup() {
    for c in "$T"/cluster-*; do [ -d "$c" ] && slurm_down "$c"; done
    if [ "${KEEP:-0}" = 1 ]; then echo "kept $T"; else rm -rf "$T"; fi
}
trap cleanup EXIT
trap 'exit 130' INT TERM

RUNS=$T/runs
MK=(make --no-print-directory -s -f Makefile.pipeline -o build BUILD="$BUILD" RUNS="$RUNS" RES="$RES" COUNT="$COUNT"
    DURATION="$DURATION" THREADS=1 SHARD_THREADS=1 "$@")
"${MK[@]}" scene boundaries >/dev/null || exit 1
OUT=(flows-$RES sweep-$RES.nc sweep-$RES.csv)

# run LABEL MAKE-ARGS...: the flows, then the sweep in SHARDS shards; prints both wall times.
run() {
    local label=$1 t0 t1 t2
    shift
    rm -rf "$RUNS/flows-$RES" "$RUNS"/sweep-"$RES"*
    t0=$(date +%s.%N)
    "${MK[@]}" "$@" flows >"$T/$label.log" 2>&1 || { echo "$label: the flows failed (log: $T/$label.log)"; KEEP=1; return 1; }
    t1=$(date +%s.%N)
    "${MK[@]}" "$@" SHARDS="$SHARDS" sweep >>"$T/$label.log" 2>&1 || { echo "$label: the sweep failed"; KEEP=1; return 1; }
    t2=$(date +%s.%N)
    mkdir -p "$T/out-$label"
    for o in "${OUT[@]}"; do cp -r "$RUNS/$o" "$T/out-$label/"; done
    # The flows' own wall and processor seconds (their last line) against the makespan:
    # how many ran at once, and how many cores they got (on a shared machine, fewer).
    grep -h "complete after" "$T/$label.log" | sed -E 's/.* in ([0-9.]+) s wall \(([0-9.]+) s processor\).*/\1 \2/' |
        awk -v label="$label" -v n="$COUNT" -v span="$(awk "BEGIN { print $t1 - $t0 }")" -v shards="$SHARDS" \
            -v sweep="$(awk "BEGIN { print $t2 - $t1 }")" \
            '{ wall += $1; cpu += $2 } END { printf "%-26s %3d flows %7.1f s (%4.2f at once, %4.2f cores; %5.1f processor s)   sweep in %d shards %6.1f s\n", label, n, span, wall / span, cpu / span, cpu, shards, sweep }'
}

echo "slurm_scaling: $COUNT flows at $RES m, $DURATION s, one thread each; the sweep ${SHARDS} shards of tests/slurm/sweep.toml"
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
run "here, make -j1" -j1 SWEEP_SPEC=tests/slurm/sweep.toml
run "here, make -j2" -j2 SWEEP_SPEC=tests/slurm/sweep.toml
for nodes in 1 2; do
    slurm_up "$T/cluster-$nodes" "$nodes" 1 2>/dev/null || { echo "Slurm with $nodes node(s) did not start"; exit 1; }
    run "Slurm, $nodes node(s) x 1 core" -j$((2 * COUNT)) LAUNCH=srun SWEEP_SPEC=tests/slurm/sweep.toml
    slurm_down "$T/cluster-$nodes"
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
same=yes
for d in "$T"/out-*; do diff -r -q "$T/out-here, make -j1" "$d" >/dev/null || { same=no; echo "differs: $d"; }; done
echo "same bytes in all four: $same"
