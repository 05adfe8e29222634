// tree_width_study: the Monte Carlo study of the tree-width thesis' chapter 4 (gain
// selection, noise and density sweeps, with occlusions ignored and with only non-occluded
// trees), for three pipelines: no width, width after XYZ-R (the thesis), width from the
// first sight (IDR, beyond the thesis). See docs/results.md for what it found.
//
//   tree_width_study [--quick]                       run every sweep on all cores, write
//                                                    the runs (JSON lines) and the report
//   tree_width_study --shard 2/3 --out part2.jsonl   one shard of the runs, no report
//   tree_width_study merge --out all.jsonl part*.jsonl
//   tree_width_study report all.jsonl                the report from merged runs
//   tree_width_study tune                            each pipeline's best setting, on maps the
//                                                    sweeps never score (docs/study/tuning.md)
//   tree_width_study --resume runs.jsonl             runs only the jobs the file lacks
//
// A run is a pure function of its configuration and the study seed (see study.hpp), so the
// merged shards are byte-identical to a single-process run of the same sweep, whatever the
// thread count.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "report.hpp"
#include "results_md.hpp"
#include "../common/run_pool.hpp"
#include "study.hpp"
#include "tuning.hpp"

#ifndef SYLVA_SOURCE_DIR
#define SYLVA_SOURCE_DIR "."
#endif

namespace {

using namespace tree_width_study;

struct Shard {
  int k = 1, n = 1;
};

Shard parseShard(const std::string& s) {
  Shard shard;
  char slash = 0;
  std::istringstream is(s);
  if (!(is >> shard.k >> slash >> shard.n) || slash != '/' || !is.eof() || shard.n < 1 ||
      shard.k < 1 || shard.k > shard.n)
    throw CLI::ValidationError("--shard", "expected K/N with 1 <= K <= N, got '" + s + "'");
  return shard;
}

std::vector<nlohmann::json> readLines(const std::vector<std::string>& files) {
  std::vector<nlohmann::json> lines;
  for (const std::string& file : files) {
    std::ifstream in(file);
    if (!in) throw std::runtime_error("cannot read " + file);
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
      ++number;
      if (line.empty()) continue;
      try {
        nlohmann::json j = nlohmann::json::parse(line);
        if (!j.contains("job") || !j.contains("sweep") || !j.contains("pipeline") ||
            !j.contains("converged"))
          throw std::runtime_error("missing fields");
        lines.push_back(std::move(j));
      } catch (const std::exception& e) {
        throw std::runtime_error(file + ":" + std::to_string(number) +
                                 ": not a tree_width_study run line (" + e.what() + ")");
      }
    }
  }
  return lines;
}

/// Sorts by job index, refuses duplicates with different content, and warns about gaps.
std::vector<nlohmann::json> mergeLines(std::vector<nlohmann::json> lines) {
  std::sort(lines.begin(), lines.end(), [](const auto& a, const auto& b) {
    return a.at("job").template get<int>() < b.at("job").template get<int>();
  });
  std::vector<nlohmann::json> out;
  for (auto& j : lines) {
    if (!out.empty() && out.back().at("job") == j.at("job")) {
      if (out.back() != j)
        throw std::runtime_error("job " + std::to_string(j.at("job").get<int>()) +
                                 " appears twice with different results");
      continue;
    }
    out.push_back(std::move(j));
  }
  int expected = 0, missing = 0;
  for (const auto& j : out) {
    missing += j.at("job").get<int>() - expected;
    expected = j.at("job").get<int>() + 1;
  }
  if (missing > 0)
    std::cerr << "tree_width_study: warning: " << missing
              << " job indices are missing (a shard not merged?)\n";
  return out;
}

void writeLines(const std::vector<nlohmann::json>& lines, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  for (const auto& j : lines) out << j.dump() << '\n';
}

