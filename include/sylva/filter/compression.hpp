#pragma once
/// @file
/// `detail::Compression<Ekf>`: the compressed EKF (Guivant and Nebot, IEEE T-RA 2001) behind
/// `BasicEkf::setCompression`. The filter keeps its active part A in its leading rows and
/// runs its own kernels on them; this class carries the rest of the state, B, through
/// detail::CompressedRegion's accumulators, moves the state when a new region is entered,
/// and corrects reads of B between global updates. See docs/filter.md ("Compressed EKF").
///
/// It is a class template reached only through `setCompression`: a program that never
/// compresses compiles none of it (filter/compression_hooks.hpp is all the filter sees).

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "sylva/core/types.hpp"
#include "sylva/detail/compressed_region.hpp"
#include "sylva/filter/compression_hooks.hpp"
#include "sylva/filter/linearization.hpp"
#include "sylva/filter/slot_table.hpp"
#include "sylva/detail/workspace.hpp"

namespace sylva::detail {

template <typename Ekf>
class Compression final : public CompressionHooks<Ekf> {
  using Hooks = CompressionHooks<Ekf>;
  using Rule = typename Ekf::RegionRule;
  static constexpr int kRobotDim = Ekf::kRobotDim;

 public:
  explicit Compression(Rule rule) : rule_(std::move(rule)) {}

  Hooks* clone() const override { return new Compression(*this); }
  int activeDim() const override { return region_.activeDim(); }
  long steps() const override { return region_.steps(); }
  long globalUpdates() const override { return global_updates_; }

  void synchronize(Ekf& ekf) override {
    if (region_.steps() == 0) return;
    region_.globalUpdate(ekf.cov_.inUse(), ekf.mean_.head(ekf.dim()), ekf.parallel_);
    ++global_updates_;
  }

  /// The landmarks that the selector or `forced` choose lead the state (in their present
  /// order), then the others. Everything that can allocate comes before anything moves; the
  /// global update changes no estimate, so a failure leaves the estimates as they were.
  void enterRegion(Ekf& ekf, const Id* forced, std::size_t count) override {
    synchronize(ekf);
    const int n = ekf.dim();
    const auto& all = ekf.slots_.slots();
    chosen_.assign(all.size(), 0);
    int a = kRobotDim;
    for (std::size_t k = 0; k < all.size(); ++k) {
      bool in = false;
      for (std::size_t f = 0; f < count && !in; ++f) in = forced[f] == all[k].id;
      if (in || rule_.select(ekf, all[k])) {
        chosen_[k] = 1;
        a += all[k].dim;
      }
    }
    order_.clear();
    order_.reserve(all.size());
    for (int pass = 1; pass >= 0; --pass)
      for (std::size_t k = 0; k < all.size(); ++k)
        if (chosen_[k] == pass) order_.push_back(all[k]);
    perm_.resize(static_cast<std::size_t>(n));
    for (int i = 0; i < kRobotDim; ++i) perm_[static_cast<std::size_t>(i)] = i;
    bool identity = true;
    int row = kRobotDim;
    for (const LandmarkSlot& s : order_) {
      identity = identity && s.offset == row;
      for (int i = 0; i < s.dim; ++i) perm_[static_cast<std::size_t>(row++)] = s.offset + i;
    }
    if (!identity) {
      growWorkspace(scratch_, n);
      // The covariance is permuted into a second matrix of the storage's size, which then
      // takes the storage's place (so compression holds two while it reorders).
      resizeWorkspace(spare_, ekf.cov_.capacity(), ekf.cov_.capacity());
    }
    region_.stageBegin(a);
    // From here on nothing can fail.
    if (!identity) {
      for (Eigen::VectorXd* v : {&ekf.mean_, &ekf.first_, &ekf.ideal_}) {
        for (int i = 0; i < n; ++i) scratch_[i] = (*v)[perm_[static_cast<std::size_t>(i)]];
        v->head(n) = scratch_.head(n);
      }
      ekf.cov_.permute(perm_, spare_);
      ekf.slots_.reorder(order_, kRobotDim);
      ekf.revision_ = nextRevision();  // linearizations made before name the old rows
    }
    region_.commitBegin();
    entry_robot_ = ekf.robotMean();
  }

  void enterRegionIfLeft(Ekf& ekf) override {
    if (rule_.left && rule_.left(ekf, entry_robot_)) enterRegion(ekf, nullptr, 0);
  }

  void predictRobot(const double* F) override {
    region_.template predictRobot<kRobotDim>(Eigen::Map<const Mat<kRobotDim, kRobotDim>>(F));
  }

