// A downstream program built against the installed sylva package: one landmark is added,
// the robot drives, the landmark is observed again, and the results are checked. Returns
// non-zero (and says why) if anything is off.
#include <cmath>
#include <iostream>
#include <string>

#include <Eigen/Eigenvalues>
#include <sylva/sylva.hpp>

namespace {

int failures = 0;

void check(bool ok, const std::string& what) {
  if (!ok) {
    std::cerr << "consumer: FAILED: " << what << "\n";
    ++failures;
  }
}

}  // namespace

int main() {
  using Filter = sylva::Ekf<sylva::Unicycle2D, sylva::Point2>;
  Filter ekf(sylva::Vec<3>::Zero(), sylva::Mat<3, 3>::Zero());

  const auto sensor_noise = sylva::Gaussian<2>::sigmas(sylva::Vec<2>(0.05, 0.01));
  const auto odometry_noise = sylva::Gaussian<2>::sigmas(sylva::Vec<2>(0.1, 0.05));

  // Landmark 7 at (4, 3), seen from the origin: range 5 m, bearing atan2(3, 4).
  const sylva::Vec<2> landmark(4.0, 3.0);
  ekf.add(7, sylva::InverseRangeBearing{}, sylva::Vec<2>(5.0, std::atan2(3.0, 4.0)), sensor_noise);
  check(ekf.contains(7) && ekf.dim() == 5, "landmark 7 was added");
  check((ekf.landmarkMean<sylva::Point2>(7) - landmark).norm() < 1e-12,
        "landmark initialized at (4, 3)");

  // Drive 1 m straight ahead; the robot becomes uncertain.
  ekf.predict(sylva::Vec<2>(1.0, 0.0), 1.0, odometry_noise);
  check((ekf.robotMean() - sylva::Vec<3>(1.0, 0.0, 0.0)).norm() < 1e-12,
        "predicted pose (1, 0, 0)");
  const double robot_var_before = ekf.robotCovariance().trace();

  // Observe the landmark from the true pose (1, 0, 0): range sqrt(18), bearing pi / 4.
  const sylva::Vec<2> z =
      sylva::RangeBearing{}.predict<double>(sylva::Vec<3>(1.0, 0.0, 0.0), landmark);
  const auto innovation = ekf.update(sylva::RangeBearing{}, 7, z, sensor_noise);
  check(std::abs(z[0] - std::sqrt(18.0)) < 1e-12 && std::abs(z[1] - sylva::kPi / 4) < 1e-12,
        "RangeBearing prediction");
  check(std::isfinite(innovation.nis()) && innovation.nis() < 1e-9, "innovation is zero");
  check(ekf.robotCovariance().trace() < robot_var_before, "the update reduced robot uncertainty");
  const Eigen::MatrixXd P = ekf.covariance();
  check(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(P).eigenvalues().minCoeff() > -1e-12,
        "covariance is positive semi-definite");

  // Bad input is reported through sylva::Error and changes nothing.
  const Eigen::VectorXd mean_before = ekf.mean();
  try {
    ekf.update(sylva::RangeBearing{}, 99, z, sensor_noise);
    check(false, "an update of unknown landmark 99 throws");
  } catch (const sylva::Error& e) {
    check(e.code() == sylva::ErrorCode::kUnknownId, std::string("error code of: ") + e.what());
  }
  check(ekf.mean() == mean_before && ekf.covariance() == P,
        "a failed update leaves the filter as it was");

  if (failures != 0) return 1;
  std::cout << "consumer: ok; robot at (" << ekf.robotMean().transpose() << "), landmark 7 at ("
            << ekf.landmarkMean<sylva::Point2>(7).transpose() << ")\n";
  return 0;
}