void writeReport(const std::vector<nlohmann::json>& lines,
                 const fs::path& docs,
                 const std::string& command,
                 const std::string& plan,
                 const TunedSettings& tuning) {
  const fs::path images = docs / "images";
  const fs::path study = docs / "study";
  // gnuplot's scripts (with the data inline) go to a scratch directory, not into docs/.
  const fs::path work = fs::temp_directory_path() / "tree_width_study_plots";
  fs::create_directories(images);
  fs::create_directories(study);
  fs::create_directories(work);
  const StudyData data = aggregate(lines);
  const double dt_s = sylva::sim::TrajectoryOptions{}.dt_s;
  writeCsv(data, study / "summary.csv");
  for (const std::string& occlusion : occlusionKeys()) {
    plotSweep(data, "noise", occlusion, images / ("study_noise_" + occlusion + ".svg"), work);
    plotSweep(data, "density", occlusion, images / ("study_density_" + occlusion + ".svg"), work);
    plotGains(data, occlusion, images / ("study_gain_" + occlusion + ".svg"), work);
  }
  plotNees(data, images / "study_nees.svg", work, dt_s);
  writeResultsMarkdown(data, docs / "results.md", "images", command, plan, dt_s, tuning);
  std::cerr << "tree_width_study: wrote " << (docs / "results.md").string() << ", "
            << (study / "summary.csv").string() << " and " << (images / "study_*.svg").string()
            << " from " << lines.size() << " runs\n";
}

