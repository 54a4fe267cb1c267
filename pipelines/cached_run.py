"""One runner for the accuracy studies: run a flotsam command once, keep what it cost.

A study repeats many runs; each is skipped when its output and its cost record both
exist (delete them to redo). The cost record is written to a temporary name and then
renamed, so an interrupted study never leaves a record that looks finished.
"""
import os
import resource
import subprocess
import sys


def run_once(who, out, record, cmd, parse, announce=False, launch=()):
    """Runs `cmd` unless `out` and `record` exist; returns the record's comma-separated fields.

    parse(stderr, cpu_s) gives the fields to record, or None when the command did not print
    what it should. cpu_s is the children's user + system time of this run; it is only
    meaningful when runs are not started from several threads at once, and it is None when
    the command ran through a launcher (`launch`, the words put in front of it: srun …,
    docs/cluster.md), since the run's processor time is then spent elsewhere. With
    `announce`, the command is printed when it runs.
    """
    if not (os.path.exists(out) and os.path.exists(record)):
        cmd = list(launch) + list(cmd)
        if announce:
            print(f"{who}:", " ".join(cmd), flush=True)
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        p = subprocess.run(cmd, stderr=subprocess.PIPE, text=True)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = None if launch else (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        if p.returncode != 0:
            sys.exit(f"{who}: {' '.join(cmd)} failed:\n{p.stderr[-2000:]}")
        fields = parse(p.stderr, cpu)
        if fields is None:
            sys.exit(f"{who}: {out}: no cost line in the output of {' '.join(cmd[:2])}")
        with open(record + ".part", "w") as f:
            f.write(",".join(fields) + "\n")
        os.replace(record + ".part", record)
    with open(record) as f:
        return f.read().strip().split(",")
