#pragma once
// The thesis' claims tested on paired runs. The three pipelines of one noise or density run
// (same sweep, occlusion mode, level, map, noise draw and tree removal) see identical
// measurements, so each comparison of a width pipeline with "no width" is paired:
// - convergence: McNemar's exact test on the runs where exactly one of the two converged,
//   with Wilson 95% intervals on each convergence ratio;
// - trajectory error e_t: the Wilcoxon signed-rank test on the runs converged in both.
// A verdict is "agrees" or "differs" only when its test rejects "no difference" at 5% (two-
// sided), in the claimed or the opposite direction; otherwise "no clear difference". Each claim
// is tested on its own, without a correction for the ten claims of the table.

#include <algorithm>
#include <cstdio>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

#include <sylva/consistency/paired_tests.hpp>

namespace tree_width_study {

/// What one run of one pipeline gave.
struct RunOutcome {
  bool converged = false;
  double et = 0.0;  ///< e_t (m^2); meaningful when converged
};

/// The runs that share their measurements: one of these per noise or density run.
struct PairKey {
  std::string sweep, occlusion;
  double x = 0.0;  ///< noise sigma (px) or density
  int map = 0, draw = 0, removal = -1;
  bool operator<(const PairKey& o) const {
    return std::tie(sweep, occlusion, x, map, draw, removal) < std::tie(o.sweep, o.occlusion, o.x, o.map, o.draw, o.removal);
  }
};

/// A run of a pipeline at its tuned setting is filed as "<pipeline>/tuned".
constexpr const char* kTunedSuffix = "/tuned";

/// pair -> pipeline -> outcome.
using PairedRuns = std::map<PairKey, std::map<std::string, RunOutcome>>;

/// Adds one run line of the noise or density sweep (the gain sweep's pipelines run different
/// grids and are not paired).
inline void addPairedRun(PairedRuns& paired, const nlohmann::json& j) {
  const std::string sweep = j.at("sweep").get<std::string>();
  if (sweep != "noise" && sweep != "density") return;
  PairKey k;
  k.sweep = sweep;
  k.occlusion = j.at("occlusion").get<std::string>();
  k.x = j.at(sweep == "noise" ? "pixel_sigma_px" : "density").get<double>();
  k.map = j.at("map").get<int>();
  k.draw = j.at("draw").get<int>();
  k.removal = j.at("removal").get<int>();
  RunOutcome r;
  r.converged = j.at("converged").get<bool>();
  const auto it = j.find("trajectory_error");
  r.et = it == j.end() || it->is_null() ? 0.0 : it->get<double>();
  const auto setting = j.find("setting");
  const bool tuned = setting != j.end() && *setting == "tuned";
  paired[k][j.at("pipeline").get<std::string>() + (tuned ? kTunedSuffix : "")] = r;
}

inline std::string format(const char* spec, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, spec, v);
  return buf;
}

/// A convergence ratio with its Wilson 95% interval, in percent: "27% [24, 31]".
inline std::string ratioWithInterval(long converged, long runs) {
  if (runs == 0) return "-";
  const auto [lo, hi] = sylva::wilsonInterval(converged, runs);
  return format("%.0f%%", 100.0 * static_cast<double>(converged) / static_cast<double>(runs)) + " [" +
         format("%.0f", 100.0 * lo) + ", " + format("%.0f", 100.0 * hi) + "]";
}

inline std::string pValue(double p) { return p < 0.001 ? std::string("p < 0.001") : "p = " + format("%.3f", p); }

inline std::string pairedVerdict(double p, bool claimed_direction) {
  if (!(p < 0.05)) return "no clear difference";
  return claimed_direction ? "agrees" : "differs";
}

struct PairedComparison {
  std::string ours;
  std::string verdict;
  std::map<std::string, std::string> figures;  ///< named figures for results.figures.json
};