std::string describePlan(const StudyPlan& p, bool quick, std::size_t runs) {
  std::ostringstream os;
  const auto list = [](const std::vector<double>& v) {
    std::ostringstream s;
    for (std::size_t i = 0; i < v.size(); ++i) s << (i ? ", " : "") << v[i];
    return s.str();
  };
  os << "**This run** (" << (quick ? "`--quick`, the reduced sweep" : "the full study")
     << ", study seed " << p.seed << "): " << runs << " runs. Maps: " << p.maps
     << ". Gain grid at 1 px: no width, u,v scale {" << list(p.gain_pixel_scales_no_width)
     << "}; with width, u,v scale {" << list(p.gain_pixel_scales) << "} x w scale {"
     << list(p.gain_width_scales) << "}. Noise sweep: sigma {" << list(p.noise_levels_px)
     << "} px, " << p.noise_draws << " noise draws per map. Density sweep: {" << list(p.densities)
     << "} of each map's trees, " << p.removals << " removals x " << p.density_draws
     << " noise draws per map, " << p.density_noise_px
     << " px. Filter noise in the sweeps: " << p.pixel_scale << " x sigma on u, v and "
     << p.width_scale
     << " x sigma on w (TreeSlamOptions' defaults); then again with each pipeline's own best "
        "setting where it differs (study/tuning.md), with the first "
     << p.tuned_noise_draws << " noise draws per map and level and " << p.tuned_removals << " removals x "
     << p.tuned_density_draws
     << " noise draws per map and density. Each configuration is run with occlusions "
        "ignored and with only non-occluded trees. Built with " __VERSION__
        ": the runs are bit-identical for one build whatever the threads and shards; another "
        "compiler changes the last bits of the numbers (about 1e-15 relative), which can tip a "
        "run at the edge of divergence.";
  if (quick)
    os << " The thesis' full sweep (10 maps, 10 x 10 runs per noise level, 90 per density) is "
          "`tree_width_study` without "
          "`--quick`; with few runs per point the quick figures are noisy.";
  return os.str();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "tree_width_study: the tree-width thesis' Monte Carlo study (Ch. 4) for three pipelines"};
  app.option_defaults()->always_capture_default();  // every option shows its default in --help
  bool quick = false;
  int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::string shard_text = "1/1";
  std::uint64_t seed = 1;
  std::string out_path = "tree_width_study_runs.jsonl";
  std::string docs = std::string(SYLVA_SOURCE_DIR) + "/docs";
  bool no_report = false;
  int nees_every = 10;
  int limit = 0;
  app.add_flag("--quick", quick, "the reduced sweep (under 10 minutes on 2 cores)");
  app.add_option("--threads", threads, "worker threads (default: every core)")
      ->check(CLI::PositiveNumber);
  app.add_option(
         "--shard", shard_text, "run only shard K of N (jobs with index % N == K - 1); no report");
  app.add_option("--seed", seed, "study seed (maps, removals and noise derive from it)");
  app.add_option("--out", out_path, "the runs, one JSON line each, in job order");
  app.add_option(
         "--docs", docs, "where the report goes: results.md, study/summary.csv, images/study_*.svg");
  app.add_flag("--no-report", no_report, "only the runs");
  app.add_option("--nees-every", nees_every, "camera pose NEES every this many frames")
      ->check(CLI::NonNegativeNumber);
  int max_frames = 0;
  app.add_option("--limit",
                 limit,
                 "only the first N runs of the sweep, before sharding (for trying things; 0: all)");
  app.add_option(
         "--frames", max_frames, "stop each run after this many frames (for trying things; 0: all)");

  std::string tuned_path;
  app.add_option("--tuned",
                 tuned_path,
                 "each pipeline's best setting, from `tune` (default: <docs>/study/tuned_settings.json; "
                 "'none': run the shared setting only)");
  std::string resume_path;
  app.add_option("--resume",
                 resume_path,
                 "a run file of the same sweep: keep its runs and run only the jobs it lacks")
      ->check(CLI::ExistingFile);

  bool list_jobs = false;
  app.add_flag("--list", list_jobs, "print how many runs the sweep has, by sweep, setting, pipeline and occlusion, and exit");

  app.fallthrough();  // --docs and friends also after a subcommand
  auto* tune = app.add_subcommand(
      "tune", "choose each pipeline's best setting on tuning maps (writes study/tuned_settings.json, study/tuning.md)");
  std::string tune_out;
  tune->add_option("--out", tune_out, "the tuning runs (default: tree_width_study_tuning.jsonl)");
  std::vector<std::string> tune_inputs;
  tune->add_option("--from", tune_inputs, "choose from these tuning run files instead of running")
      ->check(CLI::ExistingFile);
  auto* merge = app.add_subcommand("merge", "merge shards' run files into one, in job order");
  std::vector<std::string> merge_inputs;
  std::string merge_out;
  merge->add_option("inputs", merge_inputs, "run files of the shards")
      ->required()
      ->check(CLI::ExistingFile);
  merge->add_option("--out", merge_out, "merged run file")->required();

  auto* report =
      app.add_subcommand("report", "write the report (results.md, CSV, figures) from run files");
  std::vector<std::string> report_inputs;
  std::string report_command;
  report->add_option("inputs", report_inputs, "run files (merged, or all shards)")
      ->required()
      ->check(CLI::ExistingFile);
  report->add_option("--command",
                     report_command,
                     "the command to quote in results.md as the way to regenerate it");
  std::string report_plan;
  report
      ->add_option("--plan",
                   report_plan,
                   "the sweep the runs come from, to describe it in results.md (quick or full)")
      ->check(CLI::IsMember({"quick", "full"}));
  CLI11_PARSE(app, argc, argv);

  try {
    if (*merge) {
      const auto lines = mergeLines(readLines(merge_inputs));
      writeLines(lines, merge_out);
      std::cerr << "tree_width_study: merged " << lines.size() << " runs into " << merge_out
                << "\n";
      return 0;
    }
    if (*report) {
      const auto lines = mergeLines(readLines(report_inputs));
      StudyPlan plan = report_plan == "quick" ? StudyPlan::quick() : StudyPlan{};
      plan.seed = seed;
      writeReport(lines,
                  docs,
                  report_command.empty() ? "tree_width_study report <runs.jsonl>" : report_command,
                  report_plan.empty()
                      ? "**This report** covers " + std::to_string(lines.size()) + " runs."
                      : describePlan(plan, report_plan == "quick", lines.size()),
                  tuned_path == "none" ? TunedSettings{}
                                       : readTunedSettings(tuned_path.empty()
                                                               ? (fs::path(docs) / "study" / "tuned_settings.json").string()
                                                               : tuned_path));
      return 0;
    }

    StudyPlan plan = quick ? StudyPlan::quick() : StudyPlan{};
    plan.seed = seed;
    const FilterSetting shared{plan.pixel_scale, plan.width_scale, Job{}.tree_position_sigma_m};
    if (*tune) {
      TuningPlan tplan = quick ? TuningPlan::quick() : TuningPlan{};
      tplan.seed = seed;
      std::vector<nlohmann::json> lines;
      if (!tune_inputs.empty()) {
        lines = mergeLines(readLines(tune_inputs));
      } else {
        const std::vector<Job> jobs = enumerateTuningJobs(tplan, shared);
        std::cerr << "tree_width_study tune: " << jobs.size() << " runs on " << threads << " threads\n";
        lines = sylva_examples::runAll<nlohmann::json>(static_cast<int>(jobs.size()), threads, [&](int i) {
          return runJob(jobs[i], seed, 0, max_frames);
        });
        writeLines(lines, tune_out.empty() ? "tree_width_study_tuning.jsonl" : tune_out);
      }
      std::string command = "bash scripts/run_study.sh tune";
      if (quick) command += " --quick";
      if (seed != 1) command += " --seed " + std::to_string(seed);
      const TuningResult result = scoreTuning(lines);
      const fs::path study_dir = fs::path(docs) / "study";
      fs::create_directories(study_dir);
      writeTunedSettings(result, (study_dir / "tuned_settings.json").string(), command);
      writeTuningMarkdown(result, tplan, shared, (study_dir / "tuning.md").string(), command);
      std::cerr << "tree_width_study tune: wrote " << (study_dir / "tuned_settings.json").string()
                << " and tuning.md from " << lines.size() << " runs\n";
      return 0;
    }

    const Shard shard = parseShard(shard_text);
    if (tuned_path.empty()) tuned_path = (fs::path(docs) / "study" / "tuned_settings.json").string();
    const TunedSettings tuned = tuned_path == "none" ? TunedSettings{} : readTunedSettings(tuned_path);
    if (tuned.empty())
      std::cerr << "tree_width_study: no tuned settings (" << tuned_path
                << "): every pipeline runs the shared setting only\n";
    std::vector<Job> all = enumerateJobs(plan, tuned.empty() ? nullptr : &tuned);
    if (list_jobs) {
      std::map<std::string, int> counts;
      for (const Job& j : all)
        ++counts[j.sweep + " " + j.setting + " " + forest_slam::pipelineName(j.pipeline) + " " +
                 occlusionKey(j.occlusion)];
      for (const auto& [what, n] : counts) std::cout << what << " " << n << "\n";
      return 0;
    }
    if (limit > 0 && static_cast<int>(all.size()) > limit)
      all.resize(static_cast<std::size_t>(limit));
    // --resume: the runs of an earlier (interrupted or shorter) run file are kept when they are
    // the same job; a run is a pure function of its job, so the result is the same file.
    std::map<int, nlohmann::json> kept;
    if (!resume_path.empty())
      for (auto& j : readLines({resume_path})) {
        const int index = j.at("job").get<int>();
        const Job* job = index < static_cast<int>(all.size()) ? &all[static_cast<std::size_t>(index)] : nullptr;
        if (!job || j.at("sweep") != job->sweep || j.at("pipeline") != forest_slam::pipelineName(job->pipeline) ||
            j.at("occlusion") != occlusionKey(job->occlusion) || j.at("map") != job->map ||
            j.at("draw") != job->draw || j.at("removal") != job->removal || j.at("density") != job->density ||
            j.at("pixel_sigma_px") != job->pixel_sigma_px || j.at("pixel_scale") != job->pixel_scale ||
            j.at("width_scale") != job->width_scale)
          throw std::runtime_error(resume_path + ": job " + std::to_string(index) +
                                   " is not the job of this sweep with that index (other flags?)");
        kept[index] = std::move(j);
      }
    std::vector<Job> mine;
    for (const Job& j : all)
      if (j.index % shard.n == shard.k - 1 && !kept.count(j.index)) mine.push_back(j);
    std::cerr << "tree_width_study: " << mine.size() << " of " << all.size() << " runs (shard "
              << shard.k << "/" << shard.n << ") on " << threads << " threads";
    if (!kept.empty()) std::cerr << ", " << kept.size() << " kept from " << resume_path;
    std::cerr << "\n";
    const auto start = std::chrono::steady_clock::now();
    std::vector<nlohmann::json> lines =
        sylva_examples::runAll<nlohmann::json>(static_cast<int>(mine.size()), threads, [&](int i) {
          return runJob(mine[i], seed, nees_every, max_frames);
        });
    if (!kept.empty()) {
      for (auto& [index, j] : kept)
        if (index % shard.n == shard.k - 1) lines.push_back(std::move(j));
      lines = mergeLines(std::move(lines));
    }
    writeLines(lines, out_path);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cerr << "tree_width_study: " << lines.size() << " runs in " << sylva_examples::formatDuration(seconds)
              << ", written to " << out_path << "\n";
    if (!no_report && shard.n == 1 && limit == 0 && max_frames == 0) {
      // The documented way to rerun it (scripts/run_study.sh builds and runs this program).
      std::string command = "bash scripts/run_study.sh";
      if (quick) command += " --quick";
      if (seed != 1) command += " --seed " + std::to_string(seed);
      writeReport(lines,
                  docs,
                  command,
                  describePlan(plan, quick, lines.size()),
                  tuned);
    }
  } catch (const std::exception& e) {
    std::cerr << "tree_width_study: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
