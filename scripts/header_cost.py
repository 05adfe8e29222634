#!/usr/bin/env python3
"""What including sylva costs a user's translation unit, against #include <Eigen/Dense>.

Compiles small translation units with `-std=c++17 -O2 -c` and measures each compile's CPU
time (user + system of the compiler process, which a busy machine inflates less than wall
time), always beside `#include <Eigen/Dense>` compiled in the same round, so that the ratio
is what counts:

  - the umbrella headers (`sylva/sylva.hpp` and the topic umbrellas), each with an empty main;
  - the README's sample program (one Ekf<Unicycle2D, Point2>, one RangeBearing update);
  - the same work written by hand with Eigen alone (scripts/header_cost_plain_ekf.cpp): the
    floor that tells what a target for the sample asks;
  - every public header alone (`--headers`), with an empty main.

The umbrellas and the sample run in `--runs` interleaved rounds (default 3): each round
compiles Eigen/Dense, then every case, and each case's ratio is taken against that round's
Eigen/Dense. A target holds only when it holds in every round. Each header alone is compiled
once and compared with the median Eigen/Dense time of its compiler.

    python3 scripts/header_cost.py                 # g++ and clang++, 3 rounds, every header;
                                                   # rewrites docs/build-time.md and its figures file
    python3 scripts/header_cost.py --no-headers    # umbrellas and sample only (a few minutes)
    python3 scripts/header_cost.py --print-only    # prints the tables, writes nothing
    python3 scripts/header_cost.py --render-only   # rewrites the page from docs/build-time.raw.json
                                                   # (the last run's times), measures nothing
    python3 scripts/header_cost.py --check-coverage  # fails when a public header or umbrella
                                                   # is missing from the last run (a test)

The targets (issue 18): with g++ the umbrella at most 2x and the sample at most 3x Eigen/Dense;
with clang++ at most 1.5x and 2.5x.
"""

import argparse
import datetime
import glob
import json
import os
import platform
import re
import resource
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
INCLUDE = os.path.join(ROOT, "include")
DOC = os.path.join(ROOT, "docs", "build-time.md")
FIGURES = os.path.join(ROOT, "docs", "build-time.figures.json")
RAW = os.path.join(ROOT, "docs", "build-time.raw.json")  # every measured time, for --render-only
COMMAND = "python3 scripts/header_cost.py"

# (compiler label, umbrella target, sample target)
TARGETS = {"g++": (2.0, 3.0), "clang++": (1.5, 2.5)}
UMBRELLAS = ["sylva/sylva.hpp", "sylva/monocular.hpp", "sylva/laser_camera.hpp", "sylva/laser.hpp",
             "sylva/association.hpp", "sylva/consistency.hpp", "sylva/sim.hpp", "sylva/datasets.hpp",
             "sylva/eval.hpp"]


def cpu_seconds_of(argv):
    """Runs argv; returns (user + system CPU seconds of the child, its exit code, its stderr)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    proc = subprocess.run(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    seconds = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return seconds, proc.returncode, proc.stderr


def eigen_include_dir():
    for candidate in ("/usr/include/eigen3", "/usr/local/include/eigen3"):
        if os.path.isdir(os.path.join(candidate, "Eigen")):
            return candidate
    sys.exit("header_cost: Eigen 3 not found (apt-get install libeigen3-dev)")


def readme_sample():
    """The first ```cpp block of README.md: the sample program a new user compiles first."""
    with open(os.path.join(ROOT, "README.md")) as f:
        text = f.read()
    match = re.search(r"```cpp\n(.*?)```", text, re.S)
    if not match:
        sys.exit("header_cost: README.md has no ```cpp block")
    return match.group(1)


def plain_ekf():
    """The README sample's work written by hand with Eigen alone (no sylva)."""
    with open(os.path.join(ROOT, "scripts", "header_cost_plain_ekf.cpp")) as f:
        return f.read()


