#pragma once
// One EKF-SLAM run over one robot's data: sylva::Ekf<Unicycle2D, Point2> with RangeBearing
// and InverseRangeBearing, stepped from event to event; with online gains (NoiseConfig::
// online_gains) sylva::Ekf<Unicycle2DWithBias, Point2>, whose speed gain, turn-rate gain and
// turn-rate bias are states.
//
// Events are the odometry commands and the measurement times, merged in time order. A
// command logged at time t takes effect at t + command_delay_s (the robots follow their
// commands about 0.2 s late; see noise_model.hpp). Between
// two events the filter predicts with the latest command (zero before the first one) and the
// control noise of NoiseConfig; at a command it takes the new command; at a measurement time
// it fuses all landmark observations of that time in one batched update. The filter starts
// at the first Vicon sample with covariance diag(initial_sigma^2), so its frame is the Vicon
// frame up to that small uncertainty. Observations of the other robots are not used, and
// neither are the misread barcodes (the loader keeps both out of landmark_observations).
//
// Known correspondences: the barcode names the landmark. An observation of a mapped landmark
// whose NIS exceeds the chi-square gate (outlier_gate_probability, 2 dof) is rejected as an
// outlier; the first observation of a landmark adds it (a second one in the same image is
// not fused). With landmark_interval_s > 0 a landmark is fused at most once per interval.
//
// Unknown correspondences (JCBB): the barcodes are not used for pairing. Candidates are the
// mapped landmarks whose predicted reading lies within candidate_range_m and
// candidate_half_fov_rad; associateJcbb pairs the observations of one time with them, with
// jcbb_noise_scale x the measurement sigmas (the update uses the full sigmas). The
// declared rule for new landmarks: an unpaired observation becomes a new landmark when its
// NIS to every candidate exceeds the chi-square quantile new_landmark_probability (2 dof);
// otherwise it is ambiguous and dropped. The barcodes are kept only to score the pairings:
// a landmark is labelled with the barcode's subject of the observation that created it.

#include <algorithm>
#include <chrono>
#include <limits>
#include <map>
#include <optional>
#include <type_traits>
#include <vector>

#include <sylva/association/jcbb.hpp>
#include <sylva/association/smallest_nis.hpp>
#include <sylva/consistency/chi_square.hpp>
#include <sylva/datasets/utias_mrclam.hpp>
#include <sylva/filter/ekf.hpp>
#include <sylva/landmarks/point2.hpp>
#include <sylva/measurements/range_bearing.hpp>
#include <sylva/motion/unicycle_2d.hpp>
#include <sylva/motion/unicycle_2d_with_bias.hpp>
#include <sylva/slam/reach.hpp>

#include "noise_model.hpp"

