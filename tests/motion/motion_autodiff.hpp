#pragma once
// The analytic J_x and J_n of a motion model against forward-mode automatic differentiation of
// its own propagate<T>(x, u, n, dt) at n = 0: a second, independent check beside the central
// differences of checkMotionJacobians, exact to round-off (entry by entry, relative to each
// entry's own scale: tests/autodiff_check.hpp). Not for ConstantVelocity3D, whose Jacobians
// are this autodiff.

#include <string>
#include <type_traits>

#include <sylva/core/types.hpp>
#include <sylva/diff/numeric_diff.hpp>
#include <sylva/testing/check_jacobians.hpp>

#include "autodiff_check.hpp"
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
  sylva::Mat<D, D> J_x;
  sylva::Mat<D, N> J_n;
  motion(x, u, dt, J_x, J_n);
  sylva::Mat<D, D + N> analytic;
  analytic << J_x, J_n;
  sylva::Vec<D + N> v;
  v << x, sylva::Vec<N>::Zero();
  const auto f = [&](const auto& s) {
    using T = typename std::decay_t<decltype(s)>::Scalar;
    sylva::Vec<C, T> ud;
    for (int i = 0; i < C; ++i) ud[i] = T(u[i]);
    return motion.template propagate<T>(sylva::Vec<D, T>(s.template head<D>()), ud, sylva::Vec<N, T>(s.template tail<N>()), dt);
  };
  // The value compared is propagate's own (checkMotionJacobians compares operator() with it).
  const sylva::Vec<D> propagated = motion.template propagate<double>(x, u, sylva::Vec<N>::Zero(), dt);
  checkAgainstAutoDiff<D, D + N>("[J_x | J_n] (state columns 0-" + std::to_string(D - 1) + ", noise from " +
                                     std::to_string(D) + ")",
                                 analytic, propagated, f, v);
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
