#!/usr/bin/env python3
"""Monocular tree-trunk SLAM in a simulated forest, from Python: examples/forest_slam's run
(tree-width thesis, Sec. 4.1-4.2) for its three pipelines, with the thesis' picture of the
map. The same flags give forest_slam's figures (--json) to the last digit.

    python3 python/examples/forest_run.py --out-dir out            # the default forest (seed 26)

The forest, the camera's loop and its measurements come from sylva.ForestScenario; each
frame goes to sylva.MonocularTreeSlam, which predicts the camera, fuses the trunks it sees
([u, v, w] pixels) and runs the trees' life cycle (inverse depth -> XYZ -> XYZ-R). What stays
here is the evaluation of runForestSlam (examples/forest_slam/forest_run.cpp):
  landmark_error   e_l (eq. 4.2), mean squared distance (m^2) of the trees mapped in
                   Euclidean form at the end of lap 1 to the true ones, after the similarity
                   alignment of eq. 4.1-4.11 (sylva.align_similarity);
  trajectory_error e_t (eq. 4.12), of the camera positions over the last lap, aligned by the
                   similarity fitted to the final map;
  converged        e_l < 10 and e_t < 3 (Sec. 4.2);
  radius_rmse_m    RMS error of the XYZ-R trees' radii at the end, times the alignment's scale.
"""

import argparse
import json
import math
import time
from pathlib import Path

import numpy as np

import sylva

PIPELINES = [("with_width", sylva.WidthPipeline.AFTER_XYZ, "with the tree-width sensor"),
             ("without_width", sylva.WidthPipeline.NONE, "without the tree-width sensor"),
             ("width_first_sight", sylva.WidthPipeline.FROM_FIRST_SIGHT,
              "with the tree-width sensor from the first sight (IDR)")]


def make_scenario(o):
    options = sylva.ForestScenarioOptions()
    observer, trajectory = options.observer, options.trajectory
    observer.sigma_px, observer.sigma_width_px = o.pixel_noise, o.width_noise
    trajectory.laps = o.laps
    options.observer, options.trajectory = observer, trajectory
    return options, sylva.ForestScenario(options, o.seed)


def slam_options(o, scenario_options, pipeline):
    s = sylva.TreeSlamOptions()
    s.camera = scenario_options.camera
    # The filter assumes its default sigmas per pixel of simulated noise (as forest_slam does).
    s.pixel_sigma_px = 1.5 * max(scenario_options.observer.sigma_px, 0.1)
    s.width_sigma_px = 1.0 * max(scenario_options.observer.sigma_width_px, 0.1)
    s.pipeline = pipeline
    return s


def align(ids, positions, scenario):
    """The similarity of the estimated trees (named by their true ids) onto the truth, and e_l."""
    truth = scenario.tree_bases[ids]
    T = sylva.align_similarity(positions, truth)
    return T, sylva.mean_squared_error(T, positions, truth)


def run(scenario, options, max_frames=0):
    """One run of the pipeline over the scenario: forest_slam's figures and what the picture needs."""
    n = len(scenario) if max_frames <= 0 else min(max_frames, len(scenario))
    states, times, laps = scenario.camera_states, scenario.frame_times, scenario.frame_laps
    slam = sylva.MonocularTreeSlam(options, states[0])
    tree_of = {}  # landmark -> the tree of the sighting that started it
    path = np.zeros((n, 3))
    rejected = hypotheses = 0
    end_of_lap1 = None
    start = time.perf_counter()
    for k in range(n):
        dt = 0.0 if k == 0 else times[k] - times[k - 1]
        ids, Z, _, _ = scenario.observations(k)
        report = slam.process_frame(dt, ids, Z)
        for tree, landmark in zip(ids, report.landmark_of):
            if landmark >= 0 and landmark not in tree_of:
                tree_of[landmark] = tree
        rejected += report.rejected
        hypotheses += report.hypotheses
        path[k] = slam.camera_mean[:3]
        if laps[k] == 0 and (k + 1 == n or laps[k + 1] > 0):
            end_of_lap1 = slam.euclidean_landmarks()
    runtime = time.perf_counter() - start
    result = dict(landmark_error=None, trajectory_error=None, converged=False, radius_rmse_m=None,
                  mean_true_radius_m=None, runtime_s=runtime)
    landmark_ids, positions, radii = slam.euclidean_landmarks()
    trees = np.array([tree_of[i] for i in landmark_ids], dtype=np.int64)
    T = None
    try:
        lap1_ids, lap1_positions, _ = end_of_lap1
        _, result["landmark_error"] = align(np.array([tree_of[i] for i in lap1_ids], dtype=np.int64),
                                            lap1_positions, scenario)
        T, _ = align(trees, positions, scenario)
        last = laps[:n] == laps[n - 1]
        result["trajectory_error"] = sylva.mean_squared_error(T, path[last], states[:n][last, :3])
    except sylva.Error as e:
        result["failure"] = str(e)
    if result["landmark_error"] is not None and result["trajectory_error"] is not None:
        result["converged"] = sylva.ConvergenceCriteria().converged(result["landmark_error"], result["trajectory_error"])
    is_tree = np.isfinite(radii)
    if is_tree.any():
        scale = T.scale if T is not None else 1.0
        sum_sq = sum_true = 0.0  # summed in slot order, as the C++ run does
        for radius, tree in zip(radii[is_tree], trees[is_tree]):
            r_true = float(scenario.tree_radii[tree])
            d = float(radius) * scale - r_true
            sum_sq += d * d
            sum_true += r_true
        count = int(is_tree.sum())
        result["radius_rmse_m"] = math.sqrt(sum_sq / count)
        result["mean_true_radius_m"] = sum_true / count
    counts = slam.count_by_type()
    result["trees_by_parametrization"] = dict(inverse_depth=counts[0], xyz=counts[1], xyzr=counts[2], idr=counts[3])
    result["rejected_observations"] = rejected
    result["reanchored_frames"] = hypotheses
    trace = dict(path=path, T=T, positions=positions, radii=radii)
    return result, trace


