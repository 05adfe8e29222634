#pragma once
/// @file
/// `sylva::Ekf<Robot, Landmarks...>`: one extended Kalman filter for every robot, landmark
/// parametrization and sensor.
///
/// State: the robot block (`Robot::kDim`, offset 0) followed by landmark slots. Each slot has
/// a user id and a parametrization out of `Landmarks...` (a runtime tag out of a compile-time
/// list), so a map can hold e.g. inverse-depth points, XYZ points and trees side by side.
/// Every kernel works on fixed-size blocks whose sizes come from the types.
///
/// A robot whose state lives on a manifold (`kTangentDim`, `plus`, `minus`: OnManifold<Robot>
/// for a robot with a unit quaternion) keeps its mean on the manifold and its covariance on
/// the tangent there: the robot's rows in the covariance are kRobotDim = kTangentDim, every
/// model's Jacobian is chained through plusJacobian and minusJacobian, and updates move the
/// robot through plus. See docs/filter.md ("Robots on manifolds").
///
/// Complexity (n = state dimension, m = measurement dimension):
///   predict            O(n)      robot block and its cross-covariances (eq. 2.27)
///   update             O(n^2 m)  H is non-zero only in the robot block and one landmark block
///   add                O(n)      augmentation of eq. 2.33-2.39 (amortized: storage doubles)
///   remove             O(n^2)    rows and columns are moved up
///   reparametrize      O(n^2)    covariance carried through the conversion's Jacobian
///
/// The compressed EKF (`setCompression`; Guivant and Nebot 2001) updates only an active part
/// of the state between global updates: predict O(a), update O(m a^2), a global update
/// O(n^2 a) when the active part changes. See docs/filter.md ("Compressed EKF").
///
/// Storage: the covariance lives in a capacity x capacity column-major matrix of which the
/// top-left n x n corner is in use and only its lower triangle is authoritative. Nothing is
/// allocated by `predict` or `update` once the workspace has seen the largest state.
///
/// Errors: every operation validates its input and computes everything that can fail before
/// it writes a member, so a thrown `sylva::Error` leaves mean and covariance bit-identical.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <iterator>
#include <limits>
#include <sstream>
#include <string>
#include <tuple>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include "sylva/core/covariance_check.hpp"
#include "sylva/core/deferred.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/jacobian_ref.hpp"
#include "sylva/core/parallel.hpp"
#include "sylva/core/gauge.hpp"
#include "sylva/core/types.hpp"
#include "sylva/detail/model_traits.hpp"
#include "sylva/diff/evaluate.hpp"
#include "sylva/filter/compression_hooks.hpp"
#include "sylva/filter/gauge_transport.hpp"
#include "sylva/filter/invariant_transport.hpp"
#include "sylva/filter/linearization.hpp"
#include "sylva/filter/linearization_point.hpp"
#include "sylva/filter/lower_covariance.hpp"
#include "sylva/filter/slot_table.hpp"
#include "sylva/filter/update_form.hpp"
#include "sylva/noise/gaussian.hpp"
#include "sylva/detail/workspace.hpp"

namespace sylva {

/// One observation for a batched update: which landmark, what was measured, how noisy.
template <typename Model>
struct Observation {
  Id id;
  Vec<Model::kDim> z;
  Gaussian<Model::kDim> noise;
};

/// How `update(model, observations, fusion)` fuses a range of observations.
enum class Fusion {
  kBatched,     ///< one stacked update: one linearization point, one pass over P
  kSequential,  ///< one update per observation, each linearized after the previous one
};

namespace detail {

/// The Jacobian blocks and landmark offsets of the k observations of a batched update, kept
/// in buffers the filter reuses (they grow only when a larger batch is seen).
template <int M, int R, int L>
class BatchLinearizations {
 public:
  static constexpr int kStride = M * R + M * L;
  template <typename Vector>
  BatchLinearizations(Vector& buffer, std::vector<int>& offsets, int k)
      : offsets_(offsets) {
    growWorkspace(buffer, static_cast<Eigen::Index>(k) * kStride);
    offsets_.resize(static_cast<std::size_t>(k));
    data_ = buffer.data();
  }
  template <typename Lin>
  void store(int a, const Lin& lin) {
    J_z_x(a) = lin.J_z_x;
    J_z_l(a) = lin.J_z_l;
    offsets_[static_cast<std::size_t>(a)] = lin.landmark_offset;
  }
  Eigen::Map<Mat<M, R>> J_z_x(int a) const { return Eigen::Map<Mat<M, R>>(data_ + a * kStride); }
  Eigen::Map<Mat<M, L>> J_z_l(int a) const { return Eigen::Map<Mat<M, L>>(data_ + a * kStride + M * R); }
  int offset(int a) const { return offsets_[static_cast<std::size_t>(a)]; }
  void setOffset(int a, int offset) { offsets_[static_cast<std::size_t>(a)] = offset; }

 private:
  std::vector<int>& offsets_;
  double* data_ = nullptr;
};

}  // namespace detail

/// A landmark parametrization as a value: what `visit` hands its callback, so that the callback
/// can pick a model or a buffer by overloading on it (`using L = typename decltype(tag)::type`).
template <typename Landmark>
struct LandmarkTag {
  using type = Landmark;
};

template <typename UpdateForm_, typename Robot_, typename... Landmarks_>
class BasicEkf {
  static_assert(sizeof...(Landmarks_) >= 1, "Ekf needs at least one landmark parametrization");
  static_assert(Robot_::kDim > 0, "Robot must define `static constexpr int kDim` > 0");

  // The types the filter's bodies use, spelled so that they depend on the robot
  // (core/deferred.hpp): clang compiles those bodies only where a filter type is
  // instantiated, not in every unit that includes this header. Each is the Eigen type it names.
  using Deferral = detail::Deferred<void, Robot_>;
  using VectorXd = detail::Deferred<Eigen::VectorXd, Robot_>;
  using MatrixXd = detail::Deferred<Eigen::MatrixXd, Robot_>;
  using Vec2 = detail::Deferred<Vec<2>, Robot_>;
  using Workspace = detail::BatchWorkspace<Deferral>;

 public:
  using UpdateForm = UpdateForm_;
  using Robot = Robot_;
  /// True for a robot whose state lives on a manifold (motion/on_manifold.hpp): its mean
  /// holds kRobotStateDim entries, its covariance the kRobotDim of the tangent.
  static constexpr bool kRobotOnManifold = detail::HasTangent<Robot>::value;
  /// Entries of the robot's mean (`Robot::kDim`).
  static constexpr int kRobotStateDim = Robot::kDim;
  /// The robot's rows in the covariance and in every Jacobian the filter hands out: its
  /// tangent dimension on a manifold, `Robot::kDim` otherwise.
  static constexpr int kRobotDim = detail::tangentDim<Robot>();
  static constexpr int kControlDim = Robot::kControlDim;
  static constexpr int kNoiseDim = Robot::kNoiseDim;
  using RobotState = Vec<kRobotStateDim>;
  using RobotCovariance = Mat<kRobotDim, kRobotDim>;
  using Control = Vec<kControlDim>;

  /// True when the invariant EKF (LinearizationPoint::kInvariant) applies: a robot with a
  /// planar position and heading, and landmarks that all have a planar position.
  static constexpr bool kInvariantApplies = detail::HasPlanarPosition<Robot>::value &&
                                            detail::HasPlanarHeading<Robot>::value &&
                                            (detail::HasPlanarPosition<Landmarks_>::value && ...);

  /// True when the observability-constrained update (LinearizationPoint::
  /// kObservabilityConstrained) applies: the robot and every landmark type declare their gauge
  /// directions.
  static constexpr bool kObservabilityConstrainedApplies =
      detail::HasGaugeDirections<Robot>::value && (detail::HasGaugeDirections<Landmarks_>::value && ...);

  /// True when `Landmark` is one of the filter's parametrizations.
  template <typename Landmark>
  static constexpr bool kHolds = (std::is_same_v<Landmark, Landmarks_> || ...);

  /// Position of `Landmark` in `Landmarks...` (compile error if absent).
  template <typename Landmark>
  static constexpr int typeIndexOf() {
    static_assert(kHolds<Landmark>,
                  "this landmark parametrization is not in the filter's Landmarks... list");
    constexpr bool matches[] = {std::is_same_v<Landmark, Landmarks_>...};
    for (int i = 0; i < static_cast<int>(sizeof...(Landmarks_)); ++i)
      if (matches[i]) return i;
    return -1;
  }

  /// Name of the parametrization with the given type index.
  static const char* typeName(int type_index) {
    static constexpr const char* names[] = {Landmarks_::kName...};
    return names[type_index];
  }

  /// Starts the filter with the robot's prior. `P0` must be symmetric positive
  /// semi-definite (a zero matrix is fine: "the robot starts at the origin of the map"); for
  /// a robot on a manifold it is the covariance of the tangent at x0 (kRobotDim), and x0 must
  /// lie on the manifold (kOutOfDomain otherwise: a quaternion off unit norm is refused).
  BasicEkf(const RobotState& x0, const RobotCovariance& P0, Robot robot = Robot())
      : robot_(robot) {
    if (!x0.allFinite()) fail(ErrorCode::kNonFinite, "Ekf: initial robot state is not finite");
    checkRobotDomain(x0, "Ekf: initial robot state");
    detail::checkCovarianceMatrix(P0, detail::Definiteness::kPositiveSemi, "Ekf: initial robot covariance");
    reserve(0);
    robot_mean_ = x0;
    robot_first_ = x0;
    robot_ideal_.setConstant(std::numeric_limits<double>::quiet_NaN());
    cov_.stored().template topLeftCorner<kRobotDim, kRobotDim>() = 0.5 * (P0 + P0.transpose());
    cov_.setDim(kRobotDim);
    revision_ = detail::nextRevision();
  }

  /// Pre-allocates storage for landmarks totalling `landmark_dims` state entries so that
  /// later `add` calls do not reallocate.
  void reserve(int landmark_dims) { ensureCapacity(kRobotDim + std::max(0, landmark_dims)); }

  /// Chooses where Jacobians are evaluated (default: the current estimate). The filter
  /// always records each landmark's first estimate and the robot's latest prediction, so the
  /// choice can be made at any time. kFirstEstimates needs a robot with
  /// `firstEstimatesJacobian` (else kInvalidArgument, and the filter is unchanged).
  void setLinearizationPoint(LinearizationPoint point) {
    revision_ = detail::nextRevision();
    if constexpr (!detail::HasFirstEstimatesJacobian<Robot>::value) {
      if (point == LinearizationPoint::kFirstEstimates)
        fail(ErrorCode::kInvalidArgument,
             "Ekf::setLinearizationPoint: first-estimates Jacobians need a robot with "
             "firstEstimatesJacobian(from, to) or firstEstimatesJacobian(from, to, dt), and the "
             "filter's robot type has none");
    }
    if constexpr (!kInvariantApplies) {
      if (point == LinearizationPoint::kInvariant)
        fail(ErrorCode::kInvalidArgument,
             std::string("Ekf::setLinearizationPoint: the invariant EKF needs a robot that declares "
                         "kPlanarPosition and kPlanarHeading (every Pose2D robot) and landmark types that all "
                         "declare kPlanarPosition (Point2, TreeXYR); ") +
                 typesNamed());
    }
    if constexpr (!kObservabilityConstrainedApplies) {
      if (point == LinearizationPoint::kObservabilityConstrained)
        fail(ErrorCode::kInvalidArgument,
             std::string("Ekf::setLinearizationPoint: observability-constrained updates need a robot and landmark "
                         "types that all declare gaugeDirections (ConstantVelocity3D; Point3, InverseDepth, "
                         "TreeXYZR, InverseDepthRadius); ") +
                 typesNamed());
    }
    if (compressed() && (point == LinearizationPoint::kInvariant || point == LinearizationPoint::kObservabilityConstrained))
      fail(ErrorCode::kInvalidArgument,
           "Ekf::setLinearizationPoint: the invariant and observability-constrained updates transform the whole "
           "covariance after each update, which the compressed EKF does not keep current; turn compression off "
           "first (setCompression(nullptr))");
    linearization_ = point;
  }
  LinearizationPoint linearizationPoint() const { return linearization_; }

