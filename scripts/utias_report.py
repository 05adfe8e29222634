#!/usr/bin/env python3
"""The generated tables of docs/examples/utias.md from the JSON of `utias`.

scripts/real_data_report.sh runs it after the example; by hand (repository root):

  utias --json > utias.json
  utias --leave-one-out --json > utias_loro.json
  python3 scripts/utias_report.py --run utias.json --loro utias_loro.json --doc docs/examples/utias.md

It replaces, in --doc, the text between `<!-- BEGIN generated: NAME -->` and
`<!-- END generated: NAME -->` for NAME in
  loro     the leave-one-robot-out table and its summary against the targets (--loro),
  study    the settings of the grid that the procedure on all robots ranks first (--loro),
  results  the default configuration's scores per robot and against the targets (--run),
  gains    with --loro-fixed and --run-scratch: the same procedure with the fixed calibration
           (`utias --leave-one-out --gains fixed --json`), and the gains each robot's filter
           learns from an uncalibrated start (`utias --v-gain 1 --omega-gain 1 --omega-bias 0
           --gain-sigma 0.1 0.1 0.01 --json`) beside the pooled calibration,
and leaves everything else of the page as it is. Every figure comes from the JSON.
"""

import argparse
import json
import re

TARGETS = [
    ("aligned trajectory RMS <= 0.25 m, mean", "aligned_rmse_mean_m", "aligned_mean"),
    ("aligned trajectory RMS <= 0.40 m, every robot", "aligned_rmse_worst_m", "aligned_worst"),
    ("Vicon-frame trajectory RMS <= 0.50 m, mean", "vicon_rmse_mean_m", "vicon_mean"),
    ("Vicon-frame trajectory RMS <= 0.80 m, every robot", "vicon_rmse_worst_m", "vicon_worst"),
    ("aligned landmark RMS <= 0.10 m, every robot", "landmark_aligned_rmse_worst_m", "landmark_worst"),
]


def f(value, digits=3):
    return f"{value:.{digits}f}"


def yes(ok):
    return "yes" if ok else "**no**"


def setting(s):
    return f"{s['process']:g} / {s['range']:g} / {s['bearing_rad']:g}"


def targets_table(summary, worst_robot=None):
    met = summary["targets_met_each"]
    lines = ["| target | result | met? |", "|---|---|---|"]
    for label, key, name in TARGETS:
        note = ""
        if worst_robot and key in worst_robot:
            note = f" (robot {worst_robot[key]})"
        lines.append(f"| {label} | {f(summary[key])} m{note} | {yes(met[name])} |")
    lines.append(f"| mean pose NEES in [1, 6], every robot | {f(summary['nees_min'], 2)} to "
                 f"{f(summary['nees_max'], 2)} | {yes(met['nees_band'])} |")
    return lines


