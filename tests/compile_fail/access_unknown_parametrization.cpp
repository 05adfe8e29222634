// Asking for a landmark as a parametrization the filter does not hold does not compile.
#include <sylva/sylva.hpp>

namespace {
struct Point3Like {
  static constexpr int kDim = 3;
  static constexpr const char* kName = "Point3Like";
};
}  // namespace

int main() {
  using namespace sylva;
  Ekf<Unicycle2D, Point2> ekf(Vec<3>::Zero(), Mat<3, 3>::Identity());
  ekf.add(1, InverseRangeBearing{}, Vec<2>(3.0, 0.1), Gaussian<2>::sigmas(Vec<2>(0.1, 0.01)));
#if defined(SYLVA_SHOULD_FAIL)
  return static_cast<int>(ekf.landmarkMean<Point3Like>(1)[0]);
#else
  return static_cast<int>(ekf.landmarkMean<Point2>(1)[0] * 0.0);
#endif
}
