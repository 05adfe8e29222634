"""A measurement model written in Python runs through the C++ filter: with numerical
Jacobians it matches RangeBearing to the accuracy of central differences, with its own
Jacobians to round-off."""

import numpy as np
import pytest

import sylva
from conftest import R, assert_unchanged, range_bearing, snapshot


def jacobians(x, l):
    d = l - x[:2]
    q = d @ d
    r = np.sqrt(q)
    J_x = np.array([[-d[0] / r, -d[1] / r, 0.0], [d[1] / q, -d[0] / q, -1.0]])
    J_l = np.array([[d[0] / r, d[1] / r], [-d[1] / q, d[0] / q]])
    return J_x, J_l


def inverse(x, z):
    a = x[2] + z[1]
    return np.array([x[0] + z[0] * np.cos(a), x[1] + z[0] * np.sin(a)])


NUMERIC = sylva.PythonModel(2, range_bearing, angles=[1])
ANALYTIC = sylva.PythonModel(2, range_bearing, jacobians=jacobians, angles=[1])


@pytest.mark.parametrize("model, tol", [(NUMERIC, 1e-8), (ANALYTIC, 1e-13)])
def test_python_model_matches_range_bearing(ekf, model, tol):
    a, b = ekf.copy(), ekf.copy()
    ia = a.update(model, 7, [4.243, 0.7854], R)
    ib = b.update(sylva.RangeBearing(), 7, [4.243, 0.7854], R)
    assert np.allclose(ia.S, ib.S, rtol=tol, atol=0)
    assert np.allclose(a.mean, b.mean, rtol=0, atol=tol)
    assert np.allclose(a.covariance, b.covariance, rtol=0, atol=tol)


def test_python_inverse_matches_inverse_range_bearing():
    start = sylva.Unicycle2DEkf([1.0, 2.0, 0.5], np.diag([0.01, 0.02, 0.003]))
    a, b = start.copy(), start.copy()
    a.add(1, sylva.PythonInverseModel(2, inverse), [3.0, 0.2], R)
    b.add(1, sylva.InverseRangeBearing(), [3.0, 0.2], R)
    assert np.allclose(a.covariance, b.covariance, rtol=0, atol=1e-8)
    assert np.array_equal(a.landmark_mean(1), b.landmark_mean(1)) or np.allclose(
        a.landmark_mean(1), b.landmark_mean(1), rtol=0, atol=1e-14
    )


def test_bearing_wraps_across_pi():
    # A landmark straight behind: predicted bearing near +pi, measured near -pi.
    f = sylva.Unicycle2DEkf([0, 0, 0], np.diag([1e-4, 1e-4, 1e-4]))
    f.add(1, sylva.InverseRangeBearing(), [5.0, np.pi - 0.001], R)
    innovation = f.update(NUMERIC, 1, [5.0, -np.pi + 0.001], R)
    assert abs(innovation.nu[1]) == pytest.approx(0.002, abs=1e-9)


def test_one_dimensional_model(ekf):
    rng = sylva.PythonModel(1, lambda x, l: np.array([np.hypot(*(l - x[:2]))]))
    innovation = ekf.update(rng, 7, [5.0], np.array([[0.01]]))
    assert innovation.nu.shape == (1,)


def test_errors_inside_the_model_leave_the_filter_unchanged(ekf):
    before = snapshot(ekf)

    def broken(x, l):
        raise RuntimeError("sensor offline")

    with pytest.raises(RuntimeError, match="sensor offline"):
        ekf.update(sylva.PythonModel(2, broken), 7, [4.0, 0.7], R)
    assert_unchanged(ekf, before)
    with pytest.raises(sylva.Error, match=r"PythonModel: the result of the Python function: expected shape \(2,\)"):
        ekf.update(sylva.PythonModel(2, lambda x, l: np.zeros(3)), 7, [4.0, 0.7], R)
    assert_unchanged(ekf, before)
    with pytest.raises(sylva.Error) as info:
        ekf.update(sylva.PythonModel(2, lambda x, l: np.array([np.nan, 0.0])), 7, [4.0, 0.7], R)
    assert info.value.code == sylva.ErrorCode.NON_FINITE
    assert_unchanged(ekf, before)
    with pytest.raises(sylva.Error, match="pair of arrays"):
        ekf.update(sylva.PythonModel(2, range_bearing, jacobians=lambda x, l: 1.0), 7, [4.0, 0.7], R)
    assert_unchanged(ekf, before)


def test_model_arguments_are_checked():
    with pytest.raises(sylva.Error, match="dim must be 1, 2 or 3"):
        sylva.PythonModel(4, range_bearing)
    with pytest.raises(sylva.Error, match="not callable"):
        sylva.PythonModel(2, 3.0)
    with pytest.raises(sylva.Error, match="angle index 2"):
        sylva.PythonModel(2, range_bearing, angles=[2])
