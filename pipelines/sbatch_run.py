#!/usr/bin/python3
"""LAUNCH=sbatch: runs one command as a Slurm batch job and waits for it.

    python3 -m pipelines.sbatch_run [SBATCH OPTIONS] -- COMMAND [ARGS ...]

Makefile.pipeline puts this in front of every flow and sweep shard when LAUNCH=sbatch
(docs/cluster.md). Unlike srun, a batch job may be requeued (preemption, a failed node)
instead of lost: the job is submitted with `sbatch --requeue`, this command waits until
it has ended for good (through any requeues), so make waits for it too, and its exit
status is the job's. The job's log (--output, appended to
across requeues) is printed when it ends. Interrupting this command cancels the job.

In the job this file is its own batch script: a `flotsam hydro` run whose output has a
checkpoint (<out>.checkpoint.nc, written with --checkpoint-interval) gets --restart, so a
requeued flow continues from its last checkpoint instead of from the start.
"""
import os
import re
import shlex
import signal
import subprocess
import sys
import time

IN_JOB = "--in-job"


def option_value(args, long, short=None):
    """The value of `--long=V`, `--long V` or `-s V` in args, or None."""
    for i, a in enumerate(args):
        if a.startswith(long + "="):
            return a.split("=", 1)[1]
        if a in (long, short) and i + 1 < len(args):
            return args[i + 1]
    return None


def resume_if_checkpointed(cmd):
    """cmd with --restart added when it is a flotsam hydro run whose checkpoint exists."""
    if len(cmd) < 2 or os.path.basename(cmd[0]) != "flotsam" or cmd[1] != "hydro" or "--restart" in cmd:
        return cmd
    out = option_value(cmd, "--out")
    checkpoint = f"{out}.checkpoint.nc" if out else None
    if checkpoint and os.path.exists(checkpoint):
        print(f"sbatch_run: {checkpoint} exists (Slurm restart count {os.environ.get('SLURM_RESTART_COUNT', '0')}): "
              "continuing with --restart", file=sys.stderr, flush=True)
        return cmd + ["--restart"]
    return cmd


REQUEUED_OR_RUNNING = {"PENDING", "CONFIGURING", "RUNNING", "REQUEUED", "REQUEUE_HOLD", "REQUEUE_FED", "RESIZING",
                       "SUSPENDED", "COMPLETING"}


def job_state(job_id):
    """The job's state and exit status from `scontrol show job`, or (None, None) once Slurm has forgotten it."""
    if not job_id:
        return None, None
    p = subprocess.run(["scontrol", "-o", "show", "job", job_id], capture_output=True, text=True)
    state = re.search(r"\bJobState=(\S+)", p.stdout)
    code = re.search(r"\bExitCode=(\d+):(\d+)", p.stdout)
    if p.returncode != 0 or not state:
        return None, None
    exit_code, signal_number = (int(code.group(1)), int(code.group(2))) if code else (1, 0)
    status = exit_code or (128 + signal_number if signal_number else (0 if state.group(1) == "COMPLETED" else 1))
    return state.group(1), status


def wait_for(job_id):
    """Waits until the job has ended for good and returns its exit status. Slurm is asked
    after 1, 1.5, 2.25 … seconds, then every 10 s (sbatch --wait asks every 30 s at the
    end, a long wait after a short job). A requeued job passes through COMPLETING back to
    PENDING, so an ended state counts only when it is still there 2 s later."""
    delay, ended_once = 1.0, False
    while True:
        time.sleep(delay)
        state, status = job_state(job_id)
        if state is None:
            print(f"sbatch_run: Slurm no longer knows job {job_id}: its end was missed", file=sys.stderr)
            return 1
        if state in REQUEUED_OR_RUNNING:
            ended_once = False
            delay = min(1.5 * delay, 10.0)
        elif ended_once:
            return status
        else:
            ended_once, delay = True, 2.0


def log_path(pattern, job_id, job_name):
    """--output with the two patterns make gives it expanded (%j job id, %x job name)."""
    return re.sub(r"%(%|j|x)", lambda m: {"%": "%", "j": job_id, "x": job_name}[m.group(1)], pattern)


def submit(options, cmd):
    output = option_value(options, "--output", "-o")
    if output is None:
        output = "slurm-%x-%j.log"
        options = options + [f"--output={output}"]
    if os.path.dirname(output):
        os.makedirs(os.path.dirname(output), exist_ok=True)
    script = [sys.executable, os.path.abspath(__file__), IN_JOB, "--"] + cmd
    sbatch = ["sbatch", "--requeue", "--parsable", "--open-mode=append"] + options + ["--wrap", "exec " + shlex.join(script)]
    job_id = ""

    def cancel(signum, _frame):
        if job_id:
            subprocess.run(["scancel", job_id])
            print(f"sbatch_run: cancelled job {job_id}", file=sys.stderr)
        sys.exit(128 + signum)

    for s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
        signal.signal(s, cancel)
    p = subprocess.run(sbatch, stdout=subprocess.PIPE, text=True)
    if p.returncode != 0:
        return p.returncode
    job_id = p.stdout.strip().split(";")[0]
    status = wait_for(job_id)
    name = option_value(options, "--job-name", "-J") or "wrap"
    log = log_path(output, job_id, name)
    if os.path.exists(log):
        with open(log, errors="replace") as f:
            sys.stderr.write(f.read())
    if status != 0:
        print(f"sbatch_run: job {job_id or '(not submitted)'} ({' '.join(cmd[:2])}) failed with status {status}; "
              f"log: {log}", file=sys.stderr)
    return status


def main():
    args = sys.argv[1:]
    if "--" not in args or args.index("--") == len(args) - 1:
        sys.exit(__doc__)
    split = args.index("--")
    options, cmd = args[:split], args[split + 1:]
    if options == [IN_JOB]:
        cmd = resume_if_checkpointed(cmd)
        os.execvp(cmd[0], cmd)
    sys.exit(submit(options, cmd))


if __name__ == "__main__":
    main()
