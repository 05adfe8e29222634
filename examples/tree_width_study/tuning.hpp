#pragma once
// Each pipeline at its own best setting: the tuning sweep behind the study's "tuned" runs.
//
// The thesis tunes each sensor model's gains before it sweeps noise and density (Sec. 4.2),
// and its life cycle switches a tree to XYZ-R at a position uncertainty it does not state.
// `tree_width_study tune` searches, per pipeline and occlusion mode, the filter's u,v noise
// scale, its w noise scale and (for the thesis' pipeline, the only one that uses it) the XYZ-R
// switching threshold, on maps that the noise and density sweeps never score (map indices from
// kTuningMapOffset on, so their forests come from other seeds), at a low and a high noise
// level. The best setting is the one that converges most often; ties go to the higher A_at,
// then the higher A_al (thesis eq. 4.16-4.17), and exact ties to the shared default.

#include <cmath>
#include <cstdint>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

#include "study.hpp"

namespace tree_width_study {

/// Tuning maps are numbered from here: the sweeps use maps 0 .. StudyPlan::maps - 1.
constexpr int kTuningMapOffset = 100;

struct TuningPlan {
  std::uint64_t seed = 1;
  int maps = 6;
  std::vector<double> noise_levels_px{1.0, 6.0};  ///< the density sweep's level and one above 5 px
  std::vector<double> pixel_scales_no_width{0.5, 1.0, 1.5, 2.0, 3.0, 4.0};
  std::vector<double> pixel_scales{1.0, 1.5, 2.0, 3.0};
  std::vector<double> width_scales{0.5, 1.0, 2.0, 4.0};
  std::vector<double> tree_position_sigmas_m{0.05, 0.1, 0.2, 0.3, 0.5, 1.0};

