#pragma once
// The analytic J_x and J_n of a motion model against forward-mode automatic differentiation of
// its own propagate<T>(x, u, n, dt) at n = 0: a second, independent check beside the central
// differences of checkMotionJacobians, exact to round-off (so the bound is relative, 1e-12 of
// the largest entry). Not for ConstantVelocity3D, whose Jacobians are this autodiff.

#include <unsupported/Eigen/AutoDiff>

#include <sylva/core/types.hpp>

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

}  // namespace sylva_test
