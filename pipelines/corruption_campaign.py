"""Corrupts a NetCDF file's structure at random and runs flotsam on each copy, counting
named errors, runs that went through, crashes and hangs (docs/reliability.md,
"libhdf5 and corrupted files"). Copies that crashed are kept for regression tests.

    python3 -m pipelines.corruption_campaign FLOW.nc --count 300 --flotsam build/flotsam [--no-probe] --out runs/corrupt
    python3 -m pipelines.corruption_campaign SCENE.nc --kind scene --bytes 65536 --single ...
    python3 -m pipelines.corruption_campaign SWEEP.nc --kind sweep --scene SCENE.nc ...

A copy changes 1 to 4 random bytes (--single: one) of the first --bytes (16 kB by default:
superblock, object headers, B-trees; 64 kB reaches the global heap, where libhdf5 keeps
variable-length data such as the dimension scales' references), seeded, so a campaign
repeats exactly. A flow is replayed (`debris --at`), a scene run (`hydro`), a sweep's
statistics computed (`stats`, with --scene).
"""
import argparse
import os
import random
import subprocess


def main():
    p = argparse.ArgumentParser()
    p.add_argument("flow")
    p.add_argument("--count", type=int, default=300)
    p.add_argument("--seed", type=int, default=7)
    p.add_argument("--flotsam", default="build/flotsam")
    p.add_argument("--no-probe", action="store_true", help="FLOTSAM_NO_PROBE=1: let libhdf5 crash flotsam")
    p.add_argument("--out", default="runs/corrupt")
    p.add_argument("--kind", choices=["flow", "scene", "sweep"], default="flow")
    p.add_argument("--bytes", type=int, default=16384, help="corrupt within the first this many bytes")
    p.add_argument("--single", action="store_true", help="one byte a copy")
    p.add_argument("--scene", help="the scene, for --kind sweep")
    p.add_argument("--timeout", type=float, default=180, help="seconds before a run counts as a hang")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    data = open(a.flow, "rb").read()
    rng = random.Random(a.seed)
    env = dict(os.environ)
    if a.no_probe:
        env["FLOTSAM_NO_PROBE"] = "1"
    counts = {"named error": 0, "ran": 0, "crash": 0, "hang": 0}
    for k in range(a.count):
        b = bytearray(data)
        for _ in range(1 if a.single else rng.randint(1, 4)):
            b[rng.randrange(min(len(b), a.bytes))] = rng.randrange(256)
        path = os.path.join(a.out, "copy.nc")
        open(path, "wb").write(b)
        out = os.path.join(a.out, "out.nc")
        cmd = {"flow": [a.flotsam, "debris", "--flow", path, "--at", "0.5,-1,0", "--quiet", "--out", out],
               "scene": [a.flotsam, "hydro", "--scene", path, "--west", "wall", "--duration", "0.2", "--quiet", "--out", out],
               "sweep": [a.flotsam, "stats", "--sweep", path, "--scene", a.scene or "", "--out", out]}[a.kind]
        try:
            r = subprocess.run(cmd, env=env, capture_output=True, timeout=a.timeout)
        except subprocess.TimeoutExpired:
            counts["hang"] += 1
            continue
        if r.returncode < 0 or r.returncode > 2:
            counts["crash"] += 1
            open(os.path.join(a.out, f"crash_{k}.nc"), "wb").write(b)
        else:
            counts["ran" if r.returncode == 0 else "named error"] += 1
    print(f"{a.count} corrupted copies of {a.flow} ({a.kind}, first {a.bytes} bytes, "
          f"{'no probe' if a.no_probe else 'probe'}): "
          + ", ".join(f"{v} {k}" for k, v in counts.items()))


if __name__ == "__main__":
    main()
