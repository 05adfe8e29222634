// Similarity alignment (eq. 4.1-4.11) and the error metrics (eq. 4.2, 4.12, 4.16-4.17).

#include "sylva_catch.hpp"

#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include <sylva/eval.hpp>
#include <sylva/sim/random.hpp>

#include "error_helpers.hpp"

using namespace sylva;
using sylva_test::throwsCode;

namespace {
std::vector<Vec<3>> randomPoints(sim::Rng& rng, int n) {
  std::vector<Vec<3>> p;
  for (int i = 0; i < n; ++i) p.emplace_back(rng.uniform(-20, 20), rng.uniform(-20, 20), rng.uniform(-1, 1));
  return p;
}
}  // namespace

TEST_CASE("alignSimilarity recovers a known similarity", "[eval]") {
  sim::Rng rng(3);
  const std::vector<Vec<3>> truth = randomPoints(rng, 40);
  // estimated = inverse of T applied to the truth, so aligning must give T back.
  const Mat<3, 3> R = Eigen::AngleAxisd(0.7, Vec<3>(0.2, -0.5, 1.0).normalized()).toRotationMatrix();
  const double s = 0.37;
  const Vec<3> t(3.0, -1.0, 0.5);
  std::vector<Vec<3>> estimated;
  for (const Vec<3>& p : truth) estimated.push_back(R.transpose() * (p - t) / s);
  const eval::Similarity3 T = eval::alignSimilarity(estimated, truth);
  CHECK(T.scale == Approx(s).epsilon(1e-12));
  CHECK((T.rotation - R).cwiseAbs().maxCoeff() < 1e-12);
  CHECK((T.translation - t).cwiseAbs().maxCoeff() < 1e-10);
  CHECK(eval::meanSquaredError(T, estimated, truth) < 1e-20);
}

TEST_CASE("with noise the error is the mean squared residual", "[eval]") {
  sim::Rng rng(5);
  const std::vector<Vec<3>> truth = randomPoints(rng, 2000);
  std::vector<Vec<3>> estimated;
  for (const Vec<3>& p : truth) estimated.push_back(2.0 * p + Vec<3>(rng.normal(0, 0.1), rng.normal(0, 0.1), rng.normal(0, 0.1)));
  const eval::Similarity3 T = eval::alignSimilarity(estimated, truth);
  CHECK(T.scale == Approx(0.5).epsilon(1e-3));
  // Residuals of 0.1 m per axis in the estimate's scale, halved: e = 3 * 0.05^2 = 0.0075.
  CHECK(eval::meanSquaredError(T, estimated, truth) == Approx(0.0075).epsilon(0.1));
  CHECK(eval::rms(eval::meanSquaredError(T, estimated, truth)) == Approx(std::sqrt(0.0075)).epsilon(0.05));
}

TEST_CASE("a mirrored map still gets a proper rotation", "[eval]") {
  sim::Rng rng(9);
  const std::vector<Vec<3>> truth = randomPoints(rng, 30);
  std::vector<Vec<3>> mirrored;
  for (const Vec<3>& p : truth) mirrored.emplace_back(p.x(), -p.y(), p.z());
  const eval::Similarity3 T = eval::alignSimilarity(mirrored, truth);
  CHECK(T.rotation.determinant() == Approx(1.0).epsilon(1e-12));
  CHECK((T.rotation * T.rotation.transpose() - Mat<3, 3>::Identity()).cwiseAbs().maxCoeff() < 1e-12);
  CHECK(eval::meanSquaredError(T, mirrored, truth) > 1.0);  // a reflection cannot be undone
}