  /// The stopping rule of the iterated update (kInvalidArgument unless max_iterations >= 1
  /// and tolerance > 0 is finite; the filter is then unchanged).
  void setIteratedUpdate(const IteratedUpdate& settings) {
    if (settings.max_iterations < 1 || !(settings.tolerance > 0.0) || !std::isfinite(settings.tolerance)) {
      std::ostringstream os;
      os << "Ekf::setIteratedUpdate: need max_iterations >= 1 and a finite tolerance > 0, got "
         << settings.max_iterations << " and " << settings.tolerance;
      fail(ErrorCode::kInvalidArgument, os.str());
    }
    iterated_ = settings;
  }
  const IteratedUpdate& iteratedUpdate() const { return iterated_; }

  /// The left inverse of the observability-constrained update's transport (GaugeInverse).
  void setGaugeInverse(GaugeInverse inverse) { gauge_inverse_choice_ = inverse; }
  GaugeInverse gaugeInverse() const { return gauge_inverse_choice_; }

  /// Threads for the large parts of a batched update (W = P H^T L^-T and P -= W W^T) once
  /// the state has detail::kParallelMinRows rows or more; the result is the same bit for bit
  /// as without. Not owned: it must outlive the updates that use it (copies of this filter
  /// share it). nullptr, the default, keeps everything on the calling thread. See
  /// core/thread_pool.hpp.
  void setParallel(Parallel* parallel) { parallel_ = parallel; }
  Parallel* parallel() const { return parallel_; }

  // ---------------------------------------------------------------- compressed EKF

  /// Chooses the landmarks of the compressed EKF's active part when a region is entered.
  using RegionSelector = std::function<bool(const BasicEkf&, const LandmarkSlot&)>;

  /// How the compressed EKF makes its regions: `select` chooses the active landmarks when a
  /// region is entered; `left`, if given, is asked at each predict with the robot's state
  /// when the region was entered, and a true answer enters a new region. A selector alone
  /// converts to a rule without `left`; `withinRadius` gives both.
  struct RegionRule {
    using Left = std::function<bool(const BasicEkf&, const RobotState& at_entry)>;
    RegionRule() = default;
    template <typename Select, typename = std::enable_if_t<std::is_constructible_v<RegionSelector, Select>>>
    RegionRule(Select select_landmark, Left left_region = nullptr)  // NOLINT: converts a selector
        : select(std::move(select_landmark)), left(std::move(left_region)) {}
    RegionSelector select;
    Left left;
  };

  /// Turns the compressed EKF on (Guivant and Nebot 2001), with `rule.select` choosing the
  /// landmarks of the active part, or off (nullptr: a global update, then the plain filter).
  ///
  /// The active part A is the robot, the landmarks `select` chose when the region was
  /// entered, and every landmark added since. Predictions and updates that see only A cost
  /// O(a) and O(m a^2) instead of O(n) and O(n^2 m); the rest of the state, B, is carried as
  /// accumulated products (detail::CompressedRegion) and brought up to date by a global
  /// update, O(n^2 a). The filter enters a new region (a global update, `select` asked
  /// again, the state reordered so that A leads it; O(n^2)) when:
  ///   - an update observes a landmark of B (it joins the new region whatever `select` says),
  ///   - the rule's `left` says, at a predict, that the robot has left the region (for
  ///     `withinRadius`: the robot is outside the region's disc),
  ///   - the caller calls `enterRegion()`.
  /// Removing or reparametrizing a landmark of A costs a global update (the region keeps its
  /// landmarks).
  /// Everything read through the public accessors is up to date: the landmark accessors,
  /// `mean()` and `covariance()` correct what B holds on the fly (O(a^2) per block, O(n^2 a)
  /// for the whole covariance), and `covarianceView()` refuses (kInvalidArgument) until
  /// `synchronize()`. Estimates equal the plain filter's up to round-off (the accumulators are
  /// scaled by a factor of P_AA for that: docs/filter.md, "Round-off").
  ///
  /// Refused (kInvalidArgument, the filter unchanged) with LinearizationPoint::kInvariant or
  /// kObservabilityConstrained, whose transports change the whole covariance at every update.
  /// The region is entered at once: `select` is asked about every landmark now. Needs
  /// `#include <sylva/filter/compression.hpp>`, which a program that never compresses does
  /// not compile.
  void setCompression(RegionRule rule) {
    static_assert(detail::IsDefined<detail::Compression<BasicEkf>>::value,
                  "Ekf::setCompression needs #include <sylva/filter/compression.hpp>");
    if (!rule.select) {
      synchronize();
      compression_.reset();
      return;
    }
    if (linearization_ == LinearizationPoint::kInvariant || linearization_ == LinearizationPoint::kObservabilityConstrained)
      fail(ErrorCode::kInvalidArgument,
           "Ekf::setCompression: the compressed EKF cannot run the invariant or observability-constrained "
           "update (they transform the whole covariance after each update)");
    synchronize();
    // The new region is entered before it replaces the old one: if that fails, the filter
    // keeps its old region (the global update above changed no estimate).
    detail::ClonePtr<detail::CompressionHooks<BasicEkf>> next;
    next.reset(new detail::Compression<BasicEkf>(std::move(rule)));
    next->enterRegion(*this, nullptr, 0);
    compression_ = std::move(next);
  }
  bool compressed() const { return static_cast<bool>(compression_); }

  /// The compressed EKF's active part: its rows (the robot and its landmarks lead the state),
  /// dim() when compression is off.
  int activeDim() const { return compressed() ? compression_->activeDim() : dim(); }
  /// Global updates so far (for reports; 0 when compression is off).
  long globalUpdates() const { return compressed() ? compression_->globalUpdates() : 0; }

  /// Brings the whole state up to date (the compressed EKF's global update, O(n^2 a)); a
  /// no-op when compression is off or nothing happened since the last one. Changes no
  /// estimate.
  void synchronize() {
    if (compressed()) compression_->synchronize(*this);
  }

  /// Enters a new region: a global update, then the landmarks the selector chooses now become
  /// the active part (the state is reordered so that they lead it). No-op when compression is
  /// off. Changes no estimate.
  void enterRegion() {
    if (compressed()) compression_->enterRegion(*this, nullptr, 0);
  }

  /// A rule for `setCompression`: the active landmarks are those within `radius_m` of a
  /// point `ahead_m` in front of the robot when the region is entered (along its heading; 0:
  /// the robot's own position), and the robot has left the region when it is outside that
  /// disc (a new region is then entered at the next predict). For a robot that declares
  /// kPlanarPosition (every Pose2D robot; a point ahead needs kPlanarHeading too). A robot
  /// that moves forward stays in a region centred ahead of it about twice as long as in one
  /// centred on it: with a sensor of range s, ahead_m = radius_m - s lets it travel
  /// 2 (radius_m - s) before a landmark outside the region comes into view. Landmark types
  /// without a planar position (kPlanarPosition) are always active.
  static RegionRule withinRadius(double radius_m, double ahead_m = 0.0) {
    static_assert(detail::HasPlanarPosition<Robot>::value,
                  "withinRadius needs a robot that declares kPlanarPosition (every Pose2D robot)");
    if (!(radius_m > 0.0) || !std::isfinite(radius_m) || !std::isfinite(ahead_m))
      fail(ErrorCode::kInvalidArgument, "Ekf::withinRadius: the radius must be positive and finite, and the "
                                        "distance ahead finite");
    if constexpr (!detail::HasPlanarHeading<Robot>::value) {
      if (ahead_m != 0.0)
        fail(ErrorCode::kInvalidArgument, "Ekf::withinRadius: a centre ahead of the robot needs a robot that "
                                          "declares kPlanarHeading");
    }
    // The region's centre for a robot at x.
    const auto centreFor = [ahead_m](const RobotState& x) {
      Vec2 centre = x.template segment<2>(Robot::kPlanarPosition);
      if constexpr (detail::HasPlanarHeading<Robot>::value)
        centre += ahead_m * Vec2(std::cos(x[Robot::kPlanarHeading]), std::sin(x[Robot::kPlanarHeading]));
      return centre;
    };
    const auto left = [radius_m, centreFor](const BasicEkf& ekf, const RobotState& at_entry) {
      return (ekf.robotMean().template segment<2>(Robot::kPlanarPosition) - centreFor(at_entry)).squaredNorm() >
             radius_m * radius_m;
    };
    const auto select = [radius_m, centreFor](const BasicEkf& ekf, const LandmarkSlot& slot) {
      const Vec2 centre = centreFor(ekf.robotMean());
      return ekf.visit(slot.id, [&](auto tag) {
        using L = typename decltype(tag)::type;
        if constexpr (detail::HasPlanarPosition<L>::value) {
          const Vec2 p = ekf.template landmarkMean<L>(slot.id).template segment<2>(L::kPlanarPosition);
          return (p - centre).squaredNorm() <= radius_m * radius_m;
        } else {
          return true;
        }
      });
    };
    return RegionRule(select, left);
  }

  /// The robot's true state, for LinearizationPoint::kIdeal: predict linearizes the motion
  /// about it, and updates the measurement models. Each predict uses it up, so hand
  /// over the true state before a predict (the state it starts from) and after it (the state
  /// the updates see). Non-finite input is refused (kNonFinite); the filter is unchanged.
  void setIdealRobot(const RobotState& x_true) {
    revision_ = detail::nextRevision();
    if (!x_true.allFinite()) fail(ErrorCode::kNonFinite, "Ekf::setIdealRobot: the true robot state is not finite");
    checkRobotDomain(x_true, "Ekf::setIdealRobot: the true robot state");
    robot_ideal_ = x_true;
  }

  /// The true state of landmark `id` in its parametrization `Landmark`, for kIdeal. Kept until
  /// the landmark leaves the state or changes parametrization (the true state of the new
  /// parametrization must then be handed over again). Throws kUnknownId, kWrongLandmarkType or
  /// kNonFinite, and the filter is unchanged.
  template <typename Landmark>
  void setIdealLandmark(Id id, const Vec<Landmark::kDim>& l_true) {
    revision_ = detail::nextRevision();
    const LandmarkSlot& s = typedSlot<Landmark>(id, "Ekf::setIdealLandmark");
    if (!l_true.allFinite())
      fail(ErrorCode::kNonFinite, "Ekf::setIdealLandmark: the true state of landmark " + std::to_string(id) + " is not finite");
    ideal_.template segment<Landmark::kDim>(s.offset) = l_true;
  }

  // ---------------------------------------------------------------- access

  /// State dimension n = robot + all landmark blocks.
  int dim() const { return cov_.dim(); }

