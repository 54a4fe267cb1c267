#!/usr/bin/env bash
# The pipeline on a real Slurm, run by `make -f Makefile.pipeline test`.
#
# Brings up a two-node Slurm on this machine from Debian's packages (installed if missing,
# as root), then, on a coarse generated scene (16 cm, three boundary records):
#   1. the ensemble and the sweep here (LAUNCH empty): the reference bytes;
#   2. the same through Slurm (LAUNCH=srun, the sweep in SHARDS=3 jobs, merged), with one
#      flow's job cancelled while it runs (a lost node): make stops naming it and leaves no
#      finished-looking file; the rerun redoes that flow only; every output is then
#      byte-identical to step 1;
#   3. a member with a bad boundary record: make stops naming the member and the file;
#   4. a flow in a batch job (LAUNCH=sbatch, FLOW_CHECKPOINT) requeued while it runs: it
#      continues from its checkpoint and ends with the bytes of an uninterrupted run.
# The flows of step 2 checkpoint too (FLOW_CHECKPOINT), and the lost one continues from
# its checkpoint when make runs again.
# Slurm is shut down at the end, also on failure. Skipped (exit 0, with the reason) only
# where Slurm cannot be had at all: its programs are missing and cannot be installed.
#
#   tests/slurm/run_slurm_test.sh            # BUILD=build; KEEP=1 keeps the temporary folder
set -uo pipefail
cd "$(dirname "$0")/../.."
REPO=$(pwd)
BUILD=${BUILD:-build}
FLOTSAM=$BUILD/flotsam
started=$(date +%s)
passed=0
failed=0

say() { echo "slurm test: $*"; }
elapsed() { echo "$(($(date +%s) - started)) s"; }
ok() {
    say "ok   $1 ($(elapsed))"
    passed=$((passed + 1))
}
bad() {
    say "FAIL $1"
    failed=$((failed + 1))
}
# check NAME COMMAND...: one assertion.
check() {
    local name=$1
    shift
    if "$@"; then
        ok "$name"
    else
        bad "$name"
        return 1
    fi
}
# running_with_checkpoint JOB_NAME CHECKPOINT: prints the id of the running job of that
# name once the checkpoint exists (nothing after a minute without).
running_with_checkpoint() {
    local id
    for _ in $(seq 1 1200); do
        id=$(squeue -h -n "$1" -t RUNNING -o %i 2>/dev/null)
        [ -n "$id" ] && [ -e "$2" ] && echo "$id" && return 0
        sleep 0.05
    done
    return 1
}
skip() {
    say "SKIPPED: $*"
    echo "slurm: 0 passed, 0 failed, 1 skipped"
    exit 0
}

. "$REPO/tests/slurm/slurm_cluster.sh"

# ---- Slurm's programs: Debian's packages, installed when missing ----
PACKAGES="munge slurmctld slurmd slurm-client"
if [ -n "$(slurm_programs_missing)" ]; then
    SUDO=""
    if [ "$(id -u)" != 0 ]; then
        sudo -n true 2>/dev/null || skip "Slurm is not installed ($PACKAGES) and this user can neither install it (not root, no sudo)"
        SUDO="sudo -n"
    fi
    say "installing $PACKAGES"
    install() { DEBIAN_FRONTEND=noninteractive $SUDO apt-get -o DPkg::Lock::Timeout=120 install -y -qq --no-install-recommends $PACKAGES >"${TMPDIR:-/tmp}/flotsam-slurm-apt.log" 2>&1; }
    install || { $SUDO apt-get update -qq >/dev/null 2>&1 && install; } ||
        skip "apt-get could not install $PACKAGES (see ${TMPDIR:-/tmp}/flotsam-slurm-apt.log)"
    [ -z "$(slurm_programs_missing)" ] || skip "still missing after the install:$(slurm_programs_missing)"
    say "installed ($(elapsed))"
fi
[ -x "$FLOTSAM" ] || {
    say "FAIL: $FLOTSAM is missing: build first (make -f Makefile.pipeline build)"
    exit 1
}

