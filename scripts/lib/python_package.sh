# shellcheck shell=bash
# sylva_python_package VENV: installs python/ (the Python package sylva) into the virtual
# environment VENV, made first if missing, the way docs/python.md tells a user to: a venv of
# Debian's python3 that sees the system's packages (numpy, pybind11 and pytest from apt; Debian
# 12 refuses pip installs into the system itself), pip install without network or build
# isolation. SYLVA_PYTHON (default /usr/bin/python3, the interpreter apt installs for) makes
# the venv; SYLVA_PYTHON_CXX=clang++ compiles the extension with clang (default: g++, as pip
# does); SYLVA_JOBS compiles its units in parallel. Needs $repo (the repository's root).
# python3-wheel: setuptools 66 builds a wheel through it, and pip without build isolation
# does not fetch it.
sylva_python_packages=(python3-dev python3-venv python3-setuptools python3-wheel python3-pybind11 pybind11-dev
                       python3-numpy python3-pytest python3-matplotlib)

sylva_python_package() {
  local venv="$1"
  if [[ ! -x "$venv/bin/python" ]]; then
    "${SYLVA_PYTHON:-/usr/bin/python3}" -m venv --system-site-packages "$venv"
  fi
  local compilers=()
  if [[ "${SYLVA_PYTHON_CXX:-}" == clang++* ]]; then compilers=(CC=clang CXX=clang++); fi
  (cd "$repo" && env -u MAKEFLAGS "${compilers[@]}" "$venv/bin/pip" install --no-build-isolation --no-index \
    --no-deps ./python)
}
