#!/usr/bin/env python3
"""The summary of a scripts/fuzz.sh run, and the generated block of docs/reliability.md.

  fuzz_report.py collect --work DIR --targets a,b --command CMD --cxx CXX --cxxflags F
                         --fuzz-flags F --repo REPO > summary.json
  fuzz_report.py render summary.json docs/reliability.md

collect reads, for every target, DIR/<target>/logs/fuzz-*.log (libFuzzer's output with
-print_final_stats=1), exit_code, seconds, seed_count and the artifacts/ folder, and prints
one JSON object. render replaces the text between `<!-- BEGIN generated: fuzz ... -->` and
`<!-- END generated: fuzz -->` in the page with tables made from that object. Every figure
on the page comes from the summary; nothing is typed by hand. Python 3 standard library only.
"""
import argparse
import datetime
import json
import os
import platform
import re
import subprocess
import sys

LOADERS = {
    "numeric_table": "`sylva::datasets::readNumericTable`, its format (delimiters among `\" \\t,;|\"`, "
                     "field counts, comment character, non-finite values) taken from the input",
    "utias_mrclam": "`sylva::datasets::loadUtiasMrclam`: a whole MRCLAM folder (Barcodes, landmarks, "
                    "odometry, measurements, ground truth of the robots asked for)",
    "victoria_park": "`loadVictoriaParkMeasurements`, `loadVictoriaParkOdometry`, "
                     "`loadVictoriaParkGps` and the folder loader `loadVictoriaPark`",
    "leg_tracker": "`sylva::datasets::loadLegTrackerRecording`: the scan parameter file and the "
                   "CSV of scans",
    "trunk_detections": "`sylva::datasets::readTrunkDetections` and `readCameraIntrinsics`: a "
                        "trunk detector's per-frame CSV and the camera's intrinsics",
}
# Files libFuzzer writes for a finding (-artifact_prefix).
ARTIFACT = re.compile(r"^(crash|leak|timeout|oom)-")
STATUS = re.compile(r"^#(\d+)\s+\w+\s+cov: (\d+) ft: (\d+) corp: (\d+)/(\S+)")
STAT = re.compile(r"^stat::(\w+):\s+(\d+)")


def run(cmd):
    try:
        return subprocess.run(cmd, capture_output=True, text=True, check=False).stdout.strip()
    except OSError:
        return ""


def read(path, default=""):
    try:
        with open(path, encoding="utf-8") as f:
            return f.read().strip()
    except OSError:
        return default


def parse_log(text):
    """The last status line's coverage and libFuzzer's final stats of one job's log."""
    out = {}
    for line in text.splitlines():
        m = STATUS.match(line)
        if m:
            out.update(cov=int(m[2]), ft=int(m[3]), corpus_units=int(m[4]), corpus_size=m[5])
        m = STAT.match(line)
        if m:
            out[m[1]] = int(m[2])
    return out


def target_summary(work, name):
    folder = os.path.join(work, name)
    logs = sorted(f for f in os.listdir(os.path.join(folder, "logs")) if re.match(r"fuzz-\d+\.log$", f))
    jobs = [parse_log(read(os.path.join(folder, "logs", f))) for f in logs]
    artifacts = sorted(f for f in os.listdir(os.path.join(folder, "artifacts")) if ARTIFACT.match(f))
    exit_code = int(read(os.path.join(folder, "exit_code"), "-1"))
    complete = bool(jobs) and all("number_of_executed_units" in j for j in jobs)
    findings = len(artifacts)
    if not artifacts and (exit_code != 0 or not complete):
        findings = 1  # the fuzzer failed or stopped early without saving an input
    return {
        "target": name,
        "loaders": LOADERS.get(name, ""),
        "jobs": len(jobs),
        "executions": sum(j.get("number_of_executed_units", 0) for j in jobs),
        "exec_per_s": sum(j.get("average_exec_per_sec", 0) for j in jobs),
        "cov": max((j.get("cov", 0) for j in jobs), default=0),
        "ft": max((j.get("ft", 0) for j in jobs), default=0),
        "corpus_units": max((j.get("corpus_units", 0) for j in jobs), default=0),
        "corpus_size": jobs[-1].get("corpus_size", "") if jobs else "",
        "seed_inputs": int(read(os.path.join(folder, "seed_count"), "0")),
        "new_units": sum(j.get("new_units_added", 0) for j in jobs),
        "peak_rss_mb": max((j.get("peak_rss_mb", 0) for j in jobs), default=0),
        "seconds": int(read(os.path.join(folder, "seconds"), "0")),
        "exit_code": exit_code,
        "findings": findings,
        "artifacts": artifacts,
    }


