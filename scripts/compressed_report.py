#!/usr/bin/env python3
"""docs/compressed-ekf.md (and docs/compressed-ekf.figures.json) from the JSON of
bench_compressed_ekf's lap-2 families (scripts/compressed_report.sh runs the benchmark, then
this script).

Every repetition is one run of the stretch of lap 2 (the benchmark's kStretch steps, one
iteration each), and the repetitions are interleaved at random. The compressed filter's
amortized step is divided by the plain filter's step of the same repetition index: one ratio
per run. A criterion reads "met" only if it holds in every run; the page gives the median
ratio and its range over the runs.
"""

import argparse
import json
import os
import statistics
import sys
from collections import defaultdict

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_report import single_runs, write_page  # noqa: E402  (what the reports share)

TARGET_N = 2000
TARGET_RATIO = 0.25  # issue 19: amortized compressed step <= 0.25x the plain batched step
TARGET_DIFFERENCE = 1e-9  # and the final state equal to the plain filter's to 1e-9 relative


def load(path):
    """{config: [per-repetition rows]}, context. config = (family, N, radius, ahead)."""
    data = json.load(open(path, encoding="utf-8"))
    runs = defaultdict(dict)
    for family, args, b, seconds in single_runs(data):
        if not family.startswith("LapTwo"):
            continue
        row = {
            "per_step_ms": 1e3 * seconds / b["steps"],
            "steps": int(b["steps"]),
            "global_updates": b.get("global_updates"),
            "active_dim": b.get("active_dim"),
            "state_difference": b.get("state_difference"),
        }
        runs[(family,) + args][b.get("repetition_index", 0)] = row
    return {k: [v[i] for i in sorted(v)] for k, v in runs.items()}, data.get("context", {})


def victoria_park_section(path, w, figures):
    """The whole Victoria Park run, plain and compressed: times and the final states' difference."""
    w("## Victoria Park: the whole run, plain and compressed")
    w("")
    if not path:
        w("Not run: the Victoria Park data were not there (docs/examples/victoria-park.md says where to get "
          "them). `victoria_park --compare-compressed --linearization current` runs it.")
        w("")
        figures["victoria_park_agree"] = "not run"
        return
    vp = json.load(open(path, encoding="utf-8"))
    config = vp["config"]
    w(f"`victoria_park --compare-compressed --linearization current --json` (built as above): each variant "
      f"runs the whole recording twice with the same declared configuration (docs/examples/victoria-park.md), "
      f"once with the plain filter and once compressed, with a region of radius "
      f"{config['compress_radius_m']:g} m centred {config['compress_ahead_m']:g} m ahead of the car (twice and "
      f"once the laser's {config['max_range_m']:g} m range: declared, not tuned). The textbook linearization, "
      "because the compressed EKF refuses the invariant one (the example's default). Association runs in the "
      "loop, so the two runs agree only if no decision flipped on a round-off difference. *difference*: the "
      "largest difference of the final mean (covariance) from the plain filter's, landmarks matched by id, "
      "relative to the largest entry. One run each: the times are indicative; the circle-world table above "
      "is the timed comparison.")
    w("")
    w("| variant | landmarks | same ids | mean difference | covariance difference | agree to 1e-9 | plain (s) | compressed (s) | ratio | global updates |")
    w("|---|---|---|---|---|---|---|---|---|---|")
    all_agree = True
    for name in ("point", "tree"):
        if name not in vp:
            continue
        r = vp[name]
        all_agree = all_agree and r["agree"]
        w(f"| {name} | {r['plain']['landmarks']} | {'yes' if r['same_landmarks'] else 'no'} | "
          f"{r['mean_difference']:.1e} | {r['covariance_difference']:.1e} | {'yes' if r['agree'] else '**no**'} | "
          f"{r['plain']['runtime_s']:.2f} | {r['compressed']['runtime_s']:.2f} | {r['time_ratio']:.2f} | "
          f"{r['global_updates']} |")
        figures[f"victoria_park_{name}_ratio"] = f"{r['time_ratio']:.2f}"
    figures["victoria_park_agree"] = "yes" if all_agree else "no"
    w("")


