#pragma once
/// @file
/// `Ackermann2D`: a car-like robot (kinematic bicycle) whose state is the pose of the centre
/// of its rear axle, [x, y, phi] in the world frame, driven by a wheel-encoder speed and the
/// steering angle of the front wheels: control u = [v_e, alpha] (m/s, rad; alpha > 0 turns
/// left). It is the vehicle model of the Victoria Park experiments (Guivant and Nebot 2001,
/// Sec. 5; Guivant, Nebot and Baiker 2000), where the encoder sits on the rear LEFT wheel, a
/// lateral distance H from the centreline, so the speed of the axle centre is
///
///   v_c   = v_e / (1 - tan(alpha) H / L)          L: wheelbase (rear to front axle)
///   omega = v_c tan(alpha) / L                    (turn rate of the bicycle model)
///
/// (the inner wheel of a left turn is slower than the axle centre; H = 0 for an encoder on
/// the centreline, H < 0 for one on the right wheel). Over a step dt the speed and turn rate
/// are held constant and the position advances along the chord at the mid-step heading, as
/// `Unicycle2D` does (multisensor thesis eq. 2.12-2.14):
///
///   x'   = x + dt v_c cos(phi + dt omega / 2)
///   y'   = y + dt v_c sin(phi + dt omega / 2)
///   phi' = wrap(phi + dt omega)
///
/// The noise input is additive noise on the control [v_e, alpha], so the process noise of
/// the robot block is J_n Sigma_u J_n^T. Integrating n odometry samples of length dt_s in one
/// step of dt = n dt_s with the same per-sample noise needs Sigma_u scaled by dt_s / dt (the
/// per-sample errors are independent; see docs/examples/victoria-park.md).
///
/// Jacobians (additive perturbations; h = phi + dt omega / 2, t = tan(alpha),
/// D = 1 - t H / L, sec2 = 1 + t^2):
///
///   J_x = [ 1  0  -dt v_c sin h ]      d v_c / d v_e   = 1 / D
///         [ 0  1   dt v_c cos h ]      d v_c / d alpha = v_e (H / L) sec2 / D^2
///         [ 0  0        1       ]      d omega / d(.)  = (t d v_c / d(.) + v_c d t / d(.)) / L
///
///   J_n = J_unicycle(v_c, omega) * d(v_c, omega) / d(v_e, alpha), with J_unicycle the control
///   Jacobian of Unicycle2D.
///
/// Errors: |alpha| >= pi/2, or a steering angle for which D <= 0 (the encoder wheel would
/// stand still or turn backwards while the car moves: |alpha| >= atan(L / |H|)), throw
/// kDegenerateGeometry; the filter is then left unchanged. A wheelbase <= 0 or a
/// non-finite offset throws kInvalidArgument at construction.

#include <cmath>
#include <sstream>

#include "sylva/core/angles.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/jacobian_ref.hpp"
#include "sylva/core/scalar.hpp"
#include "sylva/core/types.hpp"
#include "sylva/motion/pose_2d.hpp"
#include "sylva/motion/unicycle_2d.hpp"

namespace sylva {

/// State [x, y, phi] of the rear-axle centre; normalize() and difference() come from Pose2D.
struct Ackermann2D : Pose2D {
  static constexpr int kControlDim = 2;  ///< [v_e (m/s), alpha (rad)]
  static constexpr int kNoiseDim = 2;    ///< additive noise on [v_e, alpha]
  static constexpr const char* kName = "Ackermann2D";
  using Control = Vec<2>;

  /// `wheelbase_m` L > 0; `encoder_offset_m` H: lateral distance from the centreline to the
  /// encoder wheel, positive to the left.
  explicit Ackermann2D(double wheelbase_m, double encoder_offset_m = 0.0)
      : wheelbase_(wheelbase_m), encoder_offset_(encoder_offset_m) {
    if (!(wheelbase_m > 0.0) || !std::isfinite(wheelbase_m) || !std::isfinite(encoder_offset_m)) {
      std::ostringstream os;
      os << "Ackermann2D: need a finite wheelbase > 0 and a finite encoder offset, got L = " << wheelbase_m
         << " m, H = " << encoder_offset_m << " m";
      fail(ErrorCode::kInvalidArgument, os.str());
    }
  }

  double wheelbase() const { return wheelbase_; }
  double encoderOffset() const { return encoder_offset_; }

  /// Axle-centre speed v_c and turn rate omega for control [v_e, alpha] (generic in the
  /// scalar). Throws kDegenerateGeometry outside the model's domain (see the file comment).
  template <typename T>
  void axleMotion(const T& v_e, const T& alpha, T& v_c, T& omega) const {
    using std::tan;
    const double a = scalarValue(alpha);
    const T t = tan(alpha);
    const T D = T(1.0) - t * (encoder_offset_ / wheelbase_);
    if (!(std::abs(a) < 0.5 * kPi) || !(scalarValue(D) > 1e-6)) {
      std::ostringstream os;
      os << "Ackermann2D: steering angle " << a << " rad is outside the model's domain (|alpha| < pi/2 and "
         << "1 - tan(alpha) H / L > 0, with L = " << wheelbase_ << " m, H = " << encoder_offset_ << " m)";
      fail(std::isfinite(a) ? ErrorCode::kDegenerateGeometry : ErrorCode::kNonFinite, os.str());
    }
    v_c = v_e / D;
    omega = v_c * t / wheelbase_;
  }

  /// Propagates `x` over `dt` seconds under control `u` (see the file comment).
  template <typename Tag = void>  // compiled only where called (core/deferred.hpp)
  State operator()(const State& x,
                   const Control& u,
                   double dt,
                   JacobianArg<3, 3, Tag> J_x = {},
                   JacobianArg<3, 2, Tag> J_n = {}) const {
    double v_c = 0.0;
    double omega = 0.0;
    axleMotion(u[0], u[1], v_c, omega);
    // The unicycle step at the axle centre's (v_c, omega); its control Jacobian chained with
    // d(v_c, omega) / d(v_e, alpha).
    Mat<3, 2> J_unicycle;
    const State next = Unicycle2D{}(x, Vec<2>(v_c, omega), dt, J_x, J_unicycle);
    if (J_n) {
      const double t = std::tan(u[1]);
      const double sec2 = 1.0 + t * t;
      const double k = encoder_offset_ / wheelbase_;
      const double D = 1.0 - t * k;
      Mat<2, 2> J_axle;  // d(v_c, omega) / d(v_e, alpha)
      J_axle(0, 0) = 1.0 / D;
      J_axle(0, 1) = u[0] * k * sec2 / (D * D);
      J_axle(1, 0) = t * J_axle(0, 0) / wheelbase_;
      J_axle(1, 1) = (t * J_axle(0, 1) + v_c * sec2) / wheelbase_;
      *J_n = J_unicycle * J_axle;
    }
    return next;
  }

  /// The motion with noise `n` added to the control, generic in the scalar (what J_n is the
  /// derivative of).
  template <typename T>
  Vec<3, T> propagate(const Vec<3, T>& x, const Vec<2, T>& u, const Vec<2, T>& n, double dt) const {
    T v_c;
    T omega;
    axleMotion(T(u[0] + n[0]), T(u[1] + n[1]), v_c, omega);
    return Unicycle2D{}.propagate<T>(x, Vec<2, T>(v_c, omega), Vec<2, T>::Zero(), dt);
  }

 private:
  double wheelbase_;
  double encoder_offset_;
};

}  // namespace sylva
