#!/usr/bin/env bash
# A throw-away Slurm cluster on this machine, from Debian's packages (munge, slurmctld,
# slurmd, slurm-client): one controller and NODES compute nodes, all slurmd instances of
# this host (slurmd -N NAME), every file under one folder, no cgroups, no systemd.
#
#   tests/slurm/slurm_cluster.sh up DIR [NODES] [CPUS_PER_NODE]   # prints: export SLURM_CONF=DIR/slurm.conf
#   tests/slurm/slurm_cluster.sh down DIR
#
# or, sourced: slurm_up DIR [NODES] [CPUS_PER_NODE]; ...; slurm_down DIR.
#
# NODES "nodes" of CPUS_PER_NODE cores each share this machine's cores: two nodes of one
# core each on a two-core machine are a fair model of two one-core nodes. The daemons run
# as the calling user (root in CI; any user works, since jobs then run as that user too),
# listen on free ports of 127.0.0.1 only, and are stopped by their process ids.

slurm_log() { echo "slurm_cluster: $*" >&2; }

# A free TCP port on 127.0.0.1 (the kernel's pick; closed again at once).
slurm_free_port() {
    /usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}

# The names of the daemons' programs that must exist.
slurm_programs_missing() {
    local p missing=""
    for p in munged slurmctld slurmd slurmstepd srun sbatch sinfo scontrol squeue scancel; do
        command -v "$p" >/dev/null 2>&1 || [ -x "/usr/sbin/$p" ] || missing="$missing $p"
    done
    echo "$missing"
}

slurm_up() {
    local dir=$1 nodes=${2:-1} cpus=${3:-$(nproc)}
    local user host mem_mb i
    [ -n "$dir" ] || { slurm_log "usage: slurm_up DIR [NODES] [CPUS_PER_NODE]"; return 2; }
    PATH=$PATH:/usr/sbin
    local missing
    missing=$(slurm_programs_missing)
    [ -z "$missing" ] || { slurm_log "missing programs:$missing (apt-get install munge slurmctld slurmd slurm-client)"; return 3; }
    mkdir -p "$dir" && dir=$(cd "$dir" && pwd) || return 1
    # munged wants its socket's folder and every parent searchable by all, its key private.
    chmod 755 "$dir"
    local up=$dir
    while [ "$up" != / ]; do
        up=$(dirname "$up")
        [ "$(stat -c %A "$up" | cut -c10)" = x ] || [ "$(stat -c %A "$up" | cut -c10)" = t ] ||
            { slurm_log "$up is not searchable by all users, which munged needs for its socket: choose another DIR"; return 1; }
    done
    mkdir -p "$dir/munge" "$dir/state" "$dir/spool" "$dir/log" "$dir/key"
    chmod 755 "$dir/munge"
    chmod 700 "$dir/key"
    head -c 1024 /dev/urandom >"$dir/key/munge.key"
    chmod 600 "$dir/key/munge.key"
    user=$(id -un)
    host=$(hostname -s)
    # Memory per node: what this machine has, less 1 GiB, shared among the nodes.
    mem_mb=$(awk -v n="$nodes" '/^MemTotal:/ { m = int($2 / 1024 / n) - 1024 / n; print (m < 256 ? 256 : int(m)) }' /proc/meminfo)

    munged --key-file="$dir/key/munge.key" --socket="$dir/munge/munge.socket" --pid-file="$dir/munge/munged.pid" \
        --log-file="$dir/log/munged.log" --seed-file="$dir/munge/munged.seed" ||
        { slurm_log "munged did not start:"; tail -n 5 "$dir/log/munged.log" >&2; return 1; }

    {
        echo "# written by tests/slurm/slurm_cluster.sh: a test cluster on $host, no cgroups"
        echo "ClusterName=flotsamtest"
        echo "SlurmctldHost=$host(127.0.0.1)"
        echo "SlurmctldPort=$(slurm_free_port)"
        echo "SlurmUser=$user"
        echo "SlurmdUser=$user"
        echo "AuthType=auth/munge"
        echo "CredType=cred/munge"
        echo "AuthInfo=socket=$dir/munge/munge.socket"
        echo "StateSaveLocation=$dir/state"
        echo "SlurmdSpoolDir=$dir/spool/%n"
        echo "SlurmctldPidFile=$dir/slurmctld.pid"
        echo "SlurmdPidFile=$dir/slurmd-%n.pid"
        echo "SlurmctldLogFile=$dir/log/slurmctld.log"
        echo "SlurmdLogFile=$dir/log/slurmd-%n.log"
        echo "ProctrackType=proctrack/linuxproc"
        echo "TaskPlugin=task/none"
        echo "JobAcctGatherType=jobacct_gather/none"
        echo "AccountingStorageType=accounting_storage/none"
        echo "JobCompType=jobcomp/none"
        echo "MpiDefault=none"
        echo "SelectType=select/cons_tres"
        echo "SelectTypeParameters=CR_Core_Memory"
        echo "SchedulerType=sched/backfill"
        echo "SchedulerParameters=bf_interval=1"
        echo "ReturnToService=2"
        echo "KillWait=2"
        echo "SlurmdTimeout=30"
        echo "InactiveLimit=0"
        echo "JobRequeue=1"
        for i in $(seq 1 "$nodes"); do
            echo "NodeName=n$i NodeHostname=$host NodeAddr=127.0.0.1 Port=$(slurm_free_port) CPUs=$cpus RealMemory=$mem_mb State=UNKNOWN"
        done
        echo "PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP"
    } >"$dir/slurm.conf"
    export SLURM_CONF=$dir/slurm.conf

    slurmctld -f "$SLURM_CONF" -i ||
        { slurm_log "slurmctld did not start:"; tail -n 20 "$dir/log/slurmctld.log" >&2; return 1; }
    for i in $(seq 1 "$nodes"); do
        slurmd -f "$SLURM_CONF" -N "n$i" ||
            { slurm_log "slurmd n$i did not start:"; tail -n 20 "$dir/log/slurmd-n$i.log" >&2; return 1; }
    done

    # Wait until every node is idle (registered and schedulable), at most 60 s.
    local waited=0 states
    while :; do
        states=$(sinfo -h -N -o '%N %T' 2>/dev/null)
        if [ -n "$states" ] && [ "$(grep -c ' idle$' <<<"$states")" = "$nodes" ]; then break; fi
        if [ $waited -ge 600 ]; then
            slurm_log "the nodes are not idle after 60 s:"
            echo "$states" >&2
            tail -n 20 "$dir/log/slurmctld.log" "$dir"/log/slurmd-*.log >&2
            return 1
        fi
        sleep 0.1
        waited=$((waited + 1))
    done
    slurm_log "up: $nodes node(s) x $cpus core(s), $mem_mb MB each, in $dir (SLURM_CONF=$SLURM_CONF)"
}

