import numpy as np
import pytest

import sylva

R = sylva.sigmas(0.1, 0.01)  # [range m, bearing rad]
Q = sylva.sigmas(0.05, 0.02)  # [v m/s, omega rad/s]


def range_bearing(pose, landmark):
    """The reading of a Point2 landmark from a planar pose, in numpy."""
    d = np.asarray(landmark, float) - np.asarray(pose[:2], float)
    bearing = np.arctan2(d[1], d[0]) - pose[2]
    return np.array([np.hypot(d[0], d[1]), np.arctan2(np.sin(bearing), np.cos(bearing))])


def snapshot(ekf):
    """Everything a caller can read of a filter."""
    return (ekf.mean.copy(), ekf.covariance.copy(), list(ekf.ids))


def assert_unchanged(ekf, before):
    mean, cov, ids = before
    assert list(ekf.ids) == ids
    assert np.array_equal(ekf.mean, mean)
    assert np.array_equal(ekf.covariance, cov)


@pytest.fixture
def ekf():
    """The README's filter after its first sighting and one prediction."""
    f = sylva.Unicycle2DEkf([0.0, 0.0, 0.0], np.zeros((3, 3)))
    f.add(7, sylva.InverseRangeBearing(), [5.0, 0.6435], R)
    f.predict([1.0, 0.0], 1.0, Q)
    return f
