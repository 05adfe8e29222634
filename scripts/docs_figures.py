#!/usr/bin/env python3
"""Figures quoted in prose, and the programs that produce them.

A page quotes a measured figure through a marker, invisible once rendered:

    the robot ends <!--fig:laser-camera-slam.fused.final_error_cm-->2.9<!--/fig--> cm from the truth

The figure's value lives in a figures file, `docs/**/<source>.figures.json`, written by a
program (never by hand): {"source": ..., "command": ..., "figures": {key: text}}. Sources and
keys are lower case, so that a page can show the syntax in upper case without quoting. A page
generator writes the figures file next to its page; the example runs below write theirs next
to the page that discusses them.

    docs_figures.py check              exit 1 when a quoted figure differs from its figures file
                                       or names a figure that no file has (ctest label "docs")
    docs_figures.py update             rewrite every quoted figure from the figures files
    docs_figures.py run [NAME...] --bin-dir B [--quick --out DIR]
                                       run the examples behind the figure sources (all by default)
                                       and write their figures files (and pictures); --quick runs
                                       a reduced configuration into DIR and checks that it gives
                                       the same figure keys as the committed files
    docs_figures.py selftest           shows that `check` catches a changed figure

scripts/regenerate_docs.sh calls these; run it rather than this script.
"""

import argparse
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MARKER = re.compile(r"<!--fig:([a-z0-9_.\-]+)-->(.*?)<!--/fig-->", re.S)
PROSE_GLOBS = ["README.md", "docs/**/*.md"]


# ---- checking and updating prose -----------------------------------------------------------

def figures_files(root):
    return sorted(glob.glob(os.path.join(root, "docs", "**", "*.figures.json"), recursive=True))


def load_figures(root):
    """{source.key: text} over every figures file; a source named twice is an error."""
    figures, owner = {}, {}
    for path in figures_files(root):
        with open(path) as f:
            data = json.load(f)
        source = data["source"]
        if source in owner:
            sys.exit(f"docs_figures: source '{source}' is written by both {owner[source]} and {path}")
        owner[source] = path
        for key, text in data["figures"].items():
            if not re.fullmatch(r"[a-z0-9_.\-]+", f"{source}.{key}"):
                sys.exit(f"docs_figures: {path}: '{source}.{key}' must be lower-case letters, digits, '_', '.', '-'")
            figures[f"{source}.{key}"] = str(text)
    return figures


def prose_files(root):
    paths = []
    for pattern in PROSE_GLOBS:
        paths += glob.glob(os.path.join(root, pattern), recursive=True)
    return sorted(set(paths))


def check(root, quiet=False):
    figures = load_figures(root)
    problems, quoted = [], 0
    for path in prose_files(root):
        with open(path) as f:
            text = f.read()
        for m in MARKER.finditer(text):
            quoted += 1
            line = text.count("\n", 0, m.start()) + 1
            where = f"{os.path.relpath(path, root)}:{line}"
            key, shown = m.group(1), m.group(2)
            if key not in figures:
                problems.append(f"{where}: '{key}' is quoted, but no figures file has it")
            elif shown != figures[key]:
                problems.append(f"{where}: '{key}' reads '{shown}', its figures file says '{figures[key]}'")
    if quiet:
        return 1 if problems else 0
    for p in problems:
        print(p)
    if problems:
        print(f"docs_figures: {len(problems)} of {quoted} quoted figures are stale or unknown; "
              "`bash scripts/regenerate_docs.sh` regenerates them")
        return 1
    print(f"docs_figures: all {quoted} quoted figures match their figures files "
          f"({len(figures)} figures in {len(figures_files(root))} files)")
    return 0


def update(root):
    figures = load_figures(root)
    changed = 0
    for path in prose_files(root):
        with open(path) as f:
            text = f.read()

        def substitute(m):
            key = m.group(1)
            if key not in figures:
                sys.exit(f"docs_figures: {os.path.relpath(path, root)} quotes '{key}', which no figures file has")
            return f"<!--fig:{key}-->{figures[key]}<!--/fig-->"

        new = MARKER.sub(substitute, text)
        if new != text:
            with open(path, "w") as f:
                f.write(new)
            changed += 1
    print(f"docs_figures: updated the quoted figures of {changed} files")
    return 0


