"""sylva: EKF-SLAM from Python.

The filters, models and tools are sylva's C++ code (the extension module sylva._sylva);
arrays go in and come out as numpy float64 arrays. Every error is a sylva.Error (a
ValueError) with a sylva.ErrorCode in its `code`, and leaves the filter it came from as it
was. See docs/python.md.
"""

import numpy as _np

from ._sylva import *  # noqa: F401,F403
from ._sylva import ErrorCode, Error, FrontEndOptions, RangeBearing

__all__ = [name for name in dir() if not name.startswith("_")] + ["FrontEnd", "sigmas"]


def _error(code, message):
    """A sylva.Error raised from Python, worded as the C++ library words its own."""
    error = Error(f"sylva: {str(code.name).lower().replace('_', ' ')}: {message}")
    error.code = code
    return error


def sigmas(*values):
    """The diagonal covariance with the given standard deviations: sigmas(0.1, 0.01)."""
    if len(values) == 1 and _np.ndim(values[0]) == 1:
        values = tuple(values[0])
    s = _np.asarray(values, dtype=float)
    return _np.diag(s * s)


def FrontEnd(ekf, sensor=None, reach=None, **options):
    """The SLAM step (sylva::slam::FrontEnd) for a planar filter with a range-bearing sensor.

    ekf: a Unicycle2DEkf, Odometry2DEkf or Ackermann2DEkf (the front end serves this one filter);
    sensor: a RangeBearing (default: at the robot's origin);
    reach: a RangeBearingReach, or None to offer every landmark to association;
    options: the fields of FrontEndOptions as keyword arguments, e.g.
        association=Association.NEAREST_NEIGHBOR, gate_probability=0.99.
    """
    opts = FrontEndOptions()
    for key, value in options.items():
        if not hasattr(opts, key) or key.startswith("_"):
            raise TypeError(f"FrontEnd: unknown option '{key}'")
        setattr(opts, key, value)
    if sensor is None:
        sensor = RangeBearing()
    make = getattr(ekf, "_front_end", None)
    if make is None:
        raise _error(ErrorCode.INVALID_ARGUMENT, f"FrontEnd: expected a planar filter, got a {type(ekf).__name__}")
    return make(sensor, opts, reach)
