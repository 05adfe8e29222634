"""The same seeds give the same figures from Python as from the C++ examples.

python/examples/range_bearing_study.py runs examples/range_bearing_slam's study through the
bindings. Its figures, formatted by the function that formats the C++ program's for the docs
(scripts/docs_figures.py), must equal the committed ones (docs/figures/
range-bearing-slam.figures.json, from `range_bearing_slam --runs 20`). Where the C++ program is
built (SYLVA_EXAMPLES_BIN: the examples directory of a build; scripts/test.sh sets it), its
whole JSON output must equal the Python study's, bit for bit, for each association."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python" / "examples"))
sys.path.insert(0, str(ROOT / "scripts"))

import range_bearing_study  # noqa: E402
from docs_figures import range_bearing_figures  # noqa: E402


def python_study(**flags):
    o = range_bearing_study.defaults()
    for key, value in flags.items():
        setattr(o, key, value)
    out, *_ = range_bearing_study.study(o)
    return json.loads(json.dumps(out))  # as printed


def test_published_figures_from_python():
    committed = json.loads((ROOT / "docs" / "figures" / "range-bearing-slam.figures.json").read_text())
    assert "--runs 20 " in committed["command"]
    figures = range_bearing_figures({"main": python_study(runs=20)})
    assert figures == committed["figures"]


def cpp_program():
    bin_dir = os.environ.get("SYLVA_EXAMPLES_BIN")
    if not bin_dir:
        pytest.skip("SYLVA_EXAMPLES_BIN is not set: no C++ examples to compare with (scripts/test.sh sets it)")
    program = Path(bin_dir) / "range_bearing_slam" / "range_bearing_slam"
    if not program.is_file():
        pytest.skip(f"{program} is not built")
    return program


@pytest.mark.parametrize("association, seed", [("known", 3), ("nn", 5), ("jcbb", 7)])
def test_whole_output_equals_the_cpp_program(association, seed):
    program = cpp_program()
    cpp = json.loads(subprocess.run(
        [str(program), "--runs", "2", "--seed", str(seed), "--association", association, "--json", "--svg", ""],
        check=True, capture_output=True, text=True).stdout)
    assert python_study(runs=2, seed=seed, association=association) == cpp
