// Updating with a model whose landmark type is not in the filter's list does not compile.
#include <sylva/sylva.hpp>

namespace {
struct Point2Other {
  static constexpr int kDim = 2;
  static constexpr const char* kName = "Point2Other";
};
struct RangeBearingOther : sylva::RangeBearing {
  using Landmark = Point2Other;
  static constexpr const char* kName = "RangeBearingOther";
};
}  // namespace

int main() {
  using namespace sylva;
  Ekf<Unicycle2D, Point2> ekf(Vec<3>::Zero(), Mat<3, 3>::Identity());
  const auto r = Gaussian<2>::sigmas(Vec<2>(0.1, 0.01));
  ekf.add(1, InverseRangeBearing{}, Vec<2>(3.0, 0.1), r);
#if defined(SYLVA_SHOULD_FAIL)
  ekf.update(RangeBearingOther{}, 1, Vec<2>(3.0, 0.1), r);
#else
  ekf.update(RangeBearing{}, 1, Vec<2>(3.0, 0.1), r);
#endif
  return 0;
}
