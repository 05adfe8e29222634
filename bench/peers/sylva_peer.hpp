#pragma once
/// @file
/// sylva's side of the comparison: the three ways the benchmark fuses a step's measurements.
///
///   kBatched      `Ekf::update(model, observations)`: all known landmarks of the step in one
///                 update (stacked H, one symmetric rank-2k downdate of P). The same
///                 estimator as MRPT's kfEKFNaive, which also linearizes every observation
///                 at the predicted state and applies one gain (K = P H^T S^-1,
///                 P <- (I - K H) P) (bench/peers/README.md).
///   kAlaDavison   what MRPT's kfEKFAlaDavison computes, through sylva's public API: the
///                 Jacobians of all observations are taken once at the predicted state, then
///                 each observation is fused as two scalar updates (range, then bearing) whose
///                 innovation z - h(x) is evaluated once per observation at the estimate
///                 after the previous observations (so the bearing's innovation does not see
///                 the range's correction). `FrozenComponent` is the scalar measurement model
///                 that hands the filter those fixed Jacobian rows and prediction.
///   kSequential   sylva's ordinary sequential update: one 2-D `Ekf::update` per
///                 observation, each linearized at the current estimate. Not the estimator of
///                 either MRPT method (the textbook iterated-over-observations EKF); timed
///                 for reference.

#include <vector>

#include "circle_world.hpp"
#include "sylva/core/angles.hpp"
#include "sylva/core/jacobian_ref.hpp"
#include "sylva_circle_slam.hpp"

namespace sylva_peers {

using sylva_bench::Fusion;
using sylva_bench::OdometrySlam;

enum class SylvaFusion { kBatched, kAlaDavison, kSequential };

inline const char* toString(SylvaFusion f) {
  switch (f) {
    case SylvaFusion::kBatched: return "batched";
    case SylvaFusion::kAlaDavison: return "scalar (kfEKFAlaDavison's fusion)";
    case SylvaFusion::kSequential: return "sequential";
  }
  return "?";
}

/// One scalar component (range or bearing) of a range-bearing measurement whose Jacobian
/// row and prediction were fixed beforehand: `operator()` ignores the state it is given.
/// Only for reproducing kfEKFAlaDavison; not a general-purpose model.
struct FrozenComponent {
  using Robot = sylva::Odometry2D;
  using Landmark = sylva::Point2;
  static constexpr int kDim = 1;
  static constexpr const char* kName = "FrozenComponent";

  sylva::Mat<1, 3> J_x = sylva::Mat<1, 3>::Zero();
  sylva::Mat<1, 2> J_l = sylva::Mat<1, 2>::Zero();
  double z_hat = 0.0;
  bool is_bearing = false;

  template <typename T>
  sylva::Vec<1, T> predict(const sylva::Vec<3, T>& /*robot*/, const sylva::Vec<2, T>& /*landmark*/) const {
    return sylva::Vec<1, T>(T(z_hat));
  }

  sylva::Vec<1> operator()(const sylva::Vec<3>& /*robot*/,
                           const sylva::Vec<2>& /*landmark*/,
                           sylva::JacobianRef<1, 3> J_z_x = {},
                           sylva::JacobianRef<1, 2> J_z_l = {}) const {
    if (J_z_x) *J_z_x = J_x;
    if (J_z_l) *J_z_l = J_l;
    return sylva::Vec<1>(z_hat);
  }

  sylva::Vec<1> residual(const sylva::Vec<1>& z, const sylva::Vec<1>& zh) const {
    return sylva::Vec<1>(is_bearing ? sylva::wrapAngle(z[0] - zh[0]) : z[0] - zh[0]);
  }
};

/// Reusable buffers of a step.
struct PeerScratch {
  sylva_bench::StepScratch step;
  std::vector<sylva::Linearization<sylva::RangeBearing>> prior;
};

/// kfEKFAlaDavison's update of the known landmarks (see the file comment).
inline void updateAlaDavison(OdometrySlam& ekf, PeerScratch& scratch) {
  const sylva::RangeBearing model;
  const auto& known = scratch.step.known;
  scratch.prior.clear();
  for (const auto& obs : known) scratch.prior.push_back(ekf.linearize(model, obs.id));
  for (std::size_t i = 0; i < known.size(); ++i) {
    const auto& obs = known[i];
    const auto& lin = scratch.prior[i];
    const sylva::Vec<2> z_hat = model(ekf.robotMean(), ekf.landmarkMean<sylva::Point2>(obs.id));
    const sylva::Mat<2, 2>& R = obs.noise.covariance();  // diagonal, as MRPT's scalar updates assume
    for (int c = 0; c < 2; ++c) {
      FrozenComponent component;
      component.J_x = lin.J_z_x.row(c);
      component.J_l = lin.J_z_l.row(c);
      component.z_hat = z_hat[c];
      component.is_bearing = c == 1;
      ekf.update(component, obs.id, sylva::Vec<1>(obs.z[c]),
                 sylva::Gaussian<1>::covariance(sylva::Mat<1, 1>::Constant(R(c, c))));
    }
  }
}

/// One whole step with the given fusion (predict, update, add: sylva_circle_slam.hpp).
inline void runPeerStep(OdometrySlam& ekf,
                        const sylva_bench::SylvaStep& step,
                        const sylva::Gaussian<3>& odometry_noise,
                        double dt_s,
                        SylvaFusion fusion,
                        PeerScratch& scratch) {
  if (fusion == SylvaFusion::kAlaDavison) {
    sylva_bench::predictStep(ekf, step, odometry_noise, dt_s);
    sylva_bench::splitObservations(ekf, step, scratch.step);
    updateAlaDavison(ekf, scratch);
    sylva_bench::addNewLandmarks(ekf, scratch.step);
  } else {
    sylva_bench::runStep(ekf, step, odometry_noise, dt_s,
                         fusion == SylvaFusion::kBatched ? Fusion::kBatched : Fusion::kSequential, scratch.step);
  }
}

}  // namespace sylva_peers
