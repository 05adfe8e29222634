#!/usr/bin/env python3
"""2D range-bearing EKF-SLAM on the simulated loop, from Python: the study of
examples/range_bearing_slam (C++), step for step, so that the same flags give the same
figures to the last digit. It writes a map of the first run and the run-averaged robot NEES
with its 95% band (matplotlib), and prints the results as JSON.

    python3 python/examples/range_bearing_study.py --runs 20 --out-dir /tmp/rb

Everything but the loop over steps and the pictures is sylva's C++: the world
(sylva.PlanarLoopWorld, drawn from sylva.Rng, the generator of the C++ examples), the filter
(sylva.Unicycle2DEkf) and the SLAM step (sylva.FrontEnd: known ids, nearest neighbour or JCBB).
"""

import argparse
import json
import math
from pathlib import Path

import numpy as np

import sylva

RAD_PER_DEG = math.pi / 180.0  # sylva::kRadPerDeg


def defaults():
    """The flags of range_bearing_slam, with its defaults."""
    return argparse.Namespace(
        landmarks=120, min_separation=1.5, perimeter=120.0, speed=1.0, dt=0.1, steps=0, max_range=10.0, fov=90.0,
        sigma_range=0.05, sigma_bearing=1.0, sigma_v=0.05, sigma_omega=1.0, filter_noise_scale=1.0,
        association="known", update="batched", gate=0.99, new_landmark_gate=0.999999, runs=1, seed=1)


def make_world(o):
    options = sylva.PlanarLoopWorldOptions()
    t, l, s = options.trajectory, options.landmarks, options.sensor
    t.perimeter_m, t.speed_mps, t.dt_s = o.perimeter, o.speed, o.dt
    t.sigma_v_mps, t.sigma_omega_radps = o.sigma_v, o.sigma_omega * RAD_PER_DEG
    l.count, l.min_separation_m = o.landmarks, o.min_separation
    s.max_range_m, s.fov_half_angle_rad = o.max_range, o.fov * RAD_PER_DEG
    s.sigma_range_m, s.sigma_bearing_rad = o.sigma_range, o.sigma_bearing * RAD_PER_DEG
    options.trajectory, options.landmarks, options.sensor = t, l, s
    return sylva.PlanarLoopWorld(options, o.seed)


def make_front_end(ekf, o):
    association = {"known": sylva.Association.KNOWN_IDS, "nn": sylva.Association.NEAREST_NEIGHBOR,
                   "jcbb": sylva.Association.JCBB}[o.association]
    # Candidates: landmarks predicted within the sensor's reach, with a margin (as in C++).
    reach = sylva.RangeBearingReach(max_range_m=o.max_range + 1.0,
                                    half_fov_rad=o.fov * RAD_PER_DEG + 10.0 * RAD_PER_DEG, min_range_m=1e-6)
    fusion = sylva.Fusion.BATCHED if o.update == "batched" else sylva.Fusion.SEQUENTIAL
    return sylva.FrontEnd(ekf, reach=reach, association=association, gate_probability=o.gate,
                          new_landmark_probability=o.new_landmark_gate, fusion=fusion)


def run_once(world, o, run, steps, q, r, nees):
    """One Monte Carlo run; adds its NEES to `nees` and returns its results."""
    rng = sylva.Rng(sylva.derive_seed(o.seed, 1 + run))
    truth = world.simulate(steps, rng)
    dt = world.dt
    start = world.start_pose
    ekf = sylva.Unicycle2DEkf(start, np.zeros((3, 3)))
    front = make_front_end(ekf, o)
    known = o.association == "known"
    true_id_of = {}
    odometry_pose = start
    assoc = dict(readings=0, paired=0, wrong=0, added=0, duplicates=0, ambiguous=0)
    paths = {"true": [start[:2]], "estimated": [start[:2]], "odometry": [start[:2]]}
    position_error = np.zeros(steps)
    for k in range(steps):
        pose, odometry = truth["true_pose"][k], truth["odometry"][k]
        ekf.predict(odometry, dt, q)
        odometry_pose = sylva.unicycle_2d(odometry_pose, odometry, dt)
        Z, ids = world.observe(pose, rng)
        report = front.update(Z, r, k * dt, ids=ids if known else None)
        mapped_true = {}
        if not known:
            for true in true_id_of.values():
                mapped_true[true] = mapped_true.get(true, 0) + 1
        for true, result in zip(ids, report.readings):
            if result.outcome == sylva.Outcome.ADDED:
                true_id_of[result.landmark] = true
            if known:
                continue
            assoc["readings"] += 1
            if result.outcome == sylva.Outcome.PAIRED:
                assoc["paired"] += 1
                assoc["wrong"] += int(true_id_of[result.landmark] != true)
            elif result.outcome == sylva.Outcome.AMBIGUOUS:
                assoc["ambiguous"] += 1
            elif result.outcome == sylva.Outcome.ADDED:
                assoc["added"] += 1
                assoc["duplicates"] += int(mapped_true.get(true, 0) > 0)
                mapped_true[true] = mapped_true.get(true, 0) + 1
        if k > 0:  # one prediction from P0 = 0 leaves a pose covariance of rank 2
            nees.add(k - 1, ekf.robot_nees(pose))
        position_error[k] = np.linalg.norm(ekf.robot_error(pose)[:2])
        paths["true"].append(pose[:2])
        paths["estimated"].append(ekf.robot_mean[:2])
        paths["odometry"].append(odometry_pose[:2])
    last = truth["true_pose"][-1]
    final_error = ekf.robot_error(last)
    squared, estimates = 0.0, []
    for lid in ekf.ids:
        estimate = ekf.landmark_mean(lid)
        squared += float(np.sum((estimate - world.landmarks[true_id_of[lid]]) ** 2))
        estimates.append((estimate, ekf.landmark_covariance(lid)))
    return dict(final_position_error=math.hypot(final_error[0], final_error[1]),
                final_heading_error=abs(final_error[2]),
                odometry_error=float(np.linalg.norm(odometry_pose[:2] - last[:2])), squared=squared,
                mapped=len(ekf.ids), association=assoc, paths={k: np.array(v) for k, v in paths.items()},
                estimates=estimates, position_error=position_error)


