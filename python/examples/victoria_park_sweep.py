#!/usr/bin/env python3
"""A noise sweep over Victoria Park on every core: EKF-SLAM of the car with point landmarks
(range and bearing to the trunks, JCBB, tentative tracks) for a grid of scale factors on the
filter's sensor noise and odometry noise, scored by the error against the valid GPS fixes.

    python3 python/examples/victoria_park_sweep.py --data ../shared/data/victoria-park --out-dir out

Each setting runs in a process of its own (multiprocessing, --jobs, default: every core). It
writes victoria_park_sweep.json and a heat map of the GPS error (victoria_park_sweep.png).

The filter follows examples/victoria_park's point variant with the plain car (its default adds
a speed-scale state, which the Python package does not bind): Ackermann2D with the laser
mounted at (L + 0.95 m, 0.5 m), the invariant EKF, one prediction per scan integrating the
odometry since the previous one (a constant control with the same distance and heading
change, the per-sample noise scaled by 0.025 s / T). The base noise is that program's
(Guivant and Nebot's car; the C++ example's page says how it was chosen). Nothing is tuned
here: the sweep shows how the result moves with the noise the filter is told, on the one
recording there is, so its best cell is not a default for other data.
"""

import argparse
import itertools
import json
import math
import os
import time
from multiprocessing import Pool
from pathlib import Path

import numpy as np

import sylva

WHEELBASE_M, ENCODER_OFFSET_M = 2.83, 0.76
MOUNT = (WHEELBASE_M + 0.95, 0.5)
ODOMETRY_PERIOD_S = 0.025
BASE = dict(speed_mps=0.5, steering_rad=0.019, range_m=0.25, bearing_rad=0.04)
MAX_RANGE_M = 40.0


def integrate(odo, state, t):
    """Moves the odometry cursor `state` = [t_, next_] to time t; returns (u, span) or None."""
    times, speed, steering = odo["t"], odo["speed"], odo["steering"]
    n = len(times)
    distance = turn = span = alpha_sum = 0.0
    while state[0] < t - 1e-9:
        while state[1] < n and times[state[1]] <= state[0] + 1e-9:
            state[1] += 1
        if state[1] == 0:  # before the first sample: the car stands still
            state[0] = min(t, times[0])
            continue
        k = state[1] - 1
        end = min(t, times[state[1]]) if state[1] < n else t
        dt = end - state[0]
        state[0] = end
        if dt <= 1e-9:
            continue
        v_c, omega = sylva.ackermann_axle_motion(speed[k], steering[k], WHEELBASE_M, ENCODER_OFFSET_M)
        distance += v_c * dt
        turn += omega * dt
        span += dt
        alpha_sum += steering[k] * dt
    if span <= 1e-9:
        return None
    v_c, omega, alpha = distance / span, turn / span, alpha_sum / span
    if abs(v_c) > 1e-3:
        alpha = math.atan(WHEELBASE_M * omega / v_c)
    v_e = v_c * (1.0 - math.tan(alpha) * ENCODER_OFFSET_M / WHEELBASE_M)
    return np.array([v_e, alpha]), span


