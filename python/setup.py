"""Builds the extension sylva._sylva from python/src against the headers in ../include.

The headers are found relative to this file, so build from a clone of the repository:
    python3 -m venv --system-site-packages venv
    venv/bin/pip install --no-build-isolation ./python
SYLVA_JOBS (default: the number of cores) compiles the binding units in parallel;
SYLVA_PY_OPT (default -O2) is their optimization level; SYLVA_PY_OPT_REST (default: the
same) is that of every unit but planar_unicycle.cpp (see RUNS_THE_STUDY below);
EIGEN_INCLUDE_DIR (default /usr/include/eigen3) is where Eigen is.
"""

import os
from pathlib import Path

from pybind11.setup_helpers import ParallelCompile, Pybind11Extension, build_ext
from setuptools import setup

here = Path(__file__).resolve().parent
include = here.parent / "include"
if not (include / "sylva" / "sylva.hpp").is_file():
    raise SystemExit(f"sylva headers not found at {include}: build from a clone of the repository")

ParallelCompile("SYLVA_JOBS", default=os.cpu_count() or 1).install()

# The unit whose functions run the range-bearing study, the longest computation of the tests
# (python/tests/test_same_as_cpp.py). It comes first in the link, so that the linker keeps its
# copies of the templates it shares with the other units (Eigen's product kernels) when the
# others are compiled at another level (SYLVA_PY_OPT_REST): with the -O0 copies, the study ran
# about 30 times longer.
RUNS_THE_STUDY = "planar_unicycle.cpp"
# Then the longest units, so that the parallel compile does not end on one of them alone.
LONGEST = [RUNS_THE_STUDY, "monocular_pipeline.cpp", "planar_odometry.cpp", "planar_ackermann.cpp"]


def compile_and_link_order(source):
    name = Path(source).name
    return (LONGEST.index(name) if name in LONGEST else len(LONGEST), name)


sources = sorted((str(p.relative_to(here)) for p in (here / "src").glob("*.cpp")), key=compile_and_link_order)
# Every header the units may include: setuptools rebuilds the extension when one is newer.
depends = sorted(str(p) for p in [*include.rglob("*.hpp"), *(here / "src").glob("*.hpp")])
optimization = os.environ.get("SYLVA_PY_OPT", "-O2")
rest_optimization = os.environ.get("SYLVA_PY_OPT_REST", optimization)


class BuildExtension(build_ext):
    """Compiles and links the units in the order of compile_and_link_order (setuptools sorts
    them by name), and every unit but RUNS_THE_STUDY at SYLVA_PY_OPT_REST (a later -O wins)."""

    def build_extension(self, ext):
        compile_all = self.compiler.compile
        compile_one = self.compiler._compile

        def compile_in_order(sources, *args, **kwargs):
            return compile_all(sorted(sources, key=compile_and_link_order), *args, **kwargs)

        def compile_at_its_level(obj, src, src_ext, cc_args, extra_postargs, pp_opts):
            if Path(src).name != RUNS_THE_STUDY:
                extra_postargs = [*extra_postargs, rest_optimization]
            compile_one(obj, src, src_ext, cc_args, extra_postargs, pp_opts)

        self.compiler.compile = compile_in_order
        if rest_optimization != optimization:
            self.compiler._compile = compile_at_its_level
        super().build_extension(ext)


extension = Pybind11Extension(
    "sylva._sylva",
    sources,
    depends=depends,
    include_dirs=[str(here / "src"), str(include), os.environ.get("EIGEN_INCLUDE_DIR", "/usr/include/eigen3")],
    cxx_std=17,
    extra_compile_args=[optimization, "-DNDEBUG"],
)

setup(ext_modules=[extension], cmdclass={"build_ext": BuildExtension})
