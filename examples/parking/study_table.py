#!/usr/bin/env python3
"""Prints the tables of docs/examples/parking.md from runs of the parking program.

    python3 examples/parking/study_table.py build/test/examples/parking/parking

Every number in the tables comes from `parking --json` (one attempt) or `parking --study
--json` (the repeatability study); the flags of each row are printed next to it, so any row
can be rerun by hand.
"""

import argparse
import json
import subprocess
import sys

EXPERIMENTS = [
    ("I (near the axis)", []),
    ("II (x > 0)", ["--start-x", "0.5", "--start-y", "-0.9", "--start-heading", "119.05"]),
    ("III (x < 0)", ["--start-x", "-0.5", "--start-y", "-0.9", "--start-heading", "60.95"]),
]
THESIS_TABLE_5_3 = {"I": (10.9, 1), "II": (37.8, 3), "III": (47.3, 3)}

VARIANTS = [
    ("raw f1 - f2 (eq. 5.9 as printed), gain 2", ["--raw-asymmetry", "--c-gain", "2"]),
    ("raw f1 - f2, gain 4", ["--raw-asymmetry", "--c-gain", "4"]),
    ("raw f1 - f2, gain 6", ["--raw-asymmetry", "--c-gain", "6"]),
    ("raw f1 - f2, gain 8", ["--raw-asymmetry", "--c-gain", "8"]),
    ("scaled asymmetry, gain 8", ["--c-gain", "8"]),
    ("scaled asymmetry, gain 16", ["--c-gain", "16"]),
    ("forward move ends on the uncontrolled feature only", ["--thesis-forward-exit"]),
    ("... and c_min = 275 px (Fig. 5.15)", ["--thesis-forward-exit", "--c-min", "275"]),
    ("Start decides on one frame", ["--start-exit-frames", "1"]),
    ("eq. 5.1 on two frames in a row", ["--parked-frames", "2"]),
    ("no slower reverse near the goal", ["--v-slow", "0.1"]),
    ("gains of Table 5.2 read as rad/s per px", ["--k1", "14.32", "--k2", "5.73"]),
    ("no pixel noise", ["--noise", "0"]),
    ("pixel noise 1 px", ["--noise", "1"]),
    ("pixel noise 1 px, eq. 5.1 on two frames", ["--noise", "1", "--parked-frames", "2"]),
    ("10 frames/s", ["--fps", "10"]),
    ("robot without acceleration limits", ["--accel", "0", "--alpha", "0"]),
    ("starts within +-45 deg", ["--study-angle", "45"]),
    ("starts within +-55 deg", ["--study-angle", "55"]),
    ("starts 1.5-2.5 m away", ["--study-r-min", "1.5", "--study-r-max", "2.5"]),
]


def run(binary, args):
    out = subprocess.run([binary, "--json", "--svg-prefix", ""] + args, capture_output=True,
                         text=True)
    if out.returncode not in (0, 3):
        sys.exit(f"{binary} {' '.join(args)} failed: {out.stderr}")
    return json.loads(out.stdout)


def study_row(name, flags, s):
    shown = " ".join(flags) or "--study"
    shown = shown if shown.startswith("(") else f"`{shown}`"
    head = f"| {name} | {shown} | {s['parked']}/{s['runs']} | {s['station_lost']} | {s['timed_out']} |"
    if s["parked"] == 0:
        return head + " - | - | - | - |"
    return (head + f" +-{100 * s['x_spread_m']:.2f} | +-{100 * s['y_spread_m']:.2f} | "
            f"{s['mean_cycles']:.2f} ({s['max_cycles']}) | "
            f"{s['mean_time_s']:.1f} ({s['max_time_s']:.1f}) |")


STUDY_HEADER = ("| Variant | flags | parked | lost | timed out | x spread cm | y spread cm | cycles | time s |\n"
                "|---|---|---|---|---|---|---|---|---|")


def tables(binary, seeds):
    """The page's three tables, as markdown: Experiments I-III, the study with and without the
    adaptation of c (and the thesis' figures), and the variants."""
    rows = ["| Experiment | flags | seed 1: time s, cycles, error x / y cm | "
            f"seeds 1-{seeds}: parked, cycles, mean time s | thesis Table 5.3 |",
            "|---|---|---|---|---|"]
    for name, flags in EXPERIMENTS:
        one = run(binary, flags + ["--seed", "1"])
        many = [run(binary, flags + ["--seed", str(s)]) for s in range(1, seeds + 1)]
        parked = [m for m in many if m["parked"]]
        cycles = sorted({m["cycles"] for m in parked})
        mean_t = sum(m["time_s"] for m in parked) / max(len(parked), 1)
        t, c = THESIS_TABLE_5_3[name.split()[0]]
        rows.append(f"| {name} | `{' '.join(flags) or '(defaults)'}` | {one['time_s']:.1f}, "
                    f"{one['cycles']}, {100 * one['final_error']['x_m']:.2f} / "
                    f"{100 * one['final_error']['y_m']:.2f} | {len(parked)}/{len(many)}, "
                    f"{'-'.join(str(x) for x in (cycles[0], cycles[-1])) if cycles else '-'}, "
                    f"{mean_t:.1f} | {t} s, {c} |")
    experiments = "\n".join(rows)
    base = run(binary, ["--study"])
    study = "\n".join([
        STUDY_HEADER,
        study_row("**adaptive c (defaults)**", ["--study"], base),
        study_row(f"fixed c = {base['no_adaptation']['c_px']:.0f} px = c_max (no adaptation)",
                  ["(same run: `no_adaptation`)"], base["no_adaptation"]),
        study_row(f"fixed c = {base['static_c_min']['c_px']:.0f} px = c_min",
                  ["(same run: `static_c_min`)"], base["static_c_min"]),
        "| **thesis** (Sec. 5.5.3, 5.6; Table 5.3) | 20 starts | 20/20 | | | +-4 | +-0.5 | 1-3 | 10.9-47.3 |"])
    variants = "\n".join([STUDY_HEADER] + [study_row(name, ["--study"] + flags, run(binary, ["--study"] + flags))
                                           for name, flags in VARIANTS])
    return {"experiments_table": experiments, "study_table": study, "variants_table": variants}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("binary", help="path to the parking program")
    parser.add_argument("--seeds", type=int, default=20, help="seeds per experiment")
    parser.add_argument("--json", action="store_true",
                        help="print the tables as one JSON object (scripts/docs_figures.py reads it)")
    a = parser.parse_args()
    t = tables(a.binary, a.seeds)
    if a.json:
        print(json.dumps(t))
        return
    print(f"Experiments (seed 1, and over seeds 1-{a.seeds}):\n\n{t['experiments_table']}\n")
    print(f"Study (200 starts, seed 1; spreads in cm; cycles and time: mean (max)):\n\n{t['study_table']}\n")
    print(f"Variants:\n\n{t['variants_table']}")


if __name__ == "__main__":
    main()