def run(args):
    """One setting: (sensor scale, odometry scale, data folder, duration) -> its results."""
    sensor_scale, odometry_scale, folder, duration_s = args
    data = sylva.load_victoria_park(folder)
    scans, odo = data["scans"], data["odometry"]
    ekf = sylva.Ackermann2DEkf([0.0, 0.0, 0.0], np.zeros((3, 3)), wheelbase_m=WHEELBASE_M,
                               encoder_offset_m=ENCODER_OFFSET_M)
    ekf.linearization = sylva.Linearization.INVARIANT
    tentative = sylva.TentativeTracks()
    tentative.confirm_sightings, tentative.radius_m, tentative.timeout_s = 5, 1.0, 2.0
    front = sylva.FrontEnd(
        ekf, sensor=sylva.RangeBearing(MOUNT),
        reach=sylva.RangeBearingReach(max_range_m=MAX_RANGE_M + 5.0, half_fov_rad=math.radians(100.0)),
        association=sylva.Association.JCBB, gate_probability=0.99, new_landmark_probability=0.9999,
        new_landmarks=sylva.NewLandmarks.TENTATIVE, tentative=tentative)
    q_sample = sylva.sigmas(odometry_scale * BASE["speed_mps"], odometry_scale * BASE["steering_rad"])
    R = sylva.sigmas(sensor_scale * BASE["range_m"], sensor_scale * BASE["bearing_rad"])
    state = [odo["t"][0], 0]
    path_t, path_xy = [], []
    start, begin = scans["t"][0], time.perf_counter()
    for k, t in enumerate(scans["t"]):
        if duration_s > 0 and t > start + duration_s:
            break
        step = integrate(odo, state, t)
        if step is not None:
            u, span = step
            ekf.predict(u, span, q_sample * (ODOMETRY_PERIOD_S / span))
        lo, hi = scans["start"][k], scans["start"][k + 1]
        r = scans["range"][lo:hi]
        keep = r <= MAX_RANGE_M
        Z = np.c_[r[keep], scans["bearing"][lo:hi][keep] - math.pi / 2]  # laser bearing -> car's
        front.update(Z, R, t)
        x = ekf.robot_mean
        c, s = math.cos(x[2]), math.sin(x[2])
        path_t.append(t)
        path_xy.append([x[0] + c * MOUNT[0] - s * MOUNT[1], x[1] + s * MOUNT[0] + c * MOUNT[1]])
    valid = sylva.victoria_park_valid_gps(data, WHEELBASE_M, ENCODER_OFFSET_M)
    error = sylva.victoria_park_gps_error(np.array(path_t), np.array(path_xy), data, valid)
    return dict(sensor_scale=sensor_scale, odometry_scale=odometry_scale, scans=len(path_t),
                landmarks=len(ekf), gps_rmse_valid_m=error["rmse_valid_m"],
                gps_median_valid_m=error["median_valid_m"], gps_valid_fixes=error["valid"],
                seconds=time.perf_counter() - begin)


def draw(results, sensor_scales, odometry_scales, out_dir):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    grid = np.full((len(sensor_scales), len(odometry_scales)), np.nan)
    for r in results:
        grid[sensor_scales.index(r["sensor_scale"]), odometry_scales.index(r["odometry_scale"])] = r["gps_rmse_valid_m"]
    fig, ax = plt.subplots(figsize=(6, 4.5))
    image = ax.imshow(grid, origin="lower", cmap="viridis")
    ax.set_xticks(range(len(odometry_scales)), [f"{s:g}" for s in odometry_scales])
    ax.set_yticks(range(len(sensor_scales)), [f"{s:g}" for s in sensor_scales])
    ax.set_xlabel("odometry noise told / base")
    ax.set_ylabel("sensor noise told / base")
    for (i, j), value in np.ndenumerate(grid):
        ax.text(j, i, f"{value:.2f}", ha="center", va="center", color="white", fontsize=9)
    fig.colorbar(image, label="GPS error, RMS over valid fixes (m)")
    ax.set_title("Victoria Park: EKF-SLAM against the noise it is told")
    fig.tight_layout()
    fig.savefig(out_dir / "victoria_park_sweep.png", dpi=120)
    plt.close(fig)


def main(argv=None):
    default_data = Path(os.environ.get("SYLVA_DATA_DIR", Path(__file__).resolve().parents[3] / "shared" / "data"))
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--data", type=Path, default=default_data / "victoria-park", help="the Victoria Park folder")
    p.add_argument("--sensor-scales", type=float, nargs="+", default=[0.5, 1.0, 2.0])
    p.add_argument("--odometry-scales", type=float, nargs="+", default=[0.5, 1.0, 2.0])
    p.add_argument("--duration", type=float, default=0.0, help="seconds of the recording (0: all)")
    p.add_argument("--jobs", type=int, default=os.cpu_count(), help="processes (default: every core)")
    p.add_argument("--out-dir", type=Path, default=Path("."))
    p.add_argument("--no-figures", action="store_true")
    o = p.parse_args(argv)
    if not (o.data / "measurements.dat").is_file():
        raise SystemExit(f"victoria_park_sweep.py: no Victoria Park data in {o.data} (see --data)")
    settings = [(s, q, str(o.data), o.duration) for s, q in itertools.product(o.sensor_scales, o.odometry_scales)]
    with Pool(processes=max(1, min(o.jobs, len(settings)))) as pool:
        results = pool.map(run, settings)
    o.out_dir.mkdir(parents=True, exist_ok=True)
    out = {"duration_s": o.duration, "jobs": o.jobs, "results": results}
    (o.out_dir / "victoria_park_sweep.json").write_text(json.dumps(out, indent=2) + "\n")
    if not o.no_figures:
        draw(results, o.sensor_scales, o.odometry_scales, o.out_dir)
    print(json.dumps(out, indent=2))
    return out


if __name__ == "__main__":
    main()
