#pragma once
/// @file
/// The correction and covariance transport of the right-invariant EKF of planar SLAM
/// (LinearizationPoint::kInvariant, filter/ekf.hpp; Barrau and Bonnabel 2015; docs/filter.md,
/// "Invariant EKF"). The error of the robot pose and of every landmark position lives in
/// SE_{1+k}(2), and the filter stores the covariance in the additive coordinates
/// delta = T(x) xi of the invariant error xi.
///
/// `detail::InvariantTransport` holds the workspace of one update and does its two steps:
///   - `retract`, before the mean is written: turns the additive correction delta = K nu into
///     the group's exponential, position by position;
///   - `carry`, after the covariance update: P <- M P M^T with M = T(x+) T(x)^-1.
/// It knows nothing of the filter's types (the filter walks its positions), so every filter
/// compiles the same code. `Tag` keeps the bodies dependent (core/deferred.hpp).

#include <Eigen/Core>
#include <cmath>

#include "sylva/core/deferred.hpp"
#include "sylva/core/types.hpp"
#include "sylva/detail/workspace.hpp"

namespace sylva::detail {

template <typename Tag = void>
class InvariantTransport {
  using Vec2 = Deferred<Vec<2>, Tag>;

 public:
  /// Starts an update of an n-dimensional state whose heading correction is `phi`
  /// (delta_theta): grows the workspace (before the caller writes anything) and clears c.
  void begin(int n, double phi) {
    growWorkspace(workspace_, 2 * static_cast<Eigen::Index>(n));
    workspace_.head(n).setZero();
    phi_ = phi;
    cos_phi_ = std::cos(phi);
    sin_phi_ = std::sin(phi);
    // sin(phi) / phi and (1 - cos(phi)) / phi, by their series near 0.
    const bool small = std::abs(phi) < 1e-6;
    a_ = small ? 1.0 - phi * phi / 6.0 : sin_phi_ / phi;
    b_ = small ? 0.5 * phi : (1.0 - cos_phi_) / phi;
  }

  /// The position at rows [o, o + 2) of the state, whose estimate is `p`: with
  /// xi_p = delta_p - phi J p (the invariant error, T(x)^-1 delta), the posterior is
  ///   p+ = R(phi) p + V(phi) xi_p,   V(phi) = [sin phi, -(1 - cos phi); 1 - cos phi, sin phi] / phi
  /// (the exponential of SE_{1+k}(2)), and delta_p becomes p+ - p. Records c = J (p+ - p), the
  /// position's rows of the column of M = T(x+) T(x)^-1 = I + c e_theta^T.
  template <typename Delta>
  void retract(Delta& delta, int o, const Vec2& p) {
    const Vec2 xi(delta[o] + phi_ * p.y(), delta[o + 1] - phi_ * p.x());  // delta_p - phi J p
    const Vec2 moved(cos_phi_ * p.x() - sin_phi_ * p.y() + a_ * xi.x() - b_ * xi.y(),
                     sin_phi_ * p.x() + cos_phi_ * p.y() + b_ * xi.x() + a_ * xi.y());
    const Vec2 step = moved - p;
    delta.template segment<2>(o) = step;
    workspace_.template segment<2>(o) = Vec2(-step.y(), step.x());
  }

  /// After the covariance update: P <- M P M^T with M = I + c e_theta^T, i.e. P + c a^T + a c^T
  /// for a = P e_theta + (P_theta,theta / 2) c, on the lower triangle of `P` (the filter's
  /// lower-triangle covariance: `P(i, j)` reads the symmetric matrix, `P.stored()` is the
  /// storage), n its dimension and h the heading's row. O(n^2), no allocation.
  template <typename Covariance>
  void carry(Covariance& P, int n, int h) {
    const auto c = workspace_.head(n);
    auto a = workspace_.segment(n, n);
    for (int i = 0; i < n; ++i) a[i] = P(i, h);
    a += (0.5 * P(h, h)) * c;
    for (int j = 0; j < n; ++j)
      P.stored().col(j).segment(j, n - j) += c.tail(n - j) * a[j] + a.tail(n - j) * c[j];
  }

 private:
  Deferred<Eigen::VectorXd, Tag> workspace_;  ///< c and a (2n)
  double phi_ = 0.0, cos_phi_ = 1.0, sin_phi_ = 0.0, a_ = 1.0, b_ = 0.0;
};

}  // namespace sylva::detail
