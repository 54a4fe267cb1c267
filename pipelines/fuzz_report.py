"""Summary of one libFuzzer run (make -f Makefile.pipeline fuzz): executions, time, and
the inputs that crashed, hung or ran out of memory, from the log and the artifacts.

    python3 -m pipelines.fuzz_report TARGET runs/fuzz/TARGET

Prints one line and writes it, as CSV, to runs/fuzz/TARGET/summary.csv.
"""
import os
import re
import sys


def summarise(target, folder):
    runs, seconds, cov = 0, 0, 0
    counts = {"oom": 0, "timeout": 0, "crash": 0}
    with open(os.path.join(folder, "log.txt"), errors="replace") as log:
        for line in log:
            m = re.match(r"#(\d+):? .*cov: (\d+).*oom/timeout/crash: (\d+)/(\d+)/(\d+) time: (\d+)s", line)
            if m:
                runs, cov = int(m.group(1)), int(m.group(2))
                counts = {"oom": int(m.group(3)), "timeout": int(m.group(4)), "crash": int(m.group(5))}
                seconds = int(m.group(6))
                continue
            m = re.match(r"#(\d+)\s+(?:DONE|pulse|NEW|REDUCE|INITED).*cov: (\d+)", line)
            if m:
                runs, cov = max(runs, int(m.group(1))), int(m.group(2))
            m = re.match(r"INFO: exiting: \d+ time: (\d+)s", line)
            if m:
                seconds = int(m.group(1))
            m = re.match(r"Done (\d+) runs in (\d+) second", line)  # one-process mode
            if m:
                runs, seconds = int(m.group(1)), int(m.group(2))
            m = re.match(r"stat::number_of_executed_units: (\d+)", line)
            if m:
                runs = max(runs, int(m.group(1)))
            if "ERROR: AddressSanitizer" in line or "runtime error:" in line or "deadly signal" in line:
                counts["crash"] = max(counts["crash"], 1)
            if "ERROR: libFuzzer: timeout" in line:
                counts["timeout"] += 1
            if "out-of-memory" in line:
                counts["oom"] += 1
    crashes = os.path.join(folder, "crashes")
    artifacts = sorted(os.listdir(crashes)) if os.path.isdir(crashes) else []
    return {"target": target, "runs": runs, "seconds": seconds, "coverage": cov, "crashes": counts["crash"],
            "timeouts": counts["timeout"], "ooms": counts["oom"], "artifacts": len(artifacts)}


def main():
    target, folder = sys.argv[1], sys.argv[2]
    s = summarise(target, folder)
    keys = list(s)
    print("fuzz " + ", ".join(f"{k} {s[k]}" for k in keys))
    with open(os.path.join(folder, "summary.csv"), "w") as f:
        f.write(",".join(keys) + "\n" + ",".join(str(s[k]) for k in keys) + "\n")


if __name__ == "__main__":
    main()