  /// Changes with every change of the state, or of where it is linearized. A
  /// `Linearization` records the revision it was made at; `update` with linearizations
  /// refuses one made at another revision (or by another filter).
  std::uint64_t revision() const { return revision_; }
  int landmarkCount() const { return slots_.size(); }
  const std::vector<LandmarkSlot>& slots() const { return slots_.slots(); }
  bool contains(Id id) const { return slots_.contains(id); }
  const Robot& robot() const { return robot_; }

  /// The slot of `id` (throws kUnknownId).
  const LandmarkSlot& slot(Id id) const { return slots_[slotIndex(id)]; }

  /// True when `id` exists and is parametrized as `Landmark`.
  template <typename Landmark>
  bool holds(Id id) const {
    const LandmarkSlot* s = slots_.find(id);
    return s != nullptr && s->type_index == typeIndexOf<Landmark>();
  }

  /// Calls `f(LandmarkTag<L>{})`, L being the parametrization of landmark `id`, and returns
  /// what f returns (f must return the same type for every L). One switch over `Landmarks...`
  /// in place of a chain of `holds<L>(id)` tests, and a new parametrization cannot be
  /// forgotten: f must accept each. Throws kUnknownId (before f runs) for an id not in the state.
  template <typename F>
  decltype(auto) visit(Id id, F&& f) const {
    return visitType<0>(slots_[slotIndex(id)].type_index, f);
  }

  /// The robot's mean (kRobotStateDim entries; on a manifold, a point of it).
  const RobotState& robotMean() const { return robot_mean_; }
  /// The robot's covariance (kRobotDim: on a manifold, of the tangent at robotMean()).
  RobotCovariance robotCovariance() const { return cov_.template block<kRobotDim, kRobotDim>(0, 0); }

  /// Mean of landmark `id`, which must be parametrized as `Landmark` (else kWrongLandmarkType).
  template <typename Landmark>
  Vec<Landmark::kDim> landmarkMean(Id id) const {
    const LandmarkSlot& s = typedSlot<Landmark>(id, "landmarkMean");
    return currentMean<Landmark::kDim>(s.offset);
  }

  /// Marginal covariance of landmark `id`.
  template <typename Landmark>
  Mat<Landmark::kDim, Landmark::kDim> landmarkCovariance(Id id) const {
    const LandmarkSlot& s = typedSlot<Landmark>(id, "landmarkCovariance");
    return currentBlock<Landmark::kDim, Landmark::kDim>(s.offset, s.offset);
  }

  /// Cross-covariance between the robot and landmark `id`.
  template <typename Landmark>
  Mat<kRobotDim, Landmark::kDim> robotLandmarkCovariance(Id id) const {
    const LandmarkSlot& s = typedSlot<Landmark>(id, "robotLandmarkCovariance");
    return currentBlock<kRobotDim, Landmark::kDim>(0, s.offset);
  }

  /// Copy of the whole mean: the robot's state, then the landmark blocks. Its length is n
  /// (`dim()`) but for a robot on a manifold, whose state is kRobotStateDim - kRobotDim
  /// entries longer than its rows in the covariance.
  VectorXd mean() const {
    VectorXd out(dim() - kRobotDim + kRobotStateDim);
    out << robot_mean_, mean_.segment(kRobotDim, dim() - kRobotDim);
    if (pending()) {
      const int a = compression_->activeDim();
      compression_->correctMean(*this, a, dim() - a, out.data() + out.size() - (dim() - a));
    }
    return out;
  }

  /// The covariance as a symmetric view of the stored lower triangle, without a copy: use it
  /// in products (`ekf.covarianceView() * v`) or assign it to a dense matrix. Its entries
  /// above the diagonal are not stored: read single entries from the lower triangle, or
  /// through the typed blocks below. Valid until a landmark is added, removed or
  /// reparametrized (the storage may move). With the compressed EKF, call `synchronize()`
  /// first: the stored passive part is refused as stale (kInvalidArgument).
  auto covarianceView() const {
    if (pending())
      fail(ErrorCode::kInvalidArgument,
           "Ekf::covarianceView: the compressed EKF's stored covariance is stale outside its active part; call "
           "synchronize() first (or read covariance(), which corrects it)");
    return cov_.inUse().template selfadjointView<Eigen::Lower>();
  }

  /// Copy of the whole covariance (n x n, both triangles filled). O(n^2 a) with the
  /// compressed EKF between global updates.
  MatrixXd covariance() const {
    MatrixXd full = cov_.inUse().template selfadjointView<Eigen::Lower>();
    if (pending()) compression_->correctCovariance(*this, full);
    return full;
  }

  // ---------------------------------------------------------------- predict

  /// Moves the robot by `u` over `dt` seconds with control noise `noise` (eq. 2.22-2.27):
  /// only the robot block and its cross-covariances change, O(n).
  void predict(const Control& u, double dt, const Gaussian<kNoiseDim>& noise) {
    revision_ = detail::nextRevision();
    if (!std::isfinite(dt)) fail(ErrorCode::kNonFinite, "Ekf::predict: dt is not finite");
    if (dt < 0.0) {
      std::ostringstream os;
      os << "Ekf::predict: dt = " << dt << " s is negative";
      fail(ErrorCode::kNegativeTimeStep, os.str());
    }
    if (!u.allFinite()) fail(ErrorCode::kNonFinite, "Ekf::predict: control is not finite");
    Mat<kRobotStateDim, kRobotStateDim> F_state;
    Mat<kRobotStateDim, kNoiseDim> G_state;
    // The Jacobians are taken from `from` to `to` (on a manifold, chained through the
    // tangents there).
    RobotState from = robotMean();
    RobotState next = robot_(from, u, dt, F_state, G_state);
    RobotState to = next;
    const bool ideal = linearization_ == LinearizationPoint::kIdeal;
    if (ideal) {
      from = idealRobot("Ekf::predict");
      to = robot_(from, u, dt, F_state, G_state);
    }
    if constexpr (detail::HasFirstEstimatesJacobian<Robot>::value) {
      // FEJ: the transition Jacobian between the previous prediction and this one.
      if (linearization_ == LinearizationPoint::kFirstEstimates && next.allFinite()) {
        from = robot_first_;
        F_state = detail::firstEstimatesJacobian(robot_, from, next, dt);
      }
    }
    if (!next.allFinite() || !to.allFinite() || !F_state.allFinite() || !G_state.allFinite())
      fail(ErrorCode::kNonFinite, "Ekf::predict: motion model produced a non-finite state or Jacobian");
    checkRobotDomain(to, "Ekf::predict: the motion model's state");
    Mat<kRobotDim, kRobotDim> F;
    Mat<kRobotDim, kNoiseDim> G;
    if constexpr (kRobotOnManifold) {
      const Mat<kRobotDim, kRobotStateDim> M_to = Robot::minusJacobian(to);
      F = M_to * F_state * Robot::plusJacobian(from);
      G = M_to * G_state;
    } else {
      F = F_state;
      G = G_state;
    }
    // The motion linearized about the true state: f(x_true) (+) F (x (-) x_true).
    if (ideal) next = detail::robotPlus<Robot>(to, F * detail::robotMinus<Robot>(robotMean(), from));
    if (!next.allFinite()) fail(ErrorCode::kNonFinite, "Ekf::predict: motion model produced a non-finite state");

    const RobotCovariance GQGt = G * noise.covariance() * G.transpose();
    // With P positive semi-definite, |(F P_rm)_ij| <= sqrt((F P_rr F^T)_ii P_jj) (Cauchy-
    // Schwarz), and F P_rr F^T <= P_rr_next: a finite new robot block keeps the cross rows
    // finite too.
    RobotCovariance P_rr_next = F * robotCovariance() * F.transpose() + GQGt;
    if (!P_rr_next.allFinite())
      fail(ErrorCode::kNonFinite,
           "Ekf::predict: the predicted covariance is not finite (the noise or the motion's Jacobian overflows it)");
    // The compressed EKF: a robot that has left its region enters a new one (a global update
    // and a reordering; no estimate changes, the robot's block stays where it is, and a
    // failed allocation moves nothing).
    if (compressed()) compression_->enterRegionIfLeft(*this);
    // From here on nothing can fail.
    robot_mean_ = next;
    robot_first_ = next;
    robot_ideal_.setConstant(std::numeric_limits<double>::quiet_NaN());
    const ActiveWindow window(cov_, activeDim());
    cov_.template transformRobotBlock<kRobotDim>(F, P_rr_next);  // eq. 2.27 (on A: compressed)
    if (compressed()) compression_->predictRobot(F.data());
  }

  // ---------------------------------------------------------------- update

  /// Fuses one observation `z` of landmark `id` through `model`, with measurement noise
  /// `noise`. The model's landmark type must be in `Landmarks...` (compile time) and match
  /// the slot (runtime, kWrongLandmarkType). Returns the innovation at the prior (for the
  /// iterated update too).
  ///
  /// Everything here is of the model's fixed size M: one observation never instantiates the
  /// batched path's dynamic-size kernels (docs/build-time.md). The iterated update runs the
  /// batched path's iteration (`iterateBatch`) on this batch of one.
  template <typename Model>
  Innovation<Model::kDim> update(const Model& model,
                                 Id id,
                                 const Vec<Model::kDim>& z,
                                 const Gaussian<Model::kDim>& noise) {
    checkModel<Model>();
    constexpr int M = Model::kDim;
    constexpr int L = Model::Landmark::kDim;
    if (!z.allFinite()) fail(ErrorCode::kNonFinite, nameOf<Model>() + ": measurement is not finite");
    checkMeasurement(model, z);
    const Id ids[] = {id};
    ensureActive(ids, [](Id i) { return i; });
    const Linearization<Model, kRobotDim> lin = linearize(model, id);
    Vec<M> nu = detail::residual(model, z, lin.z_hat);
    if (!nu.allFinite()) fail(ErrorCode::kNonFinite, nameOf<Model>() + ": innovation is not finite");

    // The linearization the gain uses: the prior's, or the last iterate's.
    detail::BatchLinearizations<M, kRobotDim, L> lins(batch_.lins, batch_.offsets, 1);
    lins.store(0, lin);
    const ActiveWindow window(cov_, activeDim());
    auto PHt = workspaceMatrix<M>(0);
    Mat<M, M> S;
    Eigen::LLT<Mat<M, M>> llt;
    // P H^T, S = H P H^T + R and its factor at the stored linearization.
    const auto formInnovationCovariance = [&](const char* where) {
      PHt.setZero();
      cov_.template addTimesHt<kRobotDim, L>(lins.J_z_x(0), lins.J_z_l(0), lins.offset(0), PHt, 0);
      S = lins.J_z_x(0) * PHt.template topRows<kRobotDim>() +
          lins.J_z_l(0) * PHt.template middleRows<L>(lins.offset(0)) + noise.covariance();
      S = (0.5 * (S + S.transpose())).eval();
      llt.compute(S);
      if (llt.info() != Eigen::Success || !S.allFinite())
        fail(ErrorCode::kNotPositiveDefinite, nameOf<Model>() + ": innovation covariance S is not positive definite (landmark " +
                                                  std::to_string(id) + ")" + where);
    };
    formInnovationCovariance("");
    const Innovation<M> prior{nu, S};
    if (linearization_ == LinearizationPoint::kIterated) {
      const Observation<Model> one[] = {Observation<Model>{id, z, noise}};
      iterateBatch(model, one, lins, nu, PHt, llt, [&] { formInnovationCovariance(" at an iterate"); });
    }
    // From here on only the posterior domain check can fail, before anything is written.
    applyGain<M>(PHt, llt, nu, noise.covariance(), updateBlocks(1, M, L), [&](const auto& A, auto&& out) {
      out.noalias() = A.template middleCols<kRobotDim>(0) * lins.J_z_x(0).transpose();
      out.noalias() += A.template middleCols<L>(lins.offset(0)) * lins.J_z_l(0).transpose();
    });
    return prior;
  }