def loro_block(loro):
    lines = [f"Recording: `{loro['recording']}`. One row per rotation: what was fitted on the other four "
             "robots, and the held-out robot's scores with it.", "",
             "| held out | delay (s) | v_gain | v_turn_loss (m/rad) | omega_gain | omega_bias (rad/s) "
             "| setting p / r / b | training: targets met, smallest margin "
             "| held out: aligned RMS (m) | Vicon-frame RMS (m) | landmark RMS (m) | mean NEES |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in loro["rotations"]:
        c, t, h = r["commands"], r["training"], r["held_out"]
        lines.append(f"| {r['held_out_robot']} | {c['command_delay_s']:g} | {c['v_gain']:.4f} | "
                     f"{c['v_turn_loss_m_per_rad']:.4f} | {c['omega_gain']:.4f} | {c['omega_bias_radps']:.4f} | "
                     f"{setting(r['setting'])} | {t['targets_met']}, {f(t['smallest_margin'])} | "
                     f"{f(h['aligned_rmse_m'])} | {f(h['vicon_rmse_m'])} | {f(h['landmark_aligned_rmse_m'])} | "
                     f"{f(h['nees_mean'], 2)} |")
    s = loro["held_out_summary"]
    worst = {}
    for key, field in (("aligned_rmse_worst_m", "aligned_rmse_m"), ("vicon_rmse_worst_m", "vicon_rmse_m"),
                       ("landmark_aligned_rmse_worst_m", "landmark_aligned_rmse_m")):
        worst[key] = max(loro["rotations"], key=lambda r: r["held_out"][field])["held_out_robot"]
    lines += ["", f"The five held-out robots against the targets: {s['targets_met']} of 6 met.", ""]
    lines += targets_table(s, worst)
    a = loro["all_robots"]
    c = a["commands"]
    lines += ["",
              f"The same procedure on all five robots (the rule for the default): delay {c['command_delay_s']:g} s, "
              f"v_gain {c['v_gain']:.4f}, v_turn_loss {c['v_turn_loss_m_per_rad']:.4f} m/rad, "
              f"omega_gain {c['omega_gain']:.4f}, omega_bias {c['omega_bias_radps']:.4f} rad/s, "
              f"setting {setting(a['setting'])}; on those five robots (in-sample) it meets "
              f"{a['summary']['targets_met']} of 6 targets. The compiled default of `noise_model.hpp` "
              f"{'is exactly this' if a['compiled_default_matches'] else '**is not this**'}."]
    if loro.get("notes"):
        lines += [""] + [f"- note: {n}" for n in loro["notes"]]
    return lines


def study_block(loro):
    a = loro["all_robots"]
    grid = a["grid"]
    best = max(g["summary"]["targets_met"] for g in grid)
    rows = sorted((g for g in grid if g["summary"]["targets_met"] == best),
                  key=lambda g: -g["summary"]["smallest_margin"])
    lines = [f"The procedure on all five robots of `{loro['recording']}`, with the fitted delay and calibration: "
             f"{len(rows)} of the {len(grid)} settings meet {best} of 6 targets; by smallest margin:", "",
             "| process | range | bearing (rad) | Vicon mean / worst (m) | aligned mean / worst (m) "
             "| landmark worst (m) | NEES min / max | smallest margin |",
             "|---|---|---|---|---|---|---|---|"]
    for g in rows:
        s, st = g["summary"], g["setting"]
        bold = "**" if st == a["setting"] else ""
        cells = [f"{st['process']:g}", f"{st['range']:g}", f"{st['bearing_rad']:g}",
                 f"{f(s['vicon_rmse_mean_m'])} / {f(s['vicon_rmse_worst_m'])}",
                 f"{f(s['aligned_rmse_mean_m'])} / {f(s['aligned_rmse_worst_m'])}",
                 f(s["landmark_aligned_rmse_worst_m"]), f"{f(s['nees_min'], 2)} / {f(s['nees_max'], 2)}",
                 f(s["smallest_margin"])]
        lines.append("| " + " | ".join(f"{bold}{c}{bold}" for c in cells) + " |")
    lines += ["", "The chosen setting is in bold."]
    return lines


def results_block(run):
    robots = run["robots"]
    lines = [f"Recording: `{run.get('recording', '?')}`, the default configuration (in-sample: it was fitted "
             "on these five robots).", "",
             "| robot | known_rmse_m | known_aligned_rmse_m | jcbb_aligned_rmse_m | landmark_aligned_rmse_m "
             "| nees_mean | dead reckoning RMS (m) | JCBB paired (correct / wrong, wrong within a cluster) "
             "| JCBB new (duplicates) | known: gated out |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    keys = ["known_rmse_m", "known_aligned_rmse_m", "jcbb_aligned_rmse_m", "landmark_aligned_rmse_m"]
    for r in robots:
        a = r["jcbb_association"]
        lines.append(f"| {r['robot']} | " + " | ".join(f(r[k]) for k in keys) + f" | {f(r['nees_mean'], 2)} | "
                     f"{f(r['dead_reckoning_rmse_m'], 2)} | {a['paired']} ({a['correct']} / {a['wrong']}, "
                     f"{a['wrong_same_cluster']} in the cluster) | {a['new']} ({a['duplicates']}) | "
                     f"{r['known_gated_out']} |")
    n = len(robots)
    lines.append("| mean | " + " | ".join(f(sum(r[k] for r in robots) / n) for k in keys) +
                 f" | {f(sum(r['nees_mean'] for r in robots) / n, 2)} | | | | |")
    lines.append("| worst | " + " | ".join(f(max(r[k] for r in robots)) for k in keys) +
                 f" | {f(max(r['nees_mean'] for r in robots), 2)} | | | | |")
    summary = {
        "aligned_rmse_mean_m": sum(r["known_aligned_rmse_m"] for r in robots) / n,
        "aligned_rmse_worst_m": max(r["known_aligned_rmse_m"] for r in robots),
        "vicon_rmse_mean_m": sum(r["known_rmse_m"] for r in robots) / n,
        "vicon_rmse_worst_m": max(r["known_rmse_m"] for r in robots),
        "landmark_aligned_rmse_worst_m": max(r["landmark_aligned_rmse_m"] for r in robots),
        "nees_min": min(r["nees_mean"] for r in robots),
        "nees_max": max(r["nees_mean"] for r in robots),
    }
    summary["targets_met_each"] = {
        "aligned_mean": summary["aligned_rmse_mean_m"] <= 0.25,
        "aligned_worst": summary["aligned_rmse_worst_m"] <= 0.40,
        "vicon_mean": summary["vicon_rmse_mean_m"] <= 0.50,
        "vicon_worst": summary["vicon_rmse_worst_m"] <= 0.80,
        "landmark_worst": summary["landmark_aligned_rmse_worst_m"] <= 0.10,
        "nees_band": summary["nees_min"] >= 1.0 and summary["nees_max"] <= 6.0,
    }
    worst = {}
    for key, field in (("aligned_rmse_worst_m", "known_aligned_rmse_m"), ("vicon_rmse_worst_m", "known_rmse_m"),
                       ("landmark_aligned_rmse_worst_m", "landmark_aligned_rmse_m")):
        worst[key] = max(robots, key=lambda r: r[field])["robot"]
    lines += ["", "In-sample, against the targets (known correspondences):", ""] + targets_table(summary, worst)
    if run.get("notes"):
        lines += [""] + [f"- note: {n}" for n in run["notes"]]
    return lines


def gains_block(loro_fixed, loro_online, run_scratch):
    s_fix, s_on = loro_fixed["held_out_summary"], loro_online["held_out_summary"]
    lines = [f"Recording: `{loro_fixed['recording']}`. The same leave-one-robot-out procedure with the fixed "
             f"calibration (`--gains fixed`, the default before online gains): the held-out robots meet "
             f"{s_fix['targets_met']} of 6 targets, against {s_on['targets_met']} of 6 with online gains "
             f"(the default, table above).", "",
             "| held out | setting p / r / b | training: targets met, smallest margin | held out: aligned RMS (m) "
             "| Vicon-frame RMS (m) | landmark RMS (m) | mean NEES |",
             "|---|---|---|---|---|---|---|"]
    for r in loro_fixed["rotations"]:
        t, h = r["training"], r["held_out"]
        lines.append(f"| {r['held_out_robot']} | {setting(r['setting'])} | {t['targets_met']}, "
                     f"{f(t['smallest_margin'])} | {f(h['aligned_rmse_m'])} | {f(h['vicon_rmse_m'])} | "
                     f"{f(h['landmark_aligned_rmse_m'])} | {f(h['nees_mean'], 2)} |")
    worst = {}
    for key, field in (("aligned_rmse_worst_m", "aligned_rmse_m"), ("vicon_rmse_worst_m", "vicon_rmse_m"),
                       ("landmark_aligned_rmse_worst_m", "landmark_aligned_rmse_m")):
        worst[key] = max(loro_fixed["rotations"], key=lambda r: r["held_out"][field])["held_out_robot"]
    lines += ["", "Against the targets (held-out robots, fixed calibration):", ""] + targets_table(s_fix, worst)
    c = loro_online["all_robots"]["commands"]
    lines += ["", f"What each robot's filter learns from its own landmark readings when it starts uncalibrated "
              f"(gain 1, bias 0, prior sigmas {run_scratch['config']['gain_sigma'][0]:g}, "
              f"{run_scratch['config']['gain_sigma'][1]:g}, {run_scratch['config']['gain_sigma'][2]:g} rad/s; known "
              f"correspondences; `k` is gain - 1), beside the pooled calibration fitted on the Vicon truth of all "
              f"five robots (k_v {c['v_gain'] - 1:+.4f}, k_w {c['omega_gain'] - 1:+.4f}, "
              f"b_w {c['omega_bias_radps']:+.4f} rad/s; the robots' own calibrations spread by "
              f"{c['spread'][0]:.4f}, {c['spread'][1]:.4f}, {c['spread'][2]:.4f}):", "",
              "| robot | k_v | k_w | b_w (rad/s) | Vicon-frame RMS (m) | aligned RMS (m) | mean NEES |",
              "|---|---|---|---|---|---|---|"]
    for r in run_scratch["robots"]:
        g = r["online_gains"]
        sg = g["sigmas"]
        lines.append(f"| {r['robot']} | {g['k_v']:+.4f} ± {sg[0]:.4f} | {g['k_w']:+.4f} ± {sg[1]:.4f} | "
                     f"{g['b_w_radps']:+.4f} ± {sg[2]:.4f} | {f(r['known_rmse_m'])} | "
                     f"{f(r['known_aligned_rmse_m'])} | {f(r['nees_mean'], 2)} |")
    return lines


def replace_block(text, name, lines):
    pattern = re.compile(rf"(<!-- BEGIN generated: {name} [^\n]*-->\n)(.*?)(<!-- END generated: {name} -->)", re.S)
    if not pattern.search(text):
        raise SystemExit(f"utias_report.py: no block '{name}' (<!-- BEGIN generated: {name} ... -->) in the page")
    return pattern.sub(lambda m: m.group(1) + "\n".join(lines) + "\n" + m.group(3), text, count=1)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--run", required=True, help="`utias --json`")
    parser.add_argument("--loro", required=True, help="`utias --leave-one-out --json`")
    parser.add_argument("--doc", required=True, help="the page to update (docs/examples/utias.md)")
    parser.add_argument("--loro-fixed", help="`utias --leave-one-out --gains fixed --json`")
    parser.add_argument("--run-scratch",
                        help="`utias --v-gain 1 --omega-gain 1 --omega-bias 0 --gain-sigma 0.1 0.1 0.01 --json`")
    args = parser.parse_args()
    run = json.load(open(args.run, encoding="utf-8"))
    loro = json.load(open(args.loro, encoding="utf-8"))
    text = open(args.doc, encoding="utf-8").read()
    text = replace_block(text, "loro", loro_block(loro))
    text = replace_block(text, "study", study_block(loro))
    text = replace_block(text, "results", results_block(run))
    if args.loro_fixed and args.run_scratch:
        text = replace_block(text, "gains", gains_block(json.load(open(args.loro_fixed, encoding="utf-8")), loro,
                                                        json.load(open(args.run_scratch, encoding="utf-8"))))
    with open(args.doc, "w", encoding="utf-8") as out:
        out.write(text)


if __name__ == "__main__":
    main()