def machine():
    cpu = ""
    for line in read("/proc/cpuinfo").splitlines():
        if line.startswith("model name"):
            cpu = line.split(":", 1)[1].strip()
            break
    os_name = ""
    for line in read("/etc/os-release").splitlines():
        if line.startswith("PRETTY_NAME="):
            os_name = line.split("=", 1)[1].strip('"')
    return {"cpu": cpu, "cores": os.cpu_count(), "os": os_name, "kernel": platform.release()}


def collect(args):
    summary = {
        "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
        "command": args.command,
        "commit": run(["git", "-C", args.repo, "describe", "--always", "--dirty"]),
        "compiler": (run([args.cxx, "--version"]).splitlines() or [args.cxx])[0],
        "cxxflags": args.cxxflags,
        "fuzz_flags": args.fuzz_flags,
        "machine": machine(),
        "targets": [target_summary(args.work, t) for t in args.targets.split(",")],
    }
    json.dump(summary, sys.stdout, indent=2)
    print()


def block(s):
    m = s["machine"]
    total = sum(t["executions"] for t in s["targets"])
    findings = sum(t["findings"] for t in s["targets"])
    out = [
        f"Run of {s['date']} on commit `{s['commit']}`: `{s['command']}`",
        f"(each target in turn, one process at a time), on {m['cpu']} ({m['cores']} cores), "
        f"{m['os']}, Linux {m['kernel']}; {s['compiler']}.",
        "",
        f"- compiled with `{s['cxxflags']}`",
        f"- run with `{s['fuzz_flags']}` and the target's working corpus, first filled with "
        "`fuzz/corpus/<target>/` and `fuzz/findings/<target>/`",
        "",
        "| target | what it feeds | executions | exec/s | cov | ft | corpus at the end (seeds) | "
        "time (s) | findings |",
        "|---|---|---:|---:|---:|---:|---|---:|---:|",
    ]
    for t in s["targets"]:
        loaders = LOADERS.get(t["target"], t["loaders"]).replace("|", "\\|")  # a '|' would end the cell
        out.append(f"| `{t['target']}` | {loaders} | {t['executions']:,} | {t['exec_per_s']:,} | {t['cov']} | "
                   f"{t['ft']} | {t['corpus_units']} inputs, {t['corpus_size']} ({t['seed_inputs']}) | "
                   f"{t['seconds']} | {t['findings']} |")
    out.append("")
    out.append("`cov` and `ft` are libFuzzer's figures from the last status line: code edges covered and "
               "features (edges with hit counts, comparisons) seen. exec/s is libFuzzer's average.")
    out.append("")
    if findings == 0:
        out.append(f"**No finding** in {total:,} executions: no crash, sanitizer report, leak, timeout, broken "
                   "invariant of loaded data or exception other than `sylva::Error`.")
    else:
        out.append(f"**{findings} finding(s)** in {total:,} executions:")
        for t in s["targets"]:
            for a in t["artifacts"]:
                out.append(f"- `{t['target']}`: `{a}`")
            if t["findings"] and not t["artifacts"]:
                out.append(f"- `{t['target']}`: the fuzzer ended with exit code {t['exit_code']} and no report")
    out.append("")
    out.append("Regenerate with `bash scripts/fuzz.sh --runs 1000000` (the summary it renders: "
               "`build/fuzz/summary.json`).")
    return "\n".join(out) + "\n"


def render(args):
    with open(args.summary, encoding="utf-8") as f:
        s = json.load(f)
    with open(args.doc, encoding="utf-8") as f:
        text = f.read()
    pattern = re.compile(r"(<!-- BEGIN generated: fuzz [^\n]*-->\n)(.*?)(<!-- END generated: fuzz -->)", re.S)
    if not pattern.search(text):
        raise SystemExit(f"fuzz_report.py: no block <!-- BEGIN generated: fuzz ... --> ... "
                         f"<!-- END generated: fuzz --> in {args.doc}")
    text = pattern.sub(lambda m: m[1] + block(s) + m[3], text, count=1)
    with open(args.doc, "w", encoding="utf-8") as f:
        f.write(text)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="what", required=True)
    c = sub.add_parser("collect")
    for flag in ("--work", "--targets", "--command", "--cxx", "--cxxflags", "--fuzz-flags", "--repo"):
        c.add_argument(flag, required=True)
    r = sub.add_parser("render")
    r.add_argument("summary")
    r.add_argument("doc")
    args = p.parse_args()
    collect(args) if args.what == "collect" else render(args)


if __name__ == "__main__":
    main()