def public_headers():
    headers = []
    for path in sorted(glob.glob(os.path.join(INCLUDE, "sylva", "**", "*.hpp"), recursive=True)):
        rel = os.path.relpath(path, INCLUDE)
        if "/detail/" in rel:
            continue  # internal: included through the public headers
        headers.append(rel)
    return headers


class Compiler:
    def __init__(self, name, workdir, eigen):
        self.name = name
        self.workdir = workdir
        self.flags = ["-std=c++17", "-O2", "-c", "-I", INCLUDE, "-I", eigen, "-o", os.devnull]
        self.version = subprocess.run([name, "--version"], capture_output=True, text=True).stdout.splitlines()[0]

    def time(self, label, source):
        path = os.path.join(self.workdir, re.sub(r"[^A-Za-z0-9_.]", "_", label) + ".cpp")
        with open(path, "w") as f:
            f.write(source)
        seconds, code, err = cpu_seconds_of([self.name, *self.flags, path])
        if code != 0:
            sys.exit(f"header_cost: {self.name} failed on {label}:\n{err}")
        return seconds


def short_name(signature):
    """A library function's instantiation, short: `Ekf::` for the filter, `sylva::` dropped, template
    arguments beyond the first level elided."""
    text = re.sub(r"sylva::BasicEkf<[^>]*>::", "Ekf::", signature).replace("sylva::", "")
    text = re.sub(r" \(lambda at [^)]*\)", " (lambda)", text)
    out, depth = [], 0
    for ch in text:
        if ch == "<":
            depth += 1
            out.append("<" if depth == 1 else ("..." if depth == 2 else ""))
        elif ch == ">":
            depth -= 1
            if depth == 0:
                out.append(">")
        elif depth <= 1:
            out.append(ch)
    return "".join(out)


def sample_trace(workdir, eigen, top=12):
    """Where clang++ spends the sample program's compile: its -ftime-trace, summarized as the
    front end, the back end, and the library functions whose instantiation costs most (each
    inclusive of what it instantiates in turn, so nested entries overlap)."""
    path = os.path.join(workdir, "sample_trace.cpp")
    with open(path, "w") as f:
        f.write(readme_sample())
    obj = os.path.join(workdir, "sample_trace.o")
    subprocess.run(["clang++", "-std=c++17", "-O2", "-c", "-I", INCLUDE, "-I", eigen, path, "-o", obj,
                    "-ftime-trace", "-ftime-trace-granularity=20"], check=True, capture_output=True)
    with open(os.path.join(workdir, "sample_trace.json")) as f:
        events = [e for e in json.load(f)["traceEvents"] if e.get("ph") == "X"]
    totals = {e["name"]: e["dur"] / 1e6 for e in events if e["name"] in ("Total Frontend", "Total Backend")}
    funcs = [e for e in events if e["name"] == "InstantiateFunction"
             and e.get("args", {}).get("detail", "").startswith("sylva::")]
    funcs.sort(key=lambda e: -e["dur"])
    rows = [(short_name(e["args"]["detail"]), e["dur"] / 1e6) for e in funcs[:top]]
    return {"frontend": totals.get("Total Frontend", 0.0), "backend": totals.get("Total Backend", 0.0), "functions": rows}


def include_source(header):
    return f"#include <{header}>\nint main() {{}}\n"


EIGEN = include_source("Eigen/Dense")