namespace utias {

using sylva::Id;
using sylva::Mat;
using Filter = sylva::Ekf<sylva::Unicycle2D, sylva::Point2>;
using GainFilter = sylva::Ekf<sylva::Unicycle2DWithBias, sylva::Point2>;

enum class Association { kKnown, kJcbb };

/// The filter's estimate just after one event.
struct Sample {
  double time_s;
  Vec<3> pose;
  Mat<3, 3> covariance;
};

struct MappedLandmark {
  Id id;
  int subject;  ///< known: the barcode's subject; JCBB: that of the observation that created it
  Vec<2> mean;
  Mat<2, 2> covariance;
};

struct AssociationCounts {
  long observations = 0;  ///< landmark observations offered to the filter
  long gated_out = 0;     ///< known ids: rejected by the outlier gate
  long paired = 0;        ///< fused into a mapped landmark
  long correct = 0;       ///< JCBB: paired with a landmark of the same subject
  long wrong = 0;         ///< JCBB: paired with a landmark of another subject
  long wrong_same_cluster = 0;  ///< JCBB: of the wrong ones, with a landmark of the same cluster (given clusters)
  long added = 0;         ///< new landmarks
  long duplicates = 0;    ///< JCBB: new landmark of a subject already mapped
  long ambiguous = 0;     ///< JCBB: unpaired but too close to a candidate to add
  long thinned = 0;       ///< not fused: the landmark was fused less than landmark_interval_s before
};

struct RunResult {
  std::vector<Sample> samples;
  std::vector<Vec<3>> dead_reckoning;  ///< commands integrated from the start, at each sample
  std::vector<MappedLandmark> landmarks;
  AssociationCounts counts;
  double runtime_s = 0.0;
  bool online_gains = false;
  Vec<3> gains = Vec<3>::Zero();        ///< online gains: [k_v, k_w, b_w] at the end
  Vec<3> gain_sigmas = Vec<3>::Zero();  ///< ... and their sigmas
};

namespace detail {

/// Mapped landmarks whose predicted reading is within the configured reach (JCBB candidates).
template <typename AnyFilter>
std::vector<Id> candidates(const AnyFilter& ekf, const NoiseConfig& c) {
  return sylva::slam::landmarksInReach<sylva::Point2>(ekf, sylva::RangeBearing{},
                                                      {c.candidate_range_m, c.candidate_half_fov_rad, 1e-6});
}

}  // namespace detail

/// runSlam (below) with the filter type chosen.
template <typename AnyFilter>
RunResult runSlamWith(const sylva::datasets::UtiasRobotData& robot,
                      const NoiseConfig& config,
                      Association association,
                      double max_time_s,
                      const std::map<int, int>* cluster_of) {
  constexpr bool kOnline = std::is_same_v<AnyFilter, GainFilter>;
  using sylva::datasets::UtiasObservation;
  const auto start_clock = std::chrono::steady_clock::now();
  const sylva::RangeBearing model;
  const sylva::InverseRangeBearing inverse;
  const sylva::Unicycle2D unicycle;
  const double outlier_gate = sylva::chiSquareGate(2, config.outlier_gate_probability);
  const double new_gate = sylva::chiSquareGate(2, config.new_landmark_probability);

  const auto& first = robot.groundtruth.front();
  const Mat<3, 3> P0 = config.initial_sigma.cwiseAbs2().asDiagonal();
  const auto initialFilter = [&] {
    if constexpr (kOnline) {
      Vec<6> x0;
      x0 << first.pose, config.gainPrior();
      Mat<6, 6> P = Mat<6, 6>::Zero();
      P.topLeftCorner<3, 3>() = P0;
      P.bottomRightCorner<3, 3>() = config.gain_sigma.cwiseAbs2().asDiagonal();
      return AnyFilter(x0, P);
    } else {
      return AnyFilter(first.pose, P0);
    }
  };
  AnyFilter ekf = initialFilter();
  ekf.reserve(2 * 32);
  Vec<3> dead = first.pose;
  double t = first.time_s;
  Vec<2> u = Vec<2>::Zero();       // the command the filter predicts with
  Vec<2> u_dead = Vec<2>::Zero();  // the calibrated command of the dead reckoning
  Vec<2> jitter = Vec<2>::Zero();  // pending pose effect of command changes (see command_jitter_s)
  std::map<Id, int> subject_of;  // filter id -> label subject
  std::map<Id, double> last_fused;  // filter id -> time of its last fused reading
  auto due = [&](Id id, double now) {
    const auto it = last_fused.find(id);
    return it == last_fused.end() || now - it->second >= config.landmark_interval_s - 1e-9;
  };
  Id next_id = 1000;             // JCBB ids, apart from subject numbers

  RunResult out;
  const auto& cmds = robot.odometry;
  const auto& obs = robot.landmark_observations;
  out.samples.reserve(cmds.size() + obs.size());
  const double end = max_time_s > 0.0 ? first.time_s + max_time_s : std::numeric_limits<double>::infinity();
  std::size_t i = 0, j = 0;
  std::vector<sylva::Observation<sylva::RangeBearing>> paired;
  std::vector<const UtiasObservation*> group;
  std::vector<Vec<2>> z;
  while (i < cmds.size() || j < obs.size()) {
    const double delay = config.command_delay_s;
    const bool command = j == obs.size() || (i < cmds.size() && cmds[i].time_s + delay <= obs[j].time_s);
    const double te = command ? cmds[i].time_s + delay : obs[j].time_s;
    if (te > end) break;
    if (te > t) {
      sylva::Gaussian<2> Q = config.controlNoise(u, te - t);
      if (jitter.squaredNorm() > 0.0) {
        // The last command change happened at an uncertain time: its effect on the pose is
        // |delta u| x command_jitter_s, put on this step's control noise.
        const double dt = te - t;
        Q = sylva::Gaussian<2>::variances(Q.covariance().diagonal() + jitter.cwiseAbs2() / (dt * dt));
        jitter.setZero();
      }
      if constexpr (kOnline) {
        // The gains are random walks of density gain_walk: Var(e) = q / dt (Unicycle2DWithBias).
        Vec<5> variances;
        variances << Q.covariance().diagonal(), config.gain_walk.cwiseAbs2() / (te - t);
        ekf.predict(u, te - t, sylva::Gaussian<5>::variances(variances));
      } else {
        ekf.predict(u, te - t, Q);
      }
      dead = unicycle(dead, u_dead, te - t);
      t = te;
    }
    if (command) {
      const Vec<2> logged = cmds[i++].u;
      u_dead = config.effectiveCommand(logged);
      const Vec<2> next = kOnline ? config.filterCommand(logged) : u_dead;
      jitter += (next - u).cwiseAbs() * config.command_jitter_s;
      u = next;
    } else {
      group.clear();
      while (j < obs.size() && obs[j].time_s == te) group.push_back(&obs[j++]);
      out.counts.observations += static_cast<long>(group.size());
      paired.clear();
      if (association == Association::kKnown) {
        std::vector<const UtiasObservation*> fresh;
        for (const UtiasObservation* o : group) {
          const Id id = o->subject;
          const sylva::Gaussian<2> R = config.measurementNoise(o->z[0]);
          if (!ekf.contains(id)) {
            fresh.push_back(o);
          } else if (!due(id, te)) {
            ++out.counts.thinned;
          } else if (ekf.innovation(model, id, o->z, R).nis() > outlier_gate) {
            ++out.counts.gated_out;
          } else {
            paired.push_back({id, o->z, R});
          }
        }
        ekf.update(model, paired);
        for (const auto& p : paired) last_fused[p.id] = te;
        out.counts.paired += static_cast<long>(paired.size());
        for (const UtiasObservation* o : fresh) {
          const sylva::Gaussian<2> R = config.measurementNoise(o->z[0]);
          if (ekf.contains(o->subject)) {  // seen twice in one image: the first one is enough
            ++out.counts.thinned;
            continue;
          }
          ekf.add(o->subject, inverse, o->z, R);
          last_fused[o->subject] = te;
          subject_of[o->subject] = o->subject;
          ++out.counts.added;
        }
      } else {
        z.clear();
        double farthest = 0.0;
        for (const UtiasObservation* o : group) {
          z.push_back(o->z);
          farthest = std::max(farthest, o->z[0]);
        }
        // associateJcbb takes one noise for the image: that of its farthest reading.
        const sylva::Gaussian<2> R = config.measurementNoise(farthest);
        // Association (JCBB's gates and the new-landmark rule) may use a smaller noise than
        // the fusion: jcbb_noise_scale x the sigmas.
        const sylva::Gaussian<2> R_assoc = sylva::Gaussian<2>::covariance(R.covariance() * (config.jcbb_noise_scale * config.jcbb_noise_scale));
        const std::vector<Id> cands = detail::candidates(ekf, config);
        const std::vector<std::optional<Id>> pairing =
            sylva::associateJcbb(ekf, model, z, R_assoc, cands, config.jcbb_gate_probability);
        std::vector<std::size_t> to_add;
        for (std::size_t k = 0; k < group.size(); ++k) {
          if (pairing[k]) {
            if (!due(*pairing[k], te)) {
              ++out.counts.thinned;
              continue;
            }
            paired.push_back({*pairing[k], z[k], R});
            ++out.counts.paired;
            const int label = subject_of.at(*pairing[k]);
            ++(label == group[k]->subject ? out.counts.correct : out.counts.wrong);
            if (label != group[k]->subject && cluster_of != nullptr && cluster_of->count(label) != 0 &&
                cluster_of->count(group[k]->subject) != 0 && cluster_of->at(label) == cluster_of->at(group[k]->subject))
              ++out.counts.wrong_same_cluster;
            continue;
          }
          if (sylva::smallestNis(ekf, model, z[k], R_assoc, cands) > new_gate)
            to_add.push_back(k);
          else
            ++out.counts.ambiguous;
        }
        ekf.update(model, paired);
        for (const auto& p : paired) last_fused[p.id] = te;
        for (const std::size_t k : to_add) {
          bool seen = false;
          for (const auto& entry : subject_of) seen = seen || entry.second == group[k]->subject;
          out.counts.duplicates += seen ? 1 : 0;
          const Id id = next_id++;
          ekf.add(id, inverse, z[k], R);
          last_fused[id] = te;
          subject_of[id] = group[k]->subject;
          ++out.counts.added;
        }
      }
    }
    out.samples.push_back({t, ekf.robotMean().template head<3>(), ekf.robotCovariance().template topLeftCorner<3, 3>()});
    out.dead_reckoning.push_back(dead);
  }
  for (const sylva::LandmarkSlot& s : ekf.slots())
    out.landmarks.push_back({s.id, subject_of.at(s.id), ekf.template landmarkMean<sylva::Point2>(s.id),
                             ekf.template landmarkCovariance<sylva::Point2>(s.id)});
  if constexpr (kOnline) {
    out.online_gains = true;
    out.gains = ekf.robotMean().template tail<3>();
    out.gain_sigmas = ekf.robotCovariance().template bottomRightCorner<3, 3>().diagonal().cwiseSqrt();
  }
  out.runtime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_clock).count();
  return out;
}

/// Runs the filter over `robot`'s data up to `max_time_s` (relative time; <= 0: all), with
/// the fixed calibration or, when config.online_gains, the gains as states. `cluster_of`
/// (subject -> cluster), when given, is used only to count JCBB's wrong pairings that stay
/// inside a cluster of landmarks.
inline RunResult runSlam(const sylva::datasets::UtiasRobotData& robot,
                         const NoiseConfig& config,
                         Association association,
                         double max_time_s = 0.0,
                         const std::map<int, int>* cluster_of = nullptr) {
  return config.online_gains ? runSlamWith<GainFilter>(robot, config, association, max_time_s, cluster_of)
                             : runSlamWith<Filter>(robot, config, association, max_time_s, cluster_of);
}

}  // namespace utias