  /// Fuses several observations through one model. `Fusion::kBatched` (the default) stacks
  /// them into one update: every prediction and Jacobian is taken at the same estimate, and
  /// P is updated once by a rank-(k m) product on its lower triangle. `Fusion::kSequential`
  /// fuses them one after the other, each linearized at the estimate the previous one left:
  /// k passes over P, closer to the iterated estimate when the models are very non-linear.
  /// See docs/filter.md ("Batched or sequential") for when each wins.
  ///
  /// Ids may repeat only if the caller means it (two independent measurements of the same
  /// landmark). Errors: the batched form throws before anything is written (the filter is
  /// unchanged); the sequential form checks every id, type and measurement first, and if a
  /// later observation is then rejected (S not positive definite, a posterior out of the
  /// landmark's domain), the observations before it stay fused and the error names its index.
  template <typename Model, typename ObservationRange>
  void update(const Model& model, const ObservationRange& observations, Fusion fusion = Fusion::kBatched) {
    checkModel<Model>();
    if (fusion == Fusion::kSequential) {
      updateSequentially(model, observations);
      return;
    }
    updateBatched(model, observations, static_cast<const Linearization<Model, kRobotDim>*>(nullptr));
  }

  /// The batched update with the observations' linearizations already made at the current
  /// state (`linearizations[i]` for observation i, from `linearize`, or from a
  /// `CompatibilityTable`), so that no landmark is linearized twice in one step. The result
  /// is bit for bit that of `update(model, observations)`. A linearization made at another
  /// revision of the filter, or for another landmark block, is refused (kInvalidArgument),
  /// as is a list of another length; the filter is then unchanged.
  template <typename Model, typename ObservationRange>
  void update(const Model& model,
              const ObservationRange& observations,
              const std::vector<Linearization<Model, kRobotDim>>& linearizations) {
    checkModel<Model>();
    if (linearizations.size() != std::size(observations))
      fail(ErrorCode::kInvalidArgument, nameOf<Model>() + ": " + std::to_string(linearizations.size()) +
                                            " linearizations for " + std::to_string(std::size(observations)) +
                                            " observations");
    updateBatched(model, observations, linearizations.data());
  }

 private:
  template <typename Model, typename ObservationRange>
  void updateBatched(const Model& model, const ObservationRange& observations,
                     const Linearization<Model, kRobotDim>* given) {
    constexpr int M = Model::kDim;
    constexpr int L = Model::Landmark::kDim;
    const int k = static_cast<int>(std::size(observations));
    if (k == 0) return;
    const int total = k * M;
    // Every workspace below grows only when a larger state or batch is seen: no allocation
    // in steady state.
    detail::BatchLinearizations<M, kRobotDim, L> lins(batch_.lins, batch_.offsets, k);
    auto nu = batch_.vector(Workspace::kInnovation, total);
    int i = 0;
    for (const Observation<Model>& obs : observations) {
      if (!obs.z.allFinite())
        fail(ErrorCode::kNonFinite, nameOf<Model>() + ": measurement " + std::to_string(i) +
                                        " of the batch is not finite");
      checkMeasurement(model, obs.z, "batch", i);
      if (given) checkedLinearization(given[i], obs.id, i);
      ++i;
    }
    // Compressed: a landmark of the passive part makes the filter enter a region that holds
    // it (the given linearizations stay valid: no estimate changes, only where blocks lie).
    const bool moved = ensureActive(observations, [](const Observation<Model>& obs) { return obs.id; });
    i = 0;
    for (const Observation<Model>& obs : observations) {
      const Linearization<Model, kRobotDim> lin = given ? given[i] : linearize(model, obs.id);
      lins.store(i, lin);
      if (moved && given) lins.setOffset(i, slots_[slotIndex(obs.id)].offset);
      nu.template segment<M>(i * M) = detail::residual(model, obs.z, lin.z_hat);
      ++i;
    }
    if (!nu.allFinite()) fail(ErrorCode::kNonFinite, nameOf<Model>() + ": innovation is not finite");

    const ActiveWindow window(cov_, activeDim());
    auto PHt = workspaceMatrix<Eigen::Dynamic>(total);
    auto S = batch_.matrix(Workspace::kInnovationCovariance, total);
    // P H^T and S = H P H^T + R (lower triangle, block (a, b) for b <= a, from the columns of
    // P H^T) for the linearizations in `lins`.
    const auto formInnovationCovariance = [&] {
      // Each observation's columns of P H^T on their own: shared among the threads of a
      // large state (setParallel), with the same result.
      const auto formPHt = [&](int first, int last) {
        for (int a = first; a < last; ++a) {
          PHt.middleCols(a * M, M).setZero();
          cov_.template addTimesHt<kRobotDim, L>(lins.J_z_x(a), lins.J_z_l(a), lins.offset(a), PHt, a * M);
        }
      };
      runRanges(parallel_, k, parallel_ != nullptr && dim() >= detail::kParallelMinRows ? parallel_->concurrency() : 1, formPHt);
      for (int a = 0; a < k; ++a) {
        const int off = lins.offset(a);
        for (int b = 0; b <= a; ++b) {
          const auto col = PHt.middleCols(b * M, M);
          S.block(a * M, b * M, M, M).noalias() =
              lins.J_z_x(a) * col.template topRows<kRobotDim>() + lins.J_z_l(a) * col.template middleRows<L>(off);
        }
      }
      int n_obs = 0;
      for (const Observation<Model>& obs : observations) {
        S.block(n_obs * M, n_obs * M, M, M) += obs.noise.covariance();
        ++n_obs;
      }
      for (int j = 0; j < total; ++j)
        if (!S.col(j).tail(total - j).allFinite())
          fail(ErrorCode::kNonFinite, nameOf<Model>() + ": batched innovation covariance is not finite");
    };
    formInnovationCovariance();
    // The joint R, kept for the Joseph form only.
    auto R = batch_.matrix(Workspace::kNoise, std::is_same_v<UpdateForm, JosephUpdate> ? total : 0);
    if constexpr (std::is_same_v<UpdateForm, JosephUpdate>) {
      R.setZero();
      i = 0;
      for (const Observation<Model>& obs : observations) {
        R.block(i * M, i * M, M, M) = obs.noise.covariance();
        ++i;
      }
    }
    Eigen::LLT<Eigen::Ref<MatrixXd>> llt(S);  // in place: S now holds its factor L
    if (llt.info() != Eigen::Success)
      fail(ErrorCode::kNotPositiveDefinite,
           nameOf<Model>() + ": batched innovation covariance is not positive definite");
    if (linearization_ == LinearizationPoint::kIterated) {
      iterateBatch(model, observations, lins, nu, PHt, llt, [&] {
        formInnovationCovariance();
        llt.compute(S);
        if (llt.info() != Eigen::Success)
          fail(ErrorCode::kNotPositiveDefinite,
               nameOf<Model>() + ": batched innovation covariance is not positive definite at an iterate");
      });
    }
    applyGain<Eigen::Dynamic>(PHt, llt, nu, R, updateBlocks(k, M, L), [&](const auto& A, auto&& out) {
      for (int a = 0; a < k; ++a) {
        out.middleCols(a * M, M).noalias() = A.template middleCols<kRobotDim>(0) * lins.J_z_x(a).transpose();
        out.middleCols(a * M, M).noalias() += A.template middleCols<L>(lins.offset(a)) * lins.J_z_l(a).transpose();
      }
    });
  }

  /// `lin`, if it was made at this revision for landmark `id`'s block (see `update`).
  template <typename Model>
  const Linearization<Model, kRobotDim>& checkedLinearization(const Linearization<Model, kRobotDim>& lin, Id id,
                                                              int i) const {
    const LandmarkSlot& s = typedSlot<typename Model::Landmark>(id, Model::kName);
    if (lin.revision != revision_)
      fail(ErrorCode::kInvalidArgument, nameOf<Model>() + ": the linearization of observation " + std::to_string(i) +
                                            " was made at another state (revision " + std::to_string(lin.revision) +
                                            ", the filter is at " + std::to_string(revision_) + ")");
    if (lin.landmark_offset != s.offset)
      fail(ErrorCode::kInvalidArgument, nameOf<Model>() + ": the linearization of observation " + std::to_string(i) +
                                            " is not of landmark " + std::to_string(id));
    return lin;
  }

 public:
  // ---------------------------------------------------------------- gating helpers

  /// h(x) at the current estimate and the two non-zero blocks of H for landmark `id`, at
  /// the filter's linearization point (`setLinearizationPoint`).
  template <typename Model>
  Linearization<Model, kRobotDim> linearize(const Model& model, Id id) const {
    checkModel<Model>();
    constexpr int L = Model::Landmark::kDim;
    const LandmarkSlot& s = typedSlot<typename Model::Landmark>(id, Model::kName);
    Linearization<Model, kRobotDim> lin;
    lin.landmark_offset = s.offset;
    lin.revision = revision_;
    const Vec<L> landmark = currentMean<L>(s.offset);
    if (linearization_ == LinearizationPoint::kFirstEstimates) {
      lin.z_hat = detail::evaluateOn<Robot>(model, robotMean(), landmark, {}, {});
      evaluateWithJacobians(model, robot_first_, Vec<L>(first_.template segment<L>(s.offset)), lin);
    } else if (linearization_ == LinearizationPoint::kIdeal) {
      const Vec<L> ideal_landmark = ideal_.template segment<L>(s.offset);
      if (!ideal_landmark.allFinite())
        fail(ErrorCode::kInvalidArgument,
             std::string(Model::kName) + ": ideal linearization needs the true state of landmark " +
                 std::to_string(id) + " (setIdealLandmark), and none was handed over since it entered the state");
      const RobotState ideal_robot = idealRobot(Model::kName);
      // The first-order prediction about the truth: the filter of the linearized system.
      lin.z_hat = evaluateWithJacobians(model, ideal_robot, ideal_landmark, lin) +
                  lin.J_z_x * detail::robotMinus<Robot>(robotMean(), ideal_robot) +
                  lin.J_z_l * detail::difference<typename Model::Landmark>(landmark, ideal_landmark);
    } else {
      lin.z_hat = evaluateWithJacobians(model, robotMean(), landmark, lin);
    }
    if (!lin.z_hat.allFinite() || !lin.J_z_x.allFinite() || !lin.J_z_l.allFinite())
      fail(ErrorCode::kNonFinite, nameOf<Model>() + ": prediction or Jacobian is not finite for landmark " +
                                      std::to_string(id));
    return lin;
  }

