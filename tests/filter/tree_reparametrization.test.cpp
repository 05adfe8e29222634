// The XYZ -> XYZ-R step of the landmark life cycle in the filter: the measurement-aided
// reparametrization (InverseTreeWidth) against the dense reference, TreeWidth updates
// afterwards against the dense reference, and the rejections that must leave the filter
// bit-identical (wrong type, bad measurement, degenerate geometry, a radius pushed <= 0).

#include "camera_pose.hpp"
#include "sylva_catch.hpp"

#include <cmath>

#include <Eigen/Geometry>

#include <sylva/filter/ekf.hpp>
#include <sylva/landmarks/point3.hpp>
#include <sylva/landmarks/tree_xyzr.hpp>
#include <sylva/measurements/inverse_tree_width.hpp>
#include <sylva/measurements/tree_width.hpp>
#include <sylva/motion/constant_velocity_3d.hpp>
#include <sylva/testing/dense_reference_ekf.hpp>

#include "error_helpers.hpp"

// Own namespace: the tests of a folder are compiled as one unity translation unit.
namespace unity_filter_tree_reparametrization {

using namespace sylva;
using sylva_test::lookAt;
using sylva_test::throwsCode;

namespace {

const PinholeCamera kCamera{500.0, 500.0, 320.0, 240.0, 640, 480};

// Test-only initialization of a Point3 at the camera position plus a world-frame offset z,
// so that the new landmark is correlated with the camera.
struct OffsetInit {
  using Robot = ConstantVelocity3D;
  using Landmark = Point3;
  static constexpr int kMeasurementDim = 3;
  static constexpr const char* kName = "OffsetInit";
  Vec<3> operator()(const Vec<13>& x, const Vec<3>& z, JacobianRef<3, 13> J_l_x = {}, JacobianRef<3, 3> J_l_z = {}) const {
    if (J_l_x) {
      (*J_l_x).setZero();
      (*J_l_x).leftCols<3>().setIdentity();
    }
    if (J_l_z) (*J_l_z).setIdentity();
    return x.head<3>() + z;
  }
};

using Filter = Ekf<ConstantVelocity3D, Point3, TreeXYZR>;

Mat<13, 13> initialCovariance() {
  Mat<13, 13> P = Mat<13, 13>::Identity() * 1e-4;
  P.block<3, 3>(7, 7) *= 10.0;
  P(0, 7) = P(7, 0) = 2e-5;
  return P;
}

struct Scene {
  Vec<13> camera = lookAt(Vec<3>(-8.0, 0.5, 1.5), Vec<3>(0.0, 0.0, 0.0), 0.0, 1.0, (Vec<6>() << 1.0, 0.0, 0.0, 0.0, 0.0, 0.0).finished());
  Filter ekf{camera, initialCovariance()};
  testing::DenseReferenceEkf<ConstantVelocity3D> ref{ConstantVelocity3D{}, camera, initialCovariance()};
  Vec<4> truth{0.2, -0.3, 0.0, 0.3};

