"""The planar filters' operations, against hand-computed values and against each other."""

import copy

import numpy as np
import pytest

import sylva
from conftest import Q, R, range_bearing


def test_readme_sample(ekf):
    # The README's C++ sample, line for line.
    innovation = ekf.update(sylva.RangeBearing(), 7, [4.243, 0.7854], R)
    assert innovation.nu.shape == (2,) and innovation.S.shape == (2, 2)
    assert innovation.nis == pytest.approx(innovation.nu @ np.linalg.solve(innovation.S, innovation.nu))
    assert ekf.robot_mean.shape == (3,)
    assert ekf.landmark_mean(7) == pytest.approx([4.0, 3.0], abs=2e-3)
    P = ekf.landmark_covariance(7)
    assert P.shape == (2, 2) and np.allclose(P, P.T) and np.all(np.linalg.eigvalsh(P) > 0)


def test_state_layout(ekf):
    ekf.add(3, sylva.InverseRangeBearing(), [2.0, -0.3], R)
    assert ekf.ids == [7, 3] and len(ekf) == 2 and ekf.dim == 7
    assert 3 in ekf and 4 not in ekf
    assert np.array_equal(ekf.mean[:3], ekf.robot_mean)
    assert np.array_equal(ekf.mean[5:7], ekf.landmark_mean(3))
    assert np.array_equal(ekf.covariance[3:5, 3:5], ekf.landmark_covariance(7))
    assert np.array_equal(ekf.covariance[:3, 5:7], ekf.robot_landmark_covariance(3))
    ekf.remove(7)
    assert ekf.ids == [3] and ekf.dim == 5


def test_prediction_matches_the_unicycle_equations():
    f = sylva.Unicycle2DEkf([1.0, 2.0, 0.3], np.diag([0.01, 0.01, 0.001]))
    v, w, dt = 1.5, 0.2, 0.5
    f.predict([v, w], dt, Q)
    h = 0.3 + dt * w / 2  # multisensor thesis eq. 2.12-2.14
    assert f.robot_mean == pytest.approx([1.0 + dt * v * np.cos(h), 2.0 + dt * v * np.sin(h), 0.3 + dt * w], abs=1e-15)


def test_batched_update_equals_sequential_for_one_observation(ekf):
    a, b = ekf.copy(), ekf.copy()
    a.update(sylva.RangeBearing(), 7, [4.243, 0.7854], R)
    b.update_many(sylva.RangeBearing(), [7], [[4.243, 0.7854]], R)
    assert np.allclose(a.mean, b.mean, rtol=0, atol=1e-12)
    assert np.allclose(a.covariance, b.covariance, rtol=0, atol=1e-12)


def test_copies_are_independent(ekf):
    for other in (ekf.copy(), copy.copy(ekf), copy.deepcopy(ekf)):
        other.update(sylva.RangeBearing(), 7, [4.243, 0.7854], R)
        assert not np.array_equal(other.mean, ekf.mean)


def test_the_three_robots():
    odo = sylva.Odometry2DEkf([0, 0, 0], np.zeros((3, 3)))
    odo.predict([1.0, 0.0, np.pi / 2], 0.1, sylva.sigmas(0.01, 0.01, 0.01))
    assert odo.robot_mean == pytest.approx([1.0, 0.0, np.pi / 2])
    car = sylva.Ackermann2DEkf([0, 0, 0], np.zeros((3, 3)), wheelbase_m=2.83, encoder_offset_m=0.5)
    car.predict([2.0, 0.0], 1.0, sylva.sigmas(0.1, 0.01))
    assert car.robot_mean == pytest.approx([2.0, 0.0, 0.0])
    with pytest.raises(sylva.Error, match="wheelbase_m"):
        sylva.Ackermann2DEkf([0, 0, 0], np.zeros((3, 3)))
    with pytest.raises(sylva.Error, match="unknown robot parameter 'wheel'"):
        sylva.Ackermann2DEkf([0, 0, 0], np.zeros((3, 3)), wheelbase_m=2.0, wheel=1)
    with pytest.raises(sylva.Error) as info:
        sylva.Ackermann2DEkf([0, 0, 0], np.zeros((3, 3)), wheelbase_m=-1.0)
    assert info.value.code == sylva.ErrorCode.INVALID_ARGUMENT


def test_robot_nees_wraps_the_heading():
    f = sylva.Unicycle2DEkf([0, 0, np.pi - 0.01], np.diag([1.0, 1.0, 0.01]))
    error = f.robot_error([0, 0, -np.pi + 0.01])
    assert error == pytest.approx([0, 0, 0.02], abs=1e-12)
    assert f.robot_nees([0, 0, -np.pi + 0.01]) == pytest.approx(0.02**2 / 0.01)
    assert sylva.nees(error, f.robot_covariance) == pytest.approx(f.robot_nees([0, 0, -np.pi + 0.01]))


def test_mounted_sensor():
    mount = [0.5, 0.2]
    f = sylva.Unicycle2DEkf([1.0, 1.0, 0.4], np.zeros((3, 3)))
    pose = np.array([1.0, 1.0, 0.4])
    c, s = np.cos(0.4), np.sin(0.4)
    sensor_pose = np.array([1.0 + c * 0.5 - s * 0.2, 1.0 + s * 0.5 + c * 0.2, 0.4])
    z = range_bearing(sensor_pose, [4.0, 3.0])
    f.add(1, sylva.InverseRangeBearing(mount), z, R)
    assert f.landmark_mean(1) == pytest.approx([4.0, 3.0], abs=1e-12)
    assert sylva.RangeBearing(mount).mount == pytest.approx(mount)
    assert pose[2] == f.robot_mean[2]


def test_chi_square():
    assert sylva.chi_square_quantile(0.95, 2) == pytest.approx(5.991464547107979, rel=1e-12)
    low, high = sylva.average_chi_square_bounds(3, 50)
    assert low < 3 < high
