#pragma once
/// @file
/// `sylva::slam::FrontEnd`: the SLAM step for a sensor that sees point-like landmarks, so that
/// a program keeps only its data, its world and its pictures. One `update(ekf, readings, t)`
/// after the caller's prediction (`step` does both):
///
///   1. Candidates: the mapped landmarks the sensor may have seen. By default every landmark
///      of the model's type; `candidatesInReach` (reach.hpp) keeps those a planar
///      range-bearing sensor can see, or pass any callable.
///   2. Association of the readings with the candidates (`Association`):
///        kKnownIds         each reading names its landmark (`Reading::id`);
///        kNearestNeighbor  `associateNearestNeighbor`, chi-square gate `gate_probability`;
///        kJcbb             `associateJcbb`, the same gate;
///      each reading with its own gate noise (its fusion noise unless it gives one).
///      Known ids may pass an outlier gate (`known_id_gate_probability`). A landmark fused
///      less than `min_fusion_interval_s` ago is not fused again (kThinned).
///   3. Fusion of the paired readings: one batched update, or one update per reading
///      (`fusion`). If the filter refuses the batch, the readings are fused one at a time and
///      those it refuses are reported with its reason (`fallback_to_sequential`).
///   4. New landmarks, at the updated estimate.
///      - Known ids: the first reading of an id that is not mapped starts it (a second
///        reading of it in the same step is kRepeated).
///      - NN and JCBB: a reading that paired with nothing is a new landmark only when its
///        NIS to every candidate, at the predicted estimate, exceeds
///        chi2(dim, new_landmark_probability); otherwise it is kAmbiguous and dropped. A new
///        landmark starts at once (`NewLandmarks::kImmediate`), or feeds a tentative track
///        that becomes a landmark after `confirm_sightings` steps (`kTentative`, see
///        `TentativeTracks`). New ids count up from `first_new_id`, skipping mapped ones.
///   5. Removal of landmarks that stay unconfirmed (`UnconfirmedRemoval`, off by default).
///
/// The `StepReport` says what happened to every reading (paired, added, ambiguous, refused
/// with the filter's reason, ...), which landmarks were removed, and how long each phase
/// took. Expected failures are values in the report, not exceptions: a reading that is not
/// finite, that the filter refuses to fuse or to initialize (a degenerate sighting), or a
/// known-id reading without an id. `update` throws only for a bad time or when the
/// association itself fails (say, an innovation covariance that is not positive definite);
/// it has then changed nothing. The options are checked when the front end is built.
///
/// Bookkeeping: the front end remembers, per landmark it started, when it was created, when
/// it was last fused and how many readings it has taken (`sightings`). Landmarks the caller
/// adds itself are fused like any other, and never removed as unconfirmed.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "sylva/association/compatibility_table.hpp"
#include "sylva/association/jcbb.hpp"
#include "sylva/association/nearest_neighbor.hpp"
#include "sylva/consistency/chi_square.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"
#include "sylva/detail/model_traits.hpp"
#include "sylva/filter/ekf.hpp"
#include "sylva/noise/gaussian.hpp"

