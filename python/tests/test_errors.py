"""Every error of a bound operation surfaces as sylva.Error with sylva's code, and leaves the
filter exactly as it was; wrong shapes and dtypes are refused with a message naming them."""

import numpy as np
import pytest

import sylva
from conftest import Q, R, assert_unchanged, snapshot

C = sylva.ErrorCode
RB = sylva.RangeBearing()
IRB = sylva.InverseRangeBearing()
not_pd = np.array([[1.0, 2.0], [2.0, 1.0]])

BAD_CALLS = {
    "update of an unknown id": (C.UNKNOWN_ID, lambda f: f.update(RB, 8, [4.0, 0.7], R)),
    "remove of an unknown id": (C.UNKNOWN_ID, lambda f: f.remove(8)),
    "landmark_mean of an unknown id": (C.UNKNOWN_ID, lambda f: f.landmark_mean(8)),
    "add of an existing id": (C.DUPLICATE_ID, lambda f: f.add(7, IRB, [2.0, 0.1], R)),
    "NaN measurement": (C.NON_FINITE, lambda f: f.update(RB, 7, [np.nan, 0.7], R)),
    "infinite control": (C.NON_FINITE, lambda f: f.predict([np.inf, 0.0], 1.0, Q)),
    "noise not positive definite": (C.NOT_POSITIVE_DEFINITE, lambda f: f.update(RB, 7, [4.0, 0.7], not_pd)),
    "noise with NaN": (C.NON_FINITE, lambda f: f.update(RB, 7, [4.0, 0.7], np.full((2, 2), np.nan))),
    "negative time step": (C.NEGATIVE_TIME_STEP, lambda f: f.predict([1.0, 0.0], -0.1, Q)),
    "zero range at add": (C.DEGENERATE_GEOMETRY, lambda f: f.add(9, IRB, [0.0, 0.1], R)),
    "batched update with an unknown id": (
        C.UNKNOWN_ID,
        lambda f: f.update_many(RB, [7, 8], [[4.0, 0.7], [3.0, 0.1]], R),
    ),
    "batched update with a NaN": (
        C.NON_FINITE,
        lambda f: f.update_many(RB, [7, 7], [[4.0, 0.7], [np.nan, 0.1]], R),
    ),
    "unknown fusion": (C.INVALID_ARGUMENT, lambda f: f.update_many(RB, [7], [[4.0, 0.7]], R, fusion="joint")),
    "ids and rows differ": (C.INVALID_ARGUMENT, lambda f: f.update_many(RB, [7, 7], [[4.0, 0.7]], R)),
    "control of the wrong size": (C.INVALID_ARGUMENT, lambda f: f.predict([1.0, 0.0, 0.0], 1.0, Q)),
    "measurement as a column": (C.INVALID_ARGUMENT, lambda f: f.update(RB, 7, [[4.0], [0.7]], R)),
    "noise of the wrong size": (C.INVALID_ARGUMENT, lambda f: f.update(RB, 7, [4.0, 0.7], np.eye(3))),
    "complex measurement": (C.INVALID_ARGUMENT, lambda f: f.update(RB, 7, np.array([4.0, 0.7j]), R)),
    "boolean control": (C.INVALID_ARGUMENT, lambda f: f.predict(np.array([True, False]), 1.0, Q)),
    "string measurement": (C.INVALID_ARGUMENT, lambda f: f.update(RB, 7, ["4", "0.7"], R)),
    "float ids": (C.INVALID_ARGUMENT, lambda f: f.update_many(RB, [7.0], [[4.0, 0.7]], R)),
    "not a model": (C.INVALID_ARGUMENT, lambda f: f.update("RangeBearing", 7, [4.0, 0.7], R)),
    "forward model given to add": (C.INVALID_ARGUMENT, lambda f: f.add(9, RB, [2.0, 0.1], R)),
}


@pytest.mark.parametrize("name", sorted(BAD_CALLS))
def test_error_leaves_the_filter_unchanged(ekf, name):
    code, call = BAD_CALLS[name]
    before = snapshot(ekf)
    with pytest.raises(sylva.Error) as info:
        call(ekf)
    assert info.value.code == code, str(info.value)
    assert str(info.value).startswith("sylva: ")
    assert isinstance(info.value, ValueError)
    assert_unchanged(ekf, before)


@pytest.mark.parametrize(
    "z, message",
    [
        ([4.0, 0.7, 1.0], r"z: expected shape \(2,\), got \(3,\)"),
        (np.zeros((2, 2)), r"z: expected shape \(2,\), got \(2, 2\)"),
        (np.array([4.0, 0.7], dtype=complex), "z: expected real numbers .* got dtype complex128"),
        (np.array([4, 1], dtype=bool), "z: expected real numbers .* got dtype bool"),
        (object(), "z: expected real numbers"),
    ],
)
def test_wrong_shape_or_dtype_is_named(ekf, z, message):
    with pytest.raises(sylva.Error, match=message):
        ekf.update(RB, 7, z, R)


def test_integer_and_float32_arrays_are_taken(ekf):
    a, b = ekf.copy(), ekf.copy()
    a.update(RB, 7, np.array([4, 1], dtype=np.int32), R.astype(np.float32))
    b.update(RB, 7, [4.0, 1.0], R.astype(np.float32).astype(float))
    assert np.array_equal(a.mean, b.mean)


def test_a_failed_front_end_construction_names_the_option(ekf):
    with pytest.raises(sylva.Error, match="gate_probability") as info:
        sylva.FrontEnd(ekf, gate_probability=1.5)
    assert info.value.code == C.INVALID_ARGUMENT
    with pytest.raises(TypeError, match="unknown option 'gate'"):
        sylva.FrontEnd(ekf, gate=0.9)
    with pytest.raises(sylva.Error, match="max_range_m"):
        sylva.RangeBearingReach(max_range_m=-1.0)
    with pytest.raises(sylva.Error, match="expected a planar filter") as info:
        sylva.FrontEnd(object())
    assert info.value.code == C.INVALID_ARGUMENT