  Scene() {
    Mat<3, 3> R = Mat<3, 3>::Identity() * 0.01;
    R(0, 1) = R(1, 0) = 0.002;
    for (Id id : {Id(1), Id(2), Id(3)}) {
      const Vec<3> offset = (id == 2 ? Vec<3>(truth.head<3>()) : Vec<3>(0.5 * id, 2.0 * id - 4.0, 0.0)) - camera.head<3>();
      ekf.add(id, OffsetInit{}, offset, Gaussian<3>::covariance(R));
      ref.add(OffsetInit{}, offset, R);
    }
  }
};

}  // namespace

TEST_CASE("XYZ -> XYZ-R with a width measurement equals the dense reference", "[filter][tree]") {
  Scene s;
  const Vec<3> z = TreeWidth(kCamera)(ConstantVelocity3D::pose(s.camera), s.truth);
  const Gaussian<3> noise = Gaussian<3>::sigmas(Vec<3>(1.0, 1.0, 0.5));
  const int offset = s.ekf.slot(2).offset;
  s.ekf.reparametrize(2, InverseTreeWidth(kCamera), z, noise);
  s.ref.reparametrize(offset, InverseTreeWidth(kCamera), z, noise.covariance());
  REQUIRE(s.ekf.holds<TreeXYZR>(2));
  CHECK(s.ekf.landmarkMean<TreeXYZR>(2)[3] == Approx(0.3).epsilon(1e-9));
  CHECK((s.ekf.mean() - s.ref.x).cwiseAbs().maxCoeff() < 1e-12);
  CHECK((s.ekf.covariance() - s.ref.P).cwiseAbs().maxCoeff() < 1e-12);
  // The radius' variance includes the position uncertainty and the width noise.
  const double var_r = s.ekf.landmarkCovariance<TreeXYZR>(2)(3, 3);
  Mat<4, 3> J_z;
  const InverseTreeWidth inverse(kCamera);
  inverse(ConstantVelocity3D::pose(s.camera), s.truth.head<3>(), z, {}, {}, J_z);
  CHECK(var_r > J_z(3, 2) * J_z(3, 2) * 0.25);

  // TreeWidth updates on the new block agree with the dense reference too.
  const int tree_offset = s.ekf.slot(2).offset;
  for (int k = 0; k < 3; ++k) {
    const Vec<3> zk = z + Vec<3>(0.3 * k, -0.2, 0.1 * k);
    s.ekf.update(TreeWidth(kCamera), 2, zk, noise);
    s.ref.update(TreeWidth(kCamera), tree_offset, zk, noise.covariance());
    s.ref.renormalizeRobot();
  }
  CHECK((s.ekf.mean() - s.ref.x).cwiseAbs().maxCoeff() < 1e-10);
  CHECK((s.ekf.covariance() - s.ref.P).cwiseAbs().maxCoeff() < 1e-10);
}

TEST_CASE("rejected tree reparametrizations and updates leave the filter unchanged", "[filter][tree][errors]") {
  Scene s;
  const Vec<3> z = TreeWidth(kCamera)(ConstantVelocity3D::pose(s.camera), s.truth);
  const Gaussian<3> noise = Gaussian<3>::sigmas(Vec<3>(1.0, 1.0, 0.5));
  const InverseTreeWidth inverse(kCamera);
  const Eigen::VectorXd mean0 = s.ekf.mean();
  const Eigen::MatrixXd cov0 = s.ekf.covariance();
  auto unchanged = [&] { return s.ekf.mean() == mean0 && s.ekf.covariance() == cov0 && s.ekf.holds<Point3>(2); };

  CHECK(throwsCode([&] { s.ekf.reparametrize(2, inverse, Vec<3>(z[0], NAN, z[2]), noise); }, ErrorCode::kNonFinite));
  CHECK(unchanged());
  CHECK(throwsCode([&] { s.ekf.reparametrize(2, inverse, Vec<3>(z[0], z[1], -1.0), noise); }, ErrorCode::kDegenerateGeometry));
  CHECK(unchanged());
  CHECK(throwsCode([&] { s.ekf.reparametrize(99, inverse, z, noise); }, ErrorCode::kUnknownId));
  CHECK(unchanged());

  // Once it is XYZ-R, converting it again is a type error.
  const Gaussian<3> vague = Gaussian<3>::sigmas(Vec<3>(1.0, 1.0, 20.0));
  s.ekf.reparametrize(2, inverse, z, vague);
  const Eigen::VectorXd mean1 = s.ekf.mean();
  const Eigen::MatrixXd cov1 = s.ekf.covariance();
  CHECK(throwsCode([&] { s.ekf.reparametrize(2, inverse, z, noise); }, ErrorCode::kWrongLandmarkType));
  CHECK(s.ekf.mean() == mean1);
  CHECK(s.ekf.covariance() == cov1);

  // With an uncertain radius (the width was measured with a 20 px sigma), an implausible
  // negative width measured precisely would drive the radius below zero: TreeWidth declares
  // it no measurement (as InverseTreeWidth does), so the update is refused before anything
  // moves. (The posterior domain check behind it, radius > 0, is tested with the laser's
  // diameter and the IDR trees.)
  const Vec<3> z_thin(z[0], z[1], -30.0);
  try {
    s.ekf.update(TreeWidth(kCamera), 2, z_thin, Gaussian<3>::sigmas(Vec<3>(1.0, 1.0, 0.01)));
    FAIL("an update with a negative width was accepted");
  } catch (const Error& e) {
    CHECK(e.code() == ErrorCode::kDegenerateGeometry);
    CHECK(std::string(e.what()).find("width must be > 0") != std::string::npos);
  }
  CHECK(s.ekf.mean() == mean1);
  CHECK(s.ekf.covariance() == cov1);

  // The same with the Joseph form.
  JosephEkf<ConstantVelocity3D, Point3, TreeXYZR> joseph(s.camera, initialCovariance());
  joseph.add(5, OffsetInit{}, Vec<3>(s.truth.head<3>() - s.camera.head<3>()), Gaussian<3>::sigmas(Vec<3>(0.1, 0.1, 0.1)));
  joseph.reparametrize(5, inverse, z, vague);
  const Eigen::VectorXd mean2 = joseph.mean();
  const Eigen::MatrixXd cov2 = joseph.covariance();
  CHECK(throwsCode([&] { joseph.update(TreeWidth(kCamera), 5, z_thin, Gaussian<3>::sigmas(Vec<3>(1.0, 1.0, 0.01))); },
                   ErrorCode::kDegenerateGeometry));
  CHECK(joseph.mean() == mean2);
  CHECK(joseph.covariance() == cov2);
}

}  // namespace unity_filter_tree_reparametrization