namespace sylva::slam {

/// How readings find their landmarks (see the file comment, step 2).
enum class Association { kKnownIds, kNearestNeighbor, kJcbb };

/// When an unpaired reading becomes a landmark (step 4).
enum class NewLandmarks {
  kImmediate,  ///< at once, from this reading
  kTentative,  ///< after `TentativeTracks::confirm_sightings` steps of a tentative track
};

/// Tentative tracks: a reading that would start a landmark is placed in the world with the
/// inverse model at the updated estimate. It feeds the nearest track within `radius_m` that
/// no reading of this step has fed yet (distance between the landmarks' planar positions),
/// or starts a track. A track fed in `confirm_sightings` steps becomes a landmark,
/// initialized from its latest reading; a track not fed for more than `timeout_s` is
/// dropped. Needs a landmark with a planar position (`Landmark::kPlanarPosition`).
struct TentativeTracks {
  int confirm_sightings = 3;
  double radius_m = 1.0;
  double timeout_s = 2.0;
};

/// A landmark the front end started is removed when, more than `within_s` after it was
/// started, it has taken fewer than `min_sightings` readings (the first one included).
/// `min_sightings = 0` (the default) never removes.
struct UnconfirmedRemoval {
  int min_sightings = 0;
  double within_s = 0.0;
};

struct FrontEndOptions {
  Association association = Association::kJcbb;
  double gate_probability = 0.99;             ///< NN and JCBB gates, chi-square probability
  double new_landmark_probability = 0.9999;   ///< NN and JCBB: the new-landmark test
  /// Known ids: a reading whose NIS exceeds chi2(dim, p) is rejected as an outlier. Unset:
  /// no gate.
  std::optional<double> known_id_gate_probability;
  /// Known ids: put each paired reading's NIS (at the predicted estimate) in the report, for
  /// consistency statistics. Costs one more linearization per reading.
  bool report_nis = false;
  double min_fusion_interval_s = 0.0;  ///< fuse a landmark at most once per interval (0: always)
  Fusion fusion = Fusion::kBatched;
  bool fallback_to_sequential = true;  ///< a refused batch is fused one reading at a time
  NewLandmarks new_landmarks = NewLandmarks::kImmediate;
  TentativeTracks tentative;
  UnconfirmedRemoval unconfirmed;
  Id first_new_id = 0;  ///< NN and JCBB: ids of new landmarks start here
};

/// One reading of the sensor at the step's time.
template <int M>
struct Reading {
  Reading(const Vec<M>& z_, const Gaussian<M>& noise_, std::optional<Gaussian<M>> gate_noise_ = std::nullopt,
          std::optional<Id> id_ = std::nullopt)
      : z(z_), noise(noise_), gate_noise(std::move(gate_noise_)), id(id_) {}

  Vec<M> z;
  Gaussian<M> noise;                      ///< fuses and initializes with this
  std::optional<Gaussian<M>> gate_noise;  ///< associates with this (default: `noise`)
  std::optional<Id> id;                   ///< kKnownIds: the landmark it is a reading of

  const Gaussian<M>& gateNoise() const { return gate_noise ? *gate_noise : noise; }
};

/// What happened to one reading.
enum class Outcome : std::uint8_t {
  kPaired,     ///< fused into `landmark`
  kAdded,      ///< started `landmark`
  kTentative,  ///< fed or started a tentative track
  kAmbiguous,  ///< paired with nothing, but too close to a candidate to start a landmark
  kGatedOut,   ///< known id: its NIS exceeds the outlier gate
  kThinned,    ///< paired with `landmark`, which was fused less than min_fusion_interval_s ago
  kRepeated,   ///< known id: a second reading of a landmark this step started
  kRefused,    ///< not used: `error` and `why` say why (the filter's reason, or the input's)
};

inline const char* toString(Outcome outcome) {
  switch (outcome) {
    case Outcome::kPaired: return "paired";
    case Outcome::kAdded: return "added";
    case Outcome::kTentative: return "tentative";
    case Outcome::kAmbiguous: return "ambiguous";
    case Outcome::kGatedOut: return "gated out";
    case Outcome::kThinned: return "thinned";
    case Outcome::kRepeated: return "repeated";
    case Outcome::kRefused: return "refused";
  }
  return "unknown";
}

struct ReadingResult {
  Outcome outcome = Outcome::kRefused;
  std::optional<Id> landmark;  ///< the landmark it was paired with or started
  /// NN and JCBB, unpaired readings: the smallest NIS over the candidates (+inf for none);
  /// known ids with an outlier gate or `report_nis`: its NIS. NaN otherwise.
  double nis = std::numeric_limits<double>::quiet_NaN();
  std::optional<ErrorCode> error;  ///< kRefused
  std::string why;                 ///< kRefused: the message
};

struct StepReport {
  std::vector<ReadingResult> readings;  ///< one per reading, in the order given
  std::vector<Id> removed;              ///< unconfirmed landmarks removed in this step
  int candidates = 0;                   ///< candidates offered to NN or JCBB
  int tentative_tracks = 0;             ///< live tentative tracks after the step
  std::optional<std::string> batch_refused;  ///< why the filter refused the batch (then fused one by one)
  struct Seconds {
    double association = 0.0;  ///< candidates, association and the new-landmark test
    double fusion = 0.0;
    double mapping = 0.0;  ///< new landmarks, tentative tracks, removal
    double total = 0.0;
  } seconds;