T=$(mktemp -d "${TMPDIR:-/tmp}/flotsam-slurm.XXXXXX")
chmod 755 "$T" # munged's socket lies below it
cleanup() {
    slurm_down "$T/cluster"
    if [ "${KEEP:-0}" = 1 ]; then say "kept $T"; else rm -rf "$T"; fi
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# Two nodes of one core each (two slurmd on this host): jobs of one make land on both.
slurm_up "$T/cluster" 2 1 || {
    bad "Slurm did not start (logs above)"
    echo "slurm: $passed passed, $failed failed"
    exit 1
}
ok "Slurm is up: $(sinfo -h -N -o '%N %T' | tr '\n' ' ')"

RUNS=$T/runs
MK=(make --no-print-directory -f Makefile.pipeline -o build -o tool BUILD="$BUILD" RUNS="$RUNS" RES=0.16 COUNT=3 DURATION=300
    NEST_RATIO=1 THREADS=1 SWEEP_SPEC=tests/slurm/sweep.toml)
FLOWS_DIR=$RUNS/flows-0.16
OUTPUTS=(flows-0.16/flow_r00.nc flows-0.16/flow_r01.nc flows-0.16/flow_r02.nc sweep-0.16.nc sweep-0.16.csv)

# ---- 1. here: the reference bytes ----
"${MK[@]}" scene boundaries >"$T/setup.log" 2>&1 || {
    cat "$T/setup.log"
    bad "scene and boundary records"
}
"${MK[@]}" -j2 flows sweep >"$T/local.log" 2>&1
check "the ensemble and the sweep here" test $? = 0 || tail -n 30 "$T/local.log"
mkdir -p "$T/local"
for f in "${OUTPUTS[@]}"; do mv "$RUNS/$f" "$T/local/$(basename "$f")" 2>/dev/null; done

# ---- 2. through Slurm, with one flow's job lost ----
# Checkpoints every 30 s of simulated time (not part of the output's bytes).
"${MK[@]}" LAUNCH=srun FLOW_CHECKPOINT=30 -j3 flows >"$T/slurm1.log" 2>&1 &
make_pid=$!
# Cancel r01's job once it has written a checkpoint, as a lost node would end it.
job=$(running_with_checkpoint flow-0.16-r01 "$FLOWS_DIR/flow_r01.nc.checkpoint.nc")
[ -n "$job" ] && scancel "$job"
wait $make_pid
status=$?
check "a cancelled flow job stops make (status $status)" test "$status" != 0 -a -n "$job"
check "make names the lost member" grep -q "flow_r01.nc\] Error" "$T/slurm1.log"
check "the lost member left no finished-looking file" test ! -e "$FLOWS_DIR/flow_r01.nc"
before=$(stat -c '%n %Y %i' "$FLOWS_DIR"/flow_r0[02].nc 2>/dev/null)
"${MK[@]}" LAUNCH=srun FLOW_CHECKPOINT=30 SHARDS=3 -j3 flows sweep >"$T/slurm2.log" 2>&1
check "the rerun through Slurm: flows and a sweep in 3 shards" test $? = 0 || tail -n 30 "$T/slurm2.log"
check "the rerun continued the lost member from its checkpoint" grep -q -- "--out $FLOWS_DIR/flow_r01.nc.*--restart" "$T/slurm2.log"
redone=$(grep -c -E -- "--out $FLOWS_DIR/flow_r0[02].nc" "$T/slurm2.log")
check "the rerun redid nothing else ($redone other flows)" test "$redone" = 0 \
    -a "$before" = "$(stat -c '%n %Y %i' "$FLOWS_DIR"/flow_r0[02].nc 2>/dev/null)"
check "the shards ran as Slurm jobs" grep -q -- "--job-name=sweep-0.16-2of3 .*--shard 2/3" "$T/slurm2.log"
nodes=$(grep -o "NodeList=n[0-9]" "$T/cluster/log/slurmctld.log" | sort -u | tr '\n' ' ')
check "jobs ran on both nodes ($nodes)" test "$(wc -w <<<"$nodes")" = 2
same=0
for f in "${OUTPUTS[@]}"; do
    if cmp -s "$T/local/$(basename "$f")" "$RUNS/$f"; then same=$((same + 1)); else say "differs: $f"; fi
done
check "Slurm's outputs are the local bytes ($same of ${#OUTPUTS[@]} files)" test "$same" = ${#OUTPUTS[@]}

# ---- 3. a member with a bad input ----
BAD=$T/bad
mkdir -p "$BAD/bc"
cp -p "$RUNS/scene-0.16.nc" "$BAD/"
cp -p "$RUNS"/bc/*.csv "$BAD/bc/"
sed -i '5s/.*/12.0,not-a-number/' "$BAD/bc/wg1_r01.csv"
"${MK[@]}" RUNS="$BAD" DURATION=20 LAUNCH=srun -j3 flows >"$T/bad.log" 2>&1
status=$?
check "a bad member fails the make (status $status)" test "$status" != 0
check "make names the bad member" grep -q "flow_r01.nc\] Error" "$T/bad.log"
check "the error names the file and line" grep -q "wg1_r01.csv.*5" "$T/bad.log"
check "the bad member left no finished-looking file" test ! -e "$BAD/flows-0.16/flow_r01.nc"
check "the good members finished" test -e "$BAD/flows-0.16/flow_r00.nc" -a -e "$BAD/flows-0.16/flow_r02.nc"
grep -q "flow_r01.nc\] Error" "$T/bad.log" || tail -n 20 "$T/bad.log"

# ---- 4. a flow in a batch job, requeued (preempted) while it runs ----
mv "$FLOWS_DIR/flow_r02.nc" "$T/flow_r02.first.nc"
"${MK[@]}" LAUNCH=sbatch FLOW_CHECKPOINT=20 "$FLOWS_DIR/flow_r02.nc" >"$T/requeue.log" 2>&1 &
make_pid=$!
job=$(running_with_checkpoint flow-0.16-r02 "$FLOWS_DIR/flow_r02.nc.checkpoint.nc")
requeued=no
if [ -n "$job" ] && scontrol requeue "$job"; then
    requeued=yes
    # Slurm holds a requeued job back for two minutes (its begin time): let it start in
    # three seconds instead (sooner, the node refuses it: the revoked credential of its
    # first run is compared to the second).
    for _ in $(seq 1 100); do
        [ "$(squeue -h -j "$job" -o %T 2>/dev/null)" = PENDING ] && break
        sleep 0.1
    done
    scontrol update JobId="$job" StartTime=now+3 2>/dev/null || sleep 3
fi
wait $make_pid
status=$?
check "a requeued batch job ends and make goes on (requeued: $requeued, status $status)" test "$requeued" = yes -a "$status" = 0 ||
    tail -n 30 "$T/requeue.log"
check "the requeued flow continued from its checkpoint" grep -q "continuing with --restart" "$T/requeue.log"
check "the requeued flow has the bytes of the uninterrupted one" cmp -s "$T/local/flow_r02.nc" "$FLOWS_DIR/flow_r02.nc"

# ---- summary ----
say "wall time $(elapsed)"
if [ "$failed" != 0 ]; then
    say "logs in $T (KEEP=1 keeps them); the cluster's in $T/cluster/log"
    KEEP=1
fi
echo "slurm: $passed passed, $failed failed"
[ "$failed" = 0 ]