  /// H_a P H_b^T for two linearizations (the cross term of a joint innovation covariance).
  template <typename ModelA, typename ModelB>
  Mat<ModelA::kDim, ModelB::kDim> crossCovariance(const Linearization<ModelA, kRobotDim>& a,
                                                   const Linearization<ModelB, kRobotDim>& b) const {
    if (pending() && std::max(a.landmark_offset, b.landmark_offset) >= compression_->activeDim()) {
      constexpr int La = ModelA::Landmark::kDim;
      constexpr int Lb = ModelB::Landmark::kDim;
      const int oa = a.landmark_offset;
      const int ob = b.landmark_offset;
      return a.J_z_x * (currentBlock<kRobotDim, kRobotDim>(0, 0) * b.J_z_x.transpose() +
                        currentBlock<kRobotDim, Lb>(0, ob) * b.J_z_l.transpose()) +
             a.J_z_l * (currentBlock<La, kRobotDim>(oa, 0) * b.J_z_x.transpose() +
                        currentBlock<La, Lb>(oa, ob) * b.J_z_l.transpose());
    }
    return cov_.template crossCovariance<kRobotDim>(a.J_z_x, a.J_z_l, a.landmark_offset, b.J_z_x, b.J_z_l,
                                                    b.landmark_offset);
  }

  /// Innovation and its covariance S = H P H^T + R for a candidate pairing, without
  /// changing the filter (for gating and nearest-neighbour association).
  template <typename Model>
  Innovation<Model::kDim> innovation(const Model& model,
                                     Id id,
                                     const Vec<Model::kDim>& z,
                                     const Gaussian<Model::kDim>& noise) const {
    if (!z.allFinite()) fail(ErrorCode::kNonFinite, nameOf<Model>() + ": measurement is not finite");
    checkMeasurement(model, z);
    const Linearization<Model, kRobotDim> lin = linearize(model, id);
    Innovation<Model::kDim> result;
    result.nu = detail::residual(model, z, lin.z_hat);
    result.S = crossCovariance(lin, lin) + noise.covariance();
    result.S = (0.5 * (result.S + result.S.transpose())).eval();
    // An S that is not positive definite would give a negative NIS, which passes any gate.
    const Eigen::LLT<Mat<Model::kDim, Model::kDim>> llt(result.S);
    if (llt.info() != Eigen::Success || !result.S.allFinite())
      fail(ErrorCode::kNotPositiveDefinite,
           nameOf<Model>() + ": innovation covariance S is not positive definite (landmark " + std::to_string(id) + ")");
    return result;
  }

  // ---------------------------------------------------------------- map management

  /// Adds landmark `id` from its first observation `z` through the inverse model
  /// (augmentation, eq. 2.33-2.39): the new block's cross-covariances are J_l_x P_r* and its
  /// covariance J_l_x P_rr J_l_x^T + J_l_z R J_l_z^T. O(n). With the compressed EKF the new
  /// landmark joins the active part, at its end: O(a) arithmetic, and O(n) moves when the
  /// first passive landmark has its size (the two blocks are exchanged), else O(n^2) (the
  /// passive part's storage moves down by its rows).
  template <typename InverseModel>
  void add(Id id,
           const InverseModel& inverse,
           const Vec<InverseModel::kMeasurementDim>& z,
           const Gaussian<InverseModel::kMeasurementDim>& noise) {
    revision_ = detail::nextRevision();
    using Landmark = typename InverseModel::Landmark;
    constexpr int L = Landmark::kDim;
    constexpr int Z = InverseModel::kMeasurementDim;
    static_assert(kHolds<Landmark>,
                  "the inverse model's Landmark type is not in the filter's Landmarks... list");
    static_assert(detail::kRobotFits<typename InverseModel::Robot, Robot>,
                  "the inverse model is written for another robot type (its Robot is neither "
                  "the filter's robot nor a base of it)");
    if (contains(id))
      fail(ErrorCode::kDuplicateId, std::string(InverseModel::kName) + ": landmark id " +
                                        std::to_string(id) + " already exists");
    if (!z.allFinite()) fail(ErrorCode::kNonFinite, std::string(InverseModel::kName) + ": measurement is not finite");
    Mat<L, kRobotStateDim> J_l_state;
    Mat<L, Z> J_l_z;
    const Vec<L> l = detail::initializeOn<Robot>(inverse, robotMean(), z, J_l_state, J_l_z);
    const Mat<L, kRobotDim> J_l_x = detail::onTangent<Robot>(J_l_state, robotMean());
    if (!l.allFinite() || !J_l_x.allFinite() || !J_l_z.allFinite())
      fail(ErrorCode::kNonFinite, std::string(InverseModel::kName) + ": initialization is not finite");
    if constexpr (detail::HasDomain<Landmark>::value) {
      if (const char* why = Landmark::domainViolation(l))
        fail(ErrorCode::kOutOfDomain, std::string(InverseModel::kName) + ": landmark " + std::to_string(id) + ": " + why);
    }
    const RobotCovariance P_rr = robotCovariance();
    const Mat<L, kRobotDim> J_P_rr = J_l_x * P_rr;
    Mat<L, L> P_ll = J_P_rr * J_l_x.transpose() + J_l_z * noise.covariance() * J_l_z.transpose();
    P_ll = (0.5 * (P_ll + P_ll.transpose())).eval();
    // The new block's rows against the landmarks, J_l_x P_rm, computed before anything is
    // written: the product (and its buffer) may allocate for a large state. Compressed: the
    // active landmarks only (its cross-covariance with the passive part is carried by the
    // region's accumulators, and stored as zero).
    const int m = activeDim() - kRobotDim;
    const Eigen::Matrix<double, L, Eigen::Dynamic> J_P_rm = J_l_x * cov_.stored().block(kRobotDim, 0, m, kRobotDim).transpose();
    if (!P_ll.allFinite() || !J_P_rr.allFinite() || !J_P_rm.allFinite())
      fail(ErrorCode::kNonFinite, std::string(InverseModel::kName) + ": the new landmark's covariance is not finite "
                                                                     "(its Jacobians or noise overflow it)");
    // Everything that may allocate comes first, and the filter is unchanged if it throws: the
    // slot list's room (doubling), the storage (which only grows), then the id's entry in the
    // index (the last thing that can fail).
    slots_.reserveOne();
    ensureCapacity(dim() + L);
    const int off = activeDim();  // where the new block ends up
    int at = off;                 // where it is written
    // Compressed: the new landmark joins the active part, at its end. If the first passive
    // landmark has its size, the new block is written at the end of the state and the two
    // are exchanged (O(n) moves); otherwise the passive part moves down to make room (O(n^2)).
    std::size_t exchange_with = 0;
    bool exchange = false;
    if (compressed()) {
      compression_->stageExtend(J_l_x.data(), L);
      exchange_with = activeSlotCount();
      exchange = exchange_with < slots_.slots().size() && slots_[exchange_with].dim == L;
      if (exchange) {
        at = dim();
        slots_.append(LandmarkSlot{id, typeIndexOf<Landmark>(), at, L});
        // From here on nothing can fail.
        cov_.setDim(dim() + L);
        cov_.stored().block(at, off, L, at - off).setZero();  // against the passive part: zero
      } else {
        slots_.insertAt(exchange_with, LandmarkSlot{id, typeIndexOf<Landmark>(), off, L});
        // From here on nothing can fail.
        insertRows(off, L);
      }
      compression_->commitExtend();
    } else {
      slots_.append(LandmarkSlot{id, typeIndexOf<Landmark>(), off, L});
      cov_.setDim(dim() + L);
    }
    // From here on nothing can fail.
    mean_.template segment<L>(at) = l;
    detail::normalize<Landmark>(mean_.template segment<L>(at));
    first_.template segment<L>(at) = mean_.template segment<L>(at);
    ideal_.template segment<L>(at).setConstant(std::numeric_limits<double>::quiet_NaN());
    // New rows (lower storage): [J_l_x P_rr, J_l_x P_rm]    (eq. 2.39, bottom row)
    cov_.stored().template block<L, kRobotDim>(at, 0) = J_P_rr;
    if (m > 0) cov_.stored().block(at, kRobotDim, L, m) = J_P_rm;
    cov_.stored().template block<L, L>(at, at) = P_ll;
    if (exchange) {
      for (VectorXd* v : {&mean_, &first_, &ideal_}) {
        auto block = v->template segment<L>(off);
        auto other = v->template segment<L>(at);
        block.swap(other);
      }
      cov_.swapBlocks(off, at, L);
      slots_.swapPositions(exchange_with, slots_.slots().size() - 1);
    }
  }

  /// Removes landmark `id`: its rows and columns leave the state. O(n^2) (moves). With the
  /// compressed EKF, removing an active landmark costs a global update first.
  void remove(Id id) {
    revision_ = detail::nextRevision();
    const std::size_t k = slotIndex(id);
    const LandmarkSlot s = slots_[k];
    const bool active = compressed() && s.offset < compression_->activeDim();
    if (active) {
      // The passive part's accumulators refer to this block's stored cross-covariances: a
      // global update first. The smaller region is staged before it, so that a failed
      // allocation in either leaves every stored number as it was.
      compression_->stageBegin(compression_->activeDim() - s.dim);
      synchronize();
    }
    // From here on nothing can fail.
    eraseBlock(s.offset, s.dim);
    slots_.erase(k);
    if (active) compression_->commitBegin();
  }

  /// Changes the parametrization of landmark `id` from `Conversion::From` to
  /// `Conversion::To`. The conversion maps (robot, landmark) to the new landmark with
  /// Jacobians J_to_x and J_to_l; the covariance is carried through them:
  ///   P_new,c = J_to_x P_r,c + J_to_l P_l,c   for every other block c,
  ///   P_new,new = [J_to_x J_to_l] P_(r,l),(r,l) [J_to_x J_to_l]^T.
  /// The landmark keeps its id; its block moves to the end of the state. O(n).
  template <typename Conversion>
  void reparametrize(Id id, const Conversion& conversion) {
    revision_ = detail::nextRevision();
    using From = typename Conversion::From;
    using To = typename Conversion::To;
    static_assert(kHolds<From> && kHolds<To>,
                  "both parametrizations of the conversion must be in the filter's Landmarks... list");
    static_assert(detail::kRobotFits<detail::ConversionRobotT<Conversion, Robot>, Robot>,
                  "the conversion is written for another robot (or for a pose view this robot does not expose)");
    const LandmarkSlot s = typedSlot<From>(id, Conversion::kName);
    Mat<To::kDim, kRobotStateDim> J_x;
    Mat<To::kDim, From::kDim> J_l;
    const Vec<From::kDim> from_mean = currentMean<From::kDim>(s.offset);
    const Vec<To::kDim> new_mean = detail::throughRobotView<detail::ConversionRobotT<Conversion, Robot>, Robot>(
        robotMean(), J_x, [&](const auto& view, auto& J_view) { return conversion(view, from_mean, J_view, J_l); });
    replaceBlock<From, To>(s, new_mean, detail::onTangent<Robot>(J_x, robotMean()), J_l, Mat<To::kDim, To::kDim>::Zero(),
                           Conversion::kName);
  }