  /// A small grid on two maps, for trying the machinery (not for choosing settings).
  static TuningPlan quick() {
    TuningPlan p;
    p.maps = 2;
    p.pixel_scales_no_width = {1.0, 1.5};
    p.pixel_scales = {1.5};
    p.width_scales = {1.0};
    p.tree_position_sigmas_m = {0.1, 0.3, 1.0};
    return p;
  }
};

/// The settings a pipeline is tried with; the shared default first.
inline std::vector<FilterSetting> candidateSettings(const TuningPlan& plan,
                                                    WidthPipeline pipeline,
                                                    const FilterSetting& shared) {
  std::vector<FilterSetting> out{shared};
  const auto push = [&out](const FilterSetting& f) {
    for (const FilterSetting& g : out)
      if (g == f) return;
    out.push_back(f);
  };
  if (pipeline == WidthPipeline::kNone) {
    for (double ps : plan.pixel_scales_no_width)
      push({ps, shared.width_scale, shared.tree_position_sigma_m});
    return out;
  }
  const std::vector<double> thresholds = pipeline == WidthPipeline::kAfterXyz
                                             ? plan.tree_position_sigmas_m
                                             : std::vector<double>{shared.tree_position_sigma_m};
  for (double ps : plan.pixel_scales)
    for (double ws : plan.width_scales)
      for (double t : thresholds) push({ps, ws, t});
  return out;
}

/// The tuning runs, in a fixed order.
inline std::vector<Job> enumerateTuningJobs(const TuningPlan& plan, const FilterSetting& shared) {
  std::vector<Job> jobs;
  for (bool occlusion : {false, true})
    for (WidthPipeline pipeline : kAllPipelines)
      for (const FilterSetting& f : candidateSettings(plan, pipeline, shared))
        for (double sigma : plan.noise_levels_px)
          for (int m = 0; m < plan.maps; ++m) {
            Job j;
            j.index = static_cast<int>(jobs.size());
            j.sweep = "tune";
            j.pipeline = pipeline;
            j.occlusion = occlusion;
            j.map = kTuningMapOffset + m;
            j.pixel_sigma_px = sigma;
            j.pixel_scale = f.pixel_scale;
            j.width_scale = f.width_scale;
            j.tree_position_sigma_m = f.tree_position_sigma_m;
            jobs.push_back(j);
          }
  return jobs;
}

/// What one setting gave over the tuning maps and levels.
struct TuningScore {
  FilterSetting setting;
  int runs = 0;
  int converged = 0;
  double sat_t = 0.0, sat_l = 0.0;  ///< sums of max(-3, -e_t) and max(-10, -e_l)
  double A_at() const { return runs ? sat_t / runs : std::nan(""); }
  double A_al() const { return runs ? sat_l / runs : std::nan(""); }
  bool betterThan(const TuningScore& o) const {
    return std::make_tuple(converged, A_at(), A_al()) > std::make_tuple(o.converged, o.A_at(), o.A_al());
  }
};

struct TuningResult {
  /// (pipeline, occlusion) -> every setting's score, in the order they were tried (default first)
  std::map<std::pair<std::string, std::string>, std::vector<TuningScore>> scores;
  TunedSettings best;
};

inline TuningResult scoreTuning(const std::vector<nlohmann::json>& lines) {
  TuningResult result;
  for (const auto& j : lines) {
    if (j.at("sweep") != "tune") continue;
    const std::pair<std::string, std::string> key{j.at("pipeline").get<std::string>(),
                                                  j.at("occlusion").get<std::string>()};
    FilterSetting f{j.at("pixel_scale").get<double>(), j.at("width_scale").get<double>(),
                    j.at("tree_position_sigma_m").get<double>()};
    auto& list = result.scores[key];
    auto it = list.begin();
    while (it != list.end() && it->setting != f) ++it;
    if (it == list.end()) it = list.insert(list.end(), TuningScore{f});
    const auto value = [&j](const char* name, double inf) {
      const auto v = j.find(name);
      return v == j.end() || v->is_null() ? inf : v->get<double>();
    };
    ++it->runs;
    it->converged += j.at("converged").get<bool>();
    it->sat_t += std::max(-3.0, -value("trajectory_error", 1e300));
    it->sat_l += std::max(-10.0, -value("landmark_error", 1e300));
  }
  for (const auto& [key, list] : result.scores) {
    const TuningScore* best = &list.front();
    for (const TuningScore& s : list)
      if (s.betterThan(*best)) best = &s;
    result.best[key] = best->setting;
  }
  return result;
}

inline nlohmann::json settingJson(const FilterSetting& f) {
  return {{"pixel_scale", f.pixel_scale},
          {"width_scale", f.width_scale},
          {"tree_position_sigma_m", f.tree_position_sigma_m}};
}

/// docs/study/tuned_settings.json: what the study's "tuned" runs use.
inline void writeTunedSettings(const TuningResult& r, const std::string& path, const std::string& command) {
  nlohmann::json out;
  out["command"] = command;
  out["criterion"] =
      "most converged runs over the tuning maps and noise levels, then the higher A_at, then A_al";
  nlohmann::json settings = nlohmann::json::array();
  for (const auto& [key, f] : r.best) {
    nlohmann::json s = settingJson(f);
    s["pipeline"] = key.first;
    s["occlusion"] = key.second;
    for (const TuningScore& score : r.scores.at(key))
      if (score.setting == f) {
        s["runs"] = score.runs;
        s["converged"] = score.converged;
      }
    settings.push_back(s);
  }
  out["settings"] = settings;
  std::ofstream file(path);
  if (!file) throw std::runtime_error("cannot write " + path);
  file << out.dump(2) << '\n';
}

/// Reads docs/study/tuned_settings.json (empty when the file does not exist).
inline TunedSettings readTunedSettings(const std::string& path) {
  TunedSettings tuned;
  std::ifstream in(path);
  if (!in) return tuned;
  nlohmann::json j;
  try {
    in >> j;
    for (const auto& s : j.at("settings"))
      tuned[{s.at("pipeline").get<std::string>(), s.at("occlusion").get<std::string>()}] = {
          s.at("pixel_scale").get<double>(), s.at("width_scale").get<double>(),
          s.at("tree_position_sigma_m").get<double>()};
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": not a tuned-settings file (" + e.what() + ")");
  }
  return tuned;
}

inline std::string settingText(const FilterSetting& f, const std::string& pipeline) {
  std::ostringstream os;
  os << "u,v " << f.pixel_scale << " x";
  if (pipeline != "none") os << ", w " << f.width_scale << " x";
  if (pipeline == "after_xyz") os << ", XYZ-R below " << f.tree_position_sigma_m << " m";
  return os.str();
}