  int count(Outcome outcome) const {
    int n = 0;
    for (const ReadingResult& r : readings) n += r.outcome == outcome ? 1 : 0;
    return n;
  }
};

template <typename Filter, typename Model, typename Inverse>
class FrontEnd {
 public:
  static constexpr int kDim = Model::kDim;
  using Landmark = typename Model::Landmark;
  using ReadingType = Reading<kDim>;
  using Lin = Linearization<Model, Filter::kRobotDim>;
  /// Fills the list of candidate ids (step 1).
  using Candidates = std::function<void(const Filter&, std::vector<Id>&)>;

  static_assert(std::is_same_v<Landmark, typename Inverse::Landmark>,
                "FrontEnd: the model and the inverse model must be of the same landmark type");
  static_assert(Inverse::kMeasurementDim == kDim, "FrontEnd: the inverse model reads another measurement");
  static_assert(Filter::template kHolds<Landmark>, "FrontEnd: the model's landmark is not in the filter");

  /// Throws kInvalidArgument for options out of range (probabilities outside (0, 1), a
  /// negative interval, radius or timeout, confirm_sightings < 1, tentative tracks for a
  /// landmark without a planar position).
  explicit FrontEnd(Model model, Inverse inverse, FrontEndOptions options = {}, Candidates candidates = {})
      : model_(std::move(model)),
        inverse_(std::move(inverse)),
        options_(std::move(options)),
        candidates_(std::move(candidates)),
        next_id_(options_.first_new_id) {
    checkOptions();
    new_gate_ = chiSquareGate(kDim, options_.new_landmark_probability);
    if (options_.known_id_gate_probability) known_gate_ = chiSquareGate(kDim, *options_.known_id_gate_probability);
  }

  const FrontEndOptions& options() const { return options_; }
  const Model& model() const { return model_; }
  const StepReport& lastReport() const { return report_; }
  int tentativeTracks() const { return static_cast<int>(tracks_.size()); }

  /// Readings the landmark has taken through this front end, the first one included (0 for a
  /// landmark it does not know).
  int sightings(Id id) const {
    const auto it = records_.find(id);
    return it == records_.end() ? 0 : it->second.sightings;
  }

  /// Predicts with `u` over `dt`, then `update`.
  const StepReport& step(Filter& ekf,
                         const typename Filter::Control& u,
                         double dt,
                         const Gaussian<Filter::kNoiseDim>& process_noise,
                         const std::vector<ReadingType>& readings,
                         double time_s) {
    ekf.predict(u, dt, process_noise);
    return update(ekf, readings, time_s);
  }

  /// Steps 1-5 of the file comment for the readings of one time. Throws kInvalidArgument for
  /// a time that is not finite or earlier than the last one.
  const StepReport& update(Filter& ekf, const std::vector<ReadingType>& readings, double time_s) {
    using Clock = std::chrono::steady_clock;
    if (!std::isfinite(time_s) || time_s < last_time_) {
      std::ostringstream os;
      os << "slam::FrontEnd::update: time " << time_s << " s is not finite or earlier than the last step's ("
         << last_time_ << " s)";
      fail(ErrorCode::kInvalidArgument, os.str());
    }
    const auto begin = Clock::now();
    report_.readings.assign(readings.size(), ReadingResult{});
    report_.removed.clear();
    report_.candidates = 0;
    report_.batch_refused.reset();
    valid_.clear();
    for (std::size_t i = 0; i < readings.size(); ++i) {
      if (!readings[i].z.allFinite()) {
        refuse(i, ErrorCode::kNonFinite, "the reading is not finite");
      } else if (options_.association == Association::kKnownIds && !readings[i].id) {
        refuse(i, ErrorCode::kInvalidArgument, "known-id association needs the reading's id");
      } else {
        valid_.push_back(i);
      }
    }

    paired_.clear();
    paired_lins_.clear();
    paired_index_.clear();
    fresh_.clear();
    if (options_.association == Association::kKnownIds)
      associateKnown(ekf, readings, time_s);
    else
      associateUnknown(ekf, readings, time_s);
    const auto associated = Clock::now();

    fuse(ekf, time_s);
    const auto fused = Clock::now();

    if (options_.association == Association::kKnownIds) {
      for (const std::size_t i : fresh_) {
        const Id id = *readings[i].id;
        if (ekf.contains(id)) {
          report_.readings[i].outcome = Outcome::kRepeated;
          report_.readings[i].landmark = id;
          continue;
        }
        addLandmark(ekf, i, readings[i], id, time_s);
      }
    } else if (options_.new_landmarks == NewLandmarks::kImmediate) {
      for (const std::size_t i : fresh_) addLandmark(ekf, i, readings[i], nextId(ekf), time_s);
    } else {
      feedTracks(ekf, readings, time_s);
    }
    removeUnconfirmed(ekf, time_s);
    report_.tentative_tracks = static_cast<int>(tracks_.size());
    last_time_ = time_s;
    const auto end = Clock::now();
    report_.seconds.association = std::chrono::duration<double>(associated - begin).count();
    report_.seconds.fusion = std::chrono::duration<double>(fused - associated).count();
    report_.seconds.mapping = std::chrono::duration<double>(end - fused).count();
    report_.seconds.total = std::chrono::duration<double>(end - begin).count();
    return report_;
  }

