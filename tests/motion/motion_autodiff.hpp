#pragma once
// The analytic J_x and J_n of a motion model against forward-mode automatic differentiation of
// its own propagate<T>(x, u, n, dt) at n = 0: a second, independent check beside the central
// differences of checkMotionJacobians, exact to round-off (so the bound is relative, 1e-12 of
// the largest entry). Not for ConstantVelocity3D, whose Jacobians are this autodiff.

#include <unsupported/Eigen/AutoDiff>

#include <sylva/core/types.hpp>
#include <sylva/diff/numeric_diff.hpp>
#include <sylva/testing/check_jacobians.hpp>

#include "sylva_catch.hpp"

namespace sylva_test {

template <typename Motion>
void requireMotionMatchesAutoDiff(const Motion& motion,
                                  const sylva::Vec<Motion::kDim>& x,
                                  const sylva::Vec<Motion::kControlDim>& u,
                                  double dt) {
  constexpr int D = Motion::kDim;
  constexpr int N = Motion::kNoiseDim;
  constexpr int C = Motion::kControlDim;
  using Dual = Eigen::AutoDiffScalar<sylva::Vec<D + N>>;
  sylva::Mat<D, D> J_x;
  sylva::Mat<D, N> J_n;
  motion(x, u, dt, J_x, J_n);
  sylva::Vec<D, Dual> xd;
  sylva::Vec<N, Dual> nd;
  sylva::Vec<C, Dual> ud;
  for (int i = 0; i < D; ++i) xd[i] = Dual(x[i], D + N, i);
  for (int i = 0; i < N; ++i) nd[i] = Dual(0.0, D + N, D + i);
  for (int i = 0; i < C; ++i) ud[i] = Dual(u[i]);
  const sylva::Vec<D, Dual> next = motion.template propagate<Dual>(xd, ud, nd, dt);
  sylva::Mat<D, D + N> automatic;
  for (int r = 0; r < D; ++r) automatic.row(r) = next[r].derivatives().transpose();
  const double scale = std::max(1.0, automatic.cwiseAbs().maxCoeff());
  INFO("analytic J_x\n" << J_x << "\nautodiff\n" << automatic.template leftCols<D>() << "\nanalytic J_n\n" << J_n
                        << "\nautodiff\n" << automatic.template rightCols<N>());
  CHECK((J_x - automatic.template leftCols<D>()).cwiseAbs().maxCoeff() <= 1e-12 * scale);
  CHECK((J_n - automatic.template rightCols<N>()).cwiseAbs().maxCoeff() <= 1e-12 * scale);
}

/// Both checks of a motion model's Jacobians: central differences (checkMotionJacobians, which
/// also compares operator() with propagate) and automatic differentiation.
template <typename Motion>
void requireMotionJacobians(const Motion& motion,
                            const sylva::Vec<Motion::kDim>& x,
                            const sylva::Vec<Motion::kControlDim>& u,
                            double dt) {
  const auto report = sylva::testing::checkMotionJacobians(motion, x, u, dt, 1e-6);
  INFO(report.message());
  CHECK(report.ok);
  requireMotionMatchesAutoDiff(motion, x, u, dt);
}

/// A planar robot whose state starts with its pose (Pose2DWithExtras): the pose view and its
/// Jacobian against central differences.
template <typename Robot>
void requirePlanarPoseView(const sylva::Vec<Robot::kDim>& x) {
  constexpr int D = Robot::kDim;
  sylva::Mat<3, D> J;
  const sylva::Vec<3> pose = Robot::pose(x, J);
  CHECK(pose == x.template head<3>());
  const sylva::Mat<3, D> numeric =
      sylva::numericJacobian<3, D>([](const sylva::Vec<D>& y) { return sylva::Vec<3>(Robot::pose(y)); }, x);
  CHECK((J - numeric).cwiseAbs().maxCoeff() < 1e-9);
}

}  // namespace sylva_test
