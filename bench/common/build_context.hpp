#pragma once
/// @file
/// `sylva_bench::addBuildContext()`: records the CPU model, compiler, flags, build type and
/// Eigen's version and SIMD set in a benchmark's JSON context, so the reports that read the
/// JSON (scripts/bench_report.py, scripts/step_report.py) can name the machine and the build.
/// Call it between benchmark::Initialize and benchmark::RunSpecifiedBenchmarks, or let
/// `runBenchmarks` (a benchmark program's whole main) do it.

#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <fstream>
#include <initializer_list>
#include <string>
#include <utility>

// Set by bench/CMakeLists.txt.
#ifndef SYLVA_BENCH_CXX_FLAGS
#define SYLVA_BENCH_CXX_FLAGS "unknown"
#endif
#ifndef SYLVA_BENCH_BUILD_TYPE
#define SYLVA_BENCH_BUILD_TYPE "unknown"
#endif

namespace sylva_bench {

/// "model name" of the first processor in /proc/cpuinfo, or "unknown".
inline std::string cpuModel() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(" \t", colon + 1));
    }
  }
  return "unknown";
}

inline void addBuildContext() {
  benchmark::AddCustomContext("cpu_model", cpuModel());
#if defined(__clang__)
  benchmark::AddCustomContext("compiler", std::string("clang ") + __clang_version__);
#elif defined(__GNUC__)
  benchmark::AddCustomContext("compiler", std::string("gcc ") + __VERSION__);
#else
  benchmark::AddCustomContext("compiler", "unknown");
#endif
  benchmark::AddCustomContext("cxx_flags", SYLVA_BENCH_CXX_FLAGS);
  benchmark::AddCustomContext("build_type", SYLVA_BENCH_BUILD_TYPE);
  benchmark::AddCustomContext("eigen_version", std::to_string(EIGEN_WORLD_VERSION) + "." +
                                                   std::to_string(EIGEN_MAJOR_VERSION) + "." +
                                                   std::to_string(EIGEN_MINOR_VERSION));
  benchmark::AddCustomContext("eigen_simd", Eigen::SimdInstructionSetsInUse());
}

/// A benchmark program's main: parses Google Benchmark's flags (an unknown one is an error),
/// records the build context and `extra` (name, value) pairs in the JSON context, runs the
/// benchmarks. Returns the exit code.
inline int runBenchmarks(int argc, char** argv,
                         std::initializer_list<std::pair<std::string, std::string>> extra = {}) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  addBuildContext();
  for (const auto& [name, value] : extra) benchmark::AddCustomContext(name, value);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

}  // namespace sylva_bench