def study(o):
    """The whole study: returns (results as range_bearing_slam --json prints them, run 1, NEES series)."""
    world = make_world(o)
    steps = o.steps if o.steps > 0 else (6 * world.steps_per_lap + 4) // 5
    k = o.filter_noise_scale
    q = sylva.sigmas(k * o.sigma_v, k * (o.sigma_omega * RAD_PER_DEG))
    r = sylva.sigmas(k * o.sigma_range, k * (o.sigma_bearing * RAD_PER_DEG))
    nees = sylva.NeesSeries(3)
    totals = dict(final_position_error=0.0, final_heading_error=0.0, odometry_error=0.0, squared=0.0, mapped=0)
    assoc = dict(readings=0, paired=0, wrong=0, added=0, duplicates=0, ambiguous=0)
    first = None
    for run in range(o.runs):
        result = run_once(world, o, run, steps, q, r, nees)
        for key in totals:
            totals[key] += result[key]
        for key in assoc:
            assoc[key] += result["association"][key]
        if run == 0:
            first = result
    runs = float(o.runs)
    lo, hi = nees.bounds(0.95)
    nees_mean = nees.mean()
    out = {
        "runs": o.runs, "steps": steps, "seed": o.seed, "association": o.association,
        "landmarks": len(world.landmarks), "path_length_m": world.speed * world.dt * steps,
        "landmark_rmse_m": math.sqrt(totals["squared"] / totals["mapped"]) if totals["mapped"] > 0 else 0.0,
        "landmarks_mapped_mean": totals["mapped"] / runs,
        "final_pose_error_m": totals["final_position_error"] / runs,
        "final_heading_error_rad": totals["final_heading_error"] / runs,
        "odometry_final_pose_error_m": totals["odometry_error"] / runs,
        "nees_mean": nees_mean, "nees_bounds": [lo, hi], "nees_inside": lo <= nees_mean <= hi,
        "nees_fraction_inside": nees.fraction_inside(0.95),
        "noise": {"sigma_range_m": o.sigma_range, "sigma_bearing_deg": o.sigma_bearing, "sigma_v_mps": o.sigma_v,
                  "sigma_omega_degps": o.sigma_omega, "filter_noise_scale": o.filter_noise_scale},
    }
    if o.association != "known":
        out["association_stats"] = assoc
    return out, world, first, nees


def draw(out, world, first, nees, o, out_dir):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Ellipse

    out_dir.mkdir(parents=True, exist_ok=True)
    fig, ax = plt.subplots(figsize=(9, 5.5))
    ax.plot(*first["paths"]["true"].T, color="black", lw=1, label="true path")
    ax.plot(*first["paths"]["odometry"].T, color="tab:orange", lw=1, ls="--", label="odometry only")
    ax.plot(*first["paths"]["estimated"].T, color="tab:blue", lw=1, label="EKF-SLAM")
    ax.scatter(*world.landmarks.T, marker="+", color="black", s=25, label="true landmarks")
    for mean, cov in first["estimates"]:
        values, vectors = np.linalg.eigh(cov)
        angle = math.degrees(math.atan2(vectors[1, 1], vectors[0, 1]))
        # 3-sigma ellipses, so that they can be seen at the map's scale
        ax.add_patch(Ellipse(mean, 6 * math.sqrt(values[1]), 6 * math.sqrt(values[0]), angle=angle,
                             fill=False, color="tab:blue", lw=0.6))
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(f"run 1 of {o.runs} (seed {o.seed}, association {o.association}): landmark 3-sigma ellipses")
    ax.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    fig.savefig(out_dir / "range_bearing_map.png", dpi=120)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(9, 3.5))
    averages = nees.averages()
    t = (np.arange(len(averages)) + 2) * world.dt  # series index k - 1 holds step k
    lo, hi = out["nees_bounds"]
    ax.plot(t, averages, color="tab:blue", lw=0.8, label=f"robot NEES, average of {o.runs} runs")
    ax.axhline(3, color="black", lw=0.8, label="expected (3 dof)")
    ax.axhspan(lo, hi, color="tab:green", alpha=0.15, label="95% band of the run average")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("NEES")
    ax.set_title(f"{100 * out['nees_fraction_inside']:.0f}% of steps inside the band; mean {out['nees_mean']:.2f}")
    ax.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    fig.savefig(out_dir / "range_bearing_nees.png", dpi=120)
    plt.close(fig)


def main(argv=None):
    d = defaults()
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter)
    for name, value in vars(d).items():
        flag = "--" + name.replace("_", "-")
        if name == "association":
            p.add_argument(flag, default=value, choices=["known", "nn", "jcbb"])
        elif name == "update":
            p.add_argument(flag, default=value, choices=["batched", "sequential"])
        else:
            p.add_argument(flag, type=type(value), default=value)
    p.add_argument("--out-dir", type=Path, default=Path("."), help="where the two PNG figures go")
    p.add_argument("--no-figures", action="store_true")
    o = p.parse_args(argv)
    out, world, first, nees = study(o)
    if not o.no_figures:
        draw(out, world, first, nees, o, o.out_dir)
    print(json.dumps(out, indent=2))


if __name__ == "__main__":
    main()