  /// A conversion that also takes a fresh measurement `z` with noise `noise` (XYZ -> XYZ-R:
  /// the radius comes from the tree's width in the image, thesis Sec. 3.3). The conversion
  /// returns J_to_z as well, and the new block's covariance gains J_to_z R J_to_z^T; z is
  /// independent of the state, so the cross-covariances are those of the plain overload.
  template <typename Conversion>
  void reparametrize(Id id,
                     const Conversion& conversion,
                     const Vec<Conversion::kMeasurementDim>& z,
                     const Gaussian<Conversion::kMeasurementDim>& noise) {
    revision_ = detail::nextRevision();
    using From = typename Conversion::From;
    using To = typename Conversion::To;
    constexpr int Z = Conversion::kMeasurementDim;
    static_assert(kHolds<From> && kHolds<To>,
                  "both parametrizations of the conversion must be in the filter's Landmarks... list");
    static_assert(detail::kRobotFits<detail::ConversionRobotT<Conversion, Robot>, Robot>,
                  "the conversion is written for another robot (or for a pose view this robot does not expose)");
    const LandmarkSlot s = typedSlot<From>(id, Conversion::kName);
    if (!z.allFinite()) fail(ErrorCode::kNonFinite, std::string(Conversion::kName) + ": measurement is not finite");
    Mat<To::kDim, kRobotStateDim> J_x;
    Mat<To::kDim, From::kDim> J_l;
    Mat<To::kDim, Z> J_z;
    const Vec<From::kDim> from_mean = currentMean<From::kDim>(s.offset);
    const Vec<To::kDim> new_mean = detail::throughRobotView<detail::ConversionRobotT<Conversion, Robot>, Robot>(
        robotMean(), J_x, [&](const auto& view, auto& J_view) { return conversion(view, from_mean, z, J_view, J_l, J_z); });
    if (!J_z.allFinite())
      fail(ErrorCode::kNonFinite, std::string(Conversion::kName) + ": conversion is not finite");
    const Mat<To::kDim, To::kDim> added = J_z * noise.covariance() * J_z.transpose();
    replaceBlock<From, To>(s, new_mean, detail::onTangent<Robot>(J_x, robotMean()), J_l, added, Conversion::kName);
  }

 private:
  /// "the filter's robot is R and its landmark types are A B ...", for refusals.
  static std::string typesNamed() {
    return std::string("the filter's robot is ") + Robot::kName + " and its landmark types are" +
           ((std::string(" ") + Landmarks_::kName) + ...);
  }

  /// Gauss-Newton iterations of a batched update (LinearizationPoint::kIterated; Bell and
  /// Cathey 1993): with the prior x and the Jacobians H_i at the iterate x_i,
  ///   x_{i+1} = x + K_i (z - h(x_i) - H_i (x - x_i)),   K_i = P H_i^T (H_i P H_i^T + R)^-1,
  /// on the blocks the observations see (the robot and their landmarks: nothing else enters
  /// h). On return `lins`, `nu`, `PHt` and the factor of S belong to the last iterate, so the
  /// ordinary gain step adds K_N (z - h(x_N) - H_N (x - x_N)) to the prior and updates P with
  /// K_N and H_N. Stops after `iterated_.max_iterations` linearizations, or once no coordinate
  /// of those blocks moved by more than `iterated_.tolerance` of its prior standard deviation.
  /// Nothing of the filter is written here, so an error leaves it unchanged.
  template <typename Model, typename ObservationRange, typename Lins, typename Nu, typename PHtMap, typename Llt,
            typename Relinearized>
  void iterateBatch(const Model& model, const ObservationRange& observations, Lins& lins, Nu& nu, const PHtMap& PHt,
                    Llt& llt, Relinearized&& relinearized) {
    using Landmark = typename Model::Landmark;
    constexpr int M = Model::kDim;
    constexpr int L = Landmark::kDim;
    const int k = static_cast<int>(std::size(observations));
    auto v = batch_.vector(Workspace::kWhitenedInnovation, k * M);
    auto landmark_iterates = batch_.vector(Workspace::kIterates, k * L);
    const RobotState robot_prior = robotMean();
    RobotState robot_iterate = robot_prior;
    for (int a = 0; a < k; ++a) landmark_iterates.template segment<L>(a * L) = mean_.template segment<L>(lins.offset(a));
    const auto sigma = [&](int j) { return std::max(std::sqrt(std::max(cov_(j, j), 0.0)), 1e-300); };
    for (int iteration = 1; iteration < iterated_.max_iterations; ++iteration) {
      // The next iterate on the blocks the observations see: prior + K_i nu_i.
      v = nu;
      llt.solveInPlace(v);
      const RobotState robot_next =
          detail::robotPlus<Robot>(robot_prior, Vec<kRobotDim>(PHt.template topRows<kRobotDim>() * v));
      double step = 0.0;
      const Vec<kRobotDim> robot_step = detail::robotMinus<Robot>(robot_next, robot_iterate);
      for (int j = 0; j < kRobotDim; ++j) step = std::max(step, std::abs(robot_step[j]) / sigma(j));
      for (int a = 0; a < k; ++a) {
        const int off = lins.offset(a);
        Vec<L> next = mean_.template segment<L>(off) + PHt.template middleRows<L>(off) * v;
        detail::normalize<Landmark>(next);
        const Vec<L> landmark_step = detail::difference<Landmark>(next, Vec<L>(landmark_iterates.template segment<L>(a * L)));
        for (int j = 0; j < L; ++j) step = std::max(step, std::abs(landmark_step[j]) / sigma(off + j));
        landmark_iterates.template segment<L>(a * L) = next;
      }
      robot_iterate = robot_next;
      // Relinearize there: nu_i = z - h(x_i) - H_i (x - x_i).
      int i = 0;
      for (const Observation<Model>& obs : observations) {
        const Vec<L> landmark = landmark_iterates.template segment<L>(i * L);
        const Linearization<Model, kRobotDim> lin = linearizeAt(model, obs.id, robot_iterate, landmark);
        lins.store(i, lin);
        const Vec<L> prior = mean_.template segment<L>(lin.landmark_offset);
        // (On a manifold J_z_x is taken at the iterate, so the prior is read in its tangent.)
        Vec<kRobotDim> robot_offset;
        if constexpr (kRobotOnManifold) {
          robot_offset = -Robot::minus(robot_prior, robot_iterate);
        } else {
          robot_offset = detail::difference<Robot>(robot_iterate, robot_prior);
        }
        nu.template segment<M>(i * M) = detail::residual(model, obs.z, lin.z_hat) + lin.J_z_x * robot_offset +
                                        lin.J_z_l * detail::difference<Landmark>(landmark, prior);
        ++i;
      }
      if (!nu.allFinite()) fail(ErrorCode::kNonFinite, nameOf<Model>() + ": innovation is not finite at an iterate");
      relinearized();
      if (step < iterated_.tolerance) break;
    }
  }

  /// h and its two Jacobians at the given robot and landmark state.
  template <typename Model>
  Linearization<Model, kRobotDim> linearizeAt(const Model& model, Id id, const RobotState& robot,
                                   const Vec<Model::Landmark::kDim>& landmark) const {
    Linearization<Model, kRobotDim> lin;
    lin.landmark_offset = typedSlot<typename Model::Landmark>(id, Model::kName).offset;
    lin.z_hat = evaluateWithJacobians(model, robot, landmark, lin);
    if (!lin.z_hat.allFinite() || !lin.J_z_x.allFinite() || !lin.J_z_l.allFinite())
      fail(ErrorCode::kNonFinite, nameOf<Model>() + ": prediction or Jacobian is not finite for landmark " +
                                      std::to_string(id) + " at an iterate");
    return lin;
  }

  /// h at (robot, landmark), with lin.J_z_x (w.r.t. the robot's rows of the state: on a
  /// manifold, its tangent at `robot`) and lin.J_z_l.
  template <typename Model, typename Lin>
  Vec<Model::kDim> evaluateWithJacobians(const Model& model, const RobotState& robot,
                                         const Vec<Model::Landmark::kDim>& landmark, Lin& lin) const {
    if constexpr (kRobotOnManifold) {
      Mat<Model::kDim, kRobotStateDim> J_state;
      const Vec<Model::kDim> z = detail::evaluateOn<Robot>(model, robot, landmark, J_state, lin.J_z_l);
      lin.J_z_x = J_state * Robot::plusJacobian(robot);
      return z;
    } else {
      return detail::evaluateOn<Robot>(model, robot, landmark, lin.J_z_x, lin.J_z_l);
    }
  }

  /// Throws kDegenerateGeometry when a model declares that `z` is no measurement it can make
  /// (`measurementViolation`: TreeWidth's width <= 0), naming measurement `index` of the
  /// `batch` ("batch", "sequence") if there is one. Builds no string unless it throws.
  template <typename Model>
  static void checkMeasurement(const Model& model, const Vec<Model::kDim>& z, const char* batch = nullptr,
                               int index = 0) {
    (void)model;
    if constexpr (detail::HasMeasurementDomain<Model>::value) {
      if (const char* why = Model::measurementViolation(z)) {
        std::ostringstream os;
        os << nameOf<Model>() << ": ";
        if (batch != nullptr) os << "measurement " << index << " of the " << batch << ": ";
        os << why << ", got z = [" << z.transpose() << "]";
        fail(ErrorCode::kDegenerateGeometry, os.str());
      }
    } else {
      (void)z;
      (void)batch;
      (void)index;
    }
  }

  /// Throws kOutOfDomain when a robot state is off the robot's manifold (a robot type that
  /// declares `domainViolation`, OnManifold's unit quaternion).
  static void checkRobotDomain(const RobotState& x, const char* what) {
    if constexpr (detail::HasDomain<Robot>::value) {
      if (const char* why = Robot::domainViolation(x)) fail(ErrorCode::kOutOfDomain, std::string(what) + ": " + why);
    } else {
      (void)x;
      (void)what;
    }
  }

  /// `update(model, observations, Fusion::kSequential)`: checks ids, types and measurements
  /// of all, then fuses them one by one.
  template <typename Model, typename ObservationRange>
  void updateSequentially(const Model& model, const ObservationRange& observations) {
    int i = 0;
    for (const Observation<Model>& obs : observations) {
      if (!obs.z.allFinite())
        fail(ErrorCode::kNonFinite, nameOf<Model>() + ": measurement " + std::to_string(i) +
                                        " of the sequence is not finite");
      checkMeasurement(model, obs.z, "sequence", i);
      typedSlot<typename Model::Landmark>(obs.id, Model::kName);
      ++i;
    }
    i = 0;
    for (const Observation<Model>& obs : observations) {
      try {
        update(model, obs.id, obs.z, obs.noise);
      } catch (const Error& e) {
        std::string why = e.what();
        const std::string prefix = std::string("sylva: ") + toString(e.code()) + ": ";
        if (why.compare(0, prefix.size(), prefix) == 0) why.erase(0, prefix.size());
        fail(e.code(), "sequential update stopped at observation " + std::to_string(i) + " (the " +
                           std::to_string(i) + " before it stay fused): " + why);
      }
      ++i;
    }
  }

  /// visit: f for the type with index `type_index`, found by a compile-time walk of Landmarks....
  template <std::size_t I, typename F>
  static decltype(auto) visitType(int type_index, F& f) {
    using Landmark = std::tuple_element_t<I, std::tuple<Landmarks_...>>;
    if constexpr (I + 1 < sizeof...(Landmarks_)) {
      if (type_index != static_cast<int>(I)) return visitType<I + 1>(type_index, f);
    }
    return f(LandmarkTag<Landmark>{});
  }

  // ---------------------------------------------------------------- checks

  template <typename Model>
  static constexpr void checkModel() {
    static_assert(Model::kDim > 0, "Measurement model must define `static constexpr int kDim` > 0");
    static_assert(detail::kRobotFits<typename Model::Robot, Robot>,
                  "Measurement model's `Robot` type is neither the filter's robot nor a base of it");
    static_assert(kHolds<typename Model::Landmark>,
                  "Measurement model's `Landmark` type is not in the filter's Landmarks... list");
  }