def whole_run_section(path, w, figures):
    """The whole run (both laps from the empty map), plain and compressed: the final states' difference."""
    w("## The whole run: plain and compressed agree")
    w("")
    if not path:
        w("Not run (`bench_compressed_ekf --benchmark_filter=WholeRunAgreement` runs it).")
        w("")
        return None
    data = json.load(open(path, encoding="utf-8"))
    rows = [b for b in data["benchmarks"] if b["name"].startswith("BM_WholeRunAgreement")
            and b.get("run_type", "iteration") == "iteration"]
    if not rows:
        w("Not run (`bench_compressed_ekf --benchmark_filter=WholeRun` runs it).")
        w("")
        return None
    w("`bench_compressed_ekf --benchmark_filter=WholeRunAgreement` (built as above): every step of both laps "
      "from the empty map, with the fusion of MRPT's kfEKFAlaDavison (bench/peers/sylva_peer.hpp: two scalar "
      "updates per observation, so a region holds about a thousand local updates), once plain and once "
      "compressed on the same inputs. *difference*: the largest difference of the final mean (covariance) from "
      "the plain filter's, landmarks matched by id, relative to the plain filter's largest entry. The "
      "accumulators are scaled by a factor of P_AA ([filter.md](filter.md#compressed-ekf-large-maps), "
      "\"Round-off\"); without that, this run at N = 2000 missed 1e-9. One run each: the times are indicative.")
    w("")
    w(f"| N | region (radius / ahead, m) | steps | mean difference | covariance difference | within {TARGET_DIFFERENCE:g} | plain (s) | compressed (s) | global updates |")
    w("|---|---|---|---|---|---|---|---|---|")
    for b in sorted(rows, key=lambda b: b["N"]):
        n = int(b["N"])
        worst = max(b["mean_difference"], b["covariance_difference"])
        ok = worst <= TARGET_DIFFERENCE
        w(f"| {n} | {b['radius_m']:g} / {b['ahead_m']:g} | {int(b['steps'])} | {b['mean_difference']:.1e} | "
          f"{b['covariance_difference']:.1e} | {'yes' if ok else '**no**'} | {b['plain_s']:.1f} | "
          f"{b['compressed_s']:.1f} | {int(b['global_updates'])} |")
        figures[f"whole_run_difference_n{n}"] = f"{worst:.0e}"
        figures[f"whole_run_agree_n{n}"] = "yes" if ok else "no"
    w("")
    if not all("global_floor_s" in b for b in rows):
        return None
    w("### Where the compressed run's time goes, and its floor")
    w("")
    w("The same compressed runs, step by step: *local steps* are the steps in which no global update ran, "
      "*steps with a global update* the others and the final `synchronize()`. A global update with an "
      "active part of a rows and b rows outside it costs b (b + 1) a flops for the lower triangle of "
      "(V psi) V^T and 4 b a^2 for V psi and V phi^T ([filter.md](filter.md#compressed-ekf-large-maps)), "
      "summed here from the sizes before each. Their *floor* is those flops at the GEMM peak measured "
      "after the runs in the same program (best of 20 products of 512^3): what the same global updates "
      "would take if they ran at Eigen's best speed on this build and machine. With Eigen's kernels a "
      "whole run with this region cannot be faster than that floor, so against a peer whose whole run "
      "takes T, the ratio cannot exceed T / floor.")
    w("")
    w("| N | compressed (s) | local steps (s) | steps with a global update (s) | global updates' GFLOP | GEMM peak (GFLOP/s) | floor (s) | steps with a global update / floor | 300 x floor (s) |")
    w("|---|---|---|---|---|---|---|---|---|")
    for b in sorted(rows, key=lambda b: b["N"]):
        n = int(b["N"])
        floor = b["global_floor_s"]
        w(f"| {n} | {b['compressed_s']:.1f} | {b['local_steps_s']:.2f} | {b['global_steps_s']:.2f} | "
          f"{b['global_flops'] / 1e9:.0f} | {b['gemm_gflops']:.1f} | {floor:.2f} | "
          f"{b['global_steps_s'] / floor:.2f} | {300 * floor:.0f} |")
        figures[f"whole_run_compressed_s_n{n}"] = f"{b['compressed_s']:.1f}"
        figures[f"whole_run_floor_s_n{n}"] = f"{floor:.1f}"
        figures[f"whole_run_needed_peer_s_n{n}"] = f"{300 * floor:.0f}"
    w("")
    w("So issue 19's whole-run criterion (a peer at least 300 times slower than the compressed run at "
      "N = 2000, with this region) needs the peer's whole run to take at least the last column on the "
      "machine and build that measured this page, even if sylva's whole run took no more than its global "
      "updates' floor. Fewer global-update flops or a faster GEMM (the native build) lower the floor.")
    w("")
    regions = [b for b in data["benchmarks"] if b["name"].startswith("BM_WholeRunRegions")
               and b.get("run_type", "iteration") == "iteration"]
    if not regions:
        return None
    w("### The global updates' flops against the region")
    w("")
    w("`BM_WholeRunRegions`: the compressed whole run alone at N = 2000 (same fusion, same counters), for "
      "regions centred 10 m (the sensor's range) short of their edge ahead of the robot. The flops do not "
      "depend on the machine; the times are one run each. A larger region makes fewer global updates, but "
      "each costs more: the regions of a lap together hold every landmark it sees at least once, so the "
      "global updates of a lap cost about n^3 flops whatever the region ([filter.md](filter.md#compressed-ekf-large-maps)), "
      "while the local steps grow as the square of the region.")
    w("")
    w("| region (radius / ahead, m) | global updates | global updates' GFLOP | floor (s) | local steps (s) | steps with a global update (s) | compressed (s) |")
    w("|---|---|---|---|---|---|---|")
    for b in sorted(regions, key=lambda b: b["radius_m"]):
        w(f"| {b['radius_m']:g} / {b['ahead_m']:g} | {int(b['global_updates'])} | {b['global_flops'] / 1e9:.0f} | "
          f"{b['global_floor_s']:.2f} | {b['local_steps_s']:.2f} | {b['global_steps_s']:.2f} | {b['compressed_s']:.1f} |")
    best = min(regions, key=lambda b: b["global_flops"])
    reference = [b for b in regions if b["radius_m"] == 50 and b["ahead_m"] == 40]
    w("")
    figures["regions_min_gflop"] = f"{best['global_flops'] / 1e9:.0f}"
    figures["regions_min_region"] = f"{best['radius_m']:g} m / {best['ahead_m']:g} m"
    if reference:
        factor = best["global_flops"] / reference[0]["global_flops"]
        figures["regions_min_flops_over_50_40"] = f"{factor:.2f}"
        w(f"Fewest global-update flops: {best['global_flops'] / 1e9:.0f} GFLOP ({best['radius_m']:g} m centred "
          f"{best['ahead_m']:g} m ahead), {factor:.2f} times those of the 50 m / 40 m region the peer comparison "
          "uses.")
        w("")
        return factor
    return None


