"""The Python examples run, and the Victoria Park one matches the C++ program it follows."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python" / "examples"))
DATA = Path(os.environ.get("SYLVA_DATA_DIR", ROOT.parent / "shared" / "data"))

import range_bearing_study  # noqa: E402
import victoria_park_sweep  # noqa: E402


def victoria_park():
    folder = DATA / "victoria-park"
    if not (folder / "measurements.dat").is_file():
        pytest.skip(f"Victoria Park data absent at {folder} (set SYLVA_DATA_DIR): skipped")
    return folder


def test_range_bearing_study_draws_its_figures(tmp_path):
    range_bearing_study.main(["--runs", "2", "--steps", "200", "--association", "nn", "--out-dir", str(tmp_path)])
    for name in ("range_bearing_map.png", "range_bearing_nees.png"):
        assert (tmp_path / name).stat().st_size > 10_000


def test_victoria_park_sweep_runs_on_two_processes(tmp_path):
    folder = victoria_park()
    out = victoria_park_sweep.main(["--data", str(folder), "--duration", "60", "--sensor-scales", "1",
                                    "--odometry-scales", "0.5", "1", "--jobs", "2", "--out-dir", str(tmp_path)])
    assert [r["odometry_scale"] for r in out["results"]] == [0.5, 1.0]
    for r in out["results"]:
        assert r["landmarks"] > 10 and 0.0 < r["gps_rmse_valid_m"] < 5.0
    assert json.loads((tmp_path / "victoria_park_sweep.json").read_text()) == json.loads(json.dumps(out))
    assert (tmp_path / "victoria_park_sweep.png").stat().st_size > 10_000


def test_victoria_park_run_equals_the_cpp_program():
    folder = victoria_park()
    bin_dir = os.environ.get("SYLVA_EXAMPLES_BIN")
    program = Path(bin_dir or "") / "victoria_park" / "victoria_park"
    if not bin_dir or not program.is_file():
        pytest.skip("SYLVA_EXAMPLES_BIN has no victoria_park to compare with (scripts/test.sh sets it): skipped")
    cpp = json.loads(subprocess.run(
        [str(program), "--data", str(folder), "--variant", "point", "--bias-states", "none", "--duration", "120",
         "--json"], check=True, capture_output=True, text=True).stdout)["point"]
    python = victoria_park_sweep.run((1.0, 1.0, str(folder), 120.0))
    assert python["scans"] == cpp["scans"]
    assert python["landmarks"] == cpp["landmarks"]
    assert python["gps_valid_fixes"] == cpp["gps_fixes_valid"]
    assert python["gps_rmse_valid_m"] == cpp["gps_rmse_m"]
    assert python["gps_median_valid_m"] == cpp["gps_median_m"]
