#!/usr/bin/env python3
"""What the Python layer costs, measured: writes docs/python.figures.json for docs/python.md.

    python3 python/benchmarks/overhead.py [--bin-dir build/docs/examples] [--rounds 7]

1. One update of the README's filter (one landmark), through RangeBearing (C++), and through
   the same model written in Python (sylva.PythonModel), with numerical Jacobians and with its
   own. The variants run interleaved, in a new random order each round, each on its own copy
   of the same filter; a ratio is taken within a round, and the figures are the median and
   the range over rounds (the machine is shared).
2. The range-bearing study (python/examples/range_bearing_study.py) against the C++ program
   it reproduces (range_bearing_slam, same flags, --runs 2), whole process wall time, also
   interleaved; only with --bin-dir (a build's examples directory).
"""

import argparse
import json
import os
import random
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

import sylva

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))
from header_cost import cpu_model  # noqa: E402
R = sylva.sigmas(0.1, 0.01)


def range_bearing(x, landmark):
    d = landmark - x[:2]
    b = np.arctan2(d[1], d[0]) - x[2]
    return np.array([np.hypot(d[0], d[1]), np.arctan2(np.sin(b), np.cos(b))])


def jacobians(x, landmark):
    d = landmark - x[:2]
    q = d @ d
    r = np.sqrt(q)
    return (np.array([[-d[0] / r, -d[1] / r, 0.0], [d[1] / q, -d[0] / q, -1.0]]),
            np.array([[d[0] / r, d[1] / r], [-d[1] / q, d[0] / q]]))


class Counted:
    """A Python function that counts its calls."""

    def __init__(self, f):
        self.f, self.calls = f, 0

    def __call__(self, *args):
        self.calls += 1
        return self.f(*args)


def readme_filter():
    f = sylva.Unicycle2DEkf([0.0, 0.0, 0.0], np.zeros((3, 3)))
    f.add(7, sylva.InverseRangeBearing(), [5.0, 0.6435], R)
    f.predict([1.0, 0.0], 1.0, sylva.sigmas(0.05, 0.02))
    return f


def time_updates(model, calls):
    f = readme_filter()
    z = np.array([4.243, 0.7854])
    start = time.perf_counter()
    for _ in range(calls):
        f.update(model, 7, z, R)
    return (time.perf_counter() - start) / calls


def summary(values, scale=1.0, digits=2):
    v = sorted(x * scale for x in values)
    return {"median": round(statistics.median(v), digits), "min": round(v[0], digits), "max": round(v[-1], digits)}


def update_costs(rounds, calls):
    h_numeric, h_analytic, jac = Counted(range_bearing), Counted(range_bearing), Counted(jacobians)
    variants = {
        "range_bearing": sylva.RangeBearing(),
        "python_numeric": sylva.PythonModel(2, h_numeric, angles=[1]),
        "python_analytic": sylva.PythonModel(2, h_analytic, jacobians=jac, angles=[1]),
    }
    # Python calls per update, counted on one update each.
    for model in variants.values():
        time_updates(model, 1)
    calls_per_update = {"python_numeric": h_numeric.calls, "python_analytic": h_analytic.calls + jac.calls}
    times = {name: [] for name in variants}
    order = list(variants)
    rng = random.Random(1)
    for _ in range(rounds):
        rng.shuffle(order)
        for name in order:
            times[name].append(time_updates(variants[name], calls))
    ratios = {name: [t / b for t, b in zip(times[name], times["range_bearing"])] for name in variants if name != "range_bearing"}
    return times, ratios, calls_per_update


def study_costs(bin_dir, rounds):
    program = Path(bin_dir) / "range_bearing_slam" / "range_bearing_slam"
    if not program.is_file():
        raise SystemExit(f"overhead.py: {program} is not built")
    flags = ["--runs", "2", "--seed", "1"]
    commands = {
        "cpp": [str(program), *flags, "--json", "--svg", ""],
        "python": [sys.executable, str(ROOT / "python" / "examples" / "range_bearing_study.py"), *flags, "--no-figures"],
    }
    outputs, times = {}, {name: [] for name in commands}
    order = list(commands)
    rng = random.Random(2)
    for _ in range(rounds):
        rng.shuffle(order)
        for name in order:
            start = time.perf_counter()
            outputs[name] = json.loads(subprocess.run(commands[name], check=True, capture_output=True, text=True).stdout)
            times[name].append(time.perf_counter() - start)
    same = outputs["cpp"] == outputs["python"]
    return times, [p / c for p, c in zip(times["python"], times["cpp"])], same


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--rounds", type=int, default=7)
    p.add_argument("--calls", type=int, default=2000, help="updates per variant and round")
    p.add_argument("--bin-dir", help="a build's examples directory, for the whole-study comparison")
    p.add_argument("--out", type=Path, default=ROOT / "docs" / "python.figures.json")
    a = p.parse_args()

    times, ratios, calls = update_costs(a.rounds, a.calls)
    figures = {"rounds": str(a.rounds), "calls": str(a.calls)}
    for name, values in times.items():
        s = summary(values, 1e6, 1)
        figures[f"update_us.{name}"] = f"{s['median']:.1f}"
        figures[f"update_us.{name}.range"] = f"{s['min']:.1f}-{s['max']:.1f}"
    for name, values in ratios.items():
        s = summary(values)
        figures[f"update_ratio.{name}"] = f"{s['median']:.1f}"
        figures[f"update_ratio.{name}.range"] = f"{s['min']:.1f}-{s['max']:.1f}"
        figures[f"python_calls_per_update.{name}"] = str(calls[name])
    command = f"python3 python/benchmarks/overhead.py --rounds {a.rounds} --calls {a.calls}"
    if a.bin_dir:
        study_times, study_ratio, same = study_costs(a.bin_dir, a.rounds)
        for name, values in study_times.items():
            figures[f"study_s.{name}"] = f"{statistics.median(values):.2f}"
        s = summary(study_ratio)
        figures["study_ratio"] = f"{s['median']:.1f}"
        figures["study_ratio.range"] = f"{s['min']:.1f}-{s['max']:.1f}"
        figures["study_same_output"] = "yes" if same else "no"
        command += " --bin-dir " + os.path.relpath(a.bin_dir, ROOT)
    figures["cpu"] = cpu_model()
    info = sylva.build_info
    figures["module_build"] = f"{info['compiler']}, {'optimized' if info['optimized'] else 'not optimized'}, {info['simd']}"
    out = {"source": "python", "command": command, "figures": dict(sorted(figures.items()))}
    a.out.write_text(json.dumps(out, indent=2, sort_keys=True) + "\n")
    print(json.dumps(out, indent=2, sort_keys=True))


if __name__ == "__main__":
    main()
