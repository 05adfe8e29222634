// MrptPeer: the circle world fed to mrpt::slam::CRangeBearingKFSLAM2D (see mrpt_peer.hpp).

#include "mrpt_peer.hpp"

#include <mrpt/bayes/CKalmanFilterCapable.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt/slam/CRangeBearingKFSLAM2D.h>
#include <mrpt/system/os.h>

#include <sstream>
#include <stdexcept>

namespace sylva_peers {

namespace {

/// CRangeBearingKFSLAM2D with access to its state (the mean and covariance live in the
/// protected members of CKalmanFilterCapable, the id table in CRangeBearingKFSLAM2D).
/// Nothing of the filter's algorithm is overridden.
class StatefulSlam : public mrpt::slam::CRangeBearingKFSLAM2D {
 public:
  void load(const FilterState& s) {
    const auto n = static_cast<std::size_t>(s.mean.size());
    if (s.cov.rows() != s.mean.size() || s.cov.cols() != s.mean.size() || (n - 3) != 2 * s.ids.size())
      throw std::invalid_argument("MrptPeer::setState: mean, covariance and ids do not fit together");
    m_xkk.resize(n);
    m_xkk.asEigen() = s.mean;
    m_pkk.setSize(n, n);
    m_pkk.asEigen() = s.cov;
    m_IDs.clear();
    for (std::size_t i = 0; i < s.ids.size(); ++i)
      m_IDs.insert(static_cast<mrpt::maps::CLandmark::TLandmarkID>(s.ids[i]), static_cast<unsigned int>(i));
  }

  void ids(std::vector<sylva::Id>& out) const {
    out.assign((static_cast<std::size_t>(m_xkk.size()) - 3) / 2, -1);
    for (const auto& [index, id] : m_IDs.getInverseMap()) out.at(index) = static_cast<sylva::Id>(id);
  }

  void mean(Eigen::VectorXd& out) const { out = m_xkk.asEigen(); }
  void covariance(Eigen::MatrixXd& out) const { out = m_pkk.asEigen(); }
};

/// MRPT keeps the sensor sigmas as float: refuse sigmas whose float rounding or float
/// square would differ from what sylva uses in double.
float exactFloatSigma(double sigma, const char* what) {
  const auto f = static_cast<float>(sigma);
  if (static_cast<double>(f) != sigma || static_cast<double>(f * f) != sigma * sigma) {
    std::ostringstream os;
    os << "MrptPeer: " << what << " sigma " << sigma
       << " is not exact in float with an exact float square (MRPT keeps it as float); "
          "choose e.g. a power of two";
    throw std::invalid_argument(os.str());
  }
  return f;
}

}  // namespace

struct MrptPeer::Impl {
  StatefulSlam slam;
  std::vector<mrpt::obs::CActionCollection::Ptr> actions;
  std::vector<mrpt::obs::CSensoryFrame::Ptr> frames;
};

MrptPeer::MrptPeer(const sylva_bench::CircleWorld& world, MrptMethod method) : impl_(std::make_unique<Impl>()) {
  const sylva_bench::CircleWorldConfig& config = world.config();
  StatefulSlam& slam = impl_->slam;
  slam.KF_options.method =
      method == MrptMethod::kNaive ? mrpt::bayes::kfEKFNaive : mrpt::bayes::kfEKFAlaDavison;
  slam.options.std_sensor_range = exactFloatSigma(config.range_sigma_m, "range");
  slam.options.std_sensor_yaw = exactFloatSigma(config.bearing_sigma_rad, "bearing");
  if (!config.float_measurements)
    throw std::invalid_argument("MrptPeer: the world must round its measurements to float (MRPT stores floats)");

  mrpt::math::CMatrixDouble33 odometry_cov;
  odometry_cov.asEigen() = world.odometryNoise().covariance();

  const auto& steps = world.steps();
  impl_->actions.reserve(steps.size());
  impl_->frames.reserve(steps.size());
  for (const sylva_bench::Step& step : steps) {
    auto actions = mrpt::obs::CActionCollection::Create();
    mrpt::obs::CActionRobotMovement2D movement;
    movement.estimationMethod = mrpt::obs::CActionRobotMovement2D::emOdometry;
    const mrpt::poses::CPose2D increment(step.odometry[0], step.odometry[1], step.odometry[2]);
    movement.rawOdometryIncrementReading = increment;
    movement.poseChange = mrpt::poses::CPosePDFGaussian::Create(increment, odometry_cov);
    actions->insert(movement);

    auto observation = mrpt::obs::CObservationBearingRange::Create();
    observation->minSensorDistance = static_cast<float>(config.min_range_m);
    observation->maxSensorDistance = static_cast<float>(config.max_range_m);
    observation->fieldOfView_yaw = static_cast<float>(config.field_of_view_rad);
    observation->fieldOfView_pitch = 0.0f;
    observation->sensorLocationOnRobot = mrpt::poses::CPose3D();  // the robot's origin
    observation->validCovariances = false;
    observation->sensor_std_range = static_cast<float>(config.range_sigma_m);
    observation->sensor_std_yaw = static_cast<float>(config.bearing_sigma_rad);
    observation->sensedData.resize(step.measurements.size());
    for (std::size_t i = 0; i < step.measurements.size(); ++i) {
      const sylva_bench::Measurement& m = step.measurements[i];
      auto& out = observation->sensedData[i];
      // The world rounded these to float already, so the conversions are exact.
      out.range = static_cast<float>(m.range_m);
      out.yaw = static_cast<float>(m.bearing_rad);
      out.pitch = 0.0f;
      out.landmarkID = static_cast<std::int32_t>(m.id);
    }
    auto frame = mrpt::obs::CSensoryFrame::Create();
    frame->insert(observation);
    impl_->actions.push_back(std::move(actions));
    impl_->frames.push_back(std::move(frame));
  }
}

MrptPeer::~MrptPeer() = default;

void MrptPeer::step(int k) {
  impl_->slam.processActionObservation(impl_->actions.at(static_cast<std::size_t>(k)),
                                       impl_->frames.at(static_cast<std::size_t>(k)));
}

FilterState MrptPeer::state() const {
  FilterState s;
  impl_->slam.mean(s.mean);
  impl_->slam.covariance(s.cov);
  impl_->slam.ids(s.ids);
  return s;
}

void MrptPeer::mean(Eigen::VectorXd& mean, std::vector<sylva::Id>& ids) const {
  impl_->slam.mean(mean);
  impl_->slam.ids(ids);
}

void MrptPeer::setState(const FilterState& state) { impl_->slam.load(state); }

std::string MrptPeer::version() { return mrpt::system::MRPT_getVersion(); }

}  // namespace sylva_peers
