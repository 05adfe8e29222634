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
// Association, fusion and new landmarks are sylva::slam::FrontEnd's, with these options.
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

#include <sylva/datasets/utias_mrclam.hpp>
#include <sylva/filter/ekf.hpp>
#include <sylva/landmarks/point2.hpp>
#include <sylva/measurements/range_bearing.hpp>
#include <sylva/motion/unicycle_2d.hpp>
#include <sylva/motion/unicycle_2d_with_bias.hpp>
#include <sylva/slam/front_end.hpp>
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
  const sylva::Unicycle2D unicycle;

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
  sylva::slam::FrontEndOptions options;
  options.min_fusion_interval_s = config.landmark_interval_s;
  if (association == Association::kKnown) {
    options.association = sylva::slam::Association::kKnownIds;
    options.known_id_gate_probability = config.outlier_gate_probability;
  } else {
    options.association = sylva::slam::Association::kJcbb;
    options.gate_probability = config.jcbb_gate_probability;
    options.new_landmark_probability = config.new_landmark_probability;
    options.first_new_id = 1000;  // apart from subject numbers
  }
  sylva::slam::FrontEnd<AnyFilter, sylva::RangeBearing, sylva::InverseRangeBearing> front_end(
      sylva::RangeBearing{}, sylva::InverseRangeBearing{}, options,
      sylva::slam::candidatesInReach<sylva::Point2>(
          sylva::RangeBearing{}, {config.candidate_range_m, config.candidate_half_fov_rad, 1e-6}));
  using sylva::slam::Outcome;
  std::vector<sylva::slam::Reading<2>> readings;

  RunResult out;
  const auto& cmds = robot.odometry;
  const auto& obs = robot.landmark_observations;
  out.samples.reserve(cmds.size() + obs.size());
  const double end = max_time_s > 0.0 ? first.time_s + max_time_s : std::numeric_limits<double>::infinity();
  std::size_t i = 0, j = 0;
  std::vector<const UtiasObservation*> group;
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
      readings.clear();
      if (association == Association::kKnown) {
        for (const UtiasObservation* o : group)
          readings.push_back({o->z, config.measurementNoise(o->z[0]), std::nullopt, Id{o->subject}});
      } else {
        // One noise for the image: that of its farthest reading. Association (JCBB's gates
        // and the new-landmark rule) uses jcbb_noise_scale x its sigmas.
        double farthest = 0.0;
        for (const UtiasObservation* o : group) farthest = std::max(farthest, o->z[0]);
        const sylva::Gaussian<2> R = config.measurementNoise(farthest);
        const sylva::Gaussian<2> R_assoc =
            sylva::Gaussian<2>::covariance(R.covariance() * (config.jcbb_noise_scale * config.jcbb_noise_scale));
        for (const UtiasObservation* o : group) readings.push_back({o->z, R, R_assoc});
      }
      const sylva::slam::StepReport& report = front_end.update(ekf, readings, te);
      for (std::size_t k = 0; k < group.size(); ++k) {
        const sylva::slam::ReadingResult& r = report.readings[k];
        const int subject = group[k]->subject;
        switch (r.outcome) {
          case Outcome::kPaired: {
            ++out.counts.paired;
            if (association == Association::kKnown) break;
            const int label = subject_of.at(*r.landmark);
            ++(label == subject ? out.counts.correct : out.counts.wrong);
            if (label != subject && cluster_of != nullptr && cluster_of->count(label) != 0 &&
                cluster_of->count(subject) != 0 && cluster_of->at(label) == cluster_of->at(subject))
              ++out.counts.wrong_same_cluster;
            break;
          }
          case Outcome::kAdded: {
            bool seen = false;
            for (const auto& entry : subject_of) seen = seen || entry.second == subject;
            if (association != Association::kKnown) out.counts.duplicates += seen ? 1 : 0;
            subject_of[*r.landmark] = subject;
            ++out.counts.added;
            break;
          }
          case Outcome::kThinned:
          case Outcome::kRepeated: ++out.counts.thinned; break;
          case Outcome::kGatedOut: ++out.counts.gated_out; break;
          case Outcome::kAmbiguous: ++out.counts.ambiguous; break;
          default: break;
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
