#pragma once
/// @file
/// The member functions of `sylva::slam::BasicMonocularTreeSlam` (monocular_tree_slam.hpp).
/// Include this file in one translation unit of a program and instantiate the class there;
/// every other file includes monocular_tree_slam.hpp only (see its comment).

#include <chrono>
#include <cmath>
#include <optional>
#include <string>
#include <tuple>
#include <vector>
#include <type_traits>

#include "sylva/consistency/chi_square.hpp"
#include "sylva/slam/monocular_tree_slam.hpp"

namespace sylva::slam {

namespace detail {

/// Adds the seconds between construction and destruction to `*sink` (nothing when null).
class PhaseClock {
 public:
  explicit PhaseClock(double* sink) : sink_(sink) {
    if (sink_ != nullptr) start_ = std::chrono::steady_clock::now();
  }
  ~PhaseClock() {
    if (sink_ != nullptr) *sink_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  PhaseClock(const PhaseClock&) = delete;
  PhaseClock& operator=(const PhaseClock&) = delete;

 private:
  double* sink_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace detail

template <typename Camera>
BasicMonocularTreeSlam<Camera>::BasicMonocularTreeSlam(const TreeSlamOptions& options, const Vec<13>& x0, const Mat<13, 13>& P0)
    : options_(options),
      ekf_(ConstantVelocity3D{options.velocity_frame}.fromWorldVelocity(x0), priorCovariance(x0, P0),
           Camera(ConstantVelocity3D{options.velocity_frame})),
      id_point_(options.camera),
      xyz_point_(options.camera),
      tree_width_(options.camera),
      idr_width_(options.camera),
      init_(options.camera, options.initial_inverse_depth, options.inverse_depth_sigma),
      idr_init_(options.camera, options.initial_inverse_depth, options.inverse_depth_sigma),
      life_(options.camera,
            LinearityIndexBelow{options.linearity_threshold, options.conversion_given_camera},
            PositionSigmaBelow{options.tree_position_sigma_m, options.conversion_given_camera}),
      accel_noise_(Gaussian<6>::sigmas(
          (Vec<6>() << Vec<3>::Constant(options.linear_accel_sigma), Vec<3>::Constant(options.angular_accel_sigma))
              .finished())),
      pixel_noise_(Gaussian<2>::sigmas(Vec<2>::Constant(options.pixel_sigma_px))),
      tree_noise_(Gaussian<3>::sigmas(Vec<3>(options.pixel_sigma_px, options.pixel_sigma_px, options.width_sigma_px))) {
  if (std::isnan(options.continuity_cost) || !std::isfinite(options.continuity_edge_margin_px)) {
    fail(ErrorCode::kInvalidArgument,
         "TreeSlamOptions: continuity_cost must be a number (infinity turns the continuity test off), got " +
             std::to_string(options.continuity_cost) + ", and continuity_edge_margin_px finite, got " +
             std::to_string(options.continuity_edge_margin_px));
  }
  if (options.loop_pairings < 0 || options.loop_sightings < 0) {
    fail(ErrorCode::kInvalidArgument,
         "TreeSlamOptions: loop_pairings must be >= 0 (0: off), got " + std::to_string(options.loop_pairings) +
             ", and loop_sightings >= 0, got " + std::to_string(options.loop_sightings));
  }
  if (options.unconfirmed_after_frames < 0 || options.confirm_sightings < 1) {
    fail(ErrorCode::kInvalidArgument,
         "TreeSlamOptions: unconfirmed_after_frames must be >= 0 (0: never remove), got " +
             std::to_string(options.unconfirmed_after_frames) + ", and confirm_sightings >= 1, got " +
             std::to_string(options.confirm_sightings));
  }
  ekf_.setLinearizationPoint(options.linearization);
  ekf_.setGaugeInverse(options.gauge_inverse);
  gate_.fill(std::numeric_limits<double>::infinity());
  if (options.gate_probability > 0.0)
    for (int dim = 1; dim <= 3; ++dim) gate_[dim] = chiSquareGate(dim, options.gate_probability);
}

template <typename Camera>
FrameReport BasicMonocularTreeSlam<Camera>::processFrame(double dt,
                                            const std::vector<TrunkSighting>& observations,
                                            const FrameTruth* truth) {
  const bool ideal = options_.linearization == LinearizationPoint::kIdeal;
  if ((ideal || options_.unbiased_point_uv) && (truth == nullptr || truth->trees == nullptr))
    fail(ErrorCode::kInvalidArgument,
         "MonocularTreeSlam::processFrame: ideal linearization and unbiased point measurements are "
         "diagnostics that need the frame's truth (FrameTruth with the trees)");
  if (options_.unbiased_point_uv && (truth->noise_free == nullptr || truth->noise_free->size() != observations.size()))
    fail(ErrorCode::kInvalidArgument,
         "MonocularTreeSlam::processFrame: unbiased point measurements need the noise-free reading of every "
         "sighting (FrameTruth::noise_free)");
  FrameReport report;
  if (profile_ != nullptr) ++profile_->frames;
  {
    detail::PhaseClock clock(profile_ != nullptr ? &profile_->predict_s : nullptr);
    if (ideal) ekf_.setIdealRobot(ekf_.robot().fromWorldVelocity(truth->camera_before));
    ekf_.predict(Vec<0>(), dt, accel_noise_);
    if (ideal) {
      ekf_.setIdealRobot(ekf_.robot().fromWorldVelocity(truth->camera));
      setIdealLandmarks(*truth);
    }
  }

  sightings_.clear();
  for (std::size_t i = 0; i < observations.size(); ++i) {
    const TrunkSighting& o = observations[i];
    Vec<2> uv = o.z.head<2>();
    if (options_.unbiased_point_uv) {
      // The frame's noise on the projection of the true base centre.
      const Vec<3> base = (*truth->trees)[static_cast<std::size_t>(o.id)].head<3>();
      uv += xyz_point_(ConstantVelocity3D::pose(truth->camera), base) - (*truth->noise_free)[i].head<2>();
    }
    sightings_.push_back({o.id, o.z, uv});
  }
  if (options_.association == TrunkAssociation::kNearestNeighbor) associate(sightings_, report);
  fresh_.clear();
  mapped_.clear();
  for (const Seen& s : sightings_) {
    report.landmark_of.push_back(s.id);
    if (s.id >= 0) (ekf_.contains(s.id) ? mapped_ : fresh_).push_back(s);
  }
  {
    // Gating is what fuseMapped spends beyond the updates, which fuse() books themselves.
    const double updates_before =
        profile_ != nullptr ? profile_->point_updates_s + profile_->width_updates_s : 0.0;
    const auto start = std::chrono::steady_clock::now();
    fuseMapped(report);
    if (profile_ != nullptr)
      profile_->gating_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() -
                            (profile_->point_updates_s + profile_->width_updates_s - updates_before);
  }

  std::optional<detail::PhaseClock> reparametrize_clock;
  if (profile_ != nullptr) reparametrize_clock.emplace(&profile_->reparametrize_s);
  report.to_xyz = static_cast<int>(life_.convertInverseDepth(ekf_).size());
  if (options_.pipeline == WidthPipeline::kFromFirstSight)
    report.to_tree += static_cast<int>(life_.convertInverseDepthRadius(ekf_).size());
  if (options_.pipeline == WidthPipeline::kAfterXyz) {
    for (const Seen& s : mapped_) {
      if (!ekf_.template holds<Point3>(s.id)) continue;
      try {
        if (life_.convertToTree(ekf_, s.id, s.z, tree_noise_)) ++report.to_tree;
      } catch (const Error&) {
        ++report.rejected;
      }
    }
  }

  reparametrize_clock.reset();

  detail::PhaseClock add_clock(profile_ != nullptr ? &profile_->add_s : nullptr);
  for (const Seen& s : fresh_) {
    try {
      if (options_.pipeline == WidthPipeline::kFromFirstSight)
        ekf_.add(s.id, idr_init_, idr_init_.measurement(s.z), idr_init_.noise(tree_noise_));
      else
        ekf_.add(s.id, init_, init_.measurement(s.uv), init_.noise(pixel_noise_));
      ++report.added;
      if (ideal) true_anchor_[s.id] = truth->camera.head<3>();
    } catch (const Error&) {
      ++report.rejected;
    }
  }
  if (ideal) setIdealLandmarks(*truth);  // for the landmarks added or converted above
  if (options_.unconfirmed_after_frames > 0) removeUnconfirmed(report);
  ++frame_index_;
  if (options_.association == TrunkAssociation::kNearestNeighbor) {
    if (options_.width_appearance) recordAppearance();
    sighted_last_frame_.clear();
    for (const Seen& s : sightings_)
      if (s.id >= 0) {
        sighted_last_frame_.insert(s.id);
        ++sightings_taken_[s.id];
      }
  }
  return report;
}

template <typename Camera>
typename BasicMonocularTreeSlam<Camera>::NearestPairing BasicMonocularTreeSlam<Camera>::pairNearest(
    const Filter& ekf, const std::vector<Seen>& seen) const {
  struct Pairing {
    double score;  ///< NIS over the pairing gate of its dimension: < 1 passes
    std::size_t sighting;
    std::size_t tree;
  };
  std::array<double, 4> pair_gate{}, new_gate{};
  for (int dim = 2; dim <= 3; ++dim) {
    pair_gate[dim] = chiSquareGate(dim, options_.association_gate_probability);
    new_gate[dim] = chiSquareGate(dim, options_.new_tree_probability);
  }
  std::vector<Pairing> candidates;
  std::vector<Id> trees;
  std::vector<double> closest(seen.size(), kUnpredictable);  // smallest NIS over the new-tree gate
  // The continuity test (TreeSlamOptions::continuity_cost): whether some tree within the
  // new-tree gate explains the sighting at that cost, and which sightings it applies to at any
  // tree, being near the image's left or right edge.
  const double max_cost = options_.continuity_cost;
  std::vector<char> explained(seen.size(), 0);
  std::vector<char> at_edge(seen.size(), 0);
  for (std::size_t i = 0; i < seen.size(); ++i) {
    const double margin = options_.continuity_edge_margin_px;
    const double half_width = 0.5 * seen[i].z[2];
    at_edge[i] = margin >= 0.0 && (seen[i].z[0] - half_width < margin ||
                                   seen[i].z[0] + half_width > options_.camera.width - margin);
  }
  // The loop test (TreeSlamOptions::loop_pairings): each tree's linearization and S, and the
  // pairings with trees of at least loop_sightings sightings that the continuity test refused.
  const bool loops = options_.loop_pairings > 0;
  std::vector<LoopTree> loop_trees;
  std::vector<std::size_t> loop_tree_index;  // loop tree -> its index in `trees`
  std::vector<LoopPairing> refused;
  // Each tree is linearized once, through its own model, and its S factored once.
  for (const LandmarkSlot& slot : ekf.slots()) {
    ekf.visit(slot.id, [&](auto type) {
      const auto& model = modelFor(type);
      using Model = std::decay_t<decltype(model)>;
      constexpr int M = Model::kDim;
      Linearization<Model, Filter::kRobotDim> lin;
      try {
        lin = ekf.linearize(model, slot.id);
      } catch (const Error&) {
        return;  // behind the camera, or otherwise unpredictable
      }
      Mat<M, M> S = ekf.crossCovariance(lin, lin);
      if constexpr (M == 2) {
        S += pixel_noise_.covariance();
      } else {
        S += tree_noise_.covariance();
      }
      S = (0.5 * (S + S.transpose())).eval();
      const Eigen::LLT<Mat<M, M>> llt(S);
      if (llt.info() != Eigen::Success) return;
      const std::size_t j = trees.size();
      trees.push_back(slot.id);
      // The width a point landmark predicts from its last sighting (width_appearance).
      int dof = M;
      double width_hat = 0.0, width_variance = 0.0;
      if constexpr (M == 2) {
        const auto last = appearance_.find(slot.id);
        if (options_.width_appearance && last != appearance_.end()) {
          const double depth = depthOf(ekf, slot.id);
          const double before = last->second.depth_m;
          const double ratio =
              std::isfinite(depth) && std::isfinite(before) && depth > 0.0 && before > 0.0 ? before / depth : 1.0;
          width_hat = last->second.width_px * ratio;
          const double sigma_w = options_.width_sigma_px;
          const double relative = options_.width_appearance_tolerance * width_hat;
          width_variance = sigma_w * sigma_w * (1.0 + ratio * ratio) + relative * relative;
          dof = 3;
        }
      }
      // log det(S R^-1) for the continuity cost, R being the noise of the sighting's [u, v, w]
      // (the width's share of a point landmark: its predicted width's variance over the
      // width noise).
      double log_det_ratio = 0.0;
      for (int r = 0; r < M; ++r) log_det_ratio += 2.0 * std::log(llt.matrixL()(r, r));
      if constexpr (M == 2) {
        log_det_ratio -= std::log(pixel_noise_.covariance().determinant());
        if (dof != M) log_det_ratio += std::log(width_variance / (options_.width_sigma_px * options_.width_sigma_px));
      } else {
        log_det_ratio -= std::log(tree_noise_.covariance().determinant());
      }
      const bool tree_continues = sighted_last_frame_.count(slot.id) != 0;
      const auto taken = sightings_taken_.find(slot.id);
      const bool old_tree = loops && taken != sightings_taken_.end() && taken->second >= options_.loop_sightings;
      if (old_tree) {
        loop_trees.push_back({lin.J_z_x, lin.J_z_l, lin.landmark_offset, S, dof, width_hat, width_variance});
        loop_tree_index.push_back(j);
      }
      for (std::size_t i = 0; i < seen.size(); ++i) {
        Vec<M> z;
        if constexpr (M == 2) {
          z = seen[i].uv;
        } else {
          z = seen[i].z;
        }
        double nis = llt.matrixL().solve(Vec<M>(sylva::detail::residual(model, z, lin.z_hat))).squaredNorm();
        if (dof != M) nis += (seen[i].z[2] - width_hat) * (seen[i].z[2] - width_hat) / width_variance;
        closest[i] = std::min(closest[i], nis / new_gate[dof]);
        const bool tested = dof == 3 && (!tree_continues || at_edge[i]);
        const bool continuous = !tested || nis + log_det_ratio < max_cost;
        if (nis < new_gate[dof] && continuous) explained[i] = 1;
        if (nis < pair_gate[dof] && continuous) candidates.push_back({nis / pair_gate[dof], i, j});
        if (old_tree && nis < pair_gate[dof] && !continuous)
          refused.push_back({nis, i, loop_trees.size() - 1, sylva::detail::residual(model, z, lin.z_hat)});
      }
    });
  }
  if (loops && refused.size() >= static_cast<std::size_t>(options_.loop_pairings)) {
    // Taken ahead of every single pairing (a score below any NIS over its gate).
    for (const LoopPairing& p : loopSet(ekf, seen, loop_trees, std::move(refused))) {
      candidates.push_back({-1.0, p.sighting, loop_tree_index[p.tree]});
      explained[p.sighting] = 1;
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const Pairing& a, const Pairing& b) {
    return std::tie(a.score, a.sighting, a.tree) < std::tie(b.score, b.sighting, b.tree);
  });
  NearestPairing out;
  out.tree.assign(seen.size(), -1);
  out.clear.assign(seen.size(), 0);
  std::vector<char> tree_taken(trees.size(), 0);
  for (const Pairing& c : candidates) {
    if (out.tree[c.sighting] >= 0 || tree_taken[c.tree]) continue;
    tree_taken[c.tree] = 1;
    out.tree[c.sighting] = trees[c.tree];
  }
  for (std::size_t i = 0; i < seen.size(); ++i) out.clear[i] = closest[i] > 1.0 || !explained[i] ? 1 : 0;
  return out;
}

template <typename Camera>
std::vector<typename BasicMonocularTreeSlam<Camera>::LoopPairing> BasicMonocularTreeSlam<Camera>::loopSet(
    const Filter& ekf, const std::vector<Seen>& seen, const std::vector<LoopTree>& trees,
    std::vector<LoopPairing> refused) const {
  std::sort(refused.begin(), refused.end(), [](const LoopPairing& a, const LoopPairing& b) {
    return std::tie(a.nis, a.sighting, a.tree) < std::tie(b.nis, b.sighting, b.tree);
  });
  // H P H^T of every tree with a refused pairing, from one product with the covariance (H's
  // rows: each tree's model dimensions, zero outside its camera and landmark blocks).
  std::vector<int> first_row(trees.size(), -1);
  int rows = 0;
  for (const LoopPairing& p : refused) {
    if (first_row[p.tree] >= 0) continue;
    first_row[p.tree] = rows;
    rows += static_cast<int>(trees[p.tree].S.rows());
  }
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(rows, ekf.dim());
  for (std::size_t j = 0; j < trees.size(); ++j) {
    if (first_row[j] < 0) continue;
    const LoopTree& t = trees[j];
    H.block(first_row[j], 0, t.J_x.rows(), t.J_x.cols()) = t.J_x;
    H.block(first_row[j], t.landmark_offset, t.J_l.rows(), t.J_l.cols()) = t.J_l;
  }
  const Eigen::MatrixXd HPHt = H * (ekf.covarianceView() * H.transpose());
  // Grow the set in order of NIS: the joint NIS of the innovations stacked, S from HPHt with
  // each tree's own S (noise included) on the diagonal, plus the width terms of point
  // landmarks compared on their predicted width (independent of the state).
  std::vector<LoopPairing> set;
  std::vector<char> sighting_in(seen.size(), 0), tree_in(trees.size(), 0);
  for (LoopPairing& candidate : refused) {
    if (sighting_in[candidate.sighting] || tree_in[candidate.tree]) continue;
    set.push_back(std::move(candidate));
    int n = 0, dof = 0;
    double width_terms = 0.0;
    for (const LoopPairing& p : set) {
      const LoopTree& t = trees[p.tree];
      n += static_cast<int>(t.S.rows());
      dof += t.dof;
      if (t.dof != t.S.rows()) {
        const double dw = seen[p.sighting].z[2] - t.width_hat;
        width_terms += dw * dw / t.width_variance;
      }
    }
    Eigen::MatrixXd S(n, n);
    Eigen::VectorXd nu(n);
    for (std::size_t a = 0, ra = 0; a < set.size(); ra += trees[set[a].tree].S.rows(), ++a) {
      const LoopTree& ta = trees[set[a].tree];
      nu.segment(ra, ta.S.rows()) = set[a].nu;
      for (std::size_t b = 0, rb = 0; b <= a; rb += trees[set[b].tree].S.rows(), ++b) {
        const LoopTree& tb = trees[set[b].tree];
        if (a == b) {
          S.block(ra, ra, ta.S.rows(), ta.S.rows()) = ta.S;
        } else {
          S.block(ra, rb, ta.S.rows(), tb.S.rows()) =
              HPHt.block(first_row[set[a].tree], first_row[set[b].tree], ta.S.rows(), tb.S.rows());
          S.block(rb, ra, tb.S.rows(), ta.S.rows()) = S.block(ra, rb, ta.S.rows(), tb.S.rows()).transpose();
        }
      }
    }
    const Eigen::LLT<Eigen::MatrixXd> llt(S);
    const bool compatible = llt.info() == Eigen::Success &&
                            llt.matrixL().solve(nu).squaredNorm() + width_terms <
                                chiSquareGate(dof, options_.association_gate_probability);
    if (compatible) {
      sighting_in[set.back().sighting] = 1;
      tree_in[set.back().tree] = 1;
    } else {
      set.pop_back();
    }
  }
  if (set.size() < static_cast<std::size_t>(options_.loop_pairings)) set.clear();
  return set;
}

template <typename Camera>
double BasicMonocularTreeSlam<Camera>::depthOf(const Filter& ekf, Id id) {
  const Vec<13>& camera = ekf.robotMean();
  const Vec<4> q = camera.template segment<4>(3).normalized();
  const Vec<3> t = camera.template head<3>();
  const Vec<3> optical_axis = rotationMatrix<double>(q).col(2);  // the camera's z in the world
  return ekf.visit(id, [&](auto type) {
    using Landmark = typename decltype(type)::type;
    const auto l = ekf.template landmarkMean<Landmark>(id);
    if constexpr (std::is_same_v<Landmark, InverseDepth> || std::is_same_v<Landmark, InverseDepthRadius>) {
      // the camera-frame z of rho (anchor - t) + m, the ray scaled by rho, over rho
      const double rho = l[5];
      if (!(rho > 0.0)) return std::numeric_limits<double>::infinity();
      const Vec<3> h = rho * (l.template head<3>() - t) + InverseDepth::direction<double>(l[3], l[4]);
      return optical_axis.dot(h) / rho;
    } else {
      return optical_axis.dot(Vec<3>(l.template head<3>() - t));
    }
  });
}

template <typename Camera>
void BasicMonocularTreeSlam<Camera>::removeUnconfirmed(FrameReport& report) {
  for (const Seen& s : sightings_) {
    if (s.id < 0 || !ekf_.contains(s.id)) continue;
    Sighted& record = sighted_[s.id];
    ++record.count;
    record.last_frame = frame_index_;
  }
  std::vector<Id> unconfirmed;
  for (const LandmarkSlot& slot : ekf_.slots()) {
    const auto it = sighted_.find(slot.id);
    if (it == sighted_.end()) continue;
    if (it->second.count < options_.confirm_sightings &&
        frame_index_ - it->second.last_frame >= options_.unconfirmed_after_frames)
      unconfirmed.push_back(slot.id);
  }
  for (const Id id : unconfirmed) {
    ekf_.remove(id);
    sighted_.erase(id);
    sightings_taken_.erase(id);
    appearance_.erase(id);
    true_anchor_.erase(id);
    ++report.removed;
  }
}

template <typename Camera>
void BasicMonocularTreeSlam<Camera>::recordAppearance() {
  for (const Seen& s : sightings_) {
    if (s.id < 0 || !ekf_.contains(s.id)) continue;
    appearance_[s.id] = Appearance{s.z[2], depthOf(ekf_, s.id)};
  }
}

template <typename Camera>
void BasicMonocularTreeSlam<Camera>::associate(std::vector<Seen>& seen, FrameReport& report) {
  const NearestPairing pairing = pairNearest(ekf_, seen);
  for (std::size_t i = 0; i < seen.size(); ++i) {
    if (pairing.tree[i] >= 0) {
      seen[i].id = pairing.tree[i];
    } else if (pairing.clear[i]) {
      while (ekf_.contains(next_tree_id_)) ++next_tree_id_;
      seen[i].id = next_tree_id_++;
    } else {
      seen[i].id = -1;
      ++report.ambiguous;
    }
  }
}

template <typename Camera>
void BasicMonocularTreeSlam<Camera>::setIdealLandmarks(const FrameTruth& truth) {
  for (const auto& slot : ekf_.slots()) {
    const Vec<4>& tree = (*truth.trees)[static_cast<std::size_t>(slot.id)];
    const Vec<3> base = tree.head<3>();
    ekf_.visit(slot.id, [&](auto type) {
      using Landmark = typename decltype(type)::type;
      if constexpr (std::is_same_v<Landmark, Point3>) {
        ekf_.template setIdealLandmark<Landmark>(slot.id, base);
      } else if constexpr (std::is_same_v<Landmark, TreeXYZR>) {
        ekf_.template setIdealLandmark<Landmark>(slot.id, tree);
      } else {
        // Inverse depth (and IDR) of the base centre from the true camera position at the
        // first sight: the parametrization's true value.
        const Vec<3> anchor = true_anchor_.at(slot.id);
        const Vec<3> d = base - anchor;
        const double rho = 1.0 / d.norm();
        Vec<7> l;
        l << anchor, std::atan2(d.y(), d.x()), std::atan2(d.z(), d.head<2>().norm()), rho, tree[3] * rho;
        ekf_.template setIdealLandmark<Landmark>(slot.id, l.head<Landmark::kDim>());
      }
    });
  }
}

template <typename Camera>
std::array<int, 4> BasicMonocularTreeSlam<Camera>::countByType() const {
  std::array<int, 4> n{0, 0, 0, 0};
  for (const auto& s : ekf_.slots()) ++n[static_cast<std::size_t>(s.type_index)];
  return n;
}

template <typename Camera>
double BasicMonocularTreeSlam<Camera>::nisOf(const Filter& ekf, const Seen& s) const {
  try {
    return withModelOf(ekf, s, [&](const auto& model, const auto& z, const auto& noise) {
      return ekf.innovation(model, s.id, z, noise).nis();
    });
  } catch (const Error&) {
    return kUnpredictable;
  }
}

template <typename Camera>
bool BasicMonocularTreeSlam<Camera>::passes(const Filter& ekf, const Seen& s) const { return withinGate(ekf, s.id, nisOf(ekf, s)); }

template <typename Camera>
bool BasicMonocularTreeSlam<Camera>::withinGate(const Filter& ekf, Id id, double nis) const {
  if (!(nis < kUnpredictable)) return false;
  const bool with_width = ekf.template holds<TreeXYZR>(id) || ekf.template holds<InverseDepthRadius>(id);
  return nis < gate_[with_width ? 3 : 2];
}

template <typename Camera>
void BasicMonocularTreeSlam<Camera>::fuseOne(Filter& ekf, const Seen& s) const {
  withModelOf(ekf, s, [&](const auto& model, const auto& z, const auto& noise) { ekf.update(model, s.id, z, noise); });
}

template <typename Camera>
void BasicMonocularTreeSlam<Camera>::fuseMapped(FrameReport& report) {
  candidates_.clear();
  for (const Seen& s : mapped_) {
    const double nis = nisOf(ekf_, s);
    if (nis < kUnpredictable) {
      candidates_.push_back({s, nis});
      report.nis[static_cast<std::size_t>(ekf_.slot(s.id).type_index)].add(nis);
    } else {
      ++report.rejected;
    }
  }
  if (candidates_.empty()) return;
  accepted_.clear();
  refused_.clear();
  for (const Candidate& c : candidates_) (withinGate(ekf_, c.seen.id, c.nis) ? accepted_ : refused_).push_back(c.seen);

  const bool gated = options_.gate_probability > 0.0;
  if (gated && candidates_.size() >= 2 && 2 * accepted_.size() < candidates_.size()) {
    std::sort(candidates_.begin(), candidates_.end(),
              [](const Candidate& a, const Candidate& b) { return a.nis < b.nis; });
    int best = -1;
    std::size_t best_support = accepted_.size();
    const int tries = std::min<int>(kMaxHypotheses, static_cast<int>(candidates_.size()));
    for (int h = 0; h < tries; ++h) {
      Filter trial = ekf_;
      try {
        fuseOne(trial, candidates_[h].seen);
      } catch (const Error&) {
        continue;
      }
      std::size_t support = 0;
      for (int j = 0; j < static_cast<int>(candidates_.size()); ++j)
        if (j != h && passes(trial, candidates_[j].seen)) ++support;
      if (support > best_support) {
        best_support = support;
        best = h;
      }
    }
    if (best >= 0) {
      const Seen chosen = candidates_[best].seen;
      fuseOne(ekf_, chosen);  // succeeded on the copy, so it succeeds here
      ++report.fused;
      ++report.hypotheses;
      accepted_.clear();
      refused_.clear();
      for (const Candidate& c : candidates_) {
        if (c.seen.id == chosen.id) continue;
        (passes(ekf_, c.seen) ? accepted_ : refused_).push_back(c.seen);
      }
    }
  }

  fuseBatches(accepted_, report);
  if (refused_.empty()) return;
  second_chance_.clear();
  for (const Seen& s : refused_) {
    if (passes(ekf_, s)) second_chance_.push_back(s);
    else ++report.rejected;
  }
  fuseBatches(second_chance_, report);
}

template <typename Camera>
void BasicMonocularTreeSlam<Camera>::fuseBatches(const std::vector<Seen>& observations, FrameReport& report) {
  id_batch_.clear();
  xyz_batch_.clear();
  tree_batch_.clear();
  idr_batch_.clear();
  for (const Seen& s : observations)
    withModelOf(ekf_, s, [&](const auto& model, const auto& z, const auto& noise) {
      batchOf(model).push_back({s.id, z, noise});
    });
  fuse(id_point_, id_batch_, report);
  fuse(xyz_point_, xyz_batch_, report);
  fuse(tree_width_, tree_batch_, report);
  fuse(idr_width_, idr_batch_, report);
}

template <typename Camera>
template <typename Model>
void BasicMonocularTreeSlam<Camera>::fuse(const Model& model, const std::vector<Observation<Model>>& batch, FrameReport& report) {
  if (batch.empty()) return;
  detail::PhaseClock clock(profile_ == nullptr ? nullptr
                                       : Model::kDim == 3 ? &profile_->width_updates_s : &profile_->point_updates_s);
  try {
    ekf_.update(model, batch, options_.fusion);
    report.fused += static_cast<int>(batch.size());
    report.fused_rows += static_cast<int>(batch.size()) * Model::kDim;
    return;
  } catch (const Error&) {
    // The filter is unchanged; fall back to one observation at a time.
  }
  for (const auto& o : batch) {
    try {
      ekf_.update(model, o.id, o.z, o.noise);
      ++report.fused;
      report.fused_rows += Model::kDim;
    } catch (const Error&) {
      ++report.rejected;
    }
  }
}

}  // namespace sylva::slam
