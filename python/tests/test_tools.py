"""Evaluation, consistency tools and the data-set loaders from Python."""

import math
import os
from pathlib import Path

import numpy as np
import pytest

import sylva

DATA = Path(os.environ.get("SYLVA_DATA_DIR", Path(__file__).resolve().parents[3] / "shared" / "data"))


def rotation_z(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])


def test_similarity_recovers_a_known_transform():
    rng = np.random.default_rng(4)
    truth = rng.uniform(-20, 20, size=(30, 3))
    R = rotation_z(0.7) @ np.array([[1, 0, 0], [0, math.cos(0.2), -math.sin(0.2)], [0, math.sin(0.2), math.cos(0.2)]])
    # estimated = the truth seen through the inverse of T(p) = 2.5 R p + t
    t = np.array([1.0, -2.0, 0.5])
    estimated = (truth - t) @ R / 2.5
    T = sylva.align_similarity(estimated, truth)
    assert T.scale == pytest.approx(2.5, rel=1e-12)
    assert np.allclose(T.rotation, R, atol=1e-12)
    assert np.allclose(T(estimated), truth, atol=1e-10)
    assert T(estimated[0]).shape == (3,)
    assert sylva.mean_squared_error(T, estimated, truth) < 1e-18
    with pytest.raises(sylva.Error, match="collinear") as info:
        line = np.c_[np.arange(5.0), np.zeros(5), np.zeros(5)]
        sylva.align_similarity(line, line)
    assert info.value.code == sylva.ErrorCode.DEGENERATE_GEOMETRY
    with pytest.raises(sylva.Error, match=r"truth: expected shape \(n, 3\)"):
        sylva.align_similarity(estimated, truth[:, :2])


def test_rigid_2d_recovers_a_known_transform():
    rng = np.random.default_rng(5)
    truth = rng.uniform(-10, 10, size=(12, 2))
    a, t = -2.0, np.array([3.0, 4.0])
    R = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
    estimated = (truth - t) @ R
    T = sylva.align_rigid_2d(estimated, truth)
    assert T.angle == pytest.approx(a, abs=1e-12)
    assert np.allclose(T(estimated), truth, atol=1e-10)
    assert T.pose([0, 0, 3.0])[2] == pytest.approx(math.remainder(3.0 + a, 2 * math.pi))


def test_thesis_metrics():
    c = sylva.ConvergenceCriteria()
    assert (c.max_landmark_error, c.max_trajectory_error) == (10.0, 3.0)
    assert c.converged(9.9, 2.9) and not c.converged(10.0, 1.0)
    assert sylva.negative_saturated_average([1.0, 20.0], 10.0) == pytest.approx(-5.5)


def test_nees_ensemble_of_a_consistent_sampler():
    # chi-square(2) samples: the ensemble mean sits inside its band on most steps.
    rng = sylva.Rng(11)
    e = sylva.NeesEnsemble(2)
    for run in range(50):
        for step in range(200):
            e.add(run, step, rng.normal() ** 2 + rng.normal() ** 2)
    s = e.summary()
    assert (s.runs, s.dof) == (50, 2)
    assert s.lower < 2.0 < s.upper
    # each step is inside its 95% band with probability 0.95: 200 steps, 5 sigma below
    assert s.fraction_inside > 0.95 - 5 * math.sqrt(0.95 * 0.05 / 200)
    assert e.step_averages().shape == (200,) and e.run_averages().shape == (50,)
    with pytest.raises(sylva.Error, match="NaN|negative"):
        e.add(0, 500, -1.0)


def test_paired_tests():
    assert sylva.mcnemar_exact(0, 0) == 1.0
    assert sylva.mcnemar_exact(0, 10) == pytest.approx(2 * 0.5**10)
    r = sylva.wilcoxon_signed_rank([1.0, 2.0, 3.0, 4.0, 5.0, 6.0])
    assert (r.n, r.positive, r.negative, r.exact) == (6, 6, 0, True)
    assert r.p_value == pytest.approx(2 / 2**6)
    lo, hi = sylva.wilson_interval(5, 10)
    assert lo < 0.5 < hi


def needs(folder):
    if not (DATA / folder).is_dir():
        pytest.skip(f"data set {DATA / folder} is absent (set SYLVA_DATA_DIR): skipped")
    return DATA / folder


def test_victoria_park_loader():
    data = sylva.load_victoria_park(str(needs("victoria-park")))
    scans, odo, gps = data["scans"], data["odometry"], data["gps"]
    assert scans["start"][0] == 0 and scans["start"][-1] == len(scans["range"]) == len(scans["bearing"])
    assert len(scans["start"]) == len(scans["t"]) + 1
    assert np.all(np.diff(scans["t"]) >= 0) and np.all(np.diff(odo["t"]) >= 0)
    assert gps["xy"].shape == (len(gps["t"]), 2)
    assert np.all((scans["bearing"] >= 0) & (scans["bearing"] <= math.pi))


def test_utias_loader():
    data = sylva.load_utias_mrclam(str(needs("utias-mrclam") / "MRCLAM_Dataset7"), robots=[2])
    assert list(data["robots"]) == [2]
    robot = data["robots"][2]
    assert robot["odometry"]["u"].shape == (len(robot["odometry"]["t"]), 2)
    assert robot["groundtruth"]["pose"].shape[1] == 3
    obs = robot["landmark_observations"]
    assert np.all(obs["subject"] > 5) and obs["z"].shape == (len(obs["t"]), 2)
    assert data["landmarks"]["position"].shape == (len(data["landmarks"]["subject"]), 2)


def test_loaders_name_a_missing_or_malformed_file(tmp_path):
    with pytest.raises(sylva.Error) as info:
        sylva.load_victoria_park(str(tmp_path))
    assert "measurements.dat" in str(info.value)
    (tmp_path / "measurements.dat").write_text("1.0 2.0 abc\n")
    (tmp_path / "odometry.txt").write_text("")
    (tmp_path / "gps.txt").write_text("")
    with pytest.raises(sylva.Error) as info:
        sylva.load_victoria_park(str(tmp_path))
    assert info.value.code == sylva.ErrorCode.MALFORMED_DATA
    with pytest.raises(sylva.Error, match="robot 7 does not exist"):
        sylva.load_utias_mrclam(str(tmp_path), robots=[7])
