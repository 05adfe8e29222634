"""Builds the extension sylva._sylva from python/src against the headers in ../include.

The headers are found relative to this file, so build from a clone of the repository:
    python3 -m venv --system-site-packages venv
    venv/bin/pip install --no-build-isolation ./python
SYLVA_JOBS (default: the number of cores) compiles the binding units in parallel;
SYLVA_PY_OPT (default -O2) is their optimization level; EIGEN_INCLUDE_DIR (default
/usr/include/eigen3) is where Eigen is.
"""

import os
from pathlib import Path

from pybind11.setup_helpers import ParallelCompile, Pybind11Extension
from setuptools import setup

here = Path(__file__).resolve().parent
include = here.parent / "include"
if not (include / "sylva" / "sylva.hpp").is_file():
    raise SystemExit(f"sylva headers not found at {include}: build from a clone of the repository")

ParallelCompile("SYLVA_JOBS", default=os.cpu_count() or 1).install()

# The longest units first, so that the parallel compile does not end on one of them alone.
LONGEST = ["monocular_pipeline.cpp", "planar_odometry.cpp", "planar_ackermann.cpp", "planar_unicycle.cpp"]
sources = sorted((str(p.relative_to(here)) for p in (here / "src").glob("*.cpp")),
                 key=lambda s: (LONGEST.index(Path(s).name) if Path(s).name in LONGEST else len(LONGEST), s))
# Every header the units may include: setuptools rebuilds the extension when one is newer.
depends = sorted(str(p) for p in [*include.rglob("*.hpp"), *(here / "src").glob("*.hpp")])
extension = Pybind11Extension(
    "sylva._sylva",
    sources,
    depends=depends,
    include_dirs=[str(here / "src"), str(include), os.environ.get("EIGEN_INCLUDE_DIR", "/usr/include/eigen3")],
    cxx_std=17,
    extra_compile_args=[os.environ.get("SYLVA_PY_OPT", "-O2"), "-DNDEBUG"],
)

setup(ext_modules=[extension])
