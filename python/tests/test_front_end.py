"""The SLAM layer's step from Python: a robot on a circle among point landmarks, simulated in
numpy, with known ids, nearest neighbour and JCBB."""

import numpy as np
import pytest

import sylva
from conftest import assert_unchanged, range_bearing, snapshot

SIGMA = np.array([0.05, np.radians(1.0)])  # range m, bearing rad
SIGMA_U = np.array([0.05, np.radians(1.0)])  # v m/s, omega rad/s


def world(seed):
    rng = np.random.default_rng(seed)
    angles = np.linspace(0, 2 * np.pi, 24, endpoint=False)
    radii = np.where(np.arange(24) % 2 == 0, 6.0, 14.0)
    landmarks = np.c_[radii * np.cos(angles), radii * np.sin(angles)]
    return rng, landmarks


def run(association, seed, steps=150):
    rng, landmarks = world(seed)
    dt, v, w = 0.5, 1.0, 0.1  # a circle of radius 10 m
    x = np.array([10.0, 0.0, np.pi / 2])
    ekf = sylva.Unicycle2DEkf(x, np.zeros((3, 3)))
    front = sylva.FrontEnd(ekf, association=association, reach=sylva.RangeBearingReach(max_range_m=9.0))
    truth_of = {}  # filter id -> true landmark
    right = wrong = 0
    nees = []
    for k in range(steps):
        h = x[2] + dt * w / 2
        x = np.array([x[0] + dt * v * np.cos(h), x[1] + dt * v * np.sin(h), x[2] + dt * w])
        u = np.array([v, w]) + SIGMA_U * rng.standard_normal(2)
        seen = [i for i, l in enumerate(landmarks) if np.hypot(*(l - x[:2])) < 8.0]
        Z = np.array([range_bearing(x, landmarks[i]) + SIGMA * rng.standard_normal(2) for i in seen]).reshape(-1, 2)
        ids = seen if association == sylva.Association.KNOWN_IDS else None
        report = front.step(u, dt, np.diag(SIGMA_U**2), Z, np.diag(SIGMA**2), k * dt, ids=ids)
        for i, r in zip(seen, report.readings):
            if r.outcome == sylva.Outcome.ADDED:
                truth_of[r.landmark] = i
            elif r.outcome == sylva.Outcome.PAIRED:
                if truth_of[r.landmark] == i:
                    right += 1
                else:
                    wrong += 1
        if k > 0:  # one prediction from P0 = 0 leaves a pose covariance of rank 2
            nees.append(ekf.robot_nees(x))
    return ekf, landmarks, truth_of, right, wrong, np.mean(nees)


@pytest.mark.parametrize("seed", range(1, 6))
@pytest.mark.parametrize(
    "association", [sylva.Association.KNOWN_IDS, sylva.Association.NEAREST_NEIGHBOR, sylva.Association.JCBB]
)
def test_front_end_maps_the_circle(association, seed):
    ekf, landmarks, truth_of, right, wrong, mean_nees = run(association, seed)
    assert wrong == 0 and right > 500
    # each true landmark in sight mapped once, and where it is
    assert sorted(truth_of.values()) == sorted(set(truth_of.values()))
    for lid, true in truth_of.items():
        assert np.hypot(*(ekf.landmark_mean(lid) - landmarks[true])) < 0.5
    # 3-dof pose NEES averaged over 149 steps: far above 3 would mean an over-confident filter
    assert mean_nees < 3 * 3


def test_known_ids_keep_the_callers_ids():
    ekf, _, truth_of, _, _, _ = run(sylva.Association.KNOWN_IDS, 1, steps=20)
    assert all(lid == true for lid, true in truth_of.items())


def test_refused_readings_are_values_not_exceptions():
    ekf = sylva.Unicycle2DEkf([0, 0, 0], np.zeros((3, 3)))
    front = sylva.FrontEnd(ekf, association=sylva.Association.KNOWN_IDS)
    report = front.update([[3.0, 0.1], [np.nan, 0.2], [0.0, 0.3]], np.diag(SIGMA**2), 0.0, ids=[1, 2, 3])
    assert report.outcomes == [sylva.Outcome.ADDED, sylva.Outcome.REFUSED, sylva.Outcome.REFUSED]
    assert report.readings[1].error == sylva.ErrorCode.NON_FINITE
    assert report.readings[2].error == sylva.ErrorCode.DEGENERATE_GEOMETRY
    assert ekf.ids == [1]
    assert front.sightings(1) == 1
    before = snapshot(ekf)
    with pytest.raises(sylva.Error, match="earlier than the last step"):
        front.update([[3.0, 0.1]], np.diag(SIGMA**2), -1.0, ids=[1])
    with pytest.raises(sylva.Error, match=r"noise: expected shape \(2, 2\) or \(1, 2, 2\)"):
        front.update([[3.0, 0.1]], np.zeros((2, 2, 2)), 1.0, ids=[1])
    with pytest.raises(sylva.Error, match="ids: 2 ids for 1 readings"):
        front.update([[3.0, 0.1]], np.diag(SIGMA**2), 1.0, ids=[1, 2])
    with pytest.raises(sylva.Error) as info:
        front.step([1.0, 0.0], -0.5, np.diag(SIGMA_U**2), [[3.0, 0.1]], np.diag(SIGMA**2), 1.0, ids=[1])
    assert info.value.code == sylva.ErrorCode.NEGATIVE_TIME_STEP
    assert_unchanged(ekf, before)
    assert front.sightings(1) == 1
