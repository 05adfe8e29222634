#pragma once
// The study's aggregate step: from the runs' JSON lines to a CSV of every point of every
// sweep, gnuplot figures like the thesis' Fig. 4.5-4.8 and 4.10-4.17, a NEES plot, and
// docs/results.md comparing ours with the thesis' claims.
//
// Statistics (thesis Sec. 4.2-4.3): convergence ratio = converged runs / runs
// (e_l < 10, e_t < 3); E_al, E_at (eq. 4.21-4.22) = mean e_l, e_t over the CONVERGED runs,
// with standard error sd / sqrt(n); A_al, A_at (eq. 4.16-4.17) = mean of max(-10, -e_l),
// max(-3, -e_t) over all runs (the gain figures). The camera pose NEES is averaged over the
// runs of the noise sweep at its lowest noise level, per sample time, with the two-sided 95%
// bounds of an average of N chi-square(6) variables.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

#include <sylva/consistency/chi_square.hpp>
#include <sylva/core/error.hpp>

#include "paired_claims.hpp"
#include "study.hpp"

namespace tree_width_study {

namespace fs = std::filesystem;

inline double numberOr(const nlohmann::json& j, const char* key, double fallback) {
  const auto it = j.find(key);
  return it == j.end() || it->is_null() ? fallback : it->get<double>();
}

/// Mean and standard error of `v` (NaN when empty; se 0 for one value).
inline std::pair<double, double> meanAndStandardError(const std::vector<double>& v) {
  if (v.empty()) return {std::nan(""), std::nan("")};
  double sum = 0.0;
  for (double x : v) sum += x;
  const double mean = sum / static_cast<double>(v.size());
  if (v.size() < 2) return {mean, 0.0};
  double ss = 0.0;
  for (double x : v) ss += (x - mean) * (x - mean);
  return {
      mean,
      std::sqrt(ss / static_cast<double>(v.size() - 1)) / std::sqrt(static_cast<double>(v.size()))};
}

/// One point of a sweep: the runs sharing sweep, occlusion, pipeline and x.
struct Point {
  int runs = 0;
  int converged = 0;
  std::vector<double> el, et;       ///< converged runs
  double sat_l = 0.0, sat_t = 0.0;  ///< sums for A_al, A_at
  double ratio() const { return runs > 0 ? static_cast<double>(converged) / runs : std::nan(""); }
  double A_al() const { return sat_l / runs; }
  double A_at() const { return sat_t / runs; }
};

struct Key {
  std::string sweep, occlusion, pipeline;
  double x = 0.0;  ///< noise sigma (noise), density (density), pixel scale (gain)
  double width_scale = 0.0;
  bool operator<(const Key& o) const {
    return std::tie(sweep, occlusion, pipeline, x, width_scale) <
           std::tie(o.sweep, o.occlusion, o.pipeline, o.x, o.width_scale);
  }
};

struct StudyData {
  std::map<Key, Point> points;
  /// pipeline -> per-sample NEES values (noise sweep, lowest level, non-occluded only)
  std::map<std::string, std::vector<std::vector<double>>> nees;
  int nees_every = 0;
  PairedRuns paired;  ///< the noise and density runs, grouped by identical measurements
  TunedSettings tuned;  ///< the settings of the "tuned" runs, where a pipeline has them
  double nees_level = 0.0;
  int runs = 0;
};

inline StudyData aggregate(const std::vector<nlohmann::json>& lines) {
  StudyData data;
  double lowest = std::numeric_limits<double>::infinity();
  for (const auto& j : lines)
    if (j.at("sweep") == "noise") lowest = std::min(lowest, j.at("pixel_sigma_px").get<double>());
  data.nees_level = lowest;
  for (const auto& j : lines) {
    ++data.runs;
    addPairedRun(data.paired, j);
    // The tables, figures and NEES describe the shared setting; the tuned runs enter the
    // paired comparisons only (and the tuned-settings table).
    const auto setting = j.find("setting");
    if (setting != j.end() && *setting == "tuned") {
      Key k;
      k.sweep = j.at("sweep").get<std::string>();
      k.occlusion = j.at("occlusion").get<std::string>();
      k.pipeline = j.at("pipeline").get<std::string>();
      data.tuned[{k.pipeline, k.occlusion}] = {j.at("pixel_scale").get<double>(), j.at("width_scale").get<double>(),
                                               j.at("tree_position_sigma_m").get<double>()};
      continue;
    }
    Key k;
    k.sweep = j.at("sweep").get<std::string>();
    k.occlusion = j.at("occlusion").get<std::string>();
    k.pipeline = j.at("pipeline").get<std::string>();
    if (k.sweep == "noise")
      k.x = j.at("pixel_sigma_px").get<double>();
    else if (k.sweep == "density")
      k.x = j.at("density").get<double>();
    else {
      k.x = j.at("pixel_scale").get<double>();
      k.width_scale = j.at("width_scale").get<double>();
    }
    Point& p = data.points[k];
    const double el = numberOr(j, "landmark_error", std::numeric_limits<double>::infinity());
    const double et = numberOr(j, "trajectory_error", std::numeric_limits<double>::infinity());
    ++p.runs;
    p.sat_l += std::max(-10.0, -el);
    p.sat_t += std::max(-3.0, -et);
    if (j.at("converged").get<bool>()) {
      ++p.converged;
      p.el.push_back(el);
      p.et.push_back(et);
    }
    if (k.sweep == "noise" && k.x == lowest && k.occlusion == "non_occluded_only") {
      data.nees_every = j.at("pose_nees_every").get<int>();
      auto& series = data.nees[k.pipeline];
      const auto& values = j.at("pose_nees");
      if (series.size() < values.size()) series.resize(values.size());
      for (std::size_t i = 0; i < values.size(); ++i)
        series[i].push_back(values[i].is_null() ? std::numeric_limits<double>::infinity()
                                                : values[i].get<double>());
    }
  }
  return data;
}

inline const char* pipelineTitle(const std::string& p) {
  if (p == "none") return "no width";
  if (p == "after_xyz") return "width after XYZ-R (thesis)";
  return "width from first sight (IDR)";
}

inline const std::vector<std::string>& pipelineKeys() {
  static const std::vector<std::string> keys{"none", "after_xyz", "first_sight"};
  return keys;
}

inline const std::vector<std::string>& occlusionKeys() {
  static const std::vector<std::string> keys{"ignored", "non_occluded_only"};
  return keys;
}

inline std::string fmt(double v, const char* f = "%.3f") {
  if (!std::isfinite(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

/// Writes the CSV of every point.
inline void writeCsv(const StudyData& d, const fs::path& path) {
  std::ofstream out(path);
  if (!out)
    sylva::fail(sylva::ErrorCode::kInvalidArgument,
                "tree_width_study: cannot write " + path.string());
  out << "sweep,occlusion,pipeline,x,width_scale,runs,converged,convergence_ratio,landmark_error_"
         "mean,landmark_error_se,"
         "trajectory_error_mean,trajectory_error_se,A_al,A_at\n";
  for (const auto& [k, p] : d.points) {
    const auto [el, el_se] = meanAndStandardError(p.el);
    const auto [et, et_se] = meanAndStandardError(p.et);
    out << k.sweep << ',' << k.occlusion << ',' << k.pipeline << ',' << k.x << ','
        << (k.sweep == "gain" ? fmt(k.width_scale, "%g") : "") << ',' << p.runs << ','
        << p.converged << ',' << fmt(p.ratio(), "%.4f") << ',' << fmt(el, "%.6g") << ','
        << fmt(el_se, "%.6g") << ',' << fmt(et, "%.6g") << ',' << fmt(et_se, "%.6g") << ','
        << fmt(p.A_al(), "%.6g") << ',' << fmt(p.A_at(), "%.6g") << '\n';
  }
}

/// gnuplot's data block for one sweep curve: x ratio el el_se et et_se (NaN as "NaN").
inline std::string curveData(const StudyData& d,
                             const std::string& sweep,
                             const std::string& occlusion,
                             const std::string& pipeline) {
  std::ostringstream os;
  for (const auto& [k, p] : d.points) {
    if (k.sweep != sweep || k.occlusion != occlusion || k.pipeline != pipeline) continue;
    const auto [el, el_se] = meanAndStandardError(p.el);
    const auto [et, et_se] = meanAndStandardError(p.et);
    os << k.x << ' ' << p.ratio() << ' ' << (std::isfinite(el) ? el : NAN) << ' '
       << (std::isfinite(el_se) ? el_se : NAN) << ' ' << (std::isfinite(et) ? et : NAN) << ' '
       << (std::isfinite(et_se) ? et_se : NAN) << '\n';
  }
  std::string s = os.str();
  for (std::size_t pos = 0; (pos = s.find("nan", pos)) != std::string::npos;)
    s.replace(pos, 3, "NaN");
  return s;
}

inline const char* kGnuplotHeader =
    "set terminal svg size 1200,380 dynamic font 'sans,12' background '#ffffff'\n"
    "set grid lc rgb '#dddddd'\n"
    "set key bottom left font ',10' spacing 0.9\n"
    "set style line 1 lc rgb '#555555' lw 2 dt 2 pt 6 ps 0.7\n"
    "set style line 2 lc rgb '#1f77b4' lw 2 dt 1 pt 7 ps 0.7\n"
    "set style line 3 lc rgb '#d62728' lw 2 dt 1 pt 5 ps 0.7\n";

/// Runs gnuplot on `script` (throws if it fails).
inline void runGnuplot(const fs::path& script) {
  const std::string command = "gnuplot '" + script.string() + "'";
  if (std::system(command.c_str()) != 0)
    sylva::fail(sylva::ErrorCode::kInvalidArgument,
                "tree_width_study: gnuplot failed on " + script.string() +
                    " (is gnuplot installed? apt-get install gnuplot-nox)");
}

/// Fig. 4.10-4.17 for one sweep and occlusion mode: convergence ratio, E_al and E_at.
inline void plotSweep(const StudyData& d,
                      const std::string& sweep,
                      const std::string& occlusion,
                      const fs::path& svg,
                      const fs::path& work) {
  std::ostringstream gp;
  gp << kGnuplotHeader << "set output '" << svg.string() << "'\n";
  for (std::size_t i = 0; i < pipelineKeys().size(); ++i)
    gp << "$d" << i << " << EOD\n" << curveData(d, sweep, occlusion, pipelineKeys()[i]) << "EOD\n";
  const std::string xlabel =
      sweep == "noise" ? "pixel noise sigma (px)" : "tree density (fraction of the trees kept)";
  const std::string occl =
      occlusion == "ignored" ? "occlusions ignored" : "only non-occluded trees";
  gp << "set multiplot layout 1,3 title '" << (sweep == "noise" ? "Noise sweep" : "Density sweep")
     << ", " << occl << "'\n";
  gp << "set xlabel '" << xlabel << "'\n";
  if (sweep == "density") gp << "set xrange [*:*] reverse\n";
  const auto plot = [&](const char* ylabel, const char* using_cols, bool bars) {
    gp << "set ylabel '" << ylabel << "'\n";
    gp << "plot ";
    for (std::size_t i = 0; i < pipelineKeys().size(); ++i) {
      if (i) gp << ", ";
      gp << "$d" << i << " using " << using_cols << " with "
         << (bars ? "yerrorlines" : "linespoints") << " ls " << i + 1 << " title '"
         << pipelineTitle(pipelineKeys()[i]) << "'";
    }
    gp << "\n";
  };
  gp << "set yrange [0:1.05]\n";
  plot("convergence ratio", "1:2", false);
  gp << "set yrange [0:*]\nunset key\n";
  plot("E_{al} (m^2), converged runs", "1:3:4", true);
  plot("E_{at} (m^2), converged runs", "1:5:6", true);
  gp << "unset multiplot\n";
  const fs::path script = work / (svg.stem().string() + ".gp");
  std::ofstream(script) << gp.str();
  runGnuplot(script);
}

/// Fig. 4.5-4.8: A_al and A_at over the gain grid, one panel per pipeline.
inline void plotGains(const StudyData& d,
                      const std::string& occlusion,
                      const fs::path& svg,
                      const fs::path& work) {
  std::ostringstream gp;
  gp << "set terminal svg size 1200,640 dynamic font 'sans,12' background '#ffffff'\n"
     << "set grid lc rgb '#dddddd'\nset key bottom right font ',10'\nset logscale x 2\n"
     << "set output '" << svg.string() << "'\n";
  gp << "set multiplot layout 2,3 title 'Gain selection (Sec. 4.2), "
     << (occlusion == "ignored" ? "occlusions ignored" : "only non-occluded trees")
     << "; 0 is perfect, -10 / -3 all diverged'\n";
  for (const char* metric : {"A_al", "A_at"}) {
    for (const std::string& pipeline : pipelineKeys()) {
      // Series: one per pixel scale; x = width scale (no-width pipeline: x = pixel scale).
      std::map<double, std::vector<std::pair<double, double>>> series;
      for (const auto& [k, p] : d.points) {
        if (k.sweep != "gain" || k.occlusion != occlusion || k.pipeline != pipeline) continue;
        const double value = std::string(metric) == "A_al" ? p.A_al() : p.A_at();
        if (pipeline == "none")
          series[0.0].emplace_back(k.x, value);
        else
          series[k.x].emplace_back(k.width_scale, value);
      }
      gp << "set title '" << pipelineTitle(pipeline) << "' font ',11'\n";
      gp << "set xlabel '"
         << (pipeline == "none" ? "filter sigma on u, v / simulated sigma"
                                : "filter sigma on w / simulated sigma")
         << "'\n";
      gp << "set ylabel '"
         << (std::string(metric) == "A_al" ? "A_{al} (eq. 4.16)" : "A_{at} (eq. 4.17)") << "'\n";
      gp << "set yrange [" << (std::string(metric) == "A_al" ? -10 : -3) << ":0]\n";
      if (series.empty()) {
        gp << "plot NaN notitle\n";
        continue;
      }
      int i = 0;
      std::ostringstream plots;
      for (const auto& [scale, pts] : series) {
        gp << "$g" << i << " << EOD\n";
        for (const auto& [x, y] : pts) gp << x << ' ' << y << '\n';
        gp << "EOD\n";
        plots << (i ? ", " : "") << "$g" << i
              << " using 1:2 with linespoints lw 2 pt 7 ps 0.6 title '"
              << (pipeline == "none" ? std::string("no width") : "u,v scale " + fmt(scale, "%g"))
              << "'";
        ++i;
      }
      gp << "plot " << plots.str() << "\n";
    }
  }
  gp << "unset multiplot\n";
  const fs::path script = work / (svg.stem().string() + ".gp");
  std::ofstream(script) << gp.str();
  runGnuplot(script);
}

/// Mean camera-pose NEES over time per pipeline with the 95% bounds.
inline void plotNees(const StudyData& d, const fs::path& svg, const fs::path& work, double dt_s) {
  std::ostringstream gp;
  gp << "set terminal svg size 900,420 dynamic font 'sans,12' background '#ffffff'\n"
     << "set grid lc rgb '#dddddd'\nset key top left font ',10'\nset logscale y\n"
     << "set output '" << svg.string() << "'\n"
     << "set xlabel 'time (s)'\nset ylabel 'NEES of the camera pose (6 dof)'\n";
  int runs = 0;
  std::ostringstream plots;
  for (std::size_t i = 0; i < pipelineKeys().size(); ++i) {
    const auto it = d.nees.find(pipelineKeys()[i]);
    if (it == d.nees.end()) continue;
    gp << "$n" << i << " << EOD\n";
    for (std::size_t s = 0; s < it->second.size(); ++s) {
      const auto& v = it->second[s];
      double sum = 0.0;
      for (double x : v) sum += x;
      runs = std::max<int>(runs, static_cast<int>(v.size()));
      std::vector<double> sorted = v;
      std::sort(sorted.begin(), sorted.end());
      const double median = sorted.empty() ? NAN : sorted[sorted.size() / 2];
      gp << s * d.nees_every * dt_s << ' ' << (std::isfinite(sum) ? sum / v.size() : NAN) << ' ' << median << '\n';
    }
    gp << "EOD\n";
    const char* color = i == 0 ? "#555555" : i == 1 ? "#1f77b4" : "#d62728";
    plots << (plots.tellp() > 0 ? ", " : "") << "$n" << i << " using 1:2 with lines lw 2 lc rgb '" << color << "' title '"
          << pipelineTitle(pipelineKeys()[i]) << ", mean', $n" << i << " using 1:3 with lines lw 1.5 dt 2 lc rgb '" << color
          << "' title 'median'";
  }
  if (runs == 0) return;
  const auto [lo, hi] = sylva::averageChiSquareBounds(6, runs);
  gp << "set title 'Camera pose NEES, noise sweep at " << fmt(d.nees_level, "%g")
     << " px, only non-occluded trees, " << runs
     << " runs per pipeline; 95% bounds of the mean'\n";
  gp << "plot " << plots.str() << ", " << lo
     << " with lines dt 2 lc rgb '#2ca02c' title '95% bounds', " << hi
     << " with lines dt 2 lc rgb '#2ca02c' notitle, 6 with lines dt 3 lc rgb '#999999' title 'dof "
        "= 6'\n";
  const fs::path script = work / (svg.stem().string() + ".gp");
  std::ofstream(script) << gp.str();
  runGnuplot(script);
}

}  // namespace tree_width_study