/// docs/study/tuning.md: the best setting per pipeline, and the thesis pipeline's threshold.
inline void writeTuningMarkdown(const TuningResult& r,
                                const TuningPlan& plan,
                                const FilterSetting& shared,
                                const std::string& path,
                                const std::string& command) {
  const auto title = [](const std::string& p) {
    return p == "none" ? "no width" : p == "after_xyz" ? "width after XYZ-R (thesis)" : "width from first sight (IDR)";
  };
  const auto list = [](const std::vector<double>& v) {
    std::ostringstream s;
    for (std::size_t i = 0; i < v.size(); ++i) s << (i ? ", " : "") << v[i];
    return s.str();
  };
  const auto num = [](double v, const char* spec) {
    char buf[32];
    std::snprintf(buf, sizeof buf, spec, v);
    return std::string(buf);
  };
  std::ostringstream md;
  md << "# Each pipeline at its best setting: the tuning sweep\n\n"
     << "*Generated by `" << command << "` (examples/tree_width_study/tuning.hpp); do not edit.*\n\n"
     << "The study's noise and density sweeps (docs/results.md) first run every pipeline with one "
        "shared filter setting (u,v " << shared.pixel_scale << " x sigma, w " << shared.width_scale
     << " x sigma, XYZ-R below " << shared.tree_position_sigma_m
     << " m), then each pipeline again with its own best setting from this sweep. The setting is "
        "chosen on " << plan.maps << " tuning maps (map indices " << kTuningMapOffset << " to "
     << kTuningMapOffset + plan.maps - 1
     << ", forests that the sweeps never score) at simulated noise {" << list(plan.noise_levels_px)
     << "} px: u,v noise scale {" << list(plan.pixel_scales) << "} ({"
     << list(plan.pixel_scales_no_width) << "} without the width), w noise scale {"
     << list(plan.width_scales) << "}, and for the thesis' pipeline the XYZ-R switching threshold {"
     << list(plan.tree_position_sigmas_m)
     << "} m (the largest position sigma below which a tree gets its radius; the thesis does not "
        "give its value). Best: the most converged runs, then the higher A_at, then the higher "
        "A_al (thesis eq. 4.16-4.17); an exact tie keeps the shared setting.\n\n"
     << "| pipeline | occlusion | best setting | converged | A_at | A_al | shared setting: converged | A_at |\n"
     << "|---|---|---|---|---|---|---|---|\n";
  for (const auto& [key, f] : r.best) {
    const auto& scores = r.scores.at(key);
    const TuningScore* best = nullptr;
    for (const TuningScore& s : scores)
      if (s.setting == f) best = &s;
    const TuningScore& def = scores.front();
    md << "| " << title(key.first) << " | " << key.second << " | " << settingText(f, key.first) << " | "
       << best->converged << " / " << best->runs << " | " << num(best->A_at(), "%.2f") << " | "
       << num(best->A_al(), "%.2f") << " | " << def.converged << " / " << def.runs << " | "
       << num(def.A_at(), "%.2f") << " |\n";
  }
  md << "\n## The thesis' pipeline: the XYZ-R switching threshold\n\n"
     << "For each threshold, its best gains (u,v and w noise scales) and what they gave:\n\n"
     << "| occlusion | XYZ-R below (m) | best gains | converged | A_at | A_al |\n|---|---|---|---|---|---|\n";
  for (const auto& [key, scores] : r.scores) {
    if (key.first != "after_xyz") continue;
    for (double t : plan.tree_position_sigmas_m) {
      const TuningScore* best = nullptr;
      for (const TuningScore& s : scores)
        if (s.setting.tree_position_sigma_m == t && (!best || s.betterThan(*best))) best = &s;
      if (!best) continue;
      md << "| " << key.second << " | " << t << " | u,v " << best->setting.pixel_scale << " x, w "
         << best->setting.width_scale << " x | " << best->converged << " / " << best->runs << " | "
         << num(best->A_at(), "%.2f") << " | " << num(best->A_al(), "%.2f") << " |\n";
    }
  }
  md << "\nWith so few tuning maps the differences between neighbouring settings are within the "
        "noise of a handful of runs; what the table can show is whether any threshold or gain "
        "changes the picture, not a precise optimum.\n";
  std::ofstream file(path);
  if (!file) throw std::runtime_error("cannot write " + path);
  file << md.str();
}

}  // namespace tree_width_study
