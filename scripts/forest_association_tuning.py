#!/usr/bin/env python3
"""The choices of forest_slam's association settings without ids (docs/slam.md): forest_slam
--association nn on development forests, never the forests of docs/slam.md's tables nor the
default forest, and a rule fixed before the search ran.

    python3 scripts/forest_association_tuning.py --bin build/docs/examples/forest_slam/forest_slam
    python3 scripts/forest_association_tuning.py --bin ... --search continuity

--search tolerance (the default): TreeSlamOptions::width_appearance_tolerance. Per tolerance, the
median over the forests of the share of sightings taken right by each pipeline; the tolerance
chosen is the one whose worse pipeline with point landmarks (with_width, without_width) has the
highest median.

--search continuity: TreeSlamOptions::continuity_edge_margin_px, each margin at three costs
(continuity_cost) around the middle one, which is the cost chosen. A margin qualifies if at each
of its costs, for both pipelines with point landmarks, the median over the forests of the map
error e_l and of the trajectory error e_t, each over the same forest's run with ids, is no
larger than with the test off: the test may not buy its share taken right with worse maps.
Among those, the margin chosen has the highest robustness median: the median over its costs of
the worse point pipeline's median share taken right.

Runs the forests in parallel (one process per core) and prints Markdown tables.
"""
import argparse
import concurrent.futures
import json
import math
import os
import statistics
import subprocess

PIPELINES = ("with_width", "without_width", "width_first_sight")
POINT_PIPELINES = ("with_width", "without_width")


def run(binary, seed, options):
    out = subprocess.run([binary, "--seed", str(seed), "--json", "--svg-prefix", "", *options],
                         check=True, capture_output=True, text=True).stdout
    result = json.loads(out)
    return {p: {"correct": 100.0 * result[p].get("association", {}).get("correct_fraction", math.nan),
                "duplicates": result[p].get("association", {}).get("duplicates", 0),
                "e_l": result[p]["landmark_error"], "e_t": result[p]["trajectory_error"]} for p in PIPELINES}


def tolerance_search(args, seeds, pool):
    tolerances = [float(t) for t in args.tolerances.split(",")]
    runs = {(t, s): pool.submit(run, args.bin, s, ["--association", "nn", "--width-appearance-tolerance", str(t)])
            for t in tolerances for s in seeds}
    medians = {t: {p: statistics.median(runs[(t, s)].result()[p]["correct"] for s in seeds) for p in PIPELINES}
               for t in tolerances}
    best = max(tolerances, key=lambda t: min(medians[t][p] for p in POINT_PIPELINES))
    print(f"forests {args.seeds}, share of sightings taken right (%), median over the forests\n")
    print("| tolerance | " + " | ".join(PIPELINES) + " |")
    print("|---" * (len(PIPELINES) + 1) + "|")
    for t in tolerances:
        mark = " (chosen)" if t == best else ""
        print(f"| {t:g}{mark} | " + " | ".join(f"{medians[t][p]:.1f}" for p in PIPELINES) + " |")


def continuity_search(args, seeds, pool):
    margins = [float(m) for m in args.margins.split(",")]
    costs = [float(c) for c in args.costs.split(",")]
    if len(costs) % 2 != 1:
        raise SystemExit("--costs: an odd number of costs, so that one is the middle")
    chosen_cost = sorted(costs)[len(costs) // 2]
    configs = {"ids": []}
    configs["off"] = ["--association", "nn", "--continuity-cost", "inf"]
    for m in margins:
        for c in costs:
            configs[(m, c)] = ["--association", "nn", "--continuity-cost", str(c), "--continuity-edge-margin", str(m)]
    runs = {(k, s): pool.submit(run, args.bin, s, o) for k, o in configs.items() for s in seeds}
    result = {k: {s: runs[(k, s)].result() for s in seeds} for k in configs}

    def summary(key):
        r = result[key]
        out = {}
        for p in PIPELINES:
            out[p] = {
                "correct": statistics.median(r[s][p]["correct"] for s in seeds),
                "e_l": statistics.median(r[s][p]["e_l"] / result["ids"][s][p]["e_l"] for s in seeds),
                "e_t": statistics.median(r[s][p]["e_t"] / result["ids"][s][p]["e_t"] for s in seeds),
                "duplicates": statistics.median(r[s][p]["duplicates"] for s in seeds),
            }
        return out

    off = summary("off")
    table = {(m, c): summary((m, c)) for m in margins for c in costs}

    def no_worse_maps(s):
        return all(s[p][e] <= off[p][e] for p in POINT_PIPELINES for e in ("e_l", "e_t"))

    def worse_point(s):
        return min(s[p]["correct"] for p in POINT_PIPELINES)

    qualified = [m for m in margins if all(no_worse_maps(table[(m, c)]) for c in costs)]
    robust = {m: statistics.median(worse_point(table[(m, c)]) for c in costs) for m in margins}
    best = max(qualified, key=lambda m: robust[m]) if qualified else None

    print(f"forests {args.seeds}; medians over the forests: share of sightings taken right (%), and e_l and e_t "
          "over the same forest's run with ids, for the pipelines with point landmarks (with_width / without_width)\n")
    print("| margin (px) | cost | " + " | ".join(f"taken right, {p}" for p in PIPELINES) +
          " | e_l / ids | e_t / ids | duplicate trees | maps no worse than off |")
    print("|---" * (len(PIPELINES) + 6) + "|")

    def row(label_m, label_c, s):
        maps = f"{s['with_width']['e_l']:.2f} / {s['without_width']['e_l']:.2f}"
        traj = f"{s['with_width']['e_t']:.2f} / {s['without_width']['e_t']:.2f}"
        dup = f"{s['with_width']['duplicates']:g} / {s['without_width']['duplicates']:g}"
        return f"| {label_m} | {label_c} | " + " | ".join(f"{s[p]['correct']:.1f}" for p in PIPELINES) + \
            f" | {maps} | {traj} | {dup} |"

    print(row("test off", "inf", off) + " |")
    for m in margins:
        for c in costs:
            s = table[(m, c)]
            print(row(f"{m:g}", f"{c:g}", s) + f" {'yes' if no_worse_maps(s) else 'no'} |")
    print()
    print("| margin (px) | qualifies | robustness median (%) |")
    print("|---|---|---|")
    for m in margins:
        mark = " (chosen)" if m == best else ""
        print(f"| {m:g}{mark} | {'yes' if m in qualified else 'no'} | {robust[m]:.1f} |")
    print()
    print(f"chosen: continuity_edge_margin_px = {best if best is not None else 'none qualifies'}, "
          f"continuity_cost = {chosen_cost:g} (the middle cost)")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bin", required=True, help="the forest_slam program")
    parser.add_argument("--search", choices=("tolerance", "continuity"), default="tolerance")
    parser.add_argument("--seeds", default="101-110", help="development forests, FIRST-LAST (default 101-110)")
    parser.add_argument("--tolerances", default="0,0.025,0.05,0.075,0.1,0.2,0.3")
    parser.add_argument("--margins", default="-1,15,30,45,60,90", help="continuity margins (px; -1: none)")
    parser.add_argument("--costs", default="9.5,10.5,11.5", help="continuity costs, an odd number")
    parser.add_argument("--jobs", type=int, default=os.cpu_count())
    args = parser.parse_args()
    first, last = (int(v) for v in args.seeds.split("-"))
    seeds = range(first, last + 1)
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        if args.search == "tolerance":
            tolerance_search(args, seeds, pool)
        else:
            continuity_search(args, seeds, pool)


if __name__ == "__main__":
    main()
