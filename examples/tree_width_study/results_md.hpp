#pragma once
// docs/results.md from the aggregated study: the thesis' claims next to ours, the tables
// behind every figure, and the commands that regenerate it all.

#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "report.hpp"
#include "tuning.hpp"

namespace tree_width_study {

/// What we know about why ours and the thesis' differ (written by hand from the study's
/// output; the numbers above it are regenerated, this text is not).
inline const char* kDiscussion = R"(### What we think explains the differences

*This paragraph is written by hand (examples/tree_width_study/results_md.hpp) from what the
study showed; the tables and verdicts above and below are regenerated with every run.*

- **The thesis' pipeline converges no more often than the run without the width.** A run's
  fate is decided in lap 1: e_l is measured at its end, and a monocular map whose scale drifts
  in the first tens of metres does not come back. In the thesis' life cycle a tree gets its
  radius only once its position is known to 0.3 m (our `--xyzr-sigma`; the thesis gives no
  number), which in our forest is late: on the default forest no tree is XYZ-R after 30 s and 8
  of 83 are at the end of lap 1 (`forest_slam --frames 300` and `--frames 559`, "trees XYZ-R"),
  against 23 and 62 for the IDR pipeline. The width then refines a map
  that has already converged or already drifted (it estimates the radii to millimetres and
  lowers e_t in some runs), but cannot rescue a drifted one. The thesis' Fig. 4.10-4.16 show
  better convergence with the width; its switching threshold, its gains (w1 = 16, w2 = 4 in
  its own units) and the speed of its camera are not given in enough detail to tell whether
  its trees reached XYZ-R earlier than ours do. The tuning sweep tried thresholds from 0.05
  to 1 m, each with its best gains: on the tuning maps no threshold changed how often the
  pipeline converged (study/tuning.md), so the threshold is not what keeps its width from
  helping.
- **The width from the first sighting changes that.** The width is the trunk's angular size,
  w ~ 2 fx r rho: with r constant, the ratio of two widths of the same trunk is the ratio of
  its depths. A camera driving among the trees therefore learns their depths from the change
  of w, also along its line of sight where the bearings give no parallax, from the first frames
  on, and the inverse depths settle before the map's scale can drift. The IDR pipeline also
  predicts (u, v) as the centre of the base ellipse exactly (`InverseDepthTreeWidth`), while the
  point models predict the image of the base centre, a small model error (tree_width.hpp) that
  the other two pipelines carry until XYZ-R.
- **With only non-occluded trees every pipeline converges less often** than with occlusions
  ignored, unlike the thesis (Sec. 4.4.1 reports better convergence with occlusions considered
  above 2 px): fewer trees are measured per frame, and a tree that reappears from behind a
  trunk is re-observed after a gap. We do not know what in the thesis' simulator made
  occlusion help.
- **One filter noise for every pipeline, then each at its best.** The sweeps first use the
  same filter noise for all three pipelines (1.5 x sigma on u, v and 1 x on w, chosen on
  forest_slam's default forest); the thesis tuned each sensor model's gains first (Sec. 4.2)
  and then swept. The second claims table does the same: each pipeline, "no width" included,
  at the setting that did best on separate tuning maps, on the same measurements. Compare the
  two tables to see which verdicts depend on the setting.
- **Errors are averaged over the converged runs only** (as in the thesis), so a pipeline that
  also converges in the hard runs can show a higher mean error there: the IDR pipeline's E_al
  with only non-occluded trees is the clearest case. Compare pipelines by convergence first.
- **No pipeline is consistent.** In all three the camera-pose NEES averaged over the runs
  leaves its 95% bounds at most steps (the consistency section), and the median NEES of the
  last 10% is far above 6. A mean over runs would mostly measure how many runs diverge, which
  is why the table gives the share of steps inside and the median. Monocular EKF-SLAM is known to become
  overconfident (linearization of the inverse-depth initialization and of the first updates,
  an unobservable scale); the (u, v) model error above adds to it for the point landmarks.
)";

struct ClaimCheck {
  std::string claim;    ///< the thesis' words (paraphrased) and section
  std::string ours;     ///< our numbers
  std::string verdict;  ///< agrees / differs / no clear difference / no data
  std::string id;       ///< name in results.figures.json: <pipeline>.<claim>
  std::map<std::string, std::string> figures;
};

/// The thesis' claims on the paired runs; `tuned`: each pipeline (and "no width") at its own
/// best setting (the "tuned" runs where the tuning changed it), figures named best.<...>.
inline std::vector<ClaimCheck> checkClaims(const StudyData& d, bool tuned = false) {
  std::vector<ClaimCheck> out;
  std::string id_prefix;
  const auto add = [&](const std::string& claim, const std::string& who, const std::string& id,
                       const PairedComparison& c) {
    out.push_back({claim, who + ": " + c.ours, c.verdict, (tuned ? "best." : "") + id_prefix + "." + id, c.figures});
  };
  const auto where = [](const std::string& sweep, const std::string& occlusion, std::function<bool(double)> level) {
    return [=](const PairKey& k) { return k.sweep == sweep && k.occlusion == occlusion && level(k.x); };
  };
  const auto above5 = [](double x) { return x > 5.0; };
  const auto lower = [](double x) { return x < 1.0; };
  const auto all = [](double) { return true; };
  for (const std::string& pipeline : {std::string("after_xyz"), std::string("first_sight")}) {
    const std::string who = pipeline == "after_xyz" ? "thesis pipeline" : "IDR pipeline";
    id_prefix = pipeline == "after_xyz" ? "thesis" : "first_sight";
    add("Sec. 4.3.1, Fig. 4.10: with the width, better convergence above 5 px noise (occlusions ignored)", who,
        "convergence_above_5px", compareConvergence(d.paired, pipeline, where("noise", "ignored", above5), tuned));
    for (const std::string& occlusion : occlusionKeys())
      add(std::string(occlusion == "ignored" ? "Sec. 4.3.2, Fig. 4.12" : "Sec. 4.4.2, Fig. 4.16") +
              ": with the width, better convergence at lower tree densities (" +
              (occlusion == "ignored" ? "occlusions ignored" : "non-occluded trees only") + ")",
          who, "convergence_fewer_trees." + occlusion, compareConvergence(d.paired, pipeline, where("density", occlusion, lower), tuned));
    for (const std::string& occlusion : occlusionKeys())
      add(std::string(occlusion == "ignored" ? "Sec. 4.3.1, Fig. 4.11" : "Sec. 4.4.1, Fig. 4.15") +
              ": with the width, notably lower trajectory error (" +
              (occlusion == "ignored" ? "occlusions ignored" : "non-occluded trees only") + ")",
          who, "trajectory_error." + occlusion, compareTrajectoryError(d.paired, pipeline, where("noise", occlusion, all), tuned));
    add("Sec. 4.4.1, Fig. 4.14: with the width, close to 10% better convergence ratios (non-occluded trees only)",
        who, "convergence_all_noise.non_occluded_only", compareConvergence(d.paired, pipeline, where("noise", "non_occluded_only", all), tuned));
  }
  return out;
}

inline std::string sweepTable(const StudyData& d,
                              const std::string& sweep,
                              const std::string& occlusion) {
  std::ostringstream os;
  os << "| " << (sweep == "noise" ? "sigma (px)" : "density")
     << " | pipeline | runs | converged | E_al (m^2) | E_at (m^2) |\n";
  os << "|---|---|---|---|---|---|\n";
  for (const auto& [k, p] : d.points) {
    if (k.sweep != sweep || k.occlusion != occlusion) continue;
    const auto [el, el_se] = meanAndStandardError(p.el);
    const auto [et, et_se] = meanAndStandardError(p.et);
    os << "| " << fmt(k.x, "%g") << " | " << pipelineTitle(k.pipeline) << " | " << p.runs << " | "
       << fmt(p.ratio(), "%.2f") << " | " << fmt(el, "%.3f") << " ± " << fmt(el_se, "%.3f") << " | "
       << fmt(et, "%.3f") << " ± " << fmt(et_se, "%.3f") << " |\n";
  }
  return os.str();
}

inline std::string gainTable(const StudyData& d, const std::string& occlusion) {
  std::ostringstream os;
  os << "| pipeline | u,v scale | w scale | runs | converged | A_al | A_at "
        "|\n|---|---|---|---|---|---|---|\n";
  for (const auto& [k, p] : d.points) {
    if (k.sweep != "gain" || k.occlusion != occlusion) continue;
    os << "| " << pipelineTitle(k.pipeline) << " | " << fmt(k.x, "%g") << " | "
       << (k.pipeline == "none" ? "-" : fmt(k.width_scale, "%g")) << " | " << p.runs << " | "
       << fmt(p.ratio(), "%.2f") << " | " << fmt(p.A_al(), "%.2f") << " | " << fmt(p.A_at(), "%.2f")
       << " |\n";
  }
  return os.str();
}

inline std::string neesTable(const StudyData& d, double dt_s) {
  std::ostringstream os;
  os << "| pipeline | runs | 95% bounds of one step's mean over the runs | steps inside, first half | "
        "steps inside, last 10% | median NEES, last 10% |\n";
  os << "|---|---|---|---|---|---|\n";
  for (const std::string& pipeline : pipelineKeys()) {
    const auto it = d.nees.find(pipeline);
    if (it == d.nees.end() || it->second.empty()) continue;
    const auto& series = it->second;  // series[step][run]
    const std::size_t n = series.size();
    const std::size_t half = n / 2, tail = n - std::max<std::size_t>(1, n / 10);
    const int runs = static_cast<int>(series.front().size());
    const auto [lo, hi] = sylva::averageChiSquareBounds(6, runs);
    // The statistic the bounds are for: at each step, the mean over the runs (a diverged run,
    // recorded as infinity, puts its step outside).
    int first_inside = 0, first_steps = 0, last_inside = 0, last_steps = 0;
    std::vector<double> last;
    for (std::size_t s = 0; s < n; ++s) {
      double sum = 0.0;
      for (const double v : series[s]) sum += v;
      const double mean = series[s].empty() ? std::nan("") : sum / static_cast<double>(series[s].size());
      const bool inside = mean >= lo && mean <= hi;
      if (s < half) {
        ++first_steps;
        first_inside += inside;
      }
      if (s >= tail) {
        ++last_steps;
        last_inside += inside;
        last.insert(last.end(), series[s].begin(), series[s].end());
      }
    }
    std::sort(last.begin(), last.end());
    const double median = last.empty() ? std::nan("") : last[last.size() / 2];
    const auto share = [](int k, int m) { return m > 0 ? fmt(100.0 * k / m, "%.0f%%") : std::string("-"); };
    os << "| " << pipelineTitle(pipeline) << " | " << runs << " | [" << fmt(lo, "%.2f") << ", " << fmt(hi, "%.2f")
       << "] | " << share(first_inside, first_steps) << " | " << share(last_inside, last_steps) << " | "
       << fmt(median, "%.1f") << " |\n";
  }
  (void)dt_s;
  return os.str();
}

/// Writes docs/results.md. `images` is the figures' path relative to the markdown file.
inline void writeResultsMarkdown(const StudyData& d,
                                 const fs::path& path,
                                 const std::string& images,
                                 const std::string& command,
                                 const std::string& plan_description,
                                 double dt_s,
                                 const TunedSettings& tuning = {}) {
  std::ofstream md(path);
  if (!md)
    sylva::fail(sylva::ErrorCode::kInvalidArgument,
                "tree_width_study: cannot write " + path.string());
  md << "# The tree-width study: the thesis' experiments, reproduced and extended\n\n"
     << "<!-- Generated by examples/tree_width_study (its report step); do not edit by hand. "
        "-->\n\n"
     << "This page reproduces the Monte Carlo study of chapter 4 of B. Turan, *Using shape "
        "information from natural tree "
        "landmarks for improving SLAM performance* (M.S. thesis, Bilkent University, 2012) with "
        "sylva's simulator and filter, "
        "and adds a third pipeline the thesis lists as future work (Ch. 5): a tree parametrization "
        "that carries the radius "
        "from the first observation, so that the width is used from the first frame.\n\n"
     << "Three pipelines see exactly the same measurements in every run:\n\n"
     << "- **no width**: trees are inverse-depth points, then XYZ; only the image position (u, v) "
        "is used;\n"
     << "- **width after XYZ-R (thesis)**: inverse depth, XYZ, then XYZ-R once the position is "
        "known to 0.3 m; from then on "
        "[u, v, w] (`TreeWidth`);\n"
     << "- **width from first sight (IDR)**: trees start as `InverseDepthRadius` [anchor, azimuth, "
        "elevation, rho, kappa = r rho] "
        "and are fused with [u, v, w] from the first frame (`InverseDepthTreeWidth`); they become "
        "XYZ-R when the linearity index "
        "falls below 0.1.\n\n"
     << "**Regenerate.** This page, `docs/study/summary.csv` and the figures come from\n\n```\n"
     << command << "\n```\n\n"
     << "On a cluster, the runs split into shards: GNU parallel runs them on one or several "
        "machines (`scripts/study_parallel.sh`), a Slurm job array runs one per task "
        "(`scripts/study_slurm_submit.sh`), and the merged run file is byte-identical to a "
        "single process's of the same build; [study/cluster.md](study/cluster.md) has the "
        "commands.\n\n"
     << plan_description << "\n\n"
     << "Metrics as in the thesis (Sec. 4.1.2-4.3): e_l, the mean squared error (m^2) of the "
        "Euclidean trees at the end of "
        "lap 1 and e_t, that of the camera positions over lap 2, after the similarity alignment of "
        "eq. 4.1-4.11; a run has "
        "converged when e_l < 10 and e_t < 3; E_al and E_at are means over converged runs (error "
        "bars: standard error); "
        "A_al and A_at (eq. 4.16-4.17) saturate each run's error at -10 and -3 and average over "
        "all runs.\n\n";
  md << "## The thesis' claims and ours\n\n"
     << "Each width pipeline is compared with the no-width pipeline run by run: in a noise or "
        "density run the three pipelines see identical measurements. Convergence: McNemar's exact "
        "test on the runs where exactly one of the two converged, and each convergence ratio with "
        "its Wilson 95% interval. Trajectory error: the Wilcoxon signed-rank test of the paired "
        "differences of e_t over the runs converged in both. A verdict is \"agrees\" or "
        "\"differs\" only when its two-sided test rejects \"no difference\" at 5%, in the "
        "thesis' direction or the opposite one, and \"no clear difference\" otherwise; each "
        "claim is tested on its own (no correction for multiple tests). The e_t test is of the "
        "direction only: where the thesis says \"notably\" lower, the median difference shows "
        "how much. Written by "
        "`paired_claims.hpp` (sylva/consistency/paired_tests.hpp).\n\n"
     << "| thesis | ours | verdict |\n|---|---|---|\n";
  for (const ClaimCheck& c : checkClaims(d))
    md << "| " << c.claim << " | " << c.ours << " | " << c.verdict << " |\n";
  md << "\n### The same claims, each pipeline at its best setting\n\n";
  std::vector<ClaimCheck> best;
  if (tuning.empty()) {
    md << "No tuning was available for this run (docs/study/tuned_settings.json, written by `bash "
          "scripts/run_study.sh tune`), so every pipeline ran the shared setting only.\n\n";
  } else {
    md << "The thesis tunes each sensor model before it sweeps (Sec. 4.2). Here each pipeline's "
          "filter noise and, for the thesis' pipeline, the XYZ-R switching threshold were chosen "
          "per occlusion mode on tuning maps that the sweeps never score "
          "([study/tuning.md](study/tuning.md)); the noise and density sweeps were then run again "
          "with every pipeline whose best setting differs from the shared one, and the claims "
          "tested again on those runs (paired as above; \"no width\" at its own best too).\n\n"
       << "| pipeline | occlusion | setting |\n|---|---|---|\n";
    for (const auto& [key, f] : tuning) {
      const bool ran = d.tuned.count(key) > 0;
      md << "| " << pipelineTitle(key.first) << " | " << key.second << " | " << settingText(f, key.first)
         << (ran ? "" : " (the shared setting)") << " |\n";
    }
    const bool complete = [&] {
      for (const auto& [key, f] : tuning) {
        const FilterSetting shared{StudyPlan{}.pixel_scale, StudyPlan{}.width_scale, Job{}.tree_position_sigma_m};
        if (f != shared && !d.tuned.count(key)) return false;
      }
      return true;
    }();
    if (!complete)
      md << "\n**These runs do not hold every tuned setting's runs** (a tuning newer than the runs?); "
            "the table below is then partly at the shared setting.\n";
    best = checkClaims(d, true);
    md << "\n| thesis | ours, each at its best | verdict |\n|---|---|---|\n";
    for (const ClaimCheck& c : best) md << "| " << c.claim << " | " << c.ours << " | " << c.verdict << " |\n";
  }
  md << "\n" << kDiscussion << "\n";
  // The figures of the claims, for pages that quote them (scripts/docs_figures.py).
  nlohmann::json figures;
  for (const ClaimCheck& c : checkClaims(d))
    for (const auto& [name, value] : c.figures) figures[c.id + "." + name] = value;
  for (const ClaimCheck& c : best)
    for (const auto& [name, value] : c.figures) figures[c.id + "." + name] = value;
  figures["runs"] = std::to_string(d.runs);
  fs::path figures_path = path;
  figures_path.replace_extension(".figures.json");
  std::ofstream(figures_path) << nlohmann::json{{"source", "results"}, {"command", command}, {"figures", figures}}.dump(2)
                              << "\n";
  for (const std::string& sweep : {std::string("noise"), std::string("density")}) {
    md << "## "
       << (sweep == "noise" ? "Dependence on noise (Fig. 4.10-4.11, 4.14-4.15)"
                            : "Dependence on tree density (Fig. 4.12-4.13, 4.16-4.17)")
       << "\n\n";
    for (const std::string& occlusion : occlusionKeys()) {
      md << "### "
         << (occlusion == "ignored" ? "All trees, occlusions ignored" : "Only non-occluded trees")
         << "\n\n";
      md << "![" << sweep << " sweep, " << occlusion << "](" << images << "/study_" << sweep << "_"
         << occlusion << ".svg)\n\n";
      md << sweepTable(d, sweep, occlusion) << "\n";
    }
  }
  md << "## Gain selection (Sec. 4.2, Fig. 4.5-4.8)\n\n"
     << "The thesis tunes diagonal \"gain\" matrices; sylva's equivalent is the filter's "
        "measurement noise, written as a "
        "multiple of the simulated noise (1 px here). Higher A is better (0: perfect).\n\n";
  for (const std::string& occlusion : occlusionKeys()) {
    md << "### "
       << (occlusion == "ignored" ? "All trees, occlusions ignored" : "Only non-occluded trees")
       << "\n\n";
    md << "![gains, " << occlusion << "](" << images << "/study_gain_" << occlusion << ".svg)\n\n"
       << gainTable(d, occlusion) << "\n";
  }
  md << "## Consistency: NEES of the camera pose\n\n"
     << "The filter starts at the true first pose, so its own frame is the world's and the pose "
        "NEES needs no alignment: "
        "e = [t_true - t, 2 vec(q* q_true)] against the covariance of [t, q] mapped through "
        "de/d[t, q]. The mean over the "
        "runs of the noise sweep at its lowest level (only non-occluded trees) should stay inside "
        "the 95% bounds of an "
        "average of N chi-square(6) variables (the figure, step by step).\n\n"
     << "![NEES](" << images << "/study_nees.svg)\n\n"
     << neesTable(d, dt_s) << "\n"
     << "At each step the NEES is averaged over the runs and compared with the 95% bounds of that "
        "statistic, an average of N chi-square(6) variables; a consistent filter has about 95% of "
        "its steps inside. The columns give the share of steps inside over the first half of the "
        "run and over its last 10%. The median over the runs and steps of the last 10% is "
        "descriptive (it has no bound of its own): it shows the typical run, which a few diverging "
        "runs cannot move.\n";
}

}  // namespace tree_width_study