def selftest():
    """Copies the pages and figures files, changes one quoted figure and one figure, and
    expects `check` to name each."""
    with tempfile.TemporaryDirectory() as tmp:
        for path in prose_files(ROOT) + figures_files(ROOT):
            target = os.path.join(tmp, os.path.relpath(path, ROOT))
            os.makedirs(os.path.dirname(target), exist_ok=True)
            shutil.copy(path, target)
        if check(tmp, quiet=True) != 0:
            print("selftest: the committed pages do not pass `check`; fix them first")
            return 1
        page = next(p for p in prose_files(tmp) if MARKER.search(open(p).read()))
        text = open(page).read()
        m = MARKER.search(text)
        changed = m.group(2) + "1"
        with open(page, "w") as f:
            f.write(text[:m.start(2)] + changed + text[m.end(2):])
        if check(tmp, quiet=True) == 0:
            print(f"selftest FAILED: '{m.group(1)}' changed to '{changed}' in {page}, and check passed")
            return 1
        with open(page, "w") as f:
            f.write(text)
        # An unknown key, then a figures file that changed under the prose.
        with open(page, "w") as f:
            f.write(text + "\n<!--fig:no-such-source.figure-->1<!--/fig-->\n")
        if check(tmp, quiet=True) == 0:
            print("selftest FAILED: a quote of an unknown figure passed check")
            return 1
        with open(page, "w") as f:
            f.write(text)
        fig_path = figures_files(tmp)[0]
        data = json.load(open(fig_path))
        key = next(iter(data["figures"]))
        data["figures"][key] = str(data["figures"][key]) + "9"
        json.dump(data, open(fig_path, "w"))
        quoted = any(f"<!--fig:{data['source']}.{key}-->" in open(p).read() for p in prose_files(tmp))
        if quoted and check(tmp, quiet=True) == 0:
            print("selftest FAILED: a changed figures file passed check")
            return 1
    print("selftest: check catches a changed quote, an unknown figure and a changed figures file")
    return 0


# ---- figure sources: example runs -----------------------------------------------------------
#
# Each source runs one or more example commands ({bin}: the build's examples folder, {img}:
# where pictures go) with --json and turns their output into named figures, formatted as the
# prose shows them. `quick` replaces the arguments for CI's reduced run.

def pct(x):
    return f"{100 * x:.0f}%"


def fixed(x, digits):
    return f"{x:.{digits}f}"


def range_bearing_figures(out):
    r = out["main"]
    lo, hi = r["nees_bounds"]
    return {
        "runs": str(r["runs"]),
        "landmarks": str(r["landmarks"]),
        "path_m": fixed(r["path_length_m"], 0),
        "landmark_rmse_m": fixed(r["landmark_rmse_m"], 3),
        "final_pose_error_m": fixed(r["final_pose_error_m"], 3),
        "odometry_final_pose_error_m": fixed(r["odometry_final_pose_error_m"], 2),
        "nees_bounds": f"[{lo:.2f}, {hi:.2f}]",
        "nees_steps_inside": pct(r["nees_fraction_inside"]),
        "nees_time_mean": fixed(r["nees_mean"], 2),
    }


def parking_figures(out):
    s = out["study"]
    fixed_edge = s["no_adaptation"]
    return {
        "study.runs": str(s["runs"]),
        "study.parked": str(s["parked"]),
        "study.lateral_spread_cm": fixed(100 * s["x_spread_m"], 1),
        "study.axial_spread_cm": fixed(100 * s["y_spread_m"], 1),
        "study.mean_cycles": fixed(s["mean_cycles"], 1),
        "study.fixed_edge_mean_cycles": fixed(fixed_edge["mean_cycles"], 1),
        "study.noise_px": fixed(s["camera_robot"]["sigma_px"], 1),
    }


def laser_camera_figures(out):
    one = out["main"]["runs"][0]
    seeds = out["seeds"]
    runs = seeds["runs"]
    mean = lambda variant: sum(r[variant]["final_position_error_m"] for r in runs) / len(runs)
    return {
        "fused.landmarks": str(one["fused"]["landmarks"]),
        "corners.landmarks": str(one["laser_corners"]["landmarks"]),
        "fused.final_error_cm": fixed(100 * one["fused"]["final_position_error_m"], 1),
        "corners.final_error_cm": fixed(100 * one["laser_corners"]["final_position_error_m"], 1),
        "seeds": str(seeds["seeds"]),
        "seeds.fused_lower": str(seeds["seeds_where_fused_beats_corners"]),
        "seeds.fused_mean_error_cm": fixed(100 * mean("fused"), 0),
        "seeds.corners_mean_error_cm": fixed(100 * mean("laser_corners"), 0),
    }