  template <typename T>
  static std::string nameOf() {
    return std::string(T::kName);
  }

  std::size_t slotIndex(Id id) const {
    return slots_.indexOf(id);
  }

  template <typename Landmark>
  const LandmarkSlot& typedSlot(Id id, const char* who) const {
    const LandmarkSlot& s = slots_[slotIndex(id)];
    if (s.type_index != typeIndexOf<Landmark>())
      fail(ErrorCode::kWrongLandmarkType, std::string(who) + ": landmark " + std::to_string(id) + " is a " +
                                              typeName(s.type_index) + ", not a " + Landmark::kName);
    return s;
  }

  /// The true robot state handed over for kIdeal (kInvalidArgument naming `who` if none is).
  const RobotState& idealRobot(const char* who) const {
    const RobotState& x = robot_ideal_;
    if (!x.allFinite())
      fail(ErrorCode::kInvalidArgument,
           std::string(who) + ": ideal linearization needs the robot's true state (setIdealRobot), and none was "
                              "handed over since the last predict");
    return x;
  }

  // ---------------------------------------------------------------- compressed EKF

  /// While alive, the covariance's dimension is `rows`, the compressed EKF's active part:
  /// the kernels of predict and update then work on P_AA alone (A leads the state). With
  /// compression off, rows = dim() and nothing changes.
  class ActiveWindow {
   public:
    ActiveWindow(detail::LowerCovariance<Deferral>& cov, int rows) : cov_(cov), full_(cov.dim()) { cov.setDim(rows); }
    ~ActiveWindow() { cov_.setDim(full_); }
    ActiveWindow(const ActiveWindow&) = delete;
    ActiveWindow& operator=(const ActiveWindow&) = delete;

   private:
    detail::LowerCovariance<Deferral>& cov_;
    int full_;
  };

  /// True while the stored passive part is stale (local steps since the last global update).
  bool pending() const { return compressed() && compression_->steps() > 0; }

  /// The landmarks of the active part (they lead `slots()`).
  std::size_t activeSlotCount() const {
    const auto& all = slots_.slots();
    const int a = activeDim();
    return static_cast<std::size_t>(
        std::partition_point(all.begin(), all.end(), [a](const LandmarkSlot& s) { return s.offset < a; }) -
        all.begin());
  }

  /// The current mean of the L rows at `offset` (a landmark block): stored, or for a passive
  /// block between global updates corrected by the compressed EKF.
  template <int L>
  Vec<L> currentMean(int offset) const {
    Vec<L> out = mean_.template segment<L>(offset);
    if (pending() && offset >= compression_->activeDim()) compression_->correctMean(*this, offset, L, out.data());
    return out;
  }

  /// The current R x C block of P at (row, col), each of them the start of the robot's or a
  /// landmark's block: stored, or corrected by the compressed EKF where it involves the
  /// passive part between global updates (O(a^2) then).
  template <int R, int C>
  Mat<R, C> currentBlock(int row, int col) const {
    if (!pending() || std::max(row, col) < compression_->activeDim()) return cov_.template block<R, C>(row, col);
    Mat<R, C> out;
    compression_->currentBlock(*this, row, col, R, C, out.data());
    return out;
  }

  /// Compressed: if any landmark `idOf(e)` of `range` is passive, enters a new region that
  /// holds them (a global update, the selector asked again). Returns true if the state was
  /// reordered. Changes no estimate. Unknown ids are left to the caller's own checks.
  template <typename Range, typename IdOf>
  bool ensureActive(const Range& range, const IdOf& idOf) {
    if (!compressed()) return false;
    const int a = compression_->activeDim();
    bool any = false;
    for (const auto& e : range) {
      const LandmarkSlot* s = slots_.find(idOf(e));
      if (s != nullptr && s->offset >= a) any = true;
    }
    if (!any) return false;
    std::vector<Id> forced;
    forced.reserve(std::size(range));
    for (const auto& e : range) forced.push_back(idOf(e));
    compression_->enterRegion(*this, forced.data(), forced.size());
    return true;
  }

  // ---------------------------------------------------------------- reparametrization

  /// Replaces slot `s` (type From) by a block of type To with mean `new_mean`, carrying the
  /// covariance through [J_x J_l] and adding `added` to the new diagonal block.
  template <typename From, typename To>
  void replaceBlock(const LandmarkSlot s,
                    const Vec<To::kDim>& new_mean,
                    const Mat<To::kDim, kRobotDim>& J_x,
                    const Mat<To::kDim, From::kDim>& J_l,
                    const Mat<To::kDim, To::kDim>& added,
                    const char* who) {
    constexpr int Lf = From::kDim;
    constexpr int Lt = To::kDim;
    if (!new_mean.allFinite() || !J_x.allFinite() || !J_l.allFinite() || !added.allFinite())
      fail(ErrorCode::kNonFinite, std::string(who) + ": conversion is not finite");
    if constexpr (detail::HasDomain<To>::value) {
      if (const char* why = To::domainViolation(new_mean))
        fail(ErrorCode::kOutOfDomain, std::string(who) + ": landmark " + std::to_string(s.id) + ": " + why);
    }
    bool into_active = false;
    if (compressed()) {
      synchronize();  // the cross-covariances below read the whole state
      into_active = s.offset < compression_->activeDim();
    }
    const std::size_t k = slotIndex(s.id);
    // New block rows against every other column of the state, before anything moves.
    const int rest = dim() - Lf;  // dimension of the state without the old block
    MatrixXd cross(Lt, rest);  // allocation: reparametrization is not a hot path
    for (int c = 0, dest = 0; c < dim(); ++c) {
      if (c >= s.offset && c < s.offset + Lf) continue;
      Vec<kRobotDim> p_rc;
      for (int r = 0; r < kRobotDim; ++r) p_rc[r] = cov_(r, c);
      Vec<Lf> p_lc;
      for (int r = 0; r < Lf; ++r) p_lc[r] = cov_(s.offset + r, c);
      cross.col(dest++) = J_x * p_rc + J_l * p_lc;
    }
    Mat<Lt, kRobotDim + Lf> J;
    J << J_x, J_l;
    Mat<kRobotDim + Lf, kRobotDim + Lf> P_joint;
    P_joint << cov_.template block<kRobotDim, kRobotDim>(0, 0), cov_.template block<kRobotDim, Lf>(0, s.offset),
        cov_.template block<Lf, kRobotDim>(s.offset, 0), cov_.template block<Lf, Lf>(s.offset, s.offset);
    Mat<Lt, Lt> P_new = J * P_joint * J.transpose() + added;
    P_new = (0.5 * (P_new + P_new.transpose())).eval();
    if (Lt > Lf) ensureCapacity(dim() - Lf + Lt);
    // The new block goes to the end of the state, or (compressed) an active landmark's to the
    // end of the active part, which it stays in.
    const int off = into_active ? compression_->activeDim() - Lf : rest;
    const std::size_t index = into_active ? activeSlotCount() - 1 : static_cast<std::size_t>(slots_.size() - 1);
    if (into_active) compression_->stageBegin(compression_->activeDim() - Lf + Lt);
    // From here on nothing can fail.
    eraseBlock(s.offset, Lf);
    insertRows(off, Lt);
    mean_.template segment<Lt>(off) = new_mean;
    detail::normalize<To>(mean_.template segment<Lt>(off));
    first_.template segment<Lt>(off) = mean_.template segment<Lt>(off);  // a new first estimate
    ideal_.template segment<Lt>(off).setConstant(std::numeric_limits<double>::quiet_NaN());
    cov_.stored().block(off, 0, Lt, off) = cross.leftCols(off);
    cov_.stored().block(off + Lt, off, rest - off, Lt) = cross.rightCols(rest - off).transpose();
    cov_.stored().template block<Lt, Lt>(off, off) = P_new;
    slots_.moveTo(k, LandmarkSlot{s.id, typeIndexOf<To>(), off, Lt}, index);
    if (into_active) compression_->commitBegin();
  }

  // ---------------------------------------------------------------- storage

  void ensureCapacity(int needed) {
    if (needed <= cov_.capacity()) return;
    const int capacity = std::max(needed, 2 * cov_.capacity());
    // Everything is allocated before anything is swapped in.
    VectorXd mean = VectorXd::Zero(capacity);
    VectorXd first = VectorXd::Zero(capacity);
    VectorXd ideal = VectorXd::Constant(capacity, std::numeric_limits<double>::quiet_NaN());
    MatrixXd cov = cov_.grown(capacity);
    const int n = dim();
    mean.head(n) = mean_.head(n);
    first.head(n) = first_.head(n);
    ideal.head(n) = ideal_.head(n);
    mean_.swap(mean);
    first_.swap(first);
    ideal_.swap(ideal);
    cov_.adopt(cov);
  }

  /// Opens d rows and columns at `off` in the means and the covariance (zero covariance;
  /// capacity for them reserved). Cannot fail.
  void insertRows(int off, int d) {
    const int tail = dim() - off;
    for (VectorXd* v : {&mean_, &first_, &ideal_}) std::copy_backward(v->data() + off, v->data() + off + tail, v->data() + off + tail + d);
    cov_.insert(off, d);
  }

  /// Deletes rows and columns [off, off + d) from the means and the covariance.
  void eraseBlock(int off, int d) {
    const int tail = dim() - off - d;
    if (tail > 0) {
      // Moved down in place (std::copy runs forwards, so an overlap is safe): no temporary,
      // so nothing here can fail.
      for (VectorXd* v : {&mean_, &first_, &ideal_}) std::copy(v->data() + off + d, v->data() + off + d + tail, v->data() + off);
    }
    cov_.erase(off, d);
  }

  /// Workspace view of dim() x cols doubles (cols = M or `dynamic_cols` if M is Dynamic).
  /// Grows only when a larger state or batch is seen.
  template <int M>
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, M>> workspaceMatrix(int dynamic_cols) {
    const int cols = M == Eigen::Dynamic ? dynamic_cols : M;
    const Eigen::Index needed = static_cast<Eigen::Index>(dim()) * cols;
    detail::growWorkspace(workspace_a_, needed);
    return Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, M>>(workspace_a_.data(), dim(), cols);
  }

  /// The update's blocks of H, as stored in the batch workspace (detail::BatchLinearizations),
  /// for the compressed EKF.
  detail::CompressedUpdateTerms updateBlocks(int count, int m, int landmark_dim) const {
    detail::CompressedUpdateTerms t{};
    t.lins = batch_.lins.data();
    t.offsets = batch_.offsets.data();
    t.count = count;
    t.m = m;
    t.landmark_dim = landmark_dim;
    return t;
  }

