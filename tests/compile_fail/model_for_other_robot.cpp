// A measurement model written for another robot type (here one derived from the filter's
// robot: only a base of the filter's robot fits) does not compile with this filter.
#include <sylva/sylva.hpp>

namespace {
struct OtherRobot : sylva::Unicycle2D {
  static constexpr const char* kName = "OtherRobot";
};
struct RangeBearingForOtherRobot : sylva::RangeBearing {
  using Robot = OtherRobot;
};
}  // namespace

int main() {
  using namespace sylva;
  Ekf<Unicycle2D, Point2> ekf(Vec<3>::Zero(), Mat<3, 3>::Identity());
  const auto r = Gaussian<2>::sigmas(Vec<2>(0.1, 0.01));
  ekf.add(1, InverseRangeBearing{}, Vec<2>(3.0, 0.1), r);
#if defined(SYLVA_SHOULD_FAIL)
  ekf.update(RangeBearingForOtherRobot{}, 1, Vec<2>(3.0, 0.1), r);
#else
  ekf.update(RangeBearing{}, 1, Vec<2>(3.0, 0.1), r);
#endif
  return 0;
}