def moving_objects_figures(out):
    d = out["main"]
    scene, slam = d["default_scene"], d["slam_landmark_rmse_m"]
    figures = {
        "cases_detected": str(d["cases_detected"]),
        "cases": str(len(d["cases"])),
        "static.scans": str(d["static_check"]["scans"]),
        "static.false_objects": str(d["static_check"]["false_objects"]),
        "scene.precision": fixed(scene["points"]["precision"], 2),
        "scene.recall": pct(scene["points"]["recall"]),
        "slam.rmse_without_removal_cm": fixed(100 * slam["without_removal"], 2),
        "slam.rmse_with_removal_cm": fixed(100 * slam["with_removal"], 2),
        "slam.rmse_with_memory_cm": fixed(100 * slam["with_removal_and_memory"], 2),
    }
    if "real" in out:
        real = out["real"]["real"]
        figures["real.detections_per_scan"] = fixed(real["detections_per_scan_mean"], 1)
        figures["real.background_flagged"] = f"{100 * real['background_false_detection_rate']:.2f}%"
    return figures


def study_figures(_out):
    """The README's summary of the study, from the study's own docs/study/summary.csv."""
    import csv
    rows = list(csv.DictReader(open(os.path.join(ROOT, "docs", "study", "summary.csv"))))

    def series(sweep, occlusion, pipeline):
        return sorted(((float(r["x"]), r) for r in rows if r["sweep"] == sweep and r["occlusion"] == occlusion
                       and r["pipeline"] == pipeline), key=lambda t: t[0])

    def mean_ratio(sweep, occlusion, pipeline, keep):
        vals = [float(r["convergence_ratio"]) for x, r in series(sweep, occlusion, pipeline) if keep(x)]
        return sum(vals) / len(vals)

    high_noise, fewer = (lambda x: x > 5), (lambda x: x < 1)
    figures = {"runs": f"{sum(int(r['runs']) for r in rows):,}"}
    for name, pipeline in (("none", "none"), ("thesis", "after_xyz"), ("first_sight", "first_sight")):
        figures[f"noise_above_5px.{name}"] = pct(mean_ratio("noise", "ignored", pipeline, high_noise))
        figures[f"fewer_trees.{name}"] = pct(mean_ratio("density", "ignored", pipeline, fewer))
        figures[f"fewer_trees_non_occluded.{name}"] = pct(mean_ratio("density", "non_occluded_only", pipeline, fewer))
    first = series("noise", "ignored", "first_sight")
    none = series("noise", "ignored", "none")
    figures["first_sight_lower_et_levels"] = str(sum(
        float(a["trajectory_error_mean"]) < float(b["trajectory_error_mean"]) for (_, a), (_, b) in zip(first, none)))
    figures["noise_levels"] = str(len(first))
    return figures


SOURCES = {
    "range-bearing-slam": {
        "file": "docs/figures/range-bearing-slam.figures.json",
        "runs": {"main": "{bin}/range_bearing_slam/range_bearing_slam --runs 20 --json --svg {img}/range_bearing_slam.svg"},
        "quick": {"main": "{bin}/range_bearing_slam/range_bearing_slam --runs 2 --json --svg {img}/range_bearing_slam.svg"},
        "figures": range_bearing_figures,
    },
    "parking": {
        "file": "docs/examples/parking.figures.json",
        "runs": {"single": "{bin}/parking/parking --json --svg-prefix {img}/parking",
                 "study": "{bin}/parking/parking --study --json --svg-prefix {img}/parking"},
        "quick": {"single": "{bin}/parking/parking --json --svg-prefix {img}/parking",
                  "study": "{bin}/parking/parking --study --runs 10 --json --svg-prefix {img}/parking"},
        "figures": parking_figures,
    },
    "laser-camera-slam": {
        "file": "docs/examples/laser-camera-slam.figures.json",
        "runs": {"main": "{bin}/laser_camera_slam/laser_camera_slam --json --svg-prefix {img}/laser_camera_",
                 "seeds": "{bin}/laser_camera_slam/laser_camera_slam --seeds 10 --json --svg-prefix ''"},
        "quick": {"main": "{bin}/laser_camera_slam/laser_camera_slam --json --laps 0.2 --svg-prefix {img}/laser_camera_",
                  "seeds": "{bin}/laser_camera_slam/laser_camera_slam --seeds 2 --laps 0.2 --json --svg-prefix ''"},
        "figures": laser_camera_figures,
    },
    "moving-objects": {
        "file": "docs/examples/moving-objects.figures.json",
        "runs": {"main": "{bin}/moving_objects/moving_objects --json --svg-prefix {img}/moving_objects",
                 "real?": "{bin}/moving_objects/moving_objects --real --json --svg-prefix {img}/moving_objects"},
        "quick": {"main": "{bin}/moving_objects/moving_objects --json --slam-seeds 1 --svg-prefix {img}/moving_objects"},
        "figures": moving_objects_figures,
    },
    "study-summary": {
        "file": "docs/study/summary.figures.json",
        "runs": {},
        "quick": {},
        "figures": study_figures,
        "command": "python3 scripts/docs_figures.py run study-summary (from docs/study/summary.csv, "
                   "written by `bash scripts/run_study.sh`)",
    },
}


