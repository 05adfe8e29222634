#pragma once
// Scores of one run against the Vicon ground truth. The trajectory is compared at every
// sample of the run (the filter's estimate just after each event, ~80 Hz), with the ground
// truth interpolated to the sample's time.
//
//   rmse_m           RMS position error in the Vicon frame (the filter starts at the first
//                    Vicon pose, so its frame is the Vicon frame);
//   aligned_rmse_m   RMS position error after the rigid 2D transform T that best maps the
//                    estimated landmarks onto their true positions (a SLAM map is only
//                    defined up to T); each estimated landmark is matched to the truth of its
//                    label subject (see slam_run.hpp);
//   landmark_aligned_rmse_m  RMS of |T(l_est) - l_true| over the mapped landmarks;
//   nees_mean        mean over the samples of the 3-dof pose NEES e^T P^-1 e (eq. 2.43),
//                    e = Unicycle2D::difference(x_true, x_est), in the Vicon frame.
//
// Only samples whose time the ground truth covers (GroundTruth::covers: within its span, not
// in a gap longer than its largest gap) are scored; `samples_scored` counts them, and when
// the truth ends before the run does, `truthEndsEarly()` says so and `last_scored_s` is the
// time of the last scored sample (the program prints a note). The landmark scores use the
// final map: the landmarks' truth does not end.

#include <cmath>
#include <map>
#include <vector>

#include <sylva/consistency/nees.hpp>
#include <sylva/datasets/utias_mrclam.hpp>
#include <sylva/motion/unicycle_2d.hpp>

#include "ground_truth.hpp"
#include <sylva/eval/rigid_2d.hpp>
#include "slam_run.hpp"

namespace utias {

struct Scores {
  double rmse_m = 0.0;
  double aligned_rmse_m = 0.0;
  double landmark_aligned_rmse_m = 0.0;
  double landmark_rmse_m = 0.0;  ///< Vicon frame, no alignment
  double nees_mean = 0.0;
  double final_error_m = 0.0;
  double dead_reckoning_rmse_m = 0.0;
  double alignment_angle_rad = 0.0;
  Vec<2> alignment_translation_m = Vec<2>::Zero();
  int landmarks_mapped = 0;
  int subjects_mapped = 0;  ///< distinct true landmarks among them
  long samples = 0;         ///< samples of the run
  long samples_scored = 0;  ///< of them, covered by the ground truth (the trajectory scores use these)
  long samples_after_truth = 0;  ///< of them, after the truth's last sample
  double run_end_s = 0.0;      ///< time of the run's last sample
  double truth_end_s = 0.0;    ///< time of the last ground-truth sample
  double last_scored_s = 0.0;  ///< time of the last scored sample
  sylva::eval::Rigid2 alignment;

  double truth_max_gap_s = 0.0;  ///< GroundTruth::maxGap() of the truth scored against

  /// The ground truth stops more than its largest gap (1 s) before the run's last sample: the
  /// trajectory is scored until then. (A shorter tail, such as the last command's 0.2 s delay
  /// after the truth's last sample in Dataset 7, is left out of the scores without a note.)
  bool truthEndsEarly() const { return samples > 0 && run_end_s - truth_end_s > truth_max_gap_s; }
  /// Samples left out inside the truth's span (gaps longer than GroundTruth::maxGap()).
  long samplesInGaps() const { return samples - samples_scored - samples_after_truth; }
};

inline Scores score(const RunResult& run,
                    const GroundTruth& gt,
                    const std::vector<sylva::datasets::UtiasLandmark>& truth) {
  Scores s;
  std::map<int, Vec<2>> true_of;
  for (const auto& l : truth) true_of[l.subject] = l.position_m;
  std::vector<Vec<2>> est, tru;
  std::map<int, int> subjects;
  double lm_raw = 0.0;
  for (const auto& l : run.landmarks) {
    const auto it = true_of.find(l.subject);
    if (it == true_of.end()) continue;
    est.push_back(l.mean);
    tru.push_back(it->second);
    ++subjects[l.subject];
    lm_raw += (l.mean - it->second).squaredNorm();
  }
  s.landmarks_mapped = static_cast<int>(run.landmarks.size());
  s.subjects_mapped = static_cast<int>(subjects.size());
  if (est.size() >= 2) s.alignment = sylva::eval::alignRigid2(est, tru);
  s.alignment_angle_rad = s.alignment.angle();
  s.alignment_translation_m = s.alignment.translation;
  double lm = 0.0;
  for (std::size_t k = 0; k < est.size(); ++k) lm += (s.alignment(est[k]) - tru[k]).squaredNorm();
  if (!est.empty()) {
    s.landmark_aligned_rmse_m = std::sqrt(lm / static_cast<double>(est.size()));
    s.landmark_rmse_m = std::sqrt(lm_raw / static_cast<double>(est.size()));
  }

  double e2 = 0.0, a2 = 0.0, d2 = 0.0, nees_sum = 0.0;
  const Sample* last = nullptr;
  s.truth_end_s = gt.end();
  s.truth_max_gap_s = gt.maxGap();
  for (std::size_t k = 0; k < run.samples.size(); ++k) {
    const Sample& smp = run.samples[k];
    if (!gt.covers(smp.time_s)) {
      s.samples_after_truth += smp.time_s > gt.end() ? 1 : 0;
      continue;
    }
    const Vec<3> x = gt.at(smp.time_s);
    e2 += (smp.pose.head<2>() - x.head<2>()).squaredNorm();
    a2 += (s.alignment(smp.pose.head<2>()) - x.head<2>()).squaredNorm();
    d2 += (run.dead_reckoning[k].head<2>() - x.head<2>()).squaredNorm();
    nees_sum += sylva::nees(sylva::Unicycle2D::difference(x, smp.pose), smp.covariance);
    ++s.samples_scored;
    last = &smp;
  }
  s.samples = static_cast<long>(run.samples.size());
  if (s.samples > 0) s.run_end_s = run.samples.back().time_s;
  if (last != nullptr) {
    const double n = static_cast<double>(s.samples_scored);
    s.rmse_m = std::sqrt(e2 / n);
    s.aligned_rmse_m = std::sqrt(a2 / n);
    s.dead_reckoning_rmse_m = std::sqrt(d2 / n);
    s.nees_mean = nees_sum / n;
    s.last_scored_s = last->time_s;
    s.final_error_m = (last->pose.head<2>() - gt.at(last->time_s).head<2>()).norm();
  }
  return s;
}

}  // namespace utias
