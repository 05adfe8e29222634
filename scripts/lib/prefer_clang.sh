# shellcheck shell=bash
# sylva_prefer_clang BUILD_DIR: exports CXX=clang++ for the first configure of BUILD_DIR when
# clang++ is installed and CXX is not set (the report scripts' builds: g++ 12 spends about
# 3.5x longer on sylva's templates, and the generated pages name the compiler). A build dir
# that is already configured keeps its compiler.
sylva_prefer_clang() {
  if [[ ! -f "$1/CMakeCache.txt" && -z "${CXX:-}" ]] && command -v clang++ > /dev/null; then
    export CXX=clang++
  fi
}