def measure(compilers, runs, with_headers, progress):
    sample = readme_sample()
    plain = plain_ekf()
    umbrellas = [u for u in UMBRELLAS if os.path.exists(os.path.join(INCLUDE, u))]
    result = {"runs": runs, "compilers": {}}
    for compiler in compilers:
        entry = {"version": compiler.version, "rounds": [], "headers": {}}
        for r in range(runs):
            round_ = {"eigen": compiler.time("eigen_dense", EIGEN), "cases": {}}
            for u in umbrellas:
                round_["cases"][u] = compiler.time(u, include_source(u))
                progress(f"{compiler.name} round {r + 1}: {u} {round_['cases'][u]:.2f} s "
                         f"(Eigen/Dense {round_['eigen']:.2f} s)")
            round_["cases"]["sample"] = compiler.time("readme_sample", sample)
            progress(f"{compiler.name} round {r + 1}: README sample {round_['cases']['sample']:.2f} s")
            round_["cases"]["plain"] = compiler.time("plain_ekf", plain)
            progress(f"{compiler.name} round {r + 1}: plain Eigen EKF {round_['cases']['plain']:.2f} s")
            entry["rounds"].append(round_)
        if with_headers:
            eigen_median = statistics.median(rd["eigen"] for rd in entry["rounds"])
            for h in public_headers():
                seconds = compiler.time(h, include_source(h))
                entry["headers"][h] = seconds
                progress(f"{compiler.name}: {h} {seconds:.2f} s ({seconds / eigen_median:.1f}x)")
        result["compilers"][compiler.name] = entry
    return result


def ratios(entry, case):
    return [rd["cases"][case] / rd["eigen"] for rd in entry["rounds"]]


def fmt(x):
    """Seconds and ratios: one decimal from 1 up, two below (0.85 s, 1.7x)."""
    return f"{x:.1f}" if round(x, 2) >= 1.0 else f"{x:.2f}"