def run_sources(names, bin_dir, quick, out_dir):
    failed = False
    for name in names or list(SOURCES):
        if name not in SOURCES:
            sys.exit(f"docs_figures: no figure source '{name}' (sources: {', '.join(SOURCES)})")
        src = SOURCES[name]
        target_root = out_dir if quick else ROOT
        img = os.path.join(target_root, "docs", "images")
        os.makedirs(img, exist_ok=True)
        outputs, commands, skipped = {}, [], False
        for label, template in (src["quick"] if quick else src["runs"]).items():
            optional = label.endswith("?")  # needs data that may be absent: skipped then
            command = template.format(bin=bin_dir, img=img)
            shown = template.format(bin="build/docs/examples", img="docs/images")
            print(f"==> {name}: {command}", file=sys.stderr)
            proc = subprocess.run(command, shell=True, stdout=subprocess.PIPE, cwd=ROOT)
            if proc.returncode == 77 and optional:
                print("    skipped (exit 77: its data are absent)", file=sys.stderr)
                skipped = True
                continue
            if proc.returncode != 0:
                sys.exit(f"docs_figures: '{command}' failed with exit code {proc.returncode}")
            outputs[label.rstrip("?")] = json.loads(proc.stdout)
            commands.append(shown)
        figures = src["figures"](outputs)
        path = os.path.join(target_root, src["file"])
        committed_path = os.path.join(ROOT, src["file"])
        if skipped and not quick and os.path.exists(committed_path):
            # A run skipped for want of its data keeps the figures of the last run that had it.
            for key, text in json.load(open(committed_path))["figures"].items():
                figures.setdefault(key, text)
        data = {"source": name,
                "command": src.get("command") or "bash scripts/regenerate_docs.sh (" + "; ".join(commands) + ")",
                "figures": figures}
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w") as f:
            json.dump(data, f, indent=2, sort_keys=True)
            f.write("\n")
        if quick and os.path.exists(committed_path):
            committed = set(json.load(open(committed_path))["figures"])
            # Figures of optional runs (real data) may be absent from a quick run.
            missing = {k for k in committed - set(figures) if not k.startswith("real.")}
            if missing or set(figures) - committed:
                print(f"docs_figures: the quick run of '{name}' gives other figures than {src['file']}: "
                      f"missing {sorted(missing)}, new {sorted(set(figures) - committed)}")
                failed = True
        print(f"    {len(figures)} figures -> {os.path.relpath(path, target_root) if not quick else path}",
              file=sys.stderr)
    return 1 if failed else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("command", choices=["check", "update", "run", "selftest"])
    parser.add_argument("names", nargs="*", help="figure sources for `run` (default: all)")
    parser.add_argument("--root", default=ROOT, help="repository root for check/update")
    parser.add_argument("--bin-dir", help="the build's examples folder, for `run`")
    parser.add_argument("--quick", action="store_true", help="`run`: the reduced configuration, into --out")
    parser.add_argument("--out", help="`run --quick`: folder for the figures files and pictures")
    args = parser.parse_args()
    if args.command == "check":
        return check(args.root)
    if args.command == "update":
        return update(args.root)
    if args.command == "selftest":
        return selftest()
    if args.quick and not args.out:
        parser.error("run --quick needs --out (it never writes into docs/)")
    needs_bin = any(SOURCES[n]["runs"] for n in (args.names or SOURCES) if n in SOURCES)
    if needs_bin and not args.bin_dir:
        parser.error("run needs --bin-dir (the examples folder of a build)")
    return run_sources(args.names, os.path.abspath(args.bin_dir) if args.bin_dir else "", args.quick,
                       os.path.abspath(args.out) if args.out else None)


if __name__ == "__main__":
    sys.exit(main())
