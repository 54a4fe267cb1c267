#!/usr/bin/python3
"""The full-scale demo's debris answer per source, as docs/gis.md tabulates it.

    python3 -m pipelines.full_scale_summary runs/kainan-full [--against OTHER_DIR]

Reads the sweep summary (sweep.csv), the building table (stats_csv/buildings.csv) and the
hazard regions (hazard/hazard_regions.csv) that `make -f Makefile.pipeline real-scale-maps`
writes, and prints Markdown tables: per source (a GIS feature, else a body) the members,
collision steps, jammed and unresolved steps (and the jammed share of the collision
steps), body-body contact steps, median path length and net displacement, and the share
of passages inside the design standard's +-22.5 degree region; per building the most hit
ones with their hit probability and 90th-percentile force. With --against, the same
numbers of another run of the demo (say, before a change) in a second column.
"""

import argparse
import csv
import os
import statistics
import sys


def read_rows(path):
    try:
        with open(path, newline="") as f:
            return list(csv.DictReader(f))
    except OSError as e:
        sys.exit(f"full_scale_summary: {path}: {e.strerror}")


def source_of(body):
    """'container_yard/1/17' -> 'container_yard/1' (a yard's bodies are one source)."""
    parts = body.split("/")
    return "/".join(parts[:2]) if len(parts) == 3 else body


def per_source(folder):
    rows = read_rows(os.path.join(folder, "sweep.csv"))
    regions = {r["source"]: r for r in read_rows(os.path.join(folder, "hazard", "hazard_regions.csv"))}
    out = {}
    for r in rows:
        out.setdefault(source_of(r["body"]), []).append(r)
    table = {}
    for src, members in out.items():
        num = lambda key: sum(int(m.get(key) or 0) for m in members)
        collisions, jammed = num("collision_steps"), num("jammed_steps")
        table[src] = {
            "members": len(members),
            "collision steps": collisions,
            "jammed steps": f"{jammed} ({100.0 * jammed / collisions:.2f} %)" if collisions else "0",
            "members with a jam": sum(1 for m in members if int(m.get("jammed_steps") or 0) > 0),
            "unresolved steps": num("unresolved_collisions"),
            "body-body contact steps": num("body_contact_steps") if "body_contact_steps" in members[0] else "-",
            "median path [m]": f"{statistics.median(float(m['travel_distance_m']) for m in members):.0f}",
            "median net displacement [m]": f"{statistics.median(float(m['net_displacement_m']) for m in members):.0f}",
            "passages inside the region": f"{100.0 * float(regions[src]['passage_share_region']):.1f} %" if src in regions else "-",
        }
    return table


def buildings(folder, top=8):
    rows = read_rows(os.path.join(folder, "stats_csv", "buildings.csv"))
    per = {}
    for r in rows:
        if r["body"] == "all":  # the sum over sources, also given per source
            continue
        b = per.setdefault(r["building"], {"impacts": 0, "p": 0.0, "force_p90": 0.0})
        b["impacts"] += int(r["impacts"])
        b["p"] = max(b["p"], float(r["hit_probability"]))
        b["force_p90"] = max(b["force_p90"], float(r["force_p90_N"]))
    total = sum(b["impacts"] for b in per.values())
    ranked = sorted(per.items(), key=lambda kv: (-kv[1]["impacts"], int(kv[0])))[:top]
    return total, len(per), ranked


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("folder", help="the demo's folder (runs/kainan-full)")
    ap.add_argument("--against", help="another run of the demo to set beside it")
    a = ap.parse_args()
    runs = [("this run", a.folder)] + ([("against", a.against)] if a.against else [])
    tables = [per_source(f) for _, f in runs]
    keys = list(next(iter(tables[0].values())).keys())
    for src in tables[0]:
        print(f"\n**{src}**\n")
        print("| quantity | " + " | ".join(name for name, _ in runs) + " |")
        print("| --- |" + " --- |" * len(runs))
        for k in keys:
            print(f"| {k} | " + " | ".join(str(t.get(src, {}).get(k, "-")) for t in tables) + " |")
    for name, folder in runs:
        total, hit, ranked = buildings(folder)
        print(f"\n**Buildings hit ({name})**: {total} impacts on {hit} buildings; the most hit:\n")
        print("| building | impacts | largest hit probability of a source | largest 90th-percentile force [kN] |")
        print("| --- | --- | --- | --- |")
        for bid, b in ranked:
            print(f"| {bid} | {b['impacts']} | {b['p']:.2f} | {b['force_p90'] / 1e3:.1f} |")


if __name__ == "__main__":
    main()