def render(result, cpu):
    figures = {}
    lines = []
    add = lines.append
    add("# What including sylva costs")
    add("")
    add(f"Generated by `{COMMAND}` on {result['date']}; do not edit by hand. Machine: {cpu}, "
        f"{os.cpu_count()} cores.")
    add("")
    add("A header-only library is compiled again in every translation unit that includes it, so its "
        "compile time is the user's. Each figure is the CPU time (user + system) of one "
        "`-std=c++17 -O2 -c` compile, and each is compared with `#include <Eigen/Dense>` compiled "
        "in the same round (every library that uses Eigen pays that much). The ratio is what "
        "counts: the machine is shared, and a busy machine slows both alike. The umbrellas and "
        f"the README's sample program run in {result['runs']} interleaved rounds; a target is met "
        "only when it holds in every round.")
    add("")
    # g++ first, as measured (the raw JSON may hold the compilers in another order).
    order = sorted(result["compilers"], key=lambda c: (c != "g++", c))
    for name, entry in ((c, result["compilers"][c]) for c in order):
        key = "gxx" if name == "g++" else "clangxx"
        umbrella_target, sample_target = TARGETS.get(name, (None, None))
        eig = [rd["eigen"] for rd in entry["rounds"]]
        add(f"## {name} ({entry['version']})")
        add("")
        add(f"`#include <Eigen/Dense>` with an empty main: {fmt(statistics.median(eig))} s "
            f"(median of {len(eig)} rounds, {fmt(min(eig))} to {fmt(max(eig))} s).")
        figures[f"{key}.eigen_seconds"] = fmt(statistics.median(eig))
        add("")
        add("| translation unit | CPU time, median (s) | ratio to Eigen/Dense, median | ratio, every round | target | met? |")
        add("|---|---|---|---|---|---|")
        # The umbrellas in their list's order, then the sample and its floor (the raw JSON keeps
        # its keys sorted).
        measured = entry["rounds"][0]["cases"]
        rank = {c: i for i, c in enumerate(UMBRELLAS + ["sample", "plain"])}
        cases = sorted(measured, key=lambda c: (rank.get(c, len(rank)), c))
        for case in cases:
            secs = statistics.median(rd["cases"][case] for rd in entry["rounds"])
            rs = ratios(entry, case)
            label = {"sample": "README sample program (one filter, one update)",
                     "plain": "the sample's work by hand with Eigen alone (`scripts/header_cost_plain_ekf.cpp`)"
                     }.get(case, f"`#include <{case}>`")
            target = sample_target if case == "sample" else (umbrella_target if case == "sylva/sylva.hpp" else None)
            verdict = "" if target is None else ("yes" if max(rs) <= target else "**no**")
            add(f"| {label} | {fmt(secs)} | {fmt(statistics.median(rs))} | "
                f"{', '.join(fmt(x) for x in rs)} | {'' if target is None else f'<= {target:g}x'} | {verdict} |")
            short = case if case in ("sample", "plain") else case.replace("sylva/", "").replace(".hpp", "")
            figures[f"{key}.{short}.ratio"] = fmt(statistics.median(rs))
            figures[f"{key}.{short}.seconds"] = fmt(secs)
            if target is not None:
                figures[f"{key}.{short}.met"] = "met" if max(rs) <= target else "not met"
        if "plain" in cases and sample_target:
            plain_rs, sample_rs = ratios(entry, "plain"), ratios(entry, "sample")
            add("")
            add(f"The last row is the floor: the README sample's work written by hand with Eigen alone, "
                f"{fmt(statistics.median(plain_rs))}x Eigen/Dense, so the sample's target of {sample_target:g}x "
                f"leaves sylva {fmt(sample_target / statistics.median(plain_rs))}x of what a hand-written filter costs, "
                f"where it takes {fmt(statistics.median(s / p for s, p in zip(sample_rs, plain_rs)))}x (median over rounds "
                "of the sample's time over the hand-written one's).")
            figures[f"{key}.sample_over_plain"] = fmt(statistics.median(s / p for s, p in zip(sample_rs, plain_rs)))
        add("")
        if entry["headers"]:
            eig_median = statistics.median(eig)
            add(f"Each public header alone (one compile each, against the median Eigen/Dense above), "
                f"most expensive first:")
            add("")
            add("| header | CPU time (s) | ratio to Eigen/Dense |")
            add("|---|---|---|")
            for h, secs in sorted(entry["headers"].items(), key=lambda kv: -kv[1]):
                add(f"| `{h}` | {fmt(secs)} | {fmt(secs / eig_median)} |")
            worst = max(entry["headers"].values()) / eig_median
            figures[f"{key}.worst_header_ratio"] = fmt(worst)
            add("")
    trace = result.get("sample_trace")
    if trace:
        add("## Where the sample program's time goes")
        add("")
        add(f"One `clang++ -ftime-trace` compile of the README's sample: "
            f"{fmt(trace['frontend'])} s in the front end (parsing, and instantiating templates), "
            f"{fmt(trace['backend'])} s in the back end (optimizing and emitting the instantiated code, "
            "in proportion to how much was instantiated). The library functions whose instantiation "
            "costs most, each including what it instantiates in turn (so nested entries overlap; "
            "wall time of that one compile):")
        add("")
        add("| function | s |")
        add("|---|---|")
        for name, secs in trace["functions"]:
            add(f"| `{name}` | {fmt(secs)} |")
        add("")
        add("The filter's linearization policies are chosen at run time (`setLinearizationPoint`), so "
            "one `update` compiles the code of every policy that applies to the filter's types (the "
            "iterated update's iterations, first-estimates and ideal linearization points, the "
            "invariant EKF's transport for a planar robot). The check of a noise's or a prior's "
            "covariance is compiled once for every size (`detail::checkCovarianceMatrix`, which "
            "factors through the batched update's own Cholesky type). The arithmetic keeps its fixed "
            "sizes, so each distinct small size compiles its products and the factorization of S "
            "once more: with sizes known only at run time Eigen orders some sums differently (for "
            "an odd number of rows), which changes the last bits of every result built on them. "
            "Policies compiled only where they are chosen would narrow the sample's factor over the "
            "hand-written floor in the tables above; no restructuring can take the sample below that "
            "floor while it does the same work with Eigen's fixed-size expressions, so a target below "
            "the floor is out of reach for the "
            "sample as it stands.")
        add("")
    add("## Large units and g++")
    add("")
    add("g++ 12 spends most of a large unit's time instantiating templates, and that time grows faster "
        "than the unit: [unit-growth.md](unit-growth.md) (`python3 scripts/unit_growth.py`) compiles the "
        "same fixed-size Eigen products, Eigen alone, as one unit and as two, with g++ and clang++. This is "
        "why the tests compile one file per unit with g++ (tests/CMakeLists.txt).")
    add("")
    return "\n".join(lines) + "\n", figures


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def check_coverage():
    """0 when the last run measured every public header (each compiler) and every umbrella, else
    a message naming what the page lacks: a header added since must be measured before it lands."""
    try:
        with open(RAW) as f:
            result = json.load(f)["result"]
    except (OSError, ValueError, KeyError) as e:
        return f"header_cost: cannot read {os.path.relpath(RAW, ROOT)}: {e}"
    missing = []
    for name, measured in sorted(result.get("compilers", {}).items()):
        for h in public_headers():
            if h not in measured.get("headers", {}):
                missing.append(f"{name}: header {h}")
        for h in sorted(set(measured.get("headers", {})) - set(public_headers())):
            missing.append(f"{name}: header {h} (measured, but no longer in include/)")
        rounds = measured.get("rounds") or []
        for u in UMBRELLAS:
            if not rounds or not all(u in r.get("cases", {}) for r in rounds):
                missing.append(f"{name}: umbrella {u}")
    if not result.get("compilers"):
        missing.append("no compiler measured")
    if missing:
        return ("header_cost: docs/build-time.md is stale; run `python3 scripts/header_cost.py`:\n  "
                + "\n  ".join(missing))
    print(f"header_cost: the last run measured all {len(public_headers())} public headers and "
          f"{len(UMBRELLAS)} umbrellas")
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--compilers", nargs="+", default=["g++", "clang++"])
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--no-headers", action="store_true", help="leave out each header alone")
    parser.add_argument("--print-only", action="store_true", help="print the page, write nothing")
    parser.add_argument("--render-only", action="store_true",
                        help=f"render the page from {os.path.relpath(RAW, ROOT)}, measure nothing")
    parser.add_argument("--check-coverage", action="store_true",
                        help=f"check that {os.path.relpath(RAW, ROOT)} measured every public header and umbrella")
    parser.add_argument("--quiet", action="store_true")
    args = parser.parse_args()
    if args.check_coverage:
        sys.exit(check_coverage())
    if args.runs < 1:
        sys.exit("header_cost: --runs must be at least 1")
    if args.render_only:
        try:
            with open(RAW) as f:
                raw = json.load(f)
        except (OSError, ValueError) as e:
            sys.exit(f"header_cost: cannot read {os.path.relpath(RAW, ROOT)}: {e}")
        result, cpu = raw["result"], raw["cpu"]
    else:
        eigen = eigen_include_dir()
        progress = (lambda s: None) if args.quiet else (lambda s: print(s, file=sys.stderr, flush=True))
        with tempfile.TemporaryDirectory(prefix="sylva-header-cost.") as work:
            compilers = [Compiler(c, work, eigen) for c in args.compilers]
            result = measure(compilers, args.runs, not args.no_headers, progress)
            if "clang++" in args.compilers:
                result["sample_trace"] = sample_trace(work, eigen)
        result["date"] = datetime.date.today().isoformat()
        cpu = cpu_model()
    page, figures = render(result, cpu)
    if args.print_only:
        print(page)
        return
    if not args.render_only:
        with open(RAW, "w") as f:
            json.dump({"cpu": cpu, "result": result}, f, indent=1, sort_keys=True)
            f.write("\n")
    with open(DOC, "w") as f:
        f.write(page)
    with open(FIGURES, "w") as f:
        json.dump({"source": "build-time", "command": COMMAND, "figures": figures}, f, indent=1, sort_keys=True)
        f.write("\n")
    print(page)
    print(f"header_cost: wrote {os.path.relpath(DOC, ROOT)} and {os.path.relpath(FIGURES, ROOT)}", file=sys.stderr)


if __name__ == "__main__":
    main()