 private:
  struct Record {
    double created_s;
    double last_fused_s;
    int sightings;
    bool started_here;  ///< only these may be removed as unconfirmed
  };
  struct Track {
    Vec<2> position;
    int sightings;
    double last_s;
  };

  void checkOptions() const {
    const auto bad = [](const std::string& what) {
      fail(ErrorCode::kInvalidArgument, "slam::FrontEndOptions: " + what);
    };
    const auto probability = [&](double p, const char* name) {
      if (!(p > 0.0 && p < 1.0)) bad(std::string(name) + " = " + std::to_string(p) + " must lie strictly between 0 and 1");
    };
    probability(options_.gate_probability, "gate_probability");
    probability(options_.new_landmark_probability, "new_landmark_probability");
    if (options_.known_id_gate_probability)
      probability(*options_.known_id_gate_probability, "known_id_gate_probability");
    if (!(options_.min_fusion_interval_s >= 0.0) || !std::isfinite(options_.min_fusion_interval_s))
      bad("min_fusion_interval_s must be finite and >= 0");
    const TentativeTracks& t = options_.tentative;
    if (t.confirm_sightings < 1) bad("tentative.confirm_sightings must be at least 1");
    if (!(t.radius_m >= 0.0) || !(t.timeout_s >= 0.0)) bad("tentative.radius_m and tentative.timeout_s must be >= 0");
    if (options_.new_landmarks == NewLandmarks::kTentative && !kHasPlanarPosition)
      bad("tentative tracks need a landmark with a planar position (Landmark::kPlanarPosition)");
    if (options_.unconfirmed.min_sightings < 0 || !(options_.unconfirmed.within_s >= 0.0))
      bad("unconfirmed.min_sightings and unconfirmed.within_s must be >= 0");
  }

  template <typename L, typename = void>
  struct PlanarPosition : std::false_type {};
  template <typename L>
  struct PlanarPosition<L, std::void_t<decltype(L::kPlanarPosition)>> : std::true_type {};
  static constexpr bool kHasPlanarPosition = PlanarPosition<Landmark>::value;

  void refuse(std::size_t i, ErrorCode code, const std::string& why) {
    ReadingResult& r = report_.readings[i];
    r.outcome = Outcome::kRefused;
    r.error = code;
    r.why = why;
  }

  bool due(Id id, double time_s) const {
    if (options_.min_fusion_interval_s <= 0.0) return true;
    const auto it = records_.find(id);
    return it == records_.end() || time_s - it->second.last_fused_s >= options_.min_fusion_interval_s - 1e-9;
  }

  void pair(std::size_t i, const ReadingType& reading, Id id, const Lin& lin) {
    report_.readings[i].landmark = id;
    paired_.push_back(Observation<Model>{id, reading.z, reading.noise});
    paired_lins_.push_back(lin);
    paired_index_.push_back(i);
  }

  void associateKnown(const Filter& ekf, const std::vector<ReadingType>& readings, double time_s) {
    for (const std::size_t i : valid_) {
      const ReadingType& reading = readings[i];
      const Id id = *reading.id;
      ReadingResult& r = report_.readings[i];
      if (!ekf.contains(id)) {
        fresh_.push_back(i);
        continue;
      }
      if (!due(id, time_s)) {
        r.outcome = Outcome::kThinned;
        r.landmark = id;
        continue;
      }
      Lin lin;
      try {
        lin = ekf.linearize(model_, id);
        if (known_gate_ || options_.report_nis) {
          // As Ekf::innovation forms it, from the one linearization the update reuses.
          Innovation<kDim> innovation;
          innovation.nu = sylva::detail::residual(model_, reading.z, lin.z_hat);
          innovation.S = ekf.crossCovariance(lin, lin) + reading.gateNoise().covariance();
          innovation.S = (0.5 * (innovation.S + innovation.S.transpose())).eval();
          r.nis = innovation.nis();
        }
      } catch (const Error& e) {
        refuse(i, e.code(), e.what());
        continue;
      }
      if (known_gate_ && r.nis > *known_gate_) {
        r.outcome = Outcome::kGatedOut;
        r.landmark = id;
      } else {
        pair(i, reading, id, lin);
      }
    }
  }

