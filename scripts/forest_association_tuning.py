#!/usr/bin/env python3
"""The choice of TreeSlamOptions::width_appearance_tolerance (docs/slam.md, "The width of point
landmarks"): forest_slam without ids (--association nn) on development forests, never the
forests of docs/slam.md's tables, for each tolerance; per tolerance, the median over the forests
of the share of sightings taken right by each pipeline. The tolerance chosen is the one whose
worse pipeline with point landmarks (with_width, without_width) has the highest median.

    python3 scripts/forest_association_tuning.py --bin build/docs/examples/forest_slam/forest_slam

Runs the forests in parallel (one process per core) and prints a Markdown table.
"""
import argparse
import concurrent.futures
import json
import os
import statistics
import subprocess

PIPELINES = ("with_width", "without_width", "width_first_sight")
POINT_PIPELINES = ("with_width", "without_width")


def correct_fraction(binary, seed, tolerance):
    out = subprocess.run([binary, "--seed", str(seed), "--association", "nn", "--width-appearance-tolerance",
                          str(tolerance), "--json", "--svg-prefix", ""],
                         check=True, capture_output=True, text=True).stdout
    run = json.loads(out)
    return {p: 100.0 * run[p]["association"]["correct_fraction"] for p in PIPELINES}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bin", required=True, help="the forest_slam program")
    parser.add_argument("--seeds", default="101-110", help="development forests, FIRST-LAST (default 101-110)")
    parser.add_argument("--tolerances", default="0,0.025,0.05,0.075,0.1,0.2,0.3")
    parser.add_argument("--jobs", type=int, default=os.cpu_count())
    args = parser.parse_args()
    first, last = (int(v) for v in args.seeds.split("-"))
    seeds = range(first, last + 1)
    tolerances = [float(t) for t in args.tolerances.split(",")]
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        runs = {(t, s): pool.submit(correct_fraction, args.bin, s, t) for t in tolerances for s in seeds}
        medians = {t: {p: statistics.median(runs[(t, s)].result()[p] for s in seeds) for p in PIPELINES}
                   for t in tolerances}
    best = max(tolerances, key=lambda t: min(medians[t][p] for p in POINT_PIPELINES))
    print(f"forests {args.seeds}, share of sightings taken right (%), median over the forests\n")
    print("| tolerance | " + " | ".join(PIPELINES) + " |")
    print("|---" * (len(PIPELINES) + 1) + "|")
    for t in tolerances:
        mark = " (chosen)" if t == best else ""
        print(f"| {t:g}{mark} | " + " | ".join(f"{medians[t][p]:.1f}" for p in PIPELINES) + " |")


if __name__ == "__main__":
    main()