  /// (H_A phi)^T from the update's blocks (observation i: phi^T's robot rows times its
  /// robot block, plus its landmark rows times its landmark block), then the region's
  /// staged changes.
  void stageUpdate(const Ekf& ekf, const CompressedUpdateTerms& t) override {
    // The region's first update rescales its accumulators (CompressedRegion, "Scaled
    // accumulators"); this update is then staged on the scaled phi.
    const Eigen::MatrixXd& phi = region_.scaled() ? region_.phi() : region_.stageScale(activeBlock(ekf), storedRows(ekf));
    const int total = t.count * t.m;
    const int L = t.landmark_dim;
    const Eigen::Index stride = static_cast<Eigen::Index>(t.m) * (kRobotDim + L);
    auto HphiT = region_.hphiTransposed(total);
    for (int i = 0; i < t.count; ++i) {
      const double* blocks = t.lins + i * stride;
      const Eigen::Map<const Eigen::MatrixXd> J_x(blocks, t.m, kRobotDim);
      const Eigen::Map<const Eigen::MatrixXd> J_l(blocks + static_cast<Eigen::Index>(t.m) * kRobotDim, t.m, L);
      auto out = HphiT.middleCols(i * t.m, t.m);
      out.noalias() = phi.topRows(kRobotDim).transpose() * J_x.transpose();
      out.noalias() += phi.middleRows(t.offsets[i], L).transpose() * J_l.transpose();
    }
    const Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>> factor(t.factor, total, total,
                                                                             Eigen::OuterStride<>(t.factor_stride));
    const Eigen::Map<const Eigen::VectorXd> nu(t.nu, total);
    const Eigen::Map<const Eigen::MatrixXd> gain(t.gain, region_.activeDim(), total);
    region_.stageUpdate(factor.template triangularView<Eigen::Lower>(), nu, gain, t.gain_is_k);
  }
  void commitUpdate(Ekf& ekf) override {
    if (!region_.scaled()) region_.commitScale(storedRows(ekf));
    region_.commitUpdate();
  }

  void stageExtend(const double* J_robot, int rows) override {
    region_.template stageExtend<kRobotDim>(Eigen::Map<const Eigen::MatrixXd>(J_robot, rows, kRobotDim));
  }
  void commitExtend() override { region_.commitExtend(); }
  void stageBegin(int a) override { region_.stageBegin(a); }
  void commitBegin() override { region_.commitBegin(); }

  /// Between global updates (CompressedRegion): P_BA = P_BA0 phi^T and
  /// P_BB' = P_BB'0 - P_BA0 psi P_AB'0, from the stored rows of B against A.
  void currentBlock(const Ekf& ekf, int row, int col, int rows, int cols, double* out) const override {
    const int a = region_.activeDim();
    Eigen::Map<Eigen::MatrixXd> block(out, rows, cols);
    const auto& stored = ekf.cov_.stored();
    const Eigen::MatrixXd& phi = region_.phi();
    if (row < a && col < a) {
      for (int j = 0; j < cols; ++j)
        for (int i = 0; i < rows; ++i) block(i, j) = ekf.cov_(row + i, col + j);
    } else if (row < a) {  // the transpose of a passive-active block
      block.transpose().noalias() = stored.block(col, 0, cols, a) * phi.middleRows(row, rows).transpose();
    } else if (col < a) {
      block.noalias() = stored.block(row, 0, rows, a) * phi.middleRows(col, cols).transpose();
    } else {
      for (int j = 0; j < cols; ++j)
        for (int i = 0; i < rows; ++i) block(i, j) = ekf.cov_(row + i, col + j);
      block -= region_.passivePassiveCorrection(stored.block(row, 0, rows, a), stored.block(col, 0, cols, a));
    }
  }

  void correctMean(const Ekf& ekf, int offset, int rows, double* out) const override {
    const int a = region_.activeDim();
    Eigen::Map<Eigen::VectorXd>(out, rows) += region_.passiveMeanCorrection(ekf.cov_.stored().block(offset, 0, rows, a));
  }

  void correctCovariance(const Ekf& ekf, Eigen::MatrixXd& full) const override {
    const int a = region_.activeDim();
    const int b = ekf.dim() - a;
    const auto V = ekf.cov_.stored().block(a, 0, b, a);
    full.block(a, 0, b, a) = region_.passiveActiveBlock(V);
    full.block(0, a, a, b) = full.block(a, 0, b, a).transpose();
    full.block(a, a, b, b) -= region_.passivePassiveCorrection(V, V);
  }

 private:
  /// The active block P_AA (its lower triangle is current) and the stored rows of B against A.
  /// An update runs with the covariance's dimension cut to A (Ekf::ActiveWindow), so the
  /// state's size is counted from the landmark slots.
  auto activeBlock(const Ekf& ekf) const {
    const int a = region_.activeDim();
    return ekf.cov_.stored().topLeftCorner(a, a);
  }
  static int stateDim(const Ekf& ekf) {
    int n = kRobotDim;
    for (const LandmarkSlot& s : ekf.slots_.slots()) n += s.dim;
    return n;
  }
  auto storedRows(const Ekf& ekf) const {
    const int a = region_.activeDim();
    return ekf.cov_.stored().block(a, 0, stateDim(ekf) - a, a);
  }
  auto storedRows(Ekf& ekf) const {
    const int a = region_.activeDim();
    return ekf.cov_.stored().block(a, 0, stateDim(ekf) - a, a);
  }

  Rule rule_;
  typename Ekf::RobotState entry_robot_;  ///< the robot's mean when the region was entered
  CompressedRegion region_;
  long global_updates_ = 0;
  // Workspaces of entering a region (they only grow).
  std::vector<char> chosen_;
  std::vector<LandmarkSlot> order_;
  std::vector<int> perm_;
  Eigen::VectorXd scratch_;
  Eigen::MatrixXd spare_;
};

}  // namespace sylva::detail