  void associateUnknown(const Filter& ekf, const std::vector<ReadingType>& readings, double time_s) {
    if (candidates_) {
      candidates_(ekf, candidate_ids_);
    } else {
      candidate_ids_.clear();
      const int type = Filter::template typeIndexOf<Landmark>();
      for (const LandmarkSlot& s : ekf.slots())
        if (s.type_index == type) candidate_ids_.push_back(s.id);
    }
    report_.candidates = static_cast<int>(candidate_ids_.size());
    z_.clear();
    gate_noises_.clear();
    for (const std::size_t i : valid_) {
      z_.push_back(readings[i].z);
      gate_noises_.push_back(readings[i].gateNoise());
    }
    // One table: the association, the new-landmark test and the update all read it, so each
    // candidate is linearized once in this step.
    std::vector<std::optional<Id>> pairing(valid_.size());
    const bool table = !z_.empty() && !candidate_ids_.empty();
    if (table) {
      bool shared = true;  // one noise for all: one factor of S per candidate, not per pair
      for (const Gaussian<kDim>& g : gate_noises_) shared = shared && g.covariance() == gate_noises_[0].covariance();
      std::vector<Mat<kDim, kDim>> R;
      if (shared) {
        R.push_back(gate_noises_[0].covariance());
      } else {
        for (const Gaussian<kDim>& g : gate_noises_) R.push_back(g.covariance());
      }
      table_ = sylva::detail::buildCompatibilityTable(ekf, model_, z_, std::move(R), candidate_ids_,
                                               options_.gate_probability, "slam::FrontEnd");
      pairing = options_.association == Association::kJcbb ? associateJcbb(ekf, table_)
                                                           : associateNearestNeighbor(table_);
    }
    for (std::size_t k = 0; k < valid_.size(); ++k) {
      const std::size_t i = valid_[k];
      ReadingResult& r = report_.readings[i];
      if (pairing[k]) {
        if (due(*pairing[k], time_s)) {
          const auto j = std::find(candidate_ids_.begin(), candidate_ids_.end(), *pairing[k]) - candidate_ids_.begin();
          pair(i, readings[i], *pairing[k], table_.lins[static_cast<std::size_t>(j)]);
        } else {
          r.outcome = Outcome::kThinned;
          r.landmark = *pairing[k];
        }
        continue;
      }
      r.nis = table ? table_.smallestNis(static_cast<int>(k)) : std::numeric_limits<double>::infinity();
      if (r.nis > new_gate_)
        fresh_.push_back(i);
      else
        r.outcome = Outcome::kAmbiguous;
    }
  }

  void fused(std::size_t a, double time_s) {
    const std::size_t i = paired_index_[a];
    report_.readings[i].outcome = Outcome::kPaired;
    const auto it = records_.find(paired_[a].id);
    if (it != records_.end()) {
      it->second.last_fused_s = time_s;
      ++it->second.sightings;
    } else {
      records_.emplace(paired_[a].id, Record{time_s, time_s, 1, false});
    }
  }

  void fuse(Filter& ekf, double time_s) {
    if (paired_.empty()) return;
    if (options_.fusion == Fusion::kBatched) {
      try {
        ekf.update(model_, paired_, paired_lins_);
        for (std::size_t a = 0; a < paired_.size(); ++a) fused(a, time_s);
        return;
      } catch (const Error& e) {
        if (!options_.fallback_to_sequential) {
          for (std::size_t a = 0; a < paired_.size(); ++a) refuse(paired_index_[a], e.code(), e.what());
          report_.batch_refused = e.what();
          return;
        }
        report_.batch_refused = e.what();
      }
    }
    for (std::size_t a = 0; a < paired_.size(); ++a) {
      const Observation<Model>& o = paired_[a];
      try {
        ekf.update(model_, o.id, o.z, o.noise);
        fused(a, time_s);
      } catch (const Error& e) {
        refuse(paired_index_[a], e.code(), e.what());
      }
    }
  }