/// Which pipelines were rerun at a tuned setting, by sweep and occlusion mode.
class TunedRuns {
 public:
  explicit TunedRuns(const PairedRuns& paired) {
    const std::size_t suffix = std::string(kTunedSuffix).size();
    for (const auto& [k, runs] : paired)
      for (const auto& [name, outcome] : runs)
        if (name.size() > suffix && name.compare(name.size() - suffix, suffix, kTunedSuffix) == 0)
          rerun_.insert({k.sweep, k.occlusion, name.substr(0, name.size() - suffix)});
  }
  /// The run of `pipeline` in one pair: with `tuned`, its tuned run where the pipeline was
  /// rerun in that sweep and mode (none: end(), the pair is not one of the reruns), else its
  /// run at the shared setting (the tuning kept it).
  std::map<std::string, RunOutcome>::const_iterator find(const PairKey& k,
                                                         const std::map<std::string, RunOutcome>& runs,
                                                         const std::string& pipeline, bool tuned) const {
    if (tuned && rerun_.count({k.sweep, k.occlusion, pipeline})) return runs.find(pipeline + kTunedSuffix);
    return runs.find(pipeline);
  }

 private:
  std::set<std::tuple<std::string, std::string, std::string>> rerun_;
};

/// Convergence of `pipeline` against "no width" over the pairs that `take` keeps (`tuned`: each
/// at its own best setting).
inline PairedComparison compareConvergence(const PairedRuns& paired, const std::string& pipeline,
                                           const std::function<bool(const PairKey&)>& take, bool tuned = false) {
  long n = 0, with = 0, without = 0, only_with = 0, only_without = 0;
  const TunedRuns reruns(paired);
  for (const auto& [k, runs] : paired) {
    if (!take(k)) continue;
    const auto a = reruns.find(k, runs, pipeline, tuned), b = reruns.find(k, runs, "none", tuned);
    if (a == runs.end() || b == runs.end()) continue;
    ++n;
    with += a->second.converged;
    without += b->second.converged;
    only_with += a->second.converged && !b->second.converged;
    only_without += !a->second.converged && b->second.converged;
  }
  if (n == 0) return {"no paired runs", "no data", {}};
  const double p = sylva::mcnemarExact(only_with, only_without);
  PairedComparison c{"converged " + ratioWithInterval(with, n) + " with, " + ratioWithInterval(without, n) +
                         " without (" + std::to_string(n) + " paired runs; converged only with: " +
                         std::to_string(only_with) + ", only without: " + std::to_string(only_without) + "; McNemar " +
                         pValue(p) + ")",
                     pairedVerdict(p, only_with > only_without),
                     {}};
  c.figures = {{"with", ratioWithInterval(with, n)}, {"without", ratioWithInterval(without, n)},
               {"pairs", std::to_string(n)},         {"only_with", std::to_string(only_with)},
               {"only_without", std::to_string(only_without)}, {"p", pValue(p)},
               {"verdict", c.verdict}};
  return c;
}

/// e_t of `pipeline` against "no width" on the pairs that `take` keeps and that converged in both.
inline PairedComparison compareTrajectoryError(const PairedRuns& paired, const std::string& pipeline,
                                               const std::function<bool(const PairKey&)>& take, bool tuned = false) {
  std::vector<double> d;
  const TunedRuns reruns(paired);
  for (const auto& [k, runs] : paired) {
    if (!take(k)) continue;
    const auto a = reruns.find(k, runs, pipeline, tuned), b = reruns.find(k, runs, "none", tuned);
    if (a == runs.end() || b == runs.end() || !a->second.converged || !b->second.converged) continue;
    d.push_back(a->second.et - b->second.et);
  }
  if (d.empty()) return {"no run converged in both", "no data", {}};
  const sylva::SignedRankResult r = sylva::wilcoxonSignedRank(d);
  std::vector<double> sorted = d;
  std::sort(sorted.begin(), sorted.end());
  const double median = sorted.size() % 2 ? sorted[sorted.size() / 2]
                                          : 0.5 * (sorted[sorted.size() / 2 - 1] + sorted[sorted.size() / 2]);
  const double n = static_cast<double>(r.n);
  const bool lower_with = r.w_plus < n * (n + 1.0) / 4.0;  // positive differences rank low
  PairedComparison c{"runs converged in both: " + std::to_string(d.size()) + "; e_t lower with the width in " +
                         std::to_string(r.negative) + ", higher in " + std::to_string(r.positive) +
                         "; median difference " + format("%+.4f", median) + " m^2; Wilcoxon " + pValue(r.p_value),
                     pairedVerdict(r.p_value, lower_with),
                     {}};
  c.figures = {{"pairs", std::to_string(d.size())}, {"lower", std::to_string(r.negative)},
               {"higher", std::to_string(r.positive)}, {"median_difference", format("%+.4f", median)},
               {"p", pValue(r.p_value)}, {"verdict", c.verdict}};
  return c;
}

}  // namespace tree_width_study