# Stops what slurm_up started in DIR, by the process ids in its pid files: the controller
# stops the nodes (scontrol shutdown); whatever still runs after 10 s is killed.
slurm_down() {
    local dir=$1 f pid pids="" t
    [ -d "$dir" ] || return 0
    PATH=$PATH:/usr/sbin
    # The ids first: the daemons remove their pid files as they stop.
    for f in "$dir"/slurmctld.pid "$dir"/slurmd-*.pid; do
        pid=$(cat "$f" 2>/dev/null) && [ -n "$pid" ] && pids="$pids $pid"
    done
    local munged
    munged=$(cat "$dir/munge/munged.pid" 2>/dev/null)
    [ -f "$dir/slurm.conf" ] && SLURM_CONF=$dir/slurm.conf scontrol shutdown >/dev/null 2>&1
    if [ -n "$munged" ]; then
        kill "$munged" 2>/dev/null
        pids="$pids $munged"
    fi
    for t in $(seq 1 100); do
        local alive=""
        for pid in $pids; do kill -0 "$pid" 2>/dev/null && alive="$alive $pid"; done
        [ -z "$alive" ] && return 0
        [ "$t" = 50 ] && for pid in $alive; do kill "$pid" 2>/dev/null; done
        sleep 0.1
    done
    for pid in $alive; do kill -9 "$pid" 2>/dev/null; done
    slurm_log "killed what did not stop:$alive"
}

if [ "${BASH_SOURCE[0]}" = "$0" ]; then
    case "${1:-}" in
    up)
        shift
        slurm_up "$@" && echo "export SLURM_CONF=$SLURM_CONF"
        ;;
    down)
        shift
        slurm_down "$1"
        ;;
    *)
        sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//'
        exit 2
        ;;
    esac
fi
