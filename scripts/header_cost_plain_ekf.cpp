// The README's sample program written by hand with Eigen alone, without sylva: a unicycle
// robot [x, y, theta] with 2D point landmarks, one add (range-bearing inverse model), one
// predict and one range-bearing update, fixed-size blocks on a dynamic covariance. No checks,
// no policies, no slot table: the compile-time floor of the same work, which
// scripts/header_cost.py compiles beside the sample ("plain Eigen EKF" on docs/build-time.md).
// Not part of the library or of any build.
#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
using Eigen::Matrix2d; using Eigen::Matrix3d; using Eigen::Vector2d; using Eigen::Vector3d;
using Eigen::MatrixXd; using Eigen::VectorXd;
struct Filter { VectorXd x; MatrixXd P; };
static void predict(Filter& f, double v, double w, double dt, const Matrix2d& Q) {
  const double th = f.x[2];
  f.x[0] += v * dt * std::cos(th); f.x[1] += v * dt * std::sin(th); f.x[2] += w * dt;
  Matrix3d F = Matrix3d::Identity(); F(0, 2) = -v * dt * std::sin(th); F(1, 2) = v * dt * std::cos(th);
  Eigen::Matrix<double, 3, 2> G; G << dt * std::cos(th), 0, dt * std::sin(th), 0, 0, dt;
  const int n = static_cast<int>(f.x.size());
  f.P.topLeftCorner<3, 3>() = F * f.P.topLeftCorner<3, 3>() * F.transpose() + G * Q * G.transpose();
  f.P.topRightCorner(3, n - 3) = F * f.P.topRightCorner(3, n - 3);
  f.P.bottomLeftCorner(n - 3, 3) = f.P.topRightCorner(3, n - 3).transpose();
}
static void update(Filter& f, int o, const Vector2d& z, const Matrix2d& R) {
  const Vector2d d = f.x.segment<2>(o) - f.x.head<2>();
  const double q = d.squaredNorm(), r = std::sqrt(q);
  const Vector2d zh(r, std::atan2(d.y(), d.x()) - f.x[2]);
  Eigen::Matrix<double, 2, 3> Hx; Hx << -d.x() / r, -d.y() / r, 0, d.y() / q, -d.x() / q, -1;
  Matrix2d Hl; Hl << d.x() / r, d.y() / r, -d.y() / q, d.x() / q;
  const int n = static_cast<int>(f.x.size());
  Eigen::Matrix<double, Eigen::Dynamic, 2> PHt = f.P.leftCols<3>() * Hx.transpose() + f.P.middleCols<2>(o) * Hl.transpose();
  const Matrix2d S = Hx * PHt.topRows<3>() + Hl * PHt.middleRows<2>(o) + R;
  const Eigen::LLT<Matrix2d> llt(S);
  const Eigen::Matrix<double, Eigen::Dynamic, 2> K = llt.solve(PHt.transpose()).transpose();
  f.x += K * (z - zh);
  f.P.noalias() -= K * PHt.transpose();
  (void)n;
}
static void add(Filter& f, const Vector2d& z, const Matrix2d& R) {
  const int n = static_cast<int>(f.x.size());
  const double th = f.x[2] + z[1];
  Eigen::Matrix<double, 2, 3> Jx; Jx << 1, 0, -z[0] * std::sin(th), 0, 1, z[0] * std::cos(th);
  Matrix2d Jz; Jz << std::cos(th), -z[0] * std::sin(th), std::sin(th), z[0] * std::cos(th);
  f.x.conservativeResize(n + 2); f.x.tail<2>() = f.x.head<2>() + z[0] * Vector2d(std::cos(th), std::sin(th));
  f.P.conservativeResize(n + 2, n + 2);
  f.P.bottomLeftCorner(2, n) = Jx * f.P.topLeftCorner(3, n);
  f.P.topRightCorner(n, 2) = f.P.bottomLeftCorner(2, n).transpose();
  f.P.bottomRightCorner<2, 2>() = Jx * f.P.topLeftCorner<3, 3>() * Jx.transpose() + Jz * R * Jz.transpose();
}
int main() {
  Filter f{Vector3d::Zero(), MatrixXd::Zero(3, 3)};
  const Matrix2d Q = Vector2d(0.01, 0.001).asDiagonal(), R = Vector2d(0.01, 0.0001).asDiagonal();
  add(f, Vector2d(5, 0.3), R);
  predict(f, 1.0, 0.1, 0.1, Q);
  update(f, 3, Vector2d(4.9, 0.31), R);
  std::printf("%g %g %g\n", f.x[0], f.x[1], f.x[2]);
}