def study(o):
    """forest_slam's JSON for the flags in `o`, and the traces of the three runs."""
    scenario_options, scenario = make_scenario(o)
    n = len(scenario) if o.frames <= 0 else min(o.frames, len(scenario))
    out = {"seed": o.seed, "trees": len(scenario.tree_radii), "frames": n,
           "mean_trees_per_frame": sum(len(scenario.observations(k)[0]) for k in range(len(scenario))) / len(scenario)}
    traces = {}
    for key, pipeline, _ in PIPELINES:
        out[key], traces[key] = run(scenario, slam_options(o, scenario_options, pipeline), o.frames)
    return out, scenario, traces


def draw(out, scenario, traces, o):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Circle

    fig, axes = plt.subplots(1, len(PIPELINES), figsize=(6 * len(PIPELINES), 6.6), sharex=True, sharey=True)
    truth_path = scenario.camera_states[:, :2]
    for ax, (key, _, how) in zip(axes, PIPELINES):
        r, t = out[key], traces[key]
        for base, radius in zip(scenario.tree_bases, scenario.tree_radii):
            ax.add_patch(Circle(base[:2], radius, color="saddlebrown", alpha=0.5, lw=0))
        ax.plot(*truth_path.T, color="black", lw=1, label="true path")
        if t["T"] is not None:
            T = t["T"]
            ax.plot(*T(t["path"])[:, :2].T, color="tab:blue", lw=1, label="estimated path (aligned)")
            aligned = T(t["positions"]) if len(t["positions"]) else np.zeros((0, 3))
            for p, radius in zip(aligned, t["radii"]):
                if math.isfinite(radius):
                    ax.add_patch(Circle(p[:2], radius * T.scale, fill=False, color="tab:green", lw=1.2))
                else:
                    ax.plot(p[0], p[1], "x", color="tab:red", ms=4)
        e_l = "-" if r["landmark_error"] is None else f"{r['landmark_error']:.3f}"
        e_t = "-" if r["trajectory_error"] is None else f"{r['trajectory_error']:.3f}"
        ax.set_title(f"{how}\ne_l {e_l} m^2, e_t {e_t} m^2, {'converged' if r['converged'] else 'NOT converged'}",
                     fontsize=10)
        ax.set_aspect("equal")
        ax.set_xlabel("x (m)")
    axes[0].set_ylabel("y (m)")
    axes[0].legend(loc="lower left", fontsize=8)
    fig.suptitle(f"Monocular tree SLAM, forest seed {o.seed}: true trees (brown), XYZ-R trees (green circles), "
                 "XYZ points (red x)", fontsize=11)
    fig.tight_layout(rect=(0, 0, 1, 0.94))
    o.out_dir.mkdir(parents=True, exist_ok=True)
    fig.savefig(o.out_dir / "forest_run.png", dpi=110)
    plt.close(fig)


def defaults():
    return argparse.Namespace(seed=26, pixel_noise=1.0, width_noise=1.0, laps=2, frames=0)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    for name, value in vars(defaults()).items():
        p.add_argument("--" + name.replace("_", "-"), type=type(value), default=value)
    p.add_argument("--out-dir", type=Path, default=Path("."), help="where forest_run.png goes")
    p.add_argument("--no-figures", action="store_true")
    o = p.parse_args(argv)
    out, scenario, traces = study(o)
    if not o.no_figures:
        draw(out, scenario, traces, o)
    print(json.dumps(out, indent=2))
    return out


if __name__ == "__main__":
    main()