  Id nextId(const Filter& ekf) {
    while (ekf.contains(next_id_)) ++next_id_;
    return next_id_;
  }

  /// Adds landmark `id` from reading i; on success the reading is kAdded.
  bool addLandmark(Filter& ekf, std::size_t i, const ReadingType& reading, Id id, double time_s) {
    try {
      ekf.add(id, inverse_, reading.z, reading.noise);
    } catch (const Error& e) {
      refuse(i, e.code(), e.what());
      return false;
    }
    report_.readings[i].outcome = Outcome::kAdded;
    report_.readings[i].landmark = id;
    records_[id] = Record{time_s, time_s, 1, true};
    if (id == next_id_) ++next_id_;
    return true;
  }

  /// Step 4 with tentative tracks (see `TentativeTracks`).
  void feedTracks(Filter& ekf, const std::vector<ReadingType>& readings, double time_s) {
    if constexpr (kHasPlanarPosition) {
      const TentativeTracks& opt = options_.tentative;
      for (const std::size_t i : fresh_) {
        Vec<2> position;
        try {
          Mat<Landmark::kDim, Filter::kRobotStateDim> J_l_x;
          Mat<Landmark::kDim, kDim> J_l_z;
          const Vec<Landmark::kDim> l =
              sylva::detail::initializeOn<typename Filter::Robot>(inverse_, ekf.robotMean(), readings[i].z, J_l_x, J_l_z);
          position = l.template segment<2>(Landmark::kPlanarPosition);
        } catch (const Error& e) {
          refuse(i, e.code(), e.what());
          continue;
        }
        Track* best = nullptr;
        double best_distance = opt.radius_m;
        for (Track& t : tracks_) {
          const double d = (t.position - position).norm();
          if (d <= best_distance && t.last_s < time_s) {
            best_distance = d;
            best = &t;
          }
        }
        if (!best) {
          tracks_.push_back(Track{position, 1, time_s});
          best = &tracks_.back();
        } else {
          best->position = position;
          ++best->sightings;
          best->last_s = time_s;
        }
        report_.readings[i].outcome = Outcome::kTentative;
        if (best->sightings >= opt.confirm_sightings) {
          addLandmark(ekf, i, readings[i], nextId(ekf), time_s);
          best->sightings = -1;  // consumed, whether the filter took it or not
        }
      }
      std::vector<Track> kept;
      kept.reserve(tracks_.size());
      for (const Track& t : tracks_)
        if (t.sightings >= 0 && !(time_s - t.last_s > opt.timeout_s)) kept.push_back(t);
      tracks_.swap(kept);
    }
  }

  void removeUnconfirmed(Filter& ekf, double time_s) {
    const UnconfirmedRemoval& u = options_.unconfirmed;
    if (u.min_sightings <= 0) return;
    for (auto it = records_.begin(); it != records_.end();) {
      const Record& r = it->second;
      if (r.started_here && r.sightings < u.min_sightings && time_s - r.created_s > u.within_s &&
          ekf.contains(it->first)) {
        ekf.remove(it->first);
        report_.removed.push_back(it->first);
        it = records_.erase(it);
      } else {
        ++it;
      }
    }
  }

  Model model_;
  Inverse inverse_;
  FrontEndOptions options_;
  Candidates candidates_;
  double new_gate_ = 0.0;
  std::optional<double> known_gate_;
  Id next_id_ = 0;
  double last_time_ = -std::numeric_limits<double>::infinity();
  std::map<Id, Record> records_;  // ordered: removal visits landmarks in id order
  std::vector<Track> tracks_;
  StepReport report_;
  // Per-step buffers, kept to reuse their memory.
  std::vector<std::size_t> valid_;
  std::vector<std::size_t> fresh_;
  std::vector<Id> candidate_ids_;
  std::vector<Vec<kDim>> z_;
  std::vector<Gaussian<kDim>> gate_noises_;
  CompatibilityTable<Model, Filter::kRobotDim> table_;
  std::vector<Observation<Model>> paired_;
  std::vector<Lin> paired_lins_;
  std::vector<std::size_t> paired_index_;
};

}  // namespace sylva::slam
