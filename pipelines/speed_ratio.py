#!/usr/bin/python3
"""How much faster the flows are than a reference build: both binaries at once.

Usage: python3 -m pipelines.speed_ratio --flotsam BUILD/flotsam --dem DEM.nc --runs DIR
           [--baseline COMMIT] [--setting NAME=RES:SECONDS ...] [--csv FILE]

Builds `flotsam` at COMMIT (default: FIRST_WAVE, a fixed reference build) from its files
(git archive) under DIR (once; ccache is used where installed), imports the DEM at each
setting's resolution with each binary, and runs the two flows side by side, one thread
each, so that both see the same machine: the real layout with the benchmark's pump
forcing on the scene's recommended grids (nested 4:1 west of x = -1.2 m, frames over the
port and city). The ratio is of processor time, which a busy machine inflates for both
alike; wall time is printed too. Settings default to the production one (2 cm, 0-150 s)
and the 1 cm one (0-40 s). Prints a markdown table; --csv writes the same rows.
"""
import argparse
import os
import subprocess
import sys
import time

FIRST_WAVE = "c05fa73"
NEST = ["--nest-ratio", "4", "--nest-x", "-1.2", "--output-window", "-1,8.1,-4.1,0"]


def build_baseline(commit, runs):
    """The baseline's flotsam, built once in runs/baseline-COMMIT."""
    src = os.path.join(runs, f"baseline-{commit}")
    binary = os.path.join(src, "build", "flotsam")
    if os.path.exists(binary):
        return binary
    if not os.path.isdir(os.path.join(src, "hydro")):
        # The commit's files only (git archive): no worktree to register in the repository.
        os.makedirs(src, exist_ok=True)
        archive = subprocess.run(["git", "archive", "--format=tar", commit], check=True, capture_output=True).stdout
        subprocess.run(["tar", "-x", "-C", src], input=archive, check=True)
    cmake = ["cmake", "-S", src, "-B", os.path.join(src, "build"), "-DCMAKE_BUILD_TYPE=Release"]
    if subprocess.run(["which", "ccache"], capture_output=True).returncode == 0:
        cmake.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
    subprocess.run(cmake, check=True, stdout=subprocess.DEVNULL)
    jobs = str(os.cpu_count() or 1)
    subprocess.run(["cmake", "--build", os.path.join(src, "build"), "-j", jobs, "--target", "flotsam"], check=True,
                   stdout=subprocess.DEVNULL)
    return binary


def scene(binary, dem, res, path):
    if not os.path.exists(path):
        subprocess.run([binary, "scene", "import", "--dem", dem, "--resolution", res, "--out", path], check=True,
                       stdout=subprocess.DEVNULL)
    return path


def side_by_side(commands):
    """Runs the commands at once; their processor and wall seconds, in order."""
    env = dict(os.environ, OMP_WAIT_POLICY=os.environ.get("OMP_WAIT_POLICY", "passive"))
    start = time.monotonic()
    procs = [subprocess.Popen(c, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE) for c in commands]
    cpu, wall = [0.0] * len(procs), [0.0] * len(procs)
    left = {p.pid: k for k, p in enumerate(procs)}
    while left:
        pid, status, usage = os.wait4(-1, 0)
        if pid not in left:
            continue
        k = left.pop(pid)
        cpu[k] = usage.ru_utime + usage.ru_stime
        wall[k] = time.monotonic() - start
        if os.waitstatus_to_exitcode(status) != 0:
            sys.exit(f"speed_ratio.py: {' '.join(commands[k])} failed:\n{procs[k].stderr.read().decode()}")
    return cpu, wall


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--flotsam", required=True)
    ap.add_argument("--dem", required=True)
    ap.add_argument("--runs", required=True)
    ap.add_argument("--baseline", default=FIRST_WAVE)
    ap.add_argument("--setting", action="append", help="NAME=RES:SECONDS, e.g. production=0.02:150")
    ap.add_argument("--csv")
    a = ap.parse_args(argv[1:])
    settings = a.setting or ["production (2 cm nested)=0.02:150", "1 cm nested=0.01:40"]
    out = os.path.join(a.runs, "speed-ratio")
    os.makedirs(out, exist_ok=True)
    baseline = build_baseline(a.baseline, a.runs)
    rows = []
    print(f"| setting | simulated s | {a.baseline} processor s | this build processor s | ratio | wall s (both) |")
    print("| --- | --- | --- | --- | --- | --- |")
    for s in settings:
        name, spec = s.split("=", 1)
        res, seconds = spec.split(":")
        runs = []
        for tag, binary in (("baseline", baseline), ("now", a.flotsam)):
            sc = scene(binary, a.dem, res, os.path.join(out, f"real-{res}-{tag}.nc"))
            flow = os.path.join(out, f"flow-{res}-{tag}.nc")
            for stale in (flow, flow + ".part", flow + ".checkpoint.nc"):
                if os.path.exists(stale):
                    os.remove(stale)
            runs.append([binary, "hydro", "--scene", sc, "--west", "pump", "--duration", seconds, "--threads", "1",
                         "--quiet", "--out", flow] + NEST)
        cpu, wall = side_by_side(runs)
        ratio = cpu[0] / cpu[1]
        rows.append((name, seconds, cpu[0], cpu[1], ratio, wall))
        print(f"| {name} | {seconds} | {cpu[0]:.1f} | {cpu[1]:.1f} | **{ratio:.2f}x** | {wall[0]:.0f}, {wall[1]:.0f} |",
              flush=True)
    print(f"\nload average at the end: {' '.join(f'{x:.1f}' for x in os.getloadavg())}")
    if a.csv:
        with open(a.csv + ".part", "w") as f:
            f.write("setting,simulated_s,baseline_cpu_s,now_cpu_s,ratio,baseline_wall_s,now_wall_s\n")
            for name, seconds, c0, c1, r, w in rows:
                f.write(f"{name},{seconds},{c0:.2f},{c1:.2f},{r:.3f},{w[0]:.1f},{w[1]:.1f}\n")
        os.replace(a.csv + ".part", a.csv)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