TEST_CASE("the metrics on a hand-computed example", "[eval]") {
  const eval::Similarity3 identity;
  const std::vector<Vec<3>> truth{Vec<3>(0, 0, 0), Vec<3>(1, 0, 0), Vec<3>(0, 1, 0)};
  const std::vector<Vec<3>> estimated{Vec<3>(0, 0, 1), Vec<3>(1, 0, 0), Vec<3>(0, 3, 0)};
  CHECK(eval::meanSquaredError(identity, estimated, truth) == Approx((1.0 + 0.0 + 4.0) / 3.0));
  const eval::ConvergenceCriteria criteria;
  CHECK(criteria.converged(9.9, 2.9));
  CHECK_FALSE(criteria.converged(10.0, 1.0));
  CHECK_FALSE(criteria.converged(1.0, 3.0));
  CHECK(eval::negativeSaturatedAverage({1.0, 50.0, 2.0}, 10.0) == Approx(-(1.0 + 10.0 + 2.0) / 3.0));
}

TEST_CASE("alignment rejects bad input with a reason", "[eval][errors]") {
  const std::vector<Vec<3>> three{Vec<3>(0, 0, 0), Vec<3>(1, 0, 0), Vec<3>(0, 1, 0)};
  const std::vector<Vec<3>> two{Vec<3>(0, 0, 0), Vec<3>(1, 0, 0)};
  CHECK(throwsCode([&] { eval::alignSimilarity(three, two); }, ErrorCode::kInvalidArgument));
  CHECK(throwsCode([&] { eval::alignSimilarity(two, two); }, ErrorCode::kInvalidArgument));
  std::vector<Vec<3>> bad = three;
  bad[1].y() = NAN;
  CHECK(throwsCode([&] { eval::alignSimilarity(bad, three); }, ErrorCode::kNonFinite));
  const std::vector<Vec<3>> line{Vec<3>(0, 0, 0), Vec<3>(1, 1, 0), Vec<3>(2, 2, 0), Vec<3>(3, 3, 0)};
  CHECK(throwsCode([&] { eval::alignSimilarity(line, line); }, ErrorCode::kDegenerateGeometry));
  CHECK(throwsCode([&] { eval::meanSquaredError(eval::Similarity3{}, three, two); }, ErrorCode::kInvalidArgument));
}

TEST_CASE("alignRigid2 recovers a known rotation and translation, and keeps scale", "[eval]") {
  sim::Rng rng(7);
  const double angle = 2.5;  // beyond pi/2: the rotation must not flip
  const Vec<2> t(-67.7, 41.7);
  Mat<2, 2> R;
  R << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  std::vector<Vec<2>> est, truth;
  for (int i = 0; i < 20; ++i) {
    est.emplace_back(rng.uniform(-30, 30), rng.uniform(-30, 30));
    truth.push_back(R * est.back() + t);
  }
  const eval::Rigid2 T = eval::alignRigid2(est, truth);
  CHECK(std::abs(T.angle() - angle) < 1e-12);
  CHECK((T.translation - t).norm() < 1e-10);
  CHECK((T(est[3]) - truth[3]).norm() < 1e-10);
  CHECK(std::abs(T.rotation.determinant() - 1.0) < 1e-12);
  const Vec<3> moved = T.pose(Vec<3>(1.0, 2.0, 1.0));
  CHECK(std::abs(moved[2] - wrapAngle(1.0 + angle)) < 1e-12);
  // A scaled copy is not matched by scaling: the rigid fit leaves a residual.
  std::vector<Vec<2>> scaled;
  for (const Vec<2>& p : truth) scaled.push_back(1.1 * p);
  const eval::Rigid2 U = eval::alignRigid2(est, scaled);
  CHECK(std::abs(U.rotation.determinant() - 1.0) < 1e-12);
  CHECK((U(est[3]) - scaled[3]).norm() > 0.1);
  CHECK(throwsCode([&] { eval::alignRigid2({Vec<2>(1, 2)}, {Vec<2>(1, 2)}); }, ErrorCode::kInvalidArgument));
  est[0][1] = std::nan("");
  CHECK(throwsCode([&] { eval::alignRigid2(est, truth); }, ErrorCode::kNonFinite));
}