TARGET_PEER_RATIO = 300  # issue 19: MRPT kfEKFAlaDavison's whole run / sylva compressed's, N = 2000


def peers_whole_section(path, w, figures, flops_factor=None):
    """MRPT kfEKFAlaDavison's whole run against sylva's compressed one, from bench_peers_baseline
    (the same program and run), with the bound that the compressed run's floor puts on the ratio."""
    w("## Against MRPT's whole run")
    w("")
    if not path:
        w("Not run: it needs MRPT (`PEERS_WHOLE=1 bash scripts/compressed_report.sh`; MRPT's whole run at "
          "N = 2000 takes over half an hour per repetition).")
        w("")
        figures["peers_whole_verdict"] = "not run"
        return
    data = json.load(open(path, encoding="utf-8"))
    runs = defaultdict(dict)  # (family, N) -> {repetition: benchmark}
    for family, args, b, seconds in single_runs(data):
        if family in ("mrpt_davison_whole", "sylva_davison_compressed_whole"):
            # ms_per_run: the timed window of the run (manual time), the same for both sides.
            runs[(family, args[0])][b.get("repetition_index", 0)] = dict(b, seconds=b["ms_per_run"] / 1e3)
    sizes = sorted({n for (_, n) in runs})
    w("`bench_peers_baseline --peers_whole_sizes=N --benchmark_filter=whole` (bench/peers, MRPT from Debian, "
      "sylva built as above, baseline x86-64 on both sides): every step of both laps from the empty map, once "
      "through MRPT's kfEKFAlaDavison and once through sylva's replica of its fusion on the compressed EKF "
      "(region 50 m, centred 40 m ahead), one run per repetition, MRPT's first. Each row pairs the two runs of "
      "one repetition. *MRPT / floor* is MRPT's time over the compressed run's floor of the same repetition "
      "(see above): the most that ratio could be with this region and Eigen's kernels on this machine. The "
      "bound that decides the verdict uses the floor of the region with the fewest global-update flops "
      "measured above, scaled from this run's (the flops do not depend on the machine).")
    w("")
    w("| N | repetition | MRPT (s) | sylva compressed (s) | MRPT / sylva | sylva's floor (s) | MRPT / floor | final states equal |")
    w("|---|---|---|---|---|---|---|---|")
    for n in sizes:
        mrpt, sylva = runs.get(("mrpt_davison_whole", n), {}), runs.get(("sylva_davison_compressed_whole", n), {})
        ratios, bounds, agree = [], [], []
        for r in sorted(set(mrpt) & set(sylva)):
            m, c = mrpt[r]["seconds"], sylva[r]["seconds"]
            floor = sylva[r].get("global_floor_s")
            ok = sylva[r].get("states_agree", 0.0) == 1.0
            ratios.append(m / c)
            agree.append(ok)
            if floor:
                # The fewest flops any measured region needs (flops do not depend on the machine).
                bounds.append(m / (floor * (min(flops_factor, 1.0) if flops_factor else 1.0)))
            w(f"| {n} | {r} | {m:.3g} | {c:.3g} | {m / c:.0f} | {floor:.3g} | {m / floor:.0f} | {'yes' if ok else '**no**'} |"
              if floor else f"| {n} | {r} | {m:.3g} | {c:.3g} | {m / c:.0f} | - | - | {'yes' if ok else '**no**'} |")
        if bounds and flops_factor:
            w("")
            w(f"With the region of fewest global-update flops above ({flops_factor:.2f} times this region's), the "
              f"bound would be at most {max(bounds):.0f}.")
        if n != TARGET_N or not ratios:
            continue
        figures["peers_whole_runs"] = str(len(ratios))
        figures["peers_whole_ratio_median"] = f"{statistics.median(ratios):.0f}"
        figures["peers_whole_ratio_min"] = f"{min(ratios):.0f}"
        figures["peers_whole_ratio_max"] = f"{max(ratios):.0f}"
        if bounds:
            figures["peers_whole_bound_max"] = f"{max(bounds):.0f}"
        met = min(ratios) >= TARGET_PEER_RATIO and all(agree)
        out_of_reach = len(bounds) == len(ratios) and max(bounds) < TARGET_PEER_RATIO
        figures["peers_whole_verdict"] = ("met" if met else
                                          "not met; out of reach with the measured regions and Eigen's kernels"
                                          if out_of_reach else "not met")
    w("")
    if "peers_whole_verdict" in figures and figures["peers_whole_verdict"] != "not run":
        w(f"Criterion (issue 19): at N = {TARGET_N}, MRPT's whole run at least {TARGET_PEER_RATIO}x the compressed "
          f"run's, with equal final states, in every run: **{figures['peers_whole_verdict']}**. Where every run's "
          f"bound is under {TARGET_PEER_RATIO}, no kernel work on the global updates of the measured regions can "
          "meet it here: only fewer global-update flops than any of them, or a faster GEMM (the native build), "
          "would.")
        w("")


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("json", help="bench_compressed_ekf's JSON (--benchmark_out)")
    parser.add_argument("--out", required=True, help="the Markdown page")
    parser.add_argument("--figures", required=True, help="the figures file (docs_figures.py)")
    parser.add_argument("--command", required=True, help="the command that regenerates the page")
    parser.add_argument("--victoria-park", help="victoria_park --compare-compressed --json (absent: no data)")
    parser.add_argument("--whole-run", help="bench_compressed_ekf's WholeRunAgreement JSON (absent: not run)")
    parser.add_argument("--peers-whole", help="bench_peers_baseline's JSON with the whole runs (absent: not run)")
    args = parser.parse_args()

    runs, context = load(args.json)
    plain = {k[1]: v for k, v in runs.items() if k[0] == "LapTwoPlain"}
    compressed = sorted((k for k in runs if k[0] == "LapTwoCompressed"), key=lambda k: k[1:])
    repetitions = min(len(v) for v in runs.values())

    lines = []
    w = lines.append
    w("# Compressed EKF: time on the circle world")
    w("")
    w(f"Generated by `{args.command}` (scripts/compressed_report.py); do not edit by hand.")
    w("")
    w("The compressed EKF (`Ekf::setCompression`, [filter.md](filter.md#compressed-ekf-large-maps)) "
      "against the plain filter, `Ekf<Odometry2D, Point2>` with batched updates, on the circle world of "
      "the benchmarks (bench/scenario/circle_world.hpp: about 12 landmarks in view per step, sensor range "
      "10 m, 2 m steps). Both start from the filter at the end of lap 1 and run the first steps of lap 2; "
      "the compressed filter enters its first region outside the timing, and everything after it is timed: "
      "its local steps, every region change (global update and reordering) and a final `synchronize()`. "
      "Its time per step is therefore its amortized cost.")
    w("")
    w(f"Build: {context.get('build_type', '?')}, `{context.get('compiler', '?')}`, flags "
      f"`{context.get('cxx_flags', '?')}` (baseline x86-64 unless they say otherwise; Eigen's SIMD: "
      f"{context.get('eigen_simd', '?')}), on {context.get('cpu_model', '?')} ({context.get('num_cpus', '?')} CPUs), "
      f"{repetitions} runs interleaved at random. Nothing here is tuned on these runs: the radii are a "
      "fixed sweep, and the centre ahead of the robot is radius minus sensor range, the distance that "
      "lets a robot moving forward cross the whole region (filter.md).")
    w("")
    w("Each ratio divides the compressed filter's time per step by the plain filter's in the run with "
      "the same index; the page gives the median over the runs and, in brackets, the smallest and the "
      "largest. *state difference* is the largest difference of the final mean and covariance from the "
      "plain filter's, relative to the largest entry of each, worst over the runs.")
    w("")
    w(f"| N | region radius (m) | centre ahead (m) | plain step (ms) | compressed step (ms) | ratio | global updates | active rows at the end | state difference | ratio <= {TARGET_RATIO} and difference <= {TARGET_DIFFERENCE:g} in every run |")
    w("|---|---|---|---|---|---|---|---|---|---|")
    figures = {"runs": f"{repetitions}"}
    meeting, judged = [], []
    for key in compressed:
        _, n, radius, ahead = key
        if n not in plain:
            continue
        rows = runs[key][:repetitions]
        base = plain[n][:repetitions]
        ratios = [r["per_step_ms"] / b["per_step_ms"] for r, b in zip(rows, base)]
        median = statistics.median(ratios)
        worst_difference = max(r["state_difference"] for r in rows)
        holds = max(ratios) <= TARGET_RATIO and worst_difference <= TARGET_DIFFERENCE
        w(f"| {n} | {radius} | {ahead} | {statistics.median(b['per_step_ms'] for b in base):.3g} | "
          f"{statistics.median(r['per_step_ms'] for r in rows):.3g} | "
          f"{median:.3f} [{min(ratios):.3f}, {max(ratios):.3f}] | {rows[-1]['global_updates']:.0f} | "
          f"{rows[-1]['active_dim']:.0f} | {worst_difference:.1e} | {'yes' if holds else 'no'} |")
        if n == TARGET_N:
            label = f"r{radius}_ahead{ahead}"
            figures[f"ratio_median_{label}"] = f"{median:.2f}"
            figures[f"ratio_worst_{label}"] = f"{max(ratios):.2f}"
            judged.append(f"{radius} m / {ahead} m")
            if holds:
                meeting.append(f"{radius} m centred {ahead} m ahead")
    w("")
    w("## Criterion (issue 19)")
    w("")
    w(f"At N = {TARGET_N}: the amortized compressed step at most {TARGET_RATIO}x the plain batched step, and "
      f"the final state equal to the plain filter's to {TARGET_DIFFERENCE:g} relative, in every run. "
      f"Of the {len(judged)} regions measured (radius / centre ahead: {', '.join(judged)}), "
      + (f"**met** by {len(meeting)}: " + "; ".join(meeting) + "." if meeting else "**not met** by any.")
      + " A region centred on the robot is left after about half the distance, so its global updates "
      "come twice as often (filter.md).")
    figures["regions_meeting"] = f"{len(meeting)}"
    figures["regions_judged"] = f"{len(judged)}"
    w("")
    w("Steps per run: " + ", ".join(sorted({f"{runs[k][0]['steps']} (N = {k[1]})" for k in runs})) + ".")
    w("")
    flops_factor = whole_run_section(args.whole_run, w, figures)
    peers_whole_section(args.peers_whole, w, figures, flops_factor)
    victoria_park_section(args.victoria_park, w, figures)
    write_page(args.out, lines, args.figures, "compressed-ekf", args.command, figures)


if __name__ == "__main__":
    main()