  /// Applies the gain for P H^T (n x M, overwritten), the Cholesky factor of S, the
  /// innovation, R and (for the compressed EKF) the blocks of H. `applyHt(A, out)` writes out = A H^T for an n x n matrix A (needed by
  /// the Joseph form).
  template <int M, typename PHtMap, typename Llt, typename Nu, typename RMat, typename ApplyHt>
  void applyGain(PHtMap& PHt, const Llt& llt, const Nu& nu, const RMat& R, detail::CompressedUpdateTerms blocks,
                 ApplyHt&& applyHt) {
    revision_ = detail::nextRevision();
    auto P = cov_.inUse();
    auto delta = meanIncrement();
    const auto gain = UpdateForm::template increment<M>(PHt, llt, nu, batch_, delta, parallel_);
    toInvariantIncrement(delta);
    prepareGaugeTransport(delta);
    checkPosteriorDomain(delta);  // may throw; nothing of the filter is written yet
    constexpr bool kJoseph = std::is_same_v<UpdateForm, JosephUpdate>;
    if (compressed()) {
      // The passive part's share of this update, into the region's workspaces (may allocate).
      blocks.factor = llt.matrixLLT().data();
      blocks.factor_stride = llt.matrixLLT().outerStride();
      blocks.nu = nu.data();
      blocks.gain = gain.data();
      blocks.gain_is_k = kJoseph;
      compression_->stageUpdate(*this, blocks);
    }
    if constexpr (kJoseph) {
      const auto A = JosephUpdate::posterior<M>(P, gain, PHt, R, batch_, std::forward<ApplyHt>(applyHt));  // may allocate
      applyMeanIncrement(delta);
      P.template triangularView<Eigen::Lower>() = A;
    } else {
      (void)R;
      applyMeanIncrement(delta);
      SymmetricUpdate::downdate<M>(P, gain, parallel_);
    }
    if (compressed()) compression_->commitUpdate(*this);
    carryCovarianceToPosterior();
    carryCovarianceAlongGauge();
    normalizeAll();
  }

  // ---------------------------------------------------------------- invariant EKF

  /// LinearizationPoint::kInvariant, before the mean is written: turns the additive
  /// correction `delta` into the increment of the group's exponential, for the robot's
  /// position and each landmark's (detail::InvariantTransport::retract). Grows its workspace
  /// before the caller writes anything. A no-op in every other mode.
  template <typename Delta>
  void toInvariantIncrement(Delta& delta) {
    if constexpr (kInvariantApplies) {
      if (linearization_ != LinearizationPoint::kInvariant) return;
      invariant_.begin(dim(), delta[Robot::kPlanarHeading]);
      invariant_.retract(delta, Robot::kPlanarPosition, robot_mean_.template segment<2>(Robot::kPlanarPosition));
      constexpr int kPositions[] = {Landmarks_::kPlanarPosition...};
      for (const LandmarkSlot& s : slots_.slots()) {
        const int o = s.offset + kPositions[s.type_index];
        invariant_.retract(delta, o, mean_.template segment<2>(o));
      }
    } else {
      (void)delta;
    }
  }

  /// LinearizationPoint::kInvariant, after the covariance update: P <- M P M^T
  /// (detail::InvariantTransport::carry).
  void carryCovarianceToPosterior() {
    if constexpr (kInvariantApplies) {
      if (linearization_ != LinearizationPoint::kInvariant) return;
      invariant_.carry(cov_, dim(), Robot::kPlanarHeading);
    }
  }

  // ---------------------------------------------------------------- observability constrained

  /// Writes N(x)^T for x = mean_ + scale * delta into `Nt`, block by block.
  template <typename Delta, typename Out>
  void fillGaugeDirections(const Delta& delta, double scale, Out& Nt) const {
    if constexpr (kRobotOnManifold) {
      const RobotState x = Robot::plus(robot_mean_, scale * delta.template head<kRobotDim>());
      Nt.template leftCols<kRobotDim>() = (Robot::minusJacobian(x) * robot_.gaugeDirections(x)).transpose();
    } else {
      const RobotState x = robot_mean_ + scale * delta.template head<kRobotDim>();
      Nt.template leftCols<kRobotDim>() = robot_.gaugeDirections(x).transpose();
    }
    for (const LandmarkSlot& s : slots_.slots()) fillSlotGauge(s, delta, scale, Nt, std::index_sequence_for<Landmarks_...>());
  }

  template <typename Delta, typename Out, std::size_t... I>
  void fillSlotGauge(const LandmarkSlot& s, const Delta& delta, double scale, Out& Nt, std::index_sequence<I...>) const {
    ((s.type_index == static_cast<int>(I)
          ? void(Nt.template middleCols<Landmarks_::kDim>(s.offset) =
                     Landmarks_::gaugeDirections(Vec<Landmarks_::kDim>(
                                                     mean_.template segment<Landmarks_::kDim>(s.offset) +
                                                     scale * delta.template segment<Landmarks_::kDim>(s.offset)))
                         .transpose())
          : void()),
     ...);
  }

  /// LinearizationPoint::kObservabilityConstrained, before the mean is written: the gauge
  /// directions at x- and x+ = x- + delta, and the transport's left inverse
  /// (detail::GaugeTransport::prepare). Grows its workspace before the caller writes anything.
  /// A no-op in every other mode.
  template <typename Delta>
  void prepareGaugeTransport(const Delta& delta) {
    gauge_.cancel();
    if constexpr (kObservabilityConstrainedApplies) {
      if (linearization_ != LinearizationPoint::kObservabilityConstrained) return;
      gauge_.prepare(dim(), gauge_inverse_choice_,
                     [&](double scale, auto& Nt) { fillGaugeDirections(delta, scale, Nt); });
    } else {
      (void)delta;
    }
  }

  /// LinearizationPoint::kObservabilityConstrained, after the covariance update: P <- T P T^T
  /// (detail::GaugeTransport::carry), where `prepareGaugeTransport` found a transport.
  void carryCovarianceAlongGauge() {
    if constexpr (kObservabilityConstrainedApplies) {  // else nothing to carry, and nothing compiled
      gauge_.carry(cov_.stored(), dim(), cov_.template block<kRobotDim, kRobotDim>(0, 0));
    }
  }

  /// mean (+)= delta: the robot through its `plus` on a manifold, every other block added.
  template <typename Delta>
  void applyMeanIncrement(const Delta& delta) {
    if constexpr (kRobotOnManifold) {
      robot_mean_ = Robot::plus(robot_mean_, delta.template head<kRobotDim>());
    } else {
      robot_mean_ += delta.template head<kRobotDim>();
    }
    mean_.segment(kRobotDim, dim() - kRobotDim) += delta.tail(dim() - kRobotDim);
  }

  /// Workspace for the mean increment of an update (grows only with the state).
  Eigen::Map<VectorXd> meanIncrement() {
    detail::growWorkspace(delta_, dim());
    return Eigen::Map<VectorXd>(delta_.data(), dim());
  }

  /// Throws kOutOfDomain if mean + delta would leave the domain of a landmark whose type
  /// declares one (see detail::HasDomain). O(n); a no-op without such types.
  template <typename Delta>
  void checkPosteriorDomain(const Delta& delta) const {
    constexpr bool any = (detail::HasDomain<Landmarks_>::value || ...);
    if constexpr (any) {
      for (const LandmarkSlot& s : slots_.slots())
        if (s.offset < delta.size()) checkSlotDomain(s, delta, std::index_sequence_for<Landmarks_...>());
    }
  }

  template <typename Delta, std::size_t... I>
  void checkSlotDomain(const LandmarkSlot& s, const Delta& delta, std::index_sequence<I...>) const {
    (checkSlotDomainAs<Landmarks_>(s, delta, static_cast<int>(I)), ...);
  }

  template <typename Landmark, typename Delta>
  void checkSlotDomainAs(const LandmarkSlot& s, const Delta& delta, int type_index) const {
    if constexpr (detail::HasDomain<Landmark>::value) {
      if (s.type_index != type_index) return;
      constexpr int L = Landmark::kDim;
      const Vec<L> posterior =
          mean_.template segment<L>(s.offset) + delta.template segment<L>(s.offset);
      if (const char* why = Landmark::domainViolation(posterior)) {
        fail(ErrorCode::kOutOfDomain, std::string("update rejected: ") + Landmark::kName + " " +
                                          std::to_string(s.id) + ": " + why);
      }
    } else {
      (void)s;
      (void)delta;
      (void)type_index;
    }
  }

  /// Wraps angles etc. of the robot and of every landmark type that defines `normalize`.
  /// A robot that also defines `normalizationJacobian(x)` (the camera's quaternion
  /// renormalization) has its covariance carried through that Jacobian as well.
  void normalizeAll() {
    if constexpr (kRobotOnManifold) {
      // `plus` keeps the robot on its manifold: nothing to renormalize.
    } else if constexpr (detail::HasNormalizationJacobian<Robot>::value) {
      const Mat<kRobotDim, kRobotDim> N = Robot::normalizationJacobian(robotMean());
      detail::normalize<Robot>(robot_mean_);
      cov_.template transformRobotBlock<kRobotDim>(N, RobotCovariance(N * robotCovariance() * N.transpose()));
      if (compressed()) compression_->predictRobot(N.data());  // a linear map of the robot's rows
    } else {
      detail::normalize<Robot>(robot_mean_);
    }
    constexpr bool any = (detail::HasNormalize<Landmarks_>::value || ...);
    if constexpr (any) {
      // Within the update's rows (the compressed EKF's active part; all of them otherwise).
      for (const LandmarkSlot& s : slots_.slots())
        if (s.offset < dim()) normalizeSlot(s, std::index_sequence_for<Landmarks_...>());
    }
  }

  template <std::size_t... I>
  void normalizeSlot(const LandmarkSlot& s, std::index_sequence<I...>) {
    ((s.type_index == static_cast<int>(I)
          ? detail::normalize<Landmarks_>(mean_.template segment<Landmarks_::kDim>(s.offset))
          : void()),
     ...);
  }

  Robot robot_;
  /// The robot's mean, its linearization point for kFirstEstimates (its latest prediction) and
  /// for kIdeal (the true state handed over, NaN after each predict).
  RobotState robot_mean_;
  RobotState robot_first_;
  RobotState robot_ideal_;
  /// The landmarks' means, laid out as the covariance's rows (the robot's first kRobotDim
  /// entries are unused: the robot's mean is robot_mean_).
  std::uint64_t revision_ = 0;  ///< see revision()
  VectorXd mean_;
  /// Linearization points for kFirstEstimates, laid out as mean_: each landmark's estimate
  /// when it entered the state.
  VectorXd first_;
  /// Linearization points for kIdeal, laid out as mean_: the true states the caller handed
  /// over, NaN where none is (a new landmark).
  VectorXd ideal_;
  LinearizationPoint linearization_ = LinearizationPoint::kCurrentEstimate;
  IteratedUpdate iterated_;
  Parallel* parallel_ = nullptr;  ///< see setParallel
  detail::LowerCovariance<Deferral> cov_;  ///< the covariance (lower triangle) and the state dimension n
  detail::SlotTable slots_;  ///< where each landmark's block lies
  VectorXd workspace_a_;
  VectorXd delta_;
  detail::InvariantTransport<> invariant_;  ///< the invariant EKF's correction and transport
  detail::GaugeTransport<kRobotDim> gauge_;  ///< the observability-constrained transport
  GaugeInverse gauge_inverse_choice_ = GaugeInverse::kRobot;

  Workspace batch_;

  // The compressed EKF (setCompression; empty: off). Reached only through its hooks, so a
  // program that never compresses compiles none of it.
  detail::ClonePtr<detail::CompressionHooks<BasicEkf>> compression_;
  template <typename>
  friend class detail::Compression;
};

/// The filter with the default covariance update (symmetric form, one triangle).
template <typename Robot, typename... Landmarks>
using Ekf = BasicEkf<SymmetricUpdate, Robot, Landmarks...>;

/// The filter with the Joseph-form covariance update.
template <typename Robot, typename... Landmarks>
using JosephEkf = BasicEkf<JosephUpdate, Robot, Landmarks...>;

}  // namespace sylva
